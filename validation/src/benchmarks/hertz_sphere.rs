//! Axisymmetric Hertz contact (thesis appendix A2, eqs. A13–A16): the lower
//! half of a sphere R = 8 m, E = 200 Pa, ν = 0.3, pressed 0.02 m onto a
//! rigid flat; a one-cell wedge of ±2.5°. The contact pressure against
//! Hertz with the computed full-revolution force.
use super::{read_case, swap_master_slave, RunCost};
use crate::run_toml;

/// Radius, m.
pub const RADIUS: f64 = 8.0;
/// Young's modulus, Pa.
pub const YOUNG: f64 = 200.0;
/// Poisson's ratio.
pub const POISSON: f64 = 0.3;

/// Hertz contact of a sphere on a rigid flat (A9, A13, A16).
#[derive(Debug, Clone, Copy)]
pub struct HertzSphere {
    /// Contact radius b = (3FR/(4E_c))^(1/3).
    pub radius: f64,
    /// Peak pressure p0 = 3F/(2πb²).
    pub peak_pressure: f64,
}

impl HertzSphere {
    /// For the full normal force `force`.
    pub fn new(force: f64) -> Self {
        let ec = YOUNG / (1.0 - POISSON * POISSON);
        let b = (3.0 * force * RADIUS / (4.0 * ec)).cbrt();
        HertzSphere {
            radius: b,
            peak_pressure: 3.0 * force / (2.0 * std::f64::consts::PI * b * b),
        }
    }

    /// A15: p(r) = p0 √(1 − r²/b²).
    pub fn pressure(&self, r: f64) -> f64 {
        let x = r / self.radius;
        if x < 1.0 {
            self.peak_pressure * (1.0 - x * x).sqrt()
        } else {
            0.0
        }
    }
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct SphereRun {
    /// The sphere is the master surface (the rigid flat the slave).
    pub swapped: bool,
    /// Full-revolution normal force (the wedge's times 2π/angle), N.
    pub force: f64,
    /// Hertz for that force.
    pub hertz: HertzSphere,
    /// Face-centre radius and contact pressure of the sphere's contact faces, sorted.
    pub profile: Vec<(f64, f64)>,
    /// Largest face pressure / p0 − 1.
    pub peak_error: f64,
    /// RMS(p − p_Hertz)/p0 over the faces with r ≤ b.
    pub rms_error: f64,
    /// Contact radius from the full-revolution contact area, √(A/π), m.
    pub contact_radius: f64,
    /// Radial width of the contact faces near the contact edge, m.
    pub face_width: f64,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

/// Runs the case with the rigid flat as master or (`swapped`) as slave.
pub fn run(swapped: bool) -> SphereRun {
    run_edited(swapped, |text| text)
}

/// [`run`] with the case text changed by `edit` first (settings probed).
pub fn run_edited(swapped: bool, edit: impl Fn(String) -> String) -> SphereRun {
    let (dir, text) = read_case("hertz-sphere", "case.toml");
    let mut text = edit(text);
    if swapped {
        text = swap_master_slave(&text, "flat/ymax", "sphere/curved");
    }
    let out = run_toml(&text, &dir);
    let c = &out.contacts.interfaces[0];
    let (side, contact) = if swapped {
        (&c.master, &c.tractions.master)
    } else {
        (&c.slave, &c.tractions.slave)
    };
    let angle = solver_app::results::wedge_of(&out.bodies).map_or(0.0, |w| w.1);
    let factor = std::f64::consts::TAU / angle.max(f64::MIN_POSITIVE);
    let force = c.stats.normal_force * factor;
    let hertz = HertzSphere::new(force);
    let mut profile: Vec<(f64, f64)> = side
        .surface
        .face_centres
        .iter()
        .zip(&contact.pressure)
        .map(|(x, &p)| (x.x.hypot(x.z), p))
        .collect();
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    let p0 = hertz.peak_pressure;
    let peak = profile.iter().fold(0.0f64, |a, &(_, p)| a.max(p));
    let zone: Vec<f64> = profile
        .iter()
        .filter(|(r, _)| *r <= hertz.radius)
        .map(|&(r, p)| p - hertz.pressure(r))
        .collect();
    let rms = (zone.iter().map(|e| e * e).sum::<f64>() / zone.len().max(1) as f64).sqrt();
    let contact_radius = (c.stats.contact_area * factor / std::f64::consts::PI).sqrt();
    let i = profile
        .partition_point(|p| p.0 < hertz.radius)
        .clamp(1, profile.len().max(2) - 1);
    let face_width = match (profile.get(i - 1), profile.get(i)) {
        (Some(a), Some(b)) => b.0 - a.0,
        _ => 0.0,
    };
    SphereRun {
        swapped,
        force,
        hertz,
        profile,
        peak_error: peak / p0 - 1.0,
        rms_error: rms / p0,
        contact_radius,
        face_width,
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}
