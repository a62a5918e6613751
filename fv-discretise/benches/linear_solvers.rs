//! Linear solver benchmarks on the 7-point FV Laplacian of a 64³ grid (262,144 unknowns).
//!
//! The matrix is assembled like a cell-centred FV elasticity component:
//! face coefficient 1 on every internal face, Dirichlet boundary faces add 2
//! (half-cell distance) to the diagonal. Timed, single-threaded:
//!
//! - `pcg_ic0/factorise+solve`: [`PcgIc0`] factorisation + solve to 1e-6 relative;
//! - `pcg_ic0/solve`: the solve alone (the factorisation is reused for three components);
//! - `faer_cg_ic0/factorise+solve`: faer's `conjugate_gradient` with faer-precond's `Ic0`, 1e-6 relative;
//! - `bicgstab_ilu0/factorise+solve`: [`BicgstabIlu0`] on the same matrix, for reference;
//! - `matvec`: one bare `y = A x` ([`CsrMatrix::mul_vec`]) and faer's sparse mat-vec.
//!
//! Iteration counts are printed once before timing.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::matrix_free::conjugate_gradient::{
    conjugate_gradient, conjugate_gradient_scratch, CgParams,
};
use faer::matrix_free::InitialGuessStatus;
use faer::{Mat, Par};
use faer_precond::Ic0;
use fv_discretise::{BicgstabIlu0, BicgstabParams, CsrMatrix, PcgIc0, PcgParams};

/// Grid cells per direction.
const N: usize = 64;

/// FV Laplacian of an `n³` grid with Dirichlet boundaries on all sides.
fn laplacian(n: usize) -> CsrMatrix {
    let idx = |i: usize, j: usize, k: usize| (i + n * (j + n * k)) as u32;
    let (mut own, mut nei) = (Vec::new(), Vec::new());
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                for (d, ok) in [
                    (idx(1, 0, 0), i + 1 < n),
                    (idx(0, 1, 0), j + 1 < n),
                    (idx(0, 0, 1), k + 1 < n),
                ] {
                    if ok {
                        own.push(idx(i, j, k));
                        nei.push(idx(i, j, k) + d);
                    }
                }
            }
        }
    }
    let (mut a, slots) = CsrMatrix::from_faces(n * n * n, &own, &nei);
    let diag = a.diag_index().to_vec();
    let v = a.values_mut();
    for &d in &diag {
        // 6 faces: 1 per internal face, 2 per Dirichlet boundary face = 12 − (internal faces)
        v[d as usize] = 12.0;
    }
    for f in 0..own.len() {
        v[slots.upper[f] as usize] = -1.0;
        v[slots.lower[f] as usize] = -1.0;
        v[diag[own[f] as usize] as usize] -= 1.0;
        v[diag[nei[f] as usize] as usize] -= 1.0;
    }
    a
}

/// Deterministic right-hand side.
fn rhs(n: usize) -> Vec<f64> {
    let mut s = 12345u64;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

/// Runs faer's CG with faer-precond's IC(0) from a zero guess; returns the iteration count.
fn faer_cg(
    a: faer::sparse::SparseColMatRef<'_, usize, f64>,
    b: &Mat<f64>,
    x: &mut Mat<f64>,
    buf: &mut MemBuffer,
) -> usize {
    let pc = Ic0::<usize, f64>::try_new(a).expect("SPD");
    // faer 0.24 bug: with `InitialGuessStatus::Zero` the residual work vector is
    // never initialised (CG fails with NonPositiveDefiniteOperator), so start
    // from an explicit zero guess instead (one extra mat-vec, as in PcgIc0).
    x.fill(0.0);
    let params = CgParams {
        initial_guess: InitialGuessStatus::MaybeNonZero,
        rel_tolerance: 1e-6,
        max_iters: 1000,
        ..Default::default()
    };
    let info = conjugate_gradient(
        x.as_mut(),
        &pc,
        a,
        b.as_ref(),
        params,
        |_| {},
        Par::Seq,
        MemStack::new(buf),
    )
    .expect("CG converges");
    info.iter_count
}

fn benches(c: &mut Criterion) {
    let a = laplacian(N);
    let n = a.n();
    let b = rhs(n);
    let params = PcgParams::default();
    let mut pcg = PcgIc0::new(n);
    let mut x = vec![0.0; n];

    // Iteration counts, printed once.
    pcg.factorise(&a).unwrap();
    let info = pcg.solve(&a, &b, &mut x, &params).unwrap();
    let af = a.to_faer();
    let bf = Mat::from_fn(n, 1, |i, _| b[i]);
    let mut xf = Mat::<f64>::zeros(n, 1);
    let pc = Ic0::<usize, f64>::try_new(af.as_ref()).expect("SPD");
    let mut buf = MemBuffer::new(conjugate_gradient_scratch(&pc, af.as_ref(), 1, Par::Seq));
    let faer_iters = faer_cg(af.as_ref(), &bf, &mut xf, &mut buf);
    let mut bicg = BicgstabIlu0::new(n);
    bicg.factorise(&a).unwrap();
    let mut xb = vec![0.0; n];
    let binfo = bicg
        .solve(&a, &b, &mut xb, &BicgstabParams::default())
        .unwrap();
    eprintln!(
        "n = {n}, nnz = {}: PcgIc0 {} iterations (rel. residual {:.2e}), faer CG + Ic0 {faer_iters} iterations, \
         BiCGStab+ILU(0) {} iterations",
        a.nnz(),
        info.iterations,
        info.final_residual / info.initial_residual,
        binfo.iterations,
    );

    let mut g = c.benchmark_group("linear_solvers_64cubed");
    g.sample_size(10);
    g.bench_function("pcg_ic0/factorise+solve", |bench| {
        bench.iter(|| {
            x.fill(0.0);
            pcg.factorise(black_box(&a)).unwrap();
            pcg.solve(&a, black_box(&b), &mut x, &params).unwrap()
        })
    });
    g.bench_function("pcg_ic0/solve", |bench| {
        bench.iter(|| {
            x.fill(0.0);
            pcg.solve(&a, black_box(&b), &mut x, &params).unwrap()
        })
    });
    g.bench_function("faer_cg_ic0/factorise+solve", |bench| {
        bench.iter(|| faer_cg(black_box(af.as_ref()), &bf, &mut xf, &mut buf))
    });
    g.bench_function("bicgstab_ilu0/factorise+solve", |bench| {
        bench.iter(|| {
            xb.fill(0.0);
            bicg.factorise(black_box(&a)).unwrap();
            bicg.solve(&a, black_box(&b), &mut xb, &BicgstabParams::default())
                .unwrap()
        })
    });
    let mut y = vec![0.0; n];
    g.bench_function("matvec/csr", |bench| {
        bench.iter(|| a.mul_vec(black_box(&b), &mut y))
    });
    let mut yf = Mat::<f64>::zeros(n, 1);
    g.bench_function("matvec/faer", |bench| {
        bench.iter(|| {
            faer::sparse::linalg::matmul::sparse_dense_matmul(
                yf.as_mut(),
                faer::Accum::Replace,
                af.as_ref(),
                black_box(bf.as_ref()),
                1.0,
                Par::Seq,
            )
        })
    });
    g.finish();
}

criterion_group!(linear_solvers, benches);
criterion_main!(linear_solvers);
