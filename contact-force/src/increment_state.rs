//! Friction history of one contact pair: the surface positions at the start
//! of the increment (for the incremental slip, eq. 2.36–2.37) and the
//! committed elastic slip ([`crate::SlipHistory::Accumulated`]).
use fv_mesh::{Real, Surface, Vector};

/// Per-pair state kept by the algorithms between calls.
#[derive(Debug, Clone, Default)]
pub(crate) struct IncrementState {
    pub(crate) reference_master: Vec<Vector>,
    pub(crate) reference_slave: Vec<Vector>,
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
    /// Smallest gap of every master face at the last call (+∞ or NaN: not
    /// over the other surface), committed into `start_gap_master` at
    /// increment end.
    pub gap_master: Vec<Real>,
    /// Smallest gap of every slave face at the last call.
    pub gap_slave: Vec<Real>,
    /// Smallest gap of every master face at the start of the increment.
    pub start_gap_master: Vec<Real>,
    /// Smallest gap of every slave face at the start of the increment.
    pub start_gap_slave: Vec<Real>,
    /// The start gaps hold values (committed, or recorded at the first
    /// call of the first increment).
    pub(crate) start_known: bool,
    /// The [`contact_share`] of every master and slave face at the last
    /// call that was not frozen ([`IncrementState::freeze_shares`]).
    share_master: Vec<Real>,
    share_slave: Vec<Real>,
    /// Calls reuse the shares of the last call that was not frozen.
    shares_frozen: bool,
}

fn same_size_or_reset(v: &mut Vec<Vector>, n: usize) {
    if v.len() != n {
        v.clear();
        v.resize(n, Vector::zeros());
    }
}

fn same_size_or_unknown(v: &mut Vec<Real>, n: usize) {
    if v.len() != n {
        v.clear();
        v.resize(n, Real::NAN);
    }
}

/// Share of an increment's slip that a face made in contact (beyond the
/// thesis, whose eq. 4.23 counts the whole increment). `start` and `now`
/// are the face's smallest gap (over its points, or its segments' points)
/// at the start of the increment and now. A face wholly open at the start
/// (`start` > 0) that penetrates now (`now` < 0) closed, if its gap changed
/// linearly, at the fraction start/(start − now) of the step: only the
/// rest, −now/(start − now), of its relative tangential motion was slip
/// under pressure. The share goes to 0 as the face only just touches, as
/// its pressure does. Counted whole, the approach of a face entering
/// contact, projected on its tilted tangent plane, reads as slip: loaded in
/// one step, two identical Hertz cylinders sheared each other by 27–30 %
/// of μp0 where the Cattaneo–Mindlin solution has no shear at all. 1 for a
/// face in contact at the start, or not over the other surface then (its
/// start gap is unknown), or not penetrating now (no pressure, no friction).
#[inline]
pub(crate) fn contact_share(start: Real, now: Real) -> Real {
    if !(start > 0.0 && start.is_finite() && now < 0.0) {
        return 1.0;
    }
    (-now / (start - now)).clamp(0.0, 1.0)
}

/// Which surface a face is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    Master,
    Slave,
}

impl IncrementState {
    /// While `frozen`, [`IncrementState::share`] returns the shares of the
    /// last call that was not frozen (Newton's Jacobian products: the
    /// share's steep dependence on the closing gap, 1/start, made the
    /// frictional stick traction jump with the normal motion and Newton
    /// wander; the residual itself keeps the share of its own state).
    pub(crate) fn freeze_shares(&mut self, frozen: bool) {
        self.shares_frozen = frozen;
    }

    /// [`contact_share`] of face `f` of `side` (start gap `start`,
    /// smallest gap `now`), or the recorded one while frozen.
    pub(crate) fn share(&mut self, side: Side, f: usize, start: Real, now: Real) -> Real {
        let store = match side {
            Side::Master => &mut self.share_master,
            Side::Slave => &mut self.share_slave,
        };
        if self.shares_frozen {
            if let Some(&s) = store.get(f) {
                return s;
            }
        }
        let s = contact_share(start, now);
        if !self.shares_frozen {
            if store.len() <= f {
                store.resize(f + 1, 1.0);
            }
            store[f] = s;
        }
        s
    }

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
        same_size_or_unknown(&mut self.gap_master, master.n_faces());
        same_size_or_unknown(&mut self.gap_slave, slave.n_faces());
        same_size_or_unknown(&mut self.start_gap_master, master.n_faces());
        same_size_or_unknown(&mut self.start_gap_slave, slave.n_faces());
    }

    /// The smallest gaps of this call (one per face, +∞ or NaN where a face
    /// is not over the other surface): kept for the next increment's start,
    /// and taken as this increment's start at the first call ever.
    pub(crate) fn record_gaps(&mut self, master: &[Real], slave: &[Real]) {
        self.gap_master.clear();
        self.gap_master.extend_from_slice(master);
        self.gap_slave.clear();
        self.gap_slave.extend_from_slice(slave);
        if !self.start_known {
            self.start_gap_master.clone_from(&self.gap_master);
            self.start_gap_slave.clone_from(&self.gap_slave);
            self.start_known = true;
        }
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
        if self.gap_master.len() == master.n_faces() {
            self.start_gap_master.clone_from(&self.gap_master);
        } else {
            self.start_gap_master.clear();
        }
        if self.gap_slave.len() == slave.n_faces() {
            self.start_gap_slave.clone_from(&self.gap_slave);
        } else {
            self.start_gap_slave.clear();
        }
    }

    /// Forgets everything (the freezing of the shares stays).
    pub(crate) fn reset(&mut self) {
        let frozen = self.shares_frozen;
        *self = IncrementState::default();
        self.shares_frozen = frozen;
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

#[cfg(test)]
mod tests {
    use super::contact_share;

    #[test]
    fn contact_share_counts_the_motion_after_closing() {
        // open by 3, penetrating by 1 at the end: closed at 3/4 of the step
        assert!((contact_share(3.0, -1.0) - 0.25).abs() < 1e-15);
        // in contact at the start, or start unknown: the whole increment
        assert_eq!(contact_share(-1e-3, -2e-3), 1.0);
        assert_eq!(contact_share(0.0, -2e-3), 1.0);
        assert_eq!(contact_share(f64::NAN, -2e-3), 1.0);
        // not over the other surface at the start
        assert_eq!(contact_share(f64::INFINITY, -2e-3), 1.0);
        // not penetrating now
        assert_eq!(contact_share(1.0, 0.5), 1.0);
        assert_eq!(contact_share(1.0, f64::NAN), 1.0);
        // a face that only just closed made almost no slip in contact
        assert!(contact_share(1.0, -1e-9) < 1e-8);
    }
}
