//! Force-controlled loading (`type = "force"`, thesis Algorithm 1): the
//! secant correction of a uniform patch displacement reaches the target
//! force, and the displacement is the one the force produces.
use validation::run_toml_with_history;

#[test]
fn bar_under_force_control_stretches_by_fl_over_ea() {
    // ν = 0: a uniformly displaced end face is exactly uniaxial stress
    let (l, a, e, f) = (2.0, 0.25 * 0.25, 1000.0, 3.0);
    let case = format!(
        r#"
title = "force-bar"
[time]
end = 1.0
steps = 2
[solver]
tolerance = 1e-9
[[body]]
name = "bar"
mesh = {{ generator = "box", min = [0, 0, 0], max = [{l}, 0.25, 0.25], cells = [8, 2, 2] }}
material = {{ model = "linear-elastic", E = {e}, nu = 0.0 }}
[body.boundary.xmin]
type = "symmetry"
[body.boundary.ymin]
type = "symmetry"
[body.boundary.zmin]
type = "symmetry"
[body.boundary.xmax]
type = "force"
value = {{ table = [[0.0, [0, 0, 0]], [1.0, [{f}, 0, 0]]] }}
"#
    );
    let (out, history) = run_toml_with_history(&case);
    assert!(out.converged, "{:?}", out.failure);
    let fx = history.column("bar/xmax:Fx");
    let b = &out.bodies[0];
    let control = &b.force_controls[0];
    let u = control.displacement.x;
    let exact = f * l / (e * a);
    eprintln!(
        "force control: F = {:.6} / {:.6} (targets {} / {f}), end displacement {u:.6e} (FL/EA = {exact:.6e}); {} outer iterations",
        fx[0],
        fx[1],
        0.5 * f,
        out.summary.outer_iterations
    );
    assert!((fx[0] - 0.5 * f).abs() < 1e-4 * 0.5 * f, "{}", fx[0]);
    assert!((fx[1] - f).abs() < 1e-4 * f, "{}", fx[1]);
    assert!((u - exact).abs() < 2e-4 * exact, "u = {u}, FL/EA = {exact}");
}

#[test]
fn neo_hookean_cube_reaches_the_target_force_under_large_strain() {
    let case = r#"
title = "force-cube"
[analysis]
strain = "large"
[time]
end = 1.0
steps = 4
[solver]
tolerance = 1e-8
[[body]]
name = "cube"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [4, 4, 4] }
material = { model = "neo-hookean", E = 1000.0, nu = 0.3 }
[body.boundary.xmin]
type = "symmetry"
[body.boundary.ymin]
type = "symmetry"
[body.boundary.zmin]
type = "symmetry"
[body.boundary.xmax]
type = "force"
value = { table = [[0.0, [0, 0, 0]], [1.0, [300.0, 0, 0]]] }
"#;
    let (out, history) = run_toml_with_history(case);
    assert!(out.converged, "{:?}", out.failure);
    let fx = history.column("cube/xmax:Fx");
    let fy = history.column("cube/xmax:Fy");
    for (k, (&x, &y)) in fx.iter().zip(&fy).enumerate() {
        let target = 75.0 * (k + 1) as f64;
        assert!(
            ((x - target).powi(2) + 2.0 * y * y).sqrt() < 1e-4 * target,
            "increment {}: F = ({x}, {y}) for {target}",
            k + 1
        );
    }
    // more than 40 % stretch: the cube went through large strain
    let u = out.bodies[0].force_controls[0].displacement.x;
    eprintln!(
        "force control, neo-Hookean cube: F = {:?}, end displacement {u:.4}, {} outer iterations",
        fx, out.summary.outer_iterations
    );
    assert!(u > 0.4 && u < 0.6, "end displacement {u}");
}
