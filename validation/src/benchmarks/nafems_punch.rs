//! nafems-punch and nafems-punch-modified (thesis §5.2.4, appendix A3.1):
//! an elastic punch with a rounded edge pressed into an elastic foundation,
//! axisymmetric (one-cell wedges of ±2.5°). Measures the foundation's
//! surface displacement and contact pressure along r, the full-revolution
//! force and the contact radius; the modified punch against the
//! semi-analytical pressure of eq. A26.
use super::{read_case, swap_master_slave, RunCost};
use crate::run_toml;

/// Code_Aster SSNA122 (NAFEMS, Konter 2006): foundation axial displacement
/// on the axis with μ = 0.1, mm.
pub const AXIS_DISPLACEMENT_FRICTION: f64 = -0.12858;
/// The same without friction, mm.
pub const AXIS_DISPLACEMENT_FRICTIONLESS: f64 = -0.130734;
/// Independent reference for the same set-up: axisymmetric biquadratic
/// finite elements, mesh-converged (`cases/nafems-punch/fe_reference.py`,
/// element size 0.25 mm at the contact; 0.5 mm differs by < 0.02 %):
/// foundation axial displacement on the axis with μ = 0.1, mm. SSNA122's
/// value (an average of Marc and Abaqus results) is 2.4 % smaller.
pub const FE_AXIS_DISPLACEMENT_FRICTION: f64 = -0.131758;
/// The same without friction, mm (SSNA122: 2.4 % smaller).
pub const FE_AXIS_DISPLACEMENT_FRICTIONLESS: f64 = -0.133932;
/// Contact pressure on the axis of the same finite-element reference with
/// μ = 0.1, MPa (Marc 70.5, Abaqus 71.2 in `../shared/benchmarks`).
pub const FE_AXIS_PRESSURE_FRICTION: f64 = 88.65;
/// The same without friction, MPa.
pub const FE_AXIS_PRESSURE_FRICTIONLESS: f64 = 87.22;
/// Modified punch: flat radius a, fillet radius R (mm), contact modulus of
/// two bodies with E = 70 GPa, ν = 0.3: E* = E / (2(1 − ν²)) (MPa).
pub const MODIFIED_FLAT: f64 = 10.0;
/// Fillet radius of the modified punch, mm.
pub const MODIFIED_FILLET: f64 = 100.0;
/// E* of the modified case, MPa.
pub const MODIFIED_MODULUS: f64 = 70_000.0 / (2.0 * (1.0 - 0.09));
/// Top pressure of the modified case (thesis, for a 12.5 mm contact radius), MPa.
pub const MODIFIED_PRESSURE: f64 = 37.588;
/// Punch radius, mm.
pub const PUNCH_RADIUS: f64 = 50.0;

/// Which case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// nafems-punch, μ = 0.1.
    Friction,
    /// nafems-punch, μ = 0.
    Frictionless,
    /// nafems-punch-modified (frictionless, both E = 70 GPa).
    Modified,
}

impl Variant {
    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Friction => "μ = 0.1",
            Variant::Frictionless => "frictionless",
            Variant::Modified => "modified",
        }
    }
}

/// What one run measured (lengths mm, forces N, pressures MPa).
#[derive(Debug, Clone)]
pub struct NafemsPunch {
    /// The case.
    pub variant: Variant,
    /// The punch is the master surface (the shipped cases have the foundation master).
    pub swapped: bool,
    /// Wedge opening angle, rad.
    pub wedge_angle: f64,
    /// Contact normal force of the full revolution (the wedge's times 2π/angle).
    pub force: f64,
    /// Foundation contact faces: r of the face centre, contact pressure, axial and radial displacement.
    pub surface: Vec<(f64, f64, f64, f64)>,
    /// Axial displacement of the foundation face on the axis.
    pub axis_displacement: f64,
    /// Contact pressure of the foundation face on the axis.
    pub axis_pressure: f64,
    /// Contact radius from the full-revolution contact area, √(A/π).
    pub contact_radius: f64,
    /// Radial width of the foundation contact faces near the contact edge.
    pub face_width: f64,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

/// Runs a case with the foundation as master or (`swapped`) as slave.
pub fn run(variant: Variant, swapped: bool) -> NafemsPunch {
    let (dir, text) = match variant {
        Variant::Modified => read_case("nafems-punch-modified", "case.toml"),
        _ => read_case("nafems-punch", "case.toml"),
    };
    run_text(variant, swapped, &dir, text)
}

/// [`run`] on the case text `text` whose relative mesh paths resolve
/// against `dir` (mesh-convergence and parameter studies).
pub fn run_text(
    variant: Variant,
    swapped: bool,
    dir: &std::path::Path,
    mut text: String,
) -> NafemsPunch {
    if variant == Variant::Frictionless {
        text = text.replace("friction = 0.1", "friction = 0.0");
    }
    if swapped {
        text = swap_master_slave(&text, "foundation/contact", "punch/contact");
    }
    let out = run_toml(&text, dir);
    let c = &out.contacts.interfaces[0];
    let (side, contact) = if swapped {
        (&c.slave, &c.tractions.slave)
    } else {
        (&c.master, &c.tractions.master)
    };
    let wedge_angle = solver_app::results::wedge_of(&out.bodies).map_or(0.0, |w| w.1);
    let factor = std::f64::consts::TAU / wedge_angle.max(f64::MIN_POSITIVE);
    let body = &out.bodies[0];
    let ni = body.mesh.n_internal_faces();
    let mut surface = Vec::new();
    if let Some(p) = body.mesh.patch_index("contact") {
        for (i, f) in body.mesh.patches[p].faces().enumerate() {
            let x = body.geom.face_centres[f];
            let r = x.x.hypot(x.z);
            let u = body.momentum.u_b[f - ni];
            let ur = (u.x * x.x + u.z * x.z) / r.max(f64::MIN_POSITIVE);
            let p = contact.pressure.get(i).copied().unwrap_or(0.0);
            surface.push((r, p, u.y, ur));
        }
    }
    surface.sort_by(|a, b| a.0.total_cmp(&b.0));
    let first = surface.first().copied().unwrap_or_default();
    let contact_radius = (c.stats.contact_area * factor / std::f64::consts::PI).sqrt();
    let radii: Vec<f64> = side
        .surface
        .face_centres
        .iter()
        .map(|x| x.x.hypot(x.z))
        .collect();
    let face_width = width_near(&radii, contact_radius);
    NafemsPunch {
        variant,
        swapped,
        wedge_angle,
        force: c.stats.normal_force * factor,
        surface,
        axis_displacement: first.2,
        axis_pressure: first.1,
        contact_radius,
        face_width,
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}

/// Spacing of the sorted face-centre radii around `r`.
fn width_near(radii: &[f64], r: f64) -> f64 {
    let mut v = radii.to_vec();
    v.sort_by(f64::total_cmp);
    let i = v.partition_point(|&x| x < r).clamp(1, v.len().max(2) - 1);
    match (v.get(i - 1), v.get(i)) {
        (Some(a), Some(b)) => b - a,
        _ => 0.0,
    }
}

/// A25: force of the flat-ended indenter with rounded edge (flat radius a,
/// fillet R, contact modulus E*) for contact radius b ≥ a.
pub fn a25_force(a: f64, r_fillet: f64, modulus: f64, b: f64) -> f64 {
    let s = (b * b - a * a).max(0.0).sqrt();
    modulus / (3.0 * r_fillet) * (s * (4.0 * b * b - a * a) - 3.0 * a * b * b * (a / b).acos())
}

/// Contact radius for force `force` by A25 (bisection on b ∈ (a, 10a)).
pub fn a25_radius(a: f64, r_fillet: f64, modulus: f64, force: f64) -> f64 {
    let (mut lo, mut hi) = (a, 10.0 * a);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if a25_force(a, r_fillet, modulus, m) < force {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

/// A26 normalised by the mean pressure F/(πb²) of A25: p(r)/p_mean for a
/// flat radius a and contact radius b (independent of E* and R). The
/// integral ∫ (2√(x² − a²) − a arccos(a/x)) dx/√(x² − r²) from max(r, a)
/// to b is taken in t = √(x² − r²) (no singularity), Simpson's rule.
pub fn a26_ratio(a: f64, b: f64, r: f64) -> f64 {
    if r >= b {
        return 0.0;
    }
    let lo = r.max(a);
    let (t0, t1) = ((lo * lo - r * r).max(0.0).sqrt(), (b * b - r * r).sqrt());
    let g = |t: f64| {
        let x = (r * r + t * t).sqrt();
        (2.0 * (x * x - a * a).max(0.0).sqrt() - a * (a / x).min(1.0).acos()) / x
    };
    let n = 2000;
    let h = (t1 - t0) / n as f64;
    let mut sum = g(t0) + g(t1);
    for i in 1..n {
        sum += g(t0 + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    let integral = sum * h / 3.0;
    // p = E*/(πR) ∫…, p_mean = A25(E*, R)/(π b²): E* and R cancel
    let p_mean = a25_force(a, 1.0, 1.0, b) / (std::f64::consts::PI * b * b);
    integral / std::f64::consts::PI / p_mean
}

impl NafemsPunch {
    /// Modified case: max |(p/p_mean)/(A26) − 1| over the faces with
    /// r ≤ `fraction` · b (b the measured contact radius), and the points
    /// (r/b, p/p_mean, A26) compared.
    pub fn a26_error(&self, fraction: f64) -> (f64, Vec<(f64, f64, f64)>) {
        let b = self.contact_radius;
        let p_mean = self.force / (std::f64::consts::PI * b * b);
        let pts: Vec<(f64, f64, f64)> = self
            .surface
            .iter()
            .filter(|s| s.0 <= fraction * b)
            .map(|s| (s.0 / b, s.1 / p_mean, a26_ratio(MODIFIED_FLAT, b, s.0)))
            .collect();
        let e = pts
            .iter()
            .fold(0.0f64, |m, &(_, p, a)| m.max((p / a - 1.0).abs()));
        (e, pts)
    }
}

/// `cases/nafems-punch/foundation-disc.toml`: the foundation alone under
/// 156.25 MPa on r < 40 mm (no contact). The biquadratic FE reference
/// (`fe_reference.py disc`, mesh-converged to < 0.003 %): (r, u_y) in mm.
pub const DISC_FE: [(f64, f64); 5] = [
    (0.0, -0.165254),
    (10.0, -0.162780),
    (20.0, -0.154943),
    (30.0, -0.139988),
    (35.0, -0.128134),
];

/// Runs `foundation-disc.toml`: r, u_y and u_r of the loaded faces (sorted
/// by r) and whether the run converged.
pub fn run_disc() -> (Vec<(f64, f64, f64)>, bool) {
    let (dir, text) = read_case("nafems-punch", "foundation-disc.toml");
    let out = run_toml(&text, &dir);
    let body = &out.bodies[0];
    let ni = body.mesh.n_internal_faces();
    let mut faces = Vec::new();
    if let Some(p) = body.mesh.patch_index("load") {
        for f in body.mesh.patches[p].faces() {
            let x = body.geom.face_centres[f];
            let r = x.x.hypot(x.z);
            let u = body.momentum.u_b[f - ni];
            faces.push((r, u.y, (u.x * x.x + u.z * x.z) / r.max(f64::MIN_POSITIVE)));
        }
    }
    faces.sort_by(|a, b| a.0.total_cmp(&b.0));
    (faces, out.converged)
}

/// Linear interpolation of u_y between the face centres (the first face's
/// value below its centre).
pub fn interpolate_uy(faces: &[(f64, f64, f64)], r: f64) -> f64 {
    let i = faces.partition_point(|f| f.0 < r);
    match (i.checked_sub(1).and_then(|j| faces.get(j)), faces.get(i)) {
        (Some(a), Some(b)) => a.1 + (b.1 - a.1) * (r - a.0) / (b.0 - a.0),
        (None, Some(b)) => b.1,
        (Some(a), None) => a.1,
        (None, None) => f64::NAN,
    }
}
