//! Contact patch test: two stacked blocks with non-matching meshes under a
//! uniform compression carry a uniform contact pressure (thesis ch. 6) whose
//! value follows from the blocks' compliances in series (the thesis adds
//! the penalty's; the flat faces are augmented by default here).
//!
//! Run with the settings a user tries first (`penalty_scale = 1`, default
//! relaxation), with explicit and with implicit coupling.
use validation::run_toml;

fn case(master: &str, slave: &str) -> String {
    case_with(master, slave, "explicit")
}

fn case_with(master: &str, slave: &str, coupling: &str) -> String {
    format!(
        r#"
title = "contact-patch"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-10
max_outer = 20000
[[body]]
name = "lower"
mesh = {{ generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [6, 6, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[body.boundary.xmin]
type = "symmetry"
[body.boundary.xmax]
type = "symmetry"
[[body]]
name = "upper"
mesh = {{ generator = "box", min = [0, 1, 0], max = [1, 2, 0.1], cells = [5, 5, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.ymax]
type = "displacement"
value = [0, -0.01, 0]
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[body.boundary.xmin]
type = "symmetry"
[body.boundary.xmax]
type = "symmetry"
[[contact]]
master = "{master}"
slave = "{slave}"
coupling = "{coupling}"
"#
    )
}

#[test]
fn uniform_pressure_with_non_matching_meshes_either_side_master() {
    let mut forces = Vec::new();
    for (master, slave, coupling) in [
        ("lower/ymax", "upper/ymin", "explicit"),
        ("upper/ymin", "lower/ymax", "explicit"),
        ("lower/ymax", "upper/ymin", "implicit"),
        ("upper/ymin", "lower/ymax", "implicit"),
    ] {
        let out = run_toml(
            &case_with(master, slave, coupling),
            std::path::Path::new("."),
        );
        assert!(out.converged, "{:?}", out.failure);
        let c = &out.contacts.interfaces[0];
        // uniform pressure on both sides
        for side in [&c.tractions.master, &c.tractions.slave] {
            let p = &side.pressure;
            let mean = p.iter().sum::<f64>() / p.len() as f64;
            let dev = p.iter().fold(0.0f64, |a, x| a.max((x - mean).abs())) / mean;
            assert!(dev < 1e-6, "pressure not uniform: {p:?}");
        }
        // uniaxial strain of the two blocks in series: u = p (2/K), with
        // K = λ + 2μ; the flat faces get the augmented Lagrangian by
        // default (AugmentationChoice::FlatFaces), so no penalty compliance
        // p/ε_n is added (it was −8.4 % of p). Measured −5e-5 with every
        // coupling; the updates stop at a penalty share of 1e-3.
        let (e, nu): (f64, f64) = (1000.0, 0.3);
        let k = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let p_exact = 0.01 / (2.0 / k);
        let p = c.tractions.slave.pressure[0];
        eprintln!(
            "{master} / {slave} {coupling}: p = {p:.8}, exact {p_exact:.8}, {} outer iterations",
            out.summary.outer_iterations
        );
        assert!(
            (p - p_exact).abs() < 1e-3 * p_exact,
            "{p} against {p_exact}"
        );
        // action = reaction
        let lower = &out.bodies[0];
        let fl = lower
            .momentum
            .patch_force(&lower.mesh, lower.mesh.patch_index("ymin").unwrap());
        forces.push(c.stats.normal_force);
        assert!((fl.y - p * 0.1).abs() < 1e-6 * p * 0.1, "{fl:?}");
    }
    for f in &forces[1..] {
        assert!((forces[0] - f).abs() < 1e-8 * forces[0]);
    }
}

#[test]
fn every_detection_mode_gives_the_same_contact_forces() {
    // a tilted upper block makes the pressure non-uniform, so the pairs matter
    let mut results = Vec::new();
    for mode in ["brute-force", "bvh", "advancing-front"] {
        let text = case("lower/ymax", "upper/ymin")
            .replace("value = [0, -0.01, 0]", "value = [0.002, -0.01, 0]")
            .replace(
                "coupling = \"explicit\"",
                &format!("coupling = \"explicit\"\ndetection = \"{mode}\""),
            );
        let out = run_toml(&text, std::path::Path::new("."));
        assert!(out.converged, "{mode}: {:?}", out.failure);
        let c = &out.contacts.interfaces[0];
        results.push((
            mode,
            c.stats.normal_force,
            c.tractions.slave.pressure.clone(),
        ));
    }
    for (mode, f, p) in &results[1..] {
        let (_, f0, p0) = &results[0];
        eprintln!("{mode}: normal force {f:.12e} (brute force {f0:.12e})");
        assert!((f - f0).abs() <= 1e-9 * f0.abs(), "{mode}");
        for (a, b) in p.iter().zip(p0) {
            assert!(
                (a - b).abs() <= 1e-9 * f0.abs().max(1e-300) * 10.0,
                "{mode}"
            );
        }
    }
}

/// One rigid floor under two blocks pressed by different amounts: a rigid
/// body's patch may be master of several pairs. Each block carries the
/// force it carries alone (the pairs do not see each other), and the
/// results (one floor dataset with both pairs' pressures) are written.
#[test]
fn a_rigid_floor_under_two_blocks_carries_each_as_alone() {
    let block = |name: &str, x0: f64, dy: f64| {
        format!(
            r#"
[[body]]
name = "{name}"
mesh = {{ generator = "box", min = [{x0}, 0, 0], max = [{x1}, 1, 0.1], cells = [4, 5, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.ymax]
type = "displacement"
value = [0, {dy}, 0]
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[body.boundary.xmin]
type = "symmetry"
[body.boundary.xmax]
type = "symmetry"
[[contact]]
master = "floor/ymax"
slave = "{name}/ymin"
coupling = "implicit"
"#,
            x1 = x0 + 1.0
        )
    };
    let floor = r#"
title = "shared-floor"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-10
[[body]]
name = "floor"
rigid = true
mesh = { generator = "box", min = [0, -0.2, 0], max = [3, 0, 0.1], cells = [1, 1, 1] }
material = { model = "linear-elastic", E = 1000.0, nu = 0.3 }
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
"#;
    let (a, b) = (block("a", 0.0, -0.01), block("b", 2.0, -0.004));
    let force = |text: &str, slave: &str| {
        let (out, history) = validation::run_toml_with_history(text);
        assert!(out.converged, "{:?}", out.failure);
        history.column(&format!("{slave}:normal_force"))[0]
    };
    let both = format!("{floor}{a}{b}");
    let (fa, fb) = (force(&both, "a/ymin"), force(&both, "b/ymin"));
    let (fa1, fb1) = (
        force(&format!("{floor}{a}"), "a/ymin"),
        force(&format!("{floor}{b}"), "b/ymin"),
    );
    eprintln!("shared floor: a {fa:.10e} (alone {fa1:.10e}), b {fb:.10e} (alone {fb1:.10e})");
    assert!(fa > 0.0 && fb > 0.0);
    assert!((fa - fa1).abs() <= 1e-9 * fa1, "{fa} against {fa1}");
    assert!((fb - fb1).abs() <= 1e-9 * fb1, "{fb} against {fb1}");
    // linear: the forces scale with the imposed compression
    assert!((fa / fb - 2.5).abs() < 1e-6, "{}", fa / fb);
    // and each is its block's uniaxial strain (symmetry sides, one cell in
    // z): M ε A with M = E(1 − ν)/((1 + ν)(1 − 2ν)), the face on the rigid
    // floor augmented by default (AugmentationChoice::FlatFaces).
    // Measured: −0.013 % both; with the plain penalty −16.7 % both.
    let m = 1000.0 * 0.7 / (1.3 * 0.4);
    for (f, squeeze) in [(fa, 0.01), (fb, 0.004)] {
        let exact = m * squeeze * 0.1;
        assert!((f / exact - 1.0).abs() < 1e-3, "{f} against {exact}");
    }
}

/// Two rigid half-width punches pressed together on one deformable patch
/// (the block's top in two contact pairs): each carries half of what one
/// full-width punch carries, with either coupling, and the summed
/// condition leaves the pressure uniform (uniaxial strain, symmetry sides).
#[test]
fn two_rigid_punches_on_one_deformable_patch_carry_what_one_carries() {
    let punch = |name: &str, x0: f64, x1: f64, coupling: &str| {
        format!(
            r#"
[[body]]
name = "{name}"
rigid = true
mesh = {{ generator = "box", min = [{x0}, 1, 0], max = [{x1}, 1.2, 0.1], cells = [1, 1, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.ymax]
type = "displacement"
value = [0, -0.01, 0]
[[contact]]
master = "{name}/ymin"
slave = "block/ymax"
coupling = "{coupling}"
"#
        )
    };
    let block = r#"
title = "two-punches"
[time]
end = 1.0
steps = 1
[solver]
tolerance = 1e-10
max_outer = 20000
[[body]]
name = "block"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [6, 5, 1] }
material = { model = "linear-elastic", E = 1000.0, nu = 0.3 }
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmin]
type = "empty"
[body.boundary.zmax]
type = "empty"
[body.boundary.xmin]
type = "symmetry"
[body.boundary.xmax]
type = "symmetry"
"#;
    for coupling in ["explicit", "implicit"] {
        let run = |text: String| {
            let out = run_toml(&text, std::path::Path::new("."));
            assert!(out.converged, "{coupling}: {:?}", out.failure);
            out
        };
        let one = run(format!("{block}{}", punch("whole", 0.0, 1.0, coupling)));
        let full = one.contacts.interfaces[0].stats.normal_force;
        let two = run(format!(
            "{block}{}{}",
            punch("left", 0.0, 0.5, coupling),
            punch("right", 0.5, 1.0, coupling)
        ));
        let (fl, fr) = (
            two.contacts.interfaces[0].stats.normal_force,
            two.contacts.interfaces[1].stats.normal_force,
        );
        eprintln!(
            "{coupling}: one punch {full:.10e} N; two half punches {fl:.10e} + {fr:.10e} N ({} and {} outer iterations)",
            one.summary.outer_iterations, two.summary.outer_iterations
        );
        assert!(full > 0.0);
        assert!(
            (fl - 0.5 * full).abs() <= 1e-6 * full,
            "{fl} against {full}"
        );
        assert!(
            (fr - 0.5 * full).abs() <= 1e-6 * full,
            "{fr} against {full}"
        );
        // the block's top carries the sum: its base reaction equals it
        let b = &two.bodies[0];
        let base = b
            .momentum
            .patch_force(&b.mesh, b.mesh.patch_index("ymin").unwrap());
        assert!((base.y - full).abs() <= 1e-6 * full, "{base:?}");
        // each rigid punch is held by its driven patch: the reaction there
        // is its contact force, pushing down (the block's base pushes up)
        for (bi, f) in [(1, fl), (2, fr)] {
            let p = two.bodies[bi].mesh.patch_index("ymax").unwrap();
            let r = solver_app::results::patch_reaction(&two.bodies, bi, p, &two.contacts);
            assert!(
                (r.y + f).abs() <= 1e-9 * f && r.x == 0.0 && r.z == 0.0,
                "{r:?}"
            );
        }
        // history.csv: the shared slave patch's pairs are told apart by
        // their master (`<slave>@<master>`), one column each
        let (_, history) = validation::run_toml_with_history(&format!(
            "{block}{}{}",
            punch("left", 0.0, 0.5, coupling),
            punch("right", 0.5, 1.0, coupling)
        ));
        for (master, f) in [("left", fl), ("right", fr)] {
            let column = history.column(&format!("block/ymax@{master}/ymin:normal_force"));
            assert!((column[0] - f).abs() <= 1e-9 * f, "{master}: {column:?}");
        }
    }
}
