//! hertz-cylinder (thesis §5.2.1): a half-cylinder R = 8 m, E = 200 Pa,
//! ν = 0.3, plane strain, pressed 0.02 m onto a rigid flat; the contact
//! pressure against Hertz (A4–A6) with the computed normal force.
use super::{read_case, swap_master_slave, RunCost};
use crate::analytical::{contact_modulus, HertzLine};
use crate::run_toml;

/// Radius, m.
pub const RADIUS: f64 = 8.0;
/// Young's modulus, Pa.
pub const YOUNG: f64 = 200.0;
/// Poisson's ratio.
pub const POISSON: f64 = 0.3;

/// What one run measured.
#[derive(Debug, Clone)]
pub struct HertzCylinder {
    /// "coarse" or "fine".
    pub mesh: &'static str,
    /// The cylinder is the master surface (the rigid flat the slave).
    pub swapped: bool,
    /// Face-centre x and contact pressure of the cylinder's contact faces, sorted by x.
    pub profile: Vec<(f64, f64)>,
    /// Contact face width at the axis, m.
    pub face_width: f64,
    /// Normal force per unit length, N/m.
    pub force: f64,
    /// Hertz solution for that force.
    pub hertz: HertzLine,
    /// Largest face pressure / p0 − 1.
    pub peak_error: f64,
    /// Measured half-width (contact area / 2 per unit length), m.
    pub half_width: f64,
    /// RMS(p − p_Hertz)/p0 over the faces with centres in the Hertz contact |x| ≤ b.
    pub rms_error: f64,
    /// Depth below the surface and (σ_x, σ_z) of the cells nearest the axis, z < 3b.
    pub axis_stress: Vec<(f64, f64, f64)>,
    /// max |σ − σ_Hertz| / p0 along the axis (both components).
    pub axis_stress_error: f64,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

/// Runs the coarse (1,615 cells) or fine (6,460 cells) case.
pub fn run(mesh: &'static str, swapped: bool) -> HertzCylinder {
    run_edited(mesh, swapped, |text| text)
}

/// [`run`] with the case text changed by `edit` first (a setting probed).
pub fn run_edited(
    mesh: &'static str,
    swapped: bool,
    edit: impl Fn(String) -> String,
) -> HertzCylinder {
    let (dir, text) = read_case("hertz-cylinder", &format!("{mesh}.toml"));
    let mut text = edit(text);
    if swapped {
        text = swap_master_slave(&text, "flat/ymax", "cylinder/curved");
    }
    let out = run_toml(&text, &dir);
    let c = &out.contacts.interfaces[0];
    let (side, contact) = if swapped {
        (&c.master, &c.tractions.master)
    } else {
        (&c.slave, &c.tractions.slave)
    };
    let mut profile: Vec<(f64, f64)> = side
        .surface
        .face_centres
        .iter()
        .zip(&contact.pressure)
        .map(|(x, &p)| (x.x, p))
        .collect();
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    let face_width = side
        .surface
        .face_centres
        .iter()
        .zip(&side.surface.face_mag)
        .min_by(|a, b| a.0.x.abs().total_cmp(&b.0.x.abs()))
        .map_or(0.0, |(_, &a)| a);
    let force = c.stats.normal_force;
    let hertz = HertzLine::new(force, RADIUS, contact_modulus(Some((YOUNG, POISSON)), None));
    let p0 = hertz.peak_pressure;
    let peak = profile.iter().fold(0.0f64, |a, &(_, p)| a.max(p));
    let zone: Vec<f64> = profile
        .iter()
        .filter(|(x, _)| x.abs() <= hertz.half_width)
        .map(|&(x, p)| p - hertz.pressure(x))
        .collect();
    let rms = (zone.iter().map(|e| e * e).sum::<f64>() / zone.len().max(1) as f64).sqrt();
    // the column of cells nearest the axis (x ≥ 0 side; the meshes are
    // symmetric) below the lowest point y = −R, down to 3b
    let body = &out.bodies[0];
    let mut axis: Vec<(f64, f64, f64)> = Vec::new();
    let near = |c: &fv_mesh::Vector| c.x > -1e-9 && c.x < 0.75 * face_width;
    for (c, s) in body.geom.cell_centres.iter().zip(&body.momentum.sigma) {
        let depth = c.y + RADIUS;
        if near(c) && depth < 3.0 * hertz.half_width {
            axis.push((depth, s[(0, 0)], s[(1, 1)]));
        }
    }
    axis.sort_by(|a, b| a.0.total_cmp(&b.0));
    let axis_err = axis.iter().fold(0.0f64, |a, &(z, sx, sz)| {
        let (hx, hz) = hertz.axis_stress(z);
        a.max((sx - hx).abs()).max((sz - hz).abs())
    }) / p0;
    HertzCylinder {
        mesh,
        swapped,
        profile,
        face_width,
        force,
        hertz,
        peak_error: peak / p0 - 1.0,
        half_width: c.stats.contact_area / 2.0,
        rms_error: rms / p0,
        axis_stress: axis,
        axis_stress_error: axis_err,
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}
