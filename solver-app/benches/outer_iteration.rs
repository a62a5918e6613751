//! Cost of one outer iteration of the segregated solver (thesis §3.3) on
//! issue 48's 64³ box of linear-elastic hexahedra (262,144 cells), PCG to
//! the relative tolerance 0.1 as the issue measures it: boundary update,
//! least-squares gradient, stress, residual, three PCG+IC(0) solves,
//! Anderson's mixing and the update.
//!
//! Criterion reports the time per iteration; the bench also prints µs per
//! cell per outer iteration over a timed run of [`TIMED_ITERATIONS`], the
//! PCG iterations per component solve, and the process's peak resident
//! memory per cell, so that a regression in either shows.
use criterion::{criterion_group, criterion_main, Criterion};
use solver_app::segregated::SegregatedSolver;
use std::time::Instant;

mod common;

/// Outer iterations of the timed run whose cost per cell is printed.
const TIMED_ITERATIONS: usize = 10;

fn outer_iteration(c: &mut Criterion) {
    let case = common::box_case(
        64,
        "tolerance = 1e-12\nmax_outer = 1\nlinear = { method = \"pcg-ic\", tolerance = 0.1 }",
    );
    let mut bodies = common::box_bodies(&case);
    let mut solver = SegregatedSolver::new(&bodies, &case.solver);
    if let Err(e) = solver.assemble_and_factorise(&bodies, &case.solver.linear) {
        panic!("{e}");
    }
    let cells = solver.n_unknowns() as f64;
    // a few iterations first so that the linear solves see a typical residual
    let mut contacts = solver_app::contact_coupling::ContactSet::default();
    solver.begin_increment(&mut bodies, &contacts);
    let mut linear = 0;
    for _ in 0..10 {
        if let Ok((_, l)) = solver.outer_iteration(&mut bodies, &mut contacts) {
            linear += l;
        }
    }
    let start = Instant::now();
    let mut timed_linear = 0;
    for _ in 0..TIMED_ITERATIONS {
        if let Ok((_, l)) = solver.outer_iteration(&mut bodies, &mut contacts) {
            timed_linear += l;
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    let peak = common::peak_rss_kb().map_or("peak RSS not reported here".into(), |kb| {
        format!("peak RSS {kb} kB ({:.2} kB per cell)", kb as f64 / cells)
    });
    eprintln!(
        "64³ box: {cells} cells; {:.1} PCG iterations per component solve in outer iterations 1–10, {:.1} in 11–{}; {:.3} µs per cell per outer iteration (threads: {}); {peak}",
        linear as f64 / 30.0,
        timed_linear as f64 / (3 * TIMED_ITERATIONS) as f64,
        10 + TIMED_ITERATIONS,
        1e6 * seconds / (TIMED_ITERATIONS as f64 * cells),
        rayon::current_num_threads(),
    );
    let mut group = c.benchmark_group("segregated");
    group.sample_size(10);
    group.bench_function("outer_iteration_box64", |b| {
        b.iter(|| solver.outer_iteration(&mut bodies, &mut contacts))
    });
    group.finish();
}

criterion_group!(benches, outer_iteration);
criterion_main!(benches);
