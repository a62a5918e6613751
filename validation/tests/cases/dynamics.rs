//! Inertia (thesis eq. 3.11): the axial vibration of a bar.
use validation::run_toml_with_history;

/// A bar fixed at x = 0 with a suddenly applied end traction vibrates with
/// the period of its first axial mode, T = 4L/c, c = √(E/ρ). The reaction at
/// the fixed end is a square wave about the static load; its mean crossings
/// are half a period apart.
#[test]
fn axially_vibrating_bar_has_the_analytical_period() {
    let (l, e, rho, t_load): (f64, f64, f64, f64) = (1.0, 1.0, 1.0, 1e-3);
    let period = 4.0 * l / (e / rho).sqrt();
    // 100 steps per period, three periods
    let steps = 300;
    let case = format!(
        r#"
title = "bar"
[analysis]
kind = "dynamic"
[time]
end = {}
steps = {steps}
[solver]
tolerance = 1e-9
[[body]]
name = "bar"
mesh = {{ generator = "box", min = [0, 0, 0], max = [{l}, 0.05, 0.05], cells = [50, 1, 1] }}
material = {{ model = "linear-elastic", E = {e}, nu = 0.0, rho = {rho} }}
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.xmax]
type = "traction"
value = [{t_load}, 0, 0]
[body.boundary.ymin]
type = "symmetry"
[body.boundary.ymax]
type = "symmetry"
[body.boundary.zmin]
type = "symmetry"
[body.boundary.zmax]
type = "symmetry"
"#,
        3.0 * period
    );
    let (out, history) = run_toml_with_history(&case);
    assert!(out.converged, "{:?}", out.failure);
    let time = history.column("time");
    // force on the bar through the fixed end: −F_load at rest
    let fx = history.column("bar/xmin:Fx");
    let area = 0.05 * 0.05;
    let mean = -t_load * area;
    let mut crossings = Vec::new();
    for i in 1..fx.len() {
        let (a, b) = (fx[i - 1] - mean, fx[i] - mean);
        if (a < 0.0) != (b < 0.0) {
            crossings.push(time[i - 1] + (time[i] - time[i - 1]) * a / (a - b));
        }
    }
    assert!(crossings.len() >= 5, "crossings {crossings:?}");
    // mean period over the crossings after the first (two per period)
    let n = crossings.len() - 1;
    let measured = 2.0 * (crossings[n] - crossings[0]) / n as f64;
    let err = (measured - period) / period;
    eprintln!(
        "axial bar vibration: period {measured:.4} (analytical {period:.4}), error {:.2} %, from {} mean crossings; {} outer iterations for {steps} steps",
        100.0 * err,
        crossings.len(),
        out.summary.outer_iterations
    );
    assert!(err.abs() < 0.02, "period error {err}");
}
