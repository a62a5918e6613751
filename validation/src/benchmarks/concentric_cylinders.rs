//! concentric-cylinders (thesis §4.4.1): two hollow quarter cylinders of the
//! same material in contact at r = 1.4, inner pressure p; the interface
//! pressure against Lamé for the composite tube, and the pressure
//! oscillation of the non-conformal interface (40 against 30 faces).
use super::{read_case, swap_master_slave, RunCost};
use crate::analytical::lame_cylinder_stress;
use crate::run_toml;

/// Inner pressure of the case, Pa.
pub const PRESSURE: f64 = 10.0;

/// Interface pressure of the composite tube 1 ≤ r ≤ 2 at r = 1.4 (Lamé): 0.3469 p.
pub fn lame_interface_pressure() -> f64 {
    -lame_cylinder_stress(1.0, 2.0, PRESSURE, 1.4).0
}

/// Pressure statistics of one contact surface.
#[derive(Debug, Clone, Copy, Default)]
pub struct SidePressure {
    /// Area-weighted mean pressure.
    pub mean: f64,
    /// (max − min)/2 of the face pressures, relative to the mean.
    pub oscillation: f64,
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct ConcentricCylinders {
    /// "segment-to-segment" or "pointwise".
    pub algorithm: &'static str,
    /// The inner tube's surface is the master (the outer tube's the slave).
    pub swapped: bool,
    /// Inner tube's contact surface (`inner/outer`).
    pub inner: SidePressure,
    /// Outer tube's contact surface (`outer/inner`).
    pub outer: SidePressure,
    /// Face angle (degrees) and pressure on the inner tube's surface, sorted by angle.
    pub inner_profile: Vec<(f64, f64)>,
    /// The same on the outer tube's surface.
    pub outer_profile: Vec<(f64, f64)>,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

fn side_stats(surface: &fv_mesh::Surface, p: &[f64]) -> (SidePressure, Vec<(f64, f64)>) {
    let area: f64 = surface.face_mag.iter().sum();
    let mean = surface
        .face_mag
        .iter()
        .zip(p)
        .map(|(a, p)| a * p)
        .sum::<f64>()
        / area;
    let (lo, hi) = p
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
            (l.min(x), h.max(x))
        });
    let mut profile: Vec<(f64, f64)> = surface
        .face_centres
        .iter()
        .zip(p)
        .map(|(c, &p)| (c.y.atan2(c.x).to_degrees(), p))
        .collect();
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    (
        SidePressure {
            mean,
            oscillation: 0.5 * (hi - lo) / mean,
        },
        profile,
    )
}

/// Runs the case with the given algorithm and choice of master.
pub fn run(algorithm: &'static str, swapped: bool) -> ConcentricCylinders {
    let (dir, mut text) = read_case("concentric-cylinders", "case.toml");
    text = text.replace(
        "coupling = \"implicit\"",
        &format!("coupling = \"implicit\"\nalgorithm = \"{algorithm}\""),
    );
    if swapped {
        text = swap_master_slave(&text, "outer/inner", "inner/outer");
    }
    let out = run_toml(&text, &dir);
    let c = &out.contacts.interfaces[0];
    let ((inner, ip), (outer, op)) = if swapped {
        (
            side_stats(&c.master.surface, &c.tractions.master.pressure),
            side_stats(&c.slave.surface, &c.tractions.slave.pressure),
        )
    } else {
        (
            side_stats(&c.slave.surface, &c.tractions.slave.pressure),
            side_stats(&c.master.surface, &c.tractions.master.pressure),
        )
    };
    ConcentricCylinders {
        algorithm,
        swapped,
        inner,
        outer,
        inner_profile: ip,
        outer_profile: op,
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}
