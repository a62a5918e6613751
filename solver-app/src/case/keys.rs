//! The keys and names the case reader accepts, in one place.
//!
//! Every `deny_unknown` of the reader takes its list from the constants
//! here, and every `choice` its names from the `(name, value)` lists next
//! to its enum; [`accepted_keys`] and [`accepted_names`] hand the very same
//! lists out, so that a test can check `docs/case-format.md` against what
//! the reader enforces (`solver-app/tests/suite/case_format_doc.rs`).

use fv_nonlinear::NonlinearMethod;

use super::{contact, material, mesh, settings};
use crate::newton::preconditioning::Preconditioning;

/// The top level of the file.
pub const TOP: &[&str] = &[
    "title", "analysis", "time", "solver", "body", "contact", "output",
];

/// `[analysis]`.
pub const ANALYSIS: &[&str] = &["kind", "strain"];

/// `[time]`.
pub const TIME: &[&str] = &["end", "steps", "step", "intervals"];

/// `[solver]`.
pub const SOLVER: &[&str] = &[
    "nonlinear",
    "tolerance",
    "max_outer",
    "relaxation",
    "on_nonconvergence",
    "linear",
    "rhie_chow",
    "rhie_chow_history",
    "rhie_chow_plastic",
    "acceleration",
    "acceleration_depth",
    "predictor",
    "coupling_fallback",
];

/// `[solver] linear = { ... }`.
pub const LINEAR: &[&str] = &[
    "method",
    "tolerance",
    "max_iterations",
    "restart",
    "preconditioner",
];

/// `[[body]]`.
pub const BODY: &[&str] = &["name", "mesh", "material", "rigid", "boundary"];

/// The keys of `mesh = { ... }` that say where the mesh comes from
/// (exactly one of them).
pub const MESH_SOURCES: &[&str] = &["file", "polymesh", "generator"];

/// `mesh = { file = ... }`: a Gmsh file.
pub const MESH_FILE: &[&str] = &["file", "zone", "scale", "translate"];

/// `mesh = { polymesh = ... }`: an OpenFOAM polyMesh directory.
pub const MESH_POLYMESH: &[&str] = &["polymesh", "zone", "scale", "translate"];

/// `mesh = { generator = "box", ... }`.
pub const MESH_BOX: &[&str] = &["generator", "min", "max", "cells", "grading"];

/// `mesh = { generator = "annulus", ... }`.
pub const MESH_ANNULUS: &[&str] = &[
    "generator",
    "r_inner",
    "r_outer",
    "theta0",
    "theta1",
    "z0",
    "z1",
    "cells",
    "radial_grading",
    "translate",
];

/// `mesh = { generator = "spherical-shell", ... }`.
pub const MESH_SPHERICAL_SHELL: &[&str] = &[
    "generator",
    "r_inner",
    "r_outer",
    "part",
    "cells",
    "radial_grading",
    "translate",
];

/// `material = { ... }`.
pub const MATERIAL: &[&str] = &[
    "model",
    "E",
    "nu",
    "rho",
    "plane_stress",
    "yield",
    "hardening",
    "hardening_table",
];

/// `[body.boundary.<patch>]` of the types with a value (displacement,
/// normal-displacement, traction, pressure, force).
pub const BOUNDARY_VALUED: &[&str] = &["type", "value"];

/// `[body.boundary.<patch>]` of the types without one (symmetry, empty,
/// wedge).
pub const BOUNDARY_PLAIN: &[&str] = &["type"];

/// `[body.boundary.<patch>]` of type rigid-motion.
pub const BOUNDARY_RIGID_MOTION: &[&str] = &["type", "translation", "rotation"];

/// `rotation = { ... }` of a rigid motion.
pub const ROTATION: &[&str] = &["axis", "origin", "angle"];

/// A time table `{ table = [[t, value], ...] }`, wherever a value may be one.
pub const TIME_TABLE: &[&str] = &["table"];

/// `[[contact]]`.
pub const CONTACT: &[&str] = &[
    "master",
    "slave",
    "algorithm",
    "coupling",
    "penalty_scale",
    "friction",
    "tangential_penalty_scale",
    "relaxation",
    "detection",
    "slip_history",
    "face_position",
    "augmentation",
];

/// `[[contact]] relaxation = { ... }`.
pub const CONTACT_RELAXATION: &[&str] = &["normal", "tangential"];

/// `[[contact]] augmentation = { ... }`.
pub const AUGMENTATION: &[&str] = &["penetration", "pressure", "max_updates"];

/// `[output]`.
pub const OUTPUT: &[&str] = &["directory", "every", "restart_every", "precision", "fields"];

/// The keys one table of the case file accepts.
#[derive(Debug, Clone, Copy)]
pub struct AcceptedKeys {
    /// The table, as a path (`""` the top level; `body.mesh box` the box
    /// generator's `mesh`; `body.boundary.<patch> valued` the boundary
    /// types with a `value`).
    pub table: &'static str,
    /// The keys, as the reader lists them in its messages.
    pub keys: &'static [&'static str],
}

/// Every table of the case file and the keys the reader accepts in it.
pub fn accepted_keys() -> &'static [AcceptedKeys] {
    const fn t(table: &'static str, keys: &'static [&'static str]) -> AcceptedKeys {
        AcceptedKeys { table, keys }
    }
    const ALL: &[AcceptedKeys] = &[
        t("", TOP),
        t("analysis", ANALYSIS),
        t("time", TIME),
        t("solver", SOLVER),
        t("solver.linear", LINEAR),
        t("body", BODY),
        t("body.mesh", MESH_SOURCES),
        t("body.mesh file", MESH_FILE),
        t("body.mesh polymesh", MESH_POLYMESH),
        t("body.mesh box", MESH_BOX),
        t("body.mesh annulus", MESH_ANNULUS),
        t("body.mesh spherical-shell", MESH_SPHERICAL_SHELL),
        t("body.material", MATERIAL),
        t("body.boundary.<patch> valued", BOUNDARY_VALUED),
        t("body.boundary.<patch> plain", BOUNDARY_PLAIN),
        t("body.boundary.<patch> rigid-motion", BOUNDARY_RIGID_MOTION),
        t("body.boundary.<patch>.rotation", ROTATION),
        t("time table", TIME_TABLE),
        t("contact", CONTACT),
        t("contact.relaxation", CONTACT_RELAXATION),
        t("contact.augmentation", AUGMENTATION),
        t("output", OUTPUT),
    ];
    ALL
}

/// The names one key accepts (a string, one of `names`).
#[derive(Debug, Clone)]
pub struct AcceptedNames {
    /// The table, as in [`AcceptedKeys::table`] (`body.mesh` and
    /// `body.boundary.<patch>` for `generator` and `type`, which select
    /// among the tables of those names).
    pub table: &'static str,
    /// The key.
    pub key: &'static str,
    /// The valid names, as the reader lists them in its messages.
    pub names: Vec<&'static str>,
}

fn names<T>(options: &[(&'static str, T)]) -> Vec<&'static str> {
    options.iter().map(|o| o.0).collect()
}

/// Every key whose value is one of a list of names, with those names.
pub fn accepted_names() -> Vec<AcceptedNames> {
    let n = |table, key, names| AcceptedNames { table, key, names };
    vec![
        n("analysis", "kind", names(&settings::ANALYSIS_KINDS)),
        n("analysis", "strain", names(&settings::STRAIN_KINDS)),
        n(
            "solver",
            "nonlinear",
            NonlinearMethod::ALL.map(|m| m.name()).to_vec(),
        ),
        n(
            "solver",
            "on_nonconvergence",
            names(&settings::ON_NONCONVERGENCE),
        ),
        n(
            "solver",
            "rhie_chow_history",
            names(&settings::rhie_chow_histories()),
        ),
        n(
            "solver",
            "rhie_chow_plastic",
            names(&settings::rhie_chow_plastic_names()),
        ),
        n("solver", "acceleration", names(&settings::ACCELERATIONS)),
        n("solver", "predictor", names(&settings::PREDICTORS)),
        n(
            "solver",
            "coupling_fallback",
            names(&settings::COUPLING_FALLBACKS),
        ),
        n("solver.linear", "method", names(&settings::LINEAR_METHODS)),
        n(
            "solver.linear",
            "preconditioner",
            Preconditioning::ALL.map(|p| p.name()).to_vec(),
        ),
        n("body.mesh", "generator", mesh::GENERATORS.to_vec()),
        n(
            "body.mesh spherical-shell",
            "part",
            names(&mesh::SHELL_PARTS),
        ),
        n("body.material", "model", names(&material::MODELS)),
        n(
            "body.boundary.<patch>",
            "type",
            super::BOUNDARY_TYPES.to_vec(),
        ),
        n("contact", "algorithm", names(&contact::algorithms())),
        n("contact", "coupling", names(&contact::COUPLINGS)),
        n("contact", "detection", names(&contact::DETECTIONS)),
        n("contact", "slip_history", names(&contact::SLIP_HISTORIES)),
        n("contact", "face_position", names(&contact::FACE_POSITIONS)),
        n(
            "output",
            "precision",
            names(&crate::output::Precision::NAMES),
        ),
        n("output", "fields", names(&crate::output::Field::NAMES)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every named key is a key of its table.
    #[test]
    fn names_belong_to_tables() {
        let keys = accepted_keys();
        for a in accepted_names() {
            assert!(
                keys.iter()
                    .any(|t| t.table.starts_with(a.table) && t.keys.contains(&a.key)),
                "{} {}",
                a.table,
                a.key
            );
            assert!(!a.names.is_empty());
        }
    }
}
