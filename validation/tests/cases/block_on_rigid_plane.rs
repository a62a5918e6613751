//! A block pressed onto a rigid plane, as a user writes it first: no
//! `penalty_scale`, no `augmentation`. Its bottom is a flat face on a
//! rigid plane, so the contact gets augmented Lagrangian updates by
//! default (`AugmentationChoice::FlatFaces`) and carries what
//! elasticity says, not that less the penalty's penetration: uniaxial
//! stress σ = E ε (the top `normal-displacement`, free to slide;
//! frictionless plane), and Coulomb's μ N once the top is pulled sideways.
use validation::{run_toml, run_toml_with_history};

/// 1 × 1 × 0.5 block of 8 × 8 × 4 cells (E = 1000, ν = 0.3) over a rigid
/// plane at z = 0; `top` is the `[body.boundary.zmax]` table, `contact`
/// the extra keys of the pair.
fn case(top: &str, contact: &str, steps: usize) -> String {
    format!(
        r#"
title = "block-on-rigid-plane"
[time]
end = 1.0
steps = {steps}
[[body]]
name = "block"
mesh = {{ generator = "box", min = [0, 0, 0], max = [1, 1, 0.5], cells = [8, 8, 4] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.zmax]
{top}
[[body]]
name = "floor"
rigid = true
mesh = {{ generator = "box", min = [-1, -1, -0.2], max = [2, 2, 0], cells = [3, 3, 1] }}
material = {{ model = "linear-elastic", E = 1000.0, nu = 0.3 }}
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[[contact]]
master = "floor/zmax"
slave = "block/zmin"
{contact}
"#
    )
}

/// Top pushed down 0.01 (ε = 0.02), free to slide, the sides x = 0 and
/// y = 0 symmetry planes (a frictionless floor holds nothing sideways):
/// uniaxial stress, so the plane carries E ε A = 20 with a uniform
/// pressure of 20. Measured:
/// 19.997 (−0.015 %), the pressure uniform to 9e-6; with
/// `augmentation = false` 16.87 (−15.7 %: the penalty's penetration,
/// 1.6e-3, is 16 % of the 0.01).
#[test]
fn pressed_block_carries_e_eps_a_with_the_defaults() {
    let top = "type = \"normal-displacement\"\nvalue = { table = [[0.0, -0.005], [1.0, -0.01]] }\n\
               [body.boundary.xmin]\ntype = \"symmetry\"\n[body.boundary.ymin]\ntype = \"symmetry\"";
    let exact = 1000.0 * 0.02 * 1.0;
    let out = run_toml(&case(top, "", 2), std::path::Path::new("."));
    assert!(out.converged, "{:?}", out.failure);
    let c = &out.contacts.interfaces[0];
    assert!(c.augmentation_choice.value().is_some());
    let force = c.stats.normal_force;
    let p = &c.tractions.slave.pressure;
    let mean = p.iter().sum::<f64>() / p.len() as f64;
    let spread = p.iter().fold(0.0f64, |a, x| a.max((x - mean).abs())) / mean;
    let plain = run_toml(
        &case(top, "augmentation = false", 2),
        std::path::Path::new("."),
    );
    eprintln!(
        "pressed block: normal force {force:.5} ({:+.2} % of E ε A), pressure spread {spread:.1e}; \
         plain penalty {:.5}",
        100.0 * (force / exact - 1.0),
        plain.contacts.interfaces[0].stats.normal_force
    );
    assert!((force / exact - 1.0).abs() < 0.01, "{force}");
    assert!(spread < 1e-3, "{p:?}");
    assert!((mean / 20.0 - 1.0).abs() < 0.01, "{mean}");
}

/// Pressed by 0.01 with the top held, then the top pulled 0.05 sideways
/// over μ = 0.3: the block slides, and the plane's tangential force is
/// μ times its normal force. Measured: 6.46951 / 21.5668 = 0.29998.
#[test]
fn sliding_block_carries_mu_n_with_the_defaults() {
    let top = "type = \"displacement\"\nvalue = { table = [[0.0, [0, 0, -0.005]], [0.3, [0, 0, -0.01]], [1.0, [0.05, 0, -0.01]]] }";
    let (out, history) = run_toml_with_history(&case(top, "friction = 0.3", 10));
    assert!(out.converged, "{:?}", out.failure);
    let normal = *history.column("block/zmin:normal_force").last().unwrap();
    let pulled = *history.column("block/zmax:Fx").last().unwrap();
    let ratio = pulled / normal;
    eprintln!("sliding block: Fx {pulled:.5}, N {normal:.5}, ratio {ratio:.5}");
    assert!((ratio - 0.3).abs() < 0.3 * 0.005, "{ratio}");
}

/// A rigid square punch (1.4 × 1.4, wider than the block's 1.2 × 1.2
/// top) pressed 0.01 into the block and turned 0.2 rad about its axis over
/// μ = 0.3: every face slides round the axis, so the moment that drives
/// the punch, reported on its `rigid-motion` patch, is μ Σ p_f r_f |Γ_f|
/// over the block's contact faces. Measured: 2.02280 against 2.02308.
#[test]
fn twisted_rigid_punch_reports_its_moment() {
    let case = r#"
title = "twisted-punch"
[time]
intervals = [[1.0, 2], [2.0, 6]]
[[body]]
name = "punch"
rigid = true
mesh = { generator = "box", min = [-0.7, -0.7, 1.0], max = [0.7, 0.7, 1.2], cells = [4, 4, 1] }
[body.boundary.zmax]
type = "rigid-motion"
translation = { table = [[0.0, [0, 0, 0]], [1.0, [0, 0, -0.01]], [2.0, [0, 0, -0.01]]] }
rotation = { axis = [0, 0, 1], origin = [0, 0, 1.2], angle = { table = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.2]] } }
[[body]]
name = "block"
mesh = { generator = "box", min = [-0.6, -0.6, 0], max = [0.6, 0.6, 1.0], cells = [7, 7, 5] }
material = { model = "linear-elastic", E = 1000.0, nu = 0.3 }
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[[contact]]
master = "punch/zmin"
slave = "block/zmax"
friction = 0.3
"#;
    let (out, history) = run_toml_with_history(case);
    assert!(out.converged, "{:?}", out.failure);
    let moment = *history.column("punch/zmax:Mz").last().unwrap();
    let c = &out.contacts.interfaces[0];
    let s = &c.slave.surface;
    let expected: f64 = (0..s.n_faces())
        .map(|f| {
            let x = s.face_centres[f];
            0.3 * c.tractions.slave.pressure[f] * x.x.hypot(x.y) * s.face_mag[f]
        })
        .sum();
    eprintln!("twisted punch: Mz {moment:.5} against μ Σ p r |Γ| {expected:.5}");
    assert!(
        (moment / expected - 1.0).abs() < 2e-3,
        "{moment} against {expected}"
    );
}
