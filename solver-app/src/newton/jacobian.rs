//! The assembled Jacobian of the state, as Newton's preconditioner: the
//! bodies' blocks (`SolidMomentum::jacobian_blocks`, the exact
//! linearisation of the discretisation with finite-difference material
//! tangents) and the contact block of the last evaluation: the penalty
//! springs, or, once they no longer serve ([`AssembledJacobian::use_contact_derivative`]),
//! on faces with pressure the derivative of their contact forces
//! ([`ContactSet::traction_jacobian`]) and the springs elsewhere, as
//! full 3 × 3 tensors (friction by its state: `friction_stiffness` and,
//! where a face slips, `friction_normal_coupling` of
//! [`crate::contact_coupling`]), factorised by sparse LU (faer) or, for large
//! systems, ILU(0). Where the segregated operator ignores how the
//! displacement components couple — the bending of a slender body, whose
//! shear-free rotation the component Laplacian resists at full stiffness —
//! this matrix has it, and GMRES needs a few iterations instead of
//! hundreds.
use super::layout::StateLayout;
use crate::contact_coupling::{ContactSet, TractionJacobianWork};
use crate::model::Body;
use fv_discretise::{
    BicgstabIlu0, CsrMatrix, DirectMethod, DirectSolver, LinearSolverError, MomentumParams,
    StateNode,
};
use fv_mesh::{Tensor, Vector};

/// Systems of at most this many scalar unknowns are factorised exactly
/// (sparse LU); larger ones by ILU(0).
pub const LU_LIMIT: usize = 150_000;

/// Unknowns up to which `"auto"` factorises the Jacobian of a 3-D problem
/// (its LU fills in far more than a 2-D one's). A block dragged under a
/// traction (216 cells, 756 unknowns, validation test
/// `traction_face_does_not_creep_under_constant_load`) needs it; the
/// concentric spheres (2,500 unknowns) ran 2× slower with it.
pub const LU_LIMIT_3D: usize = 2_000;

/// Unknowns up to which `"auto"` factorises the Jacobian of a larger 3-D
/// problem once a Krylov solve preconditioned by the segregated operator
/// has used all its iterations: there the per-component operator misses
/// what couples the components (a slender body's bending), and GMRES
/// makes no progress at all. Found with a tetrahedral cantilever (gmsh,
/// 455 cells, 2,439 unknowns, tip shear): every Newton step at 200 Krylov
/// iterations with the linear residual at 0.9–1.0, and the increment
/// failed; factorised, 1 Newton iteration (0.09 s). Meshes of 9,982 cells
/// (29,946 unknowns): the same, and 2.7 s factorised. Since 2026-12-01 the
/// switch factorises by ILU(0) first, and by LU only up to
/// [`RESCUE_LU_LIMIT_3D`].
pub const STALLED_LU_LIMIT_3D: usize = 100_000;

/// Unknowns up to which a 3-D problem whose Krylov solves stall with the
/// ILU(0) of the Jacobian is given its LU for the rest of the step. The
/// tetrahedral cantilevers need it (up to 29,946 unknowns, 2.7 s); the
/// sphere on a block at `penalty_scale = 100` (65,856 unknowns) stalls
/// with either factor, and its LU held 2.3 GB and ran for over 10 minutes
/// without finishing the increment.
pub const RESCUE_LU_LIMIT_3D: usize = 30_000;

/// How the assembled Jacobian is factorised.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JacobianFactor {
    /// Sparse LU (faer): exact, GMRES converges in a step or two; its
    /// fill-in costs time and memory on 3-D meshes.
    Lu,
    /// ILU(0) on the Jacobian's own pattern: one pass to factorise, two
    /// sweeps to apply; a few tens of Krylov iterations.
    Ilu0,
}

impl JacobianFactor {
    /// Exact up to [`LU_LIMIT`] unknowns, incomplete above (`"jacobian"`,
    /// plane problems).
    pub fn for_unknowns(unknowns: usize) -> Self {
        if unknowns <= LU_LIMIT {
            JacobianFactor::Lu
        } else {
            JacobianFactor::Ilu0
        }
    }
}

enum Factor {
    Lu(Box<DirectSolver>),
    Ilu(Box<BicgstabIlu0>),
}

impl Factor {
    fn new(kind: JacobianFactor, n: usize) -> Self {
        match kind {
            JacobianFactor::Lu => Factor::Lu(Box::new(DirectSolver::new(DirectMethod::Lu))),
            JacobianFactor::Ilu0 => Factor::Ilu(Box::new(BicgstabIlu0::new(n))),
        }
    }
}

/// −J of the state, assembled, and its factorisation.
pub struct AssembledJacobian {
    n_nodes: usize,
    /// Block pattern (rows = nodes), columns sorted per row.
    row_ptr: Vec<u32>,
    cols: Vec<u32>,
    blocks: Vec<Tensor>,
    /// The pattern's extra entries (contact springs between bodies).
    extra: Vec<(u32, u32)>,
    /// The scalar matrix over the solved components (`n_solved` per node)
    /// and, per block entry, the value index of each of its solved
    /// scalars (`n_solved²` per block).
    scalar: CsrMatrix,
    scalar_slot: Vec<u32>,
    /// The solved components, and how many there are.
    solved: [usize; 3],
    n_solved: usize,
    /// Right-hand side and solution over the solved components (workspace).
    rs: Vec<f64>,
    zs: Vec<f64>,
    factor: Factor,
    /// Contact springs between face nodes of two bodies (workspace).
    springs: Vec<(u32, u32, Tensor)>,
    /// Whether `factor` holds a factorisation of the last assembly.
    factorised: bool,
    /// The pseudo-transient shift σ of the last assembly.
    shift: f64,
    /// The contact block's entries (workspace) and its workspaces.
    contact_entries: Vec<(u32, u32, Tensor)>,
    contact_work: TractionJacobianWork,
    /// Whether the contact block is the derivative of the contact forces
    /// (else the springs alone).
    contact_derivative: bool,
}

/// The global node of a body's state node.
fn global(body: &Body, layout: &StateLayout, bi: usize, node: StateNode) -> Option<u32> {
    match node {
        StateNode::Cell(c) => Some(body.offset as u32 + c),
        StateNode::Face(b) => layout.face_node(bi, b as usize).map(|n| n as u32),
    }
}

impl AssembledJacobian {
    /// The pattern of the bodies (and of `extra` pairs), no values yet.
    pub fn new(bodies: &[Body], layout: &StateLayout, kind: JacobianFactor) -> Self {
        let mut solved = [0; 3];
        let mut n_solved = 0;
        for c in (0..3).filter(|&c| !layout.unsolved[c]) {
            solved[n_solved] = c;
            n_solved += 1;
        }
        let mut j = AssembledJacobian {
            solved,
            n_solved,
            rs: vec![0.0; n_solved * layout.n_nodes],
            zs: vec![0.0; n_solved * layout.n_nodes],
            n_nodes: layout.n_nodes,
            row_ptr: Vec::new(),
            cols: Vec::new(),
            blocks: Vec::new(),
            extra: Vec::new(),
            scalar: CsrMatrix::from_faces(1, &[], &[]).0,
            scalar_slot: Vec::new(),
            factor: Factor::new(kind, n_solved * layout.n_nodes),
            springs: Vec::new(),
            factorised: false,
            shift: 0.0,
            contact_entries: Vec::new(),
            contact_work: TractionJacobianWork::default(),
            contact_derivative: false,
        };
        j.build_pattern(bodies, layout);
        j
    }

    /// Bytes of the matrix and its scalar copy (the factor comes on top).
    pub fn memory_bytes(&self) -> usize {
        self.blocks.len() * (72 + 4 + 36) + self.scalar.nnz() * 12
    }

    fn build_pattern(&mut self, bodies: &[Body], layout: &StateLayout) {
        let mut rows: Vec<Vec<u32>> = vec![Vec::new(); self.n_nodes];
        for (bi, b) in bodies.iter().enumerate().filter(|(_, b)| !b.rigid) {
            b.momentum.jacobian_pattern(&b.mesh, &b.geom, &mut |r, c| {
                if let (Some(r), Some(c)) = (global(b, layout, bi, r), global(b, layout, bi, c)) {
                    rows[r as usize].push(c);
                }
            });
        }
        for (i, row) in rows.iter_mut().enumerate() {
            row.push(i as u32);
        }
        for &(r, c) in &self.extra {
            rows[r as usize].push(c);
        }
        self.row_ptr.clear();
        self.cols.clear();
        self.row_ptr.push(0);
        for r in &mut rows {
            r.sort_unstable();
            r.dedup();
            self.cols.extend_from_slice(r);
            self.row_ptr.push(self.cols.len() as u32);
        }
        self.blocks = vec![Tensor::zeros(); self.cols.len()];
        // the scalar matrix: n_solved² entries per block
        let m = self.n_solved;
        let mut triplets = Vec::with_capacity(m * m * self.cols.len());
        for r in 0..self.n_nodes {
            for k in self.row_ptr[r] as usize..self.row_ptr[r + 1] as usize {
                let c = self.cols[k] as usize;
                for i in 0..m {
                    for jj in 0..m {
                        triplets.push(((m * r + i) as u32, (m * c + jj) as u32, 0.0));
                    }
                }
            }
        }
        self.scalar = CsrMatrix::from_triplets(m * self.n_nodes, &triplets)
            .unwrap_or_else(|_| CsrMatrix::from_faces(m * self.n_nodes, &[], &[]).0);
        self.scalar_slot.clear();
        for r in 0..self.n_nodes {
            for k in self.row_ptr[r] as usize..self.row_ptr[r + 1] as usize {
                let c = self.cols[k] as usize;
                for i in 0..m {
                    for jj in 0..m {
                        let e = self.scalar.entry_index(m * r + i, m * c + jj).unwrap_or(0);
                        self.scalar_slot.push(e as u32);
                    }
                }
            }
        }
    }

    /// The block slot of (row, col), if in the pattern.
    #[inline]
    fn slot(&self, r: u32, c: u32) -> Option<usize> {
        let (s, e) = (
            self.row_ptr[r as usize] as usize,
            self.row_ptr[r as usize + 1] as usize,
        );
        self.cols[s..e].binary_search(&c).ok().map(|k| s + k)
    }

    /// Assembles −J + σ D at the bodies' current state with the contact
    /// springs of the last contact evaluation, and factorises it. `shift`:
    /// the pseudo-transient shift σ and the per-node scale D
    /// (`NonlinearProblem::damping`); σ = 0 for a Newton step.
    pub fn assemble(
        &mut self,
        bodies: &[Body],
        contacts: &mut ContactSet,
        layout: &StateLayout,
        params: &MomentumParams,
        shift: (f64, &[f64]),
    ) -> Result<(), LinearSolverError> {
        // the contact block: the forces' derivative where it can be taken
        // (a contact algorithm that fails at a perturbed point leaves the
        // springs), the springs for faces touching without pressure
        self.contact_entries.clear();
        let mut exact = self.contact_derivative;
        for k in 0..contacts.interfaces.len() {
            if exact
                && contacts.linearises_tractions(k)
                && contacts
                    .traction_jacobian(
                        k,
                        bodies,
                        layout,
                        &mut self.contact_work,
                        &mut self.contact_entries,
                    )
                    .is_err()
            {
                exact = false;
                self.contact_entries.clear();
            }
        }
        self.contact_springs(bodies, contacts, layout, exact);
        let missing = self.springs.iter().any(|s| self.slot(s.0, s.1).is_none())
            || self
                .contact_entries
                .iter()
                .any(|e| self.slot(e.0, e.1).is_none());
        if missing {
            for s in &self.springs {
                self.extra.push((s.0, s.1));
                self.extra.push((s.1, s.0));
            }
            for e in &self.contact_entries {
                self.extra.push((e.0, e.1));
                self.extra.push((e.1, e.0));
            }
            self.extra.sort_unstable();
            self.extra.dedup();
            self.build_pattern(bodies, layout);
        }
        self.blocks.iter_mut().for_each(|b| *b = Tensor::zeros());
        for (bi, b) in bodies.iter().enumerate().filter(|(_, b)| !b.rigid) {
            let mut blocks = std::mem::take(&mut self.blocks);
            b.momentum
                .jacobian_blocks(&b.mesh, &b.geom, params, &mut |r, c, blk| {
                    if let (Some(r), Some(c)) = (global(b, layout, bi, r), global(b, layout, bi, c))
                    {
                        if let Some(k) = self.slot(r, c) {
                            blocks[k] -= blk;
                        }
                    }
                });
            self.blocks = blocks;
        }
        // grounded springs were added to the diagonal blocks; the others join two face nodes
        for (a, b, k) in std::mem::take(&mut self.springs) {
            if a == b {
                if let Some(s) = self.slot(a, a) {
                    self.blocks[s] += k;
                }
                continue;
            }
            for (r, c, sign) in [(a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)] {
                if let Some(s) = self.slot(r, c) {
                    self.blocks[s] += k * sign;
                }
            }
        }
        for &(r, c, k) in &self.contact_entries {
            if let Some(s) = self.slot(r, c) {
                self.blocks[s] += k;
            }
        }
        // the continuation's shift on the diagonal blocks
        let (sigma, damping) = shift;
        if sigma > 0.0 {
            for (node, d) in damping.iter().enumerate().take(self.n_nodes) {
                if let Some(s) = self.slot(node as u32, node as u32) {
                    self.blocks[s] += Tensor::identity() * (sigma * d);
                }
            }
        }
        self.shift = sigma;
        // to the scalar matrix of the solved components
        let m = self.n_solved;
        let v = self.scalar.values_mut();
        v.iter_mut().for_each(|x| *x = 0.0);
        for (k, blk) in self.blocks.iter().enumerate() {
            for i in 0..m {
                for jj in 0..m {
                    v[self.scalar_slot[m * m * k + m * i + jj] as usize] +=
                        blk[(self.solved[i], self.solved[jj])];
                }
            }
        }
        self.factorised = false;
        match &mut self.factor {
            Factor::Lu(s) => s.factorise(&self.scalar)?,
            Factor::Ilu(s) => s.factorise(&self.scalar)?,
        };
        self.factorised = true;
        Ok(())
    }

    /// The penalty springs of the last contact evaluation, as full
    /// tensors: (node, node, k) — a grounded one has both nodes equal.
    fn contact_springs(
        &mut self,
        bodies: &[Body],
        contacts: &ContactSet,
        layout: &StateLayout,
        exact: bool,
    ) {
        self.springs.clear();
        for (k, ci) in contacts.interfaces.iter().enumerate() {
            // faces with pressure have the derivative of their forces
            let pressed_exact = exact && contacts.linearises_tractions(k);
            let eps = ci.normal_penalty();
            let eps_t = ci.tangential_penalty();
            let friction = crate::contact_coupling::friction_stiffness;
            let tensor =
                |n: &Vector, kt: Tensor, scale: f64| (n * n.transpose() * eps + kt) * scale;
            let beta = crate::contact_coupling::linearised_fraction;
            let (mb, sb) = (ci.master.body, ci.slave.body);
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
                        if !(be > 0.0) || (pressed_exact && contact.pressure[i] > 0.0) {
                            continue;
                        }
                        if let Some(node) = layout.face_node(side.body, start + i) {
                            let n = side.surface.face_normals[i];
                            let kt = friction(contact, i, &n, eps_t)
                                + crate::contact_coupling::friction_normal_coupling(
                                    contact, i, &n, eps,
                                );
                            let k = tensor(&n, kt, side.surface.face_mag[i] * be);
                            self.springs.push((node as u32, node as u32, k));
                        }
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
                    let pressed = ci.tractions.master.pressure[m] > 0.0
                        || ci.tractions.slave.pressure[s as usize] > 0.0;
                    if w > 0.0 && !(pressed_exact && pressed) {
                        // between two deformable bodies the sticking spring
                        // whatever the state (`friction_stiffness`)
                        let kt = (Tensor::identity() - normal * normal.transpose()) * eps_t;
                        self.springs
                            .push((nm as u32, ns as u32, tensor(&normal, kt, be * w)));
                    }
                }
            }
        }
    }

    /// From the next assembly on, the contact block is the derivative of
    /// the contact forces on faces with pressure, by coloured finite
    /// differences ([`ContactSet::traction_jacobian`]), not the penalty
    /// springs there. The springs miss how a face's force follows the
    /// cells around it (the interpolation to the surface points) and how
    /// the overlaps change as faces slide; at a penalty stiff against the
    /// cells that is most of the block, and GMRES with their LU needs
    /// 8–17 iterations a step (die drawing at penalty scale 100; at scale
    /// one 2–7) or stalls at its limit (a sphere on a block at 100). The
    /// derivative is not the better Newton matrix everywhere: at the die's
    /// penalty scale 1 its exact steps, taken where faces are about to
    /// slide past a facet's end, ran 2,040 Newton iterations where the
    /// springs' ran 1,157, and the steady force spread 2.6 % (0.25 %).
    pub fn use_contact_derivative(&mut self) {
        self.contact_derivative = true;
        self.factorised = false;
    }

    /// Whether the contact block is the derivative of the contact forces.
    pub fn contact_derivative(&self) -> bool {
        self.contact_derivative
    }

    /// The pseudo-transient shift σ the held factorisation includes.
    pub fn shift(&self) -> f64 {
        self.shift
    }

    /// Whether a factorisation is held.
    pub fn is_factorised(&self) -> bool {
        self.factorised
    }

    /// How it is factorised.
    pub fn kind(&self) -> JacobianFactor {
        match self.factor {
            Factor::Lu(_) => JacobianFactor::Lu,
            Factor::Ilu(_) => JacobianFactor::Ilu0,
        }
    }

    /// Factorised as `kind` says from the next assembly on.
    pub fn refactor_as(&mut self, kind: JacobianFactor) {
        if self.kind() != kind {
            self.factor = Factor::new(kind, self.n_solved * self.n_nodes);
            self.factorised = false;
        }
    }

    /// z = (−J)⁻¹ r (interleaved node-major vectors).
    pub fn apply(&mut self, r: &[f64], z: &mut [f64]) -> Result<(), LinearSolverError> {
        self.gather(r);
        match &mut self.factor {
            Factor::Lu(s) => s.substitute(&self.rs, &mut self.zs)?,
            Factor::Ilu(s) => s.apply_preconditioner(&self.rs, &mut self.zs)?,
        };
        self.scatter(z);
        Ok(())
    }

    /// The solved components of `r` into `rs`.
    fn gather(&mut self, r: &[f64]) {
        let m = self.n_solved;
        for (node, rs) in self.rs.chunks_exact_mut(m).enumerate() {
            for (i, v) in rs.iter_mut().enumerate() {
                *v = r[3 * node + self.solved[i]];
            }
        }
    }

    /// `zs` into the solved components of `z`, the others zero.
    fn scatter(&self, z: &mut [f64]) {
        let m = self.n_solved;
        z.iter_mut().for_each(|v| *v = 0.0);
        for (node, zs) in self.zs.chunks_exact(m).enumerate() {
            for (i, v) in zs.iter().enumerate() {
                z[3 * node + self.solved[i]] = *v;
            }
        }
    }

    /// −J v with the assembled blocks (for tests against the Jacobian
    /// products).
    pub fn negative_jacobian_times(&mut self, v: &[f64], out: &mut [f64]) {
        self.gather(v);
        let mut zs = std::mem::take(&mut self.zs);
        self.scalar.mul_vec(&self.rs, &mut zs);
        self.zs = zs;
        self.scatter(out);
    }
}
