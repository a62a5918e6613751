//! The contact algorithm of a contact whose case does not give
//! `algorithm`.
//!
//! The thesis's segment-to-segment algorithm is the default, except for a
//! frictional pair whose slave body flows plastically against a flat
//! master (a platen): there its slave pressure, integrated over the
//! clipped segments, alternates face to face under the plastic flow and
//! the frictional traction μp follows it.
//! Measured (2026-12-01, no tuning keys, docs/solver-notes.md "Upsetting
//! a J2 block"): a J2 billet upset by 30 % in 10 steps between rigid
//! platens with μ = 0.1 failed with segment-to-segment on all four meshes
//! (plane strain and axisymmetric, 20 × 10 and 40 × 20 cells), the
//! pressure alternating 1,294 / 663 / 1,311 / 561 and the edge face
//! carrying 20,516; pointwise contact ran three of them to the end with a
//! smooth friction hill (axisymmetric 3,757 and 3,764 against the slab
//! estimate 3,792). The refined axisymmetric wire drawing stalls Newton
//! the same way (docs/newton-krylov.md). Against a curved master the
//! default stays: the coarse 3-D wire drawing (a faceted die) runs in
//! 36 s with segment-to-segment, while pointwise needed cut-backs in two
//! of its first six increments and took 8–16 s per increment. Frictionless pairs keep
//! the default too: both algorithms converge in a handful of iterations.
use super::penalty_scale::is_flat;
use crate::case::{ContactAlgorithm, ScalarValue};
use crate::model::Body;

/// Why a contact has the algorithm it has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AlgorithmChoice {
    /// `algorithm` in the case.
    Given(ContactAlgorithm),
    /// Not given: a frictional pair with a plastic slave on a flat
    /// master, pointwise.
    FrictionOnPlasticSlave,
    /// Not given: the thesis's segment-to-segment.
    Default,
}

impl AlgorithmChoice {
    /// The choice for a pair with `friction` (μ, constant or a time table),
    /// `master` as `(body, patch)` and slave body `slave`; `given` from the
    /// case (`None`: not given).
    pub fn choose(
        given: Option<ContactAlgorithm>,
        friction: &ScalarValue,
        master: (&Body, usize),
        slave: &Body,
    ) -> Self {
        let frictional = match friction {
            ScalarValue::Constant(mu) => *mu > 0.0,
            ScalarValue::Table(rows) => rows.iter().any(|r| r.1 > 0.0),
        };
        let plastic = !slave.rigid && slave.momentum.law.plastic_strain().is_some();
        match given {
            Some(a) => AlgorithmChoice::Given(a),
            None if frictional && plastic && is_flat(master.0, master.1) => {
                AlgorithmChoice::FrictionOnPlasticSlave
            }
            None => AlgorithmChoice::Default,
        }
    }

    /// The algorithm the pair runs.
    pub fn value(self) -> ContactAlgorithm {
        match self {
            AlgorithmChoice::Given(a) => a,
            AlgorithmChoice::FrictionOnPlasticSlave => ContactAlgorithm::Pointwise,
            AlgorithmChoice::Default => ContactAlgorithm::SegmentToSegment,
        }
    }

    /// The case-file name of [`Self::value`].
    pub fn name(self) -> &'static str {
        self.value().name()
    }

    /// The reason, for the log and `fvc check`.
    pub fn reason(self) -> &'static str {
        match self {
            AlgorithmChoice::Given(_) => "given",
            AlgorithmChoice::FrictionOnPlasticSlave => {
                "not given; friction on a plastic slave against a flat master, where \
                 segment-to-segment pressure alternates face to face and Newton stalls"
            }
            AlgorithmChoice::Default => "not given; the thesis's",
        }
    }
}
