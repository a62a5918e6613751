//! The contact block of Newton's Jacobian: the derivative of the contact
//! force on every deformable contact face with respect to the surface
//! points of both sides, by coloured finite differences of the contact
//! algorithm, chained with the cell-to-point weights (eqs. 3.31–3.32) to
//! the cells and face values of the state.
//!
//! The penalty springs of the implicit coupling (eqs. 4.52–4.72) join face
//! centres along the master normal. A segment-to-segment traction depends
//! also on how each clipped segment's gap tilts with the surface points,
//! terms of the order of the penalty that those springs miss; at a stiff
//! penalty they outweigh the cells' stiffness at the edge of the contact,
//! and GMRES stalled with a preconditioner that lacked them (the sphere on
//! a block at `penalty_scale = 100`, docs/defaults.md). No library
//! differentiates the project's contact algorithms: written here.
//!
//! The columns are the deformable sides' surface points of the faces in
//! candidate pairs, one per solved component. A plane problem's points
//! move with the state in groups (the points of an extruded or wedge mesh
//! at the same place in the plane): a column moves its group together,
//! since a point moved alone tilts its faces out of the plane, and the
//! clipping of faces whose edges coincide in the extrusion direction is
//! not differentiable there (the concentric cylinders at penalty scale
//! 1000: 164 Newton iterations with points moved one by one, against 8
//! with the springs). Two columns share a colour when
//! no face's force depends on both: a point moves the faces around it, the
//! faces sharing a point with those (the point normals), and the faces of
//! the other side paired with any of them. One evaluation of the contact
//! algorithm per colour and component gives every column of the colour.
use super::{ContactInterface, ContactSet, ContactSide};
use crate::model::Body;
use crate::newton::layout::StateLayout;
use contact_force::ContactTractions;
use fv_discretise::PatchCondition;
use fv_mesh::{Tensor, Vector};

/// The finite-difference step: this fraction of the mean face size of
/// the side the point is on.
const RELATIVE_STEP: f64 = 1e-7;

/// Workspaces of [`ContactSet::traction_jacobian`], kept across calls.
#[derive(Default)]
pub struct TractionJacobianWork {
    /// Columns: (side 0 = master / 1 = slave, first local point), and
    /// the points each moves (CSR).
    columns: Vec<(u8, u32)>,
    members_offsets: Vec<u32>,
    members: Vec<u32>,
    /// Per column, the faces its point moves: (side, face), CSR.
    affected_offsets: Vec<u32>,
    affected: Vec<(u8, u32)>,
    /// Colour of every column, and the columns by colour (CSR).
    colour: Vec<u32>,
    by_colour_offsets: Vec<u32>,
    by_colour: Vec<u32>,
    /// The colours claimed by each face (side-major: master faces first).
    claimed: Vec<Vec<u32>>,
    /// Forces t |Γ| of every face at the base point and perturbed.
    base: [Vec<Vector>; 2],
    probe: [Vec<Vector>; 2],
    /// Face areas at the base point.
    fixed: [Vec<f64>; 2],
    /// Tractions of the perturbed evaluations.
    tractions: ContactTractions,
    /// Base positions of the surface points of both sides.
    positions: [Vec<Vector>; 2],
    /// The derivative of each affected face's force by its column's
    /// point, per column (in `affected` order).
    derivative: Vec<Tensor>,
    /// Scratch: marks and lists.
    mark: Vec<bool>,
    list: Vec<(u8, u32)>,
    /// Scratch: (in-plane key, point) of a plane problem's points.
    keys: Vec<(i64, i64, u32)>,
    /// Each face's partners in candidate pairs, per side (CSR).
    partner_offsets: [Vec<u32>; 2],
    partners: [Vec<u32>; 2],
    /// Scratch: fill positions.
    next: Vec<u32>,
}

fn side_of(ci: &ContactInterface, s: u8) -> &ContactSide {
    if s == 0 {
        &ci.master
    } else {
        &ci.slave
    }
}

fn side_of_mut(ci: &mut ContactInterface, s: u8) -> &mut ContactSide {
    if s == 0 {
        &mut ci.master
    } else {
        &mut ci.slave
    }
}

/// The contact force t |Γ| of every face of a side: over the moved
/// surface's area between two deformable bodies under the updated
/// Lagrangian form (as the face balance takes it, `area_ratio`), over
/// `fixed` otherwise.
/// [`forces`] of both sides (master, slave) from `tractions`.
fn side_forces(
    tractions: &ContactTractions,
    ci: &ContactInterface,
    moved: [bool; 2],
    fixed: &[Vec<f64>; 2],
    out: &mut [Vec<Vector>; 2],
) {
    let contact = [&tractions.master, &tractions.slave];
    for (s, out) in out.iter_mut().enumerate() {
        forces(contact[s], side_of(ci, s as u8), moved[s], &fixed[s], out);
    }
}

fn forces(
    contact: &contact_force::SurfaceContact,
    side: &ContactSide,
    moved: bool,
    fixed: &[f64],
    out: &mut Vec<Vector>,
) {
    out.clear();
    out.extend((0..side.surface.n_faces()).map(|i| {
        let area = if moved {
            side.surface.face_mag[i]
        } else {
            fixed[i]
        };
        contact.traction(i) * area
    }));
}

impl ContactSet {
    /// Whether interface `k` takes its block from
    /// [`ContactSet::traction_jacobian`]: a contact whose faces are at the
    /// interpolated surface (`face_position = "interpolated"`, the default;
    /// the boundary-value faces' dependence on their own values is left to
    /// the springs).
    pub fn linearises_tractions(&self, k: usize) -> bool {
        self.interfaces.get(k).is_some_and(|ci| !ci.face_shifts)
    }

    /// −∂(t |Γ|)/∂x of the contact faces of interface `k` at the state of
    /// the last evaluation, as (row node, column node, block) entries
    /// appended to `out` (several entries may share a position; they add).
    /// Leaves the contact tractions as that evaluation computed them.
    pub fn traction_jacobian(
        &mut self,
        k: usize,
        bodies: &[Body],
        layout: &StateLayout,
        work: &mut TractionJacobianWork,
        out: &mut Vec<(u32, u32, Tensor)>,
    ) -> Result<(), String> {
        let c2p = &self.cell_to_point;
        let ci = &mut self.interfaces[k];
        let rigid = [bodies[ci.master.body].rigid, bodies[ci.slave.body].rigid];
        let moved: [bool; 2] = std::array::from_fn(|s| {
            let b = &bodies[side_of(ci, s as u8).body];
            ci.deformable_pair && !b.rigid && b.momentum.law.is_updated_lagrangian()
        });
        colour_columns(ci, rigid, layout.unsolved, work);
        if work.columns.is_empty() {
            return Ok(());
        }
        // base forces; a face not moved with the surface keeps its area
        for s in 0..2 {
            work.fixed[s].clone_from(&side_of(ci, s as u8).surface.face_mag);
        }
        let fixed = std::mem::take(&mut work.fixed);
        side_forces(&ci.tractions, ci, moved, &fixed, &mut work.base);
        for (s, positions) in work.positions.iter_mut().enumerate() {
            positions.clone_from(&side_of(ci, s as u8).current);
        }
        work.derivative.clear();
        work.derivative.resize(work.affected.len(), Tensor::zeros());
        let step: [f64; 2] = std::array::from_fn(|s| {
            let side = side_of(ci, s as u8);
            let n = side.surface.n_faces().max(1) as f64;
            RELATIVE_STEP
                * (side.surface.face_mag.iter().sum::<f64>() / n)
                    .sqrt()
                    .max(1e-300)
        });
        let n_colours = work.by_colour_offsets.len().saturating_sub(1);
        for colour in 0..n_colours {
            let cols = work.by_colour_offsets[colour] as usize
                ..work.by_colour_offsets[colour + 1] as usize;
            for d in (0..3).filter(|&d| !layout.unsolved[d]) {
                // perturb the colour's points
                for &c in &work.by_colour[cols.clone()] {
                    let c = c as usize;
                    let s = work.columns[c].0;
                    let side = side_of_mut(ci, s);
                    let m = work.members_offsets[c] as usize..work.members_offsets[c + 1] as usize;
                    for &p in &work.members[m] {
                        side.current[p as usize][d] += step[s as usize];
                    }
                }
                for s in 0..2u8 {
                    let side = side_of_mut(ci, s);
                    side.surface.update_points(&side.current);
                }
                ci.apply_face_shifts(bodies);
                ci.algorithm.freeze_friction_shares(true);
                ci.algorithm
                    .compute(
                        &ci.master.surface,
                        &ci.slave.surface,
                        &ci.pairs,
                        &ci.law,
                        &mut work.tractions,
                    )
                    .map_err(|e| format!("contact {}: {e}", ci.slave_name))?;
                side_forces(&work.tractions, ci, moved, &fixed, &mut work.probe);
                for &c in &work.by_colour[cols.clone()] {
                    let c = c as usize;
                    let s = work.columns[c].0;
                    let h = step[s as usize];
                    for a in
                        work.affected_offsets[c] as usize..work.affected_offsets[c + 1] as usize
                    {
                        let (fs, f) = work.affected[a];
                        let (fs, f) = (fs as usize, f as usize);
                        let df = (work.probe[fs][f] - work.base[fs][f]) / h;
                        for r in 0..3 {
                            work.derivative[a][(r, d)] = df[r];
                        }
                    }
                    let side = side_of_mut(ci, s);
                    let m = work.members_offsets[c] as usize..work.members_offsets[c + 1] as usize;
                    for &p in &work.members[m] {
                        side.current[p as usize] = work.positions[s as usize][p as usize];
                    }
                }
            }
        }
        work.fixed = fixed;
        // back to the base point: surfaces, shifts, tractions
        for s in 0..2u8 {
            let side = side_of_mut(ci, s);
            side.surface.update_points(&side.current);
        }
        ci.apply_face_shifts(bodies);
        ci.compute_tractions()?;
        // chain: the point's displacement from the state (cell-to-point
        // weights; a group's points share them); a face's force on its
        // face node's row
        for (c, &(s, p)) in work.columns.iter().enumerate() {
            let side = side_of(ci, s);
            let body = &bodies[side.body];
            let Some(op) = c2p[side.body].as_ref() else {
                continue;
            };
            let global = side.surface.point_ids[p as usize] as usize;
            let (w0, w1) = (op.offsets[global] as usize, op.offsets[global + 1] as usize);
            for a in work.affected_offsets[c] as usize..work.affected_offsets[c + 1] as usize {
                let (fs, f) = work.affected[a];
                let fside = side_of(ci, fs);
                let fbody = &bodies[fside.body];
                if fbody.rigid {
                    continue;
                }
                let start = fbody.mesh.patches[fside.patch].start - fbody.mesh.n_internal_faces();
                let Some(row) = layout.face_node(fside.body, start + f as usize) else {
                    continue;
                };
                let dd = work.derivative[a];
                if dd.iter().all(|v| *v == 0.0) {
                    continue;
                }
                for (&src, &w) in op.sources[w0..w1].iter().zip(&op.weights[w0..w1]) {
                    let col =
                        state_node_of_source(body, side.body, layout, op.n_cells, src as usize);
                    if let Some(col) = col {
                        out.push((row as u32, col as u32, -dd * w));
                    }
                }
            }
        }
        Ok(())
    }
}

/// The state node a cell-to-point source's value follows: a cell's own
/// node; a boundary face's node where its value is an unknown, its owner
/// cell's on an empty or wedge patch (whose face values are the cell's,
/// rotated onto the wedge plane); none where the value is prescribed.
fn state_node_of_source(
    body: &Body,
    bi: usize,
    layout: &StateLayout,
    n_cells: usize,
    src: usize,
) -> Option<usize> {
    if src < n_cells {
        return Some(body.offset + src);
    }
    let b = src - n_cells;
    if let Some(node) = layout.face_node(bi, b) {
        return Some(node);
    }
    let f = body.mesh.n_internal_faces() + b;
    let patch = body
        .mesh
        .patches
        .iter()
        .position(|p| p.faces().contains(&f))?;
    match body.momentum.conditions[patch] {
        PatchCondition::Empty | PatchCondition::Wedge(_) => {
            Some(body.offset + body.mesh.owner[f] as usize)
        }
        _ => None,
    }
}

/// The columns of interface `ci` (the deformable sides' points of faces in
/// candidate pairs, grouped by their place in the plane when a component
/// is `unsolved`), the faces each moves, and a colouring in which no two
/// columns of a colour move the same face.
fn colour_columns(
    ci: &ContactInterface,
    rigid: [bool; 2],
    unsolved: [bool; 3],
    work: &mut TractionJacobianWork,
) {
    let nf = [ci.master.surface.n_faces(), ci.slave.surface.n_faces()];
    // faces in candidate pairs, and each face's partners
    // (CSR: counts, prefix sums, fill)
    for (offsets, n) in work.partner_offsets.iter_mut().zip(nf) {
        offsets.clear();
        offsets.resize(n + 1, 0);
    }
    let valid_pairs = || {
        (0..ci.pairs.n_master().min(nf[0])).flat_map(move |m| {
            ci.pairs
                .slaves_of(m)
                .iter()
                .filter(move |&&s| (s as usize) < nf[1])
                .map(move |&s| (m, s as usize))
        })
    };
    for (m, s) in valid_pairs() {
        work.partner_offsets[0][m + 1] += 1;
        work.partner_offsets[1][s + 1] += 1;
    }
    for (side, n) in nf.into_iter().enumerate() {
        for f in 0..n {
            work.partner_offsets[side][f + 1] += work.partner_offsets[side][f];
        }
        work.partners[side].clear();
        work.partners[side].resize(work.partner_offsets[side][n] as usize, 0);
        work.next.clone_from(&work.partner_offsets[side]);
        for (m, s) in valid_pairs() {
            let (f, o) = if side == 0 { (m, s) } else { (s, m) };
            work.partners[side][work.next[f] as usize] = o as u32;
            work.next[f] += 1;
        }
    }
    work.columns.clear();
    work.members_offsets.clear();
    work.members.clear();
    work.members_offsets.push(0);
    work.affected_offsets.clear();
    work.affected.clear();
    work.affected_offsets.push(0);
    // the in-plane components of a plane problem
    let plane: Option<[usize; 2]> = match unsolved.iter().position(|&u| u) {
        Some(z) if unsolved.iter().filter(|&&u| u).count() == 1 => Some([(z + 1) % 3, (z + 2) % 3]),
        _ => None,
    };
    for s in 0..2u8 {
        if rigid[s as usize] {
            continue;
        }
        let side = side_of(ci, s);
        let surf = &side.surface;
        // the candidate points, in groups that move together
        work.keys.clear();
        let n = surf.n_faces().max(1) as f64;
        let tol = 1e-6 * (surf.face_mag.iter().sum::<f64>() / n).sqrt().max(1e-300);
        for p in 0..surf.n_points() {
            if !surf.faces_of_point(p).iter().any(|&f| {
                let (side, f) = (s as usize, f as usize);
                work.partner_offsets[side][f + 1] > work.partner_offsets[side][f]
            }) {
                continue;
            }
            let key = match plane {
                Some([a, b]) => {
                    let x = side.current[p];
                    ((x[a] / tol).round() as i64, (x[b] / tol).round() as i64)
                }
                None => (p as i64, 0),
            };
            work.keys.push((key.0, key.1, p as u32));
        }
        work.keys.sort_unstable();
        let mut g0 = 0;
        while g0 < work.keys.len() {
            let mut g1 = g0 + 1;
            while g1 < work.keys.len()
                && (work.keys[g1].0, work.keys[g1].1) == (work.keys[g0].0, work.keys[g0].1)
            {
                g1 += 1;
            }
            // faces sharing a point with the points' faces (point
            // normals), and their partners on the other side
            work.list.clear();
            for &(_, _, p) in &work.keys[g0..g1] {
                work.members.push(p);
                for &f in surf.faces_of_point(p as usize) {
                    for &q in surf.face(f as usize) {
                        for &g in surf.faces_of_point(q as usize) {
                            work.list.push((s, g));
                        }
                    }
                }
            }
            work.members_offsets.push(work.members.len() as u32);
            let own = work.list.len();
            for i in 0..own {
                let (_, g) = work.list[i];
                let (side, g) = (s as usize, g as usize);
                let range = work.partner_offsets[side][g] as usize
                    ..work.partner_offsets[side][g + 1] as usize;
                for &o in &work.partners[side][range] {
                    work.list.push((1 - s, o));
                }
            }
            work.list.sort_unstable();
            work.list.dedup();
            work.columns.push((s, work.keys[g0].2));
            work.affected.extend_from_slice(&work.list);
            work.affected_offsets.push(work.affected.len() as u32);
            g0 = g1;
        }
    }
    // greedy colouring: a column takes the first colour none of its faces
    // has given to another column
    work.claimed.iter_mut().for_each(|c| c.clear());
    work.claimed.resize(nf[0] + nf[1], Vec::new());
    work.colour.clear();
    let mut n_colours = 0u32;
    for c in 0..work.columns.len() {
        let faces = &work.affected
            [work.affected_offsets[c] as usize..work.affected_offsets[c + 1] as usize];
        work.mark.clear();
        work.mark.resize(n_colours as usize + 1, false);
        for &(s, f) in faces {
            for &k in &work.claimed[s as usize * nf[0] + f as usize] {
                work.mark[k as usize] = true;
            }
        }
        let k = work
            .mark
            .iter()
            .position(|m| !m)
            .unwrap_or(n_colours as usize) as u32;
        n_colours = n_colours.max(k + 1);
        for &(s, f) in faces {
            work.claimed[s as usize * nf[0] + f as usize].push(k);
        }
        work.colour.push(k);
    }
    // columns by colour
    work.by_colour_offsets.clear();
    work.by_colour_offsets.resize(n_colours as usize + 1, 0);
    for &k in &work.colour {
        work.by_colour_offsets[k as usize + 1] += 1;
    }
    for k in 0..n_colours as usize {
        work.by_colour_offsets[k + 1] += work.by_colour_offsets[k];
    }
    work.next.clone_from(&work.by_colour_offsets);
    let next = &mut work.next;
    work.by_colour.clear();
    work.by_colour.resize(work.columns.len(), 0);
    for (c, &k) in work.colour.iter().enumerate() {
        work.by_colour[next[k as usize] as usize] = c as u32;
        next[k as usize] += 1;
    }
}
