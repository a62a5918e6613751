//! nafems-punch and nafems-punch-modified (thesis §5.2.4, appendix A3.1,
//! `../shared/benchmarks/README.md`): axisymmetric one-cell wedges from
//! Gmsh, elastic punch on an elastic foundation, with either side master.
use validation::benchmarks::nafems_punch::{
    a25_radius, interpolate_uy, run, run_disc, run_text, NafemsPunch, Variant,
    AXIS_DISPLACEMENT_FRICTION, AXIS_DISPLACEMENT_FRICTIONLESS, DISC_FE,
    FE_AXIS_DISPLACEMENT_FRICTION, FE_AXIS_DISPLACEMENT_FRICTIONLESS, FE_AXIS_PRESSURE_FRICTION,
    FE_AXIS_PRESSURE_FRICTIONLESS, MODIFIED_FILLET, MODIFIED_FLAT, MODIFIED_MODULUS,
    MODIFIED_PRESSURE, PUNCH_RADIUS,
};

fn report(r: &NafemsPunch) {
    eprintln!(
        "{} punch master={}: F = {:.6e} N (full revolution, wedge {:.3}°), u_y(axis) = {:.5} mm, p(axis) = {:.2} MPa, contact radius {:.3} mm (face {:.3}), {} outer iterations, {:.2} s",
        r.variant.name(),
        r.swapped,
        r.force,
        r.wedge_angle.to_degrees(),
        r.axis_displacement,
        r.axis_pressure,
        r.contact_radius,
        r.face_width,
        r.cost.outer_iterations,
        r.cost.wall_seconds
    );
}

fn swapped_force_agrees(a: &NafemsPunch, b: &NafemsPunch) {
    let d = (a.force - b.force).abs() / a.force;
    eprintln!(
        "{}: force with master/slave swapped {:.3} % apart",
        a.variant.name(),
        100.0 * d
    );
    assert!(d < 0.01, "{} vs {}", a.force, b.force);
}

/// The axis displacement within 1 % and the axis pressure within 3 % of the
/// independent finite-element reference (the limits of the benchmark table).
fn axis_against_fe(r: &NafemsPunch, displacement: f64, pressure: f64) {
    let du = r.axis_displacement / displacement - 1.0;
    let dp = r.axis_pressure / pressure - 1.0;
    eprintln!(
        "  vs the biquadratic FE reference: u_y(axis) {:+.2} % ({displacement}), p(axis) {:+.2} % ({pressure})",
        100.0 * du,
        100.0 * dp
    );
    assert!(du.abs() < 0.01, "{}", r.axis_displacement);
    assert!(dp.abs() < 0.03, "{}", r.axis_pressure);
}

/// Applied load of the full revolution: 100 MPa on the punch top.
fn applied(pressure: f64) -> f64 {
    pressure * std::f64::consts::PI * PUNCH_RADIUS * PUNCH_RADIUS
}

#[test]
fn nafems_punch_with_friction_either_side_master() {
    let a = run(Variant::Friction, false);
    let b = run(Variant::Friction, true);
    for r in [&a, &b] {
        report(r);
        assert!(r.converged);
        // the contact carries the top load (72 faceted wedges: 0.13 % less area)
        assert!(
            (r.force / applied(100.0) - 1.0).abs() < 0.005,
            "{}",
            r.force
        );
        // against the mesh-converged biquadratic FE solution of the same
        // set-up (cases/nafems-punch/fe_reference.py): measured +0.6 % in
        // u_y and +0.75 % in p on the axis
        axis_against_fe(r, FE_AXIS_DISPLACEMENT_FRICTION, FE_AXIS_PRESSURE_FRICTION);
        // the benchmark table's references are not converged solutions of
        // this set-up: SSNA122 (an average of Marc and Abaqus) is 2.4 %
        // below the FE reference, Marc's 70.5 MPa on the axis 20 % below;
        // measured −0.1326 mm (+3.1 % vs SSNA122) and 89 MPa (see the report)
        let e = r.axis_displacement / AXIS_DISPLACEMENT_FRICTION - 1.0;
        eprintln!("  u_y(axis) vs SSNA122: {:+.2} %", 100.0 * e);
        assert!(e.abs() < 0.035, "{}", r.axis_displacement);
    }
    swapped_force_agrees(&a, &b);
}

#[test]
fn nafems_punch_frictionless_either_side_master() {
    let a = run(Variant::Frictionless, false);
    let b = run(Variant::Frictionless, true);
    for r in [&a, &b] {
        report(r);
        assert!(r.converged);
        // measured +0.6 % in u_y and +0.7 % in p against the FE reference
        axis_against_fe(
            r,
            FE_AXIS_DISPLACEMENT_FRICTIONLESS,
            FE_AXIS_PRESSURE_FRICTIONLESS,
        );
        // SSNA122 is 2.4 % below the FE reference; measured +3.1 %
        let e = r.axis_displacement / AXIS_DISPLACEMENT_FRICTIONLESS - 1.0;
        eprintln!("  u_y(axis) vs SSNA122: {:+.2} %", 100.0 * e);
        assert!(e.abs() < 0.035, "{}", r.axis_displacement);
    }
    // friction lowers the axis displacement by 1.7 % in SSNA122
    let f = run(Variant::Friction, false);
    let ratio = a.axis_displacement / f.axis_displacement;
    let reference = AXIS_DISPLACEMENT_FRICTIONLESS / AXIS_DISPLACEMENT_FRICTION;
    eprintln!("frictionless/friction axis displacement {ratio:.4} (SSNA122 {reference:.4})");
    assert!((ratio / reference - 1.0).abs() < 0.003);
    swapped_force_agrees(&a, &b);
}

#[test]
fn nafems_punch_pointwise_either_side_master() {
    // the pointwise algorithm in the one-cell wedge: every slave point lies
    // on a wedge plane beside the master surface's border edges (before
    // 2026-11-26 points lost their gaps at random and the implicit
    // coupling oscillated for 20,000 outer iterations); with Nagata
    // smoothing, feet extrapolated beyond the patches spiked the pressure
    // at the punch's edge
    let (dir, text) = validation::benchmarks::read_case("nafems-punch", "case.toml");
    let text = text.replace(
        "coupling = \"implicit\"",
        "coupling = \"implicit\"\nalgorithm = \"pointwise\"",
    );
    for (swapped, algorithm) in [
        (false, "pointwise"),
        (true, "pointwise"),
        (false, "pointwise-nagata"),
    ] {
        let text = text.replace("\"pointwise\"", &format!("\"{algorithm}\""));
        let r = run_text(Variant::Friction, swapped, &dir, text);
        eprintln!("{algorithm}:");
        report(&r);
        assert!(r.converged);
        assert!(
            (r.force / applied(100.0) - 1.0).abs() < 0.005,
            "{}",
            r.force
        );
        // measured −0.1 % in u_y and −0.6 % in p on the axis (Nagata −0.1
        // and −0.5 %)
        axis_against_fe(&r, FE_AXIS_DISPLACEMENT_FRICTION, FE_AXIS_PRESSURE_FRICTION);
    }
}

#[test]
fn foundation_under_a_disc_pressure_against_biquadratic_fe() {
    // the wedges without contact, prisms on the axis included: measured
    // +0.19 % on the axis, +0.19 to +0.23 % at r = 10–35 mm (before the
    // wedge faces took the cell centre rotated back exactly: +0.23 %,
    // +0.19 to +0.22 %)
    let (faces, converged) = run_disc();
    assert!(converged);
    for (r, reference) in DISC_FE {
        let u = interpolate_uy(&faces, r);
        let e = u / reference - 1.0;
        eprintln!(
            "disc load: u_y(r = {r}) = {u:.6} mm, FE {reference}: {:+.3} %",
            100.0 * e
        );
        assert!(e.abs() < 0.005, "r = {r}: {u}");
    }
}

#[test]
fn nafems_punch_modified_against_a26_either_side_master() {
    let a = run(Variant::Modified, false);
    let b = run(Variant::Modified, true);
    let expected = a25_radius(
        MODIFIED_FLAT,
        MODIFIED_FILLET,
        MODIFIED_MODULUS,
        applied(MODIFIED_PRESSURE),
    );
    for r in [&a, &b] {
        report(r);
        assert!(r.converged);
        let (err, _) = r.a26_error(0.9);
        let from_force = a25_radius(MODIFIED_FLAT, MODIFIED_FILLET, MODIFIED_MODULUS, r.force);
        eprintln!(
            "  max |p/p_A26 − 1| over r ≤ 0.9 b: {:.2} %; contact radius {:.3} mm, A25 {:.3} mm for the computed force, {:.3} mm for the applied load (a/b = {:.3})",
            100.0 * err,
            r.contact_radius,
            from_force,
            expected,
            MODIFIED_FLAT / r.contact_radius
        );
        assert!(err < 0.03, "{err}");
        assert!((r.contact_radius - from_force).abs() < r.face_width);
    }
    swapped_force_agrees(&a, &b);
}

#[test]
fn a26_reproduces_the_digitised_curves() {
    // ../shared/benchmarks/nafems-punch-modified/reference/analytical_ab0{7,8}.dat:
    // p/p_mean against r/b for a/b = 0.7 and 0.8 (digitised, so 0.03 apart at most
    // below the peak)
    let Some(shared) = validation::shared_dir() else {
        eprintln!("skipped: ../shared/benchmarks is absent");
        return;
    };
    for (ab, file) in [(0.7, "analytical_ab07.dat"), (0.8, "analytical_ab08.dat")] {
        let path = shared
            .join("benchmarks/nafems-punch-modified/reference")
            .join(file);
        let Ok(text) = std::fs::read_to_string(&path) else {
            eprintln!("skipped: {} is absent", path.display());
            return;
        };
        let mut worst = 0.0f64;
        for line in text.lines() {
            let v: Vec<f64> = line
                .split(',')
                .filter_map(|s| s.trim().parse().ok())
                .collect();
            if let [x, y] = v[..] {
                if x < 0.9 * ab {
                    let p = validation::benchmarks::nafems_punch::a26_ratio(ab, 1.0, x);
                    worst = worst.max((p - y).abs());
                }
            }
        }
        eprintln!("A26 against {file} for r/b < 0.9 a/b: max |Δ(p/p_mean)| = {worst:.4}");
        assert!(worst < 0.02, "{file}: {worst}");
    }
}
