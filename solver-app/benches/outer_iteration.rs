//! Cost of one outer iteration of the segregated solver (thesis §3.3) on a
//! 64³ box of linear-elastic hexahedra: boundary update, least-squares
//! gradient, stress, residual, three PCG+IC(0) solves and the update.
//!
//! Reported as time per iteration; divide by 262,144 cells for µs per cell.
use criterion::{criterion_group, criterion_main, Criterion};
use solver_app::case::parse_case;
use solver_app::mesh_loading::load_mesh;
use solver_app::model::build_bodies;
use solver_app::segregated::SegregatedSolver;

const CASE: &str = r#"
title = "box64"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-12
max_outer = 1
[[body]]
name = "box"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [64, 64, 64] }
material = { model = "linear-elastic", E = 200e9, nu = 0.3 }
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmax]
type = "displacement"
value = [0.001, 0, -0.01]
"#;

fn outer_iteration(c: &mut Criterion) {
    let case = match parse_case(CASE, std::path::Path::new("box64.toml")) {
        Ok(c) => c,
        Err(e) => panic!("{e}"),
    };
    let mesh = match load_mesh(&case.bodies[0].mesh, 0, &case.source) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    };
    let mut bodies = match build_bodies(&case, vec![mesh]) {
        Ok(b) => b,
        Err(e) => panic!("{e}"),
    };
    bodies[0].refresh_conditions(1.0);
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
