//! `fvc run --restart` (issue 45): a run continued from an increment of
//! its results gives the history of the run that was not stopped, and a
//! case that does not fit the results, a missing file or an increment the
//! file cannot continue from is refused with exit code 2.
use std::path::{Path, PathBuf};

use crate::cli::fvc;

/// examples/shallow-ironing made small: the foundation 3 × 1.5 mm in
/// 30 × 15 cells and elastoplastic (neo-Hookean, yield 20 MPa, hardening
/// 100 MPa), the block pressed 0.5 mm down in 4 increments and dragged
/// 0.2 mm sideways in 3, friction μ = 0.3 as in the example.
fn ironing_case() -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/shallow-ironing");
    let text = std::fs::read_to_string(root.join("case.toml")).unwrap();
    let block = root.join("block.msh");
    let edits = [
        (
            "title = \"shallow-ironing\"",
            "title = \"ironing\"".to_owned(),
        ),
        (
            "intervals = [[1.0, 20], [1.5, 50]]",
            "intervals = [[0.5, 4], [0.7, 3]]".to_owned(),
        ),
        (
            "min = [0, 0, 0], max = [12, 4, 1], cells = [120, 30, 1]",
            "min = [0, 2.5, 0], max = [3, 4, 1], cells = [30, 15, 1]".to_owned(),
        ),
        (
            "material = { model = \"neo-hookean\", E = 689.6, nu = 0.32 }",
            "material = { model = \"neo-hookean-plastic\", E = 689.6, nu = 0.32, yield = 20.0, hardening = 100.0 }".to_owned(),
        ),
        (
            "[[0.0, [0, 0, 0]], [1.0, [0, -1, 0]], [1.5, [5, -1, 0]]]",
            "[[0.0, [0, 0, 0]], [0.5, [0, -0.5, 0]], [0.7, [0.2, -0.5, 0]]]".to_owned(),
        ),
        (
            "mesh = { file = \"block.msh\" }",
            format!("mesh = {{ file = {:?} }}", block.to_str().unwrap()),
        ),
    ];
    let mut case = text;
    for (from, to) in edits {
        assert!(case.contains(from), "the example no longer has {from}");
        case = case.replace(from, &to);
    }
    // states kept for increments 2, 4, 6 and the last
    case + "\n[output]\nrestart_every = 2\n"
}

/// The rows of `history.csv`, as numbers.
fn history(res: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(res.join("history.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// Runs `case` in `dir` (written to `dir/case.toml`, results in
/// `dir/out/<title>`) with `args` added; returns the exit code and stderr.
fn run(dir: &Path, case: &str, args: &[&str]) -> (i32, String) {
    let path = dir.join("case.toml");
    std::fs::write(&path, case).unwrap();
    let out = dir.join("out");
    let mut all = vec![
        "run",
        path.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
        "--quiet",
    ];
    all.extend_from_slice(args);
    let (code, _, err) = fvc(&all);
    (code, err)
}

fn h5(dir: &Path, title: &str) -> PathBuf {
    dir.join("out").join(title).join(format!("{title}.h5"))
}

/// Runs the ironing case through with its fields in `precision` (and,
/// if given, only the `[output] fields` listed), then again from
/// increment 4 of its results; returns both histories and the continued
/// run's summary.
fn run_and_continue(
    method: &str,
    precision: &str,
    fields: Option<&str>,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>, serde_json::Value) {
    let dir = tempfile::tempdir().unwrap();
    let mut case = ironing_case() + &format!("precision = \"{precision}\"\n");
    if let Some(list) = fields {
        case += &format!("fields = {list}\n");
    }
    let (code, err) = run(dir.path(), &case, &["--nonlinear", method]);
    assert_eq!(code, 0, "{err}");
    let res = dir.path().join("out/ironing");
    let whole = history(&res);
    let file = h5(dir.path(), "ironing");
    let kept: Vec<usize> = {
        let f = hdf5::File::open(&file).unwrap();
        // the fields in the precision asked for; the state double, with
        // the cell displacement where the field is not there in double
        let bytes = |p: &str| f.dataset(p).unwrap().dtype().unwrap().size();
        let single = precision == "single";
        let field = |name: &str| fields.is_none_or(|l| l.contains(&format!("\"{name}\"")));
        assert_eq!(
            bytes("time/4/foundation/von_mises"),
            if single { 4 } else { 8 }
        );
        for name in ["stress", "displacement"] {
            let p = format!("time/4/foundation/{name}");
            assert_eq!(f.link_exists(&p), field(name), "{p}");
        }
        let u = "restart/4/body/foundation/momentum/u";
        assert_eq!(f.link_exists(u), single || !field("displacement"), "{u}");
        assert_eq!(bytes("restart/4/body/foundation/momentum/material/f"), 8);
        let mut k: Vec<usize> = f
            .group("restart")
            .unwrap()
            .member_names()
            .unwrap()
            .iter()
            .map(|n| n.parse().unwrap())
            .collect();
        k.sort_unstable();
        k
    };
    assert_eq!(kept, [2, 4, 6, 7], "restart_every = 2 and the last");
    let (code, err) = run(
        dir.path(),
        &case,
        &[
            "--nonlinear",
            method,
            "--restart",
            file.to_str().unwrap(),
            "--from-increment",
            "4",
        ],
    );
    assert_eq!(code, 0, "{err}");
    let log = std::fs::read_to_string(res.join("log.txt")).unwrap();
    assert!(
        log.contains("continued from increment 4 (t = 0.5)"),
        "{log}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("summary.json")).unwrap()).unwrap();
    let file = hdf5::File::open(&file).unwrap();
    let written: Vec<u64> = file.dataset("increments").unwrap().read_raw().unwrap();
    assert_eq!(
        written,
        [1, 2, 3, 4, 5, 6, 7],
        "the index after the restart"
    );
    (whole, history(&res), summary)
}

/// The continued history against the whole one: the rows up to the
/// restart are the same numbers, the later ones agree to the solver's
/// tolerance. Measure: per force column (reactions and contact forces),
/// the largest difference over the continued increments relative to the
/// column's largest magnitude. Measured: 7.1e-7 (Newton–Krylov, relative
/// residual 1e-6; its first Jacobian after the restart is factorised
/// afresh where the uninterrupted run reused the last one), 6.6e-7
/// (segregated, relative correction 1e-6).
fn assert_continues(method: &str, precision: &str, fields: Option<&str>, bound: f64) {
    let (whole, continued, summary) = run_and_continue(method, precision, fields);
    assert_eq!(whole.len(), 7);
    assert_eq!(continued.len(), 7);
    assert_eq!(whole[..4], continued[..4], "rows kept from the first run");
    let mut worst = 0.0f64;
    for c in 3..whole[0].len() {
        let scale = whole.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
        if scale < 1e-9 {
            continue; // the out-of-plane components
        }
        for (a, b) in whole[4..].iter().zip(&continued[4..]) {
            assert_eq!(a[0], b[0], "times");
            worst = worst.max((a[c] - b[c]).abs() / scale);
        }
    }
    eprintln!("{method}: continued history within {worst:.2e} of the whole one");
    assert!(worst < bound, "{method}: {worst:e}");
    // the run makes plastic strain and friction: the contact slides
    let fx = whole[6][6];
    assert!(fx > 10.0, "block/top Fx {fx}");
    assert_eq!(summary["increments"], 7);
    assert_eq!(summary["restarted_from"], 4);
    assert_eq!(summary["time_reached"], 0.7);
}

/// Fields in single precision: the state holds the cell displacement.
#[test]
fn a_continued_run_gives_the_history_of_the_whole_run_newton_krylov() {
    assert_continues("newton-krylov", "single", None, 1e-5);
}

/// Fields in double precision: the state takes the cell displacement
/// from the `displacement` field.
#[test]
fn a_continued_run_gives_the_history_of_the_whole_run_segregated() {
    assert_continues("segregated", "double", None, 1e-5);
}

/// Fields in double precision without `displacement` (`[output]
/// fields`): the state holds the cell displacement.
#[test]
fn a_continued_run_without_the_displacement_field_holds_it_in_the_state() {
    let fields = r#"["von_mises", "contact_pressure"]"#;
    assert_continues("segregated", "double", Some(fields), 1e-5);
}

#[test]
fn a_case_that_does_not_fit_the_results_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let case = crate::cli::GOOD.to_owned();
    let (code, err) = run(dir.path(), &case, &[]);
    assert_eq!(code, 0, "{err}");
    let file = h5(dir.path(), "block");
    let f = file.to_str().unwrap();
    // another mesh
    let finer = case.replace("cells = [4, 4, 4]", "cells = [4, 5, 4]");
    let (code, err) = run(dir.path(), &finer, &["--restart", f]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("body block: cells: 64 in the file, 80 in the case"),
        "{err}"
    );
    assert!(err.contains("block.h5"), "{err}");
    // another Young's modulus (a probe restarted with E doubled, and the
    // forces jumped threefold without a word)
    let stiffer = case.replacen("E = 200.0", "E = 400.0", 1);
    assert_ne!(stiffer, case);
    let (code, err) = run(dir.path(), &stiffer, &["--restart", f]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(
            "body block: material constants: E 2e2, nu 3e-1 in the file, E 4e2, nu 3e-1 in the case"
        ),
        "{err}"
    );
    // another body
    let more = format!(
        "{case}[[body]]\nname = \"lid\"\nrigid = true\nmesh = {{ generator = \"box\", min = [0, 1, 0], max = [1, 1.2, 1], cells = [1, 1, 1] }}\n"
    );
    let (code, err) = run(dir.path(), &more, &["--restart", f]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("body lid: rigid: true in the case, absent from the file"),
        "{err}"
    );
    // an increment the file does not hold, and no file
    let (code, err) = run(
        dir.path(),
        &case,
        &["--restart", f, "--from-increment", "3"],
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--from-increment 3: the file does not hold it; the increments it can continue from are 2"),
        "{err}"
    );
    // the state of increment 1 went when that of 2 came (restart_every = 10)
    let (code, err) = run(
        dir.path(),
        &case,
        &["--restart", f, "--from-increment", "1"],
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--from-increment 1: its fields are written but not its state"),
        "{err}"
    );
    let missing = dir.path().join("out/block/nothing/block.h5");
    let (code, err) = run(dir.path(), &case, &["--restart", missing.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("no such results file"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // the refused runs left the results as they were
    assert_eq!(history(&dir.path().join("out/block")).len(), 2);
    // continuing from the last increment solves nothing and keeps them
    let (code, err) = run(dir.path(), &case, &["--restart", f]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(history(&dir.path().join("out/block")).len(), 2);
}

/// A continued run whose case changes its time steps (the contract lets
/// it) goes on along its own grid from the time it starts at. A probe
/// (2026-11-30) continued a 2-step run from t = 0.5 with 4 steps, and
/// the next increment was solved at t = 0.5 again, the one after at 0.75:
/// each increment k took the new grid's time_at(k).
#[test]
fn a_continued_run_with_other_steps_goes_on_in_time() {
    let dir = tempfile::tempdir().unwrap();
    let case = crate::cli::GOOD.replace("[solver]", "[output]\nrestart_every = 1\n[solver]");
    let (code, err) = run(dir.path(), &case, &[]);
    assert_eq!(code, 0, "{err}");
    let whole = history(&dir.path().join("out/block"));
    let file = h5(dir.path(), "block");
    for (steps, times) in [
        ("steps = 4", vec![0.5, 0.75, 1.0]),
        ("steps = 1", vec![0.5, 1.0]),
    ] {
        let finer = case.replace("steps = 2", steps);
        let (code, err) = run(
            dir.path(),
            &finer,
            &["--restart", file.to_str().unwrap(), "--from-increment", "1"],
        );
        assert_eq!(code, 0, "{steps}: {err}");
        let h = history(&dir.path().join("out/block"));
        let got: Vec<f64> = h.iter().map(|r| r[0]).collect();
        assert_eq!(got, times, "{steps}");
        // a linear problem: the end state is the uninterrupted run's
        let (a, b) = (&h[h.len() - 1], &whole[whole.len() - 1]);
        let scale = b.iter().skip(3).fold(0.0f64, |m, y| m.max(y.abs()));
        for (x, y) in a.iter().zip(b).skip(3) {
            assert!((x - y).abs() <= 1e-5 * scale, "{steps}: {a:?} vs {b:?}");
        }
    }
}

/// A restart from results that already reach the case's end solves
/// nothing (exit 0, the history kept), and its summary holds the reactions
/// of the state it continues from. They were those of no solve, zero
/// (found by a fresh-clone walkthrough, 2026-12-01).
#[test]
fn a_restart_with_nothing_left_to_solve_keeps_the_reactions() {
    let dir = tempfile::tempdir().unwrap();
    let (code, err) = run(dir.path(), crate::cli::GOOD, &[]);
    assert_eq!(code, 0, "{err}");
    let res = dir.path().join("out/block");
    let reaction = || {
        let text = std::fs::read_to_string(res.join("summary.json")).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v["patches"]["block/ymax"]["reaction_force"][1]
            .as_f64()
            .unwrap()
    };
    let before = reaction();
    let whole = history(&res);
    let file = h5(dir.path(), "block");
    let (code, err) = run(
        dir.path(),
        crate::cli::GOOD,
        &["--restart", file.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(history(&res), whole);
    let after = reaction();
    assert!(
        before < -2.0 && (after / before - 1.0).abs() < 1e-6,
        "{after} against {before}"
    );
}

/// validation/cases/wire-drawing cut to `steps` increments of its 1 ms
/// (the meshes read from the case's folder).
fn wire_drawing_case(steps: usize) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../validation/cases/wire-drawing");
    let mut case = std::fs::read_to_string(root.join("case.toml")).unwrap();
    for (from, to) in [
        (
            "end = 0.1\n".to_owned(),
            format!("end = {}\n", steps as f64 * 1e-3),
        ),
        ("steps = 100\n".to_owned(), format!("steps = {steps}\n")),
    ] {
        assert!(case.contains(&from), "the case no longer has {from}");
        case = case.replace(&from, &to);
    }
    for mesh in ["wire.msh", "die.msh"] {
        let path = root.join(mesh);
        case = case.replace(
            &format!("file = \"{mesh}\""),
            &format!("file = {:?}", path.to_str().unwrap()),
        );
    }
    case
}

/// A plastic body's increments start from the last converged change once
/// the tangent's first iterate failed (the wire drawing's second
/// increment); a run continued from its results starts there too: the
/// same 4 Newton iterations per increment as the whole run (from the
/// tangent, the continued increments needed 10–40 with cut-backs), the
/// drawing force within 1e-4.
#[test]
fn a_continued_plastic_run_keeps_its_first_iterate() {
    let dir = tempfile::tempdir().unwrap();
    let whole_dir = dir.path().join("whole");
    std::fs::create_dir_all(&whole_dir).unwrap();
    let (code, err) = run(&whole_dir, &wire_drawing_case(8), &[]);
    assert_eq!(code, 0, "{err}");
    let whole = history(&whole_dir.join("out/wire-drawing"));
    let (code, err) = run(dir.path(), &wire_drawing_case(5), &[]);
    assert_eq!(code, 0, "{err}");
    let results = h5(dir.path(), "wire-drawing");
    let (code, err) = run(
        dir.path(),
        &wire_drawing_case(8),
        &["--restart", results.to_str().unwrap()],
    );
    assert_eq!(code, 0, "{err}");
    let continued = history(&dir.path().join("out/wire-drawing"));
    assert_eq!(whole.len(), 8);
    assert_eq!(continued.len(), 8);
    // columns: time, outer_iterations, residual, wire/pulled:Fx, …
    for (a, b) in whole[5..].iter().zip(&continued[5..]) {
        assert_eq!(a[1], b[1], "Newton iterations at t = {}", a[0]);
        assert!(
            (a[3] / b[3] - 1.0).abs() < 1e-4,
            "force {} against {}",
            a[3],
            b[3]
        );
    }
}
