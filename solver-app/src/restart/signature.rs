//! What a restart state fits: the bodies (rigid or not, material law,
//! mesh sizes, patches with their face counts) and the contact pairs of
//! the case that wrote it, one `key = value` line each, stored in the
//! results file (`/restart` attribute `case`). A case continued from the
//! file must give the same lines; the message of one that does not names
//! every line that differs.
use std::path::Path;

use crate::case::InputError;
use crate::contact_coupling::ContactSet;
use crate::model::Body;

/// The lines of the bodies and contact pairs.
pub fn case_signature(bodies: &[Body], contacts: &ContactSet) -> Vec<String> {
    let mut v = Vec::new();
    for b in bodies {
        let n = &b.name;
        v.push(format!("body {n}: rigid = {}", b.rigid));
        if !b.rigid {
            v.push(format!("body {n}: material = {}", b.momentum.law.name()));
            v.push(format!(
                "body {n}: {CONSTANTS} = {}",
                material_constants(&b.material)
            ));
            let strain = if b.momentum.law.is_updated_lagrangian() {
                "large"
            } else {
                "small"
            };
            v.push(format!("body {n}: strain = {strain}"));
        }
        v.push(format!("body {n}: cells = {}", b.mesh.n_cells));
        v.push(format!("body {n}: points = {}", b.mesh.n_points()));
        let patches: Vec<String> = b
            .mesh
            .patches
            .iter()
            .map(|p| format!("{} ({} faces)", p.name, p.size))
            .collect();
        v.push(format!("body {n}: patches = {}", patches.join(", ")));
    }
    for (i, c) in contacts.interfaces.iter().enumerate() {
        let side = |s: &crate::contact_coupling::ContactSide| {
            format!(
                "{}/{}",
                bodies[s.body].name, bodies[s.body].mesh.patches[s.patch].name
            )
        };
        v.push(format!(
            "contact {}: pair = {} – {}",
            i + 1,
            side(&c.master),
            side(&c.slave)
        ));
    }
    v
}

/// The key of a body's material constants.
const CONSTANTS: &str = "material constants";

/// The case's material constants, in full precision: a continued run
/// with another E, ν, density or hardening would take the saved stresses
/// and plastic state to a different material.
fn material_constants(m: &crate::case::MaterialSpec) -> String {
    let mut s = format!("E {:e}, nu {:e}", m.e, m.nu);
    if let Some(rho) = m.rho {
        s.push_str(&format!(", rho {rho:e}"));
    }
    if m.plane_stress {
        s.push_str(", plane stress");
    }
    if let Some(y) = m.yield_stress {
        s.push_str(&format!(", yield {y:e}"));
    }
    if let Some(h) = m.hardening {
        s.push_str(&format!(", hardening {h:e}"));
    }
    if let Some(t) = &m.hardening_table {
        let rows: Vec<String> = t.iter().map(|(e, y)| format!("[{e:e}, {y:e}]")).collect();
        s.push_str(&format!(", hardening_table [{}]", rows.join(", ")));
    }
    s
}

fn split(line: &str) -> (&str, &str) {
    line.split_once(" = ").unwrap_or((line, ""))
}

/// Refuses (exit 2) a case whose lines differ from the file's, naming
/// every difference.
pub fn check_compatible(file: &Path, saved: &[String], now: &[String]) -> Result<(), InputError> {
    let mut diffs = Vec::new();
    for line in saved {
        let (key, value) = split(line);
        match now.iter().map(|l| split(l)).find(|(k, _)| *k == key) {
            Some((_, v)) if v == value => {}
            Some((_, v)) => diffs.push(format!("{key}: {value} in the file, {v} in the case")),
            None => diffs.push(format!("{key}: {value} in the file, absent from the case")),
        }
    }
    // files written before the constants were recorded (2026-11-30) have
    // the model's name only
    let constants_recorded = saved.iter().any(|l| split(l).0.ends_with(CONSTANTS));
    for line in now {
        let (key, value) = split(line);
        if key.ends_with(CONSTANTS) && !constants_recorded {
            continue;
        }
        if !saved.iter().any(|l| split(l).0 == key) {
            diffs.push(format!("{key}: {value} in the case, absent from the file"));
        }
    }
    if diffs.is_empty() {
        return Ok(());
    }
    Err(InputError::new(
        file,
        format!(
            "--restart: the results were written for another case ({}); run the case they were written for, or start afresh without --restart",
            diffs.join("; ")
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_difference_is_named() {
        let saved = vec![
            "body a: cells = 10".to_owned(),
            "body a: points = 22".to_owned(),
            "contact 1: pair = a/top – b/bottom".to_owned(),
        ];
        let now = vec![
            "body a: cells = 12".to_owned(),
            "body a: points = 22".to_owned(),
            "body c: cells = 4".to_owned(),
        ];
        let e = check_compatible(Path::new("r.h5"), &saved, &now)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("body a: cells: 10 in the file, 12 in the case"),
            "{e}"
        );
        assert!(
            e.contains("contact 1: pair: a/top – b/bottom in the file, absent from the case"),
            "{e}"
        );
        assert!(
            e.contains("body c: cells: 4 in the case, absent from the file"),
            "{e}"
        );
        assert!(!e.contains("points"), "{e}");
        assert!(check_compatible(Path::new("r.h5"), &saved, &saved).is_ok());
    }
}
