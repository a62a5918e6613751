//! flat-punch (thesis §5.2.3, `../shared/benchmarks/README.md`): contact
//! pressure under a rigid flat punch against A20 with the computed force,
//! with the punch as master and as slave.
use validation::benchmarks::flat_punch::{indentation_depth, run};

#[test]
fn punch_pressure_within_three_percent_of_a20_either_side_master() {
    let a = run(false);
    let b = run(true);
    for r in [&a, &b] {
        let worst = r
            .settlement
            .iter()
            .filter(|s| s.0 > 0.012 && s.0 < 0.05)
            .fold(0.0f64, |m, &(_, w, e)| m.max((w / e - 1.0).abs()));
        eprintln!(
            "punch master={}: F = {:.5e} N/m (A21 for 0.0967 mm: {:.5e}), max |p/p_A20 − 1| = {:.2} % over |x| ≤ 0.8 b, settlement shape vs A22 within {:.1} % for 1.2b < x < 5b, {} outer iterations, {:.2} s, {:.3} µs/cell/iter",
            !r.swapped,
            r.force,
            0.0967e-3 / indentation_depth(1.0),
            100.0 * r.pressure_error,
            100.0 * worst,
            r.cost.outer_iterations,
            r.cost.wall_seconds,
            r.cost.us_per_cell_iteration()
        );
        assert!(r.converged);
        assert!(r.pressure_error < 0.03, "{}", r.pressure_error);
        // the force of the finite block is within 10 % of the half-space's A21
        let f21 = 0.0967e-3 / indentation_depth(1.0);
        assert!((r.force / f21 - 1.0).abs() < 0.1, "{} vs {f21}", r.force);
        // settlement shape near the punch: within 10 % of A22 (finite block)
        assert!(worst < 0.1, "{worst}");
    }
    assert!((a.force - b.force).abs() < 0.01 * a.force);
}
