//! Surfaces for the detection tests: perturbed structured grids of quads or
//! triangles on two facing patches.
#![allow(dead_code)]
use fv_mesh::generators::{box_mesh, box_tet_mesh};
use fv_mesh::{Surface, Vector};

/// Pseudo-random value in [-1, 1] from a seed and two indices (splitmix64).
pub fn hash_unit(seed: u64, i: u64, k: u64) -> f64 {
    let mut z = seed
        .wrapping_add(i.wrapping_mul(0x9E37_79B9_7F4A_7C15))
        .wrapping_add(k.wrapping_mul(0xD1B5_4A32_D192_ED03));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// A flat unit-square patch at z = 0 with `n[0] × n[1]` quads (or twice as
/// many triangles): the top of a box below (`master = true`, normal +z) or
/// the bottom of a box above (normal -z).
pub fn flat_patch(n: [usize; 2], triangles: bool, master: bool) -> Surface {
    let (min, max, patch) = if master {
        (
            Vector::new(0.0, 0.0, -1.0),
            Vector::new(1.0, 1.0, 0.0),
            "zmax",
        )
    } else {
        (
            Vector::new(0.0, 0.0, 0.0),
            Vector::new(1.0, 1.0, 1.0),
            "zmin",
        )
    };
    let mesh = if triangles {
        box_tet_mesh(min, max, [n[0], n[1], 1])
    } else {
        box_mesh(min, max, [n[0], n[1], 1], [1.0; 3])
    }
    .expect("box mesh");
    let p = mesh.patch_index(patch).expect("patch");
    Surface::new(&mesh, p).expect("surface")
}

/// Placement and perturbation of a unit-square patch.
#[derive(Debug, Clone, Copy)]
pub struct Placement {
    /// Rotation about the vertical axis through the square centre (rad).
    pub rotate: f64,
    /// Tilt about the x axis through the square centre (rad).
    pub tilt: f64,
    /// Translation.
    pub shift: Vector,
    /// Curvature: z += curvature · r² / 2 about the square centre.
    pub curvature: f64,
    /// In-plane jitter of each point, as a fraction of the grid spacing (≤ 0.15 keeps
    /// quads convex); border points move along the border only.
    pub jitter: f64,
    /// Out-of-plane jitter of each point, absolute.
    pub jitter_z: f64,
    /// Seed of the jitter.
    pub seed: u64,
}

impl Default for Placement {
    fn default() -> Self {
        Placement {
            rotate: 0.0,
            tilt: 0.0,
            shift: Vector::zeros(),
            curvature: 0.0,
            jitter: 0.0,
            jitter_z: 0.0,
            seed: 0,
        }
    }
}

/// Positions of the points of `reference` (a unit-square patch with
/// spacing `spacing`) after `placement`.
pub fn placed_points(reference: &[Vector], spacing: f64, pl: &Placement) -> Vec<Vector> {
    let c = Vector::new(0.5, 0.5, 0.0);
    let (sr, cr) = pl.rotate.sin_cos();
    let (st, ct) = pl.tilt.sin_cos();
    reference
        .iter()
        .enumerate()
        .map(|(i, x)| {
            let i = i as u64;
            let mut r = x - c;
            // border points move along the border only: the patch stays a square
            let fixed = |v: f64| v.abs() < 1e-12 || (v - 1.0).abs() < 1e-12;
            if !fixed(x.x) {
                r.x += pl.jitter * spacing * hash_unit(pl.seed, i, 0);
            }
            if !fixed(x.y) {
                r.y += pl.jitter * spacing * hash_unit(pl.seed, i, 1);
            }
            r.z += pl.jitter_z * hash_unit(pl.seed, i, 2);
            r.z += 0.5 * pl.curvature * (r.x * r.x + r.y * r.y);
            let r = Vector::new(cr * r.x - sr * r.y, sr * r.x + cr * r.y, r.z);
            let r = Vector::new(r.x, ct * r.y - st * r.z, st * r.y + ct * r.z);
            c + r + pl.shift
        })
        .collect()
}

/// A placed patch: the surface and its reference (flat) points.
pub struct Patch {
    /// The surface at its current position.
    pub surface: Surface,
    /// The flat reference positions of its points.
    pub reference: Vec<Vector>,
    /// Grid spacing (the larger of the two directions).
    pub spacing: f64,
}

impl Patch {
    /// A flat patch, then placed.
    pub fn new(n: [usize; 2], triangles: bool, master: bool, pl: &Placement) -> Patch {
        let mut surface = flat_patch(n, triangles, master);
        let reference = surface.points.clone();
        let spacing = 1.0 / n[0].min(n[1]) as f64;
        surface.update_points(&placed_points(&reference, spacing, pl));
        Patch {
            surface,
            reference,
            spacing,
        }
    }

    /// Re-places the patch (the new placement replaces the old one).
    pub fn place(&mut self, pl: &Placement) {
        let pts = placed_points(&self.reference, self.spacing, pl);
        self.surface.update_points(&pts);
    }
}
