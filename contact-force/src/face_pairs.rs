//! Candidate face pairs as the algorithms read them: for every master face,
//! the slave faces whose projections may overlap it (thesis §4.2).
//!
//! [`FacePairs`] is the seam to the detection crate: it is implemented for
//! [`contact_detect::CandidatePairs`] and for a plain `[Vec<u32>]` ("slave
//! faces per master face"), so the algorithms work with either.
use crate::ContactError;
use contact_detect::CandidatePairs;

/// Slave faces per master face. Rows beyond [`FacePairs::n_master`] are
/// empty; a row may hold faces whose projections do not overlap (they are
/// skipped), duplicates are harmless but counted twice.
pub trait FacePairs {
    /// Number of rows (master faces) the pairs were built for.
    fn n_master(&self) -> usize;
    /// Slave faces paired with master face `m`.
    fn slaves_of(&self, m: usize) -> &[u32];
}

impl FacePairs for CandidatePairs {
    fn n_master(&self) -> usize {
        CandidatePairs::n_master(self)
    }
    fn slaves_of(&self, m: usize) -> &[u32] {
        CandidatePairs::slaves_of(self, m)
    }
}

/// A borrowed slice of rows: pass `&rows.as_slice()` as `&dyn FacePairs`.
impl FacePairs for &[Vec<u32>] {
    fn n_master(&self) -> usize {
        self.len()
    }
    fn slaves_of(&self, m: usize) -> &[u32] {
        self.get(m).map_or(&[], |r| r.as_slice())
    }
}

impl FacePairs for Vec<Vec<u32>> {
    fn n_master(&self) -> usize {
        self.len()
    }
    fn slaves_of(&self, m: usize) -> &[u32] {
        self.get(m).map_or(&[], |r| r.as_slice())
    }
}

/// Checks that `pairs` has at most `n_master` rows and only slave indices
/// below `n_slave`. O(pairs).
pub fn check_pairs(
    pairs: &dyn FacePairs,
    n_master: usize,
    n_slave: usize,
) -> Result<(), ContactError> {
    if pairs.n_master() > n_master {
        return Err(ContactError::InvalidPairs(format!(
            "{} rows for a master surface of {} faces",
            pairs.n_master(),
            n_master
        )));
    }
    for m in 0..pairs.n_master() {
        if let Some(&s) = pairs.slaves_of(m).iter().find(|&&s| s as usize >= n_slave) {
            return Err(ContactError::InvalidPairs(format!(
                "master face {m} is paired with slave face {s}, but the slave surface has {n_slave} faces"
            )));
        }
    }
    Ok(())
}

/// Every slave face for every master face (for tests and tiny problems;
/// O(n_master · n_slave) memory).
pub fn all_pairs(n_master: usize, n_slave: usize) -> Vec<Vec<u32>> {
    (0..n_master)
        .map(|_| (0..n_slave as u32).collect())
        .collect()
}

/// The pairs seen from the other side: master faces per slave face, rows
/// sorted. Use it to run an algorithm with master and slave swapped.
pub fn swap_pairs(pairs: &dyn FacePairs, n_slave: usize) -> Vec<Vec<u32>> {
    let mut out = vec![Vec::new(); n_slave];
    for m in 0..pairs.n_master() {
        for &s in pairs.slaves_of(m) {
            if let Some(row) = out.get_mut(s as usize) {
                row.push(m as u32);
            }
        }
    }
    for row in &mut out {
        row.sort_unstable();
        row.dedup();
    }
    out
}

/// Master faces per slave face in compressed-row form, rebuilt in place
/// (no allocation once the buffers are large enough).
#[derive(Debug, Clone, Default)]
pub(crate) struct PairsTranspose {
    offsets: Vec<u32>,
    masters: Vec<u32>,
}

impl PairsTranspose {
    /// Rebuilds from `pairs` (which must have passed [`check_pairs`]).
    pub(crate) fn build(&mut self, pairs: &dyn FacePairs, n_slave: usize) {
        self.offsets.clear();
        self.offsets.resize(n_slave + 1, 0);
        for m in 0..pairs.n_master() {
            for &s in pairs.slaves_of(m) {
                self.offsets[s as usize + 1] += 1;
            }
        }
        for s in 0..n_slave {
            self.offsets[s + 1] += self.offsets[s];
        }
        self.masters.clear();
        self.masters.resize(self.offsets[n_slave] as usize, 0);
        // fill with a moving cursor per row, then restore the offsets
        for m in 0..pairs.n_master() {
            for &s in pairs.slaves_of(m) {
                let k = &mut self.offsets[s as usize];
                self.masters[*k as usize] = m as u32;
                *k += 1;
            }
        }
        for s in (1..=n_slave).rev() {
            self.offsets[s] = self.offsets[s - 1];
        }
        self.offsets[0] = 0;
    }

    /// Master faces paired with slave face `s`, ascending.
    pub(crate) fn masters_of(&self, s: usize) -> &[u32] {
        match (self.offsets.get(s), self.offsets.get(s + 1)) {
            (Some(&a), Some(&b)) => &self.masters[a as usize..b as usize],
            _ => &[],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adapters_agree_and_transpose() {
        let rows: Vec<Vec<u32>> = vec![vec![1, 3], vec![], vec![0, 3]];
        let cp = CandidatePairs::from_pairs(3, &[(0, 1), (0, 3), (2, 0), (2, 3)]);
        for p in [
            &rows as &dyn FacePairs,
            &rows.as_slice() as &dyn FacePairs,
            &cp,
        ] {
            assert_eq!(p.n_master(), 3);
            assert_eq!(p.slaves_of(0), &[1, 3]);
            assert_eq!(p.slaves_of(7), &[] as &[u32]);
            assert!(check_pairs(p, 3, 4).is_ok());
            assert!(check_pairs(p, 2, 4).is_err());
            assert!(check_pairs(p, 3, 3).is_err());
        }
        let mut t = PairsTranspose::default();
        t.build(&rows, 4);
        assert_eq!(t.masters_of(0), &[2]);
        assert_eq!(t.masters_of(1), &[0]);
        assert_eq!(t.masters_of(2), &[] as &[u32]);
        assert_eq!(t.masters_of(3), &[0, 2]);
        assert_eq!(t.masters_of(9), &[] as &[u32]);
        assert_eq!(
            swap_pairs(&rows, 4),
            vec![vec![2], vec![0], vec![], vec![0, 2]]
        );
        assert_eq!(all_pairs(2, 2), vec![vec![0, 1], vec![0, 1]]);
    }
}
