//! Cost of one outer iteration of the segregated solver (thesis §3.3) on a
//! 64³ box of linear-elastic hexahedra: boundary update, least-squares
//! gradient, stress, residual, three PCG+IC(0) solves and the update.
//!
//! Reported as time per iteration; divide by 262,144 cells for µs per cell.
use criterion::{criterion_group, criterion_main, Criterion};
use solver_app::segregated::SegregatedSolver;

mod common;

fn outer_iteration(c: &mut Criterion) {
    let case = common::box_case(64, "tolerance = 1e-12\nmax_outer = 1");
    let mut bodies = common::box_bodies(&case);
    let mut solver = SegregatedSolver::new(&bodies, &case.solver);
    if let Err(e) = solver.assemble_and_factorise(&bodies, &case.solver.linear) {
        panic!("{e}");
    }
    // a few iterations first so that the linear solves see a typical residual
    let mut contacts = solver_app::contact_coupling::ContactSet::default();
    solver.begin_increment(&mut bodies, &contacts);
    let mut linear = 0;
    for _ in 0..10 {
        if let Ok((_, l)) = solver.outer_iteration(&mut bodies, &mut contacts) {
            linear += l;
        }
    }
    eprintln!(
        "64³ box: {} cells, {:.1} PCG iterations per component solve (first 10 outer iterations)",
        solver.n_unknowns(),
        linear as f64 / 30.0
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
