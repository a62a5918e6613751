//! Point normals from a local least-squares surface fit — the first of the
//! two approaches the thesis names in §4.6.1 ("mesh points are fitted with a
//! smooth parametric surface and point normals are subsequently calculated
//! using the newly generated surface", its ref. [143]); the thesis itself
//! uses the weighted averages of eq. 4.80.
//!
//! Around a point `p` with a first estimate `n₀` (the weighted average), the
//! neighbouring points `q` are written in the frame `(t₁, t₂, n₀)` as
//! `(u, v, w)` and the height function
//!
//! `w(u, v) = a u² + b uv + c v² + d u + e v`
//!
//! (through `p`) is fitted to them by least squares with weights `1/|q − p|⁴`;
//! the normal is `(−d, −e, 1)/|·|` in that frame. The fit is repeated once
//! in the frame of the new normal. Its error is O(h²) on any smooth
//! surface and any arrangement of the points, while the weighted averages
//! are only O(h) on irregular meshes unless the surface is a sphere (Max's
//! weighting). Measured on the 780-triangle half-tube of §4.6.1: the largest
//! radial error of the Nagata surface drops from 3.0·10⁻³ to 2·10⁻⁴ m
//! (`tests/suite/accuracy.rs`).
//!
//! Only points whose faces close around them are fitted; on the border of
//! the surface the weighted average is kept (a one-sided stencil is no
//! better). Stencil: the points of the faces around `p` (first ring); when they are
//! fewer than [`MIN_FIRST_RING`], the points of the faces around those
//! (second ring). The fit is skipped — the weighted normal kept — when
//! the stencil has fewer than five points or is degenerate, when a face of
//! the stencil is tilted from `n₀` by more than `max_angle` (a sharp edge
//! or corner nearby: a height function does not describe it), or when the
//! fitted normal leaves the cone of the normals of the faces around `p`.
//! Hand-written: a 5 × 5 weighted normal-equation solve per point.
use crate::face_table::FaceTable;
use fv_mesh::{Real, Vector};
use nalgebra::{Matrix5, Vector5};

/// The first ring is used alone when it has at least this many points
/// besides `p` (an interior point of a triangulation has about six).
pub const MIN_FIRST_RING: usize = 6;

/// Parameters of the quadric fit of point normals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalFit {
    /// A face of the stencil tilted from the first estimate by more than
    /// this angle (radians) disables the fit at the point. Default 40°.
    pub max_angle: Real,
}

impl Default for NormalFit {
    fn default() -> Self {
        NormalFit {
            max_angle: 40_f64.to_radians(),
        }
    }
}

/// Workspace of the fit: the stencil of one point and a visit stamp per
/// point (allocated once per surface).
#[derive(Debug, Clone, Default)]
pub struct FitWorkspace {
    stencil: Vec<usize>,
    faces: Vec<usize>,
    stamp: Vec<u32>,
    face_stamp: Vec<u32>,
    generation: u32,
}

impl FitWorkspace {
    /// Workspace for a table of `n_points` points and `n_faces` faces.
    pub fn new(n_points: usize, n_faces: usize) -> Self {
        FitWorkspace {
            stencil: Vec::with_capacity(32),
            faces: Vec::with_capacity(32),
            stamp: vec![0; n_points],
            face_stamp: vec![0; n_faces],
            generation: 0,
        }
    }

    fn next_generation(&mut self) {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.face_stamp.iter_mut().for_each(|s| *s = 0);
            self.generation = 1;
        }
    }

    /// Adds the faces around `p` and their points to the stencil.
    fn add_ring(&mut self, table: &FaceTable, p: usize) {
        for c in table.corners(p) {
            if self.face_stamp[c.face] != self.generation {
                self.face_stamp[c.face] = self.generation;
                self.faces.push(c.face);
            }
            for &q in table.face(c.face) {
                if self.stamp[q] != self.generation {
                    self.stamp[q] = self.generation;
                    self.stencil.push(q);
                }
            }
        }
    }
}

impl NormalFit {
    /// Refines the unit normals `normals` (first estimates, e.g. eq. 4.80)
    /// in place; points where the fit is skipped keep theirs.
    pub fn refine(
        &self,
        table: &FaceTable,
        points: &[Vector],
        face_normals: &[Vector],
        normals: &mut [Vector],
        ws: &mut FitWorkspace,
    ) {
        let cos_max = self.max_angle.cos();
        for p in 0..table.n_points() {
            let n0 = normals[p];
            if n0 == Vector::zeros() || !closed_fan(table, p) {
                continue;
            }
            ws.next_generation();
            ws.stencil.clear();
            ws.faces.clear();
            ws.stamp[p] = ws.generation;
            ws.add_ring(table, p);
            let first = ws.stencil.len();
            if first < MIN_FIRST_RING {
                for k in 0..first {
                    let q = ws.stencil[k];
                    ws.add_ring(table, q);
                }
            }
            let tilted = ws.faces.iter().any(|&f| {
                let nf = face_normals[f];
                nf != Vector::zeros() && nf.dot(&n0) < cos_max
            });
            if tilted || ws.stencil.len() < 5 {
                continue;
            }
            // cone of the normals of the faces around p
            let mut cos_cone: Real = 1.0;
            for c in table.corners(p) {
                let nf = face_normals[c.face];
                if nf != Vector::zeros() {
                    cos_cone = cos_cone.min(nf.dot(&n0));
                }
            }
            let mut n = n0;
            let mut ok = true;
            for _ in 0..2 {
                match fit_normal(&points[p], &n, points, &ws.stencil) {
                    Some(m) => n = m,
                    None => {
                        ok = false;
                        break;
                    }
                }
            }
            // within the cone (with a margin of a tenth of its opening)
            let opening = cos_cone.clamp(-1.0, 1.0).acos();
            if ok && n.dot(&n0) >= (1.1 * opening + 1e-12).min(self.max_angle).cos() {
                normals[p] = n;
            }
        }
    }
}

/// The faces around `p` close around it: each edge leaving `p` is a side
/// of two of them. At a point on the border of the surface the stencil is
/// one-sided and the fit is no better than the weighted average (the
/// fourth-order term of the height function leaks into its slope).
fn closed_fan(table: &FaceTable, p: usize) -> bool {
    let corners = table.corners(p);
    corners.iter().all(|c| {
        let poly = table.face(c.face);
        let k = poly.len();
        if k < 3 {
            return false;
        }
        [poly[(c.index + 1) % k], poly[(c.index + k - 1) % k]]
            .iter()
            .all(|&q| {
                corners
                    .iter()
                    .filter(|d| {
                        let f = table.face(d.face);
                        let m = f.len();
                        m >= 3 && (f[(d.index + 1) % m] == q || f[(d.index + m - 1) % m] == q)
                    })
                    .count()
                    == 2
            })
    })
}

/// One weighted least-squares fit of `w = a u² + b uv + c v² + d u + e v`
/// in the frame of `n`; `None` if the normal equations are singular.
fn fit_normal(x: &Vector, n: &Vector, points: &[Vector], stencil: &[usize]) -> Option<Vector> {
    let t1 = if n.x.abs() < 0.9 {
        Vector::x().cross(n)
    } else {
        Vector::y().cross(n)
    }
    .normalize();
    let t2 = n.cross(&t1);
    // length scale for conditioning
    let h = stencil
        .iter()
        .map(|&q| (points[q] - x).norm())
        .sum::<Real>()
        / stencil.len() as Real;
    if !(h > 0.0 && h.is_finite()) {
        return None;
    }
    let mut a = Matrix5::<Real>::zeros();
    let mut rhs = Vector5::<Real>::zeros();
    for &q in stencil {
        let d = (points[q] - x) / h;
        let r2 = d.norm_squared();
        if r2 < 1e-24 {
            continue;
        }
        let (u, v, w) = (d.dot(&t1), d.dot(&t2), d.dot(n));
        let row = Vector5::new(u * u, u * v, v * v, u, v);
        let omega = 1.0 / (r2 * r2);
        a += omega * row * row.transpose();
        rhs += omega * w * row;
    }
    let c = a.cholesky()?.solve(&rhs);
    let m = n - c[3] * t1 - c[4] * t2;
    let len = m.norm();
    (len.is_finite() && len > 0.0).then(|| m / len)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::face_geometry::polygon_centre_area;

    fn unit_face_normals(table: &FaceTable, points: &[Vector]) -> Vec<Vector> {
        (0..table.n_faces())
            .map(|f| polygon_centre_area(points, table.face(f)).1.normalize())
            .collect()
    }

    /// An irregular fan of six triangles around a point of the cylinder
    /// y² + z² = 1 (its normal there is +z).
    #[test]
    fn irregular_fan_on_a_cylinder_is_corrected() {
        let on = |x: Real, y: Real| Vector::new(x, y, (1.0 - y * y).sqrt());
        let mut points = vec![on(0.0, 0.0)];
        let angles = [0.1, 1.2, 2.0, 3.3, 4.1, 5.2];
        let radii = [0.2, 0.15, 0.25, 0.18, 0.22, 0.2];
        for (a, r) in angles.iter().zip(radii) {
            points.push(on(r * Real::cos(*a), r * Real::sin(*a)));
        }
        let faces: Vec<[usize; 3]> = (0..6).map(|i| [0, 1 + i, 1 + (i + 1) % 6]).collect();
        let table = FaceTable::new(points.len(), &faces).unwrap();
        let nf = unit_face_normals(&table, &points);
        // first estimate: the plain average, tilted on this fan
        let mut normals = vec![Vector::zeros(); points.len()];
        normals[0] = nf.iter().sum::<Vector>().normalize();
        let before = normals[0].angle(&Vector::z());
        let mut ws = FitWorkspace::new(points.len(), faces.len());
        NormalFit::default().refine(&table, &points, &nf, &mut normals, &mut ws);
        let after = normals[0].angle(&Vector::z());
        assert!(before > 1e-3, "{before}");
        assert!(after < 0.02 * before, "{before} → {after}"); // measured 9.5e-3 → 1.3e-4
                                                              // border points (open fans) keep their normals
        assert!(normals[1..].iter().all(|n| *n == Vector::zeros()));
    }

    /// At the corner of a cube the faces are tilted by 90°: no fit.
    #[test]
    fn sharp_corner_keeps_the_weighted_normal() {
        let points = vec![
            Vector::zeros(),
            Vector::x(),
            Vector::y(),
            Vector::z(),
            Vector::new(1.0, 1.0, 0.0),
            Vector::new(0.0, 1.0, 1.0),
            Vector::new(1.0, 0.0, 1.0),
        ];
        let faces = [[0, 2, 4, 1], [0, 3, 5, 2], [0, 1, 6, 3]];
        let table = FaceTable::new(points.len(), &faces).unwrap();
        let nf = unit_face_normals(&table, &points);
        let n0 = -Vector::new(1.0, 1.0, 1.0).normalize();
        let mut normals = vec![n0; points.len()];
        let mut ws = FitWorkspace::new(points.len(), faces.len());
        NormalFit::default().refine(&table, &points, &nf, &mut normals, &mut ws);
        assert!(normals.iter().all(|n| *n == n0));
    }
}
