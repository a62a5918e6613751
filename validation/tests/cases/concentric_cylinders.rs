//! concentric-cylinders (thesis §4.4.1, `../shared/benchmarks/README.md`):
//! mean interface pressure against Lamé (0.3469 p) with either tube as
//! master, and the pressure oscillation of the non-conformal interface.
use validation::benchmarks::concentric_cylinders::{
    lame_interface_pressure, run, ConcentricCylinders,
};

/// Runs the case and prints its figures against Lamé's `exact` pressure.
fn run_reported(algorithm: &'static str, swapped: bool, exact: f64) -> ConcentricCylinders {
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
    r
}

#[test]
fn mean_interface_pressure_within_one_percent_of_lame_either_side_master() {
    let exact = lame_interface_pressure();
    assert!((exact / 10.0 - 0.3469).abs() < 5e-5);
    let mut oscillation = Vec::new();
    for algorithm in ["segment-to-segment", "pointwise"] {
        for swapped in [false, true] {
            let r = run_reported(algorithm, swapped, exact);
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

/// The Nagata-smoothed master (issue 9): the arc ends lie on the case's
/// `symmetry` planes, whose point normals are projected into them
/// (thesis Fig. 4.40). Measured, segment-to-segment-nagata: mean p/p_Lamé
/// 0.989 with the outer tube as master, 1.009 with the inner one; 634 and
/// 488 outer iterations. Without the planes (end normals tilted by half a
/// facet) the outer loop stalled at a residual of 7e-6 after 100,000
/// iterations. The ±1 % is the *slave's* facets: against the smooth master
/// circle, the slave's inscribed chords stand off by 2/3 of their sagitta
/// on average (1.8e-4 for the inner tube's 40 facets: a gap, less
/// pressure; the outer tube's 30 facets as slave cut into the inner
/// master: more), where the faceted algorithm's inscribed master and slave
/// partly cancel (1.0025).
#[test]
fn nagata_master_with_symmetry_planes() {
    let exact = lame_interface_pressure();
    for swapped in [false, true] {
        let r = run_reported("segment-to-segment-nagata", swapped, exact);
        assert!(r.converged, "{swapped}");
        for side in [r.inner, r.outer] {
            assert!(
                (side.mean / exact - 1.0).abs() < 0.015,
                "{swapped}: {side:?}"
            );
        }
    }
}
