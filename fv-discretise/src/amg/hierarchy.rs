//! The levels of aggregation multigrid and its V-cycle.
//!
//! Setup per level: aggregates of strongly connected unknowns
//! ([`super::aggregation`]); the piecewise-constant prolongator `P` (1 from
//! an aggregate to each of its unknowns: the constant, the null space of a
//! scalar Laplacian); the Galerkin coarse operator `A_c = Pᵀ A P`, whose
//! entry (I, J) is the sum of the fine entries from aggregate I to J. Below
//! [`COARSEST`] unknowns a dense Cholesky factor.
//!
//! Plain, not smoothed, aggregation: smoothing `P` by a Jacobi step halves
//! the V-cycles to a given residual but, on the tetrahedral meshes of the
//! sphere on a block, made the coarse operators five times as dense as the
//! fine one and the setup 30 times as costly (100 ms against 3 ms per
//! component matrix), and Newton rebuilds the preconditioner at every step.
//!
//! The aggregates depend on the first matrix of a size only, the coarse
//! patterns on the first of a pattern: a matrix of the same pattern refills
//! the levels' values (one pass over each level's entries); one whose
//! pattern grew (new contact pairs) keeps the aggregates.
//!
//! The V-cycle smooths by one Gauss–Seidel sweep forward before the coarse
//! correction and one backward after it: a symmetric positive definite
//! operator, usable inside conjugate gradients.
use super::aggregation::aggregate;
use super::sparse::Sparse;
use crate::csr::CsrMatrix;
use crate::linear_solver::LinearSolverError;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};

/// Unknowns of the coarsest level at most (solved by dense Cholesky; at 400
/// its factorisation, three per Newton step, dominated the concentric
/// spheres' 734-cell run).
const COARSEST: usize = 100;
/// Levels at most.
const MAX_LEVELS: usize = 12;
/// Strength threshold θ of the aggregation on the finest level, halved on
/// each coarser one (the coarse operators' off-diagonal entries are small
/// against their diagonal).
const STRENGTH: f64 = 0.08;
/// A level that coarsens by less than this factor ends the hierarchy.
const MIN_COARSENING: f64 = 1.5;
/// Marker of the setup's accumulator: coarse column not yet in the row.
const UNSEEN: u32 = u32::MAX;

/// One level: its operator and, towards the next coarser level, the
/// aggregate of each unknown and the coarse entry of each of its entries.
#[derive(Debug, Clone, Default)]
struct Level {
    a: Sparse,
    inv_diag: Vec<f64>,
    aggregate: Vec<u32>,
    coarse_entry: Vec<u32>,
    /// Work vectors: right-hand side, solution, residual.
    b: Vec<f64>,
    x: Vec<f64>,
    res: Vec<f64>,
}

/// The multigrid hierarchy of a matrix ([`Hierarchy::build`]) and its
/// V-cycle ([`Hierarchy::v_cycle`]).
#[derive(Debug, Clone, Default)]
pub(crate) struct Hierarchy {
    levels: Vec<Level>,
    coarsest: Option<Cholesky<f64, Dyn>>,
    /// Pattern of the matrix the levels were set up for.
    pattern: Option<u64>,
    /// Workspace of the setup: marker per coarse column, members of each
    /// aggregate (by counting sort), the coarsest level densely.
    marker: Vec<u32>,
    member_ptr: Vec<u32>,
    members: Vec<u32>,
    dense: DMatrix<f64>,
    coarse_b: DVector<f64>,
}

impl Hierarchy {
    /// Unknowns per level, finest first.
    pub fn level_sizes(&self) -> Vec<usize> {
        self.levels.iter().map(|l| l.a.n_rows).collect()
    }

    /// Sum of the levels' operator entries over the finest one's.
    pub fn operator_complexity(&self) -> f64 {
        let fine = self.levels.first().map_or(1, |l| l.a.val.len().max(1));
        self.levels.iter().map(|l| l.a.val.len()).sum::<usize>() as f64 / fine as f64
    }

    /// Sets up the levels of `a` (symmetric, positive diagonal), or refills
    /// their values when `a` has the pattern of the last call.
    pub fn build(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        if self.pattern == Some(a.pattern_id()) && !self.levels.is_empty() {
            self.levels[0].a.val.copy_from_slice(a.values());
            for l in 0..self.levels.len() {
                inverse_diagonal(&mut self.levels[l])?;
                if l + 1 < self.levels.len() {
                    let (fine, coarse) = self.levels.split_at_mut(l + 1);
                    let (f, c) = (&fine[l], &mut coarse[0]);
                    c.a.val.iter_mut().for_each(|v| *v = 0.0);
                    for (&slot, &v) in f.coarse_entry.iter().zip(&f.a.val) {
                        c.a.val[slot as usize] += v;
                    }
                }
            }
        } else if self.levels.first().is_some_and(|l| l.a.n_rows == a.n()) {
            self.keep_aggregates(a)?;
        } else {
            self.set_up(a)?;
        }
        self.factorise_coarsest();
        Ok(())
    }

    /// The levels of `a`, a matrix of the last one's size but another
    /// pattern (contact pairs joined or left): the aggregates are kept, the
    /// coarse patterns rebuilt.
    fn keep_aggregates(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        self.pattern = None;
        let mut levels = std::mem::take(&mut self.levels);
        levels[0].a.copy_from(a);
        for l in 0..levels.len() {
            inverse_diagonal(&mut levels[l])?;
            if l + 1 < levels.len() {
                let (fine, coarse) = levels.split_at_mut(l + 1);
                let n_coarse = coarse[0].a.n_rows;
                self.galerkin_pattern(&mut fine[l], &mut coarse[0].a, n_coarse);
            }
        }
        self.levels = levels;
        self.pattern = Some(a.pattern_id());
        Ok(())
    }

    /// The levels of `a` from scratch.
    fn set_up(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        self.pattern = None;
        let mut levels = std::mem::take(&mut self.levels);
        if levels.is_empty() {
            levels.push(Level::default());
        }
        levels[0].a.copy_from(a);
        let mut depth = 0;
        loop {
            let lv = &mut levels[depth];
            inverse_diagonal(lv)?;
            let n = lv.a.n_rows;
            for v in [&mut lv.b, &mut lv.x, &mut lv.res] {
                v.clear();
                v.resize(n, 0.0);
            }
            if n <= COARSEST || depth + 1 == MAX_LEVELS {
                break;
            }
            let theta = STRENGTH * 0.5f64.powi(depth as i32);
            let n_coarse = aggregate(&lv.a, &lv.inv_diag, theta, &mut lv.aggregate);
            if (n as f64) < MIN_COARSENING * n_coarse as f64 {
                break;
            }
            if levels.len() == depth + 1 {
                levels.push(Level::default());
            }
            let (fine, coarse) = levels.split_at_mut(depth + 1);
            self.galerkin_pattern(&mut fine[depth], &mut coarse[0].a, n_coarse);
            depth += 1;
        }
        levels.truncate(depth + 1);
        self.levels = levels;
        self.pattern = Some(a.pattern_id());
        Ok(())
    }

    /// The coarse operator `Pᵀ A P` of `fine`'s aggregates into `coarse`,
    /// and the coarse entry of each fine entry.
    fn galerkin_pattern(&mut self, fine: &mut Level, coarse: &mut Sparse, n_coarse: usize) {
        let n = fine.a.n_rows;
        // members of each aggregate
        self.member_ptr.clear();
        self.member_ptr.resize(n_coarse + 1, 0);
        for &g in &fine.aggregate {
            self.member_ptr[g as usize + 1] += 1;
        }
        for g in 0..n_coarse {
            self.member_ptr[g + 1] += self.member_ptr[g];
        }
        self.members.clear();
        self.members.resize(n, 0);
        // the marker array serves first as each aggregate's next free slot
        self.marker.clear();
        self.marker.extend_from_slice(&self.member_ptr[..n_coarse]);
        for (i, &g) in fine.aggregate.iter().enumerate() {
            let slot = &mut self.marker[g as usize];
            self.members[*slot as usize] = i as u32;
            *slot += 1;
        }
        self.marker.clear();
        self.marker.resize(n_coarse, UNSEEN);
        fine.coarse_entry.clear();
        fine.coarse_entry.resize(fine.a.col.len(), 0);
        coarse.n_rows = n_coarse;
        coarse.n_cols = n_coarse;
        coarse.ptr.clear();
        coarse.ptr.push(0);
        coarse.col.clear();
        coarse.val.clear();
        for g in 0..n_coarse {
            let start = coarse.col.len();
            let (s, e) = (self.member_ptr[g] as usize, self.member_ptr[g + 1] as usize);
            for &i in &self.members[s..e] {
                let (rs, re) = (
                    fine.a.ptr[i as usize] as usize,
                    fine.a.ptr[i as usize + 1] as usize,
                );
                for k in rs..re {
                    let h = fine.aggregate[fine.a.col[k] as usize];
                    let m = &mut self.marker[h as usize];
                    if *m == UNSEEN {
                        *m = coarse.col.len() as u32;
                        coarse.col.push(h);
                        coarse.val.push(0.0);
                    }
                    fine.coarse_entry[k] = *m;
                    coarse.val[*m as usize] += fine.a.val[k];
                }
            }
            for &h in &coarse.col[start..] {
                self.marker[h as usize] = UNSEEN;
            }
            coarse.ptr.push(coarse.col.len() as u32);
        }
    }

    /// The dense Cholesky factor of the coarsest level (none when it is
    /// larger than [`COARSEST`] or not positive definite: then smoothing
    /// sweeps solve it).
    fn factorise_coarsest(&mut self) {
        let Some(last) = self.levels.last() else {
            self.coarsest = None;
            return;
        };
        let n = last.a.n_rows;
        if n > COARSEST {
            self.coarsest = None;
            return;
        }
        if self.dense.nrows() != n {
            self.dense = DMatrix::zeros(n, n);
            self.coarse_b = DVector::zeros(n);
        } else {
            self.dense.fill(0.0);
        }
        for i in 0..n {
            let (c, v) = last.a.row(i);
            for (&j, &x) in c.iter().zip(v) {
                self.dense[(i, j as usize)] += x;
            }
        }
        self.coarsest = self.dense.clone().cholesky();
    }

    /// `x = M⁻¹ b` by one V-cycle from a zero guess.
    pub fn v_cycle(&mut self, b: &[f64], x: &mut [f64]) {
        let Some(first) = self.levels.first_mut() else {
            x.copy_from_slice(b);
            return;
        };
        first.b.copy_from_slice(b);
        cycle(&mut self.levels, self.coarsest.as_ref(), &mut self.coarse_b);
        x.copy_from_slice(&self.levels[0].x);
    }
}

/// `inv_diag` of a level; an error for a diagonal entry that is not positive.
fn inverse_diagonal(lv: &mut Level) -> Result<(), LinearSolverError> {
    lv.inv_diag.clear();
    for i in 0..lv.a.n_rows {
        let (s, e) = (lv.a.ptr[i] as usize, lv.a.ptr[i + 1] as usize);
        let d: f64 = (s..e)
            .filter(|&k| lv.a.col[k] as usize == i)
            .map(|k| lv.a.val[k])
            .sum();
        if !(d > 0.0) {
            return Err(LinearSolverError::Breakdown {
                method: "AMG",
                iteration: 0,
                reason: "a diagonal entry of a level is not positive",
            });
        }
        lv.inv_diag.push(1.0 / d);
    }
    Ok(())
}

/// One V-cycle on `levels[0]` (its `b` given, its `x` the result) and
/// below.
fn cycle(levels: &mut [Level], coarsest: Option<&Cholesky<f64, Dyn>>, coarse_b: &mut DVector<f64>) {
    let Some((this, rest)) = levels.split_first_mut() else {
        return;
    };
    this.x.iter_mut().for_each(|v| *v = 0.0);
    if rest.is_empty() {
        match coarsest {
            Some(ch) => {
                coarse_b.as_mut_slice().copy_from_slice(&this.b);
                ch.solve_mut(coarse_b);
                this.x.copy_from_slice(coarse_b.as_slice());
            }
            None => {
                for _ in 0..10 {
                    gauss_seidel(&this.a, &this.inv_diag, &this.b, &mut this.x, false);
                    gauss_seidel(&this.a, &this.inv_diag, &this.b, &mut this.x, true);
                }
            }
        }
        return;
    }
    gauss_seidel(&this.a, &this.inv_diag, &this.b, &mut this.x, false);
    // the residual, restricted: summed over each aggregate
    let next = &mut rest[0];
    next.b.iter_mut().for_each(|v| *v = 0.0);
    for i in 0..this.a.n_rows {
        let (s, e) = (this.a.ptr[i] as usize, this.a.ptr[i + 1] as usize);
        let mut ax = 0.0;
        for k in s..e {
            ax += this.a.val[k] * this.x[this.a.col[k] as usize];
        }
        next.b[this.aggregate[i] as usize] += this.b[i] - ax;
    }
    cycle(rest, coarsest, coarse_b);
    let xc = &rest[0].x;
    for (x, &g) in this.x.iter_mut().zip(&this.aggregate) {
        *x += xc[g as usize];
    }
    gauss_seidel(&this.a, &this.inv_diag, &this.b, &mut this.x, true);
}

/// One Gauss–Seidel sweep, rows ascending (or descending when `backward`).
fn gauss_seidel(a: &Sparse, inv_diag: &[f64], b: &[f64], x: &mut [f64], backward: bool) {
    #[inline(always)]
    fn row(a: &Sparse, inv_diag: &[f64], b: &[f64], x: &mut [f64], i: usize) {
        let (s, e) = (a.ptr[i] as usize, a.ptr[i + 1] as usize);
        let mut ax = 0.0;
        for k in s..e {
            ax += a.val[k] * x[a.col[k] as usize];
        }
        x[i] += (b[i] - ax) * inv_diag[i];
    }
    if backward {
        for i in (0..a.n_rows).rev() {
            row(a, inv_diag, b, x, i);
        }
    } else {
        for i in 0..a.n_rows {
            row(a, inv_diag, b, x, i);
        }
    }
}
