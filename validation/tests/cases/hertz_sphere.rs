//! Axisymmetric Hertz contact (thesis appendix A2, eqs. A13–A16): a
//! half-sphere on a rigid flat, one-cell wedge from Gmsh, either side master.
use validation::benchmarks::hertz_sphere::run;

#[test]
fn hertz_sphere_within_three_percent_either_side_master() {
    let a = run(false);
    let b = run(true);
    for r in [&a, &b] {
        eprintln!(
            "sphere master={}: F = {:.5} N (full revolution), b = {:.4} m (measured {:.4}, face {:.4}), p0 = {:.4} Pa, peak {:+.2} %, RMS {:.2} % p0, {} outer iterations, {:.2} s",
            r.swapped,
            r.force,
            r.hertz.radius,
            r.contact_radius,
            r.face_width,
            r.hertz.peak_pressure,
            100.0 * r.peak_error,
            100.0 * r.rms_error,
            r.cost.outer_iterations,
            r.cost.wall_seconds
        );
        assert!(r.converged);
        assert!(r.peak_error.abs() < 0.03, "peak {}", r.peak_error);
        assert!(
            (r.contact_radius - r.hertz.radius).abs() < r.face_width,
            "radius {} vs {}",
            r.contact_radius,
            r.hertz.radius
        );
        assert!(r.rms_error < 0.03, "RMS {}", r.rms_error);
    }
    let d = (a.force - b.force).abs() / a.force;
    eprintln!("force with master/slave swapped {:.3} % apart", 100.0 * d);
    assert!(d < 0.01, "{} vs {}", a.force, b.force);
}
