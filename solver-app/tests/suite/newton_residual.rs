//! The residual of Newton's method as a function of the state: the same
//! bits for the same state, affine for a linear problem, and its
//! finite-difference Jacobian products consistent with it.
use fv_nonlinear::{Frozen, NonlinearMethod, NonlinearProblem};
use solver_app::case::parse_case_with;
use solver_app::newton::NewtonKrylovSolver;
use solver_app::nonlinear_solver::prepare_contact_conditions;
use solver_app::run::set_up_with_contacts;

fn seeded(n: usize, seed: u64, scale: f64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0) * scale
        })
        .collect()
}

const CURVED_BEAM: &str = r#"
title = "beam"
[analysis]
strain = "small"
[time]
end = 1.0
steps = 1
[[body]]
name = "upper"
mesh = { generator = "annulus", r_inner = 8.0, r_outer = 10.0, theta0 = 180, theta1 = 360, z0 = 0, z1 = 1, cells = [5, 50, 1] }
material = { model = "linear-elastic", E = 689.56, nu = 0.32 }
[body.boundary.start]
type = "displacement"
value = [0.2, 0, 0]
[body.boundary.end]
type = "displacement"
value = [0.2, 0, 0]
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
"#;

#[test]
fn small_strain_residual_is_affine_and_deterministic() {
    let case = parse_case_with(
        CURVED_BEAM,
        std::path::Path::new("case.toml"),
        Some(NonlinearMethod::NewtonKrylov),
    )
    .unwrap();
    let (mut bodies, mut contacts) = set_up_with_contacts(&case).unwrap();
    prepare_contact_conditions(NonlinearMethod::NewtonKrylov, &contacts, &mut bodies);
    let mut solver = NewtonKrylovSolver::new(&bodies, &contacts, &case.solver);
    for b in bodies.iter_mut() {
        b.refresh_conditions(1.0);
    }
    solver.begin_increment(&mut bodies);
    let n = solver.state_len();
    let mut p = solver.problem(&mut bodies, &mut contacts);
    let x = seeded(n, 1, 0.1);
    let a = seeded(n, 2, 0.05);
    let mut f0 = vec![0.0; n];
    let mut f1 = vec![0.0; n];
    p.residual(&x, &mut f0, Frozen::Renew).unwrap();
    p.residual(&x, &mut f1, Frozen::Renew).unwrap();
    assert_eq!(f0, f1, "two calls at one state differ");
    let plus: Vec<f64> = x.iter().zip(&a).map(|(x, a)| x + a).collect();
    let minus: Vec<f64> = x.iter().zip(&a).map(|(x, a)| x - a).collect();
    let mut fp = vec![0.0; n];
    let mut fm = vec![0.0; n];
    p.residual(&plus, &mut fp, Frozen::Renew).unwrap();
    p.residual(&minus, &mut fm, Frozen::Renew).unwrap();
    let scale = f0.iter().map(|v| v.abs()).fold(0.0, f64::max);
    let worst = fp
        .iter()
        .zip(&fm)
        .zip(&f0)
        .map(|((p, m), o)| (p + m - 2.0 * o).abs())
        .fold(0.0, f64::max);
    let worst_at = fp
        .iter()
        .zip(&fm)
        .zip(&f0)
        .map(|((p, m), o)| (p + m - 2.0 * o).abs())
        .enumerate()
        .fold((0, 0.0), |acc, (i, v)| if v > acc.1 { (i, v) } else { acc });
    eprintln!(
        "scale {scale:.3e} worst {worst:.3e} at {:?} (n {n})",
        worst_at
    );
    assert!(
        worst <= 1e-9 * scale,
        "not affine: {worst:.3e} against {scale:.3e}"
    );
}

#[test]
fn finite_difference_products_match_the_affine_residual() {
    let case = parse_case_with(
        CURVED_BEAM,
        std::path::Path::new("case.toml"),
        Some(NonlinearMethod::NewtonKrylov),
    )
    .unwrap();
    let (mut bodies, mut contacts) = set_up_with_contacts(&case).unwrap();
    prepare_contact_conditions(NonlinearMethod::NewtonKrylov, &contacts, &mut bodies);
    let mut solver = NewtonKrylovSolver::new(&bodies, &contacts, &case.solver);
    for b in bodies.iter_mut() {
        b.refresh_conditions(1.0);
    }
    solver.begin_increment(&mut bodies);
    let n = solver.state_len();
    let mut p = solver.problem(&mut bodies, &mut contacts);
    let x = vec![0.0; n];
    let mut v = seeded(n, 3, 1.0);
    for (i, vi) in v.iter_mut().enumerate() {
        if i % 3 == 2 {
            *vi = 0.0;
        }
    }
    let nv = v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let mut f0 = vec![0.0; n];
    p.residual(&x, &mut f0, Frozen::Renew).unwrap();
    let mut fv = vec![0.0; n];
    p.residual(&v, &mut fv, Frozen::Keep).unwrap();
    let exact: Vec<f64> = fv.iter().zip(&f0).map(|(a, b)| a - b).collect();
    for h in [1e-2, 1e-4, 1e-6, 1e-8] {
        let xp: Vec<f64> = v.iter().map(|v| h * v / nv).collect();
        let mut fp = vec![0.0; n];
        p.residual(&xp, &mut fp, Frozen::Keep).unwrap();
        let fd: Vec<f64> = fp
            .iter()
            .zip(&f0)
            .map(|(a, b)| (a - b) / (h / nv))
            .collect();
        let err = fd
            .iter()
            .zip(&exact)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        let norm = exact.iter().map(|a| a * a).sum::<f64>().sqrt();
        eprintln!("h {h:.0e}: relative error {:.3e}", err / norm);
    }
}

#[test]
fn probe_exact_newton_step() {
    let text = CURVED_BEAM.replace("[time]", "[solver]\nlinear = { method = \"direct\", restart = 300, max_iterations = 1000, tolerance = 1e-10 }\n[time]");
    let case = parse_case_with(
        &text,
        std::path::Path::new("case.toml"),
        Some(NonlinearMethod::NewtonKrylov),
    )
    .unwrap();
    let (mut bodies, mut contacts) = set_up_with_contacts(&case).unwrap();
    prepare_contact_conditions(NonlinearMethod::NewtonKrylov, &contacts, &mut bodies);
    let mut solver = NewtonKrylovSolver::new(&bodies, &contacts, &case.solver);
    for b in bodies.iter_mut() {
        b.refresh_conditions(1.0);
    }
    solver.begin_increment(&mut bodies);
    let n = solver.state_len();
    let params = solver_app::newton::newton_params(&case.solver);
    let mut nk = fv_nonlinear::NewtonKrylov::new(n, params);
    let mut p = solver.problem(&mut bodies, &mut contacts);
    let mut x = vec![0.0; n];
    let r = nk.solve(&mut p, &mut x, &mut |r| {
        eprintln!("{r:?}");
        std::ops::ControlFlow::Continue(())
    });
    eprintln!("{r:?}");
    // the step to the exact solution, checked: F(x) after one step
    let mut f = vec![0.0; n];
    p.residual(&x, &mut f, Frozen::Renew).unwrap();
}

/// The assembled −J against finite differences of the residual, at a
/// random state of the case, relative error of the product (the material
/// tangents are themselves finite differences: about 1e-6).
fn assembled_against_products(text: &str, seed: u64, x_scale: f64) -> f64 {
    assembled_against_shifted_products(text, seed, x_scale, 0.0, 0.0)
}

/// The relative difference between the assembled −J + σ D (the
/// preconditioner of a step shifted by `sigma`) and finite-difference
/// products of −J plus `added` × D.
fn assembled_against_shifted_products(
    text: &str,
    seed: u64,
    x_scale: f64,
    sigma: f64,
    added: f64,
) -> f64 {
    let case = parse_case_with(
        text,
        std::path::Path::new("case.toml"),
        Some(NonlinearMethod::NewtonKrylov),
    )
    .unwrap();
    let (mut bodies, mut contacts) = set_up_with_contacts(&case).unwrap();
    prepare_contact_conditions(NonlinearMethod::NewtonKrylov, &contacts, &mut bodies);
    let mut solver = NewtonKrylovSolver::new(&bodies, &contacts, &case.solver);
    for b in bodies.iter_mut() {
        b.refresh_conditions(case.time.time_at(1));
    }
    solver.begin_increment(&mut bodies);
    let n = solver.state_len();
    let layout = solver.layout().clone();
    let mut jac = Some(solver_app::newton::jacobian::AssembledJacobian::new(
        &bodies,
        &layout,
        solver_app::newton::jacobian::JacobianFactor::Lu,
    ));
    if let Some(j) = jac.as_mut().filter(|_| !contacts.is_empty()) {
        // the contact block the assembly switches to: the derivative of
        // the contact forces (the springs are only near it)
        j.use_contact_derivative();
    }
    let mut p = solver.problem(&mut bodies, &mut contacts);
    p.jacobian = &mut jac;
    // as under linear.preconditioner = "jacobian" (the shift taken in)
    p.exact_contact = true;
    let mut x = seeded(n, seed, x_scale);
    let mut v = seeded(n, seed + 1, 1.0);
    for (c, &off) in layout.unsolved.iter().enumerate() {
        if off {
            x.iter_mut().skip(c).step_by(3).for_each(|a| *a = 0.0);
            v.iter_mut().skip(c).step_by(3).for_each(|a| *a = 0.0);
        }
    }
    let mut f0 = vec![0.0; n];
    p.residual(&x, &mut f0, Frozen::Renew).unwrap();
    p.set_shift(sigma);
    p.prepare_preconditioner(&x, None).unwrap();
    let nv = v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let h = 1e-7 * x_scale.max(1e-3) / nv * (n as f64).sqrt();
    let xp: Vec<f64> = x.iter().zip(&v).map(|(x, v)| x + h * v).collect();
    let mut fp = vec![0.0; n];
    p.residual(&xp, &mut fp, Frozen::Keep).unwrap();
    let mut dv = vec![0.0; n];
    assert!(p.damping(&v, &mut dv));
    let fd: Vec<f64> = fp
        .iter()
        .zip(&f0)
        .zip(&dv)
        .map(|((a, b), d)| -(a - b) / h + added * d)
        .collect();
    drop(p);
    let mut jv = vec![0.0; n];
    jac.as_mut()
        .expect("assembled above")
        .negative_jacobian_times(&v, &mut jv);
    let err = fd
        .iter()
        .zip(&jv)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt();
    let norm = fd.iter().map(|a| a * a).sum::<f64>().sqrt();
    let worst = fd
        .iter()
        .zip(&jv)
        .enumerate()
        .map(|(i, (a, b))| (i, (a - b).abs()))
        .fold((0, 0.0), |m, e| if e.1 > m.1 { e } else { m });
    eprintln!(
        "relative error {:.3e} (worst entry {} {:.3e} of {:.3e}); n {n}",
        err / norm,
        worst.0,
        worst.1,
        fd.iter().map(|a| a.abs()).fold(0.0, f64::max)
    );
    err / norm
}

const BLOCK: &str = r#"
title = "block"
[analysis]
strain = "STRAIN"
[time]
end = 1.0
steps = 1
[[body]]
name = "b"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 0.6, 0.8], cells = [4, 3, 3], grading = GRADING }
material = MATERIAL
[body.boundary.xmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.ymin]
type = "symmetry"
[body.boundary.xmax]
type = "traction"
value = [5, 2, 0]
[body.boundary.zmax]
type = "pressure"
value = 3
[body.boundary.zmin]
type = "normal-displacement"
value = 0.01
[body.boundary.ymax]
type = "tangential-displacement"
value = [0.004, 0.5, -0.003]
"#;

#[test]
fn assembled_jacobian_is_the_derivative_of_the_residual() {
    let cases = [
        (
            "small",
            "[1, 1, 1]",
            "{ model = \"linear-elastic\", E = 1000, nu = 0.3 }",
            1e-3,
        ),
        (
            "large",
            "[1.3, 0.8, 1.1]",
            "{ model = \"neo-hookean\", E = 1000, nu = 0.3 }",
            2e-2,
        ),
        (
            "large",
            "[1.3, 0.8, 1.1]",
            "{ model = \"neo-hookean-plastic\", E = 1000, nu = 0.3, yield = 5, hardening = 50 }",
            2e-2,
        ),
        (
            "small",
            "[1.3, 0.8, 1.1]",
            "{ model = \"linear-elastic\", E = 1000, nu = 0.45 }",
            1e-3,
        ),
    ];
    for (strain, gen, material, scale) in cases {
        let text = BLOCK
            .replace("STRAIN", strain)
            .replace("GRADING", gen)
            .replace("MATERIAL", material);
        // the loads as given: under large strain the follower terms (how a
        // traction's or pressure's area follows the state) are left out
        let e = assembled_against_products(&text, 11, scale);
        let bound = if strain == "small" { 1e-6 } else { 2e-3 };
        assert!(e < bound, "{strain} {gen} {material}: {e:.3e}");
        // without loads: the rest is exact to the tangents' differences
        let unloaded = text
            .replace("value = [5, 2, 0]", "value = [0, 0, 0]")
            .replace("value = 3", "value = 0");
        let e = assembled_against_products(&unloaded, 11, scale);
        assert!(e < 1e-5, "{strain} {gen} {material} unloaded: {e:.3e}");
    }
}

#[test]
fn the_assembled_jacobian_of_a_shifted_step_holds_the_shift() {
    // the pseudo-transient continuation's operator is −J + σ D; the
    // assembled Jacobian of linear.preconditioner = "jacobian" factorises
    // the same
    let text = BLOCK
        .replace("STRAIN", "small")
        .replace("GRADING", "[1, 1, 1]")
        .replace(
            "MATERIAL",
            "{ model = \"linear-elastic\", E = 1000, nu = 0.3 }",
        );
    let e = assembled_against_shifted_products(&text, 11, 1e-3, 0.3, 0.3);
    assert!(e < 1e-6, "shifted: {e:.3e}");
    // the shift is no small part of the operator
    let e = assembled_against_shifted_products(&text, 11, 1e-3, 0.3, 0.0);
    assert!(e > 0.05, "the shift left out: {e:.3e}");
}

const PRESSED_BLOCKS: &str = r#"
title = "pressed"
[analysis]
strain = "small"
[time]
end = 1.0
steps = 1
[[body]]
name = "top"
mesh = { generator = "box", min = [0, 0, -0.02], max = [1, 1, 0.5], cells = [3, 3, 2] }
material = { model = "linear-elastic", E = 1000, nu = 0.3 }
[body.boundary.zmax]
type = "displacement"
value = [0, 0, -0.01]
[[body]]
name = "bottom"
mesh = { generator = "box", min = [-0.2, -0.2, -0.5], max = [1.2, 1.2, 0], cells = [4, 4, 2] }
material = { model = "linear-elastic", E = 1000, nu = 0.3 }
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[[contact]]
master = "bottom/zmax"
slave = "top/zmin"
penalty_scale = 100
"#;

#[test]
fn assembled_contact_block_is_the_derivative_of_the_contact_forces() {
    let e = assembled_against_products(PRESSED_BLOCKS, 11, 1e-4);
    eprintln!("pressed blocks: {e:.3e}");
    assert!(e < 1e-3, "pressed blocks: {e:.3e}");
}

/// [`PRESSED_BLOCKS`] as a plane problem: one cell through the thickness,
/// the z faces empty.
fn pressed_plane_blocks() -> String {
    PRESSED_BLOCKS
        .replace("max = [1, 1, 0.5], cells = [3, 3, 2]", "max = [1, 0.5, 0.1], cells = [3, 2, 1]")
        .replace("min = [0, 0, -0.02]", "min = [0, -0.02, 0]")
        .replace("min = [-0.2, -0.2, -0.5], max = [1.2, 1.2, 0], cells = [4, 4, 2]", "min = [-0.2, -0.5, 0], max = [1.2, 0, 0.1], cells = [4, 2, 1]")
        .replace("body.boundary.zmax]\ntype = \"displacement\"\nvalue = [0, 0, -0.01]", "body.boundary.ymax]\ntype = \"displacement\"\nvalue = [0, -0.01, 0]")
        .replace("body.boundary.zmin]\ntype = \"displacement\"", "body.boundary.ymin]\ntype = \"displacement\"")
        .replace("master = \"bottom/zmax\"\nslave = \"top/zmin\"", "master = \"bottom/ymax\"\nslave = \"top/ymin\"")
        .replace("[[body]]\nname = \"bottom\"", "[body.boundary.zmin]\ntype = \"empty\"\n[body.boundary.zmax]\ntype = \"empty\"\n[[body]]\nname = \"bottom\"")
        .replace("[[contact]]", "[body.boundary.zmin]\ntype = \"empty\"\n[body.boundary.zmax]\ntype = \"empty\"\n[[contact]]")
}

#[test]
fn assembled_contact_block_of_a_plane_problem_is_the_derivative_of_the_contact_forces() {
    let text = pressed_plane_blocks();
    let e = assembled_against_products(&text, 11, 1e-4);
    eprintln!("pressed plane blocks: {e:.3e}");
    assert!(e < 1e-3, "pressed plane blocks: {e:.3e}\n{text}");
}
