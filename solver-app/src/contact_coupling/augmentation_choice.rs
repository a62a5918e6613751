//! Whether a contact whose case does not give `augmentation` gets the
//! augmented Lagrangian (Uzawa) updates of its normal pressure.
//!
//! The penalty's penetration is a compliance in series with the bodies.
//! Where two flat faces meet, that compliance is all the penalty changes,
//! and it is an error: a block 4 cells thick (8 × 8 × 4, E = 1000,
//! ν = 0.3) pressed by 2 % onto a rigid plane, its top free to slide,
//! carries 16.87 against E ε A = 20 (−15.7 %) with the thesis's penalty,
//! 20.00 augmented; two stacked blocks with non-matching meshes −8.4 %
//! plain, −0.005 % augmented, the pressure uniform either way
//! (docs/defaults.md, "Augmentation where flat faces meet").
//!
//! Elsewhere the penalty stays plain: on curved (Hertzian) contacts and on
//! faceted or deformable masters the exact-constraint limit of the
//! discretisation oscillates at the edge of the contact zone, and the
//! penalty's softness is the better answer on the validation meshes
//! ([`super::penalty_scale`]; the whole suite with augmentation forced on
//! failed 25 tests).
use super::penalty_scale::{face_normal_of, is_flat, PARALLEL};
use crate::case::Augmentation;
use crate::model::Body;

/// The updates flat faces get: to a penalty share of 10⁻³
/// of the largest pressure as well as the default penetration, so that a
/// small compression, whose penetration is small against the cells but
/// not against the compression, reaches its elastic answer too.
pub const FLAT_FACES: Augmentation = Augmentation {
    penetration: 1e-3,
    pressure: Some(1e-3),
    max_updates: 20,
};

/// Why a contact has augmentation or not.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AugmentationChoice {
    /// `augmentation` in the case: `Some` when on, `None` for `false`.
    Given(Option<Augmentation>),
    /// Not given: a deformable body's flat face against a flat face:
    /// [`FLAT_FACES`].
    FlatFaces,
    /// Not given: the plain penalty (the thesis's).
    Default,
}

impl AugmentationChoice {
    /// The choice for the pair (`master`, `slave`), each `(body, patch)`;
    /// `given` from the case (`None`: not given).
    pub fn choose(
        given: Option<Option<Augmentation>>,
        master: (&Body, usize),
        slave: (&Body, usize),
    ) -> Self {
        match given {
            Some(a) => AugmentationChoice::Given(a),
            None if flat_faces(master, slave) => AugmentationChoice::FlatFaces,
            None => AugmentationChoice::Default,
        }
    }

    /// The updates the pair runs (`None`: plain penalty).
    pub fn value(self) -> Option<Augmentation> {
        match self {
            AugmentationChoice::Given(a) => a,
            AugmentationChoice::FlatFaces => Some(FLAT_FACES),
            AugmentationChoice::Default => None,
        }
    }

    /// The reason, for the log and `fvc check`.
    pub fn reason(self) -> &'static str {
        match self {
            AugmentationChoice::Given(_) => "given",
            AugmentationChoice::FlatFaces => {
                "not given; two flat faces, where the penalty's penetration would be the \
                 error"
            }
            AugmentationChoice::Default => "not given; the plain penalty",
        }
    }
}

/// Whether `slave` is a deformable body's flat patch facing the flat patch
/// `master` (their normals opposite), of a rigid or a deformable body.
fn flat_faces(master: (&Body, usize), slave: (&Body, usize)) -> bool {
    let ((mb, mp), (sb, sp)) = (master, slave);
    if sb.rigid || !is_flat(mb, mp) || !is_flat(sb, sp) {
        return false;
    }
    match (face_normal_of(mb, mp), face_normal_of(sb, sp)) {
        (Some(n), Some(ns)) => n.dot(&ns) <= -PARALLEL,
        _ => false,
    }
}
