//! `validation report`: runs the supported benchmarks and writes the
//! validation report (markdown + PNG plots).
//!
//! Exit codes: 0 every benchmark ran and passed, 1 a benchmark failed or
//! did not run (the report is written with the failure shown), 2 bad
//! arguments or an unwritable output folder.
use std::path::PathBuf;
use std::process::ExitCode;

use clap::builder::PossibleValuesParser;
use clap::{Parser, Subcommand};
use validation::report::{names, write_report, ReportError, ReportOptions};

/// fvcontact validation: benchmarks against analytical and reference solutions.
#[derive(Parser)]
#[command(name = "validation", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run the benchmarks and write DIR/report.md with one PNG per plot.
    Report {
        /// Output folder (made if missing; files in it are overwritten).
        #[arg(long, value_name = "DIR", default_value = "target/validation-report")]
        output: PathBuf,
        /// Run only these benchmarks (default: all).
        #[arg(long, value_name = "NAME", num_args = 1.., value_parser = PossibleValuesParser::new(names()))]
        only: Vec<String>,
    },
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match cli.command {
        Command::Report { output, only } => {
            let opts = ReportOptions { output, only };
            let written = match write_report(&opts, &mut |line| eprintln!("{line}")) {
                Ok(w) => w,
                Err(e @ (ReportError::Output { .. } | ReportError::UnknownSection { .. })) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(1);
                }
            };
            for o in &written.outcomes {
                println!("{}: {} ({:.1} s)", o.name, o.status.word(), o.seconds);
                if let validation::report::Status::Error(m) = &o.status {
                    println!("  did not run: {m}");
                }
                for line in &o.summary {
                    println!("  {line}");
                }
            }
            println!("report: {}", written.markdown.display());
            for image in &written.images {
                println!("plot:   {}", image.display());
            }
            if written.all_passed() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::error::ErrorKind;

    #[test]
    fn defaults_and_selection_parse() {
        let cli = Cli::try_parse_from(["validation", "report"]).expect("parses");
        let Command::Report { output, only } = cli.command;
        assert_eq!(output, PathBuf::from("target/validation-report"));
        assert!(only.is_empty());
        let cli = Cli::try_parse_from([
            "validation",
            "report",
            "--output",
            "x",
            "--only",
            "hertz-cylinder",
        ])
        .expect("parses");
        let Command::Report { output, only } = cli.command;
        assert_eq!(output, PathBuf::from("x"));
        assert_eq!(only, vec!["hertz-cylinder".to_string()]);
    }

    #[test]
    fn bad_arguments_are_usage_errors() {
        for args in [
            &["validation", "report", "--only", "no-such"][..],
            &["validation", "report", "--only"][..],
            &["validation", "report", "--bogus"][..],
            &["validation"][..],
        ] {
            let e = Cli::try_parse_from(args).err().expect("rejected");
            assert!(e.use_stderr(), "{args:?}: {:?}", e.kind());
            assert_ne!(e.kind(), ErrorKind::DisplayHelp);
        }
    }
}
