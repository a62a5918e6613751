//! Placeholder: this crate's issue comes later (see README.md).
