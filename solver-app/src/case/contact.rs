//! `[[contact]]`: one master/slave patch pair each.

use super::keys;
use super::reader::{list, Node, Res};
use super::values::{scalar_value, ScalarValue};
use contact_force::SlipHistory;

/// `contact.algorithm`: the library's algorithms, by their names
/// (`contact_force::ContactAlgorithmKind`).
pub use contact_force::ContactAlgorithmKind as ContactAlgorithm;

/// `contact.coupling`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coupling {
    /// `"explicit"`: under-relaxed traction exchange (default).
    Explicit,
    /// `"implicit"`: contact terms in the matrix.
    Implicit,
}

/// `contact.detection`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Detection {
    /// `"advancing-front"` (default).
    AdvancingFront,
    /// `"bvh"`: bounding volume hierarchy.
    Bvh,
    /// `"brute-force"`: all pairs.
    BruteForce,
}

/// `contact.face_position`: where a contact face is when the gap is
/// measured (`contact_force::FaceShifts`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FacePosition {
    /// `"interpolated"`: the face of the surface moved by the cell-to-point
    /// interpolation (the thesis).
    Interpolated,
    /// `"boundary-value"`: that face translated to the face's own boundary
    /// displacement u_b, the value the momentum equation and the implicit
    /// coupling act on.
    BoundaryValue,
}

/// `contact.augmentation`: augmented Lagrangian (Uzawa) updates of the
/// normal contact pressure on top of the penalty (beyond the thesis).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Augmentation {
    /// Largest penetration accepted, relative to the mean height of the
    /// slave cells in contact (default 1e-3).
    pub penetration: f64,
    /// Largest penalty share of the pressure accepted, ε_n times the
    /// largest penetration relative to the largest contact pressure
    /// (`None`, the default: not tested). Unlike `penetration` it does not
    /// depend on the cell size, so it holds a small compression to its
    /// elastic answer.
    pub pressure: Option<f64>,
    /// Most multiplier updates per increment (default 20).
    pub max_updates: usize,
}

impl Default for Augmentation {
    fn default() -> Self {
        Augmentation {
            penetration: 1e-3,
            pressure: None,
            max_updates: 20,
        }
    }
}

/// `contact.algorithm` by name.
pub(crate) fn algorithms() -> [(&'static str, ContactAlgorithm); 4] {
    ContactAlgorithm::ALL.map(|k| (k.name(), k))
}
/// `contact.coupling` by name.
pub(crate) const COUPLINGS: [(&str, Coupling); 2] = [
    ("explicit", Coupling::Explicit),
    ("implicit", Coupling::Implicit),
];

/// `contact.detection` by name.
pub(crate) const DETECTIONS: [(&str, Detection); 3] = [
    ("advancing-front", Detection::AdvancingFront),
    ("bvh", Detection::Bvh),
    ("brute-force", Detection::BruteForce),
];

/// `contact.slip_history` by name.
pub(crate) const SLIP_HISTORIES: [(&str, SlipHistory); 2] = [
    ("incremental", SlipHistory::Incremental),
    ("accumulated", SlipHistory::Accumulated),
];

/// `contact.face_position` by name.
pub(crate) const FACE_POSITIONS: [(&str, FacePosition); 2] = [
    ("boundary-value", FacePosition::BoundaryValue),
    ("interpolated", FacePosition::Interpolated),
];

/// `augmentation = true | false | { penetration = …, max_updates = … }`.
fn augmentation(n: &Node<'_>) -> Res<Option<Augmentation>> {
    if let Ok(on) = n.bool() {
        return Ok(on.then(Augmentation::default));
    }
    let t = n.table()?;
    t.deny_unknown(keys::AUGMENTATION)?;
    let d = Augmentation::default();
    Ok(Some(Augmentation {
        penetration: t.opt("penetration", d.penetration, |n| {
            n.f64_if(|x| x > 0.0 && x < 1.0, "satisfy 0 < penetration < 1")
        })?,
        pressure: t.opt("pressure", d.pressure, |n| {
            n.f64_if(|x| x > 0.0 && x < 1.0, "satisfy 0 < pressure < 1")
                .map(Some)
        })?,
        max_updates: t.opt("max_updates", d.max_updates, |n| n.usize_min(1))?,
    }))
}

/// A contact pair.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSpec {
    /// `(body, patch)` of `master = "body/patch"`; the body exists.
    pub master: (String, String),
    /// `(body, patch)` of `slave = "body/patch"`; the body exists.
    pub slave: (String, String),
    /// Contact algorithm; `None` when the case does not give it: then
    /// [`crate::contact_coupling::AlgorithmChoice::choose`] chooses.
    pub algorithm: Option<ContactAlgorithm>,
    /// Coupling of the two bodies.
    pub coupling: Coupling,
    /// Normal penalty scale f_n^scale of eq. 4.4a (> 0); `None` when the
    /// case does not give it: then
    /// [`crate::contact_coupling::PenaltyScale::choose`] chooses.
    pub penalty_scale: Option<f64>,
    /// Coulomb friction coefficient μ (>= 0, default 0): a constant or a
    /// time table `{ table = [[t, μ], ...] }`, evaluated at the end time of
    /// each increment (e.g. frictionless indentation, then twisting with
    /// μ = 0.5: thesis §5.3.5).
    pub friction: ScalarValue,
    /// Tangential penalty scale f_t^scale of eq. 4.4b (> 0, default 1).
    pub tangential_penalty_scale: f64,
    /// Normal traction under-relaxation, in (0, 1] (default 0.1; explicit coupling).
    pub relaxation_normal: f64,
    /// Tangential traction under-relaxation, in (0, 1] (default 0.1; explicit coupling).
    pub relaxation_tangential: f64,
    /// Contact search.
    pub detection: Detection,
    /// `slip_history`: what the trial frictional traction remembers
    /// (`"incremental"`: eq. 4.20, the slip of the increment only;
    /// `"accumulated"`, default: also the elastic slip committed at the end
    /// of the previous increment, so a stick traction persists across
    /// increments).
    pub slip_history: SlipHistory,
    /// `face_position`: where a contact face is when the gap is measured.
    pub face_position: FacePosition,
    /// Augmented Lagrangian updates of the normal pressure as the case
    /// gives them: `Some(Some(_))` on, `Some(None)` off (`false`), `None`
    /// not given: then
    /// [`crate::contact_coupling::AugmentationChoice::choose`] chooses.
    pub augmentation: Option<Option<Augmentation>>,
}

/// `friction`: μ >= 0, a number or a time table of numbers.
fn friction(n: &Node<'_>) -> Res<ScalarValue> {
    let v = scalar_value(n)?;
    let bad = match &v {
        ScalarValue::Constant(x) => (!(*x >= 0.0)).then_some(*x),
        ScalarValue::Table(rows) => rows.iter().map(|r| r.1).find(|x| !(*x >= 0.0)),
    };
    match bad {
        Some(x) => Err(n.err(format!(
            "friction must be >= 0, got {}",
            super::reader::fmt_num(x)
        ))),
        None => Ok(v),
    }
}

fn relaxation(n: &Node<'_>) -> Res<f64> {
    n.f64_if(|x| x > 0.0 && x <= 1.0, "satisfy 0 < relaxation <= 1")
}

/// `"body/patch"` → `(body, patch)`, the body being one of `bodies`.
fn body_patch(n: &Node<'_>, bodies: &[&str]) -> Res<(String, String)> {
    let s = n.str()?;
    let Some((body, patch)) = s.split_once('/') else {
        return Err(n.err(format!("expected \"<body>/<patch>\", got \"{s}\"")));
    };
    if body.is_empty() || patch.is_empty() || patch.contains('/') {
        return Err(n.err(format!("expected \"<body>/<patch>\", got \"{s}\"")));
    }
    if !super::column_safe(patch) {
        return Err(n.err(format!(
            "patch name \"{patch}\" contains ',' or '\"', which would split its column in history.csv; rename the patch (the mesh's physical group)"
        )));
    }
    if !bodies.contains(&body) {
        return Err(n.err(format!("unknown body \"{body}\"; bodies: {}", list(bodies))));
    }
    Ok((body.to_owned(), patch.to_owned()))
}

pub(crate) fn contact(node: &Node<'_>, bodies: &[&str]) -> Res<ContactSpec> {
    let t = node.table()?;
    t.deny_unknown(keys::CONTACT)?;
    let master = t.need("master", |n| body_patch(n, bodies))?;
    let slave_node = t.req("slave")?;
    let slave = body_patch(&slave_node.node(), bodies)?;
    if slave == master {
        return Err(slave_node.node().err(format!(
            "master and slave are the same patch \"{}/{}\"",
            slave.0, slave.1
        )));
    }
    if slave.0 == master.0 {
        return Err(slave_node.node().err(format!(
            "master \"{}/{}\" and slave \"{}/{}\" are patches of one body: self-contact is not supported",
            master.0, master.1, slave.0, slave.1
        )));
    }
    let (relaxation_normal, relaxation_tangential) = match t.get("relaxation") {
        None => (0.1, 0.1),
        Some(r) => {
            let r = r.node();
            let rt = r.table()?;
            rt.deny_unknown(keys::CONTACT_RELAXATION)?;
            (
                rt.opt("normal", 0.1, relaxation)?,
                rt.opt("tangential", 0.1, relaxation)?,
            )
        }
    };
    Ok(ContactSpec {
        master,
        slave,
        algorithm: t.opt("algorithm", None, |n| {
            n.choice("contact algorithm", &algorithms()).map(Some)
        })?,
        coupling: t.opt("coupling", Coupling::Explicit, |n| {
            n.choice("coupling", &COUPLINGS)
        })?,
        penalty_scale: t.opt("penalty_scale", None, |n| n.positive().map(Some))?,
        friction: t.opt("friction", ScalarValue::Constant(0.0), friction)?,
        tangential_penalty_scale: t.opt("tangential_penalty_scale", 1.0, |n| n.positive())?,
        relaxation_normal,
        relaxation_tangential,
        detection: t.opt("detection", Detection::AdvancingFront, |n| {
            n.choice("detection", &DETECTIONS)
        })?,
        slip_history: t.opt("slip_history", SlipHistory::Accumulated, |n| {
            n.choice("slip_history", &SLIP_HISTORIES)
        })?,
        face_position: t.opt("face_position", FacePosition::Interpolated, |n| {
            n.choice("face_position", &FACE_POSITIONS)
        })?,
        augmentation: t.opt("augmentation", None, |n| augmentation(n).map(Some))?,
    })
}
