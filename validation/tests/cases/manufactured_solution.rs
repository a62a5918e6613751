//! Method of manufactured solutions: second-order convergence of the
//! displacement on distorted hexahedral and on tetrahedral meshes.
//!
//! Exact field on the unit cube (smooth, fully 3-D, all components coupled):
//! u = c (sin πx sin πy sin πz, cos πx sin πy, sin πx sin(πz/2) cos πy);
//! the body force is b = −∇·σ(u), evaluated by nested central differences
//! of the analytic field (truncation ~1e-7, far below the discretisation
//! error measured here); displacement conditions u_exact on all faces, or
//! on the three faces through the origin with the exact traction σ·n on
//! the other three.
use fv_discretise::PatchCondition;
use fv_mesh::{PolyMesh, Tensor, Vector};
use solver_app::case::parse_case;
use solver_app::model::build_bodies;
use solver_app::segregated::SegregatedSolver;
use std::f64::consts::PI;

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const C: f64 = 0.01;

fn exact(x: &Vector) -> Vector {
    Vector::new(
        (PI * x.x).sin() * (PI * x.y).sin() * (PI * x.z).sin(),
        (PI * x.x).cos() * (PI * x.y).sin(),
        (PI * x.x).sin() * (0.5 * PI * x.z).sin() * (PI * x.y).cos(),
    ) * C
}

fn grad_exact(x: &Vector) -> Tensor {
    let h = 1e-5;
    let mut g = Tensor::zeros();
    for i in 0..3 {
        let mut e = Vector::zeros();
        e[i] = h;
        let d = (exact(&(x + e)) - exact(&(x - e))) / (2.0 * h);
        for j in 0..3 {
            g[(i, j)] = d[j];
        }
    }
    g
}

fn stress_exact(x: &Vector) -> Tensor {
    let mu = E / (2.0 * (1.0 + NU));
    let lambda = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let g = grad_exact(x);
    (g + g.transpose()) * mu + Tensor::identity() * (lambda * g.trace())
}

/// b = −∇·σ, (∇·σ)_j = Σ_i ∂σ_ij/∂x_i.
fn body_force(x: &Vector) -> Vector {
    let h = 1e-3;
    let mut div = Vector::zeros();
    for i in 0..3 {
        let mut e = Vector::zeros();
        e[i] = h;
        let ds = (stress_exact(&(x + e)) - stress_exact(&(x - e))) / (2.0 * h);
        for j in 0..3 {
            div[j] += ds[(i, j)];
        }
    }
    -div
}

/// Solves the manufactured problem on `mesh`; returns the relative L2 error
/// of the cell displacement and the outer iterations used. `traction`: the
/// faces xmax, ymax and zmax carry the exact traction instead of the
/// exact displacement.
fn solve(mesh: PolyMesh, traction: bool) -> (f64, usize) {
    let text = r#"
title = "mms"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-9
max_outer = 20000
[[body]]
name = "cube"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 1, 1] }
material = { model = "linear-elastic", E = 1000.0, nu = 0.3 }
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.xmax]
type = "displacement"
value = [0, 0, 0]
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.ymax]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmax]
type = "displacement"
value = [0, 0, 0]
"#;
    let mut text = text.to_string();
    if traction {
        for side in ["xmax", "ymax", "zmax"] {
            text = text.replace(
                &format!("[body.boundary.{side}]\ntype = \"displacement\""),
                &format!("[body.boundary.{side}]\ntype = \"traction\""),
            );
        }
    }
    let case = parse_case(&text, std::path::Path::new("mms.toml")).unwrap();
    let mut bodies = build_bodies(&case, vec![mesh]).unwrap();
    let b = &mut bodies[0];
    let mut tractions = 0;
    for (p, cond) in b.mesh.patches.iter().zip(b.momentum.conditions.iter_mut()) {
        match cond {
            PatchCondition::Displacement(v) => {
                for (i, f) in p.faces().enumerate() {
                    v[i] = exact(&b.geom.face_centres[f]);
                }
            }
            PatchCondition::Traction(t) => {
                for (i, f) in p.faces().enumerate() {
                    let n = b.geom.face_normal(f);
                    t[i] = stress_exact(&b.geom.face_centres[f]) * n;
                    tractions += 1;
                }
            }
            _ => {}
        }
    }
    assert_eq!(tractions > 0, traction);
    b.momentum.body_force = b.geom.cell_centres.iter().map(body_force).collect();
    let mut solver = SegregatedSolver::new(&bodies, &case.solver);
    solver
        .assemble_and_factorise(&bodies, &case.solver.linear)
        .unwrap();
    let info = solver
        .solve_increment(&mut bodies, &mut Default::default(), |_, _| {
            std::ops::ControlFlow::Continue(())
        })
        .unwrap();
    assert!(info.converged, "not converged: {info:?}");
    let b = &bodies[0];
    let (mut num, mut den) = (0.0, 0.0);
    for ((c, u), v) in b
        .geom
        .cell_centres
        .iter()
        .zip(&b.momentum.u)
        .zip(&b.geom.cell_volumes)
    {
        let ue = exact(c);
        num += (u - ue).norm_squared() * v;
        den += ue.norm_squared() * v;
    }
    ((num / den).sqrt(), info.outer_iterations)
}

fn check_order(name: &str, errors: &[(usize, f64, usize)]) {
    for w in errors.windows(2) {
        let ratio = w[0].1 / w[1].1;
        eprintln!(
            "{name}: n = {:>2} → {:>2}: error {:.4e} → {:.4e}, ratio {ratio:.2} (order {:.2}); outer iterations {} → {}",
            w[0].0,
            w[1].0,
            w[0].1,
            w[1].1,
            ratio.log2(),
            w[0].2,
            w[1].2
        );
        assert!(
            ratio >= 3.5,
            "{name}: error ratio {ratio:.2} < 3.5 between n = {} and {}",
            w[0].0,
            w[1].0
        );
    }
}

#[test]
fn second_order_on_distorted_hexahedra() {
    let mut errors = Vec::new();
    for n in [4usize, 8, 16, 32] {
        let mut mesh = fv_mesh::generators::box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 1.0, 1.0),
            [n, n, n],
            [1.0; 3],
        )
        .unwrap();
        // the same smooth distortion at every level (so the mesh sequence
        // is a true refinement), non-orthogonal up to ~20°
        for p in mesh.points.iter_mut() {
            let s = (PI * p.x).sin() * (PI * p.y).sin() * (PI * p.z).sin();
            *p += Vector::new(0.06 * s, -0.05 * s, 0.04 * s);
        }
        let q = fv_mesh::MeshQuality::new(&mesh, &fv_mesh::MeshGeometry::new(&mesh).unwrap());
        eprintln!(
            "n = {n}: max non-orthogonality {:.1}°",
            q.max_non_orthogonality
        );
        let (err, it) = solve(mesh, false);
        errors.push((n, err, it));
    }
    check_order("distorted hexahedra", &errors);
}

/// Errors on the Kuhn-tetrahedra cubes n = 3, 6, 12, 24 (`traction`: see
/// [`solve`]).
fn tetrahedra_errors(traction: bool) -> Vec<(usize, f64, usize)> {
    [3usize, 6, 12, 24]
        .into_iter()
        .map(|n| {
            let mesh = fv_mesh::generators::box_tet_mesh(
                Vector::zeros(),
                Vector::new(1.0, 1.0, 1.0),
                [n, n, n],
            )
            .unwrap();
            let (err, it) = solve(mesh, traction);
            (n, err, it)
        })
        .collect()
}

#[test]
fn second_order_on_tetrahedra() {
    check_order("tetrahedra", &tetrahedra_errors(false));
}

/// Half the faces carry the exact traction (eq. 3.23 sets their values).
/// Measured, n = 3 / 6 / 12 / 24: errors 1.587e-1, 3.965e-2, 1.010e-2,
/// 2.568e-3 (order 1.97–2.00) in 50–52 outer iterations.
#[test]
fn second_order_on_tetrahedra_with_traction_faces() {
    check_order("tetrahedra, traction faces", &tetrahedra_errors(true));
}
