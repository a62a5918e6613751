//! Weighted least-squares cell-centre gradient (thesis §3.2.2, refs [16, 18]).
//!
//! For cell P with neighbours k (cell centres across internal faces and the
//! centres of its boundary faces), with d_k = r_k − r_P and w_k = 1/|d_k|³
//! (see [`ls_weight`]),
//! the gradient minimises Σ w_k (φ_k − φ_P − d_k·∇φ)². Its solution is
//! ∇φ_P = Σ_k c_k ⊗ (φ_k − φ_P) with c_k = G_P⁻¹ w_k d_k and
//! G_P = Σ_k w_k d_k d_kᵀ. G_P⁻¹ is computed once per geometry and kept
//! per cell (its six distinct entries), and w per face; the vectors c_k
//! are formed from them and the geometry where they are used, with the
//! same operations as when they were kept per face (two vectors per
//! internal face: 38 MB at 64³, against 13 MB for the inverses and 6.5 MB
//! for the weights), so the gradient is the same to the bit. The weights
//! are kept because their square root and division per face were what the
//! gradient waited for (12.3 → 9.5 ms per gradient at 64³ with them;
//! 6.6 ms with the c kept).
//!
//! Faces of `empty` patches enter G but take φ_b = φ_P, which fixes the
//! gradient in the empty (out-of-plane) direction to zero and keeps G
//! invertible on one-cell-thick meshes.
use crate::cell_halves::{two_threads, CellHalves};
use fv_mesh::{MeshGeometry, PolyMesh, Tensor, Vector};

/// Least-squares gradient operator of one mesh: G_P⁻¹ of every cell.
#[derive(Debug, Clone, Default)]
pub struct LeastSquaresGradient {
    /// G_P⁻¹ of every cell (symmetric: xx, xy, xz, yy, yz, zz).
    inverse: Vec<[f64; 6]>,
    /// The weight w = 1/|d|³ of every face (8 B: its square root and
    /// division are what an evaluation of the gradient otherwise waits
    /// for).
    weight: Vec<f64>,
    /// Whether each patch is passive (its faces only regularise G).
    passive: Vec<bool>,
    /// The mesh's cells in two halves for two threads (large meshes with
    /// faces ordered by owner only).
    halves: Option<CellHalves>,
}

impl LeastSquaresGradient {
    /// Builds the operator; `passive_patch[p]` marks patches (empty) whose
    /// faces only regularise G.
    pub fn new(mesh: &PolyMesh, geom: &MeshGeometry, passive_patch: &[bool]) -> Self {
        let mut op = LeastSquaresGradient::default();
        op.update(mesh, geom, passive_patch);
        op
    }

    /// Recomputes G_P⁻¹ for the current geometry.
    pub fn update(&mut self, mesh: &PolyMesh, geom: &MeshGeometry, passive_patch: &[bool]) {
        let nc = mesh.n_cells;
        let ni = mesh.n_internal_faces();
        let nf = mesh.n_faces();
        let mut g = vec![Tensor::zeros(); nc];
        self.weight.clear();
        self.weight.reserve_exact(nf);
        for f in 0..nf {
            let d = geom.delta(mesh, f);
            let w = ls_weight(&d);
            self.weight.push(w);
            let dd = d * d.transpose() * w;
            g[mesh.owner[f] as usize] += dd;
            if f < ni {
                g[mesh.neighbour[f] as usize] += dd;
            }
        }
        self.inverse.clear();
        self.inverse.extend(g.iter().map(|g| {
            let i = pseudo_inverse_sym(g);
            [
                i[(0, 0)],
                i[(0, 1)],
                i[(0, 2)],
                i[(1, 1)],
                i[(1, 2)],
                i[(2, 2)],
            ]
        }));
        self.passive = (0..mesh.patches.len())
            .map(|p| passive_patch.get(p).copied().unwrap_or(false))
            .collect();
        self.halves = CellHalves::of(mesh);
    }

    /// The cells in two halves, when the passes over this mesh are split
    /// over two threads (a pool of two or more and a large mesh ordered by
    /// owner).
    pub(crate) fn halves(&self) -> Option<&CellHalves> {
        self.halves.as_ref().filter(|_| two_threads())
    }

    /// G_P⁻¹ of cell `c` (exactly symmetric as computed, so the six
    /// entries restore it to the bit).
    #[inline]
    fn inverse(&self, c: usize) -> Tensor {
        let [xx, xy, xz, yy, yz, zz] = self.inverse[c];
        Tensor::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
    }

    /// The vectors c of internal face `f`'s owner and of its neighbour:
    /// the owner's gradient gains c_o ⊗ (φ_N − φ_P), the neighbour's
    /// loses c_n ⊗ (φ_N − φ_P).
    #[inline]
    pub fn internal_coefficients(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        f: usize,
    ) -> (Vector, Vector) {
        let o = mesh.owner[f] as usize;
        let n = mesh.neighbour[f] as usize;
        let d = geom.cell_centres[n] - geom.cell_centres[o];
        let w = self.weight[f];
        (self.inverse(o) * d * w, -(self.inverse(n) * d * w))
    }

    /// The vector c of boundary face `f`'s owner on a patch that is
    /// `passive` or not (zero on a passive one): the gradient of cell P
    /// gains c ⊗ (φ_f − φ_P) from f.
    #[inline]
    fn boundary_coefficient(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        f: usize,
        passive: bool,
    ) -> Vector {
        if passive {
            return Vector::zeros();
        }
        let o = mesh.owner[f] as usize;
        let d = geom.face_centres[f] - geom.cell_centres[o];
        let w = self.weight[f];
        self.inverse(o) * d * w
    }

    /// The vector c of boundary face `f`'s owner (zero on passive faces):
    /// the gradient of cell P gains c ⊗ (φ_f − φ_P) from f.
    pub fn owner_coefficient(&self, mesh: &PolyMesh, geom: &MeshGeometry, f: usize) -> Vector {
        let passive = mesh
            .patches
            .iter()
            .zip(&self.passive)
            .any(|(p, &passive)| passive && p.faces().contains(&f));
        self.boundary_coefficient(mesh, geom, f, passive)
    }

    /// Gradient of a vector field: `out[P] = Σ c ⊗ (φ_k − φ_P)`, with
    /// `(∇φ)_ij = ∂φ_j/∂x_i`. `boundary` holds the boundary-face values
    /// (index `face − n_internal_faces`); `geom` is the geometry of the
    /// last [`Self::update`].
    pub fn vector_gradient(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        cell: &[Vector],
        boundary: &[Vector],
        out: &mut [Tensor],
    ) {
        self.vector_gradient_of(mesh, geom, |i| cell[i], |b| boundary[b], out);
    }

    /// [`Self::vector_gradient`] of the field whose value in cell i is
    /// `cell(i)` and on boundary face b (index `face − n_internal_faces`)
    /// `boundary(b)`: for a field formed where it is read, such as an
    /// increment u − u_old.
    pub fn vector_gradient_of(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        cell: impl Fn(usize) -> Vector + Sync,
        boundary: impl Fn(usize) -> Vector + Sync,
        out: &mut [Tensor],
    ) {
        let ni = mesh.n_internal_faces();
        let Some(halves) = self.halves() else {
            self.gradient_of_cells(mesh, geom, &cell, &boundary, 0..ni, &[], 0, out);
            return;
        };
        // each half with the faces of its cells, in the one-thread order
        let (h, fs) = (halves.split, halves.face_split);
        let (out0, out1) = out.split_at_mut(h);
        rayon::join(
            || self.gradient_of_cells(mesh, geom, &cell, &boundary, 0..fs, &[], 0, out0),
            || {
                let cross = &halves.cross;
                self.gradient_of_cells(mesh, geom, &cell, &boundary, fs..ni, cross, h, out1)
            },
        );
    }

    /// The gradient of the cells `lo..lo + out.len()` (into `out`): the
    /// faces `cross` (owner below `lo`) to their neighbour, the internal
    /// faces `faces` to their owner and neighbour, the boundary faces to
    /// their owner, each only to cells of this range, in that order.
    #[allow(clippy::too_many_arguments)]
    fn gradient_of_cells(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        cell: &impl Fn(usize) -> Vector,
        boundary: &impl Fn(usize) -> Vector,
        faces: std::ops::Range<usize>,
        cross: &[u32],
        lo: usize,
        out: &mut [Tensor],
    ) {
        out.iter_mut().for_each(|t| *t = Tensor::zeros());
        let ni = mesh.n_internal_faces();
        let hi = lo + out.len();
        for &f in cross {
            let f = f as usize;
            let o = mesh.owner[f] as usize;
            let n = mesh.neighbour[f] as usize;
            let (_, c_n) = self.internal_coefficients(mesh, geom, f);
            let diff = cell(n) - cell(o);
            out[n - lo] -= c_n * diff.transpose();
        }
        for f in faces {
            let o = mesh.owner[f] as usize;
            let n = mesh.neighbour[f] as usize;
            let (c_o, c_n) = self.internal_coefficients(mesh, geom, f);
            let diff = cell(n) - cell(o);
            out[o - lo] += c_o * diff.transpose();
            if n < hi {
                out[n - lo] -= c_n * diff.transpose();
            }
        }
        for (p, &passive) in mesh.patches.iter().zip(&self.passive) {
            for f in p.faces() {
                let o = mesh.owner[f] as usize;
                if o < lo || o >= hi {
                    continue;
                }
                let c = self.boundary_coefficient(mesh, geom, f, passive);
                out[o - lo] += c * (boundary(f - ni) - cell(o)).transpose();
            }
        }
    }
}

/// Least-squares weight w = 1/|d|³.
///
/// Any weighting is exact for linear fields; the inverse cube makes the
/// fit at a boundary cell (boundary face centre at half the spacing of the
/// interior neighbour) exact also for a quadratic variation normal to the
/// boundary, which 1/|d|² is not (its gradient error there is h·φ''/4).
#[inline]
fn ls_weight(d: &Vector) -> f64 {
    let m2 = d.norm_squared();
    1.0 / (m2 * m2.sqrt())
}

/// Inverse of a symmetric positive semi-definite 3×3 matrix; directions with
/// eigenvalues below 1e-10 of the largest are dropped (pseudo-inverse).
fn pseudo_inverse_sym(g: &Tensor) -> Tensor {
    let eig = nalgebra::SymmetricEigen::new(*g);
    let max = eig.eigenvalues.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    if max <= 0.0 {
        return Tensor::zeros();
    }
    let mut inv = Tensor::zeros();
    for i in 0..3 {
        let l = eig.eigenvalues[i];
        if l > 1e-10 * max {
            let v = eig.eigenvectors.column(i);
            inv += v * v.transpose() / l;
        }
    }
    inv
}

#[cfg(test)]
mod tests {
    use super::*;
    use fv_mesh::generators::box_mesh;

    fn perturbed_box(n: usize, amp: f64, seed: u64) -> PolyMesh {
        let mut m = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 1.0, 1.0),
            [n, n, n],
            [1.0; 3],
        )
        .unwrap();
        let h = 1.0 / n as f64;
        let mut s = seed;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        for p in m.points.iter_mut() {
            let interior = (0..3).all(|d| p[d] > 1e-9 && p[d] < 1.0 - 1e-9);
            if interior {
                *p += Vector::new(rnd(), rnd(), rnd()) * amp * h;
            }
        }
        m
    }

    #[test]
    fn linear_field_exact_on_distorted_mesh() {
        let m = perturbed_box(6, 0.4, 7);
        let g = MeshGeometry::new(&m).unwrap();
        let op = LeastSquaresGradient::new(&m, &g, &vec![false; m.patches.len()]);
        let a = Tensor::new(1.0, 2.0, -0.5, 0.3, -1.0, 4.0, 0.0, 0.7, 2.5);
        let f = |x: &Vector| a.transpose() * x + Vector::new(1.0, -2.0, 0.5);
        let cell: Vec<Vector> = g.cell_centres.iter().map(f).collect();
        let ni = m.n_internal_faces();
        let bnd: Vec<Vector> = (ni..m.n_faces()).map(|fi| f(&g.face_centres[fi])).collect();
        let mut out = vec![Tensor::zeros(); m.n_cells];
        op.vector_gradient(&m, &g, &cell, &bnd, &mut out);
        for t in &out {
            assert!((t - a).norm() < 1e-10, "{t} vs {a}");
        }
    }

    #[test]
    fn one_cell_thick_mesh_has_zero_out_of_plane_gradient() {
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 1.0, 0.1),
            [5, 5, 1],
            [1.0; 3],
        )
        .unwrap();
        let g = MeshGeometry::new(&m).unwrap();
        let passive: Vec<bool> = m.patches.iter().map(|p| p.name.starts_with('z')).collect();
        let op = LeastSquaresGradient::new(&m, &g, &passive);
        let a = Tensor::new(1.0, 2.0, 0.0, 0.3, -1.0, 0.0, 0.0, 0.0, 0.0);
        let f = |x: &Vector| a.transpose() * x;
        let cell: Vec<Vector> = g.cell_centres.iter().map(f).collect();
        let ni = m.n_internal_faces();
        let bnd: Vec<Vector> = (ni..m.n_faces()).map(|fi| f(&g.face_centres[fi])).collect();
        let mut out = vec![Tensor::zeros(); m.n_cells];
        op.vector_gradient(&m, &g, &cell, &bnd, &mut out);
        for t in &out {
            assert!((t - a).norm() < 1e-10);
        }
    }
}
