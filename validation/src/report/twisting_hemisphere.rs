//! Report section twisting-hemisphere (thesis §5.3.5; Sauer & De Lorenzis
//! 2015): the vertical force F_z and the twisting torque M_z of a hollow
//! neo-Hookean hemisphere pushed 1 mm onto a block and twisted 180° with
//! μ = 0.5, block master (as shipped) and hemisphere master, against
//! Sauer–De Lorenzis and FEBio; acceptance (benchmarks README): the twist
//! completes 180°, the plateau torque within 5 % and F_z within 3 %.
use std::path::Path;

use super::plot::{Legend, Plot, Style, BLACK_C, BLUE_C, GREEN_C, RED_C};
use super::{
    not_run_row, run_variant, shared_references, table, verdict, Figures, ReportError, Section,
    SectionReport, Status,
};
use crate::benchmarks::twisting_hemisphere::{
    angle_of, references, run, Options, ReferenceCurve, References, Twist, FORCE_TOLERANCE,
    TORQUE_TOLERANCE,
};

/// The twisting-hemisphere section.
pub struct TwistingHemisphereSection;

/// End of the case's pseudo-time (indentation 0–1, twist 1–10).
const END: f64 = 10.0;

/// Twist angles (degrees) over which the torque plateau is averaged.
const PLATEAU: (f64, f64) = (120.0, 179.0);

fn label(swapped: bool) -> &'static str {
    if swapped {
        "hemisphere master"
    } else {
        "block master (as shipped)"
    }
}

/// A reference curve against the twist angle, drawn against the pseudo-time.
fn against_time(c: &ReferenceCurve) -> Vec<(f64, f64)> {
    c.points
        .iter()
        .map(|&(deg, v)| (1.0 + deg / 20.0, v))
        .collect()
}

fn plot(torque: bool, refs: &References, runs: &[(bool, Result<Twist, String>)]) -> Plot {
    let (what, unit) = if torque {
        ("twisting torque M_z", "N·mm")
    } else {
        ("vertical force F_z", "N")
    };
    let mut plot = Plot::new(
        &format!("twisting-hemisphere: {what}"),
        "pseudo-time (indentation 0–1, twist 1–10: θ = 20°·(t − 1))",
        &format!("{what} ({unit})"),
    );
    plot.x_range = Some((0.0, END));
    plot.legend = Legend::LowerRight;
    if torque {
        plot.add(
            "Sauer–De Lorenzis",
            Style::Line(BLACK_C),
            against_time(&refs.torque),
        );
        plot.add(
            "FEBio",
            Style::Line(GREEN_C),
            against_time(&refs.torque_febio),
        );
    } else {
        plot.add(
            "Sauer–De Lorenzis",
            Style::Line(BLACK_C),
            against_time(&refs.force),
        );
    }
    for ((swapped, r), style) in runs.iter().zip([Style::Ring(BLUE_C), Style::Cross(RED_C)]) {
        let Ok(r) = r else { continue };
        let values = if torque { &r.torque } else { &r.force };
        let points = r
            .time
            .iter()
            .copied()
            .zip(values.iter().map(|v| v.abs()))
            .collect();
        plot.add(&format!("fvcontact, {}", label(*swapped)), style, points);
    }
    plot
}

impl Section for TwistingHemisphereSection {
    fn name(&self) -> &'static str {
        "twisting-hemisphere"
    }

    fn title(&self) -> &'static str {
        "a hollow hemisphere pressed onto a block and twisted 180° (thesis §5.3.5)"
    }

    fn run(&self, out: &Path, log: &mut dyn FnMut(&str)) -> Result<SectionReport, ReportError> {
        let shared = shared_references()?;
        let refs = references(&shared).map_err(ReportError::Benchmark)?;
        let mut runs = Vec::new();
        for swapped in [false, true] {
            let opts = Options {
                swapped,
                ..Options::default()
            };
            let result = run_variant(self.name(), label(swapped), log, || {
                run(Some(&shared), &opts)
            });
            runs.push((swapped, result));
        }

        let plateau_ref = refs.torque.mean(PLATEAU.0, PLATEAU.1);
        let mut pass = true;
        let mut rows = Vec::new();
        let mut summary = Vec::new();
        for (swapped, result) in &runs {
            let name = label(*swapped);
            let r = match result {
                Ok(r) => r,
                Err(e) => {
                    pass = false;
                    rows.push(not_run_row(name, e, 6));
                    summary.push(format!("{name}: did not run: {e}"));
                    continue;
                }
            };
            let reached = r.reached();
            let mut missed = Vec::new();
            if (reached - END).abs() > 1e-6 {
                missed.push(if reached < 1.0 {
                    format!("stopped in the indentation at t = {reached:.3}")
                } else {
                    format!("stopped at θ = {:.1}°", angle_of(reached))
                });
            }
            // F_z at every increment of the twist, the worst
            let (_, force_error) = r.worst_force_error(&refs.force);
            let n = 30;
            let plateau = (0..=n)
                .map(|i| r.at_angle(PLATEAU.0 + 2.0 * i as f64).1.abs())
                .sum::<f64>()
                / (n + 1) as f64;
            let torque_error = plateau / plateau_ref - 1.0;
            // (NaN where the run stopped before the angle: reported above)
            if missed.is_empty() && !(force_error.is_finite() && torque_error.is_finite()) {
                missed.push("F_z or torque not finite".into());
            }
            if force_error.abs() >= FORCE_TOLERANCE {
                missed.push(format!("F_z {:+.1} %", 100.0 * force_error));
            }
            if torque_error.abs() >= TORQUE_TOLERANCE {
                missed.push(format!("torque {:+.1} %", 100.0 * torque_error));
            }
            pass &= missed.is_empty();
            let verdict = verdict(&missed);
            let percent = |e: f64| {
                if e.is_finite() {
                    format!("{:+.1}", 100.0 * e)
                } else {
                    "—".to_string()
                }
            };
            let (f_end, _) = r.at_time(reached);
            rows.push(vec![
                name.to_string(),
                format!("{reached:.3}"),
                format!("{:.1}", angle_of(reached)),
                format!("{f_end:.3}"),
                percent(force_error),
                percent(torque_error),
                format!(
                    "{:.0}",
                    r.cost.outer_iterations as f64 / r.time.len().max(1) as f64
                ),
                format!("{:.0}", r.cost.wall_seconds),
                verdict.clone(),
            ]);
            summary.push(format!(
                "{name}: reached t = {reached:.3} (θ = {:.1}°), F_z there {f_end:.3} N, F_z worst over the twist {} %, plateau torque {} %, {:.0} s: {}",
                angle_of(reached),
                percent(force_error),
                percent(torque_error),
                r.cost.wall_seconds,
                verdict.replace("**", "")
            ));
        }

        let mut figures = Figures::default();
        for (torque, file, alt) in [
            (
                false,
                "twisting-hemisphere-force.png",
                "vertical force against pseudo-time",
            ),
            (
                true,
                "twisting-hemisphere-torque.png",
                "torque against pseudo-time",
            ),
        ] {
            figures.add(out, file, alt, &plot(torque, &refs, &runs))?;
        }

        let mut md = String::new();
        md.push_str(
            "A hollow neo-Hookean hemisphere pushed 1 mm onto a block without friction \
             (pseudo-time 0–1, 10 increments), then twisted 180° about the vertical axis \
             with μ = 0.5 (1–10, 90 increments); generated meshes, implicit coupling, \
             `penalty_scale = 1`, the Rhie–Chow stabilisation (α_RC = 0.2) of the \
             accumulated displacement \
             (`validation/cases/twisting-hemisphere/case.toml`). References: Sauer–De \
             Lorenzis (2015) F_z and M_z (stored × 1/10) and FEBio's M_z, from \
             `../shared/benchmarks/twisting-hemisphere/reference`.\n\n",
        );
        md.push_str(&table(
            &[
                "run",
                "reached (t)",
                "reached (θ, °)",
                "F_z there (N)",
                "worst F_z over the twist (%)",
                &format!("plateau torque {}–{}° (%)", PLATEAU.0, PLATEAU.1),
                "outer iterations per increment",
                "wall (s)",
                "result",
            ],
            &rows,
        ));
        md.push_str(&format!(
            "\nLimits (benchmarks README): the twist completes 180°; the plateau torque \
             within {:.0} % and F_z within {:.0} % of Sauer–De Lorenzis (—: not reached). \
             Wall time on this machine.\n\n",
            100.0 * TORQUE_TOLERANCE,
            100.0 * FORCE_TOLERANCE
        ));
        md.push_str(&figures.markdown);
        Ok(SectionReport {
            markdown: md,
            images: figures.images,
            status: if pass { Status::Pass } else { Status::Fail },
            summary,
        })
    }
}
