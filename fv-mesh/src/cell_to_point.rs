//! Cell-to-point interpolation by least squares over a mixed molecule
//! (thesis §3.3.1, eqs. 3.31–3.34, and the mixed molecule of Fig. 4.7b).
//!
//! For every mesh point p the molecule is the set of cell centres around p
//! plus, for boundary points, the centres of the boundary faces touching p.
//! A linear distribution φ(r) = φ_ref + c·(r − r_ref) (3.31) is fitted by
//! ordinary least squares (3.32), with r_ref and φ_ref the arithmetic means
//! of the molecule, and evaluated at r_p. Since Σ_k (r_k − r_ref) = 0 the
//! result is a fixed weighted sum
//!
//! φ_p = Σ_k w_k φ_k,   w_k = 1/N + (r_p − r_ref)ᵀ M⁺ (r_k − r_ref),
//!
//! with the normal matrix M = Σ_k (r_k − r_ref)(r_k − r_ref)ᵀ. The weights
//! are computed once per geometry, so each interpolation is a sparse
//! product. M⁺ is the pseudo-inverse from the eigen-decomposition of M:
//! directions whose eigenvalue is below [`EIGEN_TOLERANCE`] × the largest are
//! dropped, which means constant extrapolation along them (coplanar centres
//! of a one-cell-thick mesh, a point touched by one cell). If the weights are
//! still unusable (not finite, or Σ|w_k| above [`MAX_WEIGHT_SUM`]), the
//! inverse-distance weights of eqs. (3.33)–(3.34) are used instead.
use rayon::prelude::*;

use crate::{MeshGeometry, PolyMesh, Real, Tensor, Vector};

/// Relative eigenvalue threshold below which a direction of the normal
/// matrix is treated as degenerate.
pub const EIGEN_TOLERANCE: Real = 1e-9;

/// Largest accepted Σ|w_k| of the least-squares weights of one point before
/// the inverse-distance fallback is used.
pub const MAX_WEIGHT_SUM: Real = 1e3;

/// Number of points per parallel task.
const CHUNK: usize = 2048;

/// How the weights of one point were obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointFit {
    /// Full-rank least squares (3.32).
    LeastSquares,
    /// Least squares with some degenerate directions dropped (pseudo-inverse).
    PseudoInverse,
    /// Inverse-distance weighting (3.33)–(3.34).
    InverseDistance,
    /// No source in the molecule (a point used by no cell): the value is zero.
    Empty,
}

/// Precomputed cell-to-point interpolation weights (CSR over mesh points).
///
/// Source encoding: a source `s < n_cells` is the cell `s`; a source
/// `s ≥ n_cells` is the boundary face `n_internal_faces + (s − n_cells)`,
/// whose value is `boundary_face_values[s − n_cells]`.
#[derive(Debug, Clone)]
pub struct CellToPoint {
    /// `offsets[p]..offsets[p+1]` indexes `sources` and `weights` of point `p`.
    pub offsets: Vec<u32>,
    /// Source of every weight (cell, or `n_cells` + boundary-face index).
    pub sources: Vec<u32>,
    /// Weights; those of one point sum to one.
    pub weights: Vec<f64>,
    /// Number of cells of the mesh (the source-encoding offset).
    pub n_cells: usize,
    /// Number of boundary faces of the mesh (expected `boundary_face_values` length).
    pub n_boundary_faces: usize,
    /// How each point's weights were obtained.
    pub fits: Vec<PointFit>,
}

impl CellToPoint {
    /// Builds the mixed molecules (cells + boundary faces of every patch) and
    /// their least-squares weights (3.32).
    ///
    /// Panics if `geom` does not belong to `mesh`.
    pub fn new(mesh: &PolyMesh, geom: &MeshGeometry) -> CellToPoint {
        Self::with_boundary_patches(mesh, geom, &vec![true; mesh.patches.len()])
    }

    /// Like [`CellToPoint::new`], putting into the molecules only the boundary
    /// faces of the patches `p` with `use_patch[p]` (all `false`: cell centres only).
    pub fn with_boundary_patches(
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        use_patch: &[bool],
    ) -> CellToPoint {
        assert_eq!(use_patch.len(), mesh.patches.len(), "one flag per patch");
        let np = mesh.n_points();
        let nc = mesh.n_cells;
        let ni = mesh.n_internal_faces();
        let nb = mesh.n_faces() - ni;
        let (pc_off, pc) = mesh.point_cells();

        // boundary faces around each point (selected patches only)
        let mut pb_off = vec![0u32; np + 1];
        for (pi, patch) in mesh.patches.iter().enumerate() {
            if !use_patch[pi] {
                continue;
            }
            for f in patch.faces() {
                for &p in mesh.face(f) {
                    pb_off[p as usize + 1] += 1;
                }
            }
        }
        for i in 0..np {
            pb_off[i + 1] += pb_off[i];
        }
        let mut fill = pb_off.clone();
        let mut pb = vec![0u32; pb_off[np] as usize];
        for (pi, patch) in mesh.patches.iter().enumerate() {
            if !use_patch[pi] {
                continue;
            }
            for f in patch.faces() {
                for &p in mesh.face(f) {
                    pb[fill[p as usize] as usize] = (nc + f - ni) as u32;
                    fill[p as usize] += 1;
                }
            }
        }

        let mut offsets = Vec::with_capacity(np + 1);
        let mut sources = Vec::with_capacity(pc.len() + pb.len());
        offsets.push(0u32);
        for p in 0..np {
            sources.extend_from_slice(&pc[pc_off[p] as usize..pc_off[p + 1] as usize]);
            sources.extend_from_slice(&pb[pb_off[p] as usize..pb_off[p + 1] as usize]);
            offsets.push(sources.len() as u32);
        }
        let mut c2p = CellToPoint {
            weights: vec![0.0; sources.len()],
            offsets,
            sources,
            n_cells: nc,
            n_boundary_faces: nb,
            fits: vec![PointFit::Empty; np],
        };
        c2p.update_weights(mesh, geom);
        c2p
    }

    /// Recomputes the weights for moved points (same topology), in place.
    ///
    /// Panics if the mesh has a different number of points, cells or faces.
    pub fn update_weights(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let np = mesh.n_points();
        assert_eq!(self.offsets.len(), np + 1, "point count changed");
        assert_eq!(mesh.n_cells, self.n_cells, "cell count changed");
        assert_eq!(
            geom.cell_centres.len(),
            self.n_cells,
            "geometry/mesh mismatch"
        );
        assert_eq!(
            geom.face_centres.len(),
            mesh.n_faces(),
            "geometry/mesh mismatch"
        );
        let ni = mesh.n_internal_faces();
        let nc = self.n_cells;
        let position = |s: u32| -> Vector {
            let s = s as usize;
            if s < nc {
                geom.cell_centres[s]
            } else {
                geom.face_centres[ni + s - nc]
            }
        };
        // split weights and fits into per-chunk slices, then fill in parallel
        let mut tasks = Vec::with_capacity(np.div_ceil(CHUNK));
        let mut rest_w: &mut [f64] = &mut self.weights;
        let mut rest_f: &mut [PointFit] = &mut self.fits;
        let mut start = 0;
        while start < np {
            let end = (start + CHUNK).min(np);
            let len = (self.offsets[end] - self.offsets[start]) as usize;
            let (w, rw) = std::mem::take(&mut rest_w).split_at_mut(len);
            let (f, rf) = std::mem::take(&mut rest_f).split_at_mut(end - start);
            rest_w = rw;
            rest_f = rf;
            tasks.push((start, end, w, f));
            start = end;
        }
        let offsets = &self.offsets;
        let sources = &self.sources;
        tasks.into_par_iter().for_each(|(start, end, w, f)| {
            let base = offsets[start] as usize;
            for p in start..end {
                let (a, b) = (offsets[p] as usize, offsets[p + 1] as usize);
                f[p - start] = point_weights(
                    mesh.points[p],
                    &sources[a..b],
                    &position,
                    &mut w[a - base..b - base],
                );
            }
        });
    }

    /// Number of points.
    pub fn n_points(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Sources and weights of point `p`.
    #[inline]
    pub fn molecule(&self, p: usize) -> (&[u32], &[f64]) {
        let (a, b) = (self.offsets[p] as usize, self.offsets[p + 1] as usize);
        (&self.sources[a..b], &self.weights[a..b])
    }

    /// Interpolates a vector field to all points: φ_p = Σ w_k φ_k.
    ///
    /// `boundary_face_values` is indexed by `face − n_internal_faces`.
    /// Allocates nothing. Panics on wrong slice lengths.
    pub fn interpolate(
        &self,
        cell_values: &[Vector],
        boundary_face_values: &[Vector],
        out: &mut [Vector],
    ) {
        self.interpolate_generic(cell_values, boundary_face_values, out);
    }

    /// Scalar version of [`CellToPoint::interpolate`].
    pub fn interpolate_scalar(
        &self,
        cell_values: &[Real],
        boundary_face_values: &[Real],
        out: &mut [Real],
    ) {
        self.interpolate_generic(cell_values, boundary_face_values, out);
    }

    /// Interpolates a vector field to the listed points only:
    /// `out[i]` receives the value at point `points[i]` (e.g. the
    /// `point_ids` of a contact [`crate::Surface`]). Allocates nothing.
    pub fn interpolate_points(
        &self,
        points: &[u32],
        cell_values: &[Vector],
        boundary_face_values: &[Vector],
        out: &mut [Vector],
    ) {
        self.check_lengths(cell_values.len(), boundary_face_values.len());
        assert_eq!(points.len(), out.len(), "one output per listed point");
        for (o, &p) in out.iter_mut().zip(points) {
            *o = self.eval(p as usize, cell_values, boundary_face_values);
        }
    }

    /// Value at one point.
    #[inline]
    fn eval<T>(&self, p: usize, cells: &[T], bfaces: &[T]) -> T
    where
        T: Copy + Default + std::ops::AddAssign + std::ops::Mul<f64, Output = T>,
    {
        let (a, b) = (self.offsets[p] as usize, self.offsets[p + 1] as usize);
        let mut acc = T::default();
        for (&s, &w) in self.sources[a..b].iter().zip(&self.weights[a..b]) {
            let s = s as usize;
            let v = if s < self.n_cells {
                cells[s]
            } else {
                bfaces[s - self.n_cells]
            };
            acc += v * w;
        }
        acc
    }

    fn check_lengths(&self, nc: usize, nb: usize) {
        assert_eq!(nc, self.n_cells, "one value per cell expected");
        assert_eq!(
            nb, self.n_boundary_faces,
            "one value per boundary face expected"
        );
    }

    fn interpolate_generic<T>(&self, cells: &[T], bfaces: &[T], out: &mut [T])
    where
        T: Copy + Default + Send + Sync + std::ops::AddAssign + std::ops::Mul<f64, Output = T>,
    {
        self.check_lengths(cells.len(), bfaces.len());
        assert_eq!(out.len(), self.n_points(), "one output per point expected");
        out.par_chunks_mut(CHUNK)
            .enumerate()
            .for_each(|(chunk, o)| {
                let start = chunk * CHUNK;
                for (i, v) in o.iter_mut().enumerate() {
                    *v = self.eval(start + i, cells, bfaces);
                }
            });
    }
}

/// Weights of one point; returns how they were obtained.
fn point_weights(
    rp: Vector,
    sources: &[u32],
    position: &impl Fn(u32) -> Vector,
    w: &mut [f64],
) -> PointFit {
    let n = sources.len();
    if n == 0 {
        return PointFit::Empty;
    }
    let inv_n = 1.0 / n as f64;
    let mut r_ref = Vector::zeros();
    for &s in sources {
        r_ref += position(s);
    }
    r_ref *= inv_n;
    let mut m = Tensor::zeros();
    for &s in sources {
        let d = position(s) - r_ref;
        m += d * d.transpose();
    }
    let eig = m.symmetric_eigen();
    let lmax = eig.eigenvalues.amax();
    // pseudo-inverse applied to (r_p − r_ref): q = M⁺ (r_p − r_ref)
    let dp = rp - r_ref;
    let mut q = Vector::zeros();
    let mut dropped = false;
    for i in 0..3 {
        let l = eig.eigenvalues[i];
        if lmax > 0.0 && l > EIGEN_TOLERANCE * lmax {
            let v = eig.eigenvectors.column(i);
            q += v * (v.dot(&dp) / l);
        } else {
            dropped = true;
        }
    }
    let mut abs_sum = 0.0;
    for (wk, &s) in w.iter_mut().zip(sources) {
        *wk = inv_n + q.dot(&(position(s) - r_ref));
        abs_sum += wk.abs();
    }
    if abs_sum.is_finite() && abs_sum <= MAX_WEIGHT_SUM {
        return if dropped {
            PointFit::PseudoInverse
        } else {
            PointFit::LeastSquares
        };
    }
    // inverse distance (3.33)–(3.34)
    let mut total = 0.0;
    for (wk, &s) in w.iter_mut().zip(sources) {
        let d = (rp - position(s)).norm();
        *wk = if d > 0.0 { 1.0 / d } else { f64::INFINITY };
        total += *wk;
    }
    if total.is_finite() && total > 0.0 {
        for wk in w.iter_mut() {
            *wk /= total;
        }
    } else {
        // a source coincides with the point (or the geometry is not finite):
        // take the coincident sources, else the plain average
        let hits = w.iter().filter(|x| x.is_infinite()).count();
        for wk in w.iter_mut() {
            *wk = if hits > 0 {
                if wk.is_infinite() {
                    1.0 / hits as f64
                } else {
                    0.0
                }
            } else {
                inv_n
            };
        }
    }
    PointFit::InverseDistance
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generators::{annulus_mesh, box_mesh};

    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn linear(x: Vector) -> Vector {
        let a = Vector::new(0.3, -1.2, 2.5);
        let b = Tensor::new(1.0, -0.5, 0.25, 0.7, 2.0, -1.5, -0.3, 0.9, 1.1);
        a + b * x
    }

    /// Max error of interpolating `field` sampled at cell and boundary-face
    /// centres, over the points `check` selects.
    fn max_error(
        mesh: &PolyMesh,
        c2p: &CellToPoint,
        field: impl Fn(Vector) -> Vector,
        check: impl Fn(usize) -> bool,
    ) -> f64 {
        let g = MeshGeometry::new(mesh).unwrap();
        let ni = mesh.n_internal_faces();
        let cells: Vec<Vector> = g.cell_centres.iter().map(|&x| field(x)).collect();
        let bf: Vec<Vector> = g.face_centres[ni..].iter().map(|&x| field(x)).collect();
        let mut out = vec![Vector::zeros(); mesh.n_points()];
        c2p.interpolate(&cells, &bf, &mut out);
        let mut err: f64 = 0.0;
        for (p, v) in out.iter().enumerate() {
            if check(p) {
                err = err.max((v - field(mesh.points[p])).norm());
            }
        }
        // the scalar and subset versions agree
        let sc: Vec<f64> = cells.iter().map(|v| v.x).collect();
        let sb: Vec<f64> = bf.iter().map(|v| v.x).collect();
        let mut so = vec![0.0; mesh.n_points()];
        c2p.interpolate_scalar(&sc, &sb, &mut so);
        let ids: Vec<u32> = (0..mesh.n_points() as u32).rev().collect();
        let mut sub = vec![Vector::zeros(); ids.len()];
        c2p.interpolate_points(&ids, &cells, &bf, &mut sub);
        for p in 0..mesh.n_points() {
            assert!((so[p] - out[p].x).abs() < 1e-14 * (1.0 + out[p].x.abs()));
            assert_eq!(sub[mesh.n_points() - 1 - p], out[p]);
        }
        err
    }

    fn check_weights_sum_to_one(c2p: &CellToPoint) {
        for p in 0..c2p.n_points() {
            let (_, w) = c2p.molecule(p);
            let s: f64 = w.iter().sum();
            assert!((s - 1.0).abs() < 1e-12, "point {p}: Σw = {s}");
        }
    }

    #[test]
    fn linear_field_exact_on_box() {
        let m = box_mesh(
            Vector::new(-1.0, 0.0, 2.0),
            Vector::new(1.0, 0.5, 3.0),
            [5, 4, 3],
            [1.0, 3.0, 0.5],
        )
        .unwrap();
        let g = MeshGeometry::new(&m).unwrap();
        let c2p = CellToPoint::new(&m, &g);
        check_weights_sum_to_one(&c2p);
        assert!(c2p.fits.iter().all(|&f| f == PointFit::LeastSquares));
        let err = max_error(&m, &c2p, linear, |_| true);
        assert!(err < 1e-10, "{err}");
    }

    #[test]
    fn linear_field_exact_on_perturbed_box() {
        let n = [6, 5, 4];
        let mut m = box_mesh(Vector::zeros(), Vector::new(1.0, 1.0, 1.0), n, [1.0; 3]).unwrap();
        let h = 1.0 / 6.0;
        let mut rng = Lcg(12345);
        for x in m.points.iter_mut() {
            let interior = (0..3).all(|d| x[d] > 1e-9 && x[d] < 1.0 - 1e-9);
            if interior {
                for d in 0..3 {
                    x[d] += 0.25 * h * (2.0 * rng.next() - 1.0);
                }
            }
        }
        let g = MeshGeometry::new(&m).unwrap();
        let c2p = CellToPoint::new(&m, &g);
        check_weights_sum_to_one(&c2p);
        let err = max_error(&m, &c2p, linear, |_| true);
        assert!(err < 1e-10, "{err}");
        // a non-linear field is approximated (second order), not reproduced
        let quad = |x: Vector| Vector::new(x.x * x.x, x.y * x.z, 0.0);
        let err = max_error(&m, &c2p, quad, |_| true);
        assert!(err > 1e-6 && err < 0.1, "{err}");
    }

    #[test]
    fn one_cell_thick_box() {
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(2.0, 1.0, 0.1),
            [10, 10, 1],
            [1.0; 3],
        )
        .unwrap();
        let g = MeshGeometry::new(&m).unwrap();
        let c2p = CellToPoint::new(&m, &g);
        check_weights_sum_to_one(&c2p);
        // mixed molecule: front/back face centres make the fit three-dimensional
        let err = max_error(&m, &c2p, linear, |_| true);
        assert!(err < 1e-10, "{err}");
        let planar = |x: Vector| Vector::new(1.0 + 2.0 * x.x - x.y, 0.5 * x.x + 3.0 * x.y, 0.0);
        let err = max_error(&m, &c2p, planar, |_| true);
        assert!(err < 1e-10, "{err}");

        // cell centres only: all coplanar, the z direction is dropped
        let cells_only = CellToPoint::with_boundary_patches(&m, &g, &[false; 6]);
        check_weights_sum_to_one(&cells_only);
        let interior = |p: usize| {
            let x = m.points[p];
            x.x > 1e-9 && x.x < 2.0 - 1e-9 && x.y > 1e-9 && x.y < 1.0 - 1e-9
        };
        for p in 0..m.n_points() {
            if interior(p) {
                assert_eq!(cells_only.fits[p], PointFit::PseudoInverse);
            }
        }
        let err = max_error(&m, &cells_only, planar, interior);
        assert!(err < 1e-10, "{err}");
    }

    #[test]
    fn single_cell_molecule_is_constant() {
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 1.0, 1.0),
            [2, 2, 2],
            [1.0; 3],
        )
        .unwrap();
        let g = MeshGeometry::new(&m).unwrap();
        let c2p = CellToPoint::with_boundary_patches(&m, &g, &[false; 6]);
        // corner point 0 is touched by cell 0 only
        let (src, w) = c2p.molecule(0);
        assert_eq!(src, &[0]);
        assert_eq!(w, &[1.0]);
        assert_eq!(c2p.fits[0], PointFit::PseudoInverse);
        // with boundary faces the corner is a full-rank fit
        let mixed = CellToPoint::new(&m, &g);
        assert_eq!(mixed.fits[0], PointFit::LeastSquares);
        assert_eq!(mixed.molecule(0).0.len(), 4);
        assert!(mixed.molecule(0).0[1..].iter().all(|&s| s >= 8));
    }

    #[test]
    fn linear_field_exact_on_annulus() {
        let m = annulus_mesh(1.0, 2.0, 0.2, 1.7, -0.5, 0.5, [5, 12, 3], 2.0).unwrap();
        let g = MeshGeometry::new(&m).unwrap();
        let mut c2p = CellToPoint::new(&m, &g);
        check_weights_sum_to_one(&c2p);
        let err = max_error(&m, &c2p, linear, |_| true);
        assert!(err < 1e-10, "{err}");
        // move the mesh and update the weights in place
        let mut moved = m.clone();
        for x in moved.points.iter_mut() {
            *x = Vector::new(
                x.x + 0.1 * x.y * x.y,
                x.y + 0.05 * x.x * x.z,
                x.z * (1.0 + 0.1 * x.x),
            );
        }
        let g2 = MeshGeometry::new(&moved).unwrap();
        let cap = c2p.weights.capacity();
        c2p.update_weights(&moved, &g2);
        assert_eq!(c2p.weights.capacity(), cap);
        let err = max_error(&moved, &c2p, linear, |_| true);
        assert!(err < 1e-10, "{err}");
    }

    #[test]
    fn inverse_distance_fallback() {
        // a point far outside a molecule of two nearby sources
        let pos = [Vector::new(0.0, 0.0, 0.0), Vector::new(1e-3, 0.0, 0.0)];
        let mut w = [0.0; 2];
        let fit = point_weights(
            Vector::new(10.0, 0.0, 0.0),
            &[0, 1],
            &|s| pos[s as usize],
            &mut w,
        );
        assert_eq!(fit, PointFit::InverseDistance);
        assert!((w[0] + w[1] - 1.0).abs() < 1e-15 && w[1] > w[0] && w[0] > 0.0);
        // colinear sources: rank one, exact at a source
        let fit = point_weights(Vector::zeros(), &[0, 1], &|s| pos[s as usize], &mut w);
        assert_eq!(fit, PointFit::PseudoInverse);
        assert!((w[0] - 1.0).abs() < 1e-12 && w[1].abs() < 1e-12);
    }
}
