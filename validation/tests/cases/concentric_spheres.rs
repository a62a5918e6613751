//! concentric-spheres (thesis §5.3.4; issue 7;
//! `../shared/benchmarks/README.md`): two hollow neo-Hookean half-spheres
//! compressed by a rigid plate, 9 mm in 90 increments, quarter model, on
//! the benchmark's coarse polyMesh (extracted from `../shared` at run
//! time: every test here prints "skipped" without it).
//!
//! The default tests run the first 1.8 mm (18 increments, ~5 s each) and
//! check the plate force against Abaqus/FEBio; the full 9 mm runs are
//! `--ignored`, and FAIL as measured: every variant stops at u_z = 2.1 mm
//! (see the case file `validation/cases/concentric-spheres/polymesh.toml`).
use validation::benchmarks::concentric_spheres::{
    abaqus_febio_mean, reference_curves, run, Options, ReferenceCurve, Spheres, TOLERANCE,
};
use validation::shared_dir;

/// Plate displacements (mm) at which the force is compared: before 1.5 mm
/// the digitised Abaqus and FEBio curves differ by 10–30 % (forces below
/// 0.4 N, read off the plots' first division).
const CHECKED: [f64; 2] = [1.5, 1.8];

/// Prints F against every reference at the usual displacements up to
/// `upto` and returns the largest deviation from the Abaqus/FEBio mean at
/// those of [`CHECKED`] and beyond.
fn compare(label: &str, r: &Spheres, curves: &[ReferenceCurve], upto: f64) -> f64 {
    let mut worst = 0.0f64;
    for u in [0.5, 1.0, 1.5, 1.8, 2.0, 3.0, 4.0, 5.0] {
        if u > upto + 1e-9 {
            break;
        }
        let f = r.force_at(u);
        let parts: Vec<String> = curves
            .iter()
            .map(|c| {
                let fr = c.force_at(u);
                format!("{} {fr:.3} ({:+.1} %)", c.source, 100.0 * (f / fr - 1.0))
            })
            .collect();
        eprintln!(
            "  {label} u = {u:.1} mm: F = {f:.4} N; {}",
            parts.join(", ")
        );
        if u >= CHECKED[0] - 1e-9 {
            let mean = abaqus_febio_mean(curves, u);
            worst = worst.max((f / mean - 1.0).abs());
        }
    }
    worst
}

fn checked_run(label: &str, opts: &Options) -> Option<(Spheres, Vec<ReferenceCurve>)> {
    let Some(shared) = shared_dir() else {
        eprintln!("skipped: ../shared is absent (the benchmark mesh lives there)");
        return None;
    };
    let r = match run(&shared, opts) {
        Ok(r) => r,
        Err(e) => panic!("{label}: {e}"),
    };
    let curves = match reference_curves(&shared, opts.friction > 0.0) {
        Ok(c) => c,
        Err(e) => panic!("{e}"),
    };
    eprintln!(
        "concentric spheres, {label}: reached u_z = {:.1} mm ({}), {:.0} outer iterations per increment, {:.1} s, {:.3} µs/cell/iteration{}",
        r.reached(),
        if r.converged { "converged" } else { "stopped" },
        r.mean_outer(),
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        r.failure.as_ref().map(|f| format!("; {f}")).unwrap_or_default()
    );
    Some((r, curves))
}

/// Frictionless, first 1.8 mm: F within 5 % of the mean of Abaqus and
/// FEBio at 1.5 and 1.8 mm. Measured: 0.575 N at 1.5 mm (Abaqus 0.581,
/// FEBio 0.555: +1.2 % on their mean), 0.683 N at 1.8 mm (Abaqus 0.720
/// −5.1 %, FEBio 0.674 +1.3 %; −2.0 % on the mean); 232 outer iterations
/// per increment, ~4 s.
#[test]
fn frictionless_first_1_8_mm_against_abaqus_febio() {
    let opts = Options {
        until: 1.8,
        ..Default::default()
    };
    let Some((r, curves)) = checked_run("μ = 0, 1.8 mm", &opts) else {
        return;
    };
    assert!(r.converged, "{:?}", r.failure);
    assert!((r.reached() - 1.8).abs() < 1e-9, "reached {}", r.reached());
    let worst = compare("μ = 0", &r, &curves, 1.8);
    assert!(
        worst < TOLERANCE,
        "force off the Abaqus/FEBio mean by {:.1} %",
        100.0 * worst
    );
}

/// μ = 0.5 between the spheres, first 1.8 mm; the same check. Measured:
/// 0.600 N at 1.5 mm (Abaqus 0.586, FEBio 0.610), 0.727 N at 1.8 mm
/// (Abaqus 0.725, FEBio 0.750); 189 outer iterations per increment.
#[test]
fn frictional_first_1_8_mm_against_abaqus_febio() {
    let opts = Options {
        until: 1.8,
        friction: 0.5,
        ..Default::default()
    };
    let Some((r, curves)) = checked_run("μ = 0.5, 1.8 mm", &opts) else {
        return;
    };
    assert!(r.converged, "{:?}", r.failure);
    let worst = compare("μ = 0.5", &r, &curves, 1.8);
    assert!(
        worst < TOLERANCE,
        "force off the Abaqus/FEBio mean by {:.1} %",
        100.0 * worst
    );
}

/// The acceptance of the benchmark on the full travel: the run reaches
/// 9 mm and the force stays within 5 % of the Abaqus/FEBio mean up to
/// 5 mm (buckling of the inner sphere starts at 5.5–5.8 mm in both).
fn full_travel(label: &str, opts: &Options) {
    let Some((r, curves)) = checked_run(label, opts) else {
        return;
    };
    let worst = compare(label, &r, &curves, r.reached().min(5.0));
    assert!(r.converged, "{label}: {:?}", r.failure);
    assert!((r.reached() - 9.0).abs() < 1e-9, "reached {}", r.reached());
    assert!(worst < TOLERANCE, "{label}: off by {:.1} %", 100.0 * worst);
}

/// Frictionless, 9 mm. Measured: FAILS — increment 22 (2.2 mm) gives a
/// non-finite residual; from 1.9 mm the force climbs far above the
/// references (1.21 N at 2.0 mm against 0.80, 1.68 N at 2.1 mm) as the
/// poles of both coarse spheres kink under the plate.
#[test]
#[ignore]
fn full_travel_frictionless() {
    full_travel("μ = 0, 9 mm", &Options::default());
}

/// μ = 0.5, 9 mm. Measured: FAILS the same way at 2.1 mm (1.31 N at
/// 2.0 mm against 0.82).
#[test]
#[ignore]
fn full_travel_frictional() {
    full_travel(
        "μ = 0.5, 9 mm",
        &Options {
            friction: 0.5,
            ..Default::default()
        },
    );
}

/// Frictionless, inner sphere master on the sphere–sphere pair. Measured:
/// the same forces as outer master to 0.2 % up to 1.8 mm, and FAILS the
/// same way at 2.1 mm.
#[test]
#[ignore]
fn full_travel_swapped() {
    full_travel(
        "μ = 0, swapped, 9 mm",
        &Options {
            swapped: true,
            ..Default::default()
        },
    );
}

/// The reference files parse and the stated mapping puts every curve at
/// 2.2–2.6 N at u_z = 5 mm, before buckling (the units check).
#[test]
fn reference_curves_mapping() {
    let Some(shared) = shared_dir() else {
        eprintln!("skipped: ../shared is absent");
        return;
    };
    for frictional in [false, true] {
        let curves = match reference_curves(&shared, frictional) {
            Ok(c) => c,
            Err(e) => panic!("{e}"),
        };
        assert_eq!(curves.len(), if frictional { 3 } else { 4 });
        for c in &curves {
            let f = c.force_at(5.0);
            eprintln!(
                "μ = {}: {}: F(5 mm) = {f:.3} N",
                if frictional { 0.5 } else { 0.0 },
                c.source
            );
            assert!(f > 2.2 && f < 2.65, "{}: {f}", c.source);
            assert!(c.force_at(8.5) > 3.5, "{}", c.source);
        }
    }
}
