//! The crate's integration tests in one test binary (each release test
//! binary costs CI seconds of linking); one module per former file.

mod common;
mod curved;
mod degenerate;
mod face_shifts;
mod flat_surfaces;
mod friction;
mod tilted;
