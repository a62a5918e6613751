//! `[body.boundary.<patch>]`: one boundary condition per patch.

use super::keys;
use super::reader::{list, Node, Res};
use super::values::{rotation, scalar_value, vector_value, Rotation, ScalarValue, VectorValue};

/// A boundary condition, selected by `type`.
#[derive(Debug, Clone, PartialEq)]
pub enum BoundarySpec {
    /// `"displacement"`: prescribed displacement vector.
    Displacement {
        /// Displacement (constant or time table).
        value: VectorValue,
    },
    /// `"normal-displacement"`: scalar along the outward face normal
    /// (negative = inward), zero shear traction.
    NormalDisplacement {
        /// Normal displacement (constant or time table).
        value: ScalarValue,
    },
    /// `"tangential-displacement"`: the displacement's part in the face
    /// plane prescribed (the vector's normal part ignored), zero normal
    /// traction: a face held sideways and free along its normal.
    TangentialDisplacement {
        /// Displacement (constant or time table).
        value: VectorValue,
    },
    /// `"traction"`: prescribed traction vector.
    Traction {
        /// Traction (constant or time table).
        value: VectorValue,
    },
    /// `"pressure"`: positive presses on the face, follows the deformed normal.
    Pressure {
        /// Pressure (constant or time table).
        value: ScalarValue,
    },
    /// `"force"`: total force on the patch, reached by correcting a uniform
    /// patch displacement with the secant method (Algorithm 1).
    Force {
        /// Total force (constant or time table).
        value: VectorValue,
    },
    /// `"symmetry"`: zero normal displacement and zero shear traction.
    Symmetry,
    /// `"empty"`: the one-cell-thick direction of a 2D case.
    Empty,
    /// `"wedge"`: the sides of a one-cell axisymmetric wedge.
    Wedge,
    /// `"rigid-motion"`: translation and/or rotation of the whole patch
    /// (neither: fixed).
    RigidMotion {
        /// Translation (constant or time table).
        translation: Option<VectorValue>,
        /// Rotation about an axis (angle in radians, constant or time table).
        rotation: Option<Rotation>,
    },
}

#[derive(Clone, Copy)]
enum Kind {
    Vector(fn(VectorValue) -> BoundarySpec),
    Scalar(fn(ScalarValue) -> BoundarySpec),
    Plain(fn() -> BoundarySpec),
    Rigid,
}

/// The boundary condition types by name, with what each reads.
const KINDS: [(&str, Kind); 10] = [
    (
        "displacement",
        Kind::Vector(|value| BoundarySpec::Displacement { value }),
    ),
    (
        "normal-displacement",
        Kind::Scalar(|value| BoundarySpec::NormalDisplacement { value }),
    ),
    (
        "tangential-displacement",
        Kind::Vector(|value| BoundarySpec::TangentialDisplacement { value }),
    ),
    (
        "traction",
        Kind::Vector(|value| BoundarySpec::Traction { value }),
    ),
    (
        "pressure",
        Kind::Scalar(|value| BoundarySpec::Pressure { value }),
    ),
    ("force", Kind::Vector(|value| BoundarySpec::Force { value })),
    ("symmetry", Kind::Plain(|| BoundarySpec::Symmetry)),
    ("empty", Kind::Plain(|| BoundarySpec::Empty)),
    ("wedge", Kind::Plain(|| BoundarySpec::Wedge)),
    ("rigid-motion", Kind::Rigid),
];

/// The boundary condition types, as written in `type`.
pub const BOUNDARY_TYPES: [&str; KINDS.len()] = {
    let mut names = [""; KINDS.len()];
    let mut i = 0;
    while i < names.len() {
        names[i] = KINDS[i].0;
        i += 1;
    }
    names
};

pub(crate) fn boundary_condition(node: &Node<'_>) -> Res<BoundarySpec> {
    let t = node.table().map_err(|_| {
        node.err(format!(
            "expected a table {{ type = ..., ... }} (types: {}), got {}",
            list(&BOUNDARY_TYPES),
            node.raw()
        ))
    })?;
    let type_node = t.req("type")?;
    let tn = type_node.node();
    let kind = tn.choice("boundary type", &KINDS)?;
    let type_name = tn.str()?;
    match kind {
        Kind::Vector(make) => {
            t.deny_unknown(keys::BOUNDARY_VALUED)?;
            let v = t.req("value")?;
            let v = v.node();
            Ok(make(vector_value(&v).map_err(|mut e| {
                if e.key.as_deref() == Some(v.path) && !e.message.contains("type \"") {
                    e.message = format!("{} (type \"{type_name}\" takes a vector)", e.message);
                }
                e
            })?))
        }
        Kind::Scalar(make) => {
            t.deny_unknown(keys::BOUNDARY_VALUED)?;
            let v = t.req("value")?;
            let v = v.node();
            Ok(make(scalar_value(&v).map_err(|mut e| {
                if e.key.as_deref() == Some(v.path) {
                    e.message = format!("{} (type \"{type_name}\" takes a scalar)", e.message);
                }
                e
            })?))
        }
        Kind::Plain(make) => {
            if let Some(v) = t.get("value") {
                return Err(v.node().err(format!("type \"{type_name}\" takes no value")));
            }
            t.deny_unknown(keys::BOUNDARY_PLAIN)?;
            Ok(make())
        }
        Kind::Rigid => {
            if let Some(v) = t.get("value") {
                return Err(v.node().err(
                    "type \"rigid-motion\" takes `translation` and/or `rotation`, not `value`",
                ));
            }
            t.deny_unknown(keys::BOUNDARY_RIGID_MOTION)?;
            let translation = t.maybe("translation", vector_value)?;
            let rotation = t.maybe("rotation", rotation)?;
            if translation.is_none() && rotation.is_none() {
                // most likely a misspelt or forgotten key: the patch would
                // silently be held fixed
                return Err(t.err_at_key(
                    "translation",
                    "type \"rigid-motion\" needs `translation` and/or `rotation` (to hold the patch fixed, write type = \"displacement\" with value = [0, 0, 0])",
                ));
            }
            Ok(BoundarySpec::RigidMotion {
                translation,
                rotation,
            })
        }
    }
}
