//! block-in-half-tube (issue 9, thesis §4.6.1): an elastic block slides
//! along a rigid, triangulated half-tube (the master). With Nagata
//! smoothing of the tube the horizontal force must be the same on the
//! coarse (780 triangles) and the fine (2,440) tube within 2 %, and it must
//! oscillate less than without smoothing; the cost per outer iteration with
//! and without smoothing is printed (thesis Table 4.12).
//!
//! The shipped cases slide 10 m in 100 increments (2–4 min per run); to
//! keep the suite short the test slides [`SLIDE`] m with the same 0.1 m
//! increment and compares over 0.5–2.5 m (three facet lengths of the
//! coarse tube along the axis). `TUBE_SLIDE=10` runs the full slide; the
//! ignored tests run the other algorithm pairs.
use validation::benchmarks::block_in_half_tube::{
    compare, run, BlockInHalfTube, Tube, SLIDING_FROM,
};

/// Slide of the test, m (0.1 m per increment).
const SLIDE: f64 = 2.5;

fn slide() -> (f64, usize) {
    let s = std::env::var("TUBE_SLIDE")
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .unwrap_or(SLIDE);
    (s, (s / 0.1).round() as usize)
}

fn report(r: &BlockInHalfTube) {
    let s = r.stats();
    eprintln!(
        "{} on the {:?} tube ({} triangles): mean Fx {:.5} N over u ≥ {SLIDING_FROM} m, peak-to-peak {:.2} %, RMS {:.2} %, max |F − moving average| {:.2} % of the mean; {:.1} outer iterations per increment, {} in all, {:.1} s, {:.3} µs/cell/iter{}",
        r.algorithm,
        r.tube,
        r.tube.triangles(),
        s.mean,
        100.0 * s.peak_to_peak,
        100.0 * s.rms,
        100.0 * s.wiggle,
        r.mean_outer(),
        r.cost.outer_iterations,
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        if r.converged { "" } else { " NOT CONVERGED" }
    );
    let f: Vec<String> = r
        .displacement
        .iter()
        .zip(&r.force)
        .map(|(u, f)| format!("{u:.1}:{f:.5}"))
        .collect();
    eprintln!("  u:Fx {}", f.join(" "));
}

fn run_reported(tube: Tube, algorithm: &str) -> BlockInHalfTube {
    let (s, n) = slide();
    let r = run(tube, algorithm, s, n);
    report(&r);
    assert!(r.converged, "{algorithm} {tube:?}: {:?}", r.failure);
    assert_eq!(r.force.len(), n);
    r
}

/// Coarse vs fine tube with smoothing (`smoothed`), and the coarse tube
/// without (`flat`).
fn check(flat: &str, smoothed: &str) {
    let coarse = run_reported(Tube::Coarse, smoothed);
    let fine = run_reported(Tube::Fine, smoothed);
    let faceted = run_reported(Tube::Coarse, flat);
    let (mean, max) = compare(&coarse, &fine);
    eprintln!(
        "{smoothed}: coarse vs fine tube: mean Fx {:+.2} %, max |ΔFx| {:.2} % of the fine mean",
        100.0 * mean,
        100.0 * max
    );
    let (sa, sb) = (faceted.stats(), coarse.stats());
    eprintln!(
        "coarse tube, {flat} → {smoothed}: peak-to-peak {:.2} % → {:.2} %, max |F − moving average| {:.2} % → {:.2} %; mean {:.5} → {:.5} N; outer iterations per increment {:.1} → {:.1}; cost per outer iteration with/without smoothing {:.2}",
        100.0 * sa.peak_to_peak,
        100.0 * sb.peak_to_peak,
        100.0 * sa.wiggle,
        100.0 * sb.wiggle,
        sa.mean,
        sb.mean,
        faceted.mean_outer(),
        coarse.mean_outer(),
        coarse.cost.us_per_cell_iteration() / faceted.cost.us_per_cell_iteration()
    );
    // issue 9 asks for 2 %; measured +0.11 % and 0.25 % (segment-to-segment-
    // nagata, 2.5 m; before the quadric fit of point normals 0.41 % and
    // 0.95 %): guarded tighter so that a loss of normal accuracy shows
    assert!(mean.abs() <= 0.003, "coarse vs fine mean {mean}");
    assert!(max <= 0.006, "coarse vs fine max {max}");
    assert!(sb.peak_to_peak < 0.01, "{sb:?}");
    assert!(sb.peak_to_peak < sa.peak_to_peak, "{sb:?} {sa:?}");
    assert!(sb.wiggle < sa.wiggle, "{sb:?} {sa:?}");
}

/// Measured (2.5 m): see validation/cases/block-in-half-tube/README.md.
#[test]
fn segment_to_segment_nagata_same_force_on_both_tubes_and_smoother() {
    check("segment-to-segment", "segment-to-segment-nagata");
}

/// The same with the pointwise algorithm (not in the suite: 3 more runs).
#[test]
#[ignore]
fn pointwise_nagata_same_force_on_both_tubes_and_smoother() {
    check("pointwise", "pointwise-nagata");
}
