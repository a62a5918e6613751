//! Wire drawing (thesis §5.4.1): the steady drawing force on the quarter
//! against the thesis's per-mesh forces and its Richardson extrapolation,
//! 282.8 N; the oscillation of the coarse force against its 1.8 %.
//!
//! The coarse run takes about 40 s; the medium (with the coarse run for
//! the extrapolation) and the coarse run under the thesis's segregated
//! method are ignored by default:
//! `cargo test --release -p validation --test cases wire_drawing -- --ignored --nocapture`.
use validation::benchmarks::wire_drawing::{
    axisymmetric_meshes, observed_order, richardson, run, run_edited, WireMesh, WireRun,
    STEADY_FROM, THESIS_FORCES, THESIS_OSCILLATION, THESIS_RICHARDSON,
};

/// Prints the run and returns its steady mean force and deviation.
fn report(name: &str, r: &WireRun) -> (f64, f64) {
    for ((t, f), n) in r.time.iter().zip(&r.force).zip(&r.outer_iterations) {
        eprintln!(
            "  t = {t:.3} s ({:.3} mm drawn): F = {f:.2} N, {n} outer iterations",
            t * 250.0 / 3.0
        );
    }
    eprintln!(
        "wire drawing {name}: {} increments, {:.0} outer iterations per increment, {:.0} s, {:.2} µs per cell per outer iteration; {:?}",
        r.cost.increments,
        r.cost.outer_iterations as f64 / r.cost.increments.max(1) as f64,
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        r.failure
    );
    assert!(r.converged, "{name}: {:?}", r.failure);
    let Some((mean, dev)) = r.steady() else {
        panic!("{name}: the steady window from {STEADY_FROM} s was not reached")
    };
    eprintln!(
        "  steady force from {STEADY_FROM} s: {mean:.2} N ({:+.2} % against the Richardson {THESIS_RICHARDSON} N), largest deviation {:.2} %",
        100.0 * (mean / THESIS_RICHARDSON - 1.0),
        100.0 * dev
    );
    (mean, dev)
}

/// Prints a coarse run and asserts issue 47's bounds on Newton iterations
/// per increment (median ≤ 10, largest ≤ 40) and a steady force between
/// 282.8 N and the thesis's coarse force; returns the force and its
/// largest deviation.
fn coarse_run_within_bounds(name: &str, r: &WireRun) -> (f64, f64) {
    let (mean, dev) = report(name, r);
    let mut its = r.outer_iterations.clone();
    its.sort_unstable();
    let (median, max) = (its[its.len() / 2], its[its.len() - 1]);
    assert!(
        median <= 10 && max <= 40,
        "{name}: Newton iterations per increment: median {median}, largest {max}"
    );
    let thesis = THESIS_FORCES[0].1;
    assert!(
        mean > THESIS_RICHARDSON && mean < thesis,
        "{name}: steady force {mean} N outside ({THESIS_RICHARDSON}, {thesis}) N"
    );
    (mean, dev)
}

/// The mesh-converged force is 282.8 N; a mesh's force must lie between it
/// and the thesis's force on the mesh of the same cell count (the
/// acceptance of issue 43: closer to 282.8 N than the thesis's mesh, the
/// error from above as the thesis's). The coarse run with the default
/// settings (Newton–Krylov; 36 s, median 4 Newton iterations per
/// increment): 307.0 N, deviation 1.2 %.
#[test]
fn wire_drawing_coarse_force_between_thesis_coarse_and_richardson() {
    // median 4, largest 18 Newton iterations measured; before the last
    // change served as first iterate every increment needed cut-backs
    // (docs/newton-krylov.md)
    let (_, dev) = coarse_run_within_bounds("coarse", &run(WireMesh::Coarse));
    assert!(
        dev < THESIS_OSCILLATION,
        "coarse force deviates by {dev} from its mean (thesis < {THESIS_OSCILLATION})"
    );
}

/// The coarse wire as a new user runs it: no tuning keys, so the
/// Rhie–Chow term keeps only the flow's share in the flowing cells
/// (`rhie_chow_plastic = "flow"`, the default). The steady force comes
/// nearer 282.8 N than with the shipped elastic term (measured 290.83 N,
/// largest deviation 2.69 %, median 9 / largest 24–28 Newton iterations,
/// 71 s on one thread: the segregated operator gives way to the Jacobian's
/// ILU(0) at the third increment); its oscillation is over the thesis's
/// 1.8 %, which is why the case file keeps the elastic term.
#[test]
#[ignore = "about 70 s: cargo test --release -p validation --test cases wire_drawing_coarse_without -- --ignored --nocapture"]
fn wire_drawing_coarse_without_tuning_keys() {
    let r = run_edited(WireMesh::Coarse, |t| {
        validation::benchmarks::strip_tuning_keys(&t)
    });
    let (mean, dev) = coarse_run_within_bounds("coarse, no tuning keys", &r);
    assert!(mean < 295.0, "steady force {mean} N");
    assert!(dev < 0.03, "coarse force deviates by {dev} from its mean");
}

/// The two nonlinear methods on the coarse wire: the thesis's segregated
/// method (307.2 N, deviation 1.2 %, 144 outer iterations per increment,
/// 40 s alone) and the default Newton–Krylov agree on the steady force within
/// 0.2 % and on the force of every increment from the steady window on
/// within 1 % (both converge to the relative residual 1e-6, not to the
/// same bits).
#[test]
#[ignore = "about 90 s: cargo test --release -p validation --test cases wire_drawing_coarse_methods -- --ignored --nocapture"]
fn wire_drawing_coarse_methods_agree() {
    let newton = run(WireMesh::Coarse);
    let segregated = run_edited(WireMesh::Coarse, |t| {
        t.replacen(
            "[analysis]",
            "[solver]\nnonlinear = \"segregated\"\n\n[analysis]",
            1,
        )
    });
    let (fn_, _) = report("coarse, newton-krylov", &newton);
    let (fs, _) = report("coarse, segregated", &segregated);
    assert!(
        (fn_ / fs - 1.0).abs() < 2e-3,
        "steady forces {fn_} N (newton-krylov) and {fs} N (segregated)"
    );
    for ((t, a), b) in newton.time.iter().zip(&newton.force).zip(&segregated.force) {
        if *t >= STEADY_FROM - 1e-12 {
            assert!((a / b - 1.0).abs() < 1e-2, "t = {t}: {a} N against {b} N");
        }
    }
}

/// The medium wire (every spacing halved, 19,200 cells) between the
/// thesis's medium force and 282.8 N; and the Richardson extrapolation of
/// order 2 (the thesis's) from coarse and medium nearer 282.8 N than the
/// same extrapolation from the thesis's own coarse and medium forces
/// (297.2 N). The 2 % needs the fine mesh (README.md).
#[test]
#[ignore = "about 5 minutes: cargo test --release -p validation --test cases wire_drawing_medium -- --ignored --nocapture"]
fn wire_drawing_medium_force_and_richardson_extrapolation() {
    let (coarse, _) = report("coarse", &run(WireMesh::Coarse));
    let (medium, _) = report("medium", &run(WireMesh::Medium));
    let thesis = THESIS_FORCES[1].1;
    assert!(
        medium > THESIS_RICHARDSON && medium < thesis,
        "medium steady force {medium} N outside ({THESIS_RICHARDSON}, {thesis}) N"
    );
    let extrapolated = richardson(coarse, medium, 2.0);
    let thesis_two_meshes = richardson(THESIS_FORCES[0].1, thesis, 2.0);
    eprintln!(
        "Richardson (order 2) from {coarse:.2} and {medium:.2} N: {extrapolated:.2} N ({:+.2} % against {THESIS_RICHARDSON} N; the thesis's coarse and medium give {thesis_two_meshes:.2} N)",
        100.0 * (extrapolated / THESIS_RICHARDSON - 1.0)
    );
    assert!(
        (extrapolated - THESIS_RICHARDSON).abs() < (thesis_two_meshes - THESIS_RICHARDSON).abs(),
        "Richardson {extrapolated} N vs {THESIS_RICHARDSON} N"
    );
}

/// The axisymmetric wedge (`axisymmetric.toml`, 480 + 180 cells, 7 s)
/// solves the quarter's problem: its force, × 18, lies between the
/// thesis's coarse force and 282.8 N as the quarter's does (measured
/// 306.1 N, the quarter 307.0 N), in a handful of Newton iterations.
#[test]
fn wire_drawing_axisymmetric_wedge_between_thesis_coarse_and_richardson() {
    coarse_run_within_bounds("axisymmetric", &run(WireMesh::Axisymmetric { refine: 0 }));
}

/// Mesh convergence on the axisymmetric wedge, wire and die refined
/// together by halving (480, 1,920 and 7,680 wire cells): the force falls
/// monotonically, at the order the three meshes show (0.76 measured:
/// first order, as faceted contact surfaces and the plastic front
/// allow), and Richardson's extrapolation at that order lies within 2 %
/// of the thesis's 282.8 N (measured 282.1 N). README.md
/// ("Axisymmetric") adds the series in 200 increments (order 0.64,
/// 282.7 N) and CalculiX's forces on the same problem.
#[test]
#[ignore = "about 7 minutes: cargo test --release -p validation --test cases wire_drawing_axisymmetric_mesh -- --ignored --nocapture"]
fn wire_drawing_axisymmetric_mesh_convergence_and_richardson() {
    if let Err(e) = axisymmetric_meshes(1) {
        eprintln!("skipped: the refined meshes need Python 3 ({e})");
        return;
    }
    let forces: Vec<f64> = (0..3)
        .map(|refine| {
            report(
                &format!("axisymmetric, refine {refine}"),
                &run(WireMesh::Axisymmetric { refine }),
            )
            .0
        })
        .collect();
    let (f0, f1, f2) = (forces[0], forces[1], forces[2]);
    assert!(
        f0 > f1 && f1 > f2,
        "forces {forces:?} N do not fall with the mesh"
    );
    let order = observed_order(f0, f1, f2);
    let extrapolated = richardson(f1, f2, order);
    eprintln!(
        "observed order {order:.2}; Richardson {extrapolated:.2} N ({:+.2} % against {THESIS_RICHARDSON} N); at order 1 {:.2} N, at order 2 {:.2} N",
        100.0 * (extrapolated / THESIS_RICHARDSON - 1.0),
        richardson(f1, f2, 1.0),
        richardson(f1, f2, 2.0),
    );
    assert!((0.5..1.5).contains(&order), "observed order {order}");
    assert!(
        (extrapolated / THESIS_RICHARDSON - 1.0).abs() < 0.02,
        "Richardson {extrapolated} N against {THESIS_RICHARDSON} N"
    );
}
