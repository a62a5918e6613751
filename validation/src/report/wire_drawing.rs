//! Report section wire-drawing (thesis §5.4.1): the drawing force of a
//! J2-plastic wire drawn through an elastic die against time, on the
//! coarse and the medium wire, against the thesis's force on the mesh of
//! the same size and its Richardson extrapolation; acceptance (issue 43):
//! each mesh's steady force between 282.8 N and the thesis's force on its
//! mesh, the coarse force's oscillation under the thesis's 1.8 %.
use std::path::Path;

use super::plot::{render_png, Legend, Plot, Style, BLACK_C, BLUE_C, GREEN_C, RED_C};
use super::{
    not_run_row, run_variant, table, verdict, ReportError, Section, SectionReport, Status,
};
use crate::benchmarks::wire_drawing::{
    richardson, run, WireMesh, WireRun, STEADY_FROM, THESIS_FORCES, THESIS_OSCILLATION,
    THESIS_RICHARDSON,
};

/// The wire-drawing section.
pub struct WireDrawingSection;

const MESHES: [(WireMesh, &str, usize); 2] = [
    (WireMesh::Coarse, "coarse (2,400 wire cells)", 0),
    (WireMesh::Medium, "medium (19,200)", 1),
];

type Runs = Vec<(usize, Result<WireRun, String>)>;

fn force_plot(runs: &Runs) -> Plot {
    let mut plot = Plot::new(
        "wire-drawing: drawing force on the quarter",
        "time (s)",
        "force (N)",
    );
    plot.x_range = Some((0.0, 0.1));
    plot.legend = Legend::LowerRight;
    plot.add(
        "thesis, Richardson extrapolation (282.8 N)",
        Style::Line(BLACK_C),
        vec![(0.0, THESIS_RICHARDSON), (0.1, THESIS_RICHARDSON)],
    );
    for (k, style) in [(0, Style::Line(BLUE_C)), (1, Style::Line(RED_C))] {
        let (n, f) = THESIS_FORCES[k];
        plot.add(
            &format!("thesis, {n} cells ({f} N)"),
            style,
            vec![(STEADY_FROM, f), (0.1, f)],
        );
    }
    for ((i, r), style) in runs.iter().zip([Style::Ring(BLUE_C), Style::Cross(RED_C)]) {
        let Ok(r) = r else { continue };
        let points = r
            .time
            .iter()
            .copied()
            .zip(r.force.iter().copied())
            .collect();
        plot.add(&format!("fvcontact, {}", MESHES[*i].1), style, points);
    }
    plot.add(
        "steady window",
        Style::Line(GREEN_C),
        vec![(STEADY_FROM, 250.0), (STEADY_FROM, 320.0)],
    );
    plot
}

impl Section for WireDrawingSection {
    fn name(&self) -> &'static str {
        "wire-drawing"
    }

    fn title(&self) -> &'static str {
        "a J2-plastic wire drawn through an elastic die (thesis §5.4.1)"
    }

    fn run(&self, out: &Path, log: &mut dyn FnMut(&str)) -> Result<SectionReport, ReportError> {
        let mut runs: Runs = Vec::new();
        for (i, (mesh, name, _)) in MESHES.iter().enumerate() {
            runs.push((i, run_variant(self.name(), name, log, || Ok(run(*mesh)))));
        }
        let mut pass = true;
        let (mut rows, mut summary, mut means) = (Vec::new(), Vec::new(), Vec::new());
        for (i, result) in &runs {
            let (_, name, thesis_index) = MESHES[*i];
            let thesis = THESIS_FORCES[thesis_index].1;
            let r = match result {
                Ok(r) if r.converged => r,
                Ok(r) => {
                    pass = false;
                    let e = r.failure.clone().unwrap_or_default();
                    rows.push(not_run_row(name, &e, 5));
                    summary.push(format!("{name}: stopped: {e}"));
                    continue;
                }
                Err(e) => {
                    pass = false;
                    rows.push(not_run_row(name, e, 5));
                    summary.push(format!("{name}: did not run: {e}"));
                    continue;
                }
            };
            let mut missed = Vec::new();
            let cell = match r.steady() {
                Some((mean, dev)) => {
                    means.push(mean);
                    if !(mean > THESIS_RICHARDSON && mean < thesis) {
                        missed.push(format!(
                            "{mean:.1} N outside ({THESIS_RICHARDSON}, {thesis})"
                        ));
                    }
                    if *i == 0 && !(dev < THESIS_OSCILLATION) {
                        missed.push(format!("oscillation {:.2} %", 100.0 * dev));
                    }
                    format!(
                        "{mean:.1} (thesis {thesis}), deviation {:.2} %",
                        100.0 * dev
                    )
                }
                None => {
                    missed.push("steady window not reached".into());
                    "—".into()
                }
            };
            pass &= missed.is_empty();
            let verdict = verdict(&missed);
            let per_increment = r.cost.outer_iterations as f64 / r.cost.increments.max(1) as f64;
            rows.push(vec![
                name.to_string(),
                cell.clone(),
                format!("{per_increment:.1}"),
                format!("{:.0}", r.cost.wall_seconds),
                format!("{:.2}", r.cost.us_per_cell_iteration()),
                verdict.clone(),
            ]);
            summary.push(format!(
                "{name}: steady force from {STEADY_FROM} s {cell}, {per_increment:.1} iterations per increment, {:.0} s: {}",
                r.cost.wall_seconds,
                verdict.replace("**", "")
            ));
        }
        let file = "wire-drawing-force.png";
        let path = out.join(file);
        render_png(&force_plot(&runs), &path)?;

        let mut md = String::from(
            "A quarter of a Ø2 mm steel wire (neo-Hookean J2 plasticity, E = 190 GPa, \
             σ_Y = 0.85 GPa, H' = 0.5 GPa) drawn 8.3 mm in 100 increments through an \
             elastic die (E = 600 GPa) to Ø1.72 mm, μ = 0.08, 10 MPa back tension, with \
             the default solver settings (`validation/cases/wire-drawing/case.toml` and \
             `medium.toml`). The force is the axial reaction on the pulled end of the \
             quarter. Reference: the thesis's force on its mesh of the same size and \
             its Richardson extrapolation, 282.8 N.\n\n",
        );
        md.push_str(&table(
            &[
                "wire mesh",
                &format!("steady force from {STEADY_FROM} s (N)"),
                "iterations per increment",
                "wall (s)",
                "µs/cell/iteration",
                "result",
            ],
            &rows,
        ));
        if let [coarse, medium] = means[..] {
            md.push_str(&format!(
                "\nRichardson extrapolation (order 2, the thesis's) from the two: {:.1} N \
                 ({:+.1} % against 282.8 N; the thesis's own coarse and medium give {:.1} N).\n",
                richardson(coarse, medium, 2.0),
                100.0 * (richardson(coarse, medium, 2.0) / THESIS_RICHARDSON - 1.0),
                richardson(THESIS_FORCES[0].1, THESIS_FORCES[1].1, 2.0)
            ));
        }
        md.push_str(&format!(
            "\nLimits (issue 43): each mesh's steady force between 282.8 N and the \
             thesis's force on its mesh; the coarse force within {:.1} % of its mean. \
             Wall time on this machine.\n\n![drawing force against time]({file})\n\n",
            100.0 * THESIS_OSCILLATION
        ));
        Ok(SectionReport {
            markdown: md,
            images: vec![path],
            status: if pass { Status::Pass } else { Status::Fail },
            summary,
        })
    }
}
