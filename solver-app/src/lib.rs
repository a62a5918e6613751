//! The `fvc` application as a library: case file, model set-up, the
//! segregated solution procedure of thesis §3.3, and the result files.
//!
//! ```no_run
//! use solver_app::{case::load_case, run::{run_case, RunOptions}};
//! let case = load_case(std::path::Path::new("examples/lame-cylinder/case.toml"))?;
//! let outcome = run_case(&case, &RunOptions::default())?;
//! println!("converged: {}", outcome.converged);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod anderson;
pub mod background_writer;
pub mod case;
pub mod check;
pub mod contact_coupling;
pub mod coupled_spring_solve;
pub mod field_output;
pub mod initial_overlap;
pub mod interrupt;
pub mod mesh_loading;
pub mod model;
pub mod newton;
pub mod nonlinear_solver;
pub mod output;
pub mod plot;
pub mod predictor;
pub mod profile;
pub mod progress;
pub mod restart;
pub mod results;
pub mod run;
pub mod segregated;
pub mod springs_in_turn;
pub mod words;
