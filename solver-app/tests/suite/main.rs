//! The command-line, case-error and HDF5-output tests in one test binary
//! (each release test binary costs CI seconds of linking).

mod case_errors;
mod cli;
mod hdf5_output;
mod interrupt;
mod newton_residual;
