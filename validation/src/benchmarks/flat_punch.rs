//! flat-punch (thesis §5.2.3): a rigid flat punch of half-width b = 0.01 m
//! pressed 0.0967 mm into a 2H × H block (plane stress, half model); the
//! contact pressure against A20 with the computed force, and the surface
//! settlement outside the punch against the shape of A22.
use super::{read_case, swap_master_slave, RunCost};
use crate::run_toml;

/// Punch half-width b, m.
pub const HALF_WIDTH: f64 = 0.01;
/// Young's modulus, Pa.
pub const YOUNG: f64 = 200e9;
/// Block height H, m.
pub const HEIGHT: f64 = 0.2;
/// Poisson's ratio.
pub const POISSON: f64 = 0.3;

/// A20: p(x) = F / (π √(b² − x²)) for |x| < b, F per unit thickness.
pub fn punch_pressure(force: f64, x: f64) -> f64 {
    let b = HALF_WIDTH;
    if x.abs() < b {
        force / (std::f64::consts::PI * (b * b - x * x).sqrt())
    } else {
        0.0
    }
}

/// A21: indentation depth d = F/(πE) [2 ln(2L/b) − (1 + ν)] (plane stress).
pub fn indentation_depth(force: f64) -> f64 {
    force / (std::f64::consts::PI * YOUNG)
        * (2.0 * (2.0 * HEIGHT / HALF_WIDTH).ln() - (1.0 + POISSON))
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct FlatPunch {
    /// The block is the master (the punch the slave).
    pub swapped: bool,
    /// Normal force of the full model per unit thickness (twice the half model), N/m.
    pub force: f64,
    /// Face-centre x and contact pressure of the block's top faces under the punch.
    pub profile: Vec<(f64, f64)>,
    /// max |p/p_A20 − 1| over the faces with |x| ≤ 0.8 b.
    pub pressure_error: f64,
    /// Surface points outside the punch: x and settlement relative to the
    /// punch edge, w(b) − w(x), measured and by A22 (2F/(πE) arccosh(x/b)).
    pub settlement: Vec<(f64, f64, f64)>,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

/// Runs the case, with the rigid punch as master or (`swapped`) as slave.
pub fn run(swapped: bool) -> FlatPunch {
    let (dir, mut text) = read_case("flat-punch", "case.toml");
    if swapped {
        text = swap_master_slave(&text, "punch/ymin", "block/top");
    }
    let out = run_toml(&text, &dir);
    let c = &out.contacts.interfaces[0];
    let (side, contact) = if swapped {
        (&c.master, &c.tractions.master)
    } else {
        (&c.slave, &c.tractions.slave)
    };
    let force = 2.0 * c.stats.normal_force;
    let mut profile: Vec<(f64, f64)> = side
        .surface
        .face_centres
        .iter()
        .zip(&contact.pressure)
        .filter(|(x, _)| x.x < HALF_WIDTH * 1.2)
        .map(|(x, &p)| (x.x, p))
        .collect();
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    let pressure_error = profile
        .iter()
        .filter(|(x, _)| x.abs() <= 0.8 * HALF_WIDTH)
        .fold(0.0f64, |a, &(x, p)| {
            a.max((p / punch_pressure(force, x) - 1.0).abs())
        });
    // settlement of the top face centres (boundary displacement) beyond the punch
    let body = &out.bodies[0];
    let mut top: Vec<(f64, f64)> = Vec::new();
    if let Some(p) = body.mesh.patch_index("top") {
        let ni = body.mesh.n_internal_faces();
        for f in body.mesh.patches[p].faces() {
            top.push((body.geom.face_centres[f].x, -body.momentum.u_b[f - ni].y));
        }
    }
    top.sort_by(|a, b| a.0.total_cmp(&b.0));
    let w_edge = interpolate(&top, HALF_WIDTH);
    let scale = 2.0 * force / (std::f64::consts::PI * YOUNG);
    let settlement = top
        .iter()
        .filter(|(x, _)| *x > HALF_WIDTH && *x < 0.5 * HEIGHT)
        .map(|&(x, w)| (x, w_edge - w, scale * (x / HALF_WIDTH).acosh()))
        .collect();
    FlatPunch {
        swapped,
        force,
        profile,
        pressure_error,
        settlement,
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}

/// Linear interpolation in a table sorted by x.
fn interpolate(table: &[(f64, f64)], x: f64) -> f64 {
    let i = table
        .partition_point(|p| p.0 < x)
        .clamp(1, table.len().max(2) - 1);
    match (table.get(i - 1), table.get(i)) {
        (Some(&(x0, y0)), Some(&(x1, y1))) if x1 > x0 => y0 + (y1 - y0) * (x - x0) / (x1 - x0),
        (Some(&(_, y0)), _) => y0,
        _ => 0.0,
    }
}
