//! Thick hollow sphere of an elastic–perfectly plastic (J2) material under
//! internal pressure, on a one-cell wedge about its axis, against the
//! closed-form small-strain solution (`validation::analytical::
//! PlasticSphere`, Hill 1950): the stresses of the plastic and the elastic
//! zone, the radius of the elastic–plastic boundary and the outer
//! surface's displacement. Steel-like, so the strains stay near 0.4 % and
//! the small-strain solution applies to the (updated Lagrangian) model once
//! it is written on the current radii.
use validation::analytical::PlasticSphere;
use validation::run_toml;

const YOUNG: f64 = 210e3;
const POISSON: f64 = 0.3;
const YIELD: f64 = 240.0;
/// The pressure that yields the wall to c = 1.5 (a = 1, b = 2).
const PRESSURE: f64 = 287.1;

#[test]
fn elastoplastic_hollow_sphere_under_internal_pressure_against_hill() {
    let case = format!(
        r#"
title = "elastoplastic-sphere"
[analysis]
strain = "large"
[time]
end = 1.0
steps = 10
[solver]
tolerance = 1e-8
[[body]]
name = "shell"
mesh = {{ generator = "spherical-shell", r_inner = 1, r_outer = 2, part = "wedge", cells = [40, 32] }}
material = {{ model = "neo-hookean-plastic", E = {YOUNG}, nu = {POISSON}, yield = {YIELD}, hardening = 0 }}
[body.boundary.inner]
type = "pressure"
value = {{ table = [[0.0, 0.0], [1.0, {PRESSURE}]] }}
[body.boundary.zmax]
type = "symmetry"
[body.boundary.front]
type = "wedge"
[body.boundary.back]
type = "wedge"
"#
    );
    let out = run_toml(&case, std::path::Path::new("."));
    assert!(out.converged, "{:?}", out.failure);
    let body = &out.bodies[0];
    let ni = body.mesh.n_internal_faces();
    // mean current radius and radial displacement of a patch's faces
    let radius_and_motion = |name: &str| {
        let p = body
            .mesh
            .patch_index(name)
            .expect("a spherical-shell patch");
        let faces = body.mesh.patches[p].faces();
        let n = faces.len() as f64;
        let (r, u) = faces.fold((0.0, 0.0), |(r, u), f| {
            let x = body.geom.face_centres[f];
            (
                r + x.norm(),
                u + body.momentum.u_b[f - ni].dot(&(x / x.norm())),
            )
        });
        (r / n, u / n)
    };
    let (a_now, _) = radius_and_motion("inner");
    let (b_now, u_outer) = radius_and_motion("outer");
    // the small-strain solution on the current radii: the Cauchy stress
    // balances in the deformed wall, whose inner radius has grown by 0.25 %
    // (so has c: on the undeformed radii u(b) ∝ c³ came out 0.75 % high)
    let exact =
        PlasticSphere::new(a_now, b_now, YIELD, PRESSURE).expect("below the limit pressure");
    let eps_p = body
        .momentum
        .law
        .plastic_strain()
        .expect("a plastic material");
    // stresses against the closed form; the elastic–plastic boundary as the
    // largest radius of a cell that yielded and the smallest one that did not
    let (mut err_rr, mut err_tt, mut err_wall, mut err_inside) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut plastic_to, mut elastic_from) = (0.0f64, f64::INFINITY);
    for ((x, s), &ep) in body
        .geom
        .cell_centres
        .iter()
        .zip(&body.momentum.sigma)
        .zip(eps_p)
    {
        let r = x.norm();
        let e = x / r;
        let rr = e.dot(&(s * e));
        let tt = 0.5 * (s.trace() - rr);
        let (srr, stt) = exact.stress(r);
        err_rr = err_rr.max((rr - srr).abs() / YIELD);
        err_tt = err_tt.max((tt - stt).abs() / YIELD);
        let err = (rr - srr).abs().max((tt - stt).abs()) / YIELD;
        // the wall cells (h = 1/40), and the rest of the wall
        if r < a_now + 0.025 {
            err_wall = err_wall.max(err);
        } else {
            err_inside = err_inside.max(err);
        }
        if ep > 0.0 {
            plastic_to = plastic_to.max(r);
        } else {
            elastic_from = elastic_from.min(r);
        }
    }
    let u_exact = exact.outer_displacement(YOUNG, POISSON);
    eprintln!(
        "elastoplastic sphere: c = {:.4} (plastic cells to r = {plastic_to:.4}, elastic from {elastic_from:.4}); max |Δσ_rr|/σ_Y = {err_rr:.4} (wall cells {err_wall:.4}, the rest {err_inside:.4}), max |Δσ_θθ|/σ_Y = {err_tt:.4}; u(b) = {u_outer:.6e} against {u_exact:.6e} ({:+.2} %); {} outer iterations",
        exact.c,
        100.0 * (u_outer / u_exact - 1.0),
        out.summary.outer_iterations
    );
    // the boundary within one cell (h = 1/40) of c
    assert!(
        plastic_to < exact.c && plastic_to > exact.c - 0.025,
        "{plastic_to}"
    );
    assert!(
        elastic_from > exact.c && elastic_from < exact.c + 0.025,
        "{elastic_from}"
    );
    // The cells at the pressurised wall carry the largest error, first order
    // in the cell size (20 / 40 / 80 radial cells: 4.5 / 2.3 / 1.3 % of
    // σ_Y, on the undeformed radii): eq. 3.23 gives the wall face the
    // tangential (hoop) strain of the cell centre, half a cell inside, and
    // the traction condition balances it with the volumetric strain, which
    // under plastic flow carries the whole change of the traction; the
    // Rhie–Chow term (with α_RC = 0: 0.7 %) then acts on that trace. A
    // second-order face gradient (the owner's gradient extrapolated from its
    // neighbours) halved it here but fed an odd–even mode into elastic
    // walls (Lamé cylinder 0.5 → 2 %); not kept.
    assert!(err_wall < 0.03, "wall cells: error {err_wall} of σ_Y");
    assert!(
        err_inside < 0.02,
        "inside the wall: error {err_inside} of σ_Y"
    );
    assert!(
        (u_outer / u_exact - 1.0).abs() < 0.005,
        "u(b) {u_outer} vs {u_exact}"
    );
}
