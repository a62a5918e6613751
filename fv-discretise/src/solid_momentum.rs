//! The segregated, deferred-correction discretisation of the solid momentum
//! equation for one body (thesis §3.2, eqs. 3.7–3.29).
//!
//! The balance of every cell P is written as a force residual
//!
//! F_P(u) = Σ_f Γ_f·σ_f + α_RC Σ_f K|Γ_f| [(u_N − u_P) − d_f·(∇u)_f]/(d_f·n_f)
//!          + Σ_b (boundary forces),
//!
//! i.e. the explicit surface source (3.15) with the Rhie–Chow stabilisation
//! (3.12 minus 3.14, scaled by α_RC). The implicit operator is the compact
//! (2μ+λ) Laplacian of (3.12) without its non-orthogonal part, matrix M with
//! a_N = −K|Γ_f|/(d_f·n_f) and the boundary diagonal of (3.19). Each outer
//! iteration solves M δ = F(u*) and sets u = u* + ω δ: the implicit and the
//! explicit diffusion terms of (3.7) are the same operator, so they cancel at
//! convergence and the converged field satisfies F(u) = 0 exactly (the
//! non-orthogonal correction of (3.12) cancels identically in this form).
use crate::{LeastSquaresGradient, PatchCondition};
use fv_materials::Material;
use fv_mesh::{MeshGeometry, PolyMesh, Tensor, Vector};

/// Knobs of the discretisation.
#[derive(Debug, Clone, Copy)]
pub struct MomentumParams {
    /// Rhie–Chow scaling α_RC (thesis: 0.1).
    pub rhie_chow: f64,
}

impl Default for MomentumParams {
    fn default() -> Self {
        MomentumParams { rhie_chow: 0.1 }
    }
}

/// Discretised momentum balance and fields of one body.
#[derive(Debug, Clone)]
pub struct SolidMomentum {
    /// Implicit stiffness K = 2μ + λ.
    pub k: f64,
    /// d·n of every face (boundary: d_b·n_b = |d_n|).
    dn: Vec<f64>,
    /// Boundary non-orthogonal vector k_b = d_b − (d_b·n) n (length), per boundary face.
    kb: Vec<Vector>,
    /// Least-squares gradient operator.
    pub gradient: LeastSquaresGradient,
    /// Condition of every patch.
    pub conditions: Vec<PatchCondition>,
    /// Cell-centre displacement.
    pub u: Vec<Vector>,
    /// Boundary-face displacement (index face − n_internal_faces).
    pub u_b: Vec<Vector>,
    /// Normal derivative n·∇u on traction faces (eq. 3.22), per boundary face.
    pub snd_b: Vec<Vector>,
    /// Cell displacement gradient.
    pub grad_u: Vec<Tensor>,
    /// Cell Cauchy stress.
    pub sigma: Vec<Tensor>,
    /// Force exerted on the body through every boundary face.
    pub face_force: Vec<Vector>,
    /// Force residual F_P of every cell.
    pub residual: Vec<Vector>,
    /// Body force per unit volume ρb (eq. 3.18), per cell; empty = none.
    pub body_force: Vec<Vector>,
}

impl SolidMomentum {
    /// Sets up the discretisation of a body at rest.
    pub fn new(
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        material: &dyn Material,
        conditions: Vec<PatchCondition>,
    ) -> Self {
        let nf = mesh.n_faces();
        let ni = mesh.n_internal_faces();
        let nb = nf - ni;
        let passive: Vec<bool> = conditions
            .iter()
            .map(|c| matches!(c, PatchCondition::Empty))
            .collect();
        let mut s = SolidMomentum {
            k: material.implicit_stiffness(),
            dn: vec![0.0; nf],
            kb: vec![Vector::zeros(); nb],
            gradient: LeastSquaresGradient::new(mesh, geom, &passive),
            conditions,
            u: vec![Vector::zeros(); mesh.n_cells],
            u_b: vec![Vector::zeros(); nb],
            snd_b: vec![Vector::zeros(); nb],
            grad_u: vec![Tensor::zeros(); mesh.n_cells],
            sigma: vec![Tensor::zeros(); mesh.n_cells],
            face_force: vec![Vector::zeros(); nb],
            residual: vec![Vector::zeros(); mesh.n_cells],
            body_force: Vec::new(),
        };
        s.update_geometry(mesh, geom);
        s
    }

    /// Recomputes the geometric coefficients (after mesh motion).
    pub fn update_geometry(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let ni = mesh.n_internal_faces();
        for f in 0..mesh.n_faces() {
            let n = geom.face_normals[f];
            let d = geom.delta[f];
            // guard against faces whose d is (nearly) tangential
            let dn = d.dot(&n).max(0.05 * d.norm());
            self.dn[f] = dn;
            if f >= ni {
                self.kb[f - ni] = d - n * d.dot(&n);
            }
        }
        let passive: Vec<bool> = self
            .conditions
            .iter()
            .map(|c| matches!(c, PatchCondition::Empty))
            .collect();
        self.gradient.update(mesh, geom, &passive);
    }

    /// d_f·n_f of face f (boundary faces: the normal distance |d_n| of the
    /// owner centre), clipped as in the matrix coefficients.
    #[inline]
    pub fn normal_distance(&self, f: usize) -> f64 {
        self.dn[f]
    }

    /// Implicit Laplacian coefficient K|Γ_f|/(d_f·n_f) of internal face f.
    #[inline]
    pub fn face_coefficient(&self, geom: &MeshGeometry, f: usize) -> f64 {
        self.k * geom.face_mag[f] / self.dn[f]
    }

    /// Adds the boundary contributions to the matrix diagonal of component
    /// `c` (0, 1, 2): eq. (3.19) for displacement faces, the normal part for
    /// symmetry and normal-displacement faces, nothing for traction faces.
    pub fn add_boundary_diagonal(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        c: usize,
        diag: &mut [f64],
    ) {
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let a = self.k * geom.face_mag[f] / self.dn[f];
                let o = mesh.owner[f] as usize;
                let n = geom.face_normals[f];
                diag[o] += match cond {
                    PatchCondition::Displacement(_) => a,
                    PatchCondition::Symmetry | PatchCondition::NormalDisplacement(_) => {
                        a * n[c] * n[c]
                    }
                    // hoop stiffness: K|Γ|/δ_n · sin²θ = K|Γ| sin θ / r per face
                    PatchCondition::Wedge(r) => a * (1.0 - r[f - p.start][(c, c)].powi(2)).max(0.0),
                    PatchCondition::Traction(_) | PatchCondition::Empty => 0.0,
                    PatchCondition::LinearisedContact(lc) if !lc.grounded => 0.0,
                    PatchCondition::LinearisedContact(lc) => {
                        // penalty springs in series with the half cell (eq. 4.54 i)
                        a * lc.diagonal_factor(f - p.start, c, self.dn[f] / self.k)
                    }
                };
            }
        }
    }

    /// Updates the boundary-face displacement from the cell values and the
    /// current gradient: prescribed (3.19), traction (3.22–3.24, with the
    /// normal-gradient correction 3.23), symmetry (3.26), wedge (rotation).
    pub fn update_boundary_values(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        material: &dyn Material,
    ) {
        let ni = mesh.n_internal_faces();
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let o = mesh.owner[f] as usize;
                let n = geom.face_normals[f];
                let gp = self.grad_u[o];
                let extrapolated = self.u[o] + gp.transpose() * self.kb[b];
                self.u_b[b] = match cond {
                    PatchCondition::Displacement(v) => v[f - p.start],
                    PatchCondition::Traction(t) => {
                        // g_b ← g_b + (t − n·σ_b)/K   (3.22–3.23)
                        let g = self.snd_b[b];
                        let grad_b = gp + n * (g - gp.transpose() * n).transpose();
                        let sig_b = material.stress(&grad_b);
                        let g_new = g + (t[f - p.start] - sig_b * n) / self.k;
                        self.snd_b[b] = g_new;
                        extrapolated + g_new * self.dn[f]
                    }
                    PatchCondition::Symmetry => extrapolated - n * n.dot(&extrapolated),
                    PatchCondition::NormalDisplacement(v) => {
                        extrapolated - n * n.dot(&extrapolated) + n * v[f - p.start]
                    }
                    PatchCondition::Empty => self.u[o],
                    PatchCondition::Wedge(r) => {
                        // the cell value at the face centre rotated back into the
                        // cell's plane (Rᵀk_b), then rotated onto the face plane:
                        // exact for linear fields, also for the prisms on the axis
                        let r = r[f - p.start];
                        r * (self.u[o] + gp.transpose() * (r.transpose() * self.kb[b]))
                    }
                    PatchCondition::LinearisedContact(lc) => {
                        // (3.22–3.23) with the traction of eq. 4.52, solved for
                        // the new normal derivative (eq. 4.53):
                        // (I + s N) g = g + (t* − ε β N (u_extr − u_b*) − n·σ_b)/K
                        let i = f - p.start;
                        let g = self.snd_b[b];
                        let grad_b = gp + n * (g - gp.transpose() * n).transpose();
                        let sig_b = material.stress(&grad_b);
                        let t_extr = lc.traction_at(i, &extrapolated);
                        let r = g + (t_extr - sig_b * n) / self.k;
                        let g_new = lc.solve_normal_derivative(i, self.dn[f] / self.k, &r);
                        self.snd_b[b] = g_new;
                        extrapolated + g_new * self.dn[f]
                    }
                };
            }
        }
    }

    /// Cell gradient (least squares) and stress from the current fields.
    pub fn update_gradient_and_stress(&mut self, mesh: &PolyMesh, material: &dyn Material) {
        self.gradient
            .vector_gradient(mesh, &self.u, &self.u_b, &mut self.grad_u);
        for (s, g) in self.sigma.iter_mut().zip(&self.grad_u) {
            *s = material.stress(g);
        }
    }

    /// Gradient at boundary face f: the cell gradient with its normal part
    /// replaced by the compact normal derivative (u_b − u_P − k_b·∇u_P)/|d_n|.
    #[inline]
    fn boundary_gradient(&self, f: usize, b: usize, o: usize, n: &Vector) -> Tensor {
        let gp = self.grad_u[o];
        let snd = (self.u_b[b] - self.u[o] - gp.transpose() * self.kb[b]) / self.dn[f];
        gp + n * (snd - gp.transpose() * n).transpose()
    }

    /// Computes the force residual F_P of every cell and the force through
    /// every boundary face (see the module documentation).
    pub fn compute_residual(
        &mut self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        material: &dyn Material,
        params: &MomentumParams,
    ) {
        let ni = mesh.n_internal_faces();
        if self.body_force.len() == self.residual.len() {
            for ((r, b), v) in self
                .residual
                .iter_mut()
                .zip(&self.body_force)
                .zip(&geom.cell_volumes)
            {
                *r = b * *v;
            }
        } else {
            self.residual.iter_mut().for_each(|r| *r = Vector::zeros());
        }
        let alpha = params.rhie_chow;
        for f in 0..ni {
            let o = mesh.owner[f] as usize;
            let nb = mesh.neighbour[f] as usize;
            let w = geom.weight[f];
            let sig_f = self.sigma[o] * w + self.sigma[nb] * (1.0 - w);
            let mut force = sig_f * geom.face_areas[f];
            if alpha != 0.0 {
                let grad_f = self.grad_u[o] * w + self.grad_u[nb] * (1.0 - w);
                let d = geom.delta[f];
                let jump = self.u[nb] - self.u[o] - grad_f.transpose() * d;
                force += jump * (alpha * self.k * geom.face_mag[f] / self.dn[f]);
            }
            self.residual[o] += force;
            self.residual[nb] -= force;
        }
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let o = mesh.owner[f] as usize;
                let n = geom.face_normals[f];
                let area = geom.face_areas[f];
                let force = match cond {
                    PatchCondition::Displacement(_) => {
                        material.stress(&self.boundary_gradient(f, b, o, &n)) * area
                    }
                    PatchCondition::Traction(t) => t[f - p.start] * geom.face_mag[f],
                    PatchCondition::LinearisedContact(lc) => {
                        lc.traction_at(f - p.start, &self.u_b[b]) * geom.face_mag[f]
                    }
                    PatchCondition::Symmetry | PatchCondition::NormalDisplacement(_) => {
                        let s = material.stress(&self.boundary_gradient(f, b, o, &n));
                        area * n.dot(&(s * n))
                    }
                    PatchCondition::Empty => Vector::zeros(),
                    PatchCondition::Wedge(r) => {
                        let r = r[f - p.start];
                        (r * self.sigma[o] * r.transpose()) * area
                    }
                };
                self.face_force[b] = force;
                self.residual[o] += force;
            }
        }
    }

    /// Boundary stress at every face of patch `p` (for output).
    pub fn boundary_stress(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        material: &dyn Material,
        p: usize,
    ) -> Vec<Tensor> {
        let ni = mesh.n_internal_faces();
        mesh.patches[p]
            .faces()
            .map(|f| {
                let o = mesh.owner[f] as usize;
                let n = geom.face_normals[f];
                material.stress(&self.boundary_gradient(f, f - ni, o, &n))
            })
            .collect()
    }

    /// Total force exerted on the body through patch `p`.
    pub fn patch_force(&self, mesh: &PolyMesh, p: usize) -> Vector {
        let ni = mesh.n_internal_faces();
        mesh.patches[p]
            .faces()
            .map(|f| self.face_force[f - ni])
            .sum()
    }
}
