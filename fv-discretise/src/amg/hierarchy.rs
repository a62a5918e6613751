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
use super::sparse::{Sparse, View};
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

/// One level: its operator (a coarse level's own; the finest level's is
/// the caller's matrix, not copied) and, towards the next coarser level,
/// the aggregate of each unknown and the coarse entry of each of its
/// entries.
#[derive(Debug, Clone, Default)]
struct Level {
    a: Sparse,
    inv_diag: Vec<f64>,
    aggregate: Vec<u32>,
    coarse_entry: Vec<u32>,
    /// Work vectors of a coarse level: right-hand side and solution (the
    /// finest level's are the V-cycle's arguments).
    b: Vec<f64>,
    x: Vec<f64>,
}

/// The multigrid hierarchy of a matrix ([`Hierarchy::build`]) and its
/// V-cycle ([`Hierarchy::v_cycle`], given the same matrix).
#[derive(Debug, Clone, Default)]
pub(crate) struct Hierarchy {
    levels: Vec<Level>,
    coarsest: Option<Cholesky<f64, Dyn>>,
    /// Pattern of the matrix the levels were set up for.
    pattern: Option<u64>,
    /// Entries of that matrix.
    fine_entries: usize,
    /// Workspace of the setup: marker per coarse column, members of each
    /// aggregate (by counting sort), the coarsest level densely.
    marker: Vec<u32>,
    member_ptr: Vec<u32>,
    members: Vec<u32>,
    dense: DMatrix<f64>,
    coarse_b: DVector<f64>,
}

/// The operator of level `l`: `fine` on the finest.
fn operator<'a>(levels: &'a [Level], l: usize, fine: &'a CsrMatrix) -> View<'a> {
    if l == 0 {
        View::of(fine)
    } else {
        levels[l].a.view()
    }
}

impl Hierarchy {
    /// Unknowns per level, finest first.
    pub fn level_sizes(&self) -> Vec<usize> {
        self.levels.iter().map(|l| l.inv_diag.len()).collect()
    }

    /// Sum of the levels' operator entries over the finest one's.
    pub fn operator_complexity(&self) -> f64 {
        let fine = self.fine_entries.max(1);
        let coarse: usize = self.levels.iter().skip(1).map(|l| l.a.val.len()).sum();
        (fine + coarse) as f64 / fine as f64
    }

    /// Whether the levels were set up for a matrix of `a`'s pattern.
    pub fn is_for(&self, a: &CsrMatrix) -> bool {
        self.pattern == Some(a.pattern_id()) && !self.levels.is_empty()
    }

    /// Sets up the levels of `a` (symmetric, positive diagonal), or refills
    /// their values when `a` has the pattern of the last call.
    pub fn build(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        if self.is_for(a) {
            for l in 0..self.levels.len() {
                let (fine, coarse) = self.levels.split_at_mut(l + 1);
                let this = &mut fine[l];
                let op = if l == 0 { View::of(a) } else { this.a.view() };
                inverse_diagonal(op, &mut this.inv_diag)?;
                if let Some(c) = coarse.first_mut() {
                    c.a.val.iter_mut().for_each(|v| *v = 0.0);
                    for (&slot, &v) in this.coarse_entry.iter().zip(op.val) {
                        c.a.val[slot as usize] += v;
                    }
                }
            }
        } else if self
            .levels
            .first()
            .is_some_and(|l| l.inv_diag.len() == a.n())
        {
            self.keep_aggregates(a)?;
        } else {
            self.set_up(a)?;
        }
        self.fine_entries = a.values().len();
        self.factorise_coarsest(a);
        Ok(())
    }

    /// The levels of `a`, a matrix of the last one's size but another
    /// pattern (contact pairs joined or left): the aggregates are kept, the
    /// coarse patterns rebuilt.
    fn keep_aggregates(&mut self, a: &CsrMatrix) -> Result<(), LinearSolverError> {
        self.pattern = None;
        let mut levels = std::mem::take(&mut self.levels);
        for l in 0..levels.len() {
            let (fine, coarse) = levels.split_at_mut(l + 1);
            let this = &mut fine[l];
            let op = if l == 0 { View::of(a) } else { this.a.view() };
            inverse_diagonal(op, &mut this.inv_diag)?;
            if let Some(c) = coarse.first_mut() {
                let n_coarse = c.a.n_rows;
                self.galerkin_pattern(
                    op,
                    &this.aggregate,
                    &mut this.coarse_entry,
                    &mut c.a,
                    n_coarse,
                );
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
        levels[0].a = Sparse::default();
        levels[0].b = Vec::new();
        levels[0].x = Vec::new();
        let mut depth = 0;
        loop {
            let (fine, coarse) = levels.split_at_mut(depth + 1);
            let lv = &mut fine[depth];
            let op = if depth == 0 { View::of(a) } else { lv.a.view() };
            inverse_diagonal(op, &mut lv.inv_diag)?;
            let n = op.n_rows;
            if depth > 0 {
                for v in [&mut lv.b, &mut lv.x] {
                    v.clear();
                    v.resize(n, 0.0);
                }
            }
            if n <= COARSEST || depth + 1 == MAX_LEVELS {
                break;
            }
            let theta = STRENGTH * 0.5f64.powi(depth as i32);
            let n_coarse = aggregate(op, &lv.inv_diag, theta, &mut lv.aggregate);
            if (n as f64) < MIN_COARSENING * n_coarse as f64 {
                break;
            }
            let mut next = coarse.first_mut().map(std::mem::take).unwrap_or_default();
            self.galerkin_pattern(
                op,
                &lv.aggregate,
                &mut lv.coarse_entry,
                &mut next.a,
                n_coarse,
            );
            if levels.len() == depth + 1 {
                levels.push(next);
            } else {
                levels[depth + 1] = next;
            }
            depth += 1;
        }
        levels.truncate(depth + 1);
        self.levels = levels;
        self.pattern = Some(a.pattern_id());
        Ok(())
    }

    /// The coarse operator `Pᵀ A P` of the aggregates of `a`'s unknowns
    /// into `coarse`, and the coarse entry of each entry of `a`.
    fn galerkin_pattern(
        &mut self,
        a: View,
        aggregate: &[u32],
        coarse_entry: &mut Vec<u32>,
        coarse: &mut Sparse,
        n_coarse: usize,
    ) {
        let n = a.n_rows;
        // members of each aggregate
        self.member_ptr.clear();
        self.member_ptr.resize(n_coarse + 1, 0);
        for &g in aggregate {
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
        for (i, &g) in aggregate.iter().enumerate() {
            let slot = &mut self.marker[g as usize];
            self.members[*slot as usize] = i as u32;
            *slot += 1;
        }
        self.marker.clear();
        self.marker.resize(n_coarse, UNSEEN);
        coarse_entry.clear();
        coarse_entry.resize(a.col.len(), 0);
        coarse.n_rows = n_coarse;
        coarse.ptr.clear();
        coarse.ptr.push(0);
        coarse.col.clear();
        coarse.val.clear();
        for g in 0..n_coarse {
            let start = coarse.col.len();
            let (s, e) = (self.member_ptr[g] as usize, self.member_ptr[g + 1] as usize);
            for &i in &self.members[s..e] {
                let (rs, re) = (a.ptr[i as usize] as usize, a.ptr[i as usize + 1] as usize);
                for k in rs..re {
                    let h = aggregate[a.col[k] as usize];
                    let m = &mut self.marker[h as usize];
                    if *m == UNSEEN {
                        *m = coarse.col.len() as u32;
                        coarse.col.push(h);
                        coarse.val.push(0.0);
                    }
                    coarse_entry[k] = *m;
                    coarse.val[*m as usize] += a.val[k];
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
    /// sweeps solve it); `fine` is the finest level's operator.
    fn factorise_coarsest(&mut self, fine: &CsrMatrix) {
        if self.levels.is_empty() {
            self.coarsest = None;
            return;
        }
        let last = operator(&self.levels, self.levels.len() - 1, fine);
        let n = last.n_rows;
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
            let (c, v) = last.row(i);
            for (&j, &x) in c.iter().zip(v) {
                self.dense[(i, j as usize)] += x;
            }
        }
        self.coarsest = self.dense.clone().cholesky();
    }

    /// `x = M⁻¹ b` by one V-cycle from a zero guess; `a` is the matrix the
    /// levels were built for ([`Self::build`]).
    pub fn v_cycle(&mut self, a: &CsrMatrix, b: &[f64], x: &mut [f64]) {
        if self.levels.is_empty() {
            x.copy_from_slice(b);
            return;
        }
        cycle(
            &mut self.levels,
            View::of(a),
            b,
            x,
            self.coarsest.as_ref(),
            &mut self.coarse_b,
        );
    }
}

/// `1 / a_ii` of every row of `a` into `inv_diag`; an error for a diagonal
/// entry that is not positive.
fn inverse_diagonal(a: View, inv_diag: &mut Vec<f64>) -> Result<(), LinearSolverError> {
    inv_diag.clear();
    for i in 0..a.n_rows {
        let (c, v) = a.row(i);
        let d: f64 = c
            .iter()
            .zip(v)
            .filter(|(&j, _)| j as usize == i)
            .map(|(_, &x)| x)
            .sum();
        if !(d > 0.0) {
            return Err(LinearSolverError::Breakdown {
                method: "AMG",
                iteration: 0,
                reason: "a diagonal entry of a level is not positive",
            });
        }
        inv_diag.push(1.0 / d);
    }
    Ok(())
}

/// One V-cycle on `levels[0]`, whose operator is `a`, for the right-hand
/// side `b` into `x`, and below.
fn cycle(
    levels: &mut [Level],
    a: View,
    b: &[f64],
    x: &mut [f64],
    coarsest: Option<&Cholesky<f64, Dyn>>,
    coarse_b: &mut DVector<f64>,
) {
    let Some((this, rest)) = levels.split_first_mut() else {
        return;
    };
    x.iter_mut().for_each(|v| *v = 0.0);
    if rest.is_empty() {
        match coarsest {
            Some(ch) => {
                coarse_b.as_mut_slice().copy_from_slice(b);
                ch.solve_mut(coarse_b);
                x.copy_from_slice(coarse_b.as_slice());
            }
            None => {
                for _ in 0..10 {
                    gauss_seidel(a, &this.inv_diag, b, x, false);
                    gauss_seidel(a, &this.inv_diag, b, x, true);
                }
            }
        }
        return;
    }
    gauss_seidel(a, &this.inv_diag, b, x, false);
    // the residual, restricted: summed over each aggregate
    let next = &mut rest[0];
    let (next_a, mut next_b, mut next_x) = (
        std::mem::take(&mut next.a),
        std::mem::take(&mut next.b),
        std::mem::take(&mut next.x),
    );
    next_b.iter_mut().for_each(|v| *v = 0.0);
    for i in 0..a.n_rows {
        let (c, v) = a.row(i);
        let mut ax = 0.0;
        for (&j, &aij) in c.iter().zip(v) {
            ax += aij * x[j as usize];
        }
        next_b[this.aggregate[i] as usize] += b[i] - ax;
    }
    cycle(
        rest,
        next_a.view(),
        &next_b,
        &mut next_x,
        coarsest,
        coarse_b,
    );
    for (xi, &g) in x.iter_mut().zip(&this.aggregate) {
        *xi += next_x[g as usize];
    }
    let next = &mut rest[0];
    (next.a, next.b, next.x) = (next_a, next_b, next_x);
    gauss_seidel(a, &this.inv_diag, b, x, true);
}

/// One Gauss–Seidel sweep, rows ascending (or descending when `backward`).
fn gauss_seidel(a: View, inv_diag: &[f64], b: &[f64], x: &mut [f64], backward: bool) {
    #[inline(always)]
    fn row(a: View, inv_diag: &[f64], b: &[f64], x: &mut [f64], i: usize) {
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
