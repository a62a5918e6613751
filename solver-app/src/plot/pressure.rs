//! `contact_pressure_<body>-<patch>.png`: the contact pressure on each
//! contact patch against the position along it (see
//! [`patch_geometry`](super::patch_geometry)), at the last increment
//! written to the `.h5`.
//!
//! The patch plotted for a contact pair is its slave patch (the `<slave>`
//! of the history's `<slave>:normal_force` column); when the slave carries
//! no pressure but the master (known from `summary.json`) does, the
//! master. A patch in several pairs is plotted once (the `.h5` holds the
//! pairs' pressures added).
use std::path::Path;

use super::chart::{colour, draw_figure, num, Panel, Series};
use super::data::{self, History, ResultsFolder};
pub use super::patch_geometry::Abscissa;
use super::PlotError;

/// A contact patch to plot.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ContactPatch {
    /// Body name.
    pub body: String,
    /// Patch name.
    pub patch: String,
    /// The pair's history label (`<slave>` or `<slave>@<master>`).
    pub label: String,
    /// The master patch as (body, patch), when known.
    pub master: Option<(String, String)>,
}

fn split_patch(name: &str) -> Option<(String, String)> {
    let (b, p) = name.split_once('/')?;
    Some((b.to_string(), p.to_string()))
}

/// The slave patch of every contact pair in the history's columns, each
/// patch once, with its master from the label or `summary.json`.
pub fn contact_patches(folder: &ResultsFolder, history: &History) -> Vec<ContactPatch> {
    let pairs = folder.contact_pairs();
    let mut out: Vec<ContactPatch> = Vec::new();
    for label in history.contact_labels() {
        let (slave, master) = match label.split_once('@') {
            Some((s, m)) => (s.to_string(), Some(m.to_string())),
            None => (label.clone(), None),
        };
        let master = master.or_else(|| {
            pairs
                .iter()
                .find(|(_, s)| *s == slave)
                .map(|(m, _)| m.clone())
        });
        let Some((body, patch)) = split_patch(&slave) else {
            continue;
        };
        if out.iter().any(|c| c.body == body && c.patch == patch) {
            continue;
        }
        out.push(ContactPatch {
            body,
            patch,
            label,
            master: master.as_deref().and_then(split_patch),
        });
    }
    out
}

/// One face of a patch at one increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacePressure {
    /// Position along the patch (see [`Abscissa`]).
    pub position: f64,
    /// Contact pressure.
    pub pressure: f64,
    /// Face area, current configuration.
    pub area: f64,
    /// Face area, initial configuration.
    pub initial_area: f64,
    /// Face centre, current configuration.
    pub centre: [f64; 3],
}

/// The contact pressure on a patch at one increment, face by face.
#[derive(Debug, Clone)]
pub struct PatchPressure {
    /// Body name.
    pub body: String,
    /// Patch name.
    pub patch: String,
    /// The increment (`/time/<k>`).
    pub increment: usize,
    /// Its time.
    pub time: f64,
    /// What [`FacePressure::position`] measures.
    pub abscissa: Abscissa,
    /// The faces, in the patch's order.
    pub faces: Vec<FacePressure>,
}

/// Area of a planar (or nearly planar) polygon.
fn polygon_area(points: &[[f64; 3]], face: &[usize]) -> f64 {
    let n = face.len() as f64;
    let mut c = [0.0; 3];
    for &p in face {
        for d in 0..3 {
            c[d] += points[p][d] / n;
        }
    }
    let mut s = [0.0; 3];
    for i in 0..face.len() {
        let a = points[face[i]];
        let b = points[face[(i + 1) % face.len()]];
        let (a, b) = (
            [a[0] - c[0], a[1] - c[1], a[2] - c[2]],
            [b[0] - c[0], b[1] - c[1], b[2] - c[2]],
        );
        s[0] += a[1] * b[2] - a[2] * b[1];
        s[1] += a[2] * b[0] - a[0] * b[2];
        s[2] += a[0] * b[1] - a[1] * b[0];
    }
    0.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()
}

impl PatchPressure {
    /// Reads the patch `body/patch` at increment `k` of the `.h5`.
    pub fn read_at(file: &hdf5::File, body: &str, patch: &str, k: usize) -> Result<Self, String> {
        let initial = data::read_rows::<3>(file, &format!("mesh/{body}/points"))?;
        let current = data::read_rows::<3>(file, &format!("time/{k}/{body}/points"))?;
        if current.len() != initial.len() {
            return Err(format!(
                "time/{k}/{body}/points: {} points, the mesh has {}",
                current.len(),
                initial.len()
            ));
        }
        let mp = format!("mesh/{body}/patches/{patch}");
        let offsets = data::read_u64(file, &format!("{mp}/offsets"))?;
        let connectivity = data::read_u64(file, &format!("{mp}/connectivity"))?;
        let faces = data::polygons(&offsets, &connectivity, initial.len())
            .map_err(|e| format!("{mp}: {e}"))?;
        let tp = format!("time/{k}/{body}/{patch}");
        let pressure = data::read_f64(file, &format!("{tp}/contact_pressure"))?;
        let centres = data::read_rows::<3>(file, &format!("{tp}/face_centres"))?;
        if pressure.len() != faces.len() || centres.len() != faces.len() {
            return Err(format!(
                "{tp}: {} pressures and {} centres for {} faces",
                pressure.len(),
                centres.len(),
                faces.len()
            ));
        }
        let time = data::increment_time(file, k).map_err(|e| format!("time/{k}: {e}"))?;
        let area: Vec<f64> = faces.iter().map(|f| polygon_area(&current, f)).collect();
        let (abscissa, position) =
            super::patch_geometry::face_positions(&faces, &current, &centres, &pressure, &area);
        let faces = (0..faces.len())
            .map(|i| FacePressure {
                position: position[i],
                pressure: pressure[i],
                area: area[i],
                initial_area: polygon_area(&initial, &faces[i]),
                centre: centres[i],
            })
            .collect();
        Ok(PatchPressure {
            body: body.to_string(),
            patch: patch.to_string(),
            increment: k,
            time,
            abscissa,
            faces,
        })
    }

    /// Reads the patch at the last increment of the `.h5` that has it
    /// complete (an increment cut short by a killed run is passed over).
    /// `Ok(None)` when no increment has it; `Err` with the last
    /// increment's problem when some have the patch group but none reads.
    pub fn read_last(file: &hdf5::File, body: &str, patch: &str) -> Result<Option<Self>, String> {
        let mut first_err = None;
        for k in data::increments(file).into_iter().rev() {
            if file.group(&format!("time/{k}/{body}/{patch}")).is_err() {
                continue;
            }
            match Self::read_at(file, body, patch, k) {
                Ok(p) => return Ok(Some(p)),
                Err(e) => {
                    first_err.get_or_insert(e);
                }
            }
        }
        match first_err {
            Some(e) => Err(e),
            None => Ok(None),
        }
    }

    /// Σ p A over the faces with the current areas.
    pub fn force(&self) -> f64 {
        self.faces.iter().map(|f| f.pressure * f.area).sum()
    }

    /// Σ p A over the faces with the initial areas (the areas the
    /// small-strain contact force is integrated over).
    pub fn force_initial_areas(&self) -> f64 {
        self.faces.iter().map(|f| f.pressure * f.initial_area).sum()
    }

    /// Whether any face carries pressure.
    pub fn in_contact(&self) -> bool {
        self.faces.iter().any(|f| f.pressure > 0.0)
    }

    /// (position, pressure) sorted by position.
    pub fn profile(&self) -> Vec<(f64, f64)> {
        let mut v: Vec<(f64, f64)> = self
            .faces
            .iter()
            .map(|f| (f.position, f.pressure))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    }

    /// The largest pressure and its position.
    pub fn peak(&self) -> Option<(f64, f64)> {
        self.faces
            .iter()
            .filter(|f| f.pressure.is_finite())
            .max_by(|a, b| a.pressure.total_cmp(&b.pressure))
            .map(|f| (f.pressure, f.position))
    }

    /// Positions of the first and last face centres with pressure.
    pub fn contact_extent(&self) -> Option<(f64, f64)> {
        let pos = self
            .faces
            .iter()
            .filter(|f| f.pressure > 0.0)
            .map(|f| f.position);
        let (lo, hi) = pos.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
        (hi >= lo).then_some((lo, hi))
    }
}

/// Writes the pressure plot of `patch` to `path`; `Ok(Some(note))`, and no
/// file, when the `.h5` has no increment with the patch.
pub fn plot(
    folder: &ResultsFolder,
    history: &History,
    file: &hdf5::File,
    patch: &ContactPatch,
    path: &Path,
) -> Result<Option<String>, PlotError> {
    let read = |b: &str, p: &str| {
        PatchPressure::read_last(file, b, p).map_err(|e| PlotError::read(&folder.h5, e))
    };
    let Some(mut pp) = read(&patch.body, &patch.patch)? else {
        return Ok(Some(format!(
            "{}: no contact fields of {}/{} in any increment; {} left out",
            folder.h5.display(),
            patch.body,
            patch.patch,
            path.file_name().unwrap_or_default().to_string_lossy()
        )));
    };
    let mut side = "slave";
    if !pp.in_contact() {
        if let Some((mb, mp)) = &patch.master {
            if let Some(m) = read(mb, mp)?.filter(PatchPressure::in_contact) {
                pp = m;
                side = "master";
            }
        }
    }
    let profile = pp.profile();
    let all = fit_all(&profile);
    let x_range = match (pp.contact_extent(), pp.abscissa) {
        (None, _) => None,
        (Some((_, hi)), Abscissa::Radius { .. }) => {
            let beyond = next_out(&profile, hi, 1.0).unwrap_or(hi);
            Some((0.0, (1.5 * hi).max(beyond).min(all.1)))
        }
        (Some((lo, hi)), _) => {
            // half the contact width each side, and at least the first
            // face out of contact
            let pad = 0.5 * (hi - lo);
            let before = next_out(&profile, lo, -1.0).unwrap_or(lo);
            let after = next_out(&profile, hi, 1.0).unwrap_or(hi);
            Some((
                (lo - pad).min(before).max(all.0),
                (hi + pad).max(after).min(all.1),
            ))
        }
    };
    let x_range = x_range.map(|(a, b)| {
        let m = 0.02 * (b - a).max(1e-300);
        (a - m, b + m)
    });
    let mut facts = Vec::new();
    if let Some((p, at)) = pp.peak().filter(|p| p.0 > 0.0) {
        facts.push(format!("peak {} at {}", num(p), num_on(at, all.1 - all.0)));
    }
    if let Some((lo, hi)) = pp.contact_extent() {
        let scale = (hi - lo).abs().max(1e-300);
        facts.push(format!(
            "in contact from {} to {}",
            num_on(lo, scale),
            num_on(hi, scale)
        ));
    } else {
        facts.push("no face in contact".into());
    }
    let normal = history
        .column(&format!("{}:normal_force", patch.label))
        .and_then(|v| {
            // the history row of the plotted increment's time
            let t = history.times();
            t.iter()
                .position(|&t| (t - pp.time).abs() <= 1e-9 * pp.time.abs().max(1e-300))
                .map(|i| v[i])
        });
    match (normal, pp.abscissa) {
        (Some(f), Abscissa::Radius { wedge_angle }) if wedge_angle > 0.0 => facts.push(format!(
            "normal force {} ({:.3}° wedge; {} over 360°)",
            num(f),
            wedge_angle.to_degrees(),
            num(f * std::f64::consts::TAU / wedge_angle)
        )),
        (Some(f), _) => facts.push(format!("normal force {}", num(f))),
        (None, _) => {}
    }
    let style_markers_only = pp.abscissa == Abscissa::Distance;
    let mut series = Series::curve(
        format!("contact pressure on {}/{} ({side})", pp.body, pp.patch),
        profile.clone(),
        colour(0),
    );
    series.markers = true;
    series.line = !style_markers_only;
    let title = facts.join("; ");
    let panel = Panel {
        title,
        x_label: pp.abscissa.label().to_string(),
        y_label: "contact pressure (stress unit of the case)".into(),
        series: vec![series],
        x_range,
        y_range: (!pp.in_contact()).then_some((0.0, 1.0)),
        y_zero: true,
        empty_text: (!pp.in_contact()).then(|| "no contact pressure at this increment".into()),
        ..Default::default()
    };
    let n = data::increments(file)
        .last()
        .copied()
        .unwrap_or(pp.increment);
    let caption = format!(
        "{}: contact pressure on {}/{} at t = {} (increment {} of {} written)",
        folder.title,
        pp.body,
        pp.patch,
        num(pp.time),
        pp.increment,
        n
    );
    draw_figure(path, (1200, 760), &caption, &[panel])?;
    Ok(None)
}

/// The extent of the positions.
fn fit_all(profile: &[(f64, f64)]) -> (f64, f64) {
    profile
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            (l.min(p.0), h.max(p.0))
        })
}

/// The position nearest to `from` beyond it in direction `dir` (±1).
fn next_out(profile: &[(f64, f64)], from: f64, dir: f64) -> Option<f64> {
    profile
        .iter()
        .map(|p| p.0)
        .filter(|&x| (x - from) * dir > 0.0)
        .min_by(|a, b| (a - from).abs().total_cmp(&(b - from).abs()))
}

/// A position on an axis of extent `scale`: 0 when within 10⁻⁶ of it.
fn num_on(v: f64, scale: f64) -> String {
    if v.abs() <= 1e-6 * scale.abs() {
        "0".into()
    } else {
        num(v)
    }
}
