//! The crate's integration tests in one test binary (each release test
//! binary costs CI seconds of linking); one module per former file.

mod accuracy;
mod common;
mod edge_cases;
mod projection;
