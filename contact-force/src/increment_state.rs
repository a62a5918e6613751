//! Friction history of one contact pair: the surface positions at the start
//! of the increment (for the incremental slip, eq. 2.36–2.37) and the
//! committed elastic slip ([`crate::SlipHistory::Accumulated`]).
use fv_mesh::{Real, Surface, Vector};

/// Per-pair state kept by the algorithms between calls.
#[derive(Debug, Clone, Default)]
pub(crate) struct IncrementState {
    reference_master: Vec<Vector>,
    reference_slave: Vec<Vector>,
    /// Point displacement increments of the master surface (current − reference).
    pub du_master: Vec<Vector>,
    /// Point displacement increments of the slave surface.
    pub du_slave: Vec<Vector>,
    /// Committed elastic slip per master face.
    pub elastic_master: Vec<Vector>,
    /// Committed elastic slip per slave face.
    pub elastic_slave: Vec<Vector>,
    /// Elastic slip of the last call per master face (committed at increment end).
    pub pending_master: Vec<Vector>,
    /// Elastic slip of the last call per slave face.
    pub pending_slave: Vec<Vector>,
}

fn same_size_or_reset(v: &mut Vec<Vector>, n: usize) {
    if v.len() != n {
        v.clear();
        v.resize(n, Vector::zeros());
    }
}

impl IncrementState {
    /// Takes the current positions as reference where there is none (first
    /// call, or the surfaces changed size) and computes the point increments.
    pub(crate) fn prepare(&mut self, master: &Surface, slave: &Surface) {
        if self.reference_master.len() != master.n_points() {
            self.reference_master.clone_from(&master.points);
        }
        if self.reference_slave.len() != slave.n_points() {
            self.reference_slave.clone_from(&slave.points);
        }
        self.du_master.clear();
        self.du_master.extend(
            master
                .points
                .iter()
                .zip(&self.reference_master)
                .map(|(x, r)| x - r),
        );
        self.du_slave.clear();
        self.du_slave.extend(
            slave
                .points
                .iter()
                .zip(&self.reference_slave)
                .map(|(x, r)| x - r),
        );
        same_size_or_reset(&mut self.elastic_master, master.n_faces());
        same_size_or_reset(&mut self.elastic_slave, slave.n_faces());
        same_size_or_reset(&mut self.pending_master, master.n_faces());
        same_size_or_reset(&mut self.pending_slave, slave.n_faces());
    }

    /// End of increment: the current positions become the reference and the
    /// elastic slip of the last call is committed.
    pub(crate) fn commit(&mut self, master: &Surface, slave: &Surface) {
        self.reference_master.clone_from(&master.points);
        self.reference_slave.clone_from(&slave.points);
        if self.pending_master.len() == master.n_faces() {
            self.elastic_master.clone_from(&self.pending_master);
        } else {
            self.elastic_master.clear();
        }
        if self.pending_slave.len() == slave.n_faces() {
            self.elastic_slave.clone_from(&self.pending_slave);
        } else {
            self.elastic_slave.clear();
        }
    }

    /// Forgets everything.
    pub(crate) fn reset(&mut self) {
        *self = IncrementState::default();
    }
}

/// Mean of point values over the points of face `f` (the face-centre value
/// of §4.4: "value at the central point is calculated by averaging the face
/// points values").
#[inline]
pub(crate) fn face_mean(surface: &Surface, values: &[Vector], f: usize) -> Vector {
    let fp = surface.face(f);
    if fp.is_empty() {
        return Vector::zeros();
    }
    fp.iter()
        .fold(Vector::zeros(), |a, &p| a + values[p as usize])
        / fp.len() as Real
}
