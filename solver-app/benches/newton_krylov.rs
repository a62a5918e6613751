//! Cost of the Newton–Krylov method on boxes of linear-elastic hexahedra:
//! one evaluation of the residual F(x) (boundary faces, least-squares
//! gradient, stress, face fluxes; 64³ cells) and one whole increment
//! (Newton steps, GMRES with the segregated operator, 32³ cells).
//!
//! Divide by the cell count for µs per cell per residual evaluation; the
//! increment bench prints its Newton, Krylov and residual counts.
use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use fv_nonlinear::{Frozen, NonlinearProblem};
use solver_app::case::{parse_case, Case};
use solver_app::contact_coupling::ContactSet;
use solver_app::mesh_loading::load_mesh;
use solver_app::model::{build_bodies, Body};
use solver_app::newton::NewtonKrylovSolver;
use solver_app::nonlinear_solver::NonlinearSolver;

fn case(cells: usize) -> Case {
    let text = format!(
        r#"
title = "box"
[time]
end = 1.0
steps = 1
[solver]
nonlinear = "newton-krylov"
tolerance = 1e-6
[[body]]
name = "box"
mesh = {{ generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [{cells}, {cells}, {cells}] }}
material = {{ model = "linear-elastic", E = 200e9, nu = 0.3 }}
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmax]
type = "displacement"
value = [0.001, 0, -0.01]
"#
    );
    match parse_case(&text, std::path::Path::new("box.toml")) {
        Ok(c) => c,
        Err(e) => panic!("{e}"),
    }
}

fn bodies(case: &Case) -> Vec<Body> {
    let mesh = match load_mesh(&case.bodies[0].mesh, 0, &case.source) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    };
    let mut bodies = match build_bodies(case, vec![mesh]) {
        Ok(b) => b,
        Err(e) => panic!("{e}"),
    };
    bodies[0].refresh_conditions(1.0);
    bodies
}

fn residual_evaluation(c: &mut Criterion) {
    let case = case(64);
    let mut bodies = bodies(&case);
    let mut contacts = ContactSet::default();
    let mut solver = NewtonKrylovSolver::new(&bodies, &case.solver);
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
                let mut solver = NewtonKrylovSolver::new(&bodies, &case.solver);
                let info = solver.solve_increment(&mut bodies, &mut contacts, &mut |_, _| {});
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
