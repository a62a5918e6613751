//! `fvc`: the fvcontact command-line solver (CASE_FORMAT.md, "Command line").
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use solver_app::case::load_case;
use solver_app::interrupt::{exit_code, Interrupt};
use solver_app::results::stdout_line;
use solver_app::run::{
    check_support, run_case, set_up_with_contacts, RunError, RunOptions, RunOutcome,
};

/// Finite-volume solver for large-deformation frictional contact.
#[derive(Parser)]
#[command(name = "fvc", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case.
    Run {
        /// The case file (TOML).
        case: PathBuf,
        /// Results directory (overrides [output] directory).
        #[arg(long)]
        output: Option<PathBuf>,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// No progress bar: one log line per increment.
        #[arg(long)]
        quiet: bool,
        /// Solve with this nonlinear method whatever the case's
        /// `[solver] nonlinear` says (newton-krylov, segregated).
        #[arg(long, value_parser = parse_method)]
        nonlinear: Option<fv_nonlinear::NonlinearMethod>,
        /// Continue an earlier run of this case from its results file
        /// (RESULTS/<title>/<title>.h5), into the same results; later
        /// increments of the file are replaced.
        #[arg(long, value_name = "H5")]
        restart: Option<PathBuf>,
        /// With --restart: the increment to continue from (default: the
        /// last one the file can continue from).
        #[arg(long, value_name = "K", requires = "restart")]
        from_increment: Option<usize>,
    },
    /// Validate a case and report its meshes, without solving.
    Check {
        /// The case file (TOML).
        case: PathBuf,
    },
    /// PNG plots of a results folder (finished or interrupted run) into
    /// RESULTS_DIR/plots/: forces and iterations against time, contact
    /// pressure along each contact patch at the last increment.
    Plot {
        /// The results folder of a run (<output>/<title>/).
        results_dir: PathBuf,
    },
}

fn parse_method(s: &str) -> Result<fv_nonlinear::NonlinearMethod, String> {
    fv_nonlinear::NonlinearMethod::from_name(s).map_err(|e| e.to_string())
}

/// Fixes glibc's mmap threshold at 128 kB (its default start): from that
/// size up, an allocation gets pages of its own, returned to the system
/// when freed. Left dynamic, glibc raises the threshold to the size of
/// every mapped block freed (up to 32 MB), so the set-up's freed work
/// arrays (mesh generation, geometry, the least-squares matrices) stayed
/// in the heap and resident while the later long-lived fields took heap
/// pages of their own: 64³ box, peak RSS Newton–Krylov 575,848 →
/// 530,740 kB, segregated 774,808 → 757,368 kB. The solve allocates
/// nothing per iteration, so the extra system calls are few.
fn fix_mmap_threshold() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets an allocator parameter; called first in
    // main, before any other thread exists
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024);
    }
}

fn main() -> ExitCode {
    fix_mmap_threshold();
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_target(false)
        .without_time()
        .with_level(false)
        .init();
    match cli.command {
        Command::Plot { results_dir } => {
            let written = |p: &std::path::Path| stdout_line(&p.display().to_string());
            match solver_app::plot::plot_results(&results_dir, &mut { written }) {
                Ok(report) => {
                    for n in &report.notes {
                        eprintln!("note: {n}");
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(e.exit_code())
                }
            }
        }
        Command::Check { case } => {
            let case = match load_case(&case) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            match set_up_with_contacts(&case) {
                Ok((bodies, contacts)) => {
                    let mesh = solver_app::check::mesh_report(&case, &bodies);
                    stdout_line(mesh.trim_end_matches('\n'));
                    stdout_line(&solver_app::check::solver_report(&case, &bodies, &contacts));
                    for line in solver_app::check::contact_report(&contacts) {
                        stdout_line(&line);
                    }
                    // the report is the result (standard output); notes
                    // are diagnostics (standard error), as under `fvc run`
                    for n in bodies.iter().flat_map(|b| &b.setup_notes) {
                        eprintln!("note: {n}");
                    }
                    match check_support(&case, bodies, contacts) {
                        Ok(note) => {
                            if let Some(note) = note {
                                eprintln!("note: {note}");
                            }
                            stdout_line("case is valid");
                            ExitCode::SUCCESS
                        }
                        Err(e) => {
                            eprintln!("error: {e}");
                            ExitCode::from(2)
                        }
                    }
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            }
        }
        Command::Run {
            case,
            output,
            threads,
            quiet,
            nonlinear,
            restart,
            from_increment,
        } => {
            if let Some(n) = threads {
                if n == 0 {
                    eprintln!("error: --threads must be at least 1");
                    return ExitCode::from(2);
                }
                // more workers than cores only adds switching (100,000
                // took minutes to start a 27-cell case)
                let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
                if n > cores {
                    eprintln!(
                        "note: --threads {n} is more than the {cores} cores here; using {cores}"
                    );
                }
                let _ = rayon::ThreadPoolBuilder::new()
                    .num_threads(n.min(cores))
                    .build_global();
            }
            let case = match solver_app::case::load_case_with(&case, nonlinear) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            // Ctrl-C and SIGTERM end the run with its results so far
            let interrupt = Interrupt::install().unwrap_or_else(|e| {
                eprintln!("note: cannot catch SIGINT/SIGTERM ({e}); they end the run at once");
                Interrupt::new()
            });
            let opts = RunOptions {
                output,
                quiet,
                no_files: false,
                no_cutbacks: false,
                interrupt,
                restart: restart.map(|file| solver_app::restart::RestartFrom {
                    file,
                    increment: from_increment,
                }),
            };
            match run_case(&case, &opts) {
                Ok(out) if out.converged => ExitCode::SUCCESS,
                Ok(RunOutcome {
                    interrupted: Some(sig),
                    ..
                }) => ExitCode::from(exit_code(sig)),
                Ok(out) => {
                    eprintln!(
                        "error: {}",
                        out.failure.as_deref().unwrap_or("the run did not converge")
                    );
                    ExitCode::from(1)
                }
                Err(RunError::Input(e)) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
                Err(e @ RunError::Output(_)) => {
                    eprintln!("error: {e}");
                    ExitCode::from(1)
                }
            }
        }
    }
}
