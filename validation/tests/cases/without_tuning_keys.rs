//! The validation cases as a new user writes them (issue 46): the case
//! files with their tuning keys removed (`TUNING_KEYS`: contact coupling,
//! penalty scale, relaxation, Rhie–Chow factor, predictor, outer iteration
//! cap), run with the defaults — Newton–Krylov, penalty scale 1, or 5
//! against a rigid plane — and judged against the same references as the
//! shipped cases.
//!
//! Where the default penalty leaves the figure outside the shipped case's
//! limit, the test asserts it with the augmented Lagrangian switched on
//! (`augmentation = true`), the setting that makes the result independent
//! of the penalty, and says so.
use validation::benchmarks::curved_beams::{case_text, neto_peaks, run_text};
use validation::benchmarks::die_drawing::{self, analytical_force, CylinderMesh, STEADY};
use validation::benchmarks::sphere_block::{self, Variant};
use validation::benchmarks::{hertz_cylinder, hertz_sphere, strip_tuning_keys, TUNING_KEYS};

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

/// hertz-cylinder (shipped: implicit coupling, penalty scale 5, max_outer
/// 20,000), both meshes: within the shipped tests' limits of Hertz. The
/// rigid flat is a plane, so the penalty scale the case does not give is 5
/// (`contact_coupling::PenaltyScale`). Measured: coarse peak −3.28 %, RMS
/// 3.90 % p0; fine −0.99 %, 1.64 % (penalty scale 1: −7.60 % / 9.14 % and
/// −3.75 % / 3.11 %). Augmented on top of it (fine): −0.26 %, 2.27 %.
#[test]
fn hertz_cylinder_without_tuning_keys() {
    for (mesh, label, edit, peak, rms) in [
        (
            "coarse",
            "defaults",
            stripped as fn(String) -> String,
            0.05,
            0.05,
        ),
        ("fine", "defaults", stripped, 0.02, 0.03),
        ("fine", "augmented", stripped_augmented, 0.02, 0.03),
    ] {
        let r = hertz_cylinder::run_edited(mesh, false, edit);
        eprintln!(
            "hertz-cylinder {mesh}, no tuning keys, {label}: converged {}, peak {:+.2} %, RMS {:.2} % p0, {} nonlinear iterations, {:.2} s",
            r.converged,
            100.0 * r.peak_error,
            100.0 * r.rms_error,
            r.cost.outer_iterations,
            r.cost.wall_seconds
        );
        assert!(r.converged, "{mesh} {label}");
        assert!(
            r.peak_error.abs() < peak,
            "{mesh} {label}: peak {}",
            r.peak_error
        );
        assert!(r.rms_error < rms, "{mesh} {label}: RMS {}", r.rms_error);
    }
}

/// hertz-sphere on a rigid flat (shipped: penalty scale 10) and the sphere
/// on a rigid block (shipped: 10), without tuning keys: the rigid plane's
/// penalty scale 5 keeps them within the shipped tests' 3 % of Hertz.
/// Measured: hertz-sphere peak −1.9 %; sphere on the rigid block −1.57 %,
/// RMS 2.58 % (penalty scale 1: −5.89 % and −6.25 % / 5.47 %).
#[test]
fn spheres_on_rigid_planes_without_tuning_keys() {
    let h = hertz_sphere::run_edited(false, stripped);
    eprintln!(
        "hertz-sphere, no tuning keys: converged {}, peak {:+.2} %, RMS {:.2} % p0, {} nonlinear iterations",
        h.converged,
        100.0 * h.peak_error,
        100.0 * h.rms_error,
        h.cost.outer_iterations
    );
    assert!(h.converged);
    assert!(
        h.peak_error.abs() < 0.03,
        "hertz-sphere peak {}",
        h.peak_error
    );
    assert!(h.rms_error < 0.03, "hertz-sphere RMS {}", h.rms_error);
    let r = sphere_block::run_edited(Variant::Rigid, false, stripped);
    eprintln!(
        "sphere on a rigid block, no tuning keys: converged {}, peak {:+.2} %, RMS {:.2} % p0, {} nonlinear iterations",
        r.converged,
        100.0 * r.peak_error,
        100.0 * r.rms_error,
        r.cost.outer_iterations
    );
    assert!(r.converged);
    assert!(
        r.peak_error.abs() < 0.03,
        "rigid block peak {}",
        r.peak_error
    );
    assert!(r.rms_error < 0.03, "rigid block RMS {}", r.rms_error);
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

/// [`stripped_augmented`] with `penalty_scale` on every contact.
fn augmented_at(text: String, scale: f64) -> String {
    stripped_augmented(text).replace(
        "augmentation = true\n",
        &format!("augmentation = true\npenalty_scale = {scale}\n"),
    )
}

/// Issue 46's penalty independence: with the augmented Lagrangian, the
/// benchmark figures at penalty scale 1 and 100 agree within 1 % (hertz
/// fine: the peak pressure and the force). Measured: hertz force
/// 0.035 %, peak 0.104 %. Sphere-block (the force) at 1 and 10 only
/// (0.07 %): at 100 its GMRES stalls at 200 iterations from the fifth
/// Newton step (400 with a restart of 100: linear residual 0.1–0.5, the
/// finite-difference products of a stiff, non-smooth contact residual),
/// and Newton is taken at its floor, 7e-5–9e-5: a force 0.8 % off with
/// the absolute contact step limit (the contact area a quarter of the
/// converged one) and 10 % off with the relative one (one half cell). Not converged
/// either way: issue 46 open there. Die drawing: the steady force.
#[test]
fn augmented_results_do_not_depend_on_the_penalty() {
    let close = |what: &str, a: f64, b: f64| {
        let d = (a / b - 1.0).abs();
        eprintln!(
            "{what}: penalty 1 {a:.5}, stiffer {b:.5}, {:.3} %",
            100.0 * d
        );
        assert!(d < 0.01, "{what}: {a} vs {b}");
    };
    let [h1, h100] = [1.0, 100.0]
        .map(|s| hertz_cylinder::run_edited("fine", false, move |t| augmented_at(t, s)));
    assert!(h1.converged && h100.converged);
    close("hertz fine force", h1.force, h100.force);
    close(
        "hertz fine peak / Hertz",
        1.0 + h1.peak_error,
        1.0 + h100.peak_error,
    );
    let [s1, s10] = [1.0, 10.0]
        .map(|s| sphere_block::run_edited(Variant::Deformable, false, move |t| augmented_at(t, s)));
    assert!(s1.converged && s10.converged);
    close("sphere-block force (penalty 10)", s1.force, s10.force);
    // not its peak pressure: +7.4 % of Hertz at penalty 1 and +122 % at
    // 100 with the multipliers (+0.47 % at 1 without them), a spike the
    // Uzawa updates leave on faces at the edge of contact (issue 46 open)
    eprintln!(
        "sphere-block peak / Hertz, augmented: penalty 1 {:+.2} %, penalty 10 {:+.2} %",
        100.0 * s1.peak_error,
        100.0 * s10.peak_error
    );
    // die drawing: the steady force. Until 2026-11-30 the run at penalty
    // 100 stopped at 0.169 m (increment 68, residual 8e-2 after 500
    // iterations at 1/64 of the step); with the factorised Jacobian from
    // the first step (a plane problem of 302 unknowns) it runs to the
    // end. Measured: 656.6 N at penalty 1, 655.3 N at 100, 0.21 %. The
    // completion at 100 depends on the step: over 90, 110, 125 and 150
    // increments the penalty-100 run stops at 0.17–0.22 m (residual
    // 2–4e-2 after 500–700 iterations; measured 2026-12-02, issue 46
    // open there; docs/newton-krylov.md, "Contact derivative").
    let [d1, d100] = [1.0, 100.0].map(|s| {
        die_drawing::run_edited(
            CylinderMesh::Benchmark,
            die_drawing::FULL_PULL,
            false,
            move |t| augmented_at(t, s),
        )
    });
    assert!(
        d1.converged && d100.converged,
        "{:?} {:?}",
        d1.failure,
        d100.failure
    );
    let steady = |r: &die_drawing::DieRun| {
        r.mean_force(STEADY.0, STEADY.1)
            .map(|(mean, _)| mean)
            .expect("the steady window reached")
    };
    close("die drawing steady force", steady(&d1), steady(&d100));
}
