//! Report section shallow-ironing (thesis §5.3.2, figs. 5.17–5.19, table
//! 5.2): the reactions H and V on the block top against time, foundation
//! master (as shipped) and block master, against Code_Aster,
//! Fischer–Wriggers, Hartmann–Oliver, Poulios–Renard and Yastrebov;
//! acceptance (benchmarks README): μ_g = H/V at t = 1.5 within [0.30,
//! 0.36] and H free of oscillation above 1 % while sliding.
use std::path::Path;

use super::plot::{Legend, Plot, Style, BLACK_C, BLUE_C, GREEN_C, ORANGE_C, RED_C};
use super::{
    not_run_row, run_variant, shared_references, table, verdict, Figures, ReportError, Section,
    SectionReport, Status,
};
use crate::benchmarks::shallow_ironing::{
    reference_curves, run, Ironing, Options, ReferenceCurve, MU_G_BAND, OSCILLATION_HALF_WINDOW,
    OSCILLATION_INTERVAL, OSCILLATION_LIMIT,
};

/// The shallow-ironing section.
pub struct ShallowIroningSection;

/// One run of the section.
struct Variant {
    label: &'static str,
    opts: Options,
}

fn variants() -> [Variant; 2] {
    [
        Variant {
            label: "foundation master (as shipped)",
            opts: Options::default(),
        },
        Variant {
            label: "block master",
            opts: Options {
                swapped: true,
                ..Options::default()
            },
        },
    ]
}

/// H (`horizontal`) or V against time: the references and every run.
fn force_plot(
    horizontal: bool,
    curves: &[ReferenceCurve],
    runs: &[(&Variant, Result<Ironing, String>)],
) -> Plot {
    let (name, symbol) = if horizontal {
        ("horizontal", "H")
    } else {
        ("vertical", "V")
    };
    let mut plot = Plot::new(
        &format!("shallow-ironing: {name} reaction {symbol} on the block top"),
        "time (indentation 0–1, slide 1–2)",
        &format!("{symbol} (N/mm)"),
    );
    plot.x_range = Some((0.0, 2.0));
    // room above the curves for the legend, top left, where they are low
    plot.y_range = Some(if horizontal {
        (-5.0, 260.0)
    } else {
        (0.0, 600.0)
    });
    plot.legend = Legend::UpperLeft;
    let colours = [BLACK_C, GREEN_C, ORANGE_C, (148, 103, 189), (140, 86, 75)];
    for (c, colour) in curves.iter().zip(colours) {
        let points = if horizontal {
            &c.horizontal
        } else {
            &c.vertical
        };
        plot.add(c.source, Style::Line(colour), points.clone());
    }
    let markers = [Style::Ring(BLUE_C), Style::Cross(RED_C)];
    for ((v, r), style) in runs.iter().zip(markers) {
        let Ok(r) = r else { continue };
        let values = if horizontal {
            &r.horizontal
        } else {
            &r.vertical
        };
        let points = r.time.iter().copied().zip(values.iter().copied()).collect();
        plot.add(&format!("fvcontact, {}", v.label), style, points);
    }
    plot
}

impl Section for ShallowIroningSection {
    fn name(&self) -> &'static str {
        "shallow-ironing"
    }

    fn title(&self) -> &'static str {
        "a rounded block pressed into a foundation and dragged along it (thesis §5.3.2)"
    }

    fn run(&self, out: &Path, log: &mut dyn FnMut(&str)) -> Result<SectionReport, ReportError> {
        let shared = shared_references()?;
        let curves = reference_curves(&shared).map_err(ReportError::Benchmark)?;
        let variants = variants();
        let mut runs = Vec::new();
        for v in &variants {
            let label = format!("{} (about 6–8 min)", v.label);
            let result = run_variant(self.name(), &label, log, || Ok(run(&v.opts)));
            runs.push((v, result));
        }

        let ((t0, t1), half_window) = (OSCILLATION_INTERVAL, OSCILLATION_HALF_WINDOW);
        let mut pass = true;
        let mut rows = Vec::new();
        let mut summary = Vec::new();
        for (v, result) in &runs {
            let r = match result {
                Ok(r) => r,
                Err(e) => {
                    pass = false;
                    rows.push(not_run_row(v.label, e, 6));
                    summary.push(format!("{}: did not run: {e}", v.label));
                    continue;
                }
            };
            let mu_g = r.mu_g(1.5);
            let osc = r.oscillation(t0, t1, half_window);
            let (_, v1) = r.forces_at(1.0);
            let reached = r.time.last().copied().unwrap_or(0.0);
            let mut missed = Vec::new();
            if let Some(f) = &r.failure {
                missed.push(format!("stopped at t = {reached:.3}: {f}"));
            }
            if !(mu_g >= MU_G_BAND.0 && mu_g <= MU_G_BAND.1) {
                missed.push(format!("μ_g {mu_g:.3}"));
            }
            if !(osc < OSCILLATION_LIMIT) {
                missed.push(format!("H oscillates {:.2} %", 100.0 * osc));
            }
            pass &= missed.is_empty();
            let verdict = verdict(&missed);
            rows.push(vec![
                v.label.to_string(),
                format!("{reached:.3}"),
                format!("{v1:.1}"),
                format!("{mu_g:.3}"),
                format!("{:.2}", 100.0 * osc),
                format!(
                    "{:.0} / {:.0}",
                    r.mean_outer(0.0, 1.0),
                    r.mean_outer(1.0, 2.0)
                ),
                format!("{:.0}", r.cost.wall_seconds),
                format!("{:.3}", r.cost.us_per_cell_iteration()),
                verdict.clone(),
            ]);
            summary.push(format!(
                "{}: μ_g(1.5) = {mu_g:.3}, H oscillates {:.2} % over t {t0}–{t1}, V(1) = {v1:.1} N/mm, {:.0} outer iterations per increment while sliding, {:.0} s: {}",
                v.label,
                100.0 * osc,
                r.mean_outer(1.0, 2.0),
                r.cost.wall_seconds,
                verdict.replace("**", "")
            ));
        }
        let mut reference_rows = Vec::new();
        for c in &curves {
            let (h, v) = c.forces_at(1.5);
            let (_, v1) = c.forces_at(0.999);
            reference_rows.push(vec![
                c.source.to_string(),
                format!("{v1:.1}"),
                format!("{h:.1}"),
                format!("{v:.1}"),
                format!("{:.3}", h / v),
            ]);
        }

        let mut figures = Figures::default();
        for (horizontal, file, alt) in [
            (
                true,
                "shallow-ironing-h.png",
                "horizontal reaction against time",
            ),
            (
                false,
                "shallow-ironing-v.png",
                "vertical reaction against time",
            ),
        ] {
            figures.add(out, file, alt, &force_plot(horizontal, &curves, &runs))?;
        }

        let mut md = String::new();
        md.push_str(
            "A block with a rounded bottom (E = 6,896 MPa) pressed 1 mm into a \
             foundation (E = 689.6 MPa) in 100 increments and dragged 10 mm along it \
             in 500, μ = 0.3, neo-Hookean, plane strain, N and mm; segment-to-segment \
             with implicit coupling, `penalty_scale = 4`, Rhie–Chow 0.5 \
             (`validation/cases/shallow-ironing/case.toml`). H and V are the reactions \
             on the block top per mm of thickness. References: the five curves of \
             `../shared/benchmarks/shallow-ironing/reference` (× 100 to N/mm).\n\n",
        );
        md.push_str(&table(
            &[
                "run",
                "reached (t)",
                "V at t = 1 (N/mm)",
                "μ_g = H/V at t = 1.5",
                "oscillation of H (%)",
                "outer iterations per increment (indentation / slide)",
                "wall (s)",
                "µs/cell/outer iteration",
                "result",
            ],
            &rows,
        ));
        md.push_str(&format!(
            "\nLimits (benchmarks README): μ_g within [{:.2}, {:.2}] (thesis table 5.2: \
             0.32); H free of oscillation above {:.0} % while sliding, measured as the \
             largest deviation of H from its centred moving average over {} increments \
             (0.5 mm, five foundation faces), t {t0}–{t1}, relative to its mean. Wall \
             time on this machine.\n\nThe references at the same instants:\n\n",
            MU_G_BAND.0,
            MU_G_BAND.1,
            100.0 * OSCILLATION_LIMIT,
            2 * half_window + 1
        ));
        md.push_str(&table(
            &[
                "reference",
                "V at t = 1 (N/mm)",
                "H at t = 1.5",
                "V at t = 1.5",
                "H/V at t = 1.5",
            ],
            &reference_rows,
        ));
        md.push('\n');
        md.push_str(&figures.markdown);
        Ok(SectionReport {
            markdown: md,
            images: figures.images,
            status: if pass { Status::Pass } else { Status::Fail },
            summary,
        })
    }
}
