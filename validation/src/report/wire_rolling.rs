//! Report section wire-rolling (thesis §5.4.2): the roll's vertical force
//! and its torque against time on the coarse wire, with the slab-method
//! band of the steady force; acceptance: the run completes, the force is
//! steady (within 2 % of its mean from 0.021 s) and within the slab band.
use std::path::Path;

use super::field_map::{render_field_map_png, FieldMap};
use super::plot::{render_png, Legend, Plot, Style, BLACK_C, BLUE_C, GREEN_C, RED_C};
use super::{
    not_run_row, run_variant, table, verdict, ReportError, Section, SectionReport, Status,
};
use crate::benchmarks::steady_mean;
use crate::benchmarks::wire_rolling::{run_edited, slab_pressure_band, RollingRun, STEADY_FROM};

/// The wire-rolling section.
pub struct WireRollingSection;

/// One quantity of the run against time.
fn history_plot(r: &RollingRun, what: &str, unit: &str, values: &[f64], style: Style) -> Plot {
    let mut plot = Plot::new(
        &format!("wire-rolling: roll {what} on the quarter"),
        "time (s)",
        &format!("{what} ({unit})"),
    );
    plot.legend = Legend::LowerRight;
    let points = r.time.iter().copied().zip(values.iter().copied()).collect();
    plot.add("fvcontact, coarse wire", style, points);
    plot
}

fn plots(r: &RollingRun, band: (f64, f64), area: f64) -> (Plot, Plot) {
    let end = r.time.last().copied().unwrap_or(0.056);
    let mut force = history_plot(r, "force", "N", &r.force, Style::Line(BLUE_C));
    for (p, label, colour) in [
        (band.0, "slab, free spread", GREEN_C),
        (band.1, "slab, plane strain", BLACK_C),
    ] {
        force.add(
            &format!("{label} × computed area ({:.0} N)", p * area),
            Style::Line(colour),
            vec![(STEADY_FROM, p * area), (end, p * area)],
        );
    }
    let torque = history_plot(r, "torque", "N mm", &r.torque, Style::Line(RED_C));
    (force, torque)
}

/// The contact pressure over the wire's contact patch (the horse-shoe)
/// and the plastic strain over a cut through the rolled wire (the
/// blacksmith's cross), at the end of the run.
fn maps(r: &RollingRun) -> (FieldMap, FieldMap) {
    let patch = FieldMap {
        title: "wire-rolling: contact pressure on the wire (top view)".into(),
        x_label: "x, along the wire (mm)".into(),
        y_label: "z, across (mm)".into(),
        value_label: "p (MPa)".into(),
        polygons: r.contact_patch.clone(),
        width: 1000,
    };
    let cut = FieldMap {
        title: format!(
            "wire-rolling: plastic strain on a cut at x = {:.1} mm",
            r.section_x
        ),
        x_label: "z, across (mm)".into(),
        y_label: "y, towards the roll (mm)".into(),
        value_label: "ε_p".into(),
        polygons: r.section.clone(),
        width: 800,
    };
    (patch, cut)
}

impl Section for WireRollingSection {
    fn name(&self) -> &'static str {
        "wire-rolling"
    }

    fn title(&self) -> &'static str {
        "a J2-plastic wire rolled between flat rolls (thesis §5.4.2)"
    }

    fn run(&self, out: &Path, log: &mut dyn FnMut(&str)) -> Result<SectionReport, ReportError> {
        let name = "coarse (20,160 wire cells)";
        let r = match run_variant(self.name(), name, log, || {
            Ok(run_edited("case.toml", |t| t))
        }) {
            Ok(r) => r,
            Err(e) => {
                return Ok(SectionReport {
                    markdown: table(&["wire mesh", "result"], &[not_run_row(name, &e, 0)]),
                    images: Vec::new(),
                    status: Status::Fail,
                    summary: vec![format!("{name}: did not run: {e}")],
                })
            }
        };
        let band = slab_pressure_band();
        let mut missed = Vec::new();
        if !r.converged {
            missed.push(format!(
                "stopped: {}",
                r.failure.clone().unwrap_or_default()
            ));
        }
        let steady = |v: &[f64]| steady_mean(&r.time, v, STEADY_FROM);
        let (force, torque, area) =
            match (steady(&r.force), steady(&r.torque), steady(&r.contact_area)) {
                (Some(f), Some(t), Some(a)) => (f, t, a.0),
                _ => {
                    missed.push("steady window not reached".into());
                    ((f64::NAN, f64::NAN), (f64::NAN, f64::NAN), f64::NAN)
                }
            };
        let pressure = force.0 / area;
        if !(force.1 < 0.02) {
            missed.push(format!("force not steady (±{:.1} %)", 100.0 * force.1));
        }
        if !(pressure > 0.97 * band.0 && pressure < 1.03 * band.1) {
            missed.push(format!(
                "mean pressure {pressure:.0} MPa outside the slab band"
            ));
        }
        let pass = missed.is_empty();
        let verdict = verdict(&missed);
        let per_increment = r.cost.outer_iterations as f64 / r.cost.increments.max(1) as f64;
        let row = vec![
            name.to_string(),
            format!("{:.0} (±{:.2} %)", force.0, 100.0 * force.1),
            format!("{:.0} (±{:.2} %)", torque.0, 100.0 * torque.1),
            format!("{pressure:.0} ({:.0}–{:.0})", band.0, band.1),
            format!("{per_increment:.1}"),
            format!("{:.0}", r.cost.wall_seconds),
            verdict.clone(),
        ];
        let (fp, tp) = plots(&r, band, area);
        let (ff, tf) = ("wire-rolling-force.png", "wire-rolling-torque.png");
        render_png(&fp, &out.join(ff))?;
        render_png(&tp, &out.join(tf))?;
        let (patch, cut) = maps(&r);
        let (pf, cf) = (
            "wire-rolling-pressure.png",
            "wire-rolling-plastic-strain.png",
        );
        render_field_map_png(&patch, &out.join(pf))?;
        render_field_map_png(&cut, &out.join(cf))?;
        let peak = r
            .contact_patch
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or((f64::NAN, f64::NAN), |(c, p)| {
                (*p, c.iter().map(|q| q.1).sum::<f64>() / c.len() as f64)
            });
        let strain = |pick: fn(f64, f64) -> bool| {
            r.section
                .iter()
                .filter(|(c, _)| {
                    let (z, y) = c.iter().fold((0.0, 0.0), |a, q| (a.0 + q.0, a.1 + q.1));
                    pick(z / c.len() as f64, y / c.len() as f64)
                })
                .map(|(_, e)| *e)
                .fold(f64::NAN, f64::max)
        };
        let mut md = String::from(
            "A quarter of a Ø2.7 mm steel wire (neo-Hookean J2 plasticity, E = 210 GPa, \
             the thesis's hardening table from 1.3 GPa) rolled between flat neo-Hookean \
             rolls (radii 60/89 mm, 60 rpm, μ = 0.1) to a gap of 1.89 mm; the roll closes \
             and speeds up over 40 increments, then turns 0.126° per increment \
             (`validation/cases/wire-rolling/case.toml`). The thesis gives the force and \
             torque as plots only; the check is a slab-method band of the mean roll \
             pressure (README.md of the case: Q σ̄ for free spread, 1.155 Q σ̄ for plane \
             strain) on the computed contact area.\n\n",
        );
        md.push_str(&table(
            &[
                "wire mesh",
                &format!("steady force from {STEADY_FROM} s (N)"),
                "steady torque (N mm)",
                "mean pressure (slab band), MPa",
                "Newton iterations per increment",
                "wall (s)",
                "result",
            ],
            &[row],
        ));
        md.push_str(&format!(
            "\n![roll force against time]({ff})\n\n![roll torque against time]({tf})\n\n"
        ));
        md.push_str(&format!(
            "At the end of the run: the contact pressure over the wire's contact \
             patch (the thesis's horse-shoe, fig. 5.41; peak {:.0} MPa at z = {:.2} mm) \
             and the equivalent plastic strain over a cut through the rolled wire \
             (the blacksmith's cross, fig. 5.42; largest {:.3} near the axis, where \
             the cross meets, against {:.3} at the free side z > 1 mm).\n\n\
             ![contact pressure on the wire]({pf})\n\n![plastic strain on a cut]({cf})\n\n",
            peak.0,
            peak.1,
            strain(|z, y| z < 0.3 && y < 0.3),
            strain(|z, _| z > 1.0),
        ));
        Ok(SectionReport {
            markdown: md,
            images: vec![out.join(ff), out.join(tf), out.join(pf), out.join(cf)],
            status: if pass { Status::Pass } else { Status::Fail },
            summary: vec![format!(
                "{name}: force {:.0} N, torque {:.0} N mm, mean pressure {pressure:.0} MPa (slab {:.0}–{:.0}), {per_increment:.1} iterations per increment, {:.0} s: {}",
                force.0,
                torque.0,
                band.0,
                band.1,
                r.cost.wall_seconds,
                verdict.replace("**", "")
            )],
        })
    }
}
