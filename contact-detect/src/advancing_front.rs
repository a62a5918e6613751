//! Advancing-front detection seeded by the previous pairs (thesis §4.2.2,
//! Algorithm 2, Figs. 4.12–4.13).
use crate::freeze::FreezeState;
use crate::seed_search::SeedSearch;
use crate::workspace::Workspace;
use crate::{CandidatePairs, DetectError, DetectParams, DetectionMethod, DetectionStats, Detector};
use fv_mesh::Surface;

/// Advancing-front detection (Algorithm 2).
///
/// For every master face `m` in the contact zone, in index order:
///
/// 1. **Seeds**: the slave faces whose OBBs overlapped `m` at the previous
///    call (Fig. 4.13), and those of its master neighbours — this call's
///    for neighbours already processed, the previous call's for the others.
/// 2. **Front**: a seed whose OBB overlaps `m`'s (global phase) is
///    accepted; the edge neighbours of accepted slave faces are tested in
///    turn until no new overlapping face appears (Fig. 4.12 b–d). Each
///    slave face is tested at most once per master face (stamp array).
///    Accepted faces that pass the local phase are the pairs of `m`.
/// 3. **Seed search**: if no seed overlapped, every slave face of the zone
///    that could overlap is tested (the brute-force search of Fig. 4.12 a,
///    restricted by a sorted sweep that skips only faces whose boxes cannot
///    meet, see [`SeedSearch`]); each overlapping face not yet reached
///    starts a new front, so the result for such a face is complete
///    whatever the shape of its overlap set.
///
/// The OBB-overlap sets of this call are kept as the next call's seeds.
///
/// **Exactness**: the result equals [`crate::BruteForce`]'s whenever every
/// edge-connected component (in the slave surface) of the set of slave
/// faces whose OBBs overlap `m` contains a seed, or `m` has no overlapping
/// seed at all. This holds for the smooth, facing surfaces of contact
/// problems with the small motions between outer iterations; a master face
/// whose OBB meets two separate sheets of the slave surface (or one sheet
/// twice, across a hole) and was seeded on one only can miss the other.
///
/// **Cost**: O(k) pair tests for k tested neighbours with seeds. A seed
/// search scans a strip of the zone one box wide (O(√n_s) faces for a
/// square contact zone) after an O(n_s) sort, done once per call when
/// needed and adaptive to the previous order; a cold start pays one search
/// and reaches all connected faces from it, but a master face in the zone
/// without any slave face near it pays one search per call.
#[derive(Debug, Default, Clone)]
pub struct AdvancingFront {
    params: DetectParams,
    ws: Workspace,
    freeze: FreezeState,
    /// OBB-overlap sets of the previous call (the seeds).
    prev: CandidatePairs,
    /// OBB-overlap sets of this call.
    cur: CandidatePairs,
    prev_sizes: Option<(usize, usize)>,
    mark: Vec<u32>,
    stamp: u32,
    stack: Vec<u32>,
    seeds: SeedSearch,
}

impl AdvancingFront {
    /// An advancing-front detector with the given parameters and no seeds.
    pub fn new(params: DetectParams) -> Self {
        AdvancingFront {
            params,
            ..Default::default()
        }
    }

    /// Whether the next call will be seeded by previous results.
    pub fn has_seeds(&self) -> bool {
        self.prev_sizes.is_some()
    }
}

/// Per-master-face search state, split from the detector for borrowing.
struct Front<'a> {
    ws: &'a Workspace,
    slave: &'a Surface,
    mark: &'a mut [u32],
    stamp: u32,
    stack: &'a mut Vec<u32>,
    stats: &'a mut DetectionStats,
}

impl Front<'_> {
    /// Tests slave face `s` against master `m` once; queues it if the OBBs overlap.
    #[inline]
    fn visit(&mut self, m: usize, s: u32) {
        let si = s as usize;
        match self.mark.get_mut(si) {
            Some(k) if *k != self.stamp => *k = self.stamp,
            _ => return,
        }
        if self.ws.zone.slave_in_zone[si] && self.ws.global_test(m, si, self.stats) {
            self.stack.push(s);
        }
    }

    /// Advances the front from the queued faces; records candidates and pairs.
    fn advance(&mut self, m: usize, cur: &mut CandidatePairs, out: &mut CandidatePairs) {
        while let Some(s) = self.stack.pop() {
            cur.push(s);
            if self.ws.local_test(self.slave, m, s as usize, self.stats) {
                out.push(s);
            }
            for &n in self.slave.neighbours_of_face(s as usize) {
                self.visit(m, n);
            }
        }
    }
}

impl Detector for AdvancingFront {
    fn detect(
        &mut self,
        master: &Surface,
        slave: &Surface,
        out: &mut CandidatePairs,
    ) -> Result<DetectionStats, DetectError> {
        if let Some(stats) = self.freeze.try_reuse(master, slave, out) {
            return Ok(stats);
        }
        self.ws.prepare(master, slave, &self.params)?;
        let mut stats = self.ws.base_stats();
        let (nm, ns) = (master.faces.len(), slave.faces.len());
        let seeded = self.prev_sizes == Some((nm, ns));
        if self.mark.len() != ns {
            self.mark.clear();
            self.mark.resize(ns, 0);
            self.stamp = 0;
        }
        let Self {
            ws,
            prev,
            cur,
            mark,
            stamp,
            stack,
            seeds: search,
            ..
        } = self;
        search.invalidate();
        let ws = &*ws;
        cur.begin(nm);
        out.begin(nm);
        stack.clear();
        for m in 0..nm {
            if !ws.zone.master_in_zone[m] {
                cur.end_row();
                out.end_row();
                continue;
            }
            if *stamp == u32::MAX {
                mark.fill(0);
                *stamp = 0;
            }
            *stamp += 1;
            let mut front = Front {
                ws,
                slave,
                mark: mark.as_mut_slice(),
                stamp: *stamp,
                stack,
                stats: &mut stats,
            };
            let row_start = cur.n_pairs();
            // 1. seeds: own previous candidates, then the neighbours'
            if seeded {
                for &s in prev.slaves_of(m) {
                    front.visit(m, s);
                }
            }
            for &mn in master.neighbours_of_face(m) {
                let mn = mn as usize;
                let seeds = if mn < m {
                    cur.slaves_of(mn)
                } else if seeded {
                    prev.slaves_of(mn)
                } else {
                    &[]
                };
                for &s in seeds {
                    front.visit(m, s);
                }
            }
            // 2. advance the front
            front.advance(m, cur, out);
            // 3. exhaustive seed search when nothing overlapped
            if cur.n_pairs() == row_start {
                front.stats.seed_searches += 1;
                search.prepare(ws);
                for s in search.candidates(&ws.master.aabb[m]) {
                    front.visit(m, s);
                    front.advance(m, cur, out);
                }
            }
            cur.end_row();
            out.end_row();
        }
        cur.finish(nm);
        out.finish(nm);
        std::mem::swap(prev, cur);
        self.prev_sizes = Some((nm, ns));
        stats.pairs = out.n_pairs();
        self.freeze.store(master, slave, out, &stats);
        Ok(stats)
    }

    fn reset(&mut self) {
        self.prev_sizes = None;
        self.seeds.clear();
        self.freeze.clear();
    }

    fn set_frozen(&mut self, frozen: bool) {
        self.freeze.frozen = frozen;
    }

    fn is_frozen(&self) -> bool {
        self.freeze.frozen
    }

    fn method(&self) -> DetectionMethod {
        DetectionMethod::AdvancingFront
    }
}
