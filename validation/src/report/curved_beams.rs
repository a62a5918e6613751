//! Report section curved-beams (thesis §5.3.3): the reaction on the upper
//! beam's driven ends against the slide for μ = 0, 0.3 and 0.6, the lower
//! beam master, and μ = 0 and 0.3 with the upper beam master, against Neto et
//! al. (2016); acceptance (benchmarks README): peak Fx and Fy within 3 %
//! for each μ, the same whichever beam is master.
use std::path::Path;

use super::plot::{Legend, Plot, Style, BLACK_C, BLUE_C, GREEN_C, ORANGE_C, RED_C};
use super::{
    not_run_row, run_variant, shared_references, table, verdict, Figures, ReportError, Section,
    SectionReport, Status,
};
use crate::benchmarks::curved_beams::{
    neto_peaks, reference_curve, run, CurvedBeams, FULL_SLIDE, TOLERANCE,
};

/// The curved-beams section.
pub struct CurvedBeamsSection;

/// (μ, upper beam master) of the runs.
const RUNS: [(f64, bool); 5] = [
    (0.0, false),
    (0.0, true),
    (0.3, false),
    (0.3, true),
    (0.6, false),
];

/// One run: (μ, upper beam master) and its result.
type Run = ((f64, bool), Result<CurvedBeams, String>);

fn label(mu: f64, upper_master: bool) -> String {
    format!(
        "μ = {mu:.1}, {} beam master",
        if upper_master { "upper" } else { "lower" }
    )
}

/// |F_component| against the slide: Neto et al. and every run.
fn force_plot(component: &str, neto: &[(f64, Vec<(f64, f64)>)], runs: &[Run]) -> Plot {
    let mut plot = Plot::new(
        &format!("curved-beams: |F{component}| on the upper beam's driven ends"),
        "slide (mm)",
        &format!("|F{component}| (N)"),
    );
    plot.x_range = Some((0.0, FULL_SLIDE));
    // room above the curves for the legend, clear of the peaks
    plot.y_range = Some((0.0, if component == "x" { 40.0 } else { 65.0 }));
    plot.legend = Legend::UpperLeft;
    let colours = [BLACK_C, GREEN_C, ORANGE_C];
    for ((mu, points), colour) in neto.iter().zip(colours) {
        plot.add(
            &format!("Neto et al., μ = {mu:.1}"),
            Style::Line(colour),
            points.clone(),
        );
    }
    let markers = [
        Style::Ring(BLUE_C),
        Style::Cross(RED_C),
        Style::Triangle(BLUE_C),
        Style::Ring(RED_C),
        Style::Triangle(RED_C),
    ];
    for (((mu, upper), r), style) in runs.iter().zip(markers) {
        let Ok(r) = r else { continue };
        let f = if component == "x" { &r.fx } else { &r.fy };
        let points = r
            .slide
            .iter()
            .copied()
            .zip(f.iter().map(|v| v.abs()))
            .collect();
        plot.add(&format!("fvcontact, {}", label(*mu, *upper)), style, points);
    }
    plot
}

impl Section for CurvedBeamsSection {
    fn name(&self) -> &'static str {
        "curved-beams"
    }

    fn title(&self) -> &'static str {
        "two elastoplastic curved beams slid past each other (thesis §5.3.3)"
    }

    fn run(&self, out: &Path, log: &mut dyn FnMut(&str)) -> Result<SectionReport, ReportError> {
        let shared = shared_references()?;
        let mut neto = [Vec::new(), Vec::new()];
        for (component, curves) in ["x", "y"].into_iter().zip(&mut neto) {
            for (mu, _, _) in crate::benchmarks::curved_beams::NETO_PEAKS {
                let c = reference_curve(&shared, mu, component).map_err(ReportError::Benchmark)?;
                curves.push((mu, c));
            }
        }
        let mut runs = Vec::new();
        for (mu, upper) in RUNS {
            let result = run_variant(self.name(), &label(mu, upper), log, || {
                Ok(run(mu, FULL_SLIDE, upper))
            });
            runs.push(((mu, upper), result));
        }

        let mut pass = true;
        let mut rows = Vec::new();
        let mut summary = Vec::new();
        for ((mu, upper), result) in &runs {
            let name = label(*mu, *upper);
            let r = match result {
                Ok(r) => r,
                Err(e) => {
                    pass = false;
                    rows.push(not_run_row(&name, e, 5));
                    summary.push(format!("{name}: did not run: {e}"));
                    continue;
                }
            };
            let Some((neto_fx, neto_fy)) = neto_peaks(*mu) else {
                continue;
            };
            let (fx, fy) = (r.fx_peak(), r.fy_peak());
            let (dx, dy) = (fx.0 / neto_fx - 1.0, fy.0 / neto_fy - 1.0);
            let mut missed = Vec::new();
            if let Some(f) = &r.failure {
                missed.push(format!("stopped at {:.1} mm: {f}", r.reached()));
            }
            if !(dx.abs() < TOLERANCE) {
                missed.push(format!("Fx {:+.1} %", 100.0 * dx));
            }
            if !(dy.abs() < TOLERANCE) {
                missed.push(format!("Fy {:+.1} %", 100.0 * dy));
            }
            pass &= missed.is_empty();
            let verdict = verdict(&missed);
            let per_increment = r.cost.outer_iterations as f64 / r.cost.increments.max(1) as f64;
            rows.push(vec![
                name.clone(),
                format!("{:.1}", r.reached()),
                format!("{:.3} at {:.1} mm ({:+.1} %)", fx.0, fx.1, 100.0 * dx),
                format!("{:.3} at {:.1} mm ({:+.1} %)", fy.0, fy.1, 100.0 * dy),
                format!("{per_increment:.0}"),
                format!("{:.0}", r.cost.wall_seconds),
                format!("{:.3}", r.cost.us_per_cell_iteration()),
                verdict.clone(),
            ]);
            summary.push(format!(
                "{name}: peak |Fx| {:.3} N ({:+.1} % of {neto_fx}), |Fy| {:.3} N ({:+.1} % of {neto_fy}), {per_increment:.0} outer iterations per increment, {:.0} s: {}",
                fx.0,
                100.0 * dx,
                fy.0,
                100.0 * dy,
                r.cost.wall_seconds,
                verdict.replace("**", "")
            ));
        }

        let mut figures = Figures::default();
        for (component, curves) in ["x", "y"].into_iter().zip(&neto) {
            figures.add(
                out,
                &format!("curved-beams-f{component}.png"),
                &format!("|F{component}| against the slide"),
                &force_plot(component, curves, &runs),
            )?;
        }

        let mut md = String::new();
        md.push_str(
            "Two half-annuli (E = 689.56 MPa, ν = 0.32, neo-Hookean J2 plasticity, \
             yield 31 MPa, linear hardening 261.2 MPa, updated Lagrangian), the upper one driven 31.5 mm across the \
             lower in 63 increments; 5 × 50 cells per beam, segment-to-segment with \
             implicit coupling, `penalty_scale = 1`, Rhie–Chow 1 \
             (`validation/cases/curved-beams/case.toml`). Reference: Neto et al. \
             (2016) from `../shared/benchmarks/curved-beams/reference`; peaks as \
             quoted by the benchmark table.\n\n",
        );
        md.push_str(&table(
            &[
                "run",
                "reached (mm)",
                "peak Fx magnitude (N)",
                "peak Fy magnitude (N)",
                "outer iterations per increment",
                "wall (s)",
                "µs/cell/outer iteration",
                "result",
            ],
            &rows,
        ));
        md.push_str(&format!(
            "\nLimits (benchmarks README): both peaks within {:.0} % of Neto et al. for \
             each μ, whichever beam is master. Wall time on this machine. A peer code \
             run here on the same 5 × 50 mesh at μ = 0.6 (CalculiX 2.20, quadratic \
             plane-strain elements, finite-strain J2, penalty contact; \
             `validation/cases/curved-beams/calculix_plane_strain.py`) peaks at \
             |Fx| 27.36 N and |Fy| 44.11 N: Fy 3.3 % under Neto et al., as ours is \
             3.6 %; refined to 10 × 100, its forces fall, as ours do.\n\n",
            100.0 * TOLERANCE
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
