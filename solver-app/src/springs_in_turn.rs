//! The linear step of an outer iteration with the displacement components
//! solved one after another across stiff contact springs (Gauss–Seidel
//! over the components) — beyond the thesis, which solves them side by
//! side with every off-diagonal tensor part lagged (eq. 4.54 iv–v).
//!
//! A penalty spring k_n n⊗n + k_t (I − n⊗n) between two cells (implicit
//! coupling of deformable bodies, eqs. 4.60–4.72) couples the components
//! through its n_c n_d parts, which the segregated solve takes from the
//! residual. Side by side (Jacobi) they act at the last outer iteration's
//! corrections: each component takes up the whole normal approach by
//! itself, and for a stiff spring (ε_n δ/K ≫ 1) inclined to the axes the
//! iterate grows. Moving the off-diagonal row onto the diagonal (this
//! project's earlier remedy) makes it contract, but every motion along
//! the interface then meets a stiffness that is not there. Solved in turn
//! — first the component the springs hold hardest, each next one with the
//! off-diagonal parts at the corrections just found — the splitting of
//! the springs is Gauss–Seidel on a symmetric positive definite system,
//! which contracts whatever the stiffness, with the true diagonal. The
//! residual is the full one, so the converged state does not change, only
//! the path to it.
//!
//! Measured: two grounded chains joined by a spring 50 times their link
//! stiffness (the tests below) take 53–55 outer iterations in turn, 96–98
//! side by side and 472–483 with the dominant diagonal (normal 6° off an
//! axis, pulled or sheared); at 45° and 200 times the link stiffness in
//! turn takes 3,310 and both others grow. The sphere on a block at
//! ε_n/E = 1000 (`validation` implicit-efficiency tests) to the case's
//! tolerance 1e-6: 84 outer iterations against 114 with the dominant
//! diagonal (116 against 151 to 1e-7); at ε_n/E = 2,700 and 10,000 the
//! carried-traction base of the contact linearisation sets the pace (440
//! and 803 against 442 and 809). The cost is the two threads: the three
//! component solves run one after another. Normals far from the axes are
//! solved with the whole spring tensor instead
//! ([`crate::coupled_spring_solve`]; chosen per pair in
//! [`crate::contact_coupling`], `INCLINED_SHARE`); below the stiff ratio
//! the components stay side by side.
//!
//! Written by hand: a sweep over the project's spring list between the
//! project's own component solves; no crate offers that.
use crate::contact_coupling::CellSpring;
use fv_discretise::{CsrMatrix, LinearSolver, LinearSolverError};

/// Solves the components `component_matrix[c] = Some(matrix)` in turn:
/// `rhs[c]` holds the residual of component c on entry (it is changed),
/// `x[c]` receives the correction (zero for unsolved components). The
/// matrices hold each spring's [`CellSpring::tensor_diagonal`]; the
/// off-diagonal parts towards components already solved move to the
/// right-hand side.
/// Returns the linear iterations.
pub fn solve_in_turn(
    matrices: &[CsrMatrix],
    component_matrix: &[Option<usize>; 3],
    solvers: &mut [Box<dyn LinearSolver + Send>],
    springs: &[CellSpring],
    rhs: &mut [Vec<f64>; 3],
    x: &mut [Vec<f64>; 3],
) -> Result<usize, LinearSolverError> {
    // first the component the springs hold hardest
    let mut weight = [0.0f64; 3];
    for sp in springs {
        for (c, w) in weight.iter_mut().enumerate() {
            *w += sp.tensor_diagonal(c);
        }
    }
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| weight[b].total_cmp(&weight[a]));
    let mut solved = [false; 3];
    let mut iterations = 0;
    for c in order {
        x[c].iter_mut().for_each(|v| *v = 0.0);
        let Some(mi) = component_matrix[c] else {
            continue;
        };
        for sp in springs {
            let (a, b) = (sp.cells.0 as usize, sp.cells.1 as usize);
            let mut f = 0.0;
            for d in (0..3).filter(|&d| solved[d]) {
                f += sp.tensor_off_diagonal(c, d) * (x[d][a] - x[d][b]);
            }
            rhs[c][a] -= f;
            rhs[c][b] += f;
        }
        iterations += solvers[mi]
            .solve(&matrices[mi], &rhs[c], &mut x[c])?
            .iterations;
        solved[c] = true;
    }
    Ok(iterations)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fv_discretise::PcgIc0;
    use fv_mesh::Vector;

    const M: usize = 5;
    const N: usize = 2 * M;

    /// How the components of an outer iteration are solved.
    #[derive(Clone, Copy, PartialEq)]
    enum Splitting {
        SideBySide,
        /// Side by side with |k_cd| of the other components on the diagonal.
        DominantDiagonal,
        InTurn,
    }

    /// Two chains of five cells (x and y solved), each grounded at its
    /// outer end (stiffness 1, links 4), joined at their inner ends by a
    /// spring of stiffness `k` along `normal`.
    struct Chains {
        matrices: Vec<CsrMatrix>,
        solvers: Vec<Box<dyn LinearSolver + Send>>,
        spring: CellSpring,
        /// What the matrices add to each component's tensor diagonal.
        extra: [f64; 2],
    }

    impl Chains {
        fn new(k: f64, normal: Vector, splitting: Splitting) -> Self {
            let spring = CellSpring {
                cells: ((M - 1) as u32, (N - 1) as u32),
                stiffness: k,
                tangential: 0.0,
                normal: normal.normalize(),
                in_turn: splitting == Splitting::InTurn,
                coupled: false,
            };
            let mut extra = [0.0; 2];
            if splitting == Splitting::DominantDiagonal {
                extra = [0, 1].map(|c| spring.tensor_off_diagonal(c, 1 - c).abs());
            }
            let mut matrices = Vec::new();
            let mut solvers: Vec<Box<dyn LinearSolver + Send>> = Vec::new();
            for (comp, extra) in extra.iter().enumerate() {
                let mut t = Vec::new();
                for o in [0, M] {
                    for i in 0..M {
                        let mut d = if i == 0 { 1.0 } else { 4.0 };
                        if i + 1 < M {
                            d += 4.0;
                            t.push(((o + i) as u32, (o + i + 1) as u32, -4.0));
                            t.push(((o + i + 1) as u32, (o + i) as u32, -4.0));
                        }
                        t.push(((o + i) as u32, (o + i) as u32, d));
                    }
                }
                let kd = spring.tensor_diagonal(comp) + extra;
                let (a, b) = spring.cells;
                t.extend([(a, a, kd), (b, b, kd), (a, b, -kd), (b, a, -kd)]);
                let a = CsrMatrix::from_triplets(N, &t).unwrap();
                let mut s = PcgIc0::new(N);
                s.factorise(&a).unwrap();
                matrices.push(a);
                solvers.push(Box::new(s));
            }
            Chains {
                matrices,
                solvers,
                spring,
                extra,
            }
        }

        /// [`solve_in_turn`] of x and y for the residual `r`.
        fn solve_in_turn(&mut self, r: &mut [Vec<f64>; 3]) -> [Vec<f64>; 3] {
            // a guess that must not matter
            let mut x: [Vec<f64>; 3] = [vec![1.0; N], vec![1.0; N], vec![1.0; N]];
            let map = [Some(0), Some(1), None];
            let springs = [self.spring];
            solve_in_turn(&self.matrices, &map, &mut self.solvers, &springs, r, &mut x).unwrap();
            x
        }

        /// Outer iterations u ← u + δ (δ from the components' matrices, the
        /// residual with the whole spring tensor: the solver's defect
        /// correction), loaded by `load` (component, cell, force), until the
        /// correction is below 1e-10 of u; `None` if that takes more than
        /// 5,000 or the iterate grows without bound.
        fn outer_iterations(&mut self, load: &[(usize, usize, f64)]) -> Option<usize> {
            let mut u = [vec![0.0; N], vec![0.0; N], vec![0.0; N]];
            let (sa, sb) = (self.spring.cells.0 as usize, self.spring.cells.1 as usize);
            for it in 1..=5000 {
                let mut r: [Vec<f64>; 3] = [vec![0.0; N], vec![0.0; N], vec![0.0; N]];
                for comp in 0..2 {
                    self.matrices[comp].mul_vec(&u[comp], &mut r[comp]);
                    r[comp].iter_mut().for_each(|v| *v = -*v);
                    let other = 1 - comp;
                    let f = self.spring.tensor_off_diagonal(comp, other)
                        * (u[other][sa] - u[other][sb])
                        - self.extra[comp] * (u[comp][sa] - u[comp][sb]);
                    r[comp][sa] -= f;
                    r[comp][sb] += f;
                }
                for &(comp, cell, value) in load {
                    r[comp][cell] += value;
                }
                let x = if self.spring.in_turn {
                    self.solve_in_turn(&mut r)
                } else {
                    let mut x: [Vec<f64>; 3] = [vec![0.0; N], vec![0.0; N], vec![0.0; N]];
                    for comp in 0..2 {
                        self.solvers[comp]
                            .solve(&self.matrices[comp], &r[comp], &mut x[comp])
                            .unwrap();
                    }
                    x
                };
                let (mut dx, mut un) = (0.0, 0.0);
                for comp in 0..2 {
                    for i in 0..N {
                        u[comp][i] += x[comp][i];
                        dx += x[comp][i] * x[comp][i];
                        un += u[comp][i] * u[comp][i];
                    }
                }
                if !(un < 1e12) {
                    return None;
                }
                if dx.sqrt() < 1e-10 * un.sqrt() {
                    return Some(it);
                }
            }
            None
        }
    }

    #[test]
    fn stiff_springs_solved_in_turn_contract_fastest() {
        use Splitting::*;
        let near_axis = Vector::new(0.1, 1.0, 0.0);
        let pull = [(0, M - 1, 1.0), (1, N - 1, -0.5)];
        let shear = [(0, M - 1, 1.0), (0, N - 1, -1.0)];
        for load in [pull, shear] {
            let count = |s| Chains::new(50.0, near_axis, s).outer_iterations(&load);
            let (side, dominant, turn) =
                (count(SideBySide), count(DominantDiagonal), count(InTurn));
            let (side, dominant, turn) = (side.unwrap(), dominant.unwrap(), turn.unwrap());
            // measured 96–98, 472–483 and 53–55
            assert!(turn <= 60, "in turn {turn}");
            assert!(5 * turn <= 3 * side, "in turn {turn}, side by side {side}");
            assert!(
                5 * turn <= dominant,
                "in turn {turn}, dominant diagonal {dominant}"
            );
        }
        // 45° and 200 times the links: side by side the iterate grows
        let inclined = Vector::new(1.0, 1.0, 0.0);
        let count = |s| Chains::new(200.0, inclined, s).outer_iterations(&pull);
        assert_eq!(count(SideBySide), None);
        assert!(count(InTurn).is_some());
    }

    #[test]
    fn in_turn_solves_the_component_the_springs_hold_hardest_first() {
        // a spring along y: y is solved first, and x then sees no
        // off-diagonal part, so both equal the independent solves
        let mut ch = Chains::new(50.0, Vector::new(0.0, 1.0, 0.0), Splitting::InTurn);
        let mut r: [Vec<f64>; 3] = [vec![0.0; N], vec![0.0; N], vec![0.0; N]];
        r[0][M - 1] = 1.0;
        r[1][N - 1] = 1.0;
        let expect: Vec<Vec<f64>> = (0..2)
            .map(|c| {
                let mut x = vec![0.0; N];
                ch.solvers[c].solve(&ch.matrices[c], &r[c], &mut x).unwrap();
                x
            })
            .collect();
        let x = ch.solve_in_turn(&mut r);
        for c in 0..2 {
            for i in 0..N {
                assert!((x[c][i] - expect[c][i]).abs() < 1e-12, "x[{c}][{i}]");
            }
        }
        assert!(x[2].iter().all(|&v| v == 0.0));
    }

    #[test]
    fn in_turn_a_component_sees_the_correction_of_the_one_before() {
        // a spring at 45° between the chains, a load in y only: y is solved
        // first (equal weights: the lower index, x, would come first — so
        // tilt the spring towards y), and x then moves by the spring's
        // off-diagonal part although its own residual is zero
        let mut ch = Chains::new(50.0, Vector::new(0.9, 1.0, 0.0), Splitting::InTurn);
        let mut r: [Vec<f64>; 3] = [vec![0.0; N], vec![0.0; N], vec![0.0; N]];
        r[1][N - 1] = 1.0;
        let x = ch.solve_in_turn(&mut r);
        let (a, b) = (M - 1, N - 1);
        assert!(x[1][b] > 0.0);
        // x's equation at the spring's cells: K_x x = −k_xy (y_a − y_b) at a
        let push = -ch.spring.tensor_off_diagonal(0, 1) * (x[1][a] - x[1][b]);
        assert!(push > 0.0);
        assert!(x[0][a] > 0.0 && x[0][b] < 0.0, "{} {}", x[0][a], x[0][b]);
    }
}
