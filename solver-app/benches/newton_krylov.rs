//! Cost of the Newton–Krylov method on boxes of linear-elastic hexahedra:
//! one evaluation of the residual F(x) (boundary faces, least-squares
//! gradient, stress, face fluxes; 64³ cells) and one whole increment
//! (Newton steps, GMRES with the segregated operator, 32³ cells).
//!
//! Divide by the cell count for µs per cell per residual evaluation; the
//! increment bench prints its Newton, Krylov and residual counts.
use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use fv_nonlinear::{Frozen, NonlinearProblem};
use solver_app::contact_coupling::ContactSet;
use solver_app::newton::NewtonKrylovSolver;
use solver_app::nonlinear_solver::NonlinearSolver;

mod common;
use common::{box_bodies as bodies, box_case};

const SOLVER: &str = "nonlinear = \"newton-krylov\"\ntolerance = 1e-6";

fn case(cells: usize) -> solver_app::case::Case {
    box_case(cells, SOLVER)
}

fn residual_evaluation(c: &mut Criterion) {
    let case = case(64);
    let mut bodies = bodies(&case);
    let mut contacts = ContactSet::default();
    let mut solver = NewtonKrylovSolver::new(&bodies, &contacts, &case.solver);
    solver.begin_increment(&mut bodies);
    let n = solver.state_len();
    let x = vec![0.0; n];
    let mut f = vec![0.0; n];
    let mut problem = solver.problem(&mut bodies, &mut contacts);
    let mut group = c.benchmark_group("newton_krylov");
    group.sample_size(10);
    group.bench_function("residual_evaluation_box64", |b| {
        b.iter(|| problem.residual(&x, &mut f, Frozen::Keep))
    });
    group.finish();
}

fn increment(c: &mut Criterion) {
    let case = case(32);
    let mut group = c.benchmark_group("newton_krylov");
    group.sample_size(10);
    let mut reported = false;
    group.bench_function("increment_box32", |b| {
        b.iter_batched(
            || bodies(&case),
            |mut bodies| {
                let mut contacts = ContactSet::default();
                let mut solver = NewtonKrylovSolver::new(&bodies, &contacts, &case.solver);
                let info = solver.solve_increment(&mut bodies, &mut contacts, &mut |_, _| {
                    std::ops::ControlFlow::Continue(())
                });
                if !reported {
                    if let Ok(i) = &info {
                        eprintln!(
                            "32³ box: {} Newton iterations, {} Krylov iterations, {} residual evaluations, converged {}",
                            i.outer_iterations, i.linear_iterations, i.residual_evaluations, i.converged
                        );
                    }
                    reported = true;
                }
                info.map(|i| i.converged)
            },
            BatchSize::PerIteration,
        )
    });
    group.finish();
}

criterion_group!(benches, residual_evaluation, increment);
criterion_main!(benches);
