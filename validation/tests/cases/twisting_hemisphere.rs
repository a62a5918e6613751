//! twisting-hemisphere (thesis §5.3.5, figs. 5.28–5.32; issue 7;
//! `../shared/benchmarks/README.md`): a hollow neo-Hookean hemisphere
//! pushed 1 mm onto a block (10 increments, frictionless), then twisted
//! 180° (90 increments, μ = 0.5). N, mm, MPa. The shipped case uses the
//! built-in generators; the benchmark's coarse polyMesh is extracted from
//! `../shared` at run time (those tests print `skipped` without it).
//!
//! The default test runs the first 0.3 mm of the indentation as shipped;
//! the full cases (generated mesh, swapped master, benchmark mesh) are
//! `--ignored`.
use validation::benchmarks::twisting_hemisphere::{
    angle_of, references, run, MeshSource, Options, Twist, FORCE_TOLERANCE, TORQUE_TOLERANCE,
};
use validation::shared_dir;

/// F_z at t = 0.3 (0.3 mm of the 1 mm indentation) measured as shipped
/// (implicit coupling, block master, generated mesh, Rhie–Chow 1), N.
/// With the thesis's Rhie–Chow 0.1 it was 0.9260 and the benchmark's
/// polyMesh gave 0.9332.
const FZ_INDENTATION_03: f64 = 0.9680;

fn report(label: &str, r: &Twist) {
    eprintln!(
        "twisting hemisphere, {label}: reached t = {:.4} (θ = {:.1}°), {} increments, {:.0} outer iterations per increment (indentation {:.0}, twist {:.0}), {:.1} s, {:.3} µs/cell/iteration{}",
        r.reached(),
        angle_of(r.reached()),
        r.time.len(),
        r.cost.outer_iterations as f64 / r.cost.increments.max(1) as f64,
        r.mean_outer(0.0, 1.0),
        r.mean_outer(1.0, 10.0),
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        r.failure
            .as_ref()
            .map(|f| format!("; failure: {f}"))
            .unwrap_or_default()
    );
    for (t, (f, m)) in r.time.iter().zip(r.force.iter().zip(&r.torque)) {
        eprintln!(
            "  t = {t:.4}  θ = {:6.1}°  F_z = {f:.5} N  M = {m:.5} N·mm",
            angle_of(*t)
        );
    }
}

/// The first 0.3 mm of the indentation as shipped (3 increments of
/// 0.1 mm, 126 outer iterations each; 6 s): F_z(t = 0.3) = 0.968 N
/// (0.926 N with the thesis's Rhie–Chow 0.1, whose increments had to be
/// redone in eighths), and no twisting moment while the contact is frictionless and
/// the motion a pure translation (this also checks that the `friction`
/// table keeps μ = 0 before t = 1, and the moment column).
#[test]
fn indentation_force_and_no_moment() {
    let r = match run(
        shared_dir().as_deref(),
        &Options {
            until: 0.3,
            ..Default::default()
        },
    ) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    report("indentation to t = 0.3", &r);
    assert!(r.converged, "{:?}", r.failure);
    let (f, m) = r.at_time(0.3);
    assert!(
        (f / FZ_INDENTATION_03 - 1.0).abs() < 0.01,
        "F_z(0.3) = {f} N, measured {FZ_INDENTATION_03}"
    );
    // the force grows faster than linearly (the contact spreads)
    let (f1, _) = r.at_time(0.1);
    assert!(f > 4.0 * f1, "F_z(0.1) = {f1}, F_z(0.3) = {f}");
    // frictionless and axisymmetric: the moment is round-off (F_z · 1 mm
    // is the scale of a twisting moment)
    assert!(m.abs() < 1e-3 * f, "M = {m} N·mm with F_z = {f} N");
    // far below the Sauer–De Lorenzis force at the end of the indentation
    if let Some(shared) = shared_dir() {
        if let Ok(refs) = references(&shared) {
            let f_end = refs.force.at(0.0);
            assert!(
                f < f_end,
                "F_z(0.3) = {f} above the full-indentation {f_end}"
            );
        }
    }
}

/// Runs `opts` and checks the benchmark's acceptance: the run completes
/// 180°, the plateau torque (mean over 120–179°, where the Sauer–De Lorenzis curve ends) within 5 % and F_z
/// (at 0°, 90°, 180°) within 3 % of Sauer–De Lorenzis.
fn full_case(label: &str, opts: &Options) {
    let Some(shared) = shared_dir() else {
        eprintln!("skipped: ../shared is absent");
        return;
    };
    let r = match run(Some(&shared), opts) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    report(label, &r);
    let refs = match references(&shared) {
        Ok(x) => x,
        Err(e) => panic!("{e}"),
    };
    for deg in [0.0, 20.0, 40.0, 60.0, 90.0, 120.0, 150.0, 180.0] {
        let (f, m) = r.at_angle(deg);
        eprintln!(
            "  θ = {deg:5.1}°: F_z {f:.4} (S–DL {:.4}), M {m:.4} (S–DL {:.4}, FEBio {:.4})",
            refs.force.at(deg),
            refs.torque.at(deg),
            refs.torque_febio.at(deg)
        );
    }
    assert!(
        r.converged && r.reached() > 10.0 - 1e-6,
        "the twist stopped at θ = {:.1}°: {:?}",
        angle_of(r.reached()),
        r.failure
    );
    let n = 30;
    let plateau = (0..=n)
        .map(|i| r.at_angle(120.0 + 2.0 * i as f64).1)
        .sum::<f64>()
        / (n + 1) as f64;
    let plateau_ref = refs.torque.mean(120.0, 179.0);
    eprintln!(
        "  plateau torque (120–179°): {plateau:.4} N·mm, Sauer–De Lorenzis {plateau_ref:.4} ({:+.2} %), FEBio {:.4}",
        100.0 * (plateau / plateau_ref - 1.0),
        refs.torque_febio.mean(120.0, 179.0)
    );
    assert!(
        (plateau / plateau_ref - 1.0).abs() < TORQUE_TOLERANCE,
        "plateau torque {plateau} against {plateau_ref}"
    );
    for deg in [0.0, 90.0, 180.0] {
        let (f, _) = r.at_angle(deg);
        let fr = refs.force.at(deg);
        assert!(
            (f / fr - 1.0).abs() < FORCE_TOLERANCE,
            "F_z at {deg}°: {f} against {fr}"
        );
    }
}

/// The full case as shipped (generated mesh, block master, Rhie–Chow 1).
/// Measured: FAILS — the run stops in the indentation at t = 0.65
/// (increments 1–6: 249, 61, 68, 77, 90 and 84 outer iterations; the
/// seventh's sub-steps converge to 0.6375, then the residual creeps up by
/// a factor of about 1.001 per outer iteration while the wall between the
/// rim and the contact bulges outwards, 0.045 mm radially per 0.05 mm of
/// indentation). With the thesis's Rhie–Chow 0.1 it stopped at t ≈ 0.6:
/// increments of 685–1,730 outer iterations, then a cell of the wall
/// collapsing (det f 0.93 → 0.5 within a 1/16 sub-step) at every step
/// size, with implicit and explicit coupling, with or without Anderson
/// acceleration or under-relaxation 0.5. (A redone attempt also began
/// from the failed attempt's contact weights then; mended.)
#[test]
#[ignore]
fn full_twist_block_master() {
    full_case("as shipped", &Options::default());
}

/// Master and slave swapped (hemisphere master); the same acceptance.
/// Measured (with `fvc` on the swapped case file): FAILS as
/// [`full_twist_block_master`], at the same t ≈ 0.54 (F_z(0.5) = 1.948 N,
/// −0.6 % against the block master; 680–1,705 outer iterations per
/// increment; 33 s): the failure is in the hemisphere's wall, not in the
/// contact.
#[test]
#[ignore]
fn full_twist_hemisphere_master() {
    full_case(
        "hemisphere master",
        &Options {
            swapped: true,
            ..Default::default()
        },
    );
}

/// The full case on the benchmark's coarse polyMesh. Measured: FAILS —
/// stops at t = 0.575 (F_z = 2.61 N; cells on the inner surface at
/// mid-latitude compressed to J ≈ 0.36); with `rhie_chow = 1` it gets to
/// t = 0.625 (F_z = 3.15 N, then the force drops and the iterations stall).
#[test]
#[ignore]
fn full_twist_benchmark_mesh() {
    full_case(
        "benchmark polyMesh",
        &Options {
            mesh: MeshSource::Benchmark,
            ..Default::default()
        },
    );
}

/// The reference files parse, in N and N·mm after the ×10 of the
/// Sauer–De Lorenzis values: F_z ≈ 12.3 N at 0°, the plateau torque
/// ≈ 4.0 N·mm, FEBio's torque within 2 % of Sauer–De Lorenzis on the
/// plateau (the check of the scale).
#[test]
fn reference_curves_parse() {
    let Some(shared) = shared_dir() else {
        eprintln!("skipped: ../shared is absent");
        return;
    };
    let refs = match references(&shared) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    let f0 = refs.force.at(0.0);
    let m = refs.torque.mean(120.0, 179.0);
    let mf = refs.torque_febio.mean(120.0, 179.0);
    eprintln!("F_z(0°) = {f0:.3} N, plateau torque {m:.3} N·mm (FEBio {mf:.3})");
    assert!((f0 - 12.30).abs() < 0.05, "{f0}");
    assert!((m - 4.04).abs() < 0.05, "{m}");
    assert!((mf / m - 1.0).abs() < 0.02, "{mf} against {m}");
}
