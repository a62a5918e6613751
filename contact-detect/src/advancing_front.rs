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
/// 1. **Seeds** (Fig. 4.13): the slave faces of `m`'s front at the
///    previous call, and this call's fronts of its master neighbours
///    already processed (lower index).
/// 2. **Front** (Fig. 4.12 b–d): a seed is accepted if its projection onto
///    the plane of `m` overlaps polygon `m` — the local phase alone, blind
///    to the distance along the normal ([`Workspace::front_test`], after a
///    cheap bounding-disc test). The faces sharing a *point* with an
///    accepted face are tested in turn, until no new face is accepted;
///    each slave face is tested at most once per master face (stamp
///    array). Accepted faces that also pass the global phase (AABB, then
///    OBB SAT) are the pairs of `m`: the pair definition is unchanged.
/// 3. **Seed search** (Fig. 4.12 a): if no seed was accepted, every slave
///    face of the zone whose box AABB meets `m`'s is tried as a seed (a
///    brute-force search, restricted by a sorted sweep that skips only
///    faces whose boxes cannot meet, see [`SeedSearch`]); each accepted
///    face not reached yet starts a new front. Every pair of `m` is among
///    the faces tried, so the result for such a face is complete.
/// 4. **Repair**: a face in the front of a neighbour processed later, not
///    in the front of `m` but passing its front condition, seeds `m` again;
///    grown fronts propagate to their neighbours until nothing changes
///    (a rare, allocating path; the check itself costs a few lookups per
///    face). The fronts are thus closed over face adjacency on both surfaces.
///
/// The fronts of this call are kept as the next call's seeds. Because the
/// front ignores the distance along the normal, it follows the slave faces
/// under each master face while the surfaces approach, separate or dip in
/// and out of the detection band of eq. (4.10).
///
/// **Exactness**: the result equals [`crate::BruteForce`]'s whenever every
/// pair `(m, s)` is linked to a seed by a chain of steps that keep the
/// front condition: to a slave face sharing a point, or to a master face
/// sharing an edge. In particular it holds where the slave surface over
/// each master face is a single sheet (no fold in the projection along
/// the master normal, no hole, no concave border bay across the face), or
/// where neighbouring master faces bridge such gaps, which covers contact
/// between the outer iterations. Two separate contact regions that share
/// no master face are found separately by seed searches. A sheet reached
/// by no chain (say a second sheet under master faces that already see a
/// first one) can be missed: the limitation the thesis accepts for
/// Algorithm 2. The property tests (`tests/suite/pair_sets.rs`) check the
/// equality on random perturbed, rotated, tilted and curved grids of
/// quadrilaterals and triangles.
///
/// **Cost**: O(k) tests for the k faces of the fronts and their point
/// neighbours. A seed search scans a strip of the zone one box wide
/// (O(√n_s) faces for a square zone) after a sort done once per call when
/// needed and adaptive to the previous order; a cold start pays one search
/// per connected contact region, but a master face in the zone with no
/// slave face under it pays one search per call.
#[derive(Debug, Default, Clone)]
pub struct AdvancingFront {
    params: DetectParams,
    ws: Workspace,
    freeze: FreezeState,
    /// Fronts of the previous call (the seeds).
    prev: CandidatePairs,
    /// Fronts of this call.
    cur: CandidatePairs,
    prev_sizes: Option<(usize, usize)>,
    buf: Buffers,
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
    /// Faces accepted into the front of the current master face.
    row: &'a mut Vec<u32>,
    /// Pairs of the current master face.
    pairs: &'a mut Vec<u32>,
    stats: &'a mut DetectionStats,
}

impl Front<'_> {
    /// Tests slave face `s` against master `m` once; queues it if its
    /// projection overlaps polygon `m` (the front condition).
    #[inline]
    fn visit(&mut self, m: usize, s: u32) {
        let si = s as usize;
        match self.mark.get_mut(si) {
            Some(k) if *k != self.stamp => *k = self.stamp,
            _ => return,
        }
        if self.ws.front_test(self.slave, m, si, self.stats) {
            self.stack.push(s);
        }
    }

    /// Seed search: visits `s` if it is unvisited and its box AABB meets `m`'s.
    #[inline]
    fn visit_if_near(&mut self, m: usize, s: u32) {
        let si = s as usize;
        match self.mark.get(si) {
            Some(&k) if k != self.stamp => {}
            _ => return,
        }
        if self.ws.aabb_test(m, si, self.stats) {
            self.visit(m, s);
        }
    }

    /// Advances the front from the queued faces; records the front and the pairs.
    fn advance(&mut self, m: usize) {
        while let Some(s) = self.stack.pop() {
            self.row.push(s);
            let si = s as usize;
            // the local phase passed in the front condition
            if self.ws.zone.slave_in_zone[si] && self.ws.global_test(m, si, self.stats) {
                self.pairs.push(s);
            }
            for &p in self.slave.face(si) {
                for &n in self.slave.faces_of_point(p as usize) {
                    self.visit(m, n);
                }
            }
        }
    }
}

/// A fresh stamp for the visited marks (clearing them on wrap-around).
fn next_stamp(mark: &mut [u32], stamp: &mut u32) -> u32 {
    if *stamp == u32::MAX {
        mark.fill(0);
        *stamp = 0;
    }
    *stamp += 1;
    *stamp
}

/// Buffers of the advancing front, reused between calls.
#[derive(Debug, Default, Clone)]
struct Buffers {
    mark: Vec<u32>,
    stamp: u32,
    stack: Vec<u32>,
    row: Vec<u32>,
    pairs: Vec<u32>,
    repairs: Vec<(u32, u32)>,
}

impl AdvancingFront {
    /// Main pass: every master face of the zone, seeded by the previous
    /// fronts and by its neighbours' fronts.
    fn main_pass(
        &mut self,
        master: &Surface,
        slave: &Surface,
        seeded: bool,
        out: &mut CandidatePairs,
        stats: &mut DetectionStats,
    ) {
        let nm = master.faces.len();
        let Self {
            ws,
            prev,
            cur,
            buf,
            seeds: search,
            ..
        } = self;
        let ws = &*ws;
        cur.begin(nm);
        out.begin(nm);
        buf.stack.clear();
        for m in 0..nm {
            if !ws.zone.master_in_zone[m] {
                cur.end_row();
                out.end_row();
                continue;
            }
            let stamp = next_stamp(&mut buf.mark, &mut buf.stamp);
            buf.row.clear();
            buf.pairs.clear();
            let mut front = Front {
                ws,
                slave,
                mark: &mut buf.mark,
                stamp,
                stack: &mut buf.stack,
                row: &mut buf.row,
                pairs: &mut buf.pairs,
                stats,
            };
            // 1. seeds: own previous front, then the neighbours'
            if seeded {
                for &s in prev.slaves_of(m) {
                    front.visit(m, s);
                }
            }
            for &mn in master.neighbours_of_face(m) {
                let mn = mn as usize;
                if mn < m {
                    for &s in cur.slaves_of(mn) {
                        front.visit(m, s);
                    }
                }
            }
            // 2. advance the front
            front.advance(m);
            // 3. exhaustive seed search when no seed was accepted
            if front.row.is_empty() {
                front.stats.seed_searches += 1;
                search.prepare(ws);
                for s in search.candidates(&ws.master.aabb[m]) {
                    front.visit_if_near(m, s);
                    front.advance(m);
                }
            }
            for &s in buf.row.iter() {
                cur.push(s);
            }
            for &s in buf.pairs.iter() {
                out.push(s);
            }
            cur.end_row();
            out.end_row();
        }
    }

    /// Lists `(m, s)` where `s` is in the front of a neighbour `m' > m`
    /// (processed after `m`, so not offered to it), not in `m`'s front, and
    /// passes `m`'s front condition.
    fn find_repairs(&mut self, master: &Surface, slave: &Surface, stats: &mut DetectionStats) {
        let Self { ws, cur, buf, .. } = self;
        buf.repairs.clear();
        for m in 0..master.faces.len() {
            if !ws.zone.master_in_zone[m] {
                continue;
            }
            let stamp = next_stamp(&mut buf.mark, &mut buf.stamp);
            let own = cur.slaves_of(m);
            for &mn in master.neighbours_of_face(m) {
                if (mn as usize) <= m {
                    continue;
                }
                for &s in cur.slaves_of(mn as usize) {
                    let k = &mut buf.mark[s as usize];
                    if *k == stamp {
                        continue;
                    }
                    *k = stamp;
                    if own.binary_search(&s).is_err() && ws.front_test(slave, m, s as usize, stats)
                    {
                        buf.repairs.push((m as u32, s));
                    }
                }
            }
        }
    }

    /// Slow path, taken when [`Self::find_repairs`] found something: grows
    /// the fronts from the missed seeds and propagates to neighbours until
    /// no front changes, then rebuilds the rows.
    fn repair(
        &mut self,
        master: &Surface,
        slave: &Surface,
        out: &mut CandidatePairs,
        stats: &mut DetectionStats,
    ) {
        let nm = master.faces.len();
        let Self { ws, cur, buf, .. } = self;
        let ws = &*ws;
        let mut rows: Vec<Vec<u32>> = (0..nm).map(|m| cur.slaves_of(m).to_vec()).collect();
        let mut prs: Vec<Vec<u32>> = (0..nm).map(|m| out.slaves_of(m).to_vec()).collect();
        let mut pending: Vec<Vec<u32>> = vec![Vec::new(); nm];
        let mut queued = vec![false; nm];
        let mut queue = std::collections::VecDeque::new();
        for &(m, s) in &buf.repairs {
            pending[m as usize].push(s);
            if !queued[m as usize] {
                queued[m as usize] = true;
                queue.push_back(m as usize);
            }
        }
        while let Some(m) = queue.pop_front() {
            queued[m] = false;
            let stamp = next_stamp(&mut buf.mark, &mut buf.stamp);
            for &s in &rows[m] {
                buf.mark[s as usize] = stamp;
            }
            buf.row.clear();
            buf.pairs.clear();
            let mut front = Front {
                ws,
                slave,
                mark: &mut buf.mark,
                stamp,
                stack: &mut buf.stack,
                row: &mut buf.row,
                pairs: &mut buf.pairs,
                stats,
            };
            for s in std::mem::take(&mut pending[m]) {
                front.visit(m, s);
            }
            front.advance(m);
            if buf.row.is_empty() {
                continue;
            }
            rows[m].extend_from_slice(&buf.row);
            prs[m].extend_from_slice(&buf.pairs);
            for &mn in master.neighbours_of_face(m) {
                let mn = mn as usize;
                if !ws.zone.master_in_zone[mn] {
                    continue;
                }
                for &s in buf.row.iter() {
                    if !rows[mn].contains(&s)
                        && !pending[mn].contains(&s)
                        && ws.front_test(slave, mn, s as usize, stats)
                    {
                        pending[mn].push(s);
                        if !queued[mn] {
                            queued[mn] = true;
                            queue.push_back(mn);
                        }
                    }
                }
            }
        }
        cur.begin(nm);
        out.begin(nm);
        for m in 0..nm {
            for &s in &rows[m] {
                cur.push(s);
            }
            for &s in &prs[m] {
                out.push(s);
            }
            cur.end_row();
            out.end_row();
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
        if self.buf.mark.len() != ns {
            self.buf.mark.clear();
            self.buf.mark.resize(ns, 0);
            self.buf.stamp = 0;
        }
        self.seeds.invalidate();
        self.main_pass(master, slave, seeded, out, &mut stats);
        self.find_repairs(master, slave, &mut stats);
        if !self.buf.repairs.is_empty() {
            stats.repairs = self.buf.repairs.len();
            self.repair(master, slave, out, &mut stats);
        }
        std::mem::swap(&mut self.prev, &mut self.cur);
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
