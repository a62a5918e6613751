//! The output of detection: candidate slave faces of every master face (CSR).

/// Candidate pairs in compressed-row form: for master face `m`, the slave
/// faces `slaves[offsets[m]..offsets[m+1]]`, sorted ascending, without
/// duplicates.
///
/// The buffers are reused from call to call: after the first calls no
/// allocation happens unless the number of pairs grows.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct CandidatePairs {
    offsets: Vec<u32>,
    slaves: Vec<u32>,
}

impl CandidatePairs {
    /// An empty set (no master faces).
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of master faces the set was built for.
    pub fn n_master(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Total number of pairs.
    pub fn n_pairs(&self) -> usize {
        self.slaves.len()
    }

    /// Whether there is no pair at all.
    pub fn is_empty(&self) -> bool {
        self.slaves.is_empty()
    }

    /// Sorted slave faces paired with master face `m` (empty if `m` is out of range).
    pub fn slaves_of(&self, m: usize) -> &[u32] {
        match (self.offsets.get(m), self.offsets.get(m + 1)) {
            (Some(&a), Some(&b)) => &self.slaves[a as usize..b as usize],
            _ => &[],
        }
    }

    /// Whether `(m, s)` is a pair.
    pub fn contains(&self, m: usize, s: u32) -> bool {
        self.slaves_of(m).binary_search(&s).is_ok()
    }

    /// The row offsets (`n_master + 1` entries).
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// All slave indices, row after row.
    pub fn slave_indices(&self) -> &[u32] {
        &self.slaves
    }

    /// All pairs `(master, slave)` in row order.
    pub fn iter(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        (0..self.n_master())
            .flat_map(move |m| self.slaves_of(m).iter().map(move |&s| (m as u32, s)))
    }

    /// Empties the set and starts a new one; rows are then appended with
    /// [`CandidatePairs::push`] and [`CandidatePairs::end_row`] in master order.
    pub(crate) fn begin(&mut self, n_master: usize) {
        self.offsets.clear();
        self.offsets.reserve(n_master + 1);
        self.offsets.push(0);
        self.slaves.clear();
    }

    /// Appends one slave to the row being built (close it with [`CandidatePairs::end_row`]).
    #[inline]
    pub(crate) fn push(&mut self, s: u32) {
        self.slaves.push(s);
    }

    /// Closes the row being built: sorts and deduplicates it.
    pub(crate) fn end_row(&mut self) {
        let start = self.offsets.last().copied().unwrap_or(0) as usize;
        let row = &mut self.slaves[start..];
        row.sort_unstable();
        let mut w = 0;
        for r in 0..row.len() {
            if w == 0 || row[w - 1] != row[r] {
                row[w] = row[r];
                w += 1;
            }
        }
        self.slaves.truncate(start + w);
        self.offsets.push(self.slaves.len() as u32);
    }

    /// Makes `self` a copy of `other`, reusing the buffers.
    pub fn copy_from(&mut self, other: &CandidatePairs) {
        self.offsets.clear();
        self.offsets.extend_from_slice(&other.offsets);
        self.slaves.clear();
        self.slaves.extend_from_slice(&other.slaves);
    }

    /// Builds a set from `(master, slave)` pairs in any order (duplicates removed).
    pub fn from_pairs(n_master: usize, pairs: &[(u32, u32)]) -> Self {
        let mut sorted: Vec<(u32, u32)> = pairs
            .iter()
            .copied()
            .filter(|&(m, _)| (m as usize) < n_master)
            .collect();
        sorted.sort_unstable();
        sorted.dedup();
        let mut out = CandidatePairs::new();
        out.begin(n_master);
        let mut i = 0;
        for m in 0..n_master as u32 {
            while i < sorted.len() && sorted[i].0 == m {
                out.slaves.push(sorted[i].1);
                i += 1;
            }
            out.offsets.push(out.slaves.len() as u32);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_and_lookup() {
        let p = CandidatePairs::from_pairs(4, &[(2, 7), (0, 3), (2, 1), (2, 7), (9, 1)]);
        assert_eq!(p.n_master(), 4);
        assert_eq!(p.n_pairs(), 3);
        assert_eq!(p.slaves_of(0), &[3]);
        assert_eq!(p.slaves_of(1), &[] as &[u32]);
        assert_eq!(p.slaves_of(2), &[1, 7]);
        assert_eq!(p.slaves_of(3), &[] as &[u32]);
        assert_eq!(p.slaves_of(99), &[] as &[u32]);
        assert!(p.contains(2, 7) && !p.contains(2, 3));
        assert_eq!(p.iter().collect::<Vec<_>>(), vec![(0, 3), (2, 1), (2, 7)]);

        let mut q = CandidatePairs::new();
        q.begin(4);
        q.push(3);
        q.end_row();
        q.push(9);
        q.push(1);
        q.push(9);
        q.end_row();
        q.end_row();
        q.end_row();
        assert_eq!(q.slaves_of(1), &[1, 9]);
        assert_eq!(q.n_master(), 4);
        let mut r = CandidatePairs::new();
        r.copy_from(&q);
        assert_eq!(r, q);
        assert_eq!(CandidatePairs::new().n_master(), 0);
    }
}
