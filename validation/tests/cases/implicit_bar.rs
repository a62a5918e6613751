//! The 1D bar examples of the implicit Neumann–Neumann coupling (thesis
//! §4.5.1, tables 4.2 and 4.3): unit bars of AE = 1 in three cells, the left
//! end moved 0.1, ε = 1e5, initial gap zero. The contact face is treated
//! with the project's linearised contact condition
//! ([`fv_discretise::LinearisedContact`], eqs. 4.52–4.54): its penalty
//! spring in series with the half cell on the matrix diagonal
//! (`diagonal_factor`, the ε β/(1 + δβε) of eq. 4.42, in series with the
//! opposite half cell for two bars: c = ε/(1 + 2δβε) of eq. 4.48) and the
//! boundary displacement from the normal derivative (`solve_normal_derivative`,
//! eqs. 4.40, 4.46). The 3D solver's outer loop adds its deferred
//! corrections on top of this; here the cell equations are solved exactly,
//! as in the thesis, so the iteration history is the printed one.

/// Implicit against tuned explicit coupling on the 3D benchmarks (thesis
/// tables 4.5–4.7); in this test binary to keep CI from linking another.
mod implicit_efficiency;
use fv_discretise::LinearisedContact;
use fv_mesh::Vector;
use nalgebra::{DMatrix, DVector};

const EPS: f64 = 1e5;
const DX: f64 = 1.0 / 3.0;
const DELTA: f64 = DX / 2.0;
const LOAD: f64 = 0.1;

/// One contact face along +x (the bar's outward normal) with traction
/// t* = ε g* n, stiffness ε β (in series with `opposite` half-cell
/// compliance) and reference u_b*.
fn condition(gap: f64, beta: f64, reference: f64, opposite: f64) -> LinearisedContact {
    let mut lc = LinearisedContact::new(1);
    lc.normal[0] = Vector::x();
    lc.traction[0] = Vector::x() * (EPS * gap.min(0.0));
    let k = EPS * beta;
    lc.stiffness[0] = k / (1.0 + k * opposite);
    lc.reference[0] = Vector::x() * reference;
    lc
}

/// The bar matrix of eq. 4.30 for `n` cells: 1/Δx = 3 between cells, the
/// Dirichlet face 1/δ = 6 on the first cell.
fn bar_matrix(n: usize) -> DMatrix<f64> {
    let mut a = DMatrix::zeros(n, n);
    for i in 0..n - 1 {
        a[(i, i)] -= 1.0 / DX;
        a[(i + 1, i + 1)] -= 1.0 / DX;
        a[(i, i + 1)] += 1.0 / DX;
        a[(i + 1, i)] += 1.0 / DX;
    }
    a[(0, 0)] -= 1.0 / DELTA;
    a
}

#[test]
fn table_4_2_bar_against_a_rigid_wall_converges_in_two_iterations() {
    // printed: iteration, u_0, u_1, u_2 (three decimals in iteration 1, four after)
    let printed = [
        [0.100, 0.100, 0.100],
        [0.0833, 0.0500, 0.0166],
        [0.0833, 0.0500, 0.0166],
    ];
    let (mut gap, mut beta, mut reference) = (0.0, 0.0, 0.0);
    let mut history = Vec::new();
    for row in &printed {
        let lc = condition(gap, beta, reference, 0.0);
        let mut a = bar_matrix(3);
        let mut b = DVector::zeros(3);
        b[0] = -LOAD / DELTA;
        // contact face: K|Γ|/δ · (spring in series with the half cell) on the
        // diagonal, the rest of t(u_b) = t* − εβ(u_b − u_b*) on the right side
        let df = lc.diagonal_factor(0, 0, DELTA);
        a[(2, 2)] -= df / DELTA;
        b[2] = -lc.traction_at(0, &Vector::zeros()).x * (1.0 - df);
        let u = a.lu().solve(&b).expect("regular");
        let r = lc.traction_at(0, &(Vector::x() * u[2]));
        let u_b = u[2] + DELTA * lc.solve_normal_derivative(0, DELTA, &r).x;
        let force = lc.traction_at(0, &(Vector::x() * u_b)).x;
        eprintln!(
            "u = {:.7} {:.7} {:.7}, u_b = {:.4e}, g* = {gap:.4e}, F_c = {force:.6}",
            u[0], u[1], u[2], u_b
        );
        for (v, p) in u.iter().zip(row) {
            assert!((v - p).abs() < 1e-4, "{v} vs printed {p}");
        }
        history.push(force);
        // the wall at x = 1: the gap of the next iteration (eq. 4.33)
        gap = -u_b;
        beta = if gap < 0.0 { 1.0 } else { 0.0 };
        reference = u_b;
    }
    // F_c = −0.099 in iterations 2 and 3, unchanged by the third iteration
    assert!((history[1] + 0.099999).abs() < 1e-5, "{}", history[1]);
    assert!((history[2] - history[1]).abs() < 1e-9 * history[1].abs());
    assert!((-gap - 9.9999e-7).abs() < 1e-10, "{gap}");
}

#[test]
fn table_4_3_two_bars_converge_in_two_iterations() {
    let printed = [
        [0.100, 0.100, 0.100, 0.0, 0.0, 0.0],
        [
            0.0916667, 0.0750001, 0.0583335, 0.0416665, 0.0249999, 0.0083333,
        ],
        [
            0.0916667, 0.0750001, 0.0583335, 0.0416665, 0.0249999, 0.0083333,
        ],
    ];
    // bar A: cells 0–2, contact face on its right; bar B: cells 3–5, contact
    // face on its left (normal −x), its right end fixed
    let (mut gap, mut beta, mut ref_a, mut ref_b) = (0.0, 0.0, 0.0, 0.0);
    for (k, row) in printed.iter().enumerate() {
        let lc = condition(gap, beta, ref_a, DELTA);
        let mut a = DMatrix::zeros(6, 6);
        a.view_mut((0, 0), (3, 3)).copy_from(&bar_matrix(3));
        let mirrored = bar_matrix(3);
        for i in 0..3 {
            for j in 0..3 {
                a[(5 - i, 5 - j)] = mirrored[(i, j)];
            }
        }
        // c = ε/(1 + 2δβε): the spring between the two cells (eq. 4.48)
        let c = lc.diagonal_factor(0, 0, DELTA) / DELTA;
        a[(2, 2)] -= c;
        a[(3, 3)] -= c;
        a[(2, 3)] += c;
        a[(3, 2)] += c;
        let mut b = DVector::zeros(6);
        b[0] = -LOAD / DELTA;
        // c (g* + β u_2b* − β u_3b*) on both cells, with the signs of the
        // two outward normals
        let explicit = c / (EPS * beta).max(f64::MIN_POSITIVE)
            * (lc.traction[0].x + EPS * beta * (ref_a - ref_b));
        b[2] = -explicit;
        b[3] = explicit;
        let u = a.lu().solve(&b).expect("regular");
        eprintln!(
            "iteration {}: u = {:.7} {:.7} {:.7} {:.7} {:.7} {:.7}, g* = {gap:.3e}",
            k + 1,
            u[0],
            u[1],
            u[2],
            u[3],
            u[4],
            u[5]
        );
        for (v, p) in u.iter().zip(row) {
            assert!((v - p).abs() < 1.5e-7, "{v} vs printed {p}");
        }
        // boundary displacements of eq. 4.46 and its mirror
        let w = 1.0 + 2.0 * DELTA * EPS * beta;
        let common = DELTA * EPS / w * (gap.min(0.0) + beta * (ref_a - ref_b));
        let (u2b, u3b) = if beta > 0.0 {
            (
                common + DELTA * EPS * beta / w * u[3] + (1.0 + DELTA * EPS * beta) / w * u[2],
                -common + DELTA * EPS * beta / w * u[2] + (1.0 + DELTA * EPS * beta) / w * u[3],
            )
        } else {
            (u[2], u[3])
        };
        gap = u3b - u2b;
        beta = if gap < 0.0 { 1.0 } else { 0.0 };
        (ref_a, ref_b) = (u2b, u3b);
    }
    // the printed g* of iteration 3: 5e-7 (overlap of the two bars)
    assert!((-gap - 5e-7).abs() < 1e-8, "{gap}");
}
