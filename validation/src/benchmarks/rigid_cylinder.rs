//! rigid-cylinder-indent (issue 9, Nagata smoothing acceptance): a rigid
//! cylinder R = 8 m whose surface is a polygon of 68 facets over 0.6 rad
//! (0.071 m, about 8 across the Hertz contact width) pressed 0.02 m into a
//! deformable block (E = 200 Pa, ν = 0.3, plane strain, 0.02 m faces on the
//! contact). The cylinder is the master: the smoothed algorithm variants
//! replace its facets by Nagata patches (thesis §4.6.1). The block's
//! contact pressure is compared with Hertz (A4–A5, one rigid body:
//! E* = E/(1 − ν²)) for the computed force.
use super::{read_case, RunCost};
use crate::analytical::{contact_modulus, HertzLine};
use crate::run_toml;

/// Cylinder radius, m.
pub const RADIUS: f64 = 8.0;
/// Block Young's modulus, Pa.
pub const YOUNG: f64 = 200.0;
/// Block Poisson's ratio.
pub const POISSON: f64 = 0.3;
/// Facets of the cylinder in the shipped case (over 0.6 rad).
pub const FACETS: usize = 68;

/// What one run measured.
#[derive(Debug, Clone)]
pub struct RigidCylinder {
    /// Contact algorithm name.
    pub algorithm: String,
    /// Facets of the cylinder over 0.6 rad.
    pub facets: usize,
    /// Facet width, m.
    pub facet_width: f64,
    /// Face-centre x and contact pressure of the block's contact faces, sorted by x.
    pub profile: Vec<(f64, f64)>,
    /// Normal force per unit length, N/m.
    pub force: f64,
    /// Hertz solution for that force.
    pub hertz: HertzLine,
    /// Largest face pressure / p0 − 1.
    pub peak_error: f64,
    /// RMS(p − p_Hertz)/p0 over the faces with centres in |x| ≤ b.
    pub rms_error: f64,
    /// max |p − p_Hertz|/p0 over the faces with centres in |x| ≤ 0.8 b.
    pub max_error: f64,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

/// Runs the case with contact algorithm `algorithm` and a cylinder of
/// `facets` facets over 0.6 rad ([`FACETS`] in the shipped case).
pub fn run(algorithm: &str, facets: usize) -> RigidCylinder {
    let (dir, text) = read_case("rigid-cylinder-indent", "case.toml");
    let text = text
        .replace(
            "algorithm = \"segment-to-segment\"",
            &format!("algorithm = \"{algorithm}\""),
        )
        .replace(
            &format!("cells = [1, {FACETS}, 1]"),
            &format!("cells = [1, {facets}, 1]"),
        );
    let out = run_toml(&text, &dir);
    let c = &out.contacts.interfaces[0];
    let (side, contact) = (&c.slave, &c.tractions.slave);
    let mut profile: Vec<(f64, f64)> = side
        .surface
        .face_centres
        .iter()
        .zip(&contact.pressure)
        .map(|(x, &p)| (x.x, p))
        .collect();
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    let force = c.stats.normal_force;
    let hertz = HertzLine::new(force, RADIUS, contact_modulus(Some((YOUNG, POISSON)), None));
    let p0 = hertz.peak_pressure;
    let peak = profile.iter().fold(0.0f64, |a, &(_, p)| a.max(p));
    let errors = |within: f64| -> Vec<f64> {
        profile
            .iter()
            .filter(|(x, _)| x.abs() <= within * hertz.half_width)
            .map(|&(x, p)| (p - hertz.pressure(x)) / p0)
            .collect()
    };
    let zone = errors(1.0);
    let rms = (zone.iter().map(|e| e * e).sum::<f64>() / zone.len().max(1) as f64).sqrt();
    let max_error = errors(0.8).iter().fold(0.0f64, |a, e| a.max(e.abs()));
    RigidCylinder {
        algorithm: algorithm.to_string(),
        facets,
        facet_width: 2.0 * RADIUS * (0.3 / facets as f64).sin(),
        profile,
        force,
        hertz,
        peak_error: peak / p0 - 1.0,
        rms_error: rms,
        max_error,
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}
