//! twisting-hemisphere (thesis §5.3.5, figs. 5.28–5.32; issue 7;
//! `../shared/benchmarks/README.md`): a hollow neo-Hookean hemisphere
//! (E = 50) pushed 1 mm into a softer block (E = 10; the case file says
//! why not the table's inverse) in 10 frictionless increments, then twisted
//! 180° (90 increments, μ = 0.5). N, mm, MPa. The shipped case uses the
//! built-in generators; the benchmark's coarse polyMesh is extracted from
//! `../shared` at run time (those tests print `skipped` without it).
//!
//! The default test runs the indentation (t ≤ 1) as shipped; the full
//! cases (generated mesh, swapped master, benchmark mesh) are `--ignored`.
use validation::benchmarks::twisting_hemisphere::{
    angle_of, references, run, MeshSource, Options, Twist, FORCE_TOLERANCE, TORQUE_TOLERANCE,
};
use validation::shared_dir;

/// F_z at the end of the indentation (t = 1, 1 mm) measured as shipped
/// (implicit coupling, block master, generated mesh, the accumulated
/// Rhie–Chow stabilisation at α_RC = 0.2), N; the check of the case where
/// `../shared` is absent. Since the contact force is carried over the
/// moved surface's areas (`LinearisedContact::area_ratio`) the block's base
/// reads the same force; before, the hemisphere's top read 12.4375 N and
/// the base 12.3308 N. With the stabilisation of the increment alone at
/// α_RC = 1 (the case until the accumulated one) it was 12.3757 N, and
/// 12.01 and 11.90 N with 20 and 40 increments; accumulated at α_RC = 0.1
/// 12.196 and 12.215 N with 10 and 20.
const FZ_INDENTATION_END: f64 = 12.2829;

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

/// The indentation as shipped (10 increments of 0.1 mm, about 1,800 outer
/// iterations in all; 6 s): F_z at 1 mm = 12.28 N, −0.1 % on
/// Sauer–De Lorenzis (12.295 N at 0°); the force grows faster than
/// linearly and there is no twisting
/// moment while the contact is frictionless and the motion a pure
/// translation (this also checks that the `friction` table keeps μ = 0
/// before t = 1, and the moment column).
#[test]
fn indentation_force_against_sauer_de_lorenzis() {
    let r = match run(
        shared_dir().as_deref(),
        &Options {
            until: 1.0,
            ..Default::default()
        },
    ) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    };
    report("indentation", &r);
    assert!(r.converged, "{:?}", r.failure);
    assert!(
        (r.reached() - 1.0).abs() < 1e-9,
        "reached t = {}",
        r.reached()
    );
    let (f, m) = r.at_time(1.0);
    assert!(
        (f / FZ_INDENTATION_END - 1.0).abs() < 0.01,
        "F_z(1) = {f} N, measured {FZ_INDENTATION_END}"
    );
    let (f1, _) = r.at_time(0.1);
    let (f3, _) = r.at_time(0.3);
    assert!(f3 > 4.0 * f1, "F_z(0.1) = {f1}, F_z(0.3) = {f3}");
    // frictionless and axisymmetric: the moment is round-off (F_z · 1 mm
    // is the scale of a twisting moment)
    assert!(m.abs() < 1e-3 * f, "M = {m} N·mm with F_z = {f} N");
    // the block's base carries what the hemisphere's top carries: the
    // contact transmits the force it computes (0.86 % apart when the
    // traction was carried over the face gradients' areas)
    for (t, (top, base)) in r.time.iter().zip(r.force.iter().zip(&r.base_force)) {
        assert!(
            (base / top - 1.0).abs() < 1e-4,
            "t = {t}: hemisphere top {top} N, block base {base} N"
        );
    }
    match shared_dir().map(|s| references(&s)) {
        Some(Ok(refs)) => {
            let fr = refs.force.at(0.0);
            eprintln!(
                "F_z at 1 mm: {f:.4} N, Sauer–De Lorenzis {fr:.4} N ({:+.2} %)",
                100.0 * (f / fr - 1.0)
            );
            assert!(
                (f / fr - 1.0).abs() < FORCE_TOLERANCE,
                "F_z(1) = {f} against {fr}"
            );
        }
        Some(Err(e)) => panic!("{e}"),
        None => eprintln!("skipped: the comparison with Sauer–De Lorenzis (../shared is absent)"),
    }
}

/// Runs `opts` and checks the benchmark's acceptance: the run completes
/// 180°, the plateau torque (mean over 120–179°, where the Sauer–De
/// Lorenzis curve ends) within 5 % and F_z at every increment of the twist
/// within 3 % of Sauer–De Lorenzis.
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
    // F_z at every increment of the twist
    let worst = r.worst_force_error(&refs.force);
    eprintln!(
        "  F_z against Sauer–De Lorenzis over the twist: worst {:+.2} % at {:.0}°",
        100.0 * worst.1,
        worst.0
    );
    assert!(
        worst.1.abs() < FORCE_TOLERANCE, // (false when NaN)
        "F_z {:+.2} % at {:.0}°",
        100.0 * worst.1,
        worst.0
    );
}

/// The full case as shipped (generated mesh, block master, accumulated
/// Rhie–Chow stabilisation at α_RC = 0.2, accumulated slip). Measured:
/// runs to 180° (100 increments, 268 outer iterations per increment, 95 s
/// beside another run). F_z = 12.28 N at 0° (−0.1 % on Sauer–De
/// Lorenzis), worst −1.70 % at 78°, 12.71 N at 180° (−1.4 %); plateau
/// torque 4.127 N·mm (120–179°), +2.0 % (FEBio 4.07). At α_RC = 0.1: F_z
/// worst −2.54 % at 156°, torque +1.4 %. With the stabilisation of the
/// increment alone at α_RC = 1 (the case before): F_z fell to −4.3 % at
/// 80° and −3.7 % at 180° where the reference rises, the held indentation
/// lost 1.7 % in ten increments; plateau torque +1.0 %.
#[test]
#[ignore]
fn full_twist_block_master() {
    full_case("as shipped", &Options::default());
}

/// Master and slave swapped (hemisphere master); the same acceptance.
/// Measured: runs to 180° (268 outer iterations per increment, 94 s
/// beside another run); F_z −0.6 % at 0°, worst −2.24 % at 76°; plateau
/// torque 4.145 N·mm, +2.5 %. At α_RC = 0.1 it failed: worst −3.14 % at
/// 78°, torque +1.7 %. (Increment alone, α_RC = 1: −4.9 % at 80°, torque
/// +1.4 %.)
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

/// The full case on the benchmark's coarse polyMesh. Measured: runs to
/// 180° (278 outer iterations per increment, 83 s beside another run);
/// F_z +0.04 % at 0°, worst −1.55 % at 78°, −1.0 % at 180°; plateau
/// torque 4.171 N·mm, +3.1 %. At α_RC = 0.1: F_z worst −2.18 %, torque
/// +2.4 %. (Increment alone, α_RC = 1: F_z −3.6 % at 80°, torque +2.6 %.)
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
