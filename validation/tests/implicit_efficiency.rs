//! Implicit against explicit contact coupling (thesis §4.5, Tables 4.5–4.7).
use validation::benchmarks::coupling_efficiency::{calibrate, sweep, Benchmark, CouplingRun};

fn line(r: &CouplingRun) {
    eprintln!(
        "  {} f_n {:.4} r {:.3}: {} {} outer, {:.2} s, {:.3} µs/cell/iter, eps {:.4e}, rel gap {:.4} %, {:?}",
        if r.settings.implicit { "implicit" } else { "explicit" },
        r.settings.penalty_scale,
        r.settings.relaxation,
        if r.converged { "converged" } else { "NOT converged" },
        r.cost.outer_iterations,
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        r.normal_penalty,
        100.0 * r.relative_gap,
        r.failure
    );
}

#[test]
#[ignore = "exploration"]
fn probe() {
    let b = match std::env::var("FVC_CASE").as_deref() {
        Ok("fine") => Benchmark::HertzCylinderFine,
        Ok("rigid") => Benchmark::SphereRigid,
        Ok("block") => Benchmark::SphereBlock,
        Ok("tubes") => Benchmark::ConcentricCylinders,
        _ => Benchmark::HertzCylinderCoarse,
    };
    let cal = calibrate(b);
    eprintln!(
        "{}: eps(1) = {:.4e}, K/E = {:.4}, l = {:.4e}",
        b.name(),
        cal.unit_penalty,
        cal.stiffness_ratio,
        cal.cell_height()
    );
    let ratio: f64 = std::env::var("FVC_RATIO").ok().and_then(|s| s.parse().ok()).unwrap_or(1000.0);
    let rel: Vec<f64> = std::env::var("FVC_RELAX")
        .ok()
        .map(|s| s.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_default();
    let cap: usize = std::env::var("FVC_CAP").ok().and_then(|s| s.parse().ok()).unwrap_or(3000);
    let row = sweep(&cal, ratio, &rel, cap, line);
    eprintln!("f_n = {}", row.penalty_scale);
    for e in &row.explicit {
        eprintln!(
            "  r {:.4}: {} outer ({}), dp vs implicit {:.3e}, gap {:.4} %",
            e.settings.relaxation,
            e.cost.outer_iterations,
            e.converged,
            e.pressure_difference(&row.implicit),
            100.0 * e.relative_gap
        );
    }
    if let Some(best) = row.best_explicit() {
        eprintln!(
            "best explicit r = {}, {} outer, ratio {:.2}, dp {:.3e}",
            best.settings.relaxation,
            best.cost.outer_iterations,
            best.cost.outer_iterations as f64 / row.implicit.cost.outer_iterations as f64,
            best.pressure_difference(&row.implicit)
        );
    }
}
