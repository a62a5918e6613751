//! The `fvc` binary on good and malformed input: exit codes and messages
//! (CASE_FORMAT.md, "Command line").
use std::path::{Path, PathBuf};
use std::process::Command;

pub(crate) const GOOD: &str = r#"title = "block"
[time]
end = 1.0
steps = 2
[solver]
tolerance = 1e-6
[[body]]
name = "block"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [4, 4, 4] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.ymax]
type = "displacement"
value = { table = [[0.0, [0, 0, 0]], [1.0, [0, -0.01, 0]]] }
"#;

/// A rigid plate on top of [`GOOD`]'s block (appended to it).
const RIGID_PLATE: &str = r#"[[body]]
name = "plate"
rigid = true
mesh = { generator = "box", min = [0, 1, 0], max = [1, 1.2, 1], cells = [2, 1, 2] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
"#;

pub(crate) fn fvc(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_fvc"))
        .args(args)
        .output()
        .expect("fvc runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Runs `fvc run` on a case and expects exit 2 with every `expected` piece in stderr.
/// Writes `case` to `dir/case.toml` and runs `fvc run … --output dir/out
/// --quiet` on it; returns the exit code, the output folder and stderr.
fn run_quietly(dir: &Path, case: &[u8]) -> (i32, PathBuf, String) {
    let p = write(dir, "case.toml", case);
    let outdir = dir.join("out");
    let (code, _, err) = fvc(&[
        "run",
        p.to_str().unwrap(),
        "--output",
        outdir.to_str().unwrap(),
        "--quiet",
    ]);
    (code, outdir, err)
}

/// `summary.json` of the results folder `res`: its text (for messages)
/// and its parsed value.
fn read_summary(res: &Path) -> (String, serde_json::Value) {
    let text = std::fs::read_to_string(res.join("summary.json")).unwrap();
    let v = serde_json::from_str(&text).unwrap();
    (text, v)
}

/// The last row of a results folder's `history.csv`, as numbers.
fn last_history_row(res: &Path) -> Vec<f64> {
    let hist = std::fs::read_to_string(res.join("history.csv")).unwrap();
    hist.lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect()
}

/// Runs `case` (titled `title`), expects it to solve, and returns the
/// normal force of its first contact from `summary.json`.
fn first_contact_force(dir: &Path, case: &str, title: &str) -> f64 {
    let (code, outdir, err) = run_quietly(dir, case.as_bytes());
    assert_eq!(code, 0, "{err}");
    let (summary, v) = read_summary(&outdir.join(title));
    v["contacts"][0]["normal_force"]
        .as_f64()
        .unwrap_or_else(|| panic!("no contact force in {summary}"))
}

fn expect_input_error(dir: &Path, case: &[u8], expected: &[&str]) {
    let (code, _, err) = run_quietly(dir, case);
    assert_eq!(code, 2, "exit code for {expected:?}; stderr: {err}");
    for e in expected {
        assert!(err.contains(e), "stderr lacks {e:?}:\n{err}");
    }
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn good_case_runs_and_writes_results() {
    let dir = tempfile::tempdir().unwrap();
    let (code, outdir, err) = run_quietly(dir.path(), GOOD.as_bytes());
    assert_eq!(code, 0, "{err}");
    let res = outdir.join("block");
    let (_, v) = read_summary(&res);
    assert_eq!(v["converged"], true);
    assert_eq!(v["increments"], 2);
    // uniaxial compression of a free-sided block: F = E ε A (lateral faces free,
    // but ends held: reaction larger than E ε A, smaller than the oedometric value)
    let fy = v["patches"]["block/ymax"]["reaction_force"][1]
        .as_f64()
        .unwrap();
    let e_eps_a = 200.0 * 0.01;
    let oedometric = e_eps_a * (1.0 - 0.3) / ((1.0 + 0.3) * (1.0 - 0.6));
    assert!(fy < -e_eps_a && fy > -oedometric, "reaction {fy}");
    let fy0 = v["patches"]["block/ymin"]["reaction_force"][1]
        .as_f64()
        .unwrap();
    assert!(
        (fy + fy0).abs() < 1e-6 * fy.abs(),
        "equilibrium {fy} vs {fy0}"
    );
    let hist = std::fs::read_to_string(res.join("history.csv")).unwrap();
    let lines: Vec<&str> = hist.lines().collect();
    assert_eq!(lines.len(), 3);
    assert!(lines[0].starts_with("time,outer_iterations,residual,block/ymin:Fx"));
    assert!(std::fs::read_to_string(res.join("log.txt"))
        .unwrap()
        .contains("increment 2/2"));
}

#[test]
fn check_prints_the_mesh_report() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "case.toml", GOOD.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    for s in [
        "64 cells",
        "non-orthogonality",
        "skewness",
        "ymax",
        "displacement",
        "traction-free",
    ] {
        assert!(out.contains(s), "{s} missing in:\n{out}");
    }
}

#[test]
fn check_into_a_closed_pipe_ends_without_a_panic() {
    // `fvc check case.toml | head -1`: the reader is gone before the
    // report is written
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "case.toml", GOOD.as_bytes());
    let mut child = Command::new(env!("CARGO_BIN_EXE_fvc"))
        .args(["check", p.to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("fvc runs");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("fvc ends");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(out.status.code(), Some(0), "{err}");
}

#[test]
fn ten_malformed_inputs_exit_2_with_precise_messages() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // 1 syntax error
    expect_input_error(
        d,
        GOOD.replace("end = 1.0", "end = 1.0 =").as_bytes(),
        &["case.toml:3"],
    );
    // 2 unknown key
    expect_input_error(
        d,
        GOOD.replace("tolerance = 1e-6", "tolerence = 1e-6")
            .as_bytes(),
        &["case.toml:6", "tolerence"],
    );
    // 3 unknown patch
    expect_input_error(
        d,
        GOOD.replace("[body.boundary.ymin]", "[body.boundary.bottom]")
            .as_bytes(),
        &["case.toml:11", "bottom", "ymin"],
    );
    // 4 nu >= 0.5
    expect_input_error(
        d,
        GOOD.replace("nu = 0.3", "nu = 0.5").as_bytes(),
        &["case.toml:10", "nu"],
    );
    // 5 E <= 0
    expect_input_error(
        d,
        GOOD.replace("E = 200.0", "E = 0.0").as_bytes(),
        &["case.toml:10", "E"],
    );
    // 6 missing mesh file
    expect_input_error(
        d,
        GOOD.replace(
            r#"{ generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [4, 4, 4] }"#,
            r#"{ file = "nowhere.msh" }"#,
        )
        .as_bytes(),
        &["nowhere.msh"],
    );
    // 7 truncated mesh file
    let msh = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/quarter-annulus/annulus.msh"),
    )
    .unwrap();
    write(d, "cut.msh", &msh[..msh.len() / 2]);
    expect_input_error(
        d,
        GOOD.replace(
            r#"{ generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [4, 4, 4] }"#,
            r#"{ file = "cut.msh" }"#,
        )
        .as_bytes(),
        &["cut.msh"],
    );
    // 8 unknown body in a contact
    expect_input_error(
        d,
        format!("{GOOD}\n[[contact]]\nmaster = \"plate/top\"\nslave = \"block/ymax\"\n").as_bytes(),
        &["case.toml:19", "plate"],
    );
    // 9 negative steps
    expect_input_error(
        d,
        GOOD.replace("steps = 2", "steps = -2").as_bytes(),
        &["case.toml:4", "steps"],
    );
    // 10 non-UTF-8 file
    let mut bytes = GOOD.as_bytes().to_vec();
    bytes.splice(0..0, [b'#', 0xff, 0xfe, b'\n']);
    expect_input_error(d, &bytes, &["case.toml:1", "UTF-8"]);
    // and a missing case file
    let (code, _, err) = fvc(&["run", d.join("absent.toml").to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn a_contact_patch_with_its_own_boundary_condition_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let two = format!("{GOOD}{RIGID_PLATE}")
        + r#"[[contact]]
master = "plate/ymin"
slave = "block/xmax"
coupling = "implicit"
"#;
    // a contact patch may not carry a boundary condition of its own
    let own = two.replace(
        "slave = \"block/xmax\"\ncoupling = \"implicit\"",
        "slave = \"block/ymax\"",
    );
    expect_input_error(
        dir.path(),
        own.as_bytes(),
        &[
            "contact[0].slave",
            "block/ymax",
            "must not have a boundary condition",
        ],
    );
}

/// What `run` refuses before it solves, `check` refuses too: a contact
/// patch that does not exist (found where the contact pairs are built).
#[test]
fn check_refuses_a_contact_that_run_refuses() {
    let dir = tempfile::tempdir().unwrap();
    let case = format!("{GOOD}{RIGID_PLATE}")
        + r#"[[contact]]
master = "plate/ymin"
slave = "block/bottom"
"#;
    let p = write(dir.path(), "case.toml", case.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains("contact[0].slave") && err.contains("no patch 'bottom'"),
        "{err}"
    );
    assert!(!out.contains("case is valid"), "{out}");
}

/// Contact between two patches of one body: exit 2 naming the contact,
/// its line and "self-contact is not supported".
#[test]
fn self_contact_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let case = format!("{GOOD}[[contact]]\nmaster = \"block/xmax\"\nslave = \"block/xmin\"\n");
    let line = case.lines().position(|l| l.contains("block/xmin")).unwrap() + 1;
    expect_input_error(
        dir.path(),
        case.as_bytes(),
        &[
            &format!("case.toml:{line}: contact[0].slave"),
            "self-contact is not supported",
        ],
    );
}

/// A rigid plate with no `material` and no condition: accepted, noted by
/// `check` and in the log as held fixed, and the run is that of the same
/// plate with a material and `displacement = [0, 0, 0]` to the last bit.
/// The block, pushed 0.01 up against it (frictionless, implicit contact),
/// carries less than the oedometric E ε A (1 − ν)/((1 + ν)(1 − 2ν)) and,
/// with the penalty's penetration, more than half of E ε A.
#[test]
fn a_rigid_body_without_material_or_motion_is_held_fixed() {
    let dir = tempfile::tempdir().unwrap();
    let pushed = GOOD
        .replace(
            "[body.boundary.ymax]\ntype = \"displacement\"\nvalue = { table = [[0.0, [0, 0, 0]], [1.0, [0, -0.01, 0]]] }\n",
            "",
        )
        .replace(
            "[body.boundary.ymin]\ntype = \"displacement\"\nvalue = [0, 0, 0]",
            "[body.boundary.ymin]\ntype = \"displacement\"\nvalue = { table = [[0.0, [0, 0, 0]], [1.0, [0, 0.01, 0]]] }",
        );
    assert!(pushed.contains("[0, 0.01, 0]") && !pushed.contains("ymax"));
    let contact =
        "[[contact]]\nmaster = \"plate/ymin\"\nslave = \"block/ymax\"\ncoupling = \"implicit\"\n";
    let bare = RIGID_PLATE.replace(
        "material = { model = \"linear-elastic\", E = 200.0, nu = 0.3 }\n",
        "",
    );
    let case = format!("{pushed}{bare}{contact}");
    // the `[[body]]` header just above the name (0-based index = 1-based line)
    let body_line = case.lines().position(|l| l == "name = \"plate\"").unwrap();
    let p = write(dir.path(), "case.toml", case.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    let note = format!(
        "case.toml:{body_line}: body[1]: body 'plate' is rigid and no patch of it has a \"displacement\" or \"rigid-motion\" condition: it is held fixed where it is"
    );
    // a note is a diagnostic: standard error, as under `fvc run`
    assert!(err.contains(&note) && !out.contains(&note), "{out}{err}");
    let reaction = |sub: &str, case: &str| {
        let d = dir.path().join(sub);
        std::fs::create_dir_all(&d).unwrap();
        let (code, res, err) = run_quietly(&d, case.as_bytes());
        assert_eq!(code, 0, "{err}");
        let log = std::fs::read_to_string(res.join("block/log.txt")).unwrap();
        let (_, v) = read_summary(&res.join("block"));
        let fy = v["patches"]["block/ymin"]["reaction_force"][1]
            .as_f64()
            .unwrap();
        (fy, log.contains("held fixed where it is"))
    };
    let (fy, noted) = reaction("bare", &case);
    assert!(noted);
    let fixed = format!(
        "{pushed}{RIGID_PLATE}[body.boundary.ymax]\ntype = \"displacement\"\nvalue = [0, 0, 0]\n{contact}"
    );
    let (fy_fixed, noted) = reaction("fixed", &fixed);
    assert!(!noted);
    assert_eq!(fy.to_bits(), fy_fixed.to_bits(), "{fy} vs {fy_fixed}");
    let e_eps_a = 200.0 * 0.01;
    let oedometric = e_eps_a * (1.0 - 0.3) / ((1.0 + 0.3) * (1.0 - 0.6));
    assert!(fy > 0.5 * e_eps_a && fy < oedometric, "reaction {fy}");
}

/// Loads on a rigid body act on nothing (it is not solved), and a case of
/// rigid bodies alone has nothing to solve: both are input errors.
#[test]
fn loads_on_rigid_bodies_and_all_rigid_cases_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let rigid_block = GOOD.replace("[body.boundary.ymin]", "rigid = true\n[body.boundary.ymin]");
    expect_input_error(
        dir.path(),
        rigid_block.as_bytes(),
        &["body[0].rigid", "at least one body must be deformable"],
    );
    let case = format!("{GOOD}{RIGID_PLATE}")
        + r#"[body.boundary.xmax]
type = "traction"
value = [5.0, 0, 0]
"#;
    expect_input_error(
        dir.path(),
        case.as_bytes(),
        &[
            "body[1].boundary.xmax",
            "\"traction\" needs a deformable body",
        ],
    );
    let pressure = case.replace(
        "type = \"traction\"\nvalue = [5.0, 0, 0]",
        "type = \"pressure\"\nvalue = 1.0",
    );
    expect_input_error(
        dir.path(),
        pressure.as_bytes(),
        &[
            "body[1].boundary.xmax",
            "\"pressure\" needs a deformable body",
        ],
    );
}

/// `empty` is for the front and back of a body one cell thick: on a body
/// four cells thick, or on one side only, it is refused (it would solve a
/// 3-D body as plane strain).
#[test]
fn empty_needs_a_body_one_cell_thick() {
    let dir = tempfile::tempdir().unwrap();
    let both = format!(
        "{GOOD}[body.boundary.zmin]\ntype = \"empty\"\n[body.boundary.zmax]\ntype = \"empty\"\n"
    );
    expect_input_error(
        dir.path(),
        both.as_bytes(),
        &[
            "body[0].boundary.zmin",
            "one cell thick",
            "has 1 of its faces",
        ],
    );
    let thin = both.replace("cells = [4, 4, 4]", "cells = [4, 4, 1]");
    let (code, _, err) = run_quietly(dir.path(), thin.as_bytes());
    assert_eq!(code, 0, "{err}");
    let one_side = thin.replace("[body.boundary.zmax]\ntype = \"empty\"\n", "");
    expect_input_error(
        dir.path(),
        one_side.as_bytes(),
        &["body[0].boundary.zmin", "not 2"],
    );
}

/// `wedge` on patches that are not the two planes of a one-cell wedge is
/// refused, naming the patch: two perpendicular sides of a box 4 cells
/// thick (it solved it as a 90° wedge), and a third wedge patch besides
/// them (a face on neither plane).
#[test]
fn wedge_needs_a_one_cell_wedge() {
    let dir = tempfile::tempdir().unwrap();
    let box_wedge = format!(
        "{GOOD}[body.boundary.xmin]\ntype = \"wedge\"\n[body.boundary.zmin]\ntype = \"wedge\"\n"
    );
    expect_input_error(
        dir.path(),
        box_wedge.as_bytes(),
        &["body[0].boundary.xmin", "one cell thick around its axis"],
    );
    let third = format!("{box_wedge}[body.boundary.zmax]\ntype = \"wedge\"\n");
    expect_input_error(
        dir.path(),
        third.as_bytes(),
        &["body[0].boundary.zmax", "lies on neither wedge plane"],
    );
}

/// A results folder that cannot be created is the input's fault (exit 2),
/// named by where it came from: `--output` or `output.directory`.
#[test]
fn an_unwritable_results_folder_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "case.toml", GOOD.as_bytes());
    let file = write(dir.path(), "a-file", b"not a folder");
    let inside = file.join("out");
    let (code, _, err) = fvc(&[
        "run",
        p.to_str().unwrap(),
        "--output",
        inside.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--output") && err.contains("cannot write the results folder"),
        "{err}"
    );
    let case = format!(
        "{GOOD}[output]\ndirectory = {:?}\n",
        inside.to_str().unwrap()
    );
    let p = write(dir.path(), "case.toml", case.as_bytes());
    let (code, _, err) = fvc(&["run", p.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("output.directory") && err.contains("case.toml:"),
        "{err}"
    );
}

/// `--threads` beyond the cores is capped (100,000 workers took minutes to
/// start), with a note.
#[test]
fn more_threads_than_cores_are_capped() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "case.toml", GOOD.as_bytes());
    let out = dir.path().join("out");
    let (code, _, err) = fvc(&[
        "run",
        p.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
        "--threads",
        "100000",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("note: --threads 100000"), "{err}");
}

#[test]
fn unconstrained_body_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let free = GOOD
        .replace(
            "type = \"displacement\"\nvalue = [0, 0, 0]",
            "type = \"traction\"\nvalue = [0, 0, 0]",
        )
        .replace(
            "type = \"displacement\"\nvalue = { table",
            "type = \"traction\"\nvalue = { table",
        );
    expect_input_error(dir.path(), free.as_bytes(), &["not held"]);
}

/// A block resting on a fixed base, loaded by a pressure on its top and
/// held in y by the contact alone (plane strain); solved by the segregated
/// method, whose explicit coupling cannot hold it.
const RESTING: &str = r#"title = "resting"
[time]
end = 1.0
steps = 2
[solver]
nonlinear = "segregated"
tolerance = 1e-6
[[body]]
name = "base"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 0.5, 0.1], cells = [10, 5, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[body]]
name = "top"
mesh = { generator = "box", min = [0.25, 0.5, 0], max = [0.75, 0.8, 0.1], cells = [6, 4, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.ymax]
type = "pressure"
value = { table = [[0.0, 0.0], [1.0, 0.2]] }
[body.boundary.xmin]
type = "symmetry"
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[contact]]
master = "base/ymax"
slave = "top/ymin"
"#;

#[test]
fn a_body_held_by_contact_alone_is_coupled_implicitly() {
    let dir = tempfile::tempdir().unwrap();
    // explicit coupling (the default) applies the contact traction as a
    // load and cannot hold the block: its contact is coupled implicitly,
    // with a warning, and the base carries the pressure's force,
    // p · 0.5 · 0.1 = 0.01 at t = 1 (small strain: the initial area)
    let (code, outdir, err) = run_quietly(dir.path(), RESTING.as_bytes());
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("body 'top' is held in the y direction by contact alone")
            && err.contains("base/ymax – top/ymin coupled implicitly"),
        "{err}"
    );
    let (_, v) = read_summary(&outdir.join("resting"));
    let fy = v["patches"]["base/ymin"]["reaction_force"][1]
        .as_f64()
        .unwrap();
    assert!((fy / 0.01 - 1.0).abs() < 2e-3, "base reaction {fy}");
    let log = std::fs::read_to_string(outdir.join("resting/log.txt")).unwrap();
    assert!(log.contains("coupled implicitly"), "{log}");

    // the block's patch in a second pair with a deformable body: implicit
    // coupling cannot join them, so the case is an input error that names
    // the contacts and the remedy
    let second = RESTING.replace("[[contact]]", "[[body]]\nname = \"side\"\nmesh = { generator = \"box\", min = [0.8, 0.5, 0], max = [1, 0.8, 0.1], cells = [2, 3, 1] }\nmaterial = { model = \"linear-elastic\", E = 200.0, nu = 0.3 }\n[body.boundary.xmax]\ntype = \"displacement\"\nvalue = [0, 0, 0]\n[body.boundary.zmin]\ntype = \"empty\"\n[body.boundary.zmax]\ntype = \"empty\"\n[[contact]]\nmaster = \"side/ymin\"\nslave = \"top/ymin\"\n[[contact]]")
        ;
    expect_input_error(
        dir.path(),
        second.as_bytes(),
        &[
            "body 'top' is not held in the y direction",
            "side/ymin – top/ymin, base/ymax – top/ymin",
            "coupling = \"implicit\"",
        ],
    );
}

/// The segregated method on two blocks stacked in plane strain, on rollers (symmetry) at the bottom
/// and the left, the top face pushed down by 0.008 (a normal
/// displacement): uniaxial stress σ_yy = E' (d − g) / 0.8, with
/// E' = E / (1 − ν²) and g the penalty's uniform penetration. Explicit
/// coupling with the relaxation 1 is unstable (the relaxed iteration is
/// stable only below about 2 / (1 + ε_n c)).
const STACKED: &str = r#"title = "stacked"
[time]
end = 1.0
steps = 2
[solver]
nonlinear = "segregated"
tolerance = 1e-6
max_outer = 300
[[body]]
name = "base"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 0.5, 0.1], cells = [10, 5, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.ymin]
type = "symmetry"
[body.boundary.xmin]
type = "symmetry"
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[body]]
name = "top"
mesh = { generator = "box", min = [0, 0.5, 0], max = [1, 0.8, 0.1], cells = [7, 3, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.ymax]
type = "normal-displacement"
value = { table = [[0.0, 0.0], [1.0, -0.008]] }
[body.boundary.xmin]
type = "symmetry"
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[contact]]
master = "base/ymax"
slave = "top/ymin"
relaxation = { normal = 1.0, tangential = 1.0 }
"#;

#[test]
fn explicit_coupling_that_fails_is_redone_implicitly() {
    let dir = tempfile::tempdir().unwrap();
    let (code, outdir, err) = run_quietly(dir.path(), STACKED.as_bytes());
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("failed with explicit coupling")
            && err.contains("base/ymax – top/ymin coupled implicitly"),
        "{err}"
    );
    let (summary, v) = read_summary(&outdir.join("stacked"));
    assert_eq!(v["contacts"][0]["coupling"], "implicit", "{summary}");
    assert_eq!(
        v["coupling_switched"].as_array().map(|a| a.len()),
        Some(1),
        "{summary}"
    );
    // the switched run's answer is the uniaxial one
    let g = v["contacts"][0]["max_penetration"].as_f64().unwrap();
    let fy = v["patches"]["top/ymax"]["reaction_force"][1]
        .as_f64()
        .unwrap();
    let e_plane = 200.0 / (1.0 - 0.3 * 0.3);
    let expected = -e_plane * (0.008 - g) / 0.8 * 0.1;
    assert!(g > 0.0 && g < 1e-3, "penetration {g}");
    assert!(
        (fy / expected - 1.0).abs() < 1e-4,
        "{fy} against {expected}"
    );
    // both increments are in the results
    let history = std::fs::read_to_string(outdir.join("stacked/history.csv")).unwrap();
    assert_eq!(history.lines().count(), 3, "{history}");

    // kept explicit on request: the step is cut back instead, and the run
    // fails (exit code 1) with what it wrote so far
    let kept = STACKED.replace("[solver]\n", "[solver]\ncoupling_fallback = \"none\"\n");
    let (code, outdir, err) = run_quietly(dir.path(), kept.as_bytes());
    assert_eq!(code, 1, "{err}");
    assert!(!err.contains("coupled implicitly"), "{err}");
    assert!(err.contains("redone in steps of"), "{err}");
    let (summary, v) = read_summary(&outdir.join("stacked"));
    assert_eq!(v["contacts"][0]["coupling"], "explicit", "{summary}");
    assert!(v.get("coupling_switched").is_none(), "{summary}");
}

/// Issue 46's two-cylinder pair: the shipped concentric-cylinders case (thesis §4.4.1) with 8 cells through each
/// wall, 160 and 120 faces along the interface, penalty ×10 and
/// explicit coupling, by the segregated method: the explicit coupling
/// stalls (smallest residual 9.1e-3 at outer iteration 433, then a limit
/// cycle at 1e-3), and used to switch to implicit coupling only at
/// `max_outer`, after 50,000 outer iterations and 287 s.
fn two_tubes_explicit() -> String {
    let shipped = include_str!("../../../validation/cases/concentric-cylinders/case.toml");
    let case = shipped
        .replace("title = \"concentric-cylinders\"", "title = \"tubes\"")
        .replace("[solver]\n", "[solver]\nnonlinear = \"segregated\"\n")
        .replace("max_outer = 20000", "max_outer = 50000")
        .replace("cells = [10, 40, 1]", "cells = [8, 160, 1]")
        .replace("cells = [12, 30, 1]", "cells = [8, 120, 1]")
        .replace(
            "coupling = \"implicit\"",
            "coupling = \"explicit\"\npenalty_scale = 10",
        );
    assert_eq!(case.matches("[8, 1").count(), 2, "{case}");
    assert!(case.contains("max_outer = 50000") && case.contains("penalty_scale = 10"));
    case
}

#[test]
fn a_stalled_explicit_coupling_is_switched_within_about_a_thousand_iterations() {
    let dir = tempfile::tempdir().unwrap();
    let (code, outdir, err) = run_quietly(dir.path(), two_tubes_explicit().as_bytes());
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("explicit coupling stalled")
            && err.contains("outer/inner – inner/outer coupled implicitly"),
        "{err}"
    );
    let (summary, v) = read_summary(&outdir.join("tubes"));
    // 1,433 explicit (the stall seen 1,000 after the smallest residual)
    // and 395 implicit outer iterations
    let outer = v["outer_iterations"].as_u64().unwrap();
    assert!(outer < 3000, "{outer} outer iterations: {summary}");
    // Lamé for the composite tube: interface pressure 0.3469 p, on the
    // quarter interface π/2 · 1.4 · 0.1
    let lame = 0.3469 * 10.0 * std::f64::consts::FRAC_PI_2 * 1.4 * 0.1;
    let fn_ = v["contacts"][0]["normal_force"].as_f64().unwrap();
    assert!((fn_ / lame - 1.0).abs() < 2e-3, "{fn_} against Lamé {lame}");
    // the final block (standard output, and the log) gives the same figure
    let line = format!(
        "contact outer/inner – inner/outer: normal force {}",
        solver_app::words::Num(fn_)
    );
    let log = std::fs::read_to_string(outdir.join("tubes/log.txt")).unwrap();
    assert!(log.contains(&line), "{line} not in:\n{log}");
}

/// A mesh one cell thick whose front and back have no condition is a 3-D
/// slab (traction-free faces), not a 2-D model: `fvc check` says so, and
/// says nothing once they are `empty`.
#[test]
fn check_notes_a_one_cell_thick_mesh_left_traction_free() {
    let dir = tempfile::tempdir().unwrap();
    let slab = GOOD.replace("cells = [4, 4, 4]", "cells = [4, 4, 1]");
    let p = write(dir.path(), "case.toml", slab.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        err.contains(
            "body 'block', patches 'zmin' and 'zmax': the front and back faces of every cell"
        ) && err.contains("give the front and back type = \"empty\""),
        "{err}"
    );
    let plane = format!(
        "{slab}[body.boundary.zmin]\ntype = \"empty\"\n[body.boundary.zmax]\ntype = \"empty\"\n"
    );
    let p = write(dir.path(), "case.toml", plane.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        !out.contains("3-D slab") && !err.contains("3-D slab"),
        "{out}{err}"
    );
}

#[test]
fn check_reports_a_benchmark_polymesh() {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/benchmarks");
    let archive = shared.join("twisting-hemisphere/mesh/polyMesh_coarse.tar.xz");
    if !archive.is_file() {
        eprintln!("skipped: ../shared not found ({})", archive.display());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let status = Command::new("tar")
        .arg("-xJf")
        .arg(&archive)
        .arg("-C")
        .arg(dir.path())
        .status()
        .unwrap();
    assert!(status.success());
    let case = r#"title = "hemisphere-mesh"
[time]
end = 1.0
steps = 1
[[body]]
name = "sphere"
mesh = { polymesh = "polyMesh", zone = "sphere" }
material = { model = "linear-elastic", E = 10.0, nu = 0.3 }
[body.boundary.sphere-displacement]
type = "displacement"
value = [0, 0, -0.1]
[[body]]
name = "block"
mesh = { polymesh = "polyMesh", zone = "block" }
material = { model = "linear-elastic", E = 50.0, nu = 0.3 }
[body.boundary.block-fixed]
type = "displacement"
value = [0, 0, 0]
"#;
    let p = write(dir.path(), "case.toml", case.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    eprintln!("{out}");
    assert!(out.contains("body 'sphere': 1620 cells"), "{out}");
    assert!(out.contains("body 'block': 729 cells"), "{out}");
    assert!(out.contains("sphere-contact"));
    // an unknown zone lists the valid ones
    let bad = case.replace("zone = \"block\"", "zone = \"plate\"");
    let p = write(dir.path(), "case.toml", bad.as_bytes());
    let (code, _, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        err.contains("plate") && err.contains("sphere") && err.contains("block"),
        "{err}"
    );
}

/// Runs GOOD with `max_outer = 2` (every attempt fails, every cut-back
/// too) under the given `on_nonconvergence`, `large` selecting the updated
/// Lagrangian form (nonlinear, so failed steps are cut back); returns the
/// exit code and the (time, block/ymax:Fy) rows of history.csv.
fn run_unconverged(policy: &str, large: bool) -> (i32, Vec<(f64, f64)>, String) {
    let dir = tempfile::tempdir().unwrap();
    let strain = if large {
        "[analysis]\nstrain = \"large\"\n"
    } else {
        ""
    };
    let case = GOOD.replace(
        "tolerance = 1e-6",
        &format!("tolerance = 1e-12\nmax_outer = 2\non_nonconvergence = \"{policy}\""),
    );
    let case = case.replacen("[time]", &format!("{strain}[time]"), 1);
    let (code, outdir, err) = run_quietly(dir.path(), case.as_bytes());
    let hist = std::fs::read_to_string(outdir.join("block/history.csv")).unwrap();
    let mut lines = hist.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let fy = head.iter().position(|h| *h == "block/ymax:Fy").unwrap();
    let rows = lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0], v[fy])
        })
        .collect();
    (code, rows, err)
}

/// A sub-step that fails after the last cut-back: under `continue` the
/// increment goes on to its end time (the fields then belong to that time);
/// under `abort` the run stops and the history row carries the time the
/// fields belong to, the first sub-step's (0.5/2⁴), not the increment's.
#[test]
fn unconverged_sub_steps_are_reported_at_their_own_time() {
    // `continue` warns and goes on: exit 0 (CASE_FORMAT.md, "Exit codes")
    let (code, rows, err) = run_unconverged("continue", true);
    assert_eq!(code, 0, "{err}");
    let times: Vec<f64> = rows.iter().map(|r| r.0).collect();
    assert_eq!(times, vec![0.5, 1.0], "{err}");
    // the boundary moved the full 0.01 by t = 1: the reaction is of the
    // full step (beyond E ε A = 2 N), not that of the sub-step t = 0.53
    let fy = rows[1].1;
    assert!(fy < -2.0, "reaction at t = 1: {fy}");

    let (code, rows, err) = run_unconverged("abort", true);
    assert_eq!(code, 1, "{err}");
    assert_eq!(rows.len(), 1, "{err}");
    assert!((rows[0].0 - 0.5 / 16.0).abs() < 1e-12, "{rows:?}");
}

/// A linear problem (GOOD: small strain, Hooke's law, no contact) that
/// fails to converge is not cut back — a smaller step converges no faster
/// — and says so; it stops at the increment's own time.
#[test]
fn a_linear_problem_is_not_cut_back() {
    let (code, rows, err) = run_unconverged("abort", false);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("not redone in smaller steps: the problem is linear"),
        "{err}"
    );
    assert!(!err.contains("redone in steps of"), "{err}");
    assert_eq!(rows.len(), 1, "{err}");
    assert!((rows[0].0 - 0.5).abs() < 1e-12, "{rows:?}");
    // under `continue` both increments are kept
    let (code, rows, err) = run_unconverged("continue", false);
    assert_eq!(code, 0, "{err}");
    let times: Vec<f64> = rows.iter().map(|r| r.0).collect();
    assert_eq!(times, vec![0.5, 1.0], "{err}");
}

/// A plane Gmsh mesh (`gmsh -2`): a 2 × 1 plate of two triangles (one
/// written clockwise) and a quadrangle, physical curves "left", "bottom"
/// and "right", physical surface "plate".
const PLANE_MSH: &str = include_str!("../../../fv-mesh/tests/data/plate_2d.msh");

/// A plane mesh runs as a plane-strain problem once its `frontAndBack`
/// patch is `empty`: uniaxial stress σ on the plate, symmetric on the left
/// and bottom edges, gives ε_xx = σ(1 − ν²)/E, ε_yy = −σν(1 + ν)/E in every
/// cell (the patch test, exact for the least-squares gradient).
#[test]
fn a_plane_gmsh_mesh_runs_as_plane_strain() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "plate.msh", PLANE_MSH.as_bytes());
    let case = r#"title = "plate"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-9
[[body]]
name = "plate"
mesh = { file = "plate.msh" }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
[body.boundary.left]
type = "symmetry"
[body.boundary.bottom]
type = "symmetry"
[body.boundary.right]
type = "traction"
value = [1.0, 0, 0]
[body.boundary.frontAndBack]
type = "empty"
"#;
    let (code, outdir, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 0, "{err}");
    let file = hdf5::File::open(outdir.join("plate").join("plate.h5")).unwrap();
    let u = file
        .dataset("time/1/plate/displacement")
        .unwrap()
        .read_2d::<f64>()
        .unwrap();
    let (e, nu) = (200.0, 0.3);
    let (exx, eyy) = ((1.0 - nu * nu) / e, -nu * (1.0 + nu) / e);
    // cell centres: the two triangles' centroids, then the quadrangle's
    for (c, (x, y)) in [(2.0 / 3.0, 1.0 / 3.0), (1.0 / 3.0, 2.0 / 3.0), (1.5, 0.5)]
        .into_iter()
        .enumerate()
    {
        assert!(
            (u[[c, 0]] - exx * x).abs() < 1e-6 * exx,
            "cell {c}: u_x {}",
            u[[c, 0]]
        );
        assert!(
            (u[[c, 1]] - eyy * y).abs() < 1e-6 * exx,
            "cell {c}: u_y {}",
            u[[c, 1]]
        );
        assert_eq!(u[[c, 2]], 0.0);
    }
    // plane strain: σ_zz = ν σ_xx
    let stress = |file: &hdf5::File| {
        file.dataset("time/1/plate/stress")
            .unwrap()
            .read_2d::<f64>()
            .unwrap()
    };
    let s = stress(&file);
    for c in 0..3 {
        assert!((s[[c, 0]] - 1.0).abs() < 1e-6, "σ_xx {}", s[[c, 0]]);
        assert!((s[[c, 2]] - nu).abs() < 1e-6, "σ_zz {}", s[[c, 2]]);
    }
    // plane stress: ε_xx = σ/E, ε_yy = −ν σ/E, and nothing out of the
    // plane (the material's λ* leaves a σ_zz of its own, not reported)
    let plane_stress = case.replace("nu = 0.3 }", "nu = 0.3, plane_stress = true }");
    drop(file);
    let (code, outdir, err) = run_quietly(dir.path(), plane_stress.as_bytes());
    assert_eq!(code, 0, "{err}");
    let file = hdf5::File::open(outdir.join("plate").join("plate.h5")).unwrap();
    let u = file
        .dataset("time/1/plate/displacement")
        .unwrap()
        .read_2d::<f64>()
        .unwrap();
    let (exx, eyy) = (1.0 / e, -nu / e);
    for (c, (x, y)) in [(2.0 / 3.0, 1.0 / 3.0), (1.0 / 3.0, 2.0 / 3.0), (1.5, 0.5)]
        .into_iter()
        .enumerate()
    {
        assert!(
            (u[[c, 0]] - exx * x).abs() < 1e-6 * exx,
            "cell {c}: u_x {}",
            u[[c, 0]]
        );
        assert!(
            (u[[c, 1]] - eyy * y).abs() < 1e-6 * exx,
            "cell {c}: u_y {}",
            u[[c, 1]]
        );
    }
    let s = stress(&file);
    let von_mises = file
        .dataset("time/1/plate/von_mises")
        .unwrap()
        .read_1d::<f64>()
        .unwrap();
    for c in 0..3 {
        assert!((s[[c, 0]] - 1.0).abs() < 1e-6, "σ_xx {}", s[[c, 0]]);
        assert_eq!(s[[c, 2]], 0.0, "σ_zz");
        assert!(
            (von_mises[c] - 1.0).abs() < 1e-6,
            "von Mises {}",
            von_mises[c]
        );
    }
}

/// `zone` picks one body of a Gmsh file by its physical group; an unknown
/// name is refused with the valid ones.
#[test]
fn a_gmsh_zone_selects_a_body_and_an_unknown_one_is_named() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "plate.msh", PLANE_MSH.as_bytes());
    let case = |zone: &str| {
        format!(
            r#"title = "plate"
[time]
end = 1.0
steps = 1
[[body]]
name = "plate"
mesh = {{ file = "plate.msh", zone = "{zone}" }}
material = {{ model = "linear-elastic", E = 200.0, nu = 0.3 }}
[body.boundary.left]
type = "displacement"
value = [0, 0, 0]
[body.boundary.frontAndBack]
type = "empty"
"#
        )
    };
    let (code, _, err) = fvc(&[
        "check",
        write(dir.path(), "a.toml", case("plate").as_bytes())
            .to_str()
            .unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    expect_input_error(
        dir.path(),
        case("plat").as_bytes(),
        &["body[0].mesh.zone", "no zone named 'plat'", "plate"],
    );
}

/// Two hexahedra side by side; the physical surface "mid" holds their
/// shared, interior face (fv-mesh/tests/data/two_cubes_mid.geo).
const TWO_CUBES_MID: &str = include_str!("../../../fv-mesh/tests/data/two_cubes_mid.msh");

/// The same two hexahedra sharing no face (fv-mesh/tests/data/
/// two_cubes_apart.geo: two Gmsh volumes not fragmented).
const TWO_CUBES_APART: &str = include_str!("../../../fv-mesh/tests/data/two_cubes_apart.msh");

/// A body of the two-cube mesh `msh`, held at xmin and pulled at xmax.
fn two_cubes_case(msh: &str) -> String {
    format!(
        r#"title = "cubes"
[time]
end = 1.0
steps = 1
[[body]]
name = "solid"
mesh = {{ file = "{msh}" }}
material = {{ model = "linear-elastic", E = 200.0, nu = 0.3 }}
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.xmax]
type = "traction"
value = [1.0, 0, 0]
"#
    )
}

/// A condition on a patch without faces (here a physical surface of
/// interior faces) would act on nothing: exit 2 naming the patch. The same
/// mesh runs without it, the patch being empty.
#[test]
fn a_condition_on_a_patch_without_faces_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "cubes.msh", TWO_CUBES_MID.as_bytes());
    let case = two_cubes_case("cubes.msh");
    let with_mid = format!("{case}[body.boundary.mid]\ntype = \"traction\"\nvalue = [5.0, 0, 0]\n");
    let (code, _, err) = run_quietly(dir.path(), with_mid.as_bytes());
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("body[0].boundary.mid") && err.contains("has no faces"),
        "{err}"
    );
    let (code, _, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 0, "{err}");
}

/// Finite-strain plane stress reports the Cauchy stress (the momentum
/// balance carries λ_z σ): a neo-Hookean plate stretched to 1.5 in
/// uniaxial stress has σ_xx = μ J^(−5/3) (λ² − s²), J = λ s², with s the
/// root of (K/2)(J² − 1) = (μ/3) J^(−2/3) (λ² − s²), and σ_zz = 0.
#[test]
fn finite_strain_plane_stress_reports_the_cauchy_stress() {
    let dir = tempfile::tempdir().unwrap();
    let case = r#"title = "sheet"
[analysis]
strain = "large"
[time]
end = 1.0
steps = 5
[solver]
tolerance = 1e-10
[[body]]
name = "sheet"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [3, 3, 1] }
material = { model = "neo-hookean", E = 1000.0, nu = 0.3, plane_stress = true }
[body.boundary.xmin]
type = "symmetry"
[body.boundary.ymin]
type = "symmetry"
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[body.boundary.xmax]
type = "normal-displacement"
value = { table = [[0.0, 0.0], [1.0, 0.5]] }
"#;
    let (code, outdir, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 0, "{err}");
    let (mu, k, a) = (1000.0 / 2.6, 1000.0 / 1.2, 1.5f64);
    let g = |s: f64| {
        let j = a * s * s;
        0.5 * k * (j * j - 1.0) - mu / 3.0 * j.powf(-2.0 / 3.0) * (a * a - s * s)
    };
    let (mut lo, mut hi) = (0.5, 1.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let s = 0.5 * (lo + hi);
    let sxx = mu * (a * s * s).powf(-5.0 / 3.0) * (a * a - s * s);
    let file = hdf5::File::open(outdir.join("sheet").join("sheet.h5")).unwrap();
    let stress = file
        .dataset("time/5/sheet/stress")
        .unwrap()
        .read_2d::<f64>()
        .unwrap();
    for c in 0..9 {
        assert!(
            (stress[[c, 0]] - sxx).abs() < 1e-6 * sxx,
            "σ_xx {} vs {sxx}",
            stress[[c, 0]]
        );
        assert!(stress[[c, 1]].abs() < 1e-6 * sxx, "σ_yy {}", stress[[c, 1]]);
        assert_eq!(stress[[c, 2]], 0.0, "σ_zz");
    }
}

/// Finite-strain plane stress solves for the thickness along z: a body
/// that is not a plane model (no `empty` z faces) is refused.
#[test]
fn finite_strain_plane_stress_needs_a_plane_model() {
    let dir = tempfile::tempdir().unwrap();
    let case = GOOD
        .replacen("[time]", "[analysis]\nstrain = \"large\"\n[time]", 1)
        .replace("nu = 0.3 }", "nu = 0.3, plane_stress = true }");
    let (code, _, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("body[0].material") && err.contains("plane_stress"),
        "{err}"
    );
}

/// Two hexahedra side by side that share no face (two Gmsh volumes not
/// fragmented; fv-mesh/tests/data/two_cubes_apart.geo): the right one is
/// held by nothing. Refused before solving (exit 2) naming the region,
/// instead of a linear-solver breakdown (exit 1).
#[test]
fn a_part_of_a_body_held_by_nothing_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "apart.msh", TWO_CUBES_APART.as_bytes());
    let case = two_cubes_case("apart.msh");
    let (code, _, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("region1 of 2")
            && err.contains("zone = \"region1\"")
            && err.contains("not held in the x direction"),
        "{err}"
    );
    // the two cubes meet on a face each, at x = 0.5, without sharing its
    // points: a crack, which the log names (`fvc check` too)
    let (code, out, err) = fvc(&["check", dir.path().join("case.toml").to_str().unwrap()]);
    let all = format!("{out}{err}");
    assert!(
        all.contains("1 pair of boundary faces lie on each other") && all.contains("(0.5, "),
        "{code}: {all}"
    );
}

/// A neo-Hookean tube (r 1–2, E = 1) inflated past its limit pressure
/// (about 0.19) in one increment.
const TUBE_PAST_ITS_LIMIT: &str = r#"title = "tube"
[analysis]
strain = "large"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-8
[[body]]
name = "tube"
mesh = { generator = "annulus", r_inner = 1.0, r_outer = 2.0, theta0 = 0, theta1 = 90, z1 = 0.1, cells = [20, 30, 1] }
material = { model = "neo-hookean", E = 1.0, nu = 0.3 }
[body.boundary.inner]
type = "pressure"
value = { table = [[0.0, 0.0], [1.0, 0.2]] }
[body.boundary.start]
type = "symmetry"
[body.boundary.end]
type = "symmetry"
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
"#;

/// The increment fails after sub-steps of its cut-backs converged (the
/// tube inflates up to t ≈ 0.94, then no equilibrium exists): the last
/// converged sub-step is written as increment 1 at its own time, with its
/// fields and its history row, and the summary reports it, not the
/// diverged iterate. Before, the results held no increment at all
/// (check-results: "no /time/<k> groups").
#[test]
fn a_failed_increment_keeps_its_last_converged_sub_step() {
    let dir = tempfile::tempdir().unwrap();
    let (code, outdir, err) = run_quietly(dir.path(), TUBE_PAST_ITS_LIMIT.as_bytes());
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("is written as increment 1"), "{err}");
    let res = outdir.join("tube");
    let hist = std::fs::read_to_string(res.join("history.csv")).unwrap();
    let rows: Vec<&str> = hist.lines().skip(1).collect();
    assert_eq!(rows.len(), 1, "{hist}");
    let t: f64 = rows[0].split(',').next().unwrap().parse().unwrap();
    assert!(t > 0.5 && t < 1.0, "time {t}");
    let file = hdf5::File::open(res.join("tube.h5")).unwrap();
    let g = file.group("time/1").unwrap();
    let time: f64 = g.attr("time").unwrap().read_scalar().unwrap();
    let converged: u8 = g.attr("converged").unwrap().read_scalar().unwrap();
    assert_eq!((time, converged), (t, 1));
    let u = file
        .dataset("time/1/tube/displacement")
        .unwrap()
        .read_2d::<f64>()
        .unwrap();
    assert!(u.iter().all(|x| x.is_finite()));
    let (_, v) = read_summary(&res);
    assert_eq!(v["converged"], false);
    assert!(v["outer_iterations"].as_u64().unwrap() > 0);
}

/// Nothing prescribed changes over the step (the pressure is a constant,
/// applied in full from the first increment): an increment that does not
/// converge is not redone in smaller steps, which would be the same
/// problem, and the message says how to ramp the load.
#[test]
fn a_constant_load_is_not_cut_back() {
    let dir = tempfile::tempdir().unwrap();
    let case = TUBE_PAST_ITS_LIMIT
        .replace("{ table = [[0.0, 0.0], [1.0, 0.2]] }", "0.1")
        .replace(
            "tolerance = 1e-8",
            "nonlinear = \"segregated\"\ntolerance = 1e-8\nmax_outer = 5",
        );
    let (code, _, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("not redone in smaller steps"), "{err}");
    assert!(err.contains("as a table"), "{err}");
    assert!(!err.contains("redone in steps of"), "{err}");
}

/// Two blocks (10 × 10 cells of 0.1) whose contact surfaces start
/// overlapping by `overlap`.
fn overlapping_blocks(overlap: f64) -> String {
    format!(
        r#"title = "overlap"
[time]
end = 1.0
steps = 1
[[body]]
name = "lower"
mesh = {{ generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [10, 10, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.ymin]
type = "symmetry"
[body.boundary.xmin]
type = "symmetry"
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[body]]
name = "upper"
mesh = {{ generator = "box", min = [0, {y0}, 0], max = [1, {y1}, 0.1], cells = [10, 10, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.ymax]
type = "normal-displacement"
value = 0.0
[body.boundary.xmin]
type = "symmetry"
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[contact]]
master = "lower/ymax"
slave = "upper/ymin"
coupling = "implicit"
"#,
        y0 = 1.0 - overlap,
        y1 = 2.0 - overlap
    )
}

/// Surfaces that start overlapping by 2.5 cell heights: the contact search
/// (one cell height into each body) finds no pairs there, and the run
/// converged in one iteration with no contact force. Refused now, naming
/// the contact; an overlap of 1.5 cell heights still runs, with the force
/// of the pressed stack (E′ ε A = 1098.9 · 0.075 · 0.1 = 8.24, less the
/// penalty's give).
#[test]
fn surfaces_overlapping_beyond_the_search_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    expect_input_error(
        dir.path(),
        overlapping_blocks(0.25).as_bytes(),
        &[
            "contact[0].slave",
            "start overlapping deeper than the contact search reaches",
            "'upper/ymin'",
            "body 'lower'",
        ],
    );
    let force = first_contact_force(dir.path(), &overlapping_blocks(0.15), "overlap");
    assert!(force > 7.0 && force < 8.3, "normal force {force}");
    // placed through each other (the upper spans y −0.001…0.999) or on top
    // of each other: each contact surface lies outside the other body, so
    // the faces alone did not show it and the run solved with no contact
    // force (found by a probe, 2026-12-01); the cells show it
    for overlap in [1.001, 1.0] {
        expect_input_error(
            dir.path(),
            overlapping_blocks(overlap).as_bytes(),
            &[
                "contact[0].",
                "start overlapping deeper than the contact search reaches",
                "cell ",
                "lies inside body",
            ],
        );
    }
}

/// A rigid floor of one cell layer (0.65 high) whose top starts 0.45
/// inside a block: within the layer the search reaches, but deeper than
/// the face boxes' extrusions (the two surfaces' mean face sizes, 0.224 +
/// 0.158), so no pair was found and the block went through the floor
/// with no contact force (found by a probe, 2026-11-30). Refused now; at
/// 0.30 it runs.
#[test]
fn a_deep_overlap_within_one_cell_layer_is_refused() {
    let case = |top: f64| {
        format!(
            r#"title = "deep"
[time]
end = 1.0
steps = 2
[[body]]
name = "block"
mesh = {{ generator = "box", min = [0.0, 0.0, 0.0], max = [1.0, 0.5, 0.1], cells = [4, 2, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.ymax]
type = "displacement"
value = {{ table = [[0.0, [0.0, 0.0, 0.0]], [1.0, [0.0, -0.005, 0.0]]] }}
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[body]]
name = "floor"
mesh = {{ generator = "box", min = [-1.0, -0.2, 0.0], max = [2.0, {top}, 0.1], cells = [6, 1, 1] }}
rigid = true
[body.boundary.ymin]
type = "displacement"
value = [0.0, 0.0, 0.0]
[[contact]]
master = "floor/ymax"
slave = "block/ymin"
"#
        )
    };
    let dir = tempfile::tempdir().unwrap();
    expect_input_error(
        dir.path(),
        case(0.45).as_bytes(),
        &[
            "contact[0]",
            "start overlapping deeper than the contact search reaches",
            "deeper than the search's reach there",
        ],
    );
    let force = first_contact_force(dir.path(), &case(0.3), "deep");
    assert!(force > 0.0, "normal force {force}");
}

/// A time table that ends before `[time] end` holds its last value, as
/// the contract says; the log says so (usually a ramp meant to reach the
/// end), naming the key.
#[test]
fn a_table_ending_early_is_noted_in_the_log() {
    let dir = tempfile::tempdir().unwrap();
    let case = GOOD.replace("[1.0, [0, -0.01, 0]]", "[0.5, [0, -0.01, 0]]");
    let (code, _, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("body[0].boundary.ymax.value: the table ends at t = 0.5"),
        "{err}"
    );
    let (code, _, err) = run_quietly(dir.path(), GOOD.as_bytes());
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("the table ends"), "{err}");
}

/// Writes a polyMesh of two unit hexahedra along x into `dir/polyMesh`:
/// patches `left` (x = 0), `right` (x = 2), `walls` (y) of type `walls`
/// and `frontAndBack` (z) of type `sides`.
fn write_two_hex_polymesh(dir: &Path, walls: &str, sides: &str) {
    let d = dir.join("polyMesh");
    std::fs::create_dir_all(&d).unwrap();
    let head = |class: &str, object: &str| {
        format!("FoamFile\n{{\n    version 2.0;\n    format ascii;\n    class {class};\n    object {object};\n}}\n")
    };
    let files = [
        ("points", head("vectorField", "points") + "12\n(\n(0 0 0) (1 0 0) (2 0 0) (0 1 0) (1 1 0) (2 1 0)\n(0 0 1) (1 0 1) (2 0 1) (0 1 1) (1 1 1) (2 1 1)\n)\n"),
        ("faces", head("faceList", "faces") + "11\n(\n4(1 4 10 7)\n4(0 6 9 3)\n4(2 5 11 8)\n4(0 1 7 6)\n4(3 9 10 4)\n4(1 2 8 7)\n4(4 10 11 5)\n4(0 3 4 1)\n4(6 7 10 9)\n4(1 4 5 2)\n4(7 8 11 10)\n)\n"),
        ("owner", head("labelList", "owner") + "11\n(\n0 0 1 0 0 1 1 0 0 1 1\n)\n"),
        ("neighbour", head("labelList", "neighbour") + "1\n(\n1\n)\n"),
        ("boundary", head("polyBoundaryMesh", "boundary") + &format!("4\n(\n    left {{ type patch; nFaces 1; startFace 1; }}\n    right {{ type patch; nFaces 1; startFace 2; }}\n    walls {{ type {walls}; nFaces 4; startFace 3; }}\n    frontAndBack {{ type {sides}; nFaces 4; startFace 7; }}\n)\n")),
    ];
    for (name, text) in files {
        write(&d, name, text.as_bytes());
    }
}

/// An OpenFOAM constraint type on a patch the case does not list is that
/// condition (not the traction-free default of an unlisted patch), with a
/// note; a decomposed mesh's processor patch is refused; `fvc check`
/// refuses what `fvc run` would (a body nothing holds).
#[test]
fn polymesh_patch_types_and_check_agree_with_run() {
    let dir = tempfile::tempdir().unwrap();
    write_two_hex_polymesh(dir.path(), "wall", "empty");
    let case = br#"title = "two-hex"
[time]
end = 1.0
steps = 1
[[body]]
name = "bar"
mesh = { polymesh = "polyMesh" }
material = { model = "linear-elastic", E = 100.0, nu = 0.3 }
[body.boundary.left]
type = "displacement"
value = [0, 0, 0]
[body.boundary.right]
type = "traction"
value = [1, 0, 0]
"#;
    let p = write(dir.path(), "case.toml", case);
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("patch 'frontAndBack' is not in the case and is of type empty in the mesh: taken as type = \"empty\""),
        "{out}{err}"
    );
    let (code, outdir, err) = run_quietly(dir.path(), case);
    assert_eq!(code, 0, "{err}");
    let log = std::fs::read_to_string(outdir.join("two-hex/log.txt")).unwrap();
    assert!(log.contains("taken as type = \"empty\""), "{log}");
    // plane strain: the pull carried by the fixed end, 1 × area 1
    let (summary, v) = read_summary(&outdir.join("two-hex"));
    let fx = v["patches"]["bar/left"]["reaction_force"][0]
        .as_f64()
        .unwrap();
    assert!((fx + 1.0).abs() < 1e-6, "{summary}");

    // `fvc check`'s message for the mesh with its `walls` patch of type
    // `walls`, after asserting that it refuses it
    let refused = |walls: &str| {
        write_two_hex_polymesh(dir.path(), walls, "empty");
        let (code, _, err) = fvc(&["check", p.to_str().unwrap()]);
        assert_eq!(code, 2, "{err}");
        err
    };
    // a piece of a decomposed mesh
    let err = refused("processor");
    assert!(
        err.contains("'walls'") && err.contains("reconstructParMesh"),
        "{err}"
    );
    // a periodic patch the case leaves out
    let err = refused("cyclic");
    assert!(
        err.contains("body[0].boundary.walls") && err.contains("cyclic"),
        "{err}"
    );

    // nothing holds the bar in z: check says so, as run does
    write_two_hex_polymesh(dir.path(), "wall", "patch");
    let free = String::from_utf8_lossy(case).replace(
        "[body.boundary.left]\ntype = \"displacement\"\nvalue = [0, 0, 0]",
        "[body.boundary.left]\ntype = \"symmetry\"",
    );
    let p = write(dir.path(), "case.toml", free.as_bytes());
    let (code, _, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("is not held in the"), "{err}");
    let (code, _, err) = run_quietly(dir.path(), free.as_bytes());
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("is not held in the"), "{err}");
}

/// `check` prints each contact's normal penalty scale and augmentation
/// and why: 5 and no augmentation for the example's curved cylinder on its
/// rigid flat (not given), 1 for a block face across a rigid plate's
/// (not given), augmentation for the block's top under the plate, and the
/// case's own values when given.
#[test]
fn check_reports_the_penalty_scale_of_each_contact_and_why() {
    let example =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/hertz-cylinder/case.toml");
    let (code, out, err) = fvc(&["check", example.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("contact[0] cylinder/contact on flat/ymax: algorithm segment-to-segment (not given; the thesis's); penalty_scale 5 (not given; a curved surface on a rigid plane); augmentation off (not given; the plain penalty)"),
        "{out}"
    );
    let dir = tempfile::tempdir().unwrap();
    let plate = format!("{GOOD}{RIGID_PLATE}")
        + "[[contact]]\nmaster = \"plate/ymin\"\nslave = \"block/xmax\"\n";
    let p = write(dir.path(), "case.toml", plate.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains(
            "contact[0] block/xmax on plate/ymin: algorithm segment-to-segment (not given; the thesis's); penalty_scale 1 (not given; the thesis's)"
        ),
        "{out}"
    );
    let given = plate + "penalty_scale = 2.5\naugmentation = true\n";
    let p = write(dir.path(), "case.toml", given.as_bytes());
    let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("penalty_scale 2.5 (given); augmentation on (given)"),
        "{out}"
    );
    // the block's top free for the contact
    let free_top = GOOD.replace(
        "[body.boundary.ymax]\ntype = \"displacement\"\nvalue = { table = [[0.0, [0, 0, 0]], [1.0, [0, -0.01, 0]]] }\n",
        "",
    );
    assert_ne!(free_top, GOOD);
    let on_top = |plate: &str| {
        let case = format!("{free_top}{plate}")
            + "[[contact]]\nmaster = \"plate/ymin\"\nslave = \"block/ymax\"\n";
        let p = write(dir.path(), "case.toml", case.as_bytes());
        let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
        assert_eq!(code, 0, "{out}{err}");
        out
    };
    let out = on_top(RIGID_PLATE);
    assert!(
        out.contains("augmentation on (not given; two flat faces"),
        "{out}"
    );
}

/// `check` names the contact algorithm and why: pointwise for friction on
/// a plastic block under a flat rigid plate, the thesis's
/// segment-to-segment without friction or for an elastic block, and the
/// case's own when given.
#[test]
fn check_reports_the_contact_algorithm_and_why() {
    let dir = tempfile::tempdir().unwrap();
    let free_top = GOOD.replace(
        "[body.boundary.ymax]\ntype = \"displacement\"\nvalue = { table = [[0.0, [0, 0, 0]], [1.0, [0, -0.01, 0]]] }\n",
        "",
    );
    let plastic = free_top.replace(
        "material = { model = \"linear-elastic\", E = 200.0, nu = 0.3 }\n[body.boundary",
        "material = { model = \"neo-hookean-plastic\", E = 200.0, nu = 0.3, yield = 1, hardening = 1 }\n[body.boundary",
    );
    assert_ne!(plastic, free_top);
    let check = |block: &str, contact: &str| {
        let case = format!("{block}{RIGID_PLATE}")
            + "[[contact]]\nmaster = \"plate/ymin\"\nslave = \"block/ymax\"\n"
            + contact;
        let p = write(dir.path(), "case.toml", case.as_bytes());
        let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
        assert_eq!(code, 0, "{out}{err}");
        out
    };
    let out = check(&plastic, "friction = 0.1\n");
    assert!(
        out.contains(
            "algorithm pointwise (not given; friction on a plastic slave against a flat master"
        ),
        "{out}"
    );
    for (block, contact) in [(&plastic, ""), (&free_top, "friction = 0.1\n")] {
        let out = check(block, contact);
        assert!(
            out.contains("algorithm segment-to-segment (not given; the thesis's)"),
            "{out}"
        );
    }
    let out = check(
        &plastic,
        "friction = 0.1\nalgorithm = \"segment-to-segment\"\n",
    );
    assert!(
        out.contains("algorithm segment-to-segment (given)"),
        "{out}"
    );
}

/// A block that only a frictionless floor holds sideways is not held
/// there: `check` and `run` stop with exit 2 naming the body, the
/// direction and the contact; symmetry planes or friction make it valid.
#[test]
fn frictionless_floor_alone_does_not_hold_a_block_sideways() {
    let case = |extra_block: &str, contact: &str| {
        block_on_floor(
            "block-on-floor",
            ("0", "0.5"),
            &format!("[body.boundary.zmax]\ntype = \"normal-displacement\"\nvalue = -0.01\n{extra_block}"),
            contact,
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "case.toml", case("", "").as_bytes());
    let out_dir = dir.path().join("results");
    let (path, out_dir) = (p.to_str().unwrap(), out_dir.to_str().unwrap());
    for (cmd, args) in [
        ("check", vec!["check", path]),
        ("run", vec!["run", path, "--quiet", "--output", out_dir]),
    ] {
        let (code, out, err) = fvc(&args);
        assert_eq!(code, 2, "{cmd}: {out}{err}");
        assert!(
            err.contains("body 'block' is not held in the x direction: frictionless contact on flat faces along it (contact[0] block/zmin on floor/zmax)"),
            "{cmd}: {err}"
        );
        assert!(err.contains("case.toml:"), "{err}");
    }
    for (extra, contact) in [
        ("[body.boundary.xmin]\ntype = \"symmetry\"\n[body.boundary.ymin]\ntype = \"symmetry\"\n", ""),
        ("", "friction = 0.2\n"),
    ] {
        let p = write(dir.path(), "case.toml", case(extra, contact).as_bytes());
        let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
        assert_eq!(code, 0, "{out}{err}");
    }
}

/// A block that only contact holds, 1e-4 above a rigid floor and pressed
/// by a pressure: Newton–Krylov starts it translated along its load into
/// contact (`contact_closing_translations`; before, its first direction
/// threw the block off and the run failed), and carries p A = 1 into the
/// floor, as the segregated method and the same load as a total force do.
#[test]
fn pressure_on_a_body_that_contact_alone_holds_reaches_the_floor() {
    let case = |load: &str| {
        block_on_floor(
            "float",
            ("0.0001", "0.5001"),
            &format!(
                "[body.boundary.zmax]\n{load}\n[body.boundary.xmin]\ntype = \"symmetry\"\n\
                 [body.boundary.ymin]\ntype = \"symmetry\"\n"
            ),
            "",
        )
    };
    let pressure = case("type = \"pressure\"\nvalue = 1.0");
    let segregated = pressure.replace(
        "steps = 1\n",
        "steps = 1\n[solver]\nnonlinear = \"segregated\"\n",
    );
    let force = case("type = \"force\"\nvalue = [0, 0, -1.0]");
    // Newton–Krylov: 1 in 3 Newton iterations; segregated: 1 (1,063 outer
    // iterations); the force condition: 1.00005 (55 Newton iterations)
    for (label, text, most) in [
        ("newton-krylov", &pressure, 10.0),
        ("segregated", &segregated, 5000.0),
        ("force", &force, 200.0),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let (code, out, err) = run_quietly(dir.path(), text.as_bytes());
        assert_eq!(code, 0, "{label}: {err}");
        let (summary, v) = read_summary(&out.join("float"));
        let f = v["contacts"][0]["normal_force"].as_f64();
        assert!(
            f.is_some_and(|f| (f - 1.0).abs() < 1e-3),
            "{label}: {summary}"
        );
        let its = v["outer_iterations"].as_f64();
        assert!(its.is_some_and(|n| n <= most), "{label}: {summary}");
    }
}

/// A 1 × 1 × 0.5 block of 4 × 4 × 2 cells between heights `z` (E = 1000,
/// ν = 0.3) with the condition tables `block`, over a rigid floor at
/// z = 0, the block's bottom the slave of one contact with the `contact`
/// keys.
fn block_on_floor(title: &str, z: (&str, &str), block: &str, contact: &str) -> String {
    let (z0, z1) = z;
    format!(
        r#"title = "{title}"
[time]
end = 1.0
steps = 1
[[body]]
name = "block"
mesh = {{ generator = "box", min = [0, 0, {z0}], max = [1, 1, {z1}], cells = [4, 4, 2] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
{block}[[body]]
name = "floor"
rigid = true
mesh = {{ generator = "box", min = [-1, -1, -0.2], max = [2, 2, 0], cells = [1, 1, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[[contact]]
master = "floor/zmax"
slave = "block/zmin"
{contact}"#
    )
}

/// A plane-strain block pressed onto a rigid floor (μ = 0.3), then pushed
/// sideways by a traction that passes μN at t ≈ 1.69: no equilibrium
/// exists beyond, and the run fails after converged sub-steps of its
/// second increment.
const BLOCK_PUSHED_PAST_FRICTION: &str = r#"title = "pushed"
[time]
end = 2.0
steps = 2
[[body]]
name = "block"
mesh = { generator = "box", min = [0.0, 0.0, 0.0], max = [1.0, 0.5, 0.1], cells = [10, 5, 1] }
material = { model = "linear-elastic", E = 1e9, nu = 0.3 }
[body.boundary.ymax]
type = "normal-displacement"
value = { table = [[0.0, 0.0], [1.0, -1e-3]] }
[body.boundary.xmin]
type = "traction"
value = { table = [[0.0, [0.0, 0.0, 0.0]], [1.0, [0.0, 0.0, 0.0]], [2.0, [2.066e6, 0.0, 0.0]]] }
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[[body]]
name = "floor"
rigid = true
mesh = { generator = "box", min = [-1.0, -0.2, 0.0], max = [2.0, 0.0, 0.1], cells = [3, 1, 1] }
[[contact]]
master = "floor/ymax"
slave = "block/ymin"
friction = 0.3
"#;

/// Runs a variant of [`BLOCK_PUSHED_PAST_FRICTION`] with `method` (the
/// segregated one allowed 3000 outer iterations), which must fail after
/// converged sub-steps of its second increment; returns the temporary
/// folder (kept alive) and the results folder.
fn run_failing_push(case: &str, method: &str) -> (tempfile::TempDir, PathBuf) {
    let max_outer = if method == "segregated" {
        "max_outer = 3000\n"
    } else {
        ""
    };
    let case = case.replace(
        "steps = 2\n",
        &format!("steps = 2\n[solver]\nnonlinear = \"{method}\"\n{max_outer}"),
    );
    let dir = tempfile::tempdir().unwrap();
    let (code, outdir, err) = run_quietly(dir.path(), case.as_bytes());
    assert_eq!(code, 1, "{method}: {err}");
    assert!(err.contains("is written as increment 2"), "{method}: {err}");
    (dir, outdir.join("pushed"))
}

/// In a history row of the pushed block (time, iterations, residual,
/// ymax Fx Fy Fz, normal force, area): the pressing face's reaction is the
/// floor's normal force.
fn assert_pressing_reaction_is_n(method: &str, last: &[f64]) {
    assert!(
        (last[4] + last[6]).abs() < 2e-3 * last[6],
        "{method}: reaction {} against N {}",
        last[4],
        last[6]
    );
}

/// The last converged sub-step that a failed run writes is that state
/// throughout: its stresses, reactions, contact surfaces, pressures and
/// tractions and its residual. Found by a probe (2026-11-30): under
/// Newton–Krylov the results held the failed attempt's stresses (σ_yy
/// 6.3e12), contact faces at x ≈ 6e10 with no pressure, a reaction of
/// 1.1e12 and the failed residual 0.68 beside `converged = 1`; and under
/// both methods `contact_traction` was zero under Newton–Krylov in every
/// run. Measured now: reaction −253,692 against N = 253,683; F_t = 71,019
/// = the applied 0.6875 × 2.066e6 × 0.05.
#[test]
fn a_failed_contact_run_writes_its_last_sub_step_throughout() {
    for method in ["newton-krylov", "segregated"] {
        let (_dir, res) = run_failing_push(BLOCK_PUSHED_PAST_FRICTION, method);
        let file = hdf5::File::open(res.join("pushed.h5")).unwrap();
        let g = file.group("time/2").unwrap();
        let t: f64 = g.attr("time").unwrap().read_scalar().unwrap();
        let residual: f64 = g.attr("residual").unwrap().read_scalar().unwrap();
        assert!(t > 1.5 && t < 1.75, "{method}: t = {t}");
        assert!(residual < 1e-5, "{method}: residual {residual}");
        let read = |name: &str| g.dataset(name).unwrap().read_2d::<f64>().unwrap();
        let stress = read("block/stress");
        assert!(
            stress.iter().all(|s| s.abs() < 1e8),
            "{method}: stress {stress:?}"
        );
        let centres = read("block/ymin/face_centres");
        assert!(
            centres.iter().all(|x| x.abs() < 2.0),
            "{method}: {centres:?}"
        );
        let traction = read("block/ymin/contact_traction");
        let pressure = g
            .dataset("block/ymin/contact_pressure")
            .unwrap()
            .read_1d::<f64>()
            .unwrap();
        // 10 faces of 0.01 m²: N from the pressures, F_t from the tractions
        let n: f64 = pressure.iter().map(|p| 0.01 * p).sum();
        let ft: f64 = traction.column(0).iter().map(|t| 0.01 * t).sum();
        let applied = 2.066e6 * (t - 1.0) * 0.05;
        assert!((n - 253_683.0).abs() < 0.01 * n, "{method}: N {n}");
        assert!(
            (ft.abs() / applied - 1.0).abs() < 1e-3,
            "{method}: F_t {ft} against {applied}"
        );
        let last = last_history_row(&res);
        // the summary counts the increment written, as the history does
        let (_, v) = read_summary(&res);
        assert_eq!(v["increments"], 2, "{method}");
        assert_eq!(v["time_reached"].as_f64(), Some(t), "{method}");
        assert_pressing_reaction_is_n(method, &last);
    }
}

/// The block of [`BLOCK_PUSHED_PAST_FRICTION`] pressed further during its
/// failing increment (the `normal-displacement` ramps on): the sub-step
/// written is at its own time, with that time's prescribed face, so the
/// pressing face's reaction is the floor's normal force. The failed
/// attempt's conditions were left in place: a reaction of 501,360 against
/// N = 333,076 (found by a probe, 2026-12-01, on a sphere inflated by a
/// `normal-displacement`: 2.3e9 against 8.4e4). Measured: 333,091.
#[test]
fn a_failed_run_writes_its_last_sub_step_with_that_time_s_conditions() {
    let case = BLOCK_PUSHED_PAST_FRICTION
        .replace(
            "[[0.0, 0.0], [1.0, -1e-3]]",
            "[[0.0, 0.0], [1.0, -1e-3], [2.0, -2e-3]]",
        )
        .replace("2.066e6", "6e6");
    for method in ["newton-krylov", "segregated"] {
        let (_dir, res) = run_failing_push(&case, method);
        let last = last_history_row(&res);
        assert!(last[0] > 1.0 && last[0] < 2.0, "{method}: t = {}", last[0]);
        assert_pressing_reaction_is_n(method, &last);
    }
}

/// `[output] fields` without `von_mises` on a contact case: the results
/// writer indexed the von Mises stress it had not formed for the contact
/// patches' cells and panicked, and the run lost its `summary.json`
/// (found by a probe, 2026-11-30). Each choice now writes what it names.
#[test]
fn any_choice_of_fields_writes_a_contact_case() {
    for (fields, kept) in [
        ("[\"stress\"]", vec!["stress"]),
        ("[]", vec![]),
        ("[\"gap\", \"contact_pressure\"]", vec![]),
    ] {
        let case = block_on_floor(
            "fields",
            ("0", "0.5"),
            "[body.boundary.zmax]\ntype = \"displacement\"\nvalue = [0, 0, -0.005]\n",
            "",
        ) + &format!("[output]\nfields = {fields}\n");
        let dir = tempfile::tempdir().unwrap();
        let (code, out, err) = run_quietly(dir.path(), case.as_bytes());
        assert_eq!(code, 0, "fields = {fields}: {err}");
        let (_, v) = read_summary(&out.join("fields"));
        assert!(v["converged"].as_bool().unwrap(), "fields = {fields}");
        let file = hdf5::File::open(out.join("fields/fields.h5")).unwrap();
        let block = file.group("time/1/block").unwrap();
        for name in ["displacement", "stress", "von_mises"] {
            assert_eq!(
                block.link_exists(name),
                kept.contains(&name),
                "fields = {fields}: {name}"
            );
        }
    }
}

/// A dynamic analysis of a tetrahedral mesh: `fvc check` warns that such
/// runs were seen to grow without bound (a probe's cantilever, 2026-12-01:
/// displacements 1e150 on a 2 m beam with exit 0). The same mesh static:
/// no such note.
#[test]
fn dynamics_on_tetrahedra_is_warned_of() {
    let dir = tempfile::tempdir().unwrap();
    let msh = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../validation/cases/tet-cantilever/beam-coarse.msh"
    ))
    .unwrap();
    write(dir.path(), "beam.msh", &msh);
    let case = |kind: &str| {
        format!(
            r#"title = "beam"
[analysis]
kind = "{kind}"
[time]
end = 0.1
steps = 2
[[body]]
name = "beam"
mesh = {{ file = "beam.msh" }}
material = {{ model = "linear-elastic", E = 1.0e5, nu = 0.3, rho = 1.0 }}
[body.boundary.root]
type = "displacement"
value = [0, 0, 0]
"#
        )
    };
    for (kind, warned) in [("dynamic", true), ("static", false)] {
        let p = write(dir.path(), "case.toml", case(kind).as_bytes());
        let (code, out, err) = fvc(&["check", p.to_str().unwrap()]);
        assert_eq!(code, 0, "{kind}: {err}");
        let all = format!("{out}{err}");
        assert_eq!(all.contains("grow without bound"), warned, "{kind}: {all}");
    }
}
