//! The contact-force seam: one trait, one file per algorithm, selection by
//! name (`contact_algorithm = "..."` in the case file).
use crate::contact_tractions::{ContactStats, ContactTractions};
use crate::coulomb_friction::FrictionState;
use crate::face_pairs::{check_pairs, FacePairs};
use crate::penalty::ContactLaw;
use crate::{ContactError, Pointwise, SegmentToSegment};
use fv_mesh::Surface;
use std::fmt;
use std::str::FromStr;

/// A contact-force algorithm (thesis §4.3, §4.4): from the current master
/// and slave surfaces and their candidate pairs, the penalty tractions on
/// both surfaces (explicit Neumann–Neumann coupling, §4.1.3).
///
/// Called once per outer iteration after the surfaces were moved and the
/// pairs detected. An algorithm keeps the friction history of one contact
/// pair: the surface positions at the start of the increment (slip is
/// measured from them) and, with [`crate::SlipHistory::Accumulated`], the
/// committed elastic slip.
pub trait ContactAlgorithm: Send {
    /// Computes tractions and contact quantities into `out` (resized to the
    /// surfaces) and returns the summary. Fails only on inconsistent input
    /// (pair indices out of range, invalid law); degenerate geometry is
    /// skipped. On the first call (or when a surface changed its number of
    /// points) the current positions become the slip reference.
    fn compute(
        &mut self,
        master: &Surface,
        slave: &Surface,
        pairs: &dyn FacePairs,
        law: &ContactLaw,
        out: &mut ContactTractions,
    ) -> Result<ContactStats, ContactError>;

    /// End of a converged increment: the given (converged) positions become
    /// the slip reference of the next increment and the elastic slip of the
    /// last [`ContactAlgorithm::compute`] is committed.
    fn commit_increment(&mut self, master: &Surface, slave: &Surface);

    /// Forgets the friction history (new problem).
    fn reset(&mut self);

    /// Restart: puts the committed friction history under `prefix`
    /// (`fvc run --restart`).
    fn save_state(&self, prefix: &str, out: &mut fv_mesh::StateArrays);

    /// Restart: takes back the history of [`Self::save_state`].
    fn restore_state(&mut self, prefix: &str, state: &fv_mesh::StateArrays) -> Result<(), String>;

    /// Which algorithm this is.
    fn kind(&self) -> ContactAlgorithmKind;

    /// Symmetry planes of the master's body, for the point normals of a
    /// smoothed master (thesis Fig. 4.40); ignored without smoothing.
    fn set_symmetry_planes(&mut self, _planes: &[contact_smooth::SymmetryPlane]) {}

    /// Per-face translations of the master and the slave faces for the
    /// next calls of [`ContactAlgorithm::compute`] ([`crate::FaceShifts`]):
    /// the gap between two faces is measured with them moved by these.
    /// Empty slices: none (the surfaces as given).
    fn set_face_shifts(&mut self, master: &[fv_mesh::Vector], slave: &[fv_mesh::Vector]);

    /// While `frozen`, the friction of [`ContactAlgorithm::compute`] counts
    /// the slip of a face entering contact with the share of the last call
    /// that was not frozen (Newton's Jacobian products about a base point;
    /// see `IncrementState::share`).
    fn freeze_friction_shares(&mut self, _frozen: bool) {}
}

/// The contact algorithms, by case-file name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ContactAlgorithmKind {
    /// [`SegmentToSegment`] (§4.4), `"segment-to-segment"`.
    #[default]
    SegmentToSegment,
    /// [`Pointwise`] (§4.3), `"pointwise"`.
    Pointwise,
    /// [`Pointwise::nagata`]: slave points against the Nagata-smoothed
    /// master (§4.6.1), `"pointwise-nagata"`.
    PointwiseNagata,
    /// [`SegmentToSegment::nagata`]: the segment gap integrated against the
    /// Nagata-smoothed master (beyond the thesis), `"segment-to-segment-nagata"`.
    SegmentToSegmentNagata,
}

impl ContactAlgorithmKind {
    /// Every available algorithm, in the order of [`ContactAlgorithmKind::valid_names`].
    pub const ALL: [ContactAlgorithmKind; 4] = [
        ContactAlgorithmKind::SegmentToSegment,
        ContactAlgorithmKind::Pointwise,
        ContactAlgorithmKind::PointwiseNagata,
        ContactAlgorithmKind::SegmentToSegmentNagata,
    ];

    /// The case-file name.
    pub fn name(self) -> &'static str {
        match self {
            ContactAlgorithmKind::SegmentToSegment => "segment-to-segment",
            ContactAlgorithmKind::Pointwise => "pointwise",
            ContactAlgorithmKind::PointwiseNagata => "pointwise-nagata",
            ContactAlgorithmKind::SegmentToSegmentNagata => "segment-to-segment-nagata",
        }
    }

    /// Whether the master surface is Nagata-smoothed.
    pub fn smoothed(self) -> bool {
        matches!(
            self,
            ContactAlgorithmKind::PointwiseNagata | ContactAlgorithmKind::SegmentToSegmentNagata
        )
    }

    /// The valid names, comma separated.
    pub fn valid_names() -> String {
        Self::ALL.map(|k| k.name()).join(", ")
    }

    /// Parses a case-file name. An unknown name is rejected with the list
    /// of valid ones.
    pub fn from_name(name: &str) -> Result<Self, ContactError> {
        let name = name.trim();
        if let Some(k) = Self::ALL.into_iter().find(|k| k.name() == name) {
            return Ok(k);
        }
        Err(ContactError::UnknownAlgorithm {
            name: name.to_string(),
            valid: Self::valid_names(),
        })
    }

    /// A new algorithm of this kind, with no history.
    pub fn build(self) -> Box<dyn ContactAlgorithm> {
        match self {
            ContactAlgorithmKind::SegmentToSegment => Box::new(SegmentToSegment::new()),
            ContactAlgorithmKind::Pointwise => Box::new(Pointwise::new()),
            ContactAlgorithmKind::PointwiseNagata => Box::new(Pointwise::nagata()),
            ContactAlgorithmKind::SegmentToSegmentNagata => Box::new(SegmentToSegment::nagata()),
        }
    }
}

impl fmt::Display for ContactAlgorithmKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ContactAlgorithmKind {
    type Err = ContactError;
    fn from_str(s: &str) -> Result<Self, ContactError> {
        Self::from_name(s)
    }
}

/// Validates the law and the pairs against the surfaces.
pub(crate) fn check_inputs(
    master: &Surface,
    slave: &Surface,
    pairs: &dyn FacePairs,
    law: &ContactLaw,
) -> Result<(), ContactError> {
    law.validate()?;
    check_pairs(pairs, master.n_faces(), slave.n_faces())
}

/// The summary fields that follow from the per-face output (forces,
/// maximum pressure, active and stick/slip counts); the algorithm fills in
/// contact area, penetration and overlapping pairs.
pub(crate) fn finish_stats(
    master: &Surface,
    slave: &Surface,
    out: &ContactTractions,
) -> ContactStats {
    let mut st = ContactStats::default();
    for m in 0..master.n_faces() {
        let a = master.face_mag[m];
        st.normal_force += out.master.pressure[m] * a;
        st.tangential_force += out.master.tangential_traction[m] * a;
        st.master_force += out.master.traction(m) * a;
        st.max_pressure = st.max_pressure.max(out.master.pressure[m]);
        if out.master.contact_fraction[m] > 0.0 {
            st.n_active += 1;
        }
    }
    for s in 0..slave.n_faces() {
        st.slave_force += out.slave.traction(s) * slave.face_mag[s];
        st.max_pressure = st.max_pressure.max(out.slave.pressure[s]);
    }
    for state in out
        .master
        .friction_state
        .iter()
        .chain(&out.slave.friction_state)
    {
        match state {
            FrictionState::Stick => st.n_stick += 1,
            FrictionState::Slip => st.n_slip += 1,
            FrictionState::Inactive => {}
        }
    }
    st
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown() {
        for k in ContactAlgorithmKind::ALL {
            assert_eq!(ContactAlgorithmKind::from_name(k.name()).unwrap(), k);
            assert_eq!(k.to_string().parse::<ContactAlgorithmKind>().unwrap(), k);
            assert_eq!(k.build().kind(), k);
        }
        let msg = ContactAlgorithmKind::from_name("mortar")
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("mortar")
                && msg.contains(
                    "segment-to-segment, pointwise, pointwise-nagata, segment-to-segment-nagata"
                ),
            "{msg}"
        );
        // the Nagata variants are available now
        for (name, smoothed) in [
            ("pointwise-nagata", true),
            ("segment-to-segment-nagata", true),
            ("pointwise", false),
        ] {
            let k = ContactAlgorithmKind::from_name(name).unwrap();
            assert_eq!(k.smoothed(), smoothed);
            assert_eq!(k.build().kind().name(), name);
        }
    }
}
