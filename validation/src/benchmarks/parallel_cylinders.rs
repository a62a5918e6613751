//! parallel-cylinders (thesis §5.2.2, appendix A1): two identical elastic
//! half-cylinders R = 8 m, E = 200 Pa, ν = 0.3, μ = 0.2, pressed together
//! by F = 10 N per metre (increment 1), then sheared by Q = 0.93616 N
//! (increment 2). Normal pressure against Hertz (A4–A5) and tangential
//! traction against Cattaneo–Mindlin partial slip (A10–A11) on both bodies.
use super::{read_case, swap_master_slave, RunCost};
use crate::analytical::{contact_modulus, face_average, HertzLine};
use crate::run_toml;
use contact_force::FrictionState;

/// Radius of both cylinders, m.
pub const RADIUS: f64 = 8.0;
/// Young's modulus of both cylinders, Pa.
pub const YOUNG: f64 = 200.0;
/// Poisson's ratio of both cylinders.
pub const POISSON: f64 = 0.3;
/// Coefficient of friction.
pub const FRICTION: f64 = 0.2;
/// Tangential force of increment 2, N per metre (0.05851 Pa over the 16 m top).
pub const SHEAR: f64 = 0.93616;
/// Stick half-width over contact half-width for Q/(μF) = 0.468 (A11).
pub const STICK_RATIO: f64 = 0.7293;

/// One contact face of one cylinder as measured.
#[derive(Debug, Clone, Copy)]
pub struct ContactFace {
    /// Face-centre x relative to the centre of pressure, m.
    pub x: f64,
    /// Width of the face projected on x, m.
    pub width: f64,
    /// Contact pressure, Pa.
    pub pressure: f64,
    /// Tangential traction along +x on the lower cylinder (−x on the upper), Pa.
    pub shear: f64,
    /// Friction state.
    pub stick: bool,
}

/// One cylinder's contact surface against the analytical solution.
#[derive(Debug, Clone)]
pub struct CylinderProfile {
    /// "upper" or "lower".
    pub body: &'static str,
    /// Faces sorted by x.
    pub faces: Vec<ContactFace>,
    /// Centre of pressure Σ p w x / Σ p w on the deformed surface, m.
    pub centre: f64,
    /// max over faces |p − ⟨p_Hertz⟩| / p0 (⟨⟩: mean over the face).
    pub pressure_error: f64,
    /// max over faces |q − ⟨q_Cattaneo⟩| / (μ p0).
    pub shear_error: f64,
    /// Half the summed width of the faces in stick, m.
    pub stick_width_faces: f64,
    /// Stick half-width from the outermost stick face on each side,
    /// c² = x² + (1 − q/(μp))² (b² − x²) (A10 solved for c), averaged, m.
    pub stick_half_width: f64,
    /// Largest face width in the contact, m.
    pub face_width: f64,
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct ParallelCylinders {
    /// "coarse" or "fine".
    pub mesh: &'static str,
    /// 1: normal load only; 2: normal and tangential load.
    pub increment: usize,
    /// The upper cylinder is the master surface (else the lower is).
    pub swapped: bool,
    /// Normal contact force per metre, N/m.
    pub force: f64,
    /// Tangential contact force per metre on the lower cylinder, N/m.
    pub shear: f64,
    /// Hertz solution for that force (E* of the two cylinders, R = R/2).
    pub hertz: HertzLine,
    /// Cattaneo–Mindlin stick half-width c = b √(1 − Q/(μF)) for the measured forces, m.
    pub stick_half_width: f64,
    /// Upper and lower cylinder.
    pub profiles: [CylinderProfile; 2],
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

/// Runs `coarse` (`case.toml`) or `fine` (`fine.toml`) to the end of
/// `increment` (1 or 2).
pub fn run(mesh: &'static str, increment: usize, swapped: bool) -> ParallelCylinders {
    let file = if mesh == "fine" {
        "fine.toml"
    } else {
        "case.toml"
    };
    let (dir, mut text) = read_case("parallel-cylinders", file);
    if increment == 1 {
        text = text.replace("end = 2.0\nsteps = 2", "end = 1.0\nsteps = 1");
    }
    if swapped {
        text = swap_master_slave(&text, "lower/curved", "upper/curved");
    }
    let out = run_toml(&text, &dir);
    let c = &out.contacts.interfaces[0];
    let (upper, lower) = if swapped {
        (
            (&c.master, &c.tractions.master),
            (&c.slave, &c.tractions.slave),
        )
    } else {
        (
            (&c.slave, &c.tractions.slave),
            (&c.master, &c.tractions.master),
        )
    };
    // as the lower body receives it (undeformed areas, small strain)
    let force_on_lower = if swapped {
        c.stats.slave_force
    } else {
        c.stats.master_force
    };
    let force = -force_on_lower.y;
    let shear = force_on_lower.x;
    let hertz = HertzLine::new(
        force,
        RADIUS / 2.0,
        contact_modulus(Some((YOUNG, POISSON)), Some((YOUNG, POISSON))),
    );
    let stick = hertz.stick_half_width(shear.abs(), FRICTION, force);
    let profile = |body, (side, contact), sign| measure(body, side, contact, sign, &hertz, stick);
    ParallelCylinders {
        mesh,
        increment,
        swapped,
        force,
        shear,
        hertz,
        stick_half_width: stick,
        profiles: [profile("upper", upper, -1.0), profile("lower", lower, 1.0)],
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}

/// The faces of one side against Hertz and Cattaneo–Mindlin; `sign` turns
/// the traction on the side into the +x shear of the lower cylinder.
fn measure(
    body: &'static str,
    side: &solver_app::contact_coupling::ContactSide,
    contact: &contact_force::SurfaceContact,
    sign: f64,
    hertz: &HertzLine,
    stick: f64,
) -> CylinderProfile {
    let s = &side.surface;
    let mut faces: Vec<ContactFace> = (0..s.n_faces())
        .map(|f| ContactFace {
            x: s.face_centres[f].x,
            width: s.face_areas[f].y.abs(),
            pressure: contact.pressure[f],
            shear: sign * contact.tangential_traction[f].x,
            stick: contact.friction_state[f] == FrictionState::Stick,
        })
        .collect();
    let load: f64 = faces.iter().map(|f| f.pressure * f.width).sum();
    let centre = faces
        .iter()
        .map(|f| f.pressure * f.width * f.x)
        .sum::<f64>()
        / load.max(f64::MIN_POSITIVE);
    for f in faces.iter_mut() {
        f.x -= centre;
    }
    faces.sort_by(|a, b| a.x.total_cmp(&b.x));
    let (b, p0) = (hertz.half_width, hertz.peak_pressure);
    let mut pressure_error = 0.0f64;
    let mut shear_error = 0.0f64;
    let mut face_width = 0.0f64;
    for f in &faces {
        let p = face_average(|x| hertz.pressure(x), f.x, f.width);
        let q = face_average(
            |x| hertz.tangential_traction(x, stick, FRICTION),
            f.x,
            f.width,
        );
        pressure_error = pressure_error.max((f.pressure - p).abs() / p0);
        shear_error = shear_error.max((f.shear - q).abs() / (FRICTION * p0));
        if f.x.abs() < b {
            face_width = face_width.max(f.width);
        }
    }
    let stick_width_faces = 0.5
        * faces
            .iter()
            .filter(|f| f.stick)
            .map(|f| f.width)
            .sum::<f64>();
    // outermost stick face on either side of the centre: A10 inside the stick
    // zone gives 1 − q/(μp) = √(c² − x²)/√(b² − x²), solved for c
    let edge = |f: &ContactFace| {
        let r = 1.0 - f.shear / (FRICTION * f.pressure.max(f64::MIN_POSITIVE));
        (f.x * f.x + r * r * (b * b - f.x * f.x).max(0.0)).sqrt()
    };
    let left = faces.iter().find(|f| f.stick && f.x < 0.0).map(edge);
    let right = faces.iter().rev().find(|f| f.stick && f.x > 0.0).map(edge);
    let stick_half_width = match (left, right) {
        (Some(l), Some(r)) => 0.5 * (l + r),
        (Some(e), None) | (None, Some(e)) => e,
        (None, None) => 0.0,
    };
    CylinderProfile {
        body,
        faces,
        centre,
        pressure_error,
        shear_error,
        stick_width_faces,
        stick_half_width,
        face_width,
    }
}
