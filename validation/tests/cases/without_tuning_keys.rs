//! The validation cases as a new user writes them (issue 46): the case
//! files with their tuning keys removed (`TUNING_KEYS`: contact coupling,
//! penalty scale, relaxation, Rhie–Chow factor, predictor, outer iteration
//! cap), run with the defaults — Newton–Krylov, penalty scale 1 — and
//! judged against the same references as the shipped cases.
//!
//! Where the penalty scale 1 leaves the figure outside the shipped case's
//! limit, the test asserts it with the augmented Lagrangian switched on
//! (`augmentation = true`), the setting that makes the result independent
//! of the penalty, and says so.
use validation::benchmarks::curved_beams::{case_text, neto_peaks, run_text};
use validation::benchmarks::die_drawing::{self, analytical_force, CylinderMesh, STEADY};
use validation::benchmarks::sphere_block::{self, Variant};
use validation::benchmarks::{hertz_cylinder, strip_tuning_keys, TUNING_KEYS};

/// The stripped text, checked to have lost every tuning key.
fn stripped(text: String) -> String {
    let s = strip_tuning_keys(&text);
    for key in TUNING_KEYS {
        assert!(
            !s.lines()
                .any(|l| l.trim_start().starts_with(&format!("{key} ="))),
            "{key} left in the stripped case"
        );
    }
    s
}

/// The stripped text with the augmented Lagrangian on every contact.
fn stripped_augmented(text: String) -> String {
    stripped(text).replace("[[contact]]\n", "[[contact]]\naugmentation = true\n")
}

/// hertz-cylinder, fine mesh (shipped: implicit coupling, penalty scale 5,
/// max_outer 20,000): within the shipped test's limits of Hertz with the
/// augmented Lagrangian (measured: peak −0.48 %, RMS 1.10 % p0, 9 Newton
/// iterations). At penalty scale 1 alone the peak is flattened by the
/// penetration, −3.75 % (RMS 3.11 %): the reason the case gives 5.
#[test]
fn hertz_cylinder_fine_without_tuning_keys() {
    for (label, edit) in [
        ("penalty scale 1", stripped as fn(String) -> String),
        ("augmented", stripped_augmented),
    ] {
        let r = hertz_cylinder::run_edited("fine", false, edit);
        eprintln!(
            "hertz-cylinder fine, no tuning keys, {label}: converged {}, peak {:+.2} %, RMS {:.2} % p0, {} nonlinear iterations, {:.2} s",
            r.converged,
            100.0 * r.peak_error,
            100.0 * r.rms_error,
            r.cost.outer_iterations,
            r.cost.wall_seconds
        );
        assert!(r.converged, "{label}");
        if label == "augmented" {
            assert!(r.peak_error.abs() < 0.02, "{label}: peak {}", r.peak_error);
            assert!(r.rms_error < 0.03, "{label}: RMS {}", r.rms_error);
        }
    }
}

/// sphere-block (shipped: implicit coupling, penalty scale 1, max_outer
/// 20,000): the peak pressure within the shipped test's 3 % of Hertz
/// (measured +0.47 %, RMS 2.33 %, 11 Newton iterations).
#[test]
fn sphere_block_without_tuning_keys() {
    let r = sphere_block::run_edited(Variant::Deformable, false, stripped);
    eprintln!(
        "sphere-block, no tuning keys: converged {}, force {:.4}, peak {:+.2} %, RMS {:.2} %, {} nonlinear iterations, {:.2} s",
        r.converged,
        r.force,
        100.0 * r.peak_error,
        100.0 * r.rms_error,
        r.cost.outer_iterations,
        r.cost.wall_seconds
    );
    assert!(r.converged);
    assert!(r.peak_error.abs() < 0.03, "peak {}", r.peak_error);
    assert!(r.rms_error < 0.03, "RMS {}", r.rms_error);
}

/// die-drawing (shipped: implicit coupling, penalty scale 20, max_outer
/// 5,000): the steady force within the shipped test's 3 % of eq. 5.1
/// and levelled off (spread under 2 %). Measured: penalty scale 1
/// 629.0 N (−1.78 %, spread 0.25 %), augmented 657.3 N (+2.63 %); the
/// shipped case +2.18 %.
#[test]
fn die_drawing_without_tuning_keys() {
    let reference = analytical_force();
    for (label, edit) in [
        ("penalty scale 1", stripped as fn(String) -> String),
        ("augmented", stripped_augmented),
    ] {
        let r =
            die_drawing::run_edited(CylinderMesh::Benchmark, die_drawing::FULL_PULL, false, edit);
        assert!(r.converged, "{label}: {:?}", r.failure);
        let Some((mean, spread)) = r.mean_force(STEADY.0, STEADY.1) else {
            panic!("{label}: the steady window was not reached")
        };
        let error = mean / reference - 1.0;
        eprintln!(
            "die-drawing, no tuning keys, {label}: steady force {mean:.1} N ({:+.2} % of eq. 5.1), spread {:.2} %, {} nonlinear iterations, {:.2} s",
            100.0 * error,
            100.0 * spread,
            r.cost.outer_iterations,
            r.cost.wall_seconds
        );
        assert!(spread < 0.02, "{label}: spread {spread}");
        assert!(error.abs() < 0.03, "{label}: {mean} vs {reference}");
    }
}

/// curved-beams μ = 0.3, the full slide (shipped: implicit coupling and
/// Rhie–Chow 1, both stripped; the case's notes give peaks 1–2 % lower
/// with the default Rhie–Chow factor): the reaction peaks within the
/// shipped test's 3 % of Neto et al. (measured: Fx 17.007 N, −1.7 %;
/// Fy 38.807 N, −0.5 %; 984 Newton iterations over the 63 increments).
#[test]
fn curved_beams_frictional_without_tuning_keys() {
    let r = run_text(&stripped(case_text(0.3, 31.5, false)));
    assert!(r.converged(), "{:?}", r.failure);
    let ((fx, at_x), (fy, at_y)) = (r.fx_peak(), r.fy_peak());
    eprintln!(
        "curved beams μ = 0.3, no tuning keys: peak |Fx| {fx:.3} N at {at_x:.1} mm, |Fy| {fy:.3} N at {at_y:.1} mm, {} nonlinear iterations, {:.1} s",
        r.cost.outer_iterations, r.cost.wall_seconds
    );
    let (nx, ny) = neto_peaks(0.3).expect("μ = 0.3 is in the table");
    assert!((fx / nx - 1.0).abs() < 0.03, "Fx {fx} vs {nx}");
    assert!((fy / ny - 1.0).abs() < 0.03, "Fy {fy} vs {ny}");
}
