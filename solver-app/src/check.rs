//! `fvc check`: validate a case and report its meshes without solving.
use std::fmt::Write;

use crate::case::Case;
use crate::model::Body;
use crate::words::{count, Num};
use fv_mesh::MeshQuality;

/// The mesh report printed by `fvc check`.
pub fn mesh_report(case: &Case, bodies: &[Body]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "case '{}': {}",
        case.title,
        count(bodies.len(), "body", "bodies")
    );
    for b in bodies {
        let q = MeshQuality::new(&b.mesh, &b.geom);
        let _ = writeln!(
            s,
            "body '{}'{}: {}, {} ({} internal), {}, volume {}",
            b.name,
            if b.rigid { " (rigid)" } else { "" },
            count(b.mesh.n_cells, "cell", "cells"),
            count(b.mesh.n_faces(), "face", "faces"),
            b.mesh.n_internal_faces(),
            count(b.mesh.n_points(), "point", "points"),
            Num(b.geom.total_volume())
        );
        let _ = writeln!(
            s,
            "  non-orthogonality: max {:.2}°, mean {:.2}°; max skewness {:.3}; cell volume {} … {}",
            q.max_non_orthogonality,
            q.mean_non_orthogonality,
            q.max_skewness,
            Num(q.min_volume),
            Num(q.max_volume)
        );
        let _ = writeln!(s, "  patches ({}):", b.mesh.patches.len());
        for (p, spec) in b.mesh.patches.iter().zip(&b.patch_specs) {
            let area: f64 = p.faces().map(|f| b.geom.face_mag(f)).sum();
            // a contact patch carries the contact traction
            let contact: Vec<String> = case
                .contacts
                .iter()
                .enumerate()
                .flat_map(|(i, c)| {
                    [("master", &c.master), ("slave", &c.slave)]
                        .into_iter()
                        .filter(|(_, (body, patch))| *body == b.name && *patch == p.name)
                        .map(move |(side, _)| format!("contact[{i}] {side}"))
                })
                .collect();
            let cond = if contact.is_empty() {
                spec.as_ref()
                    .map(spec_name)
                    .unwrap_or("traction-free")
                    .to_owned()
            } else {
                contact.join(", ")
            };
            let _ = writeln!(
                s,
                "    {:<24} {:>8} {:<5}  area {:<12}  {}",
                p.name,
                p.size,
                if p.size == 1 { "face" } else { "faces" },
                Num(area),
                cond
            );
        }
    }
    s
}

/// One line per contact: its surfaces and the normal penalty scale, with
/// why it is that (`fvc check` and the run's log).
pub fn contact_report(contacts: &crate::contact_coupling::ContactSet) -> Vec<String> {
    contacts
        .interfaces
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let augmentation = if c.augmentation_choice.value().is_some() {
                "on"
            } else {
                "off"
            };
            format!(
                "contact[{i}] {} on {}: algorithm {} ({}); penalty_scale {} ({}); augmentation {augmentation} ({})",
                c.slave_name,
                c.master_name,
                c.algorithm_choice.name(),
                c.algorithm_choice.reason(),
                c.penalty_scale.value(),
                c.penalty_scale.reason(),
                c.augmentation_choice.reason()
            )
        })
        .collect()
}

/// The nonlinear method and the settings it chose, and why (`fvc check`
/// and the first lines of a run's log).
pub fn solver_report(
    case: &Case,
    bodies: &[Body],
    contacts: &crate::contact_coupling::ContactSet,
) -> String {
    use crate::case::NEWTON_FINAL_ATTEMPT_ITERATIONS;
    use fv_nonlinear::NonlinearMethod;
    let s = &case.solver;
    let given = case.source.line_of("solver.nonlinear");
    let in_file = |line: usize| {
        case.source
            .text()
            .lines()
            .nth(line.saturating_sub(1))
            .is_some_and(|l| l.contains(&format!("\"{}\"", s.nonlinear.name())))
    };
    let why = match given {
        Some(line) if in_file(line) => format!("[solver] nonlinear, line {line}"),
        None if s.nonlinear == NonlinearMethod::default() => "the default".to_owned(),
        _ => "the command line".to_owned(),
    };
    let mut out = format!(
        "solver: {} ({why}), tolerance {:e}",
        s.nonlinear.name(),
        s.tolerance
    );
    match s.nonlinear {
        NonlinearMethod::NewtonKrylov => {
            let last = if s.max_outer_given {
                String::new()
            } else {
                format!(
                    ", {} in an increment's last attempt",
                    NEWTON_FINAL_ATTEMPT_ITERATIONS.max(s.max_outer)
                )
            };
            let auto = if s.linear.preconditioner
                == crate::newton::preconditioning::Preconditioning::Auto
            {
                format!(
                    ": {}",
                    crate::newton::auto_preconditioner_report(bodies, contacts)
                )
            } else {
                String::new()
            };
            let _ = write!(
                out,
                " (residual relative to the cells' force scale); at most {} Newton iterations per attempt{last}; GMRES({}) to Eisenstat–Walker forcing terms ≤ {}, preconditioner \"{}\"{auto}; a failed step is cut back up to four times; first iterate: the linearised response to the step (`predictor` is the segregated method's)",
                s.max_outer, s.linear.restart, s.linear.tolerance, s.linear.preconditioner
            );
            return out;
        }
        NonlinearMethod::Segregated => {
            let _ = write!(
                out,
                " (relative correction); at most {} outer iterations per increment; acceleration {}, relaxation {}",
                s.max_outer,
                match s.acceleration {
                    crate::case::Acceleration::None => "none",
                    crate::case::Acceleration::Anderson => "anderson",
                },
                s.relaxation
            );
        }
    }
    let _ = write!(
        out,
        "; predictor {}",
        match s.predictor {
            crate::case::Predictor::None => "none",
            crate::case::Predictor::Linear => "linear",
        }
    );
    out
}

/// The `type` name of a boundary condition.
pub fn spec_name(s: &crate::case::BoundarySpec) -> &'static str {
    use crate::case::BoundarySpec as B;
    match s {
        B::Displacement { .. } => "displacement",
        B::NormalDisplacement { .. } => "normal-displacement",
        B::TangentialDisplacement { .. } => "tangential-displacement",
        B::Traction { .. } => "traction",
        B::Pressure { .. } => "pressure",
        B::Force { .. } => "force",
        B::Symmetry => "symmetry",
        B::Empty => "empty",
        B::Wedge => "wedge",
        B::RigidMotion { .. } => "rigid-motion",
    }
}
