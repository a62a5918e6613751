//! sphere-block (thesis §5.2.5): the lower half of a sphere, R = 1 m,
//! pressed onto a block, half-symmetry model (plane y = 0), top of the
//! sphere moved down 0.01 m in one step; the block deformable
//! (E_s/E_b = 3, ν_b/ν_s = 1.1) or rigid. The contact pressure, the contact
//! radius and the stresses on the axis (A13–A16, A19) against Hertz with
//! the computed normal force.
use super::{read_case, swap_master_slave, RunCost};
use crate::analytical::{contact_modulus, HertzPoint};
use crate::run_toml;

/// Sphere radius, m (the lowest point at the origin, the centre at z = R).
pub const RADIUS: f64 = 1.0;
/// Sphere: Young's modulus (Pa) and Poisson's ratio.
pub const SPHERE: (f64, f64) = (600.0, 0.3);
/// Block: Young's modulus (Pa) and Poisson's ratio (E_s/E_b = 3, ν_b/ν_s = 1.1).
pub const BLOCK: (f64, f64) = (200.0, 0.33);
/// Edge of the block's cells at the contact point (`block.geo`: h), m.
pub const BLOCK_FACE: f64 = 0.014;

/// The two variants of the benchmark.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// Deformable block (`case.toml`).
    Deformable,
    /// Rigid block (`case-rigid.toml`).
    Rigid,
}

impl Variant {
    /// Both, in report order.
    pub const ALL: [Variant; 2] = [Variant::Deformable, Variant::Rigid];

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Deformable => "deformable block",
            Variant::Rigid => "rigid block",
        }
    }

    fn file(self) -> &'static str {
        match self {
            Variant::Deformable => "case.toml",
            Variant::Rigid => "case-rigid.toml",
        }
    }

    /// The block's contact surface (the master in the shipped cases).
    pub fn block_surface(self) -> &'static str {
        match self {
            Variant::Deformable => "block/top",
            Variant::Rigid => "block/zmax",
        }
    }

    /// E* of A13: both bodies, or the sphere alone on the rigid block.
    pub fn contact_modulus(self) -> f64 {
        match self {
            Variant::Deformable => contact_modulus(Some(SPHERE), Some(BLOCK)),
            Variant::Rigid => contact_modulus(Some(SPHERE), None),
        }
    }
}

/// Stresses along the axis below (above) the contact in one body.
#[derive(Debug, Clone, Default)]
pub struct AxisStress {
    /// Depth below the undeformed surface, σ_rr, σ_zz (Pa), one row per
    /// depth (the cells nearest the axis at that depth averaged), z < 3b.
    pub rows: Vec<(f64, f64, f64)>,
    /// max |σ_rr − A19| / p0.
    pub rr_error: f64,
    /// max |σ_zz − A19| / p0.
    pub zz_error: f64,
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct SphereBlock {
    /// Deformable or rigid block.
    pub variant: Variant,
    /// The sphere is the master surface (the block the slave).
    pub swapped: bool,
    /// Whole-model normal force (twice the half model's), N.
    pub force: f64,
    /// Hertz for that force.
    pub hertz: HertzPoint,
    /// Radius (from the z axis) and contact pressure of the sphere's contact faces, sorted.
    pub profile: Vec<(f64, f64)>,
    /// Largest sphere face pressure / p0 − 1.
    pub peak_error: f64,
    /// RMS(p − p_Hertz)/p0 over the sphere faces with r ≤ b.
    pub rms_error: f64,
    /// Contact radius from the contact area of the half model, √(2A/π), m.
    pub contact_radius: f64,
    /// Radial width of the sphere's contact faces at r = b, m.
    pub face_width: f64,
    /// Stresses on the axis in the sphere (ν_s).
    pub sphere_axis: AxisStress,
    /// Stresses on the axis in the block (ν_b); empty for the rigid block.
    pub block_axis: AxisStress,
    /// Whether the run converged.
    pub converged: bool,
    /// Cost.
    pub cost: RunCost,
}

impl SphereBlock {
    /// The larger of the sphere's σ_rr and σ_zz axis errors, / p0.
    pub fn sphere_axis_error(&self) -> f64 {
        self.sphere_axis.rr_error.max(self.sphere_axis.zz_error)
    }
}

/// Cells of `body` within `near` of the z axis, grouped by depth (a
/// relative tolerance of 1e-6 R), with `depth(z)` below the undeformed
/// contact point and below 3b; averages (σ_xx + σ_yy)/2 (= σ_rr = σ_θθ on
/// the axis) and σ_zz per depth, and compares with A19.
fn axis_stress(
    body: &solver_app::model::Body,
    near: f64,
    depth: impl Fn(f64) -> f64,
    hertz: &HertzPoint,
    nu: f64,
) -> AxisStress {
    let mut cells: Vec<(f64, f64, f64)> = body
        .geom
        .cell_centres
        .iter()
        .zip(&body.momentum.sigma)
        .filter(|(c, _)| c.x.hypot(c.y) < near)
        .map(|(c, s)| (depth(c.z), 0.5 * (s[(0, 0)] + s[(1, 1)]), s[(2, 2)]))
        .filter(|&(z, _, _)| z > 0.0 && z < 3.0 * hertz.radius)
        .collect();
    cells.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut rows: Vec<(f64, f64, f64)> = Vec::new();
    let mut count = 0.0;
    for (z, rr, zz) in cells {
        match rows.last_mut() {
            Some(last) if (z - last.0).abs() < 1e-6 * RADIUS => {
                count += 1.0;
                last.1 += (rr - last.1) / count;
                last.2 += (zz - last.2) / count;
            }
            _ => {
                count = 1.0;
                rows.push((z, rr, zz));
            }
        }
    }
    let p0 = hertz.peak_pressure;
    let (mut rr_error, mut zz_error) = (0.0f64, 0.0f64);
    for &(z, rr, zz) in &rows {
        let (hr, hz) = hertz.axis_stress(z, nu);
        rr_error = rr_error.max((rr - hr).abs() / p0);
        zz_error = zz_error.max((zz - hz).abs() / p0);
    }
    AxisStress {
        rows,
        rr_error,
        zz_error,
    }
}

/// Runs the variant with the block as master or (`swapped`) as slave.
pub fn run(variant: Variant, swapped: bool) -> SphereBlock {
    run_edited(variant, swapped, |text| text)
}

/// [`run`] with the case text changed by `edit` first (settings probed).
pub fn run_edited(variant: Variant, swapped: bool, edit: impl Fn(String) -> String) -> SphereBlock {
    let (dir, text) = read_case("sphere-block", variant.file());
    let mut text = edit(text);
    if swapped {
        text = swap_master_slave(&text, variant.block_surface(), "sphere/curved");
    }
    let out = run_toml(&text, &dir);
    let c = &out.contacts.interfaces[0];
    let (side, contact) = if swapped {
        (&c.master, &c.tractions.master)
    } else {
        (&c.slave, &c.tractions.slave)
    };
    let force = 2.0 * c.stats.normal_force;
    let hertz = HertzPoint::new(force, RADIUS, variant.contact_modulus());
    let b = hertz.radius;
    let p0 = hertz.peak_pressure;
    let mut profile: Vec<(f64, f64)> = side
        .surface
        .face_centres
        .iter()
        .zip(&contact.pressure)
        .map(|(x, &p)| (x.x.hypot(x.y), p))
        .collect();
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    let peak = profile.iter().fold(0.0f64, |a, &(_, p)| a.max(p));
    let zone: Vec<f64> = profile
        .iter()
        .filter(|(r, _)| *r <= b)
        .map(|&(r, p)| p - hertz.pressure(r))
        .collect();
    let rms = (zone.iter().map(|e| e * e).sum::<f64>() / zone.len().max(1) as f64).sqrt();
    // the revolved sphere mesh has rings of faces at equal radius: the
    // face width at b is the spacing of the distinct ring radii there
    let mut rings: Vec<f64> = profile.iter().map(|p| p.0).collect();
    rings.dedup_by(|a, b| (*a - *b).abs() < 1e-9 * RADIUS);
    let i = rings
        .partition_point(|&r| r < b)
        .clamp(1, rings.len().max(2) - 1);
    let face_width = match (rings.get(i - 1), rings.get(i)) {
        (Some(a), Some(b)) => b - a,
        _ => 0.0,
    };
    let contact_radius = (2.0 * c.stats.contact_area / std::f64::consts::PI).sqrt();

    let body = |name: &str| out.bodies.iter().find(|x| x.name == name);
    let sphere_axis = body("sphere").map_or_else(AxisStress::default, |s| {
        axis_stress(s, 0.75 * face_width, |z| z, &hertz, SPHERE.1)
    });
    let block_axis = match body("block") {
        Some(k) if !k.rigid => {
            // the four cell columns around the axis, centres at (±h/2, h/2)
            axis_stress(k, 1.1 * BLOCK_FACE, |z| -z, &hertz, BLOCK.1)
        }
        _ => AxisStress::default(),
    };
    SphereBlock {
        variant,
        swapped,
        force,
        hertz,
        profile,
        peak_error: peak / p0 - 1.0,
        rms_error: rms / p0,
        contact_radius,
        face_width,
        sphere_axis,
        block_axis,
        converged: out.converged,
        cost: RunCost::of(&out),
    }
}
