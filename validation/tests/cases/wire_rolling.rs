//! Wire rolling (thesis §5.4.2): the roll's vertical force and torque in
//! the steady state on the coarse wire, against a slab-method estimate of
//! the roll pressure, and the coarse against the medium wire (the thesis:
//! its coarse and finest meshes within 2.7 % in force, 5.2 % in torque).
//!
//! Both are long and ignored by default:
//! `cargo test --release -p validation --test cases wire_rolling -- --ignored --nocapture`.
use validation::benchmarks::steady_mean;
use validation::benchmarks::wire_rolling::{
    contact_length, run_edited, slab_pressure_band, RollingRun, CLOSED_AT, STEADY_FROM,
};

fn report(name: &str, r: &RollingRun) -> ((f64, f64), (f64, f64)) {
    eprintln!(
        "wire rolling {name}: {} increments, {:.1} Newton iterations per increment, {:.0} s; {:?}",
        r.cost.increments,
        r.cost.outer_iterations as f64 / r.cost.increments.max(1) as f64,
        r.cost.wall_seconds,
        r.failure
    );
    for (k, ((t, f), m)) in r.time.iter().zip(&r.force).zip(&r.torque).enumerate() {
        if k % 10 == 9 {
            eprintln!("  t = {t:.5} s: force {f:.1} N, torque {m:.0} N mm");
        }
    }
    assert!(r.converged, "{name}: {:?}", r.failure);
    let force = steady_mean(&r.time, &r.force, STEADY_FROM).expect("steady window reached");
    let torque = steady_mean(&r.time, &r.torque, STEADY_FROM).expect("steady window reached");
    eprintln!(
        "  steady from {STEADY_FROM} s: force {:.1} N (deviation {:.2} %), torque {:.0} N mm ({:.2} %)",
        force.0,
        100.0 * force.1,
        torque.0,
        100.0 * torque.1
    );
    (force, torque)
}

/// The slab method's band of the mean roll pressure
/// ([`slab_pressure_band`]) holds the force over the computed contact
/// area (the estimate checks the pressure, not the area, whose spread the
/// slab method does not give). The torque's lever arm, T / F, is 0.4–0.55
/// of the contact length for cold rolling.
#[test]
#[ignore = "about 10 minutes: cargo test --release -p validation --test cases wire_rolling -- --ignored --nocapture"]
fn wire_rolling_coarse_steady_force_within_the_slab_estimate() {
    let r = run_edited("case.toml", |t| t);
    let ((force, dev_f), (torque, dev_t)) = report("coarse", &r);
    assert!(dev_f < 0.02 && dev_t < 0.05, "not steady: {dev_f}, {dev_t}");
    let mut its = r.iterations.clone();
    its.sort_unstable();
    assert!(its[its.len() / 2] <= 10, "Newton iterations {its:?}");
    let contact_length = contact_length();
    let area = steady_mean(&r.time, &r.contact_area, STEADY_FROM)
        .expect("steady window")
        .0;
    let pressure = force / area;
    let (low, high) = slab_pressure_band();
    eprintln!(
        "  contact length {contact_length:.2} mm, area {area:.3} mm², mean pressure {pressure:.0} MPa; slab: {low:.0}–{high:.0} MPa; lever arm {:.2} of L",
        torque / force / contact_length
    );
    assert!(
        pressure > 0.97 * low && pressure < 1.03 * high,
        "mean pressure {pressure} MPa outside the slab estimate {low}–{high} MPa"
    );
    let arm = torque / force / contact_length;
    assert!((0.4..0.55).contains(&arm), "lever arm {arm} of L");
    assert!(r.time.last().is_some_and(|t| *t > CLOSED_AT));
}

/// The coarse and the medium wire (spacings / 1.5, 68,040 cells) agree in
/// the steady state within the thesis's coarse-to-finest differences:
/// 3 % in force, 6 % in torque (issue 43).
#[test]
#[ignore = "about 40 minutes: cargo test --release -p validation --test cases wire_rolling -- --ignored --nocapture"]
fn wire_rolling_coarse_and_medium_agree() {
    let ((fc, _), (tc, _)) = report("coarse", &run_edited("case.toml", |t| t));
    let ((fm, _), (tm, _)) = report("medium", &run_edited("medium.toml", |t| t));
    eprintln!(
        "medium against coarse: force {:+.2} %, torque {:+.2} %",
        100.0 * (fm / fc - 1.0),
        100.0 * (tm / tc - 1.0)
    );
    assert!((fm / fc - 1.0).abs() < 0.03, "force {fc} → {fm} N");
    assert!((tm / tc - 1.0).abs() < 0.06, "torque {tc} → {tm} N mm");
}
