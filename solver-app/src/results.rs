//! Result files of a run: `history.csv`, `summary.json`, `log.txt`
//! (CASE_FORMAT.md, "Results"). Each is written so that a run killed at any
//! moment leaves what was already written readable: history rows are
//! flushed per increment, the summary is replaced atomically.
use crate::words::Num;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::contact_coupling::ContactSet;
use crate::model::Body;
use fv_mesh::Vector;

/// The run log: every line goes to `log.txt` (flushed) and to `tracing`.
pub struct RunLog {
    file: Option<BufWriter<File>>,
}

impl RunLog {
    /// Opens `<dir>/log.txt`.
    pub fn create(dir: &Path) -> std::io::Result<Self> {
        Ok(RunLog {
            file: Some(BufWriter::new(File::create(dir.join("log.txt"))?)),
        })
    }

    /// Opens `<dir>/log.txt` to add to it (a continued run).
    pub fn append(dir: &Path) -> std::io::Result<Self> {
        let f = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(dir.join("log.txt"))?;
        Ok(RunLog {
            file: Some(BufWriter::new(f)),
        })
    }

    /// A log that only forwards to `tracing`.
    pub fn none() -> Self {
        RunLog { file: None }
    }

    /// Writes an informational line.
    pub fn info(&mut self, msg: &str) {
        tracing::info!("{msg}");
        self.write(msg);
    }

    /// Writes a result (the final figures, where the results are): on
    /// standard output, where `fvc run … > file` keeps them, and to the
    /// file; progress and diagnostics go to standard error.
    pub fn result(&mut self, msg: &str) {
        stdout_line(msg);
        self.write(msg);
    }

    /// Writes a warning line.
    pub fn warn(&mut self, msg: &str) {
        tracing::warn!("{msg}");
        self.write(&format!("warning: {msg}"));
    }

    /// Writes a line to the file only (the progress bar shows it on a TTY).
    pub fn write(&mut self, msg: &str) {
        if let Some(f) = &mut self.file {
            let _ = writeln!(f, "{msg}");
            let _ = f.flush();
        }
    }
}

/// `history.csv`: one row per increment.
pub struct History {
    out: BufWriter<File>,
}

/// Reported patches: (body index, patch index, `"<body>/<patch>"`).
pub fn reported_patches(bodies: &[Body]) -> Vec<(usize, usize, String)> {
    let mut v = Vec::new();
    for (bi, b) in bodies.iter().enumerate() {
        for p in b.reported_patches() {
            v.push((bi, p, format!("{}/{}", b.name, b.mesh.patches[p].name)));
        }
    }
    v
}

/// Column names of the history table (CSV header and `/history` columns).
pub fn history_columns(bodies: &[Body], contacts: &ContactSet) -> Vec<String> {
    let mut cols: Vec<String> = ["time", "outer_iterations", "residual"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    for (_, _, name) in reported_patches(bodies) {
        for c in ["Fx", "Fy", "Fz"] {
            cols.push(format!("{name}:{c}"));
        }
    }
    let labels = contact_labels(contacts);
    for label in &labels {
        cols.push(format!("{label}:normal_force"));
    }
    // beyond CASE_FORMAT.md, after its columns: the area in contact, so
    // that the mean pressure F_n/A (and the mean penetration F_n/(ε_n A)
    // of the linear penalty, eq. 4.4a) can be followed
    for label in &labels {
        cols.push(format!("{label}:contact_area"));
    }
    for (_, _, name) in moment_patches(bodies) {
        for c in ["Mx", "My", "Mz"] {
            cols.push(format!("{name}:{c}"));
        }
    }
    cols
}

/// Name of each contact pair in the history columns: its slave patch
/// (`<body>/<patch>`, CASE_FORMAT.md), or `<slave>@<master>` when the slave
/// patch is in several pairs, so that no two columns share a name.
fn contact_labels(contacts: &ContactSet) -> Vec<String> {
    let pairs = &contacts.interfaces;
    pairs
        .iter()
        .map(|c| {
            if pairs
                .iter()
                .filter(|o| o.slave_name == c.slave_name)
                .count()
                > 1
            {
                format!("{}@{}", c.slave_name, c.master_name)
            } else {
                c.slave_name.clone()
            }
        })
        .collect()
}

/// Patches with a `rigid-motion` condition that has a rotation, of
/// deformable and rigid bodies: (body index, patch index,
/// `"<body>/<patch>"`). Their moments close the history rows.
pub fn moment_patches(bodies: &[Body]) -> Vec<(usize, usize, String)> {
    reported_patches(bodies)
        .into_iter()
        .filter(|&(bi, p, _)| {
            matches!(
                bodies[bi].patch_specs[p],
                Some(crate::case::BoundarySpec::RigidMotion {
                    rotation: Some(_),
                    ..
                })
            )
        })
        .collect()
}

/// Moment of the reaction of a `rigid-motion` patch with a rotation about
/// the point of its axis at time `t` (the rotation `origin` moved by the
/// translation): Σ (x_f − o) × F_f over the patch faces, x_f the prescribed
/// current face centre and F_f the face force of [`patch_reaction`] (the
/// twisting torque of thesis §5.3.5 is its component along the axis). A
/// rigid body's patch takes minus the moment of the contact forces on it,
/// shared by area as [`patch_reaction`] shares the force. Zero for other
/// patches.
pub fn patch_moment(bodies: &[Body], bi: usize, p: usize, t: f64, contacts: &ContactSet) -> Vector {
    let body = &bodies[bi];
    let Some(crate::case::BoundarySpec::RigidMotion {
        translation,
        rotation: Some(r),
    }) = &body.patch_specs[p]
    else {
        return Vector::zeros();
    };
    let tr = translation
        .as_ref()
        .map(|x| Vector::from(x.at(t)))
        .unwrap_or_else(Vector::zeros);
    let o = Vector::from(r.origin) + tr;
    if body.rigid {
        return rigid_patch_moment(bodies, bi, p, o, contacts);
    }
    let ni = body.mesh.n_internal_faces();
    let fv_discretise::PatchCondition::Displacement(u) = &body.momentum.conditions[p] else {
        return Vector::zeros();
    };
    body.mesh.patches[p]
        .faces()
        .zip(u)
        .map(|(f, u)| {
            let x = body.initial_face_centres[f - ni] + u;
            (x - o).cross(&body.momentum.face_force[f - ni])
        })
        .sum()
}

/// The share of patch `p` of the moment about `o` that holds rigid body
/// `bi` against its contacts: minus Σ (x_f − o) × F_f over the faces of
/// the deformable sides opposite, F_f the force on the rigid body there
/// (the deformable face's traction reversed), in proportion to the patch's
/// area among the body's reported patches.
fn rigid_patch_moment(
    bodies: &[Body],
    bi: usize,
    p: usize,
    o: Vector,
    contacts: &ContactSet,
) -> Vector {
    let mut on_body = Vector::zeros();
    for c in &contacts.interfaces {
        for (this, other, tractions) in [
            (&c.master, &c.slave, &c.tractions.slave),
            (&c.slave, &c.master, &c.tractions.master),
        ] {
            if this.body != bi || bodies[other.body].rigid {
                continue;
            }
            let s = &other.surface;
            for f in 0..s.n_faces() {
                let force = -tractions.traction(f) * s.face_mag[f];
                on_body += (s.face_centres[f] - o).cross(&force);
            }
        }
    }
    (-on_body * rigid_patch_share(&bodies[bi], p)).map(|v| v + 0.0)
}

/// One history row, in the order of [`history_columns`].
pub fn history_row(
    time: f64,
    outer: usize,
    residual: f64,
    bodies: &[Body],
    contacts: &ContactSet,
) -> Vec<f64> {
    let mut row = vec![time, outer as f64, residual];
    for (bi, p, _) in reported_patches(bodies) {
        let f = patch_reaction(bodies, bi, p, contacts);
        row.extend([f.x, f.y, f.z]);
    }
    for c in &contacts.interfaces {
        row.push(c.stats.normal_force);
    }
    for c in &contacts.interfaces {
        row.push(c.stats.contact_area);
    }
    for (bi, p, _) in moment_patches(bodies) {
        let m = patch_moment(bodies, bi, p, time, contacts);
        row.extend([m.x, m.y, m.z]);
    }
    row
}

impl History {
    /// Creates the file and writes the header.
    pub fn create(dir: &Path, bodies: &[Body], contacts: &ContactSet) -> std::io::Result<Self> {
        let mut out = BufWriter::new(File::create(dir.join("history.csv"))?);
        writeln!(out, "{}", history_columns(bodies, contacts).join(","))?;
        out.flush()?;
        Ok(History { out })
    }

    /// Opens the file of an earlier run to continue it after increment
    /// `keep` (`fvc run --restart`): the header and the first `keep` rows
    /// stay, later rows go.
    pub fn reopen(dir: &Path, keep: usize) -> std::io::Result<Self> {
        let path = dir.join("history.csv");
        let text = std::fs::read_to_string(&path)?;
        let kept: Vec<&str> = text.lines().take(keep + 1).collect();
        let mut out = BufWriter::new(File::create(&path)?);
        for line in kept {
            writeln!(out, "{line}")?;
        }
        out.flush()?;
        Ok(History { out })
    }

    /// Appends one row (see [`history_row`]) and flushes it.
    pub fn append(&mut self, row: &[f64]) -> std::io::Result<()> {
        for (i, v) in row.iter().enumerate() {
            let sep = if i == 0 { "" } else { "," };
            if i == 1 {
                write!(self.out, "{sep}{}", *v as u64)?;
            } else {
                write!(self.out, "{sep}{v:.10e}")?;
            }
        }
        writeln!(self.out)?;
        self.out.flush()
    }
}

/// Reaction force of patch `p` of body `bi`: ∫ σ·n dA, the force exerted
/// on the body through the patch. A rigid body carries no stress; it is
/// held in equilibrium by its prescribed patches, so they take minus the
/// contact forces on it (the forces its contact pairs exert on the bodies
/// opposite, reversed), shared in proportion to their areas: the force on
/// a rigid punch's driven patch is the punch force.
pub fn patch_reaction(bodies: &[Body], bi: usize, p: usize, contacts: &ContactSet) -> Vector {
    let body = &bodies[bi];
    if !body.rigid {
        return body.momentum.patch_force(&body.mesh, p);
    }
    let mut on_body = Vector::zeros();
    for c in &contacts.interfaces {
        // the force on the deformable side, reversed (a rigid–rigid pair
        // carries none)
        if c.master.body == bi && !bodies[c.slave.body].rigid {
            on_body -= c.stats.slave_force;
        }
        if c.slave.body == bi && !bodies[c.master.body].rigid {
            on_body -= c.stats.master_force;
        }
    }
    // + 0: no −0 in the tables
    (-on_body * rigid_patch_share(body, p)).map(|v| v + 0.0)
}

/// The share of a rigid body's reported patch `p` in what holds the body:
/// its area over theirs (0 without reported patches).
fn rigid_patch_share(body: &Body, p: usize) -> f64 {
    let area = |q: usize| -> f64 {
        body.mesh.patches[q]
            .faces()
            .map(|f| body.geom.face_mag(f))
            .sum()
    };
    let total: f64 = body.reported_patches().map(area).sum();
    if total > 0.0 {
        area(p) / total
    } else {
        0.0
    }
}

/// The wedge of an axisymmetric model: (axis direction, opening angle in
/// radians) from the `wedge` faces of the deformable bodies — the angle
/// between the two wedge planes, whose outward normals are the most
/// opposite pair. The axis points along its largest component's positive
/// sense (+y for a wedge about y), whichever wedge face comes first, so
/// that the logged axial forces keep their sign. `None` without wedge
/// faces.
pub fn wedge_of(bodies: &[Body]) -> Option<(Vector, f64)> {
    let mut normals = Vec::new();
    for b in bodies.iter().filter(|b| !b.rigid) {
        for (p, c) in b.mesh.patches.iter().zip(&b.momentum.conditions) {
            if matches!(c, fv_discretise::PatchCondition::Wedge(_)) {
                normals.extend(p.faces().map(|f| b.geom.face_normal(f)));
            }
        }
    }
    let &na = normals.first()?;
    let nb = normals
        .iter()
        .copied()
        .min_by(|a, b| a.dot(&na).total_cmp(&b.dot(&na)))?;
    let axis = na.cross(&nb);
    let angle = (-na.dot(&nb)).clamp(-1.0, 1.0).acos();
    let largest = axis.iamax();
    let axis = if axis[largest] < 0.0 { -axis } else { axis };
    (axis.norm() > 1e-12 && angle > 0.0).then(|| (axis.normalize(), angle))
}

/// Log lines with the full-revolution forces of an axisymmetric (wedge)
/// model: the forces of the modelled wedge (as in `history.csv` and
/// `summary.json`) times 2π/wedge angle — the axial component of every
/// reported patch reaction (the radial components cancel over the
/// revolution) and every contact normal force. Empty for other models.
pub fn full_revolution_lines(bodies: &[Body], contacts: &ContactSet) -> Vec<String> {
    let Some((axis, angle)) = wedge_of(bodies) else {
        return Vec::new();
    };
    let factor = std::f64::consts::TAU / angle;
    let mut parts = Vec::new();
    for (bi, p, name) in reported_patches(bodies) {
        let f = patch_reaction(bodies, bi, p, contacts);
        parts.push(format!("{name} axial {:.6e}", factor * f.dot(&axis)));
    }
    for c in &contacts.interfaces {
        parts.push(format!(
            "{} normal force {:.6e}",
            c.slave_name,
            factor * c.stats.normal_force
        ));
    }
    vec![format!(
        "  axisymmetric wedge of {:.4}° about ({:.3}, {:.3}, {:.3}), full revolution (x {:.4}): {}",
        angle.to_degrees(),
        axis.x,
        axis.y,
        axis.z,
        factor,
        parts.join(", ")
    )]
}

/// Data of `summary.json`.
#[derive(Debug, Clone, Default)]
pub struct Summary {
    /// Case title.
    pub title: String,
    /// All increments converged (or were accepted with `continue`).
    pub converged: bool,
    /// Increments completed.
    pub increments: usize,
    /// Time of the last increment completed (of its last converged
    /// sub-step when a later one failed); 0 before the first.
    pub time_reached: f64,
    /// The signal that stopped the run before its end (`"SIGINT"`,
    /// `"SIGTERM"`), if one did.
    pub interrupted: Option<String>,
    /// Total outer iterations.
    pub outer_iterations: usize,
    /// Total linear-solver iterations.
    pub linear_iterations: usize,
    /// Total residual evaluations (Newton–Krylov: base points,
    /// line-search trials and Jacobian products; the segregated method
    /// evaluates one per outer iteration).
    pub residual_evaluations: usize,
    /// The nonlinear method (`[solver] nonlinear`).
    pub nonlinear: &'static str,
    /// Wall-clock seconds.
    pub wall_seconds: f64,
    /// Cells of all bodies.
    pub cells: usize,
    /// Why the run failed, if it did.
    pub failure: Option<String>,
    /// Seconds per phase of the solution (after at least one increment).
    pub profile: Option<crate::profile::PhaseTimes>,
    /// Explicitly coupled contacts the run coupled implicitly after an
    /// increment failed, one message per switch.
    pub coupling_switched: Vec<String>,
    /// The increment this run continued from (`--restart`).
    pub restarted_from: Option<usize>,
}

/// The physical figures of `summary.json` at one state: the reaction of
/// every reported patch and the statistics of every contact pair. Taken
/// after every increment written, so that a run that stops in the middle
/// of an increment (failure, interrupt) reports the last one written,
/// not the abandoned iterate.
#[derive(Debug, Clone, Default)]
pub struct SummaryFigures {
    patches: serde_json::Map<String, serde_json::Value>,
    contacts: Vec<serde_json::Value>,
}

impl SummaryFigures {
    /// The figures of the bodies and contacts as they are.
    pub fn of(bodies: &[Body], contacts: &ContactSet) -> Self {
        let mut patches = serde_json::Map::new();
        for (bi, p, name) in reported_patches(bodies) {
            let b = &bodies[bi];
            let f = patch_reaction(bodies, bi, p, contacts);
            let area: f64 = b.mesh.patches[p].faces().map(|f| b.geom.face_mag(f)).sum();
            patches.insert(
                name,
                serde_json::json!({ "reaction_force": [f.x, f.y, f.z], "area": area }),
            );
        }
        let contacts = contacts
            .interfaces
            .iter()
            .map(|c| {
                let t = c.stats.tangential_force;
                serde_json::json!({
                    "master": c.master_name,
                    "slave": c.slave_name,
                    "coupling": if c.implicit { "implicit" } else { "explicit" },
                    "normal_force": c.stats.normal_force,
                    "tangential_force": [t.x, t.y, t.z],
                    "max_pressure": c.stats.max_pressure,
                    "contact_area": c.stats.contact_area,
                    "max_penetration": c.stats.max_penetration,
                    "augmentation_updates": c.augmentation_updates_run,
                })
            })
            .collect();
        SummaryFigures { patches, contacts }
    }

    /// The physics at the end of the run, a line per reported patch and
    /// per contact, as the log's final block (the figures of
    /// `summary.json`).
    pub fn report(&self) -> String {
        let num = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::NAN);
        let vec3 = |v: &serde_json::Value| {
            // a component 1e-9 of the largest is round-off: 0
            let c = [num(&v[0]), num(&v[1]), num(&v[2])];
            let big = c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let c: Vec<String> = c
                .iter()
                .map(|&x| Num(if x.abs() < 1e-9 * big { 0.0 } else { x }).to_string())
                .collect();
            format!("({})", c.join(", "))
        };
        let mut lines = Vec::new();
        for (name, p) in &self.patches {
            lines.push(format!(
                "  {name}: reaction force {}",
                vec3(&p["reaction_force"])
            ));
        }
        for c in &self.contacts {
            lines.push(format!(
                "  contact {} – {}: normal force {}, tangential force {}, peak pressure {}, contact area {}, largest penetration {}",
                c["master"].as_str().unwrap_or("?"),
                c["slave"].as_str().unwrap_or("?"),
                Num(num(&c["normal_force"])),
                vec3(&c["tangential_force"]),
                Num(num(&c["max_pressure"])),
                Num(num(&c["contact_area"])),
                Num(num(&c["max_penetration"])),
            ));
        }
        if lines.is_empty() {
            return String::new();
        }
        format!("at the last increment written:\n{}", lines.join("\n"))
    }
}

/// Writes `summary.json` (atomically: temp file + rename).
pub fn write_summary(
    dir: &Path,
    s: &Summary,
    figures: &SummaryFigures,
) -> std::io::Result<PathBuf> {
    let mut v = serde_json::json!({
        "title": s.title,
        "converged": s.converged,
        "increments": s.increments,
        "time_reached": s.time_reached,
        "interrupted": s.interrupted.is_some(),
        "outer_iterations": s.outer_iterations,
        "linear_iterations": s.linear_iterations,
        "residual_evaluations": s.residual_evaluations,
        "nonlinear": s.nonlinear,
        "wall_seconds": s.wall_seconds,
        "cells": s.cells,
        "patches": figures.patches,
        "contacts": figures.contacts,
    });
    // `coupling` is the segregated method's; Newton–Krylov solves the
    // contact inside its Newton loop
    if s.nonlinear == fv_nonlinear::NonlinearMethod::NewtonKrylov.name() {
        if let Some(list) = v["contacts"].as_array_mut() {
            for c in list {
                c["coupling"] = serde_json::Value::from("newton");
            }
        }
    }
    if !s.coupling_switched.is_empty() {
        v["coupling_switched"] = serde_json::json!(s.coupling_switched);
    }
    if let Some(k) = s.restarted_from {
        v["restarted_from"] = serde_json::json!(k);
    }
    if let Some(sig) = &s.interrupted {
        v["interrupted_by"] = serde_json::Value::String(sig.clone());
    }
    if let Some(reason) = &s.failure {
        v["failure"] = serde_json::Value::String(reason.clone());
    }
    if let Some(times) = &s.profile {
        let mut seconds = serde_json::Map::new();
        for p in crate::profile::Phase::ALL {
            seconds.insert(p.name().to_owned(), serde_json::json!(times.get(p)));
        }
        v["profile_seconds"] = serde_json::Value::Object(seconds);
    }
    let path = dir.join("summary.json");
    let tmp = dir.join("summary.json.tmp");
    std::fs::write(
        &tmp,
        serde_json::to_string_pretty(&v).unwrap_or_default() + "\n",
    )?;
    std::fs::rename(&tmp, &path)?;
    Ok(path)
}

/// Writes `msg` and a newline to standard output. A reader that has gone
/// (`fvc check case.toml | head -3`) is not an error of the run: the line
/// is dropped, where `println!` would panic on the broken pipe.
pub fn stdout_line(msg: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{msg}");
}
