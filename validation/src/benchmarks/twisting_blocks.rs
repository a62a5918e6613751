//! twisting-blocks (thesis §4.4.1, Fig. 4.25): an upper unit cube pushed
//! onto a lower one and turned 90° about the vertical axis, frictionless;
//! the contact area changes gradually (partial contact of many faces). The
//! vertical reaction against the angle must not depend on which side is
//! the master.
use super::{read_case, swap_master_slave, RunCost};
use crate::run_toml_with_history;

/// Degrees turned per increment after the push (90° in 18 increments).
pub const DEGREES_PER_INCREMENT: f64 = 5.0;

/// What one run measured.
#[derive(Debug, Clone)]
pub struct TwistingBlocks {
    /// The upper block's bottom is the master surface (else the lower's top).
    pub swapped: bool,
    /// (angle in degrees, vertical reaction on the lower block's bottom), one per increment.
    pub reaction: Vec<(f64, f64)>,
    /// Outer iterations of each increment.
    pub outer_iterations: Vec<f64>,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

/// Runs the shipped case, with the lower block's top as master unless `swapped`.
pub fn run(swapped: bool) -> TwistingBlocks {
    run_algorithm(swapped, None)
}

/// [`run`] with another contact algorithm (`algorithm = "..."` of the pair).
pub fn run_algorithm(swapped: bool, algorithm: Option<&str>) -> TwistingBlocks {
    let (_, mut text) = read_case("twisting-blocks", "case.toml");
    if let Some(a) = algorithm {
        text = text.replace(
            "coupling = \"implicit\"",
            &format!("coupling = \"implicit\"\nalgorithm = \"{a}\""),
        );
    }
    if swapped {
        text = swap_master_slave(&text, "lower/zmax", "upper/zmin");
    }
    let (out, history) = run_toml_with_history(&text);
    let time = history.column("time");
    let fz = history.column("lower/zmin:Fz");
    let reaction = time
        .iter()
        .zip(&fz)
        .map(|(&t, &f)| (DEGREES_PER_INCREMENT * (t - 1.0).max(0.0), f))
        .collect();
    TwistingBlocks {
        swapped,
        reaction,
        outer_iterations: history.column("outer_iterations"),
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}
