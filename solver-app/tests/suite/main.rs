//! The command-line, case-error, example and HDF5-output tests in one test binary
//! (each release test binary costs CI seconds of linking).

mod case_errors;
mod case_format_doc;
mod cli;
mod examples;
mod fuzz_corpus;
mod hdf5_output;
mod interrupt;
mod newton_residual;
mod paraview;
mod plot;
mod restart;
