//! A block under uniform uniaxial stress on a distorted mesh must reproduce
//! the uniform stress to solver tolerance: every operator of the
//! discretisation is exact for linear displacement fields.
use solver_app::case::parse_case;
use solver_app::model::build_bodies;
use solver_app::segregated::SegregatedSolver;
use validation::distort_interior;

#[test]
fn uniaxial_stress_on_distorted_hex_mesh_is_uniform() {
    let text = r#"
title = "patch"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-10
max_outer = 20000
[[body]]
name = "block"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [6, 6, 6] }
material = { model = "linear-elastic", E = 1000.0, nu = 0.3 }
[body.boundary.xmin]
type = "symmetry"
[body.boundary.ymin]
type = "symmetry"
[body.boundary.zmin]
type = "symmetry"
[body.boundary.xmax]
type = "traction"
value = [10.0, 0.0, 0.0]
"#;
    let case = parse_case(text, std::path::Path::new("case.toml")).unwrap();
    let mut mesh = fv_mesh::generators::box_mesh(
        fv_mesh::Vector::zeros(),
        fv_mesh::Vector::new(1.0, 1.0, 1.0),
        [6, 6, 6],
        [1.0; 3],
    )
    .unwrap();
    distort_interior(&mut mesh, [1.0; 3], 1.0 / 6.0, 0.3, 42);
    let mut bodies = build_bodies(&case, vec![mesh]).unwrap();
    let q = fv_mesh::MeshQuality::new(&bodies[0].mesh, &bodies[0].geom);
    assert!(
        q.max_non_orthogonality > 15.0,
        "mesh not distorted enough: {q:?}"
    );
    bodies[0].refresh_conditions(1.0);
    let mut solver = SegregatedSolver::new(&bodies, &case.solver);
    solver
        .assemble_and_factorise(&bodies, &case.solver.linear)
        .unwrap();
    let info = solver
        .solve_increment(&mut bodies, &mut Default::default(), |_, _| {
            std::ops::ControlFlow::Continue(())
        })
        .unwrap();
    assert!(info.converged);
    let mut max_dev = 0.0f64;
    for s in &bodies[0].momentum.sigma {
        let mut expected = nalgebra::Matrix3::zeros();
        expected[(0, 0)] = 10.0;
        max_dev = max_dev.max((s - expected).abs().max());
    }
    eprintln!(
        "uniform stress on distorted mesh (max non-orthogonality {:.1}°): max |σ − σ_exact| = {max_dev:.3e} (σ_xx = 10) after {} outer iterations",
        q.max_non_orthogonality, info.outer_iterations
    );
    assert!(max_dev < 1e-6 * 10.0, "stress deviates by {max_dev}");
    // and the reaction on the symmetry plane balances the applied load
    let f: f64 = bodies[0].momentum.face_force.iter().map(|f| f.x).sum();
    assert!(f.abs() < 1e-8, "net force {f}");
}

/// Simple shear u = (0, 0, c x) held by `tangential-displacement` faces:
/// the x faces hold (u_y, u_z) = (0, 0) and (0, c) and leave u_x free
/// (σ_xx = 0 there), the z faces hold (u_x, u_y) = 0 and leave u_z free
/// (σ_zz = 0), the y faces are symmetry planes (σ_xy = σ_zy = 0). The
/// exact solution is the homogeneous shear σ_xz = μ c, which every
/// operator reproduces on a graded mesh, by either nonlinear method.
#[test]
fn simple_shear_held_by_tangential_displacement_faces_is_uniform() {
    let c = 0.002;
    let text = format!(
        r#"
title = "shear"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-10
nonlinear = "METHOD"
[[body]]
name = "block"
mesh = {{ generator = "box", min = [0, 0, 0], max = [1, 0.5, 0.8], cells = [6, 3, 5], grading = [1.4, 1.0, 0.7] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.xmin]
type = "tangential-displacement"
value = [0.5, 0, 0]
[body.boundary.xmax]
type = "tangential-displacement"
value = [-0.3, 0, {c}]
[body.boundary.zmin]
type = "tangential-displacement"
value = [0, 0, 0]
[body.boundary.zmax]
type = "tangential-displacement"
value = [0, 0, 0.7]
[body.boundary.ymin]
type = "symmetry"
[body.boundary.ymax]
type = "symmetry"
"#
    );
    let mu = 1000.0 / (2.0 * 1.3);
    for method in ["newton-krylov", "segregated"] {
        let out = validation::run_toml(&text.replace("METHOD", method), std::path::Path::new("."));
        assert!(out.converged, "{method}: {:?}", out.failure);
        let b = &out.bodies[0];
        let mut dev = 0.0f64;
        for (x, u) in b.geom.cell_centres.iter().zip(&b.momentum.u) {
            dev = dev.max((u - fv_mesh::Vector::new(0.0, 0.0, c * x.x)).norm());
        }
        let mut stress_dev = 0.0f64;
        for s in &b.momentum.sigma {
            let mut expected = nalgebra::Matrix3::zeros();
            expected[(0, 2)] = mu * c;
            expected[(2, 0)] = mu * c;
            stress_dev = stress_dev.max((s - expected).abs().max());
        }
        eprintln!("{method}: max |u − u_exact| {dev:.2e}, max |σ − σ_exact| {stress_dev:.2e}");
        assert!(dev < 1e-8 * c, "{method}: displacement off by {dev}");
        assert!(
            stress_dev < 1e-6 * mu * c,
            "{method}: stress off by {stress_dev}"
        );
        // the xmax faces carry the shear force μ c A along z, nothing along x
        let xmax = b
            .mesh
            .patches
            .iter()
            .position(|p| p.name == "xmax")
            .unwrap();
        let ni = b.mesh.n_internal_faces();
        let f: fv_mesh::Vector = b.mesh.patches[xmax]
            .faces()
            .map(|f| b.momentum.face_force[f - ni])
            .sum();
        let area = 0.5 * 0.8;
        assert!(
            (f.z.abs() - mu * c * area).abs() < 1e-6 * mu * c * area && f.x.abs() < 1e-8,
            "{method}: force on xmax {f}"
        );
    }
}
