//! The Jacobian of the balance of one body as a function of its state
//! ([`super::state_function`]), assembled block by block: the exact
//! linearisation of the finite-volume operators — least-squares gradients
//! with the kinematic faces eliminated, face interpolation, Rhie–Chow term,
//! boundary-face gradients and forces, face balances, inertia — with the
//! material tangent of every cell and boundary-face point taken by finite
//! differences of its stress update (the consistent, algorithmic tangent
//! of any model, plasticity included). Left out, as second-order for a
//! preconditioner: how a traction's or pressure's current area and a
//! plane-stress thickness follow the state, and the contact tractions
//! (their springs are added by the caller).
//!
//! Convention: G_ij = ∂u_j/∂x_i; tensors are vectorised column by column,
//! index i + 3j (nalgebra's storage order). A block (row, column) is
//! ∂F_row/∂u_column (3 × 3).
use super::{RhieChowHistory, SolidMomentum};
use crate::{MomentumParams, PatchCondition};
use fv_mesh::{MeshGeometry, PolyMesh, Tensor, Vector};
use nalgebra::SMatrix;

type M9 = SMatrix<f64, 9, 9>;
type M93 = SMatrix<f64, 9, 3>;
type M39 = SMatrix<f64, 3, 9>;

/// A node of the state of one body: a cell, or a boundary face (index
/// face − n_internal_faces) whose value is an unknown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum StateNode {
    /// A cell.
    Cell(u32),
    /// A boundary face with a traction-type condition.
    Face(u32),
}

/// Relative finite-difference step of the material tangents.
const TANGENT_STEP: f64 = 1e-7;

/// vec(c vᵀ) = (I ⊗ c) v: the 9 × 3 map of a vector v into the tensor c vᵀ.
fn outer_left(c: &Vector) -> M93 {
    let mut b = M93::zeros();
    for j in 0..3 {
        for i in 0..3 {
            b[(i + 3 * j, j)] = c[i];
        }
    }
    b
}

/// vec(c (A v)ᵀ): the 9 × 3 map of v.
fn outer_left_mapped(c: &Vector, a: &Tensor) -> M93 {
    let mut b = M93::zeros();
    for j in 0..3 {
        for k in 0..3 {
            for i in 0..3 {
                b[(i + 3 * j, k)] = c[i] * a[(j, k)];
            }
        }
    }
    b
}

/// S ↦ S v (3 × 9).
fn times_vector(v: &Vector) -> M39 {
    let mut l = M39::zeros();
    for j in 0..3 {
        for i in 0..3 {
            l[(i, i + 3 * j)] = v[j];
        }
    }
    l
}

/// G ↦ Gᵀ v (3 × 9).
fn transpose_times(v: &Vector) -> M39 {
    let mut r = M39::zeros();
    for j in 0..3 {
        for i in 0..3 {
            r[(j, i + 3 * j)] = v[i];
        }
    }
    r
}

fn vec9(t: &Tensor) -> SMatrix<f64, 9, 1> {
    SMatrix::<f64, 9, 1>::from_column_slice(t.as_slice())
}

/// The 9 × 9 derivative of `stress` (σ̂ of a gradient) at `g`, by forward
/// differences; `None` where the stress cannot be evaluated.
fn tangent(g: &Tensor, stress: impl Fn(&Tensor) -> Option<Tensor>) -> Option<M9> {
    let s0 = vec9(&stress(g)?);
    let h = TANGENT_STEP * g.amax().max(1.0);
    let mut c = M9::zeros();
    for k in 0..9 {
        let mut gp = *g;
        gp.as_mut_slice()[k] += h;
        let s = vec9(&stress(&gp)?);
        c.set_column(k, &((s - s0) / h));
    }
    Some(c)
}

/// The gradient stencil of one cell: vec(dG_P) = Σ B_k du_k.
type Stencil = Vec<(StateNode, M93)>;

impl SolidMomentum {
    /// The gradient stencils of every cell at the current geometry (the
    /// kinematic faces eliminated).
    fn gradient_stencils(&self, mesh: &PolyMesh, geom: &MeshGeometry) -> Vec<Stencil> {
        let ni = mesh.n_internal_faces();
        let mut st: Vec<Stencil> = vec![Vec::new(); mesh.n_cells];
        let add = |s: &mut Stencil, node: StateNode, b: M93| {
            if let Some(e) = s.iter_mut().find(|e| e.0 == node) {
                e.1 += b;
            } else {
                s.push((node, b));
            }
        };
        for f in 0..ni {
            let o = mesh.owner[f] as usize;
            let n = mesh.neighbour[f] as usize;
            // G_o += c_o (u_n − u_o)ᵀ, G_n −= c_n (u_n − u_o)ᵀ
            let (c_o, c_n) = self.gradient.internal_coefficients(mesh, geom, f);
            let bo = outer_left(&c_o);
            add(&mut st[o], StateNode::Cell(n as u32), bo);
            add(&mut st[o], StateNode::Cell(o as u32), -bo);
            let bn = outer_left(&c_n);
            add(&mut st[n], StateNode::Cell(n as u32), -bn);
            add(&mut st[n], StateNode::Cell(o as u32), bn);
        }
        let kin: std::collections::HashMap<u32, usize> = self
            .kinematic
            .faces
            .iter()
            .enumerate()
            .map(|(i, k)| (k.b, i))
            .collect();
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let o = mesh.owner[f] as usize;
                let c = self.gradient.owner_coefficient(mesh, geom, f);
                match cond {
                    // Δu_b − Δu_o = 0 (and passive)
                    PatchCondition::Empty => {}
                    // prescribed: −Δu_o
                    PatchCondition::Displacement(_) => {
                        add(&mut st[o], StateNode::Cell(o as u32), -outer_left(&c));
                    }
                    PatchCondition::Symmetry
                    | PatchCondition::NormalDisplacement(_)
                    | PatchCondition::TangentialDisplacement(_)
                    | PatchCondition::Wedge(_) => {
                        // (M − I) Δu_o; the Gᵀw part is in the elimination
                        if let Some(&i) = kin.get(&(b as u32)) {
                            let m = self.kinematic.faces[i].m;
                            add(
                                &mut st[o],
                                StateNode::Cell(o as u32),
                                outer_left_mapped(&c, &(m - Tensor::identity())),
                            );
                        }
                    }
                    _ => {
                        add(&mut st[o], StateNode::Face(b as u32), outer_left(&c));
                        add(&mut st[o], StateNode::Cell(o as u32), -outer_left(&c));
                    }
                }
            }
        }
        for (&cell, inv) in self.kinematic.cells.iter().zip(&self.kinematic.inverses) {
            for e in &mut st[cell as usize] {
                e.1 = inv * e.1;
            }
        }
        st
    }

    /// σ̂ of cell `o`'s material at a point with gradient `g`.
    fn cell_point_stress(&self, o: usize, g: &Tensor) -> Option<Tensor> {
        self.law.point_stress(o, g).map(|(_, h)| h)
    }

    /// σ̂ of boundary face `b` (owner `o`) whose force comes from its own
    /// stress (prescribed, symmetry, normal displacement), as
    /// `boundary_sigma_hat` evaluates it.
    fn face_point_stress(&self, b: usize, o: usize, g: &Tensor) -> Option<Tensor> {
        match &self.face_state {
            Some(fs) => match self.law.point_stress_in(fs, b, g) {
                Some((_, h)) => Some(h),
                None => self.cell_point_stress(o, g),
            },
            None => self.cell_point_stress(o, g),
        }
    }

    /// Calls `add(row, column, block)` with every block of the Jacobian
    /// ∂F/∂u of this body at its current state (the fields of the last
    /// evaluation of [`Self::compute_residual_with_face_rows`]); a block
    /// may come in several parts for one entry. Rows are the cells'
    /// balances and the state faces' balances.
    pub fn jacobian_blocks(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        params: &MomentumParams,
        add: &mut dyn FnMut(StateNode, StateNode, &Tensor),
    ) {
        let ni = mesh.n_internal_faces();
        let ul = self.law.is_updated_lagrangian();
        let stencils = self.gradient_stencils(mesh, geom);
        // cell tangents
        let tangents: Vec<M9> = (0..mesh.n_cells)
            .map(|o| {
                tangent(&self.grad_u[o], |g| self.cell_point_stress(o, g)).unwrap_or_else(M9::zeros)
            })
            .collect();
        let alpha = self.rhie_chow_override.unwrap_or(params.rhie_chow);
        let carry = ul && params.rhie_chow_history == RhieChowHistory::Accumulated;
        // row `row` += q · dG_cell
        let through_gradient =
            |row: StateNode,
             cell: usize,
             q: &M39,
             add: &mut dyn FnMut(StateNode, StateNode, &Tensor)| {
                for (node, b) in &stencils[cell] {
                    let blk: Tensor = q * b;
                    add(row, *node, &blk);
                }
            };
        for f in 0..ni {
            let o = mesh.owner[f] as usize;
            let n = mesh.neighbour[f] as usize;
            let w = geom.weight(mesh, f);
            let l = times_vector(&geom.face_areas[f]);
            let s = alpha * self.rc_face_scale(mesh, f) * self.k * geom.face_mag(f) / self.dn[f];
            // ∂force/∂G_f from the Rhie–Chow term and the carried forces
            let mut qf = transpose_times(&(geom.cell_centres[n] - geom.cell_centres[o])) * (-s);
            if carry {
                if let Some(c) = self.rc_carried.get(f) {
                    qf += transpose_times(c);
                }
            }
            let qo = l * tangents[o] * w + qf * w;
            let qn = l * tangents[n] * (1.0 - w) + qf * (1.0 - w);
            let (ro, rn) = (StateNode::Cell(o as u32), StateNode::Cell(n as u32));
            through_gradient(ro, o, &qo, add);
            through_gradient(ro, n, &qn, add);
            through_gradient(rn, o, &(-qo), add);
            through_gradient(rn, n, &(-qn), add);
            if alpha != 0.0 {
                let si = Tensor::identity() * s;
                add(ro, rn, &si);
                add(ro, ro, &(-si));
                add(rn, rn, &(-si));
                add(rn, ro, &si);
            }
        }
        let kin: std::collections::HashMap<u32, usize> = self
            .kinematic
            .faces
            .iter()
            .enumerate()
            .map(|(i, k)| (k.b, i))
            .collect();
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let o = mesh.owner[f] as usize;
                let row = StateNode::Cell(o as u32);
                let n = geom.face_normal(f);
                let area = geom.face_areas[f];
                let dn = self.dn[f];
                let gb = {
                    let (u, u_b) = self.increment();
                    let gp = self.grad_u[o];
                    let snd = (u_b[b] - u[o] - gp.transpose() * self.kb[b]) / dn;
                    gp + n * (snd - gp.transpose() * n).transpose()
                };
                // vec dG_b = P dG_o + (I ⊗ n)(du_b − du_o)/dn
                let i_n = outer_left(&n);
                let proj = M9::identity()
                    - i_n * transpose_times(&n)
                    - i_n * transpose_times(&self.kb[b]) / dn;
                match cond {
                    PatchCondition::Empty => {}
                    PatchCondition::Wedge(r) => {
                        // R σ̂_o Rᵀ Γ
                        let r = r[f - p.start];
                        let q = r * times_vector(&(r.transpose() * area)) * tangents[o];
                        through_gradient(row, o, &q, add);
                    }
                    PatchCondition::Displacement(_)
                    | PatchCondition::Symmetry
                    | PatchCondition::NormalDisplacement(_)
                    | PatchCondition::TangentialDisplacement(_) => {
                        let Some(cb) = tangent(&gb, |g| self.face_point_stress(b, o, g)) else {
                            continue;
                        };
                        let mut lf = times_vector(&area);
                        if let Some(held) = cond.held_projection(&n) {
                            lf = held * lf;
                        }
                        let q = lf * cb;
                        // du_b − du_o: −du_o (prescribed) or (M − I) du_o + M Gᵀw
                        let (mu, mw) = match kin.get(&(b as u32)) {
                            Some(&i) => {
                                let kf = &self.kinematic.faces[i];
                                (kf.m - Tensor::identity(), kf.m * transpose_times(&kf.w))
                            }
                            None => (-Tensor::identity(), M39::zeros()),
                        };
                        let qg = q * (proj + i_n * mw / dn);
                        through_gradient(row, o, &qg, add);
                        let qu: Tensor = q * i_n * mu / dn;
                        add(row, row, &qu);
                    }
                    PatchCondition::Traction(_)
                    | PatchCondition::Pressure(_)
                    | PatchCondition::LinearisedContact(_) => {
                        let face = StateNode::Face(b as u32);
                        let Some(cb) = tangent(&gb, |g| self.cell_point_stress(o, g)) else {
                            continue;
                        };
                        // internal = (σ̂_b n + m + G_bᵀ m) |Γ|
                        let mut q = times_vector(&n) * cb;
                        if let Some(m) = self.traction_offset.get(b) {
                            q += transpose_times(m);
                        }
                        let q = q * geom.face_mag(f);
                        let qg = q * proj;
                        let qu: Tensor = q * i_n / dn;
                        through_gradient(row, o, &qg, add);
                        add(row, face, &qu);
                        add(row, row, &(-qu));
                        through_gradient(face, o, &(-qg), add);
                        add(face, face, &(-qu));
                        add(face, row, &qu);
                    }
                }
            }
        }
        if let Some(inertia) = &self.inertia {
            for i in 0..mesh.n_cells {
                let d = Tensor::identity() * (-inertia.diagonal(i));
                add(StateNode::Cell(i as u32), StateNode::Cell(i as u32), &d);
            }
        }
    }

    /// The nodes each row of [`Self::jacobian_blocks`] can reach, for the
    /// sparsity pattern: `add(row, column)` for every pair (repeats
    /// possible).
    pub fn jacobian_pattern(
        &self,
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        add: &mut dyn FnMut(StateNode, StateNode),
    ) {
        let ni = mesh.n_internal_faces();
        let stencils = self.gradient_stencils(mesh, geom);
        let reach = |row: StateNode, cell: usize, add: &mut dyn FnMut(StateNode, StateNode)| {
            for (node, _) in &stencils[cell] {
                add(row, *node);
            }
        };
        for f in 0..ni {
            let o = mesh.owner[f] as usize;
            let n = mesh.neighbour[f] as usize;
            for row in [o, n] {
                let r = StateNode::Cell(row as u32);
                reach(r, o, add);
                reach(r, n, add);
                add(r, StateNode::Cell(o as u32));
                add(r, StateNode::Cell(n as u32));
            }
        }
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let o = mesh.owner[f] as usize;
                let row = StateNode::Cell(o as u32);
                reach(row, o, add);
                add(row, row);
                if matches!(
                    cond,
                    PatchCondition::Traction(_)
                        | PatchCondition::Pressure(_)
                        | PatchCondition::LinearisedContact(_)
                ) {
                    let face = StateNode::Face((f - ni) as u32);
                    reach(face, o, add);
                    add(face, face);
                    add(face, row);
                    add(row, face);
                }
            }
        }
    }
}
