//! A preconditioner of Newton's method: the segregated operator of the
//! thesis — per displacement component, the compact (2μ + λ) Laplacian of
//! eq. 3.29 with the boundary diagonal of eq. 3.19 — extended to the
//! state's face nodes and to the contact penalty springs, factorised by
//! IC(0).
//!
//! A traction-type face is a node of its own joined to its owner cell by
//! the half-cell coefficient a_b = K|Γ|/|d_n|: eliminated, it gives the
//! owner nothing (a free face), as the segregated matrix has it. A contact
//! face against a rigid body adds ε_n β|Γ| n_c² and, with friction, the
//! component's diagonal of the friction stiffness β|Γ| K_t (the tangential
//! penalty where the face sticks, the return map's derivative where it
//! slips: [`crate::contact_coupling::friction_stiffness`]) to its node's
//! diagonal; two deformable faces that overlap by the GGI area ω are
//! joined by a spring ε_n β ω (ε_t β ω across the normal with friction).
//! Eliminating the face nodes gives the springs in series with the
//! half cells, the cell coupling of implicit contact (eqs. 4.54, 4.63–4.72).
//! The matrix approximates −J: F(x + δ) ≈ F(x) − P δ.
use super::layout::StateLayout;
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use fv_discretise::{
    CsrMatrix, DirectMethod, DirectSolver, FaceSlots, LinearSolverError, PatchCondition, PcgAmg,
    PcgIc0,
};

/// Each application solves the operator of every component by IC(0)-PCG
/// to this relative residual (Newton's GMRES is flexible: the inner solve
/// may differ from one application to the next). Far cheaper than the
/// residual evaluation behind each GMRES iteration, it pays: measured on
/// Hertz (fine) / sphere on a block / flat punch, Newton–Krylov wall time
/// 0.39 / 1.52 / 0.30 s with one IC(0) sweep per application (28–43 GMRES
/// iterations per Newton step), 0.20 / 0.62 / 0.19 s at 0.1 (7–10),
/// 0.24 / 0.78 / 0.18 s at 0.3, 0.31 / 0.68 / 0.23 s at 0.03.
const INNER_TOLERANCE: f64 = 0.1;
/// Most inner PCG iterations per component and application.
const INNER_MAX_ITERATIONS: usize = 50;

/// Three-dimensional problems apply one V-cycle of aggregation multigrid
/// per component instead of IC(0)-PCG ([`fv_discretise::PcgAmg`]). The
/// V-cycle does on coarse levels what IC(0) needs ~33 iterations for on
/// the 19,904-cell sphere on a block; measured with Newton–Krylov
/// (Newton / residual evaluations, IC(0)-PCG → V-cycle): sphere on a block
/// ε_n/E = 1000 22 / 555 → 19 / 318 (11.1 → 2.9 s), scale 1 11 / 66 →
/// 12 / 86 with 31 % fewer instructions in the Newton solve (callgrind),
/// twisting hemisphere most Newton iterations per increment 15 → 10,
/// concentric spheres 43 → 37. On the plane cases (curved beams, die
/// drawing; 226–500 cells) the Newton paths changed for the worse (more
/// cut-backs), so they keep IC(0).
const MULTIGRID: bool = true;

/// Diagonal added to a body that nothing holds in a component (no
/// prescribed face, no contact spring yet), relative to its cells'
/// diagonal: it keeps the factorisation regular; the Newton step then
/// moves the body freely until contact holds it.
const FLOATING_STABILISATION: f64 = 1e-5;

/// How the preconditioner matrix of a component is inverted.
pub enum Factor {
    /// One IC(0) forward and backward sweep (the default).
    Ic0(Box<PcgIc0>),
    /// A sparse Cholesky factorisation (exact; small problems).
    Direct(Box<DirectSolver>),
    /// One V-cycle of aggregation multigrid (three-dimensional problems).
    Multigrid(Box<PcgAmg>),
}

impl Factor {
    fn factorise(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        match self {
            Factor::Ic0(s) => s.factorise(a),
            Factor::Direct(s) => s.factorise(a),
            Factor::Multigrid(s) => s.factorise(a),
        }
    }

    fn apply(
        &mut self,
        a: &CsrMatrix,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<usize, LinearSolverError> {
        match self {
            Factor::Ic0(s) => {
                z.iter_mut().for_each(|v| *v = 0.0);
                let p = fv_discretise::PcgParams {
                    tolerance: INNER_TOLERANCE,
                    max_iterations: INNER_MAX_ITERATIONS,
                };
                s.solve(a, r, z, &p).map(|i| i.iterations)
            }
            Factor::Direct(s) => s.substitute(r, z).map(|_| 1),
            Factor::Multigrid(s) => s.apply_preconditioner(a, r, z).map(|_| 1),
        }
    }
}

/// One matrix and factor per distinct solved component: components whose
/// matrices are equal (the same boundary diagonal, floating stabilisation
/// and spring components) share one, allocated as they first differ.
pub struct SegregatedOperator {
    matrices: Vec<CsrMatrix>,
    solvers: Vec<Factor>,
    /// Whether the factors are sparse Cholesky ones.
    direct: bool,
    /// Whether they are multigrid V-cycles ([`MULTIGRID`]).
    multigrid: bool,
    /// Component → matrix (None: not solved).
    component: [Option<usize>; 3],
    /// Solved components (those with `Some` in `layout.unsolved`'s complement).
    solved: [bool; 3],
    /// Slots of the links (internal faces, then face-node links).
    slots: FaceSlots,
    /// Coefficient of every link.
    link_coefficient: Vec<f64>,
    /// Contact springs between face nodes: (node a, node b, the diagonal
    /// of the spring tensor k_n n⊗n + K_t per component).
    springs: Vec<(u32, u32, [f64; 3])>,
    spring_entries: Vec<(u32, u32)>,
    spring_slots: Vec<u32>,
    /// Diagonal per component (workspace), node numbering.
    diagonal: [Vec<f64>; 3],
    /// Whether a body is held in a component (workspace, per body).
    held: Vec<[bool; 3]>,
    /// Per node, bit c: its body floats in component c (workspace).
    floating: Vec<u8>,
    /// Inner iterations of the preconditioner applications so far.
    pub inner_iterations: usize,
    /// Component vectors of `precondition`.
    r: Vec<f64>,
    z: Vec<f64>,
}

impl SegregatedOperator {
    /// Builds the pattern of the links: the internal faces of every
    /// deformable body and the link of every face node to its owner cell.
    pub fn new(bodies: &[Body], layout: &StateLayout, direct: bool) -> Self {
        let mut owner = Vec::new();
        let mut neighbour = Vec::new();
        for b in bodies.iter().filter(|b| !b.rigid) {
            let off = b.offset as u32;
            let ni = b.mesh.n_internal_faces();
            owner.extend(b.mesh.owner[..ni].iter().map(|&o| o + off));
            neighbour.extend(b.mesh.neighbour.iter().map(|&x| x + off));
        }
        for &(bi, bf) in &layout.face_of_node {
            let b = &bodies[bi as usize];
            let f = b.mesh.n_internal_faces() + bf as usize;
            owner.push(b.offset as u32 + b.mesh.owner[f]);
        }
        neighbour.extend((layout.n_cells..layout.n_nodes).map(|n| n as u32));
        let (matrix, slots) = CsrMatrix::from_faces(layout.n_nodes, &owner, &neighbour);
        let solved: [bool; 3] = std::array::from_fn(|c| !layout.unsolved[c]);
        let multigrid = MULTIGRID && !direct && solved.iter().all(|&s| s);
        // every solved component on the first matrix until they differ
        let component = solved.map(|s| s.then_some(0));
        SegregatedOperator {
            matrices: vec![matrix],
            solvers: vec![new_factor(direct, multigrid, layout.n_nodes)],
            direct,
            multigrid,
            component,
            solved,
            link_coefficient: vec![0.0; owner.len()],
            slots,
            springs: Vec::new(),
            spring_entries: Vec::new(),
            spring_slots: Vec::new(),
            diagonal: std::array::from_fn(|_| vec![0.0; layout.n_nodes]),
            held: vec![[false; 3]; bodies.len()],
            floating: vec![0; layout.n_nodes],
            r: vec![0.0; layout.n_nodes],
            z: vec![0.0; layout.n_nodes],
            inner_iterations: 0,
        }
    }

    /// Bytes held by the matrices and factors (an estimate: values,
    /// indices and the factors' triangles).
    pub fn memory_bytes(&self) -> usize {
        self.matrices
            .iter()
            .map(|m| m.nnz() * 12 * 2 + m.n() * 16)
            .sum()
    }

    /// Assembles and factorises the matrices about the current state of
    /// the bodies and the contact tractions of its last evaluation.
    pub fn assemble(
        &mut self,
        bodies: &[Body],
        contacts: &ContactSet,
        layout: &StateLayout,
    ) -> Result<(), LinearSolverError> {
        // link coefficients: internal faces, then face nodes
        let mut k = 0;
        for b in bodies.iter().filter(|b| !b.rigid) {
            for f in 0..b.mesh.n_internal_faces() {
                self.link_coefficient[k] = b.momentum.face_coefficient(&b.geom, f);
                k += 1;
            }
        }
        for &(bi, bf) in &layout.face_of_node {
            let b = &bodies[bi as usize];
            let f = b.mesh.n_internal_faces() + bf as usize;
            self.link_coefficient[k] = b.momentum.face_coefficient(&b.geom, f);
            k += 1;
        }
        for d in &mut self.diagonal {
            d.iter_mut().for_each(|v| *v = 0.0);
        }
        self.held.iter_mut().for_each(|h| *h = [false; 3]);
        self.boundary_diagonal(bodies);
        self.contact_springs(bodies, contacts, layout);
        // the spring entries join face nodes of two bodies: grow the
        // pattern when new pairs appear
        self.spring_entries.clear();
        for s in &self.springs {
            self.spring_entries.push((s.0, s.1));
            self.spring_entries.push((s.1, s.0));
        }
        if !self.spring_entries.is_empty()
            && !self.matrices[0].find_entries(&self.spring_entries, &mut self.spring_slots)
        {
            for (mi, m) in self.matrices.iter_mut().enumerate() {
                let growth = m.add_entries(&self.spring_entries)?;
                if mi == 0 {
                    self.slots.remap(&growth);
                    self.spring_slots.clear();
                    self.spring_slots.extend_from_slice(&growth.slots);
                }
            }
        }
        self.floating(bodies);
        self.share_matrices(layout.n_nodes);
        for c in 0..3 {
            let Some(mi) = self.component[c] else {
                continue;
            };
            if (0..c).any(|c0| self.component[c0] == Some(mi)) {
                continue; // assembled for an earlier, equal component
            }
            let m = &mut self.matrices[mi];
            m.fill_zero();
            let v = m.values_mut();
            for ((&up, &lo), &a) in self
                .slots
                .upper
                .iter()
                .zip(&self.slots.lower)
                .zip(&self.link_coefficient)
            {
                v[up as usize] -= a;
                v[lo as usize] -= a;
            }
            for (s, slots) in self.springs.iter().zip(self.spring_slots.chunks_exact(2)) {
                let kc = spring_component(s, c);
                v[slots[0] as usize] -= kc;
                v[slots[1] as usize] -= kc;
            }
            // diagonal: the links' and springs' coefficients of the row
            // (a Laplacian), a floating body's stabilisation, and the
            // boundary and contact diagonals
            for i in 0..m.n() {
                let (_, vals) = m.row(i);
                let links = -vals.iter().sum::<f64>();
                let k = m.diag_index()[i] as usize;
                let float = if self.floating[i] & (1 << c) != 0 {
                    FLOATING_STABILISATION * links
                } else {
                    0.0
                };
                m.values_mut()[k] = links + float + self.diagonal[c][i];
            }
        }
        let used = self.component.iter().flatten().max().map_or(0, |&m| m + 1);
        for (s, m) in self.solvers.iter_mut().zip(&self.matrices).take(used) {
            s.factorise(m)?;
        }
        Ok(())
    }

    /// Numbers the solved components' matrices so that equal ones share
    /// one: components c and c′ assemble bitwise the same matrix when their
    /// boundary and contact diagonals, floating stabilisations and spring
    /// components are equal. Allocates a matrix and factor only when more
    /// distinct ones are needed than ever before.
    fn share_matrices(&mut self, n_nodes: usize) {
        let mut component = [None; 3];
        let mut n_distinct = 0;
        for c in (0..3).filter(|&c| self.solved[c]) {
            let equal = (0..c).filter(|&c0| self.solved[c0]).find(|&c0| {
                self.diagonal[c0] == self.diagonal[c]
                    && self.floating.iter().all(|f| (f >> c0) & 1 == (f >> c) & 1)
                    && self
                        .springs
                        .iter()
                        .all(|s| spring_component(s, c0) == spring_component(s, c))
            });
            component[c] = Some(match equal {
                Some(c0) => component[c0].unwrap_or(0),
                None => {
                    n_distinct += 1;
                    n_distinct - 1
                }
            });
        }
        while self.matrices.len() < n_distinct {
            let template = self.matrices[0].clone();
            self.matrices.push(template);
            self.solvers
                .push(new_factor(self.direct, self.multigrid, n_nodes));
        }
        self.component = component;
    }

    /// Boundary diagonal of the cells (eq. 3.19 and the kinematic faces)
    /// and the temporal term, per component.
    fn boundary_diagonal(&mut self, bodies: &[Body]) {
        for (bi, b) in bodies.iter().enumerate().filter(|(_, b)| !b.rigid) {
            let m = &b.momentum;
            for (p, cond) in b.mesh.patches.iter().zip(&m.conditions) {
                for f in p.faces() {
                    let a = m.face_coefficient(&b.geom, f);
                    let o = b.offset + b.mesh.owner[f] as usize;
                    let n = b.geom.face_normal(f);
                    for c in 0..3 {
                        let add = match cond {
                            PatchCondition::Displacement(_) => a,
                            PatchCondition::Symmetry
                            | PatchCondition::NormalDisplacement(_)
                            | PatchCondition::TangentialDisplacement(_) => {
                                cond.held_projection(&n).map_or(0.0, |h| a * h[(c, c)])
                            }
                            PatchCondition::Wedge(r) => {
                                a * (1.0 - r[f - p.start][(c, c)].powi(2)).max(0.0)
                            }
                            _ => 0.0,
                        };
                        if add > 0.0 {
                            self.diagonal[c][o] += add;
                            self.held[bi][c] = true;
                        }
                    }
                }
            }
            if let Some(inertia) = &m.inertia {
                for i in 0..b.mesh.n_cells {
                    for c in 0..3 {
                        self.diagonal[c][b.offset + i] += inertia.diagonal(i);
                    }
                }
                self.held[bi] = [true; 3];
            }
        }
    }

    /// The contact springs of the last contact evaluation: grounded ones on
    /// the face nodes' diagonals, the others into `springs`.
    fn contact_springs(&mut self, bodies: &[Body], contacts: &ContactSet, layout: &StateLayout) {
        self.springs.clear();
        for ci in &contacts.interfaces {
            let eps = ci.normal_penalty();
            let eps_t = ci.tangential_penalty();
            let (mb, sb) = (ci.master.body, ci.slave.body);
            let beta = crate::contact_coupling::linearised_fraction;
            let friction = crate::contact_coupling::friction_stiffness;
            if bodies[mb].rigid || bodies[sb].rigid {
                for (side, contact) in [
                    (&ci.master, &ci.tractions.master),
                    (&ci.slave, &ci.tractions.slave),
                ] {
                    let b = &bodies[side.body];
                    if b.rigid {
                        continue;
                    }
                    let start = b.mesh.patches[side.patch].start - b.mesh.n_internal_faces();
                    for i in 0..side.surface.n_faces() {
                        let be = beta(side, contact, i);
                        if !(be > 0.0) {
                            continue;
                        }
                        let Some(node) = layout.face_node(side.body, start + i) else {
                            continue;
                        };
                        let a = side.surface.face_mag[i] * be;
                        let n = side.surface.face_normals[i];
                        let kt = friction(contact, i, &n, eps_t);
                        for c in 0..3 {
                            self.diagonal[c][node] += a * (eps * n[c] * n[c] + kt[(c, c)]);
                        }
                        self.held[side.body] = [true; 3];
                    }
                }
                continue;
            }
            let (bm, bs) = (&bodies[mb], &bodies[sb]);
            let m_start = bm.mesh.patches[ci.master.patch].start - bm.mesh.n_internal_faces();
            let s_start = bs.mesh.patches[ci.slave.patch].start - bs.mesh.n_internal_faces();
            for m in 0..ci.master.surface.n_faces() {
                let be = beta(&ci.master, &ci.tractions.master, m);
                if !(be > 0.0) {
                    continue;
                }
                let Some(nm) = layout.face_node(mb, m_start + m) else {
                    continue;
                };
                let normal = ci.master.surface.face_normals[m];
                let (slaves, overlaps) = ci.tractions.ggi.master_row(m);
                for (&s, &w) in slaves.iter().zip(overlaps) {
                    let Some(ns) = layout.face_node(sb, s_start + s as usize) else {
                        continue;
                    };
                    if !(w > 0.0) {
                        continue;
                    }
                    // between two deformable bodies the sticking spring
                    // whatever the state (`friction_stiffness`)
                    let k = [0, 1, 2].map(|c| {
                        let nc2 = normal[c] * normal[c];
                        (eps * nc2 + eps_t * (1.0 - nc2)) * be * w
                    });
                    self.springs.push((nm as u32, ns as u32, k));
                    self.held[mb] = [true; 3];
                    self.held[sb] = [true; 3];
                }
            }
        }
    }

    /// Marks the cells of a body held by nothing in a component for the
    /// [`FLOATING_STABILISATION`] of their diagonal.
    fn floating(&mut self, bodies: &[Body]) {
        self.floating.iter_mut().for_each(|f| *f = 0);
        for (bi, b) in bodies.iter().enumerate().filter(|(_, b)| !b.rigid) {
            for c in 0..3 {
                if !self.held[bi][c] {
                    for f in &mut self.floating[b.offset..b.offset + b.mesh.n_cells] {
                        *f |= 1 << c;
                    }
                }
            }
        }
    }

    /// Whether [`Self::apply`] is a fixed linear map between two
    /// assemblies (sparse Cholesky or multigrid V-cycles; IC(0)-PCG to a
    /// tolerance is not).
    pub fn is_linear(&self) -> bool {
        self.direct || self.multigrid
    }

    /// z = P⁻¹ r (interleaved node-major vectors).
    pub fn apply(&mut self, r: &[f64], z: &mut [f64]) {
        for c in 0..3 {
            let Some(mi) = self.component[c] else {
                for zi in z.iter_mut().skip(c).step_by(3) {
                    *zi = 0.0;
                }
                continue;
            };
            for (rc, ri) in self.r.iter_mut().zip(r.iter().skip(c).step_by(3)) {
                *rc = *ri;
            }
            match self.solvers[mi].apply(&self.matrices[mi], &self.r, &mut self.z) {
                Ok(k) => self.inner_iterations += k,
                Err(_) => self.z.copy_from_slice(&self.r),
            }
            for (zi, zc) in z.iter_mut().skip(c).step_by(3).zip(&self.z) {
                *zi = *zc;
            }
        }
    }
}

/// Component c of a spring's tensor k_n n⊗n + k_t (I − n⊗n), diagonal.
fn spring_component(s: &(u32, u32, [f64; 3]), c: usize) -> f64 {
    s.2[c]
}

/// The inverse of one component's matrix.
fn new_factor(direct: bool, multigrid: bool, n: usize) -> Factor {
    if direct {
        Factor::Direct(Box::new(DirectSolver::new(DirectMethod::Cholesky)))
    } else if multigrid {
        Factor::Multigrid(Box::new(PcgAmg::new(n)))
    } else {
        Factor::Ic0(Box::new(PcgIc0::new(n)))
    }
}
