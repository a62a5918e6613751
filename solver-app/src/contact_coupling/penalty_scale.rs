//! The normal penalty scale f_n^scale (thesis eq. 4.4a) of a contact whose
//! case does not give `penalty_scale`.
//!
//! The penalty's penetration softens a contact, but on a faceted or
//! deformable master it also absorbs the surfaces' interpolation error:
//! there a stiffer penalty is less accurate. Measured by Newton–Krylov on
//! the validation meshes (peak pressure against Hertz, RMS of the profile
//! in % of p0; docs/defaults.md, "The penalty a contact gets"):
//!
//! | master | scale 1 | 5 | 10 | 20 |
//! |---|---|---|---|---|
//! | rigid plane, Hertz cylinder coarse | −7.6 / 9.1 | −3.3 / 3.9 | −0.7 / 6.4 | +3.2 / 9.4 |
//! | rigid plane, Hertz cylinder fine | −3.8 / 3.1 | −1.0 / 1.6 | −0.7 / 1.9 | −0.5 / 2.3 |
//! | rigid plane, sphere on a block | −6.3 / 5.5 | −1.6 / 2.6 | −0.9 / 2.6 | −0.7 / 2.9 |
//! | deformable block, sphere on a block | +0.4 / 2.3 | +10.8 / 5.4 | +26.4 / 10.7 | +27.1 / 14.1 |
//! | rigid faceted cylinder indenting a block | +1.8 | +10.6 | | |
//!
//! A flat surface on a rigid plane (the flat punch) is a conforming
//! contact with singular edges, where the penalty regularises too: at 5
//! the flat punch's pressure leaves A20 by 3.9 % (1: within 3 %).
//!
//! So: [`RIGID_PLANE_PENALTY_SCALE`] where a curved surface meets a rigid
//! plane (a Hertzian, non-conforming contact), where only the
//! penetration errs, and the thesis's 1 otherwise.
use crate::model::Body;

/// The scale against a rigid plane: within 3.3 % of Hertz's peak and
/// 4 % RMS on the coarse Hertz cylinder, where 10 and more sharpen the
/// coarse profile beyond the analytical one.
pub const RIGID_PLANE_PENALTY_SCALE: f64 = 5.0;

/// Cosine within which two face normals count as parallel.
pub(super) const PARALLEL: f64 = 1.0 - 1e-9;

/// Why a contact's normal penalty scale is what it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PenaltyScale {
    /// `penalty_scale` in the case.
    Given(f64),
    /// Not given, a curved surface on a rigid plane:
    /// [`RIGID_PLANE_PENALTY_SCALE`].
    RigidPlane,
    /// Not given: the thesis's 1.
    Default,
}

impl PenaltyScale {
    /// The scale of a contact between patch `master.1` of `master.0` and
    /// patch `slave.1` of `slave.0`, `given` from the case. `stiff_ok`:
    /// the solve takes a stiffer penalty in its stride (Newton–Krylov, or
    /// the segregated method's implicit coupling). The segregated method's
    /// explicit coupling keeps the thesis's 1: on the Hertz cylinder
    /// example it converged in 93 outer iterations at 1 and stalled at 5
    /// (1,939 outer iterations before switching to implicit coupling).
    pub fn choose(
        given: Option<f64>,
        master: (&Body, usize),
        slave: (&Body, usize),
        stiff_ok: bool,
    ) -> Self {
        let hertzian =
            || curved_on_rigid_plane(master, slave) || curved_on_rigid_plane(slave, master);
        match given {
            Some(f) => PenaltyScale::Given(f),
            None if stiff_ok && hertzian() => PenaltyScale::RigidPlane,
            None => PenaltyScale::Default,
        }
    }

    /// f_n^scale.
    pub fn value(self) -> f64 {
        match self {
            PenaltyScale::Given(f) => f,
            PenaltyScale::RigidPlane => RIGID_PLANE_PENALTY_SCALE,
            PenaltyScale::Default => 1.0,
        }
    }

    /// The reason, for the log and `fvc check`.
    pub fn reason(self) -> &'static str {
        match self {
            PenaltyScale::Given(_) => "given",
            PenaltyScale::RigidPlane => "not given; a curved surface on a rigid plane",
            PenaltyScale::Default => "not given; the thesis's",
        }
    }
}

/// Whether `plane` is a rigid body's flat patch and `other` is not flat.
fn curved_on_rigid_plane(plane: (&Body, usize), other: (&Body, usize)) -> bool {
    plane.0.rigid && is_flat(plane.0, plane.1) && !is_flat(other.0, other.1)
}

/// Whether patch `patch` of `body` is flat (in its current geometry):
/// every face normal parallel to the first's.
pub(super) fn is_flat(body: &Body, patch: usize) -> bool {
    let Some(p) = body.mesh.patches.get(patch) else {
        return false;
    };
    let mut normals = p
        .faces()
        .filter(|&f| body.geom.face_mag(f) > 0.0)
        .map(|f| body.geom.face_normal(f));
    let Some(first) = normals.next() else {
        return false;
    };
    normals.all(|n| n.dot(&first) >= PARALLEL)
}

/// The unit normal of the patch's first face of nonzero area.
pub(super) fn face_normal_of(body: &Body, patch: usize) -> Option<fv_mesh::Vector> {
    let p = body.mesh.patches.get(patch)?;
    p.faces()
        .find(|&f| body.geom.face_mag(f) > 0.0)
        .map(|f| body.geom.face_normal(f))
}
