//! shallow-ironing (thesis §5.3.2, table 5.2; issue 7;
//! `../shared/benchmarks/README.md`): a stiff block with a rounded bottom
//! pressed 1 mm into a foundation and dragged 10 mm along it, μ = 0.3,
//! neo-Hookean, plane strain, N and mm.
//!
//! The full case (600 increments, ~186,000 outer iterations, 12 min on
//! one core) is `--ignored`, as is implicit against explicit coupling up
//! to t = 1.2 (issue 8); the default test runs the indentation as
//! shipped (100 increments, ~45 s) and checks the vertical force at
//! t = 1 against the published curves.
use validation::benchmarks::shallow_ironing::{
    reference_curves, run, Options, MU_G_BAND, OSCILLATION_HALF_WINDOW, OSCILLATION_INTERVAL,
    OSCILLATION_LIMIT,
};
use validation::shared_dir;

/// V at t = 1 (just before the slide) of Code_Aster SSNP153
/// (`reference/asterVertical.dat` at t = 0.999, × 100), N/mm.
const V_ASTER_T1: f64 = 330.8;
/// The same of Hartmann–Oliver (`hartmannOliverVertical.dat`), N/mm.
const V_HARTMANN_T1: f64 = 318.8;

/// Indentation as shipped: V(t = 1) = 325.1 N/mm, −1.7 % against
/// Code_Aster and +2.0 % against Hartmann–Oliver (Fischer–Wriggers 297,
/// Yastrebov 289, Poulios–Renard 267); 321.7 at penalty_scale 1.
#[test]
fn indentation_vertical_force_against_code_aster() {
    let r = run(&Options {
        until: 1.0,
        ..Default::default()
    });
    assert!(r.converged, "{:?}", r.failure);
    let (h, v) = r.forces_at(1.0);
    eprintln!(
        "shallow ironing, indentation: H = {h:.2}, V = {v:.2} N/mm at t = 1 (Code_Aster {V_ASTER_T1}, Hartmann–Oliver {V_HARTMANN_T1}); {:.0} outer iterations per increment, {:.1} s, {:.3} µs/cell/iteration",
        r.mean_outer(0.0, 1.0),
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration()
    );
    assert!(
        (v / V_ASTER_T1 - 1.0).abs() < 0.05,
        "V = {v} against {V_ASTER_T1}"
    );
    assert!(
        (v / V_HARTMANN_T1 - 1.0).abs() < 0.05,
        "V = {v} against {V_HARTMANN_T1}"
    );
    // the block is pressed, not yet dragged: H is a fraction of μ V
    assert!(h > 0.0 && h < 0.3 * v, "H = {h}, V = {v}");
}

/// The full case: μ_g = H/V at t = 1.5 within [0.30, 0.36] (thesis 0.32)
/// and the oscillation of H over t 1.2–1.9 (largest deviation from its
/// centred 25-increment moving average) below 1 % of its mean.
///
/// Measured (implicit coupling, foundation master, the case's Rhie–Chow
/// 0.5 and penalty_scale 4, the accumulated slip history and the contact
/// share of the friction): μ_g = 0.3111 and an oscillation of 0.626 %,
/// both pass; 75 outer iterations per increment indenting, 332 sliding.
/// Before those two (incremental slip history): 0.3108 and 0.513 %, 76
/// and 261 (`fvc run`, one thread). At penalty_scale 1: 0.3090 and 0.358 %, 69 and
/// 300 (before the contact springs per current area and the
/// path-following predictor: 0.3055 and 0.763 %; before the boundary-face
/// state: 0.307 and 0.78 %). With Rhie–Chow 0.1: μ_g = 0.306,
/// oscillation 1.16 % (period five increments = one 0.1 mm foundation
/// face, peak-to-peak 2.3 N on 126 N), which failed.
#[test]
#[ignore]
fn full_slide_global_friction_and_smoothness() {
    let r = run(&Options::default());
    assert!(r.converged, "{:?}", r.failure);
    let mu_g = r.mu_g(1.5);
    let osc = r.oscillation(
        OSCILLATION_INTERVAL.0,
        OSCILLATION_INTERVAL.1,
        OSCILLATION_HALF_WINDOW,
    );
    let (h1, v1) = r.forces_at(1.0);
    let (h15, v15) = r.forces_at(1.5);
    eprintln!(
        "shallow ironing: t = 1: H = {h1:.2}, V = {v1:.2}; t = 1.5: H = {h15:.2}, V = {v15:.2} N/mm, μ_g = {mu_g:.4}; oscillation of H over t 1.2–1.9 {:.3} %; outer iterations per increment {:.0} (indentation), {:.0} (slide); {:.0} s, {:.3} µs/cell/iteration",
        100.0 * osc,
        r.mean_outer(0.0, 1.0),
        r.mean_outer(1.0, 2.0),
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration()
    );
    if let Some(shared) = shared_dir() {
        match reference_curves(&shared) {
            Ok(curves) => {
                for c in &curves {
                    let (h, v) = c.forces_at(1.5);
                    eprintln!(
                        "  {}: t = 1.5 H = {h:.1} ({:+.1} %), V = {v:.1} ({:+.1} %), μ_g = {:.3}",
                        c.source,
                        100.0 * (h15 / h - 1.0),
                        100.0 * (v15 / v - 1.0),
                        h / v
                    );
                }
            }
            Err(e) => eprintln!("  reference curves: {e}"),
        }
    } else {
        eprintln!("  reference curves skipped: ../shared is absent");
    }
    assert!(
        mu_g >= MU_G_BAND.0 && mu_g <= MU_G_BAND.1,
        "μ_g = {mu_g} outside {MU_G_BAND:?}"
    );
    assert!(
        osc < OSCILLATION_LIMIT,
        "H oscillates by {:.3} % (limit {:.0} %)",
        100.0 * osc,
        100.0 * OSCILLATION_LIMIT
    );
}

/// Master and slave swapped (block arc master), the full case; the same
/// acceptance as [`full_slide_global_friction_and_smoothness`]. Measured
/// (the case as shipped, penalty_scale 4, accumulated slip history and
/// contact share of the friction): runs to the end, μ_g(1.5) = 0.3031 and
/// oscillation 0.545 %, both pass (foundation master 0.3111), 760 s in
/// the test binary. Before those two: 0.3023 and 0.401 %, 74 outer
/// iterations per increment indenting, 252 sliding. At
/// penalty_scale 1 it was 0.2989 and 0.463 %, just under the band: the
/// regularisation of the penalty (0.2989 / 0.3011 / 0.3023 / 0.3022 at
/// penalty_scale 1 / 2 / 4 / 6, to t = 1.5). With the accumulated Rhie–Chow
/// stabilisation at 0.1 (penalty_scale 1): 0.2939 and 0.532 %.
#[test]
#[ignore]
fn full_slide_block_master() {
    let r = run(&Options {
        swapped: true,
        ..Default::default()
    });
    assert!(r.converged, "{:?}", r.failure);
    let mu_g = r.mu_g(1.5);
    let osc = r.oscillation(
        OSCILLATION_INTERVAL.0,
        OSCILLATION_INTERVAL.1,
        OSCILLATION_HALF_WINDOW,
    );
    eprintln!(
        "shallow ironing, block master: μ_g(1.5) = {mu_g:.4}, oscillation {:.3} %, {:.0} s",
        100.0 * osc,
        r.cost.wall_seconds
    );
    assert!(mu_g >= MU_G_BAND.0 && mu_g <= MU_G_BAND.1, "μ_g = {mu_g}");
    assert!(osc < OSCILLATION_LIMIT, "oscillation {:.3} %", 100.0 * osc);
}

/// The reference files parse into five curves with V(t = 1) of the order
/// of the computed 322 N/mm (the units check of the case file).
#[test]
fn reference_curves_parse() {
    let Some(shared) = shared_dir() else {
        eprintln!("skipped: ../shared is absent");
        return;
    };
    let curves = match reference_curves(&shared) {
        Ok(c) => c,
        Err(e) => panic!("{e}"),
    };
    assert_eq!(curves.len(), 5);
    for c in &curves {
        let (_, v) = c.forces_at(0.999);
        eprintln!("{}: V(t = 1) = {v:.1} N/mm", c.source);
        assert!(v > 250.0 && v < 350.0, "{}: {v}", c.source);
    }
}

/// Issue 8, friction: implicit against explicit coupling over the
/// indentation and the first 2 mm of the slide (t = 1.2, 100 increments
/// each), explicit at relaxation 0.05, the best that runs (0.07 stops at
/// t = 0.43 and the default 0.1 at 0.335, no convergence in 20,000 outer
/// iterations at four cut-backs; 0.02 needs 202 outer iterations per
/// indentation increment against 169).
/// Measured: implicit 69.4 outer iterations per indentation increment and
/// 228 per slide increment, explicit 169 and 559 (2.4× each); H and V
/// within 0.1 % and 0.4 % of each other at t = 1, 1.1 and 1.2 (μ_g(1.2)
/// 0.3046 implicit, 0.3033 explicit). The thesis reports more than 10× on
/// ironing; here the explicit coupling that runs at all is nearly the
/// best. About 8 minutes. Both at penalty_scale 1 (the case ships 4), the
/// penalty these figures and the relaxation sweep were measured at.
#[test]
#[ignore]
fn implicit_against_explicit_coupling() {
    let opts = |implicit: bool| Options {
        until: 1.2,
        slide_step: 0.002,
        implicit: Some(implicit),
        relaxation: 0.05,
        penalty_scale: Some(1.0),
        ..Default::default()
    };
    let implicit = run(&opts(true));
    let explicit = run(&opts(false));
    for r in [&implicit, &explicit] {
        assert!(r.converged, "{:?}", r.failure);
    }
    for t in [1.0, 1.1, 1.2] {
        let (hi, vi) = implicit.forces_at(t);
        let (he, ve) = explicit.forces_at(t);
        eprintln!("t = {t}: H {hi:.3} / {he:.3}, V {vi:.3} / {ve:.3} N/mm (implicit / explicit)");
        assert!(
            (hi / he - 1.0).abs() < 0.01,
            "H at t = {t}: {hi} against {he}"
        );
        assert!(
            (vi / ve - 1.0).abs() < 0.01,
            "V at t = {t}: {vi} against {ve}"
        );
    }
    let phases = [("indentation", 0.0, 1.0), ("slide", 1.0, 1.2)];
    for (name, t0, t1) in phases {
        let (ni, ne) = (implicit.mean_outer(t0, t1), explicit.mean_outer(t0, t1));
        eprintln!(
            "{name}: {ni:.1} implicit against {ne:.1} explicit outer iterations per increment ({:.2}×)",
            ne / ni
        );
        assert!(ne / ni > 2.0, "{name}: {ni} against {ne}");
    }
    eprintln!(
        "wall time: implicit {:.0} s, explicit {:.0} s",
        implicit.cost.wall_seconds, explicit.cost.wall_seconds
    );
}
