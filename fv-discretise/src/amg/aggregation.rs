//! Aggregation of the unknowns of one level into the coarse unknowns of the
//! next (Vaněk, Mandel & Brezina 1996, "Algebraic multigrid by smoothed
//! aggregation for second and fourth order elliptic problems", §3): three
//! passes over the graph of strong connections.
use super::sparse::View;

/// Not yet in an aggregate.
const FREE: u32 = u32::MAX;

/// Whether `a_ij` is a strong connection, `|a_ij| > θ √(a_ii a_jj)`, given
/// the inverse diagonal entries.
#[inline]
fn strong(aij: f64, inv_aii: f64, inv_ajj: f64, theta: f64) -> bool {
    aij * aij * inv_aii * inv_ajj > theta * theta
}

/// Fills `aggregate[i]` with the coarse unknown of every fine unknown of
/// `a` and returns the number of aggregates. `inv_diag` holds `1 / a_ii`.
///
/// 1. A free unknown whose strong neighbours are all free starts an
///    aggregate with them (the aggregates' roots are independent).
/// 2. A still free unknown joins the aggregate of pass 1 it is most
///    strongly connected to.
/// 3. The rest form aggregates with their free strong neighbours.
pub(crate) fn aggregate(a: View, inv_diag: &[f64], theta: f64, aggregate: &mut Vec<u32>) -> usize {
    let n = a.n_rows;
    aggregate.clear();
    aggregate.resize(n, FREE);
    let strong_neighbours = |i: usize| {
        let (c, v) = a.row(i);
        c.iter()
            .zip(v)
            .filter(move |(&j, &x)| {
                j as usize != i && strong(x, inv_diag[i], inv_diag[j as usize], theta)
            })
            .map(|(&j, &x)| (j as usize, x))
    };
    let mut n_agg = 0u32;
    for i in 0..n {
        if aggregate[i] != FREE || strong_neighbours(i).any(|(j, _)| aggregate[j] != FREE) {
            continue;
        }
        aggregate[i] = n_agg;
        for (j, _) in strong_neighbours(i) {
            aggregate[j] = n_agg;
        }
        n_agg += 1;
    }
    let first_pass = n_agg;
    for i in 0..n {
        if aggregate[i] != FREE {
            continue;
        }
        let best = strong_neighbours(i)
            .filter(|&(j, _)| aggregate[j] < first_pass)
            .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()));
        if let Some((j, _)) = best {
            aggregate[i] = aggregate[j] | (1 << 31); // joined in pass 2
        }
    }
    for g in aggregate.iter_mut().filter(|g| **g != FREE) {
        *g &= !(1 << 31);
    }
    for i in 0..n {
        if aggregate[i] != FREE {
            continue;
        }
        aggregate[i] = n_agg;
        for (j, _) in strong_neighbours(i) {
            if aggregate[j] == FREE {
                aggregate[j] = n_agg;
            }
        }
        n_agg += 1;
    }
    n_agg as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::amg::sparse::Sparse;

    /// The 1-D Laplacian of n unknowns (Dirichlet at both ends).
    fn laplacian_1d(n: usize) -> Sparse {
        let mut m = Sparse {
            n_rows: n,
            ptr: vec![0],
            ..Default::default()
        };
        for i in 0..n {
            if i > 0 {
                m.col.push(i as u32 - 1);
                m.val.push(-1.0);
            }
            m.col.push(i as u32);
            m.val.push(2.0);
            if i + 1 < n {
                m.col.push(i as u32 + 1);
                m.val.push(-1.0);
            }
            m.ptr.push(m.col.len() as u32);
        }
        m
    }

    #[test]
    fn a_chain_is_cut_into_aggregates_of_three_that_cover_every_unknown() {
        let a = laplacian_1d(10);
        let mut agg = Vec::new();
        let n = aggregate(a.view(), &[0.5; 10], 0.08, &mut agg);
        // pass 1 takes (0,1), (2,3,4), (5,6,7); pass 2 attaches 8 to (5,6,7)
        // and 9 is left for pass 3, or so: every unknown in one aggregate,
        // each aggregate contiguous and of 1–4 unknowns
        assert!(agg.iter().all(|&g| (g as usize) < n));
        assert!((3..=5).contains(&n), "{n} aggregates: {agg:?}");
        for g in 0..n as u32 {
            let members: Vec<usize> = (0..10).filter(|&i| agg[i] == g).collect();
            assert!(!members.is_empty() && members.len() <= 4, "{agg:?}");
            assert_eq!(members.last().unwrap() - members[0] + 1, members.len());
        }
    }
}
