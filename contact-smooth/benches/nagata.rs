//! Placeholder until the surface exists.
fn main() {}
