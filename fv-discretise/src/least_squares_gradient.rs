//! Weighted least-squares cell-centre gradient (thesis §3.2.2, refs [16, 18]).
//!
//! For cell P with neighbours k (cell centres across internal faces and the
//! centres of its boundary faces), with d_k = r_k − r_P and w_k = 1/|d_k|³
//! (see [`ls_weight`]),
//! the gradient minimises Σ w_k (φ_k − φ_P − d_k·∇φ)². Its solution is
//! ∇φ_P = Σ_k c_k ⊗ (φ_k − φ_P) with c_k = G_P⁻¹ w_k d_k and
//! G_P = Σ_k w_k d_k d_kᵀ. The vectors c_k are precomputed once per
//! geometry, so the gradient is one pass over the faces.
//!
//! Faces of `empty` patches enter G but take φ_b = φ_P, which fixes the
//! gradient in the empty (out-of-plane) direction to zero and keeps G
//! invertible on one-cell-thick meshes.
use fv_mesh::{MeshGeometry, PolyMesh, Tensor, Vector};

/// Precomputed least-squares gradient operator of one mesh.
#[derive(Debug, Clone, Default)]
pub struct LeastSquaresGradient {
    /// c vector of the owner for every face.
    owner_coeff: Vec<Vector>,
    /// c vector of the neighbour for every internal face.
    neighbour_coeff: Vec<Vector>,
}

impl LeastSquaresGradient {
    /// Builds the operator; `passive_patch[p]` marks patches (empty) whose
    /// faces only regularise G.
    pub fn new(mesh: &PolyMesh, geom: &MeshGeometry, passive_patch: &[bool]) -> Self {
        let mut op = LeastSquaresGradient::default();
        op.update(mesh, geom, passive_patch);
        op
    }

    /// Recomputes the coefficients for the current geometry.
    pub fn update(&mut self, mesh: &PolyMesh, geom: &MeshGeometry, passive_patch: &[bool]) {
        let nc = mesh.n_cells;
        let ni = mesh.n_internal_faces();
        let nf = mesh.n_faces();
        let mut g = vec![Tensor::zeros(); nc];
        for f in 0..nf {
            let d = geom.delta(mesh, f);
            let w = ls_weight(&d);
            let dd = d * d.transpose() * w;
            g[mesh.owner[f] as usize] += dd;
            if f < ni {
                g[mesh.neighbour[f] as usize] += dd;
            }
        }
        let ginv: Vec<Tensor> = g.iter().map(pseudo_inverse_sym).collect();
        self.owner_coeff.resize(nf, Vector::zeros());
        self.neighbour_coeff.resize(ni, Vector::zeros());
        for f in 0..ni {
            let d = geom.delta(mesh, f);
            let w = ls_weight(&d);
            self.owner_coeff[f] = ginv[mesh.owner[f] as usize] * d * w;
            self.neighbour_coeff[f] = -(ginv[mesh.neighbour[f] as usize] * d * w);
        }
        for (pi, p) in mesh.patches.iter().enumerate() {
            let passive = passive_patch.get(pi).copied().unwrap_or(false);
            for f in p.faces() {
                let d = geom.delta(mesh, f);
                let w = ls_weight(&d);
                self.owner_coeff[f] = if passive {
                    Vector::zeros()
                } else {
                    ginv[mesh.owner[f] as usize] * d * w
                };
            }
        }
    }

    /// The vector c of every face's owner (zero on passive faces): the
    /// gradient of cell P gains c ⊗ (φ_f − φ_P) from its boundary face f.
    pub fn owner_coefficients(&self) -> &[Vector] {
        &self.owner_coeff
    }

    /// The vector c of every internal face's neighbour: the neighbour's
    /// gradient gains −c ⊗ (φ_N − φ_P) from face f.
    pub fn neighbour_coefficients(&self) -> &[Vector] {
        &self.neighbour_coeff
    }

    /// Gradient of a vector field: `out[P] = Σ c ⊗ (φ_k − φ_P)`, with
    /// `(∇φ)_ij = ∂φ_j/∂x_i`. `boundary` holds the boundary-face values
    /// (index `face − n_internal_faces`).
    pub fn vector_gradient(
        &self,
        mesh: &PolyMesh,
        cell: &[Vector],
        boundary: &[Vector],
        out: &mut [Tensor],
    ) {
        out.iter_mut().for_each(|t| *t = Tensor::zeros());
        let ni = mesh.n_internal_faces();
        for f in 0..ni {
            let o = mesh.owner[f] as usize;
            let n = mesh.neighbour[f] as usize;
            let diff = cell[n] - cell[o];
            out[o] += self.owner_coeff[f] * diff.transpose();
            out[n] -= self.neighbour_coeff[f] * diff.transpose();
        }
        for (b, &ub) in boundary.iter().enumerate() {
            let f = ni + b;
            let o = mesh.owner[f] as usize;
            out[o] += self.owner_coeff[f] * (ub - cell[o]).transpose();
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
        op.vector_gradient(&m, &cell, &bnd, &mut out);
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
        op.vector_gradient(&m, &cell, &bnd, &mut out);
        for t in &out {
            assert!((t - a).norm() < 1e-10);
        }
    }
}
