//! The validation report: runs the benchmarks of
//! `../shared/benchmarks/README.md` that the project supports and writes a
//! markdown file with error tables and PNG plots
//! (`cargo run --release -p validation -- report`).
//!
//! Each benchmark is a [`Section`] in its own file; [`sections`] lists them.
//! A new benchmark is one file implementing [`Section`] and one line in
//! [`sections`].
pub mod concentric_cylinders;
pub mod concentric_spheres;
pub mod curved_beams;
pub mod die_drawing;
pub mod field_map;
pub mod flat_punch;
pub mod hertz_cylinder;
pub mod nafems_punch;
pub mod plot;
pub mod shallow_ironing;
pub mod sphere_block;
pub mod strand_compacting;
pub mod twisting_hemisphere;
pub mod wire_drawing;
pub mod wire_rolling;

use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Every section of the report, in report order.
pub fn sections() -> Vec<Box<dyn Section>> {
    vec![
        Box::new(hertz_cylinder::HertzCylinderSection),
        Box::new(flat_punch::FlatPunchSection),
        Box::new(concentric_cylinders::ConcentricCylindersSection),
        Box::new(nafems_punch::NafemsPunchSection),
        Box::new(nafems_punch::NafemsPunchModifiedSection),
        Box::new(sphere_block::SphereBlockSection),
        // large deformation, in the thesis's order (§5.3.1–5.3.5)
        Box::new(die_drawing::DieDrawingSection),
        Box::new(shallow_ironing::ShallowIroningSection),
        Box::new(curved_beams::CurvedBeamsSection),
        Box::new(concentric_spheres::ConcentricSpheresSection),
        Box::new(twisting_hemisphere::TwistingHemisphereSection),
        // industrial (§5.4)
        Box::new(wire_drawing::WireDrawingSection),
        Box::new(wire_rolling::WireRollingSection),
        Box::new(strand_compacting::StrandCompactingSection),
        // one line per benchmark section
    ]
}

/// Names of every section ([`Section::name`]), for `--only`.
pub fn names() -> Vec<&'static str> {
    sections().iter().map(|s| s.name()).collect()
}

/// One benchmark's part of the report.
pub trait Section {
    /// Benchmark id as in `../shared/benchmarks/README.md`, e.g. `hertz-cylinder`.
    fn name(&self) -> &'static str;
    /// Heading text after the id.
    fn title(&self) -> &'static str;
    /// Runs the benchmark, writes its images into `out` and returns its
    /// markdown. `log` takes progress lines for the terminal.
    ///
    /// A failed acceptance check is `Ok` with [`Status::Fail`]; `Err` (or a
    /// panic, which the caller catches) means the benchmark did not run.
    fn run(&self, out: &Path, log: &mut dyn FnMut(&str)) -> Result<SectionReport, ReportError>;
}

/// Whether a section met its acceptance limits.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Status {
    /// Ran and met every limit.
    Pass,
    /// Ran (perhaps partly) and missed a limit, or a run failed.
    Fail,
    /// Did not run; the message says why.
    Error(String),
}

impl Status {
    /// `PASS`, `FAIL` or `ERROR`.
    pub fn word(&self) -> &'static str {
        match self {
            Status::Pass => "PASS",
            Status::Fail => "FAIL",
            Status::Error(_) => "ERROR",
        }
    }
}

/// What a section produced.
#[derive(Debug, Clone)]
pub struct SectionReport {
    /// Markdown body (without the section heading); images linked by file name.
    pub markdown: String,
    /// Image files written into the output folder.
    pub images: Vec<PathBuf>,
    /// Pass or fail.
    pub status: Status,
    /// Key figures, one line each, printed on the terminal.
    pub summary: Vec<String>,
}

/// Errors of the report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// The output folder cannot be made or written.
    #[error("output {path}: {message}")]
    Output {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// A plot could not be drawn.
    #[error("plot {path}: {message}")]
    Plot {
        /// The image file.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// A benchmark did not run.
    #[error("{0}")]
    Benchmark(String),
    /// `--only` named no known section.
    #[error("unknown benchmark `{name}`; valid: {valid}")]
    UnknownSection {
        /// The name given.
        name: String,
        /// The valid names, comma-separated.
        valid: String,
    },
}

/// What to run and where to write.
#[derive(Debug, Clone)]
pub struct ReportOptions {
    /// Output folder (made if missing).
    pub output: PathBuf,
    /// Section names to run; empty runs all.
    pub only: Vec<String>,
}

/// One section's outcome.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Section name.
    pub name: &'static str,
    /// Pass, fail or error.
    pub status: Status,
    /// Key figures (see [`SectionReport::summary`]).
    pub summary: Vec<String>,
    /// Wall time of the section, s.
    pub seconds: f64,
}

/// What [`write_report`] wrote.
#[derive(Debug, Clone)]
pub struct Written {
    /// `report.md`.
    pub markdown: PathBuf,
    /// Every image.
    pub images: Vec<PathBuf>,
    /// Per section.
    pub outcomes: Vec<Outcome>,
}

impl Written {
    /// Whether every section passed.
    pub fn all_passed(&self) -> bool {
        self.outcomes.iter().all(|o| o.status == Status::Pass)
    }
}

/// `../shared` for a section that reads its reference curves from there.
pub fn shared_references() -> Result<PathBuf, ReportError> {
    crate::shared_dir().ok_or_else(|| {
        ReportError::Benchmark("../shared is absent (the reference curves live there)".into())
    })
}

/// Runs one variant of section `section` under [`guarded`], logging its
/// start and, if it did not run, why.
pub fn run_variant<T>(
    section: &str,
    label: &str,
    log: &mut dyn FnMut(&str),
    f: impl FnOnce() -> Result<T, String>,
) -> Result<T, String> {
    log(&format!("{section}: {label}"));
    let result = guarded(f).and_then(|r| r);
    if let Err(e) = &result {
        log(&format!("{section}: {label}: {e}"));
    }
    result
}

/// The table row of a run that did not run: its label, the message,
/// `blank` empty cells and FAIL.
pub fn not_run_row(label: &str, error: &str, blank: usize) -> Vec<String> {
    let mut row = vec![
        label.to_string(),
        format!("did not run: {}", error.replace('|', "/")),
    ];
    row.extend(std::iter::repeat_n(String::new(), blank));
    row.push("**FAIL**".to_string());
    row
}

/// The PNG plots of a section and the markdown lines that show them.
#[derive(Debug, Default)]
pub struct Figures {
    /// The files written.
    pub images: Vec<PathBuf>,
    /// One image line per plot.
    pub markdown: String,
}

impl Figures {
    /// Renders `plot` into `out/file` and adds it with the caption `alt`.
    pub fn add(
        &mut self,
        out: &Path,
        file: &str,
        alt: &str,
        plot: &plot::Plot,
    ) -> Result<(), ReportError> {
        let path = out.join(file);
        plot::render_png(plot, &path)?;
        self.markdown.push_str(&format!("![{alt}]({file})\n\n"));
        self.images.push(path);
        Ok(())
    }
}

/// PASS, or FAIL with the limits a run missed.
pub fn verdict(missed: &[String]) -> String {
    if missed.is_empty() {
        "PASS".to_string()
    } else {
        format!("**FAIL** ({})", missed.join(", ").replace('|', "/"))
    }
}

/// Runs `f`, turning a panic into `Err` with its message.
pub fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "panicked".to_string())
    })
}

/// Checks the `--only` names against [`names`].
pub fn select(only: &[String]) -> Result<Vec<Box<dyn Section>>, ReportError> {
    let all = sections();
    if let Some(bad) = only
        .iter()
        .find(|n| !all.iter().any(|s| s.name() == n.as_str()))
    {
        return Err(ReportError::UnknownSection {
            name: bad.clone(),
            valid: names().join(", "),
        });
    }
    Ok(all
        .into_iter()
        .filter(|s| only.is_empty() || only.iter().any(|n| n == s.name()))
        .collect())
}

/// Makes the output folder, runs the selected sections and writes
/// `report.md`. A section that fails or panics is shown in the report as
/// such; only a bad `--only` name or an unwritable output folder is `Err`.
pub fn write_report(
    opts: &ReportOptions,
    log: &mut dyn FnMut(&str),
) -> Result<Written, ReportError> {
    let chosen = select(&opts.only)?;
    write_sections(&chosen, &opts.output, log)
}

/// [`write_report`] for a given list of sections.
pub fn write_sections(
    chosen: &[Box<dyn Section>],
    out: &Path,
    log: &mut dyn FnMut(&str),
) -> Result<Written, ReportError> {
    let out_err = |path: &Path, e: &dyn std::fmt::Display| ReportError::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(out).map_err(|e| out_err(out, &e))?;
    // fail now rather than after minutes of solving
    let md_path = out.join("report.md");
    std::fs::write(&md_path, "# fvcontact validation report\n\n(running…)\n")
        .map_err(|e| out_err(&md_path, &e))?;

    let mut bodies = Vec::new();
    let mut images = Vec::new();
    let mut outcomes = Vec::new();
    for s in chosen {
        log(&format!("{}: running", s.name()));
        let start = Instant::now();
        let result = guarded(|| s.run(out, log));
        let seconds = start.elapsed().as_secs_f64();
        let (status, summary, body) = match result {
            Ok(Ok(r)) => {
                images.extend(r.images);
                (r.status, r.summary, r.markdown)
            }
            Ok(Err(e)) => {
                let m = e.to_string();
                let body = format!("**Did not run:** {m}\n");
                (Status::Error(m), Vec::new(), body)
            }
            Err(panic) => {
                let body = format!("**Did not run** (panicked): {panic}\n");
                (Status::Error(panic), Vec::new(), body)
            }
        };
        log(&format!(
            "{}: {} in {seconds:.1} s",
            s.name(),
            status.word()
        ));
        bodies.push(format!(
            "## {} — {}\n\n**{}** (section wall time {seconds:.1} s)\n\n{body}",
            s.name(),
            s.title(),
            status.word()
        ));
        outcomes.push(Outcome {
            name: s.name(),
            status,
            summary,
            seconds,
        });
    }

    let mut md = String::new();
    md.push_str("# fvcontact validation report\n\n");
    md.push_str(
        "Written by `cargo run --release -p validation -- report`: the benchmarks of \
         `../shared/benchmarks/README.md` that the project supports, run from the case \
         files in `validation/cases/`, against their analytical or reference solutions.\n\n",
    );
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let _ = writeln!(
        md,
        "fvcontact {}, {} hardware threads.\n",
        env!("CARGO_PKG_VERSION"),
        threads
    );
    md.push_str("| benchmark | result | wall (s) |\n|---|---|---|\n");
    for o in &outcomes {
        let _ = writeln!(
            md,
            "| {} | {} | {:.1} |",
            o.name,
            o.status.word(),
            o.seconds
        );
    }
    md.push('\n');
    for b in bodies {
        md.push_str(&b);
        if !md.ends_with("\n\n") {
            md.push('\n');
        }
    }
    std::fs::write(&md_path, md).map_err(|e| out_err(&md_path, &e))?;
    Ok(Written {
        markdown: md_path,
        images,
        outcomes,
    })
}

/// A markdown table from a header and rows of cells.
pub fn table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "| {} |", header.join(" | "));
    let _ = writeln!(t, "|{}", "---|".repeat(header.len()));
    for r in rows {
        let _ = writeln!(t, "| {} |", r.join(" | "));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_section_lists_the_valid_names() {
        let err = select(&["no-such".to_string()]).err().expect("rejected");
        let msg = err.to_string();
        assert!(
            msg.contains("no-such") && msg.contains("hertz-cylinder"),
            "{msg}"
        );
        assert_eq!(select(&[]).map(|s| s.len()).ok(), Some(sections().len()));
    }

    #[test]
    fn names_are_unique() {
        let mut n = names();
        n.sort_unstable();
        n.dedup();
        assert_eq!(n.len(), sections().len());
    }

    #[test]
    fn panics_become_messages() {
        assert_eq!(guarded(|| 3), Ok(3));
        let r: Result<(), String> = guarded(|| panic!("boom {}", 1));
        assert_eq!(r, Err("boom 1".to_string()));
    }

    struct Fake(&'static str, u8);

    impl Section for Fake {
        fn name(&self) -> &'static str {
            self.0
        }
        fn title(&self) -> &'static str {
            "fake"
        }
        fn run(&self, _: &Path, _: &mut dyn FnMut(&str)) -> Result<SectionReport, ReportError> {
            match self.1 {
                0 => Ok(SectionReport {
                    markdown: "all good\n".into(),
                    images: Vec::new(),
                    status: Status::Pass,
                    summary: vec!["x = 1".into()],
                }),
                1 => Ok(SectionReport {
                    markdown: "limit missed\n".into(),
                    images: Vec::new(),
                    status: Status::Fail,
                    summary: Vec::new(),
                }),
                2 => Err(ReportError::Benchmark("mesh missing".into())),
                _ => panic!("solver blew up"),
            }
        }
    }

    #[test]
    fn failures_are_written_into_the_report() {
        let dir = tempfile::tempdir().expect("temp dir");
        let out = dir.path().join("nested/report");
        let all: Vec<Box<dyn Section>> = vec![
            Box::new(Fake("ok", 0)),
            Box::new(Fake("missed", 1)),
            Box::new(Fake("error", 2)),
            Box::new(Fake("panics", 3)),
        ];
        let w = write_sections(&all, &out, &mut |_| {}).expect("written");
        let md = std::fs::read_to_string(&w.markdown).expect("report.md");
        assert!(!w.all_passed());
        let words: Vec<&str> = w.outcomes.iter().map(|o| o.status.word()).collect();
        assert_eq!(words, ["PASS", "FAIL", "ERROR", "ERROR"]);
        for text in [
            "| ok | PASS |",
            "| missed | FAIL |",
            "| panics | ERROR |",
            "limit missed",
            "mesh missing",
            "solver blew up",
        ] {
            assert!(md.contains(text), "{text} not in\n{md}");
        }
        let only_ok = write_sections(&all[..1], &out, &mut |_| {}).expect("written");
        assert!(only_ok.all_passed());
    }

    #[test]
    fn verdict_lists_the_missed_limits() {
        assert_eq!(verdict(&[]), "PASS");
        assert_eq!(
            verdict(&["Fx +4.0 %".into(), "a|b".into()]),
            "**FAIL** (Fx +4.0 %, a/b)"
        );
        let row = not_run_row("μ = 0", "no | column", 2);
        assert_eq!(
            row,
            ["μ = 0", "did not run: no / column", "", "", "**FAIL**"]
        );
    }

    #[test]
    fn table_has_a_separator_row() {
        let t = table(&["a", "b"], &[vec!["1".into(), "2".into()]]);
        assert_eq!(t, "| a | b |\n|---|---|\n| 1 | 2 |\n");
    }
}
