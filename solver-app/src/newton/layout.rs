//! The unknowns of Newton's method: the cells of every deformable body
//! (global numbering, as the segregated system's) followed by the
//! boundary faces whose value is an unknown of its own (traction,
//! pressure and contact faces, `SolidMomentum::is_state_patch`). Each
//! node carries three components, interleaved: entry `3 node + c`.
use crate::model::Body;

/// Node numbering of the state.
#[derive(Debug, Clone, Default)]
pub struct StateLayout {
    /// Cells of all deformable bodies.
    pub n_cells: usize,
    /// Cells and state faces.
    pub n_nodes: usize,
    /// Per body, per boundary face: its node, or `u32::MAX` when the face
    /// is not an unknown (and for rigid bodies: empty).
    face_node: Vec<Vec<u32>>,
    /// (body, boundary face) of every face node, in node order from `n_cells`.
    pub face_of_node: Vec<(u32, u32)>,
    /// Directions not solved (2-D, axisymmetric): their components are
    /// held at zero.
    pub unsolved: [bool; 3],
}

impl StateLayout {
    /// The layout of the bodies' current conditions.
    pub fn new(bodies: &[Body], unsolved: [bool; 3]) -> Self {
        let n_cells = bodies
            .iter()
            .filter(|b| !b.rigid)
            .map(|b| b.offset + b.mesh.n_cells)
            .max()
            .unwrap_or(0);
        let mut layout = StateLayout {
            n_cells,
            n_nodes: n_cells,
            face_node: Vec::with_capacity(bodies.len()),
            face_of_node: Vec::new(),
            unsolved,
        };
        for (bi, b) in bodies.iter().enumerate() {
            if b.rigid {
                layout.face_node.push(Vec::new());
                continue;
            }
            let ni = b.mesh.n_internal_faces();
            let mut nodes = vec![u32::MAX; b.mesh.n_faces() - ni];
            for (pi, p) in b.mesh.patches.iter().enumerate() {
                if !b.momentum.is_state_patch(pi) {
                    continue;
                }
                for f in p.faces() {
                    nodes[f - ni] = layout.n_nodes as u32;
                    layout.face_of_node.push((bi as u32, (f - ni) as u32));
                    layout.n_nodes += 1;
                }
            }
            layout.face_node.push(nodes);
        }
        layout
    }

    /// Number of unknowns (three per node).
    pub fn len(&self) -> usize {
        3 * self.n_nodes
    }

    /// Number of solved unknowns (the solved components of every node).
    pub fn solved_len(&self) -> usize {
        self.unsolved.iter().filter(|u| !**u).count() * self.n_nodes
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.n_nodes == 0
    }

    /// Node of boundary face `b` of body `body`, if it is an unknown.
    #[inline]
    pub fn face_node(&self, body: usize, b: usize) -> Option<usize> {
        match self.face_node.get(body).and_then(|v| v.get(b)) {
            Some(&n) if n != u32::MAX => Some(n as usize),
            _ => None,
        }
    }

    /// The boundary faces of `body` that are unknowns, with their nodes.
    pub fn faces_of(&self, body: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.face_node
            .get(body)
            .into_iter()
            .flatten()
            .enumerate()
            .filter(|(_, &n)| n != u32::MAX)
            .map(|(b, &n)| (b, n as usize))
    }
}
