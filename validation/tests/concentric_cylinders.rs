//! concentric-cylinders (thesis §4.4.1, `../shared/benchmarks/README.md`):
//! mean interface pressure against Lamé (0.3469 p) with either tube as
//! master, and the pressure oscillation of the non-conformal interface.
use validation::benchmarks::concentric_cylinders::{lame_interface_pressure, run};

#[test]
fn mean_interface_pressure_within_one_percent_of_lame_either_side_master() {
    let exact = lame_interface_pressure();
    assert!((exact / 10.0 - 0.3469).abs() < 5e-5);
    let mut oscillation = Vec::new();
    for algorithm in ["segment-to-segment", "pointwise"] {
        for swapped in [false, true] {
            let r = run(algorithm, swapped);
            eprintln!(
                "{algorithm} inner-master={swapped}: mean p/p_Lamé inner {:.4} outer {:.4}, oscillation inner {:.3} outer {:.3}, {} outer iterations, {:.2} s, {:.3} µs/cell/iter",
                r.inner.mean / exact,
                r.outer.mean / exact,
                r.inner.oscillation,
                r.outer.oscillation,
                r.cost.outer_iterations,
                r.cost.wall_seconds,
                r.cost.us_per_cell_iteration()
            );
            assert!(r.converged, "{algorithm} {swapped}");
            if algorithm == "segment-to-segment" {
                for side in [r.inner, r.outer] {
                    assert!(
                        (side.mean / exact - 1.0).abs() < 0.01,
                        "{algorithm} {swapped}: {side:?}"
                    );
                }
                oscillation.push(r.inner.oscillation.max(r.outer.oscillation));
            }
        }
    }
    // segment-to-segment: the oscillation does not depend on the choice of master
    let (a, b) = (oscillation[0], oscillation[1]);
    assert!((a - b).abs() <= 0.1 * a.max(b), "{a} vs {b}");
}
