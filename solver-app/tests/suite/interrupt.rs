//! `fvc run` stopped by SIGINT or SIGTERM (issue 45): exit code 130 / 143,
//! one line naming the results folder, `summary.json` with
//! `"interrupted": true` and the figures of the last increment written,
//! and an `.h5` that opens and holds every increment written.
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The block of `cli.rs` compressed in 100,000 increments: far more than
/// any test waits for, so the signal finds it mid-run.
fn long_case() -> String {
    let case = crate::cli::GOOD.replace("steps = 2\n", "steps = 100000\n");
    assert!(case.contains("steps = 100000"));
    case
}

/// Data rows of `history.csv` (0 while it does not exist).
fn history_rows(res: &Path) -> usize {
    std::fs::read_to_string(res.join("history.csv"))
        .map(|t| t.lines().count().saturating_sub(1))
        .unwrap_or(0)
}

/// Runs [`long_case`], sends `signal` once 3 increments are written, and
/// checks what the run left.
fn interrupted_run(signal: i32, name: &str, exit: i32) {
    interrupted_run_times(signal, name, exit, 1);
}

/// [`interrupted_run`] with the signal sent `times` times at once.
fn interrupted_run_times(signal: i32, name: &str, exit: i32, times: usize) {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, long_case()).unwrap();
    let out = dir.path().join("out");
    let res = out.join("block");
    let mut child = Command::new(env!("CARGO_BIN_EXE_fvc"))
        .args(["run", case.to_str().unwrap(), "--output"])
        .arg(&out)
        .arg("--quiet")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while history_rows(&res) < 3 {
        if start.elapsed() > Duration::from_secs(120) || child.try_wait().unwrap().is_some() {
            let _ = child.kill();
            panic!("no 3 increments written in 120 s (or the run ended)");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    for _ in 0..times {
        // SAFETY: kill(2) on the child's own pid, which has not been reaped
        let sent = unsafe { libc::kill(child.id() as libc::pid_t, signal) };
        assert_eq!(sent, 0);
    }
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("the run did not stop within 60 s of {name}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut err = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut err).unwrap();
    assert_eq!(status.code(), Some(exit), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let line = err
        .lines()
        .find(|l| l.contains(&format!("interrupted by {name} after increment")))
        .unwrap_or_else(|| panic!("no interrupt line in:\n{err}"));
    assert!(line.contains(res.to_str().unwrap()), "{line}");

    let text = std::fs::read_to_string(res.join("summary.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["interrupted"], true, "{text}");
    assert_eq!(v["interrupted_by"], name, "{text}");
    assert_eq!(v["converged"], false, "{text}");
    let n = v["increments"].as_u64().unwrap() as usize;
    assert!((3..100_000).contains(&n), "{text}");
    let dt = 1.0 / 100_000.0;
    let t = v["time_reached"].as_f64().unwrap();
    assert!((t - n as f64 * dt).abs() < 1e-12, "{text}");
    assert!(line.contains(&format!("increment {n}/100000")), "{line}");

    // history and summary end at the same increment: the reaction of the
    // summary is the last row's, between E ε A and the oedometric E ε A
    // (1 − ν)/((1 + ν)(1 − 2ν)) at the strain ε = 0.01 t reached
    let history = std::fs::read_to_string(res.join("history.csv")).unwrap();
    let rows: Vec<&str> = history.lines().skip(1).collect();
    assert_eq!(rows.len(), n);
    let header: Vec<&str> = history.lines().next().unwrap().split(',').collect();
    let col = header.iter().position(|c| *c == "block/ymax:Fy").unwrap();
    let last: Vec<f64> = rows[n - 1].split(',').map(|x| x.parse().unwrap()).collect();
    let fy = v["patches"]["block/ymax"]["reaction_force"][1]
        .as_f64()
        .unwrap();
    assert!(
        (fy - last[col]).abs() <= 1e-9 * fy.abs(),
        "{fy} vs {}",
        last[col]
    );
    let e_eps_a = 200.0 * 0.01 * t;
    let oedometric = e_eps_a * (1.0 - 0.3) / ((1.0 + 0.3) * (1.0 - 0.6));
    assert!(
        fy < -e_eps_a && fy > -oedometric,
        "reaction {fy} at t = {t}"
    );

    // the .h5 opens as it is and holds every increment written
    let f = hdf5::File::open(res.join("block.h5")).unwrap();
    let time = f.group("time").unwrap();
    let mut keys: Vec<usize> = time
        .member_names()
        .unwrap()
        .iter()
        .filter_map(|k| k.parse().ok())
        .collect();
    keys.sort_unstable();
    assert_eq!(keys, (1..=n).collect::<Vec<_>>());
    let g = f.group(&format!("time/{n}")).unwrap();
    let tk: f64 = g.attr("time").unwrap().read_scalar().unwrap();
    assert!((tk - t).abs() < 1e-15);
    let stress = f.dataset(&format!("time/{n}/block/stress")).unwrap();
    assert_eq!(stress.shape(), [64, 6]);
    assert_eq!(f.dataset("history").unwrap().shape()[0], n);
}

#[test]
fn sigint_stops_the_run_with_its_results_and_exit_130() {
    interrupted_run(libc::SIGINT, "SIGINT", 130);
}

#[test]
fn sigterm_stops_the_run_with_its_results_and_exit_143() {
    interrupted_run(libc::SIGTERM, "SIGTERM", 143);
}

/// GNU `timeout` sends SIGTERM to the process and then to its process
/// group: the run gets it twice within microseconds. That is one request,
/// not the second signal that ends the process at once (it used to, and
/// the run lost its `summary.json`).
#[test]
fn sigterm_twice_at_once_as_timeout_sends_it_stops_the_run_once() {
    interrupted_run_times(libc::SIGTERM, "SIGTERM", 143, 2);
}
