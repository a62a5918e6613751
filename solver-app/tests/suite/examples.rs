//! The shipped examples (`examples/*/case.toml`, found by listing the
//! folder, so a new example is covered without touching this file): every
//! one passes `fvc check` and is listed in `examples/README.md`, and the two
//! fastest contact examples are solved with their default settings and
//! compared with Hertz's solution.
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;

fn examples_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples")
}

/// Every `examples/<name>/case.toml`, sorted by name.
fn example_cases() -> Vec<PathBuf> {
    let dir = examples_dir();
    let mut cases: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path().join("case.toml"))
        .filter(|case| case.is_file())
        .collect();
    cases.sort();
    cases
}

fn fvc(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_fvc"))
        .args(args)
        .output()
        .expect("fvc runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn every_example_passes_fvc_check_and_is_in_the_readme() {
    let cases = example_cases();
    assert!(
        cases.len() >= 6,
        "expected the six examples in {}, found {cases:?}",
        examples_dir().display()
    );
    let readme = std::fs::read_to_string(examples_dir().join("README.md")).unwrap();
    let mut failures = Vec::new();
    for case in &cases {
        let (code, err) = fvc(&["check", case.to_str().unwrap()]);
        if code != 0 {
            failures.push(format!("{}: exit {code}\n{err}", case.display()));
        }
        let name = case
            .parent()
            .unwrap()
            .file_name()
            .unwrap()
            .to_str()
            .unwrap();
        if !readme.contains(&format!("({name}/)")) {
            failures.push(format!("examples/README.md has no link ({name}/)"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every case file of the validation cases (`validation/cases/*/*.toml`)
/// passes `fvc check` on a fresh clone: their meshes are shipped or built
/// by a generator. The two that read a benchmark's polyMesh from
/// `../shared` (extracted by their tests into a temporary folder) are
/// left out, named.
#[test]
fn every_validation_case_passes_fvc_check() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../validation/cases");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|entry| std::fs::read_dir(entry.ok()?.path()).ok())
        .flatten()
        .filter_map(|entry| Some(entry.ok()?.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 20, "validation cases: {files:?}");
    let mut failures = Vec::new();
    for case in &files {
        let text = std::fs::read_to_string(case).unwrap();
        if text.contains("polymesh = \"polyMesh\"") {
            eprintln!(
                "skipped (a polyMesh from ../shared, extracted by its test): {}",
                case.display()
            );
            continue;
        }
        let (code, err) = fvc(&["check", case.to_str().unwrap()]);
        if code != 0 {
            failures.push(format!("{}: exit {code}\n{err}", case.display()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Runs `fvc run examples/<name>/case.toml` into a temporary folder;
/// returns that folder (deleted when dropped), the results folder in it and
/// the parsed `summary.json`, which says the run converged.
fn solve_example(name: &str) -> (tempfile::TempDir, PathBuf, serde_json::Value) {
    let case = examples_dir().join(name).join("case.toml");
    let out = tempfile::tempdir().unwrap();
    let (code, err) = fvc(&[
        "run",
        case.to_str().unwrap(),
        "--output",
        out.path().to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "fvc run {}: {err}", case.display());
    let res = out.path().join(name);
    let text = std::fs::read_to_string(res.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(summary["converged"], true, "{text}");
    (out, res, summary)
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The contact pressure and the face centres (x, y, z) of a patch at the
/// last increment (1) of `<res>/<title>.h5`.
fn contact_pressure(res: &Path, title: &str, patch: &str) -> (Vec<f64>, Vec<[f64; 3]>) {
    let f = hdf5::File::open(res.join(format!("{title}.h5"))).unwrap();
    let p = f
        .dataset(&format!("time/1/{patch}/contact_pressure"))
        .unwrap()
        .read_raw::<f64>()
        .unwrap();
    let c = f
        .dataset(&format!("time/1/{patch}/face_centres"))
        .unwrap()
        .read_raw::<f64>()
        .unwrap();
    let centres = c.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    (p, centres)
}

/// RMS over the faces with ρ < 0.8 × `half` of (p − p0 √(1 − ρ²/half²)) / p0,
/// ρ being `dist` of the face centre.
fn profile_rms(
    p: &[f64],
    centres: &[[f64; 3]],
    dist: impl Fn(&[f64; 3]) -> f64,
    p0: f64,
    half: f64,
) -> (f64, usize) {
    let mut sum = 0.0;
    let mut n = 0;
    for (p, c) in p.iter().zip(centres) {
        let rho = dist(c);
        if rho < 0.8 * half {
            let hertz = p0 * (1.0 - (rho / half).powi(2)).sqrt();
            sum += ((p - hertz) / p0).powi(2);
            n += 1;
        }
    }
    ((sum / n as f64).sqrt(), n)
}

/// The outermost face centre in contact (p > 0), by `dist`.
fn contact_extent(p: &[f64], centres: &[[f64; 3]], dist: impl Fn(&[f64; 3]) -> f64) -> f64 {
    p.iter()
        .zip(centres)
        .filter(|(p, _)| **p > 0.0)
        .map(|(_, c)| dist(c))
        .fold(0.0, f64::max)
}

/// examples/hertz-cylinder with its default settings: the contact force
/// balances the load, and the pressure is Hertz's for that load. Measured
/// (2,018 cells, penalty scale 5 as the default against a rigid plane):
/// P = 1.6888 N/m, peak 3.796 against p0 = 3.843 Pa (−1.2 %: the
/// penalty's penetration, 0.14 mm), last face in contact at |x| = 0.286
/// against b = 0.280 m (faces 0.034 m wide). With penalty scale 1:
/// P = 1.6558, −4.5 %, 0.66 mm.
#[test]
fn hertz_cylinder_example_against_hertz() {
    let (_guard, res, s) = solve_example("hertz-cylinder");
    let (e, nu, r) = (200.0, 0.3, 8.0);
    let e_star = e / (1.0 - nu * nu);
    // The load per metre: the reaction on the driven top.
    let load = -num(&s["patches"]["cylinder/top"]["reaction_force"][1]);
    let flat = num(&s["patches"]["flat/ymin"]["reaction_force"][1]);
    let contact = &s["contacts"][0];
    let normal = num(&contact["normal_force"]);
    assert!((load - 1.6888).abs() < 0.01, "load {load}");
    assert!((flat - load).abs() < 1e-3 * load, "flat {flat} load {load}");
    assert!(
        (normal - load).abs() < 1e-3 * load,
        "contact {normal} load {load}"
    );
    let b = (4.0 * load * r / (PI * e_star)).sqrt();
    let p0 = (load * e_star / (PI * r)).sqrt();
    let peak = num(&contact["max_pressure"]);
    let peak_error = peak / p0 - 1.0;
    assert!(
        (-0.02..0.0).contains(&peak_error),
        "peak {peak} against Hertz {p0}: {:+.2} %",
        100.0 * peak_error
    );
    let (p, centres) = contact_pressure(&res, "hertz-cylinder", "cylinder/contact");
    let (rms, n) = profile_rms(&p, &centres, |c| c[0].abs(), p0, b);
    assert!(n >= 12, "{n} faces within 0.8 b");
    assert!(rms < 0.05, "profile RMS {rms} of p0");
    let extent = contact_extent(&p, &centres, |c| c[0].abs());
    assert!(
        (extent - b).abs() < 0.034,
        "contact to |x| = {extent}, b = {b}"
    );
    let newton = s["outer_iterations"].as_u64().unwrap();
    assert!(newton <= 10, "{newton} Newton iterations");
}

/// examples/sphere-block with its default settings (a quarter model): the
/// block carries the sphere's load, and the pressure is Hertz's for that
/// load. Measured (4,000 cells, 6 Newton iterations, 0.3 s): P = 4 ×
/// 0.06071 N, the block's bottom 0.5 % more; peak 10.60 against
/// p0 = 10.96 Pa (−3.3 %), profile RMS 3.2 % of p0 over r < 0.8 a, last
/// face in contact at r = 0.1024 against a = 0.1028 m (faces 0.019 m).
#[test]
fn sphere_block_example_against_hertz() {
    let (_guard, res, s) = solve_example("sphere-block");
    let (e_s, nu_s, e_b, nu_b, r) = (600.0, 0.3, 200.0, 0.33, 1.0);
    let e_star = 1.0 / ((1.0 - nu_s * nu_s) / e_s + (1.0 - nu_b * nu_b) / e_b);
    // The whole sphere's load: four times the quarter's.
    let load = -4.0 * num(&s["patches"]["sphere/top"]["reaction_force"][2]);
    let block = 4.0 * num(&s["patches"]["block/zmin"]["reaction_force"][2]);
    assert!((load - 0.2428).abs() < 0.005, "load {load}");
    assert!(
        (block - load).abs() < 0.01 * load,
        "block {block} load {load}"
    );
    let a = (3.0 * load * r / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * load / (2.0 * PI * a * a);
    let peak = num(&s["contacts"][0]["max_pressure"]);
    let peak_error = peak / p0 - 1.0;
    assert!(
        (-0.05..0.0).contains(&peak_error),
        "peak {peak} against Hertz {p0}: {:+.2} %",
        100.0 * peak_error
    );
    let (p, centres) = contact_pressure(&res, "sphere-block", "sphere/curved");
    let radius = |c: &[f64; 3]| c[0].hypot(c[1]);
    let (rms, n) = profile_rms(&p, &centres, radius, p0, a);
    assert!(n >= 20, "{n} faces within 0.8 a");
    assert!(rms < 0.05, "profile RMS {rms} of p0");
    let extent = contact_extent(&p, &centres, radius);
    assert!(
        (extent - a).abs() < 0.019,
        "contact to r = {extent}, a = {a}"
    );
    let newton = s["outer_iterations"].as_u64().unwrap();
    assert!(newton <= 10, "{newton} Newton iterations");
}
