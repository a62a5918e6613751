//! Cylinder drawn through a rigid die (thesis §5.3.1, eq. 5.1): the
//! pulling force against the steady drawing force of an incompressible
//! neo-Hookean cylinder, 640.4 N; large strain in a one-cell wedge.
use validation::benchmarks::die_drawing::{
    analytical_force, run, CylinderMesh, DieRun, FULL_PULL, STEADY,
};

fn report(r: &DieRun) {
    let reference = analytical_force();
    for (d, (f, n)) in r.pull.iter().zip(r.force.iter().zip(&r.outer_iterations)) {
        if *d >= 0.1 {
            eprintln!(
                "  pull {d:.4} m: F = {f:.1} N ({:+.2} %), {n} outer iterations",
                100.0 * (f / reference - 1.0)
            );
        }
    }
    eprintln!(
        "die drawing (die master: {}): reached {:.4} m, {} increments, {} outer iterations ({:.0} per increment), {:.1} s, {:.2} µs per cell per outer iteration; wedge {:.6}°, axis points at most {:.1e} m off the axis; {:?}",
        !r.swapped,
        r.reached(),
        r.cost.increments,
        r.cost.outer_iterations,
        r.cost.outer_iterations as f64 / r.cost.increments.max(1) as f64,
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        r.wedge_degrees,
        r.axis_drift,
        r.failure
    );
}

/// The whole pull on the cylinder `mesh` with the die (`swapped` false)
/// or the cylinder as master: runs to the end with the wedge kept a
/// wedge, and the steady force over 0.18–0.25 m within `tolerance` of
/// eq. 5.1 and spread under 2 %.
fn full_pull_levels_off(mesh: CylinderMesh, swapped: bool, tolerance: f64) {
    let r = run(mesh, FULL_PULL, swapped);
    report(&r);
    assert!(r.converged, "{:?}", r.failure);
    // the wedge keeps its shape under the mesh motion (WedgePointConstraint)
    assert!(
        r.axis_drift < 1e-12,
        "axis points moved off the axis by {}",
        r.axis_drift
    );
    assert!(
        (r.wedge_degrees - 5.0).abs() < 1e-9,
        "wedge {}°",
        r.wedge_degrees
    );
    let reference = analytical_force();
    let Some((mean, spread)) = r.mean_force(STEADY.0, STEADY.1) else {
        panic!("the steady window was not reached")
    };
    let error = mean / reference - 1.0;
    eprintln!(
        "steady force over {:.4}–{:.4} m: {mean:.1} N vs {reference:.1} N (eq. 5.1): {:+.2} %, spread {:.2} %",
        STEADY.0,
        STEADY.1,
        100.0 * error,
        100.0 * spread
    );
    assert!(
        error.abs() < tolerance,
        "steady force {mean} vs {reference}"
    );
    assert!(
        spread < 0.02,
        "the force still changes by {spread} over the window"
    );
}

/// The whole 0.25 m pull as shipped (100 increments, 145 outer iterations
/// each under Anderson acceleration, ~3 s): the force over 0.18–0.25 m is
/// 653.1–656.2 N, mean 654.3 N, +2.18 % against eq. 5.1 (the thesis
/// reports +5 %), spread 0.47 %.
#[test]
fn die_drawing_force_levels_off_within_three_percent_of_eq_5_1() {
    full_pull_levels_off(CylinderMesh::Benchmark, false, 0.03);
}

/// Master and slave swapped (the cylinder as master, the rigid die as
/// slave). Measured: 652.9–656.0 N over the window, mean 654.2 N, +2.15 %;
/// 147 outer iterations per increment, ~3 s. It used to stop at
/// 0.1475 m: the contact faces' boundary values took a circumferential
/// component along their tilted normals, which the cell-to-point fit
/// passed to the points of the two wedge planes with opposite signs,
/// tilting the faces further (`SolidMomentum::unsolved`).
#[test]
fn die_drawing_cylinder_master() {
    full_pull_levels_off(CylinderMesh::Benchmark, true, 0.03);
}

/// The same on the cylinder refined twice in every direction (40 × 6 +
/// 34 × 6 cells, `cylinder-fine.msh`): the force converges on eq. 5.1.
/// Measured: 639.7–640.3 N over 0.18–0.25 m, mean 640.1 N, −0.06 %,
/// spread 0.09 %; 193 outer iterations per increment, 13 s (before the
/// wedge faces took the cell centre rotated back exactly: 628.4 N,
/// −1.9 %). The benchmark mesh gives +2.2 %.
#[test]
fn die_drawing_fine_mesh_converges_on_eq_5_1() {
    full_pull_levels_off(CylinderMesh::Fine, false, 0.005);
}

/// The fine mesh with the cylinder as master (`--ignored`, 17 s):
/// measured mean 640.0 N, −0.07 %, spread 0.08 %.
#[test]
#[ignore]
fn die_drawing_fine_mesh_cylinder_master() {
    full_pull_levels_off(CylinderMesh::Fine, true, 0.005);
}
