//! Candidate pairs reused between searches while the surfaces move less
//! than a skin: a Verlet list of face pairs, tested exactly at every call.
use crate::aabb::Aabb;
use crate::box_bound::face_box_bound;
use crate::face_boxes::{mean_face_size, DEGENERATE_AREA};
use crate::freeze::FreezeState;
use crate::obb::FaceBoxSize;
use crate::surface_check::check_surface;
use crate::workspace::Workspace;
use crate::{CandidatePairs, DetectError, DetectParams, DetectionMethod, DetectionStats, Detector};
use fv_mesh::{Real, Surface};
use parry3d_f64::bounding_volume::Aabb as PAabb;
use parry3d_f64::math::Vector as PVector;
use parry3d_f64::partitioning::{Bvh, BvhBuildStrategy};

/// Default skin of [`PairReuse`], as a fraction of h̄.
pub const DEFAULT_SKIN: Real = 0.1;

/// A list that served fewer reuse calls than this did not pay for itself
/// (building it costs up to 1.6 advancing-front searches at 10⁵ faces).
const MIN_REUSES: usize = 8;

/// Most searches without a list after lists that did not pay.
const MAX_BACKOFF: usize = 64;

/// A detector that searches only when a face has moved out of its skin,
/// and otherwise finds the pairs among those listed at the last search:
/// the neighbour list with a skin of molecular dynamics (L. Verlet, Phys.
/// Rev. 159 (1967) 98), applied to the pair definition of the crate docs
/// (thesis §4.2, eq. 4.10), which is evaluated in full at every call.
///
/// **Search** (first call, or when the list does not hold): the inner
/// detector of the configured [`DetectionMethod`] finds the pairs. Every
/// valid face f also gets its *skin box* W_f: the bound
/// [`face_box_bound`] of its OBB (a box independent of the rectangle's
/// axes), grown by σ = `skin` · h̄ on every side. The pairs (m, s) whose
/// skin boxes meet are listed (BVH broad phase, parry3d, restricted to the
/// intersection of the two surfaces' skin boxes).
///
/// **Reuse** (every later call while the list holds): the list holds when
/// the face counts are those of the search and the bound of every face
/// that is valid now, at the current positions and h̄, lies inside its
/// skin box. Then a pair (m, s) now has overlapping OBBs, so overlapping
/// bounds, so meeting skin boxes: it is listed. The call keeps the listed
/// pairs whose current bounds meet and that pass the pair test, for which
/// it builds the boxes of their faces only (the same boxes, to the bit, as
/// a search builds): the pairs of [`crate::BruteForce`], row by row in
/// ascending order.
///
/// **Exactness**: every call returns the pair definition's set, identical
/// to the inner detector's for [`crate::BruteForce`] and
/// [`crate::BvhDetector`], and for [`crate::AdvancingFront`] wherever that
/// is exact (see there); a pair the advancing front would miss is found on
/// reuse calls. The contact algorithms thus see the same pairs in the same
/// order as without reuse.
///
/// **Cost** of a reuse call: O(face points) for the bounds of both
/// surfaces (no hull, no rectangle), the boxes of the faces of listed
/// pairs whose bounds meet, one pair test per such pair, no thread
/// hand-off and no allocation once the buffers have grown. It gains most
/// where much of a surface is away from the other (no boxes there, no
/// seed searches); where every face is in contact it costs about what a
/// warm advancing front does (the crate README's benchmark). A search
/// costs the inner detector plus the list, O(n log n) and up to 1.6
/// searches at 10⁵ faces, so a list that serves fewer than
/// 8 calls makes the next 1, 2, 4, … 64 searches go without
/// one. Between outer iterations the surfaces move a small fraction of
/// h̄, so searches are rare: with the default skin, curved beams search
/// at about 100 of 92,135 calls and die drawing at about 1,400 of
/// 165,574 (a skin of 0.03 or 0.3 changes die drawing's detection time
/// by under 3 %: fewer searches, more listed pairs to test).
pub struct PairReuse {
    inner: Box<dyn Detector + Send>,
    params: DetectParams,
    skin: Real,
    freeze: FreezeState,
    ws: Workspace,
    /// Skin box of every face, `[master, slave]` (empty: invalid at the search).
    skin_boxes: [Vec<Aabb>; 2],
    /// Bound of every face at the last check, `[master, slave]` (empty: invalid).
    bounds: [Vec<Aabb>; 2],
    /// Faces in a listed pair whose bounds meet, `[master, slave]`.
    near: [Vec<bool>; 2],
    /// The listed pairs.
    list: CandidatePairs,
    /// Face counts `(master, slave)` of the list; `None`: no list.
    list_sizes: Option<(usize, usize)>,
    /// Statistics of the last search.
    search_stats: DetectionStats,
    leaves: [Vec<PAabb>; 2],
    leaf_faces: [Vec<u32>; 2],
    pairs: Vec<(u32, u32)>,
    /// Reuse calls served by the current list.
    list_reuses: usize,
    /// Searches to go without building a list, and how many to skip after
    /// the next list that does not pay (doubling up to [`MAX_BACKOFF`]).
    skip: usize,
    backoff: usize,
    searches: usize,
    lists: usize,
    reuses: usize,
}

impl PairReuse {
    /// Reuse around a new detector of kind `method` with `params`; `skin`
    /// is σ / h̄ (finite, ≥ 0; [`DEFAULT_SKIN`]).
    pub fn new(
        method: DetectionMethod,
        params: DetectParams,
        skin: Real,
    ) -> Result<Self, DetectError> {
        if !(skin.is_finite() && skin >= 0.0) {
            return Err(DetectError::InvalidParameter {
                name: "skin",
                value: skin,
                reason: "must be finite and non-negative",
            });
        }
        Ok(PairReuse {
            inner: method.detector(params)?,
            params,
            skin,
            freeze: FreezeState::default(),
            ws: Workspace::default(),
            skin_boxes: Default::default(),
            bounds: Default::default(),
            near: Default::default(),
            list: CandidatePairs::new(),
            list_sizes: None,
            search_stats: DetectionStats::default(),
            leaves: Default::default(),
            leaf_faces: Default::default(),
            pairs: Vec::new(),
            list_reuses: 0,
            skip: 0,
            backoff: 0,
            searches: 0,
            lists: 0,
            reuses: 0,
        })
    }

    /// Calls that searched, lists built, and calls that reused a list, so far.
    pub fn counts(&self) -> (usize, usize, usize) {
        (self.searches, self.lists, self.reuses)
    }

    /// The pairs listed at the last search that built a list, while that
    /// list holds (a superset of the pairs of every call since); `None`
    /// when there is no such list.
    pub fn list(&self) -> Option<&CandidatePairs> {
        self.list_sizes.map(|_| &self.list)
    }

    fn box_size(&self, h: Real) -> (FaceBoxSize, Real) {
        let p = &self.params;
        let size = FaceBoxSize {
            extrude_out: p.extrusion_out * h,
            extrude_in: p.extrusion_in * h,
            inflation: p.inflation,
        };
        (size, DEGENERATE_AREA * h * h)
    }

    /// Whether every pair at the current positions is listed (see
    /// [`PairReuse`]); records the bounds of the faces on the way.
    fn list_holds(&mut self, surfaces: [&Surface; 2], h: Real) -> bool {
        let sizes = (surfaces[0].faces.len(), surfaces[1].faces.len());
        if self.list_sizes != Some(sizes) {
            return false;
        }
        let (size, min_area) = self.box_size(h);
        for ((s, boxes), bounds) in surfaces.iter().zip(&self.skin_boxes).zip(&mut self.bounds) {
            bounds.clear();
            for (f, skin_box) in boxes.iter().enumerate().take(s.faces.len()) {
                let b = face_box_bound(s, f, &size, min_area).unwrap_or_else(Aabb::empty);
                if !skin_box.contains_box(&b) {
                    return false;
                }
                bounds.push(b);
            }
        }
        true
    }

    /// A search: the inner detector's pairs, and a new list.
    fn search(
        &mut self,
        surfaces: [&Surface; 2],
        h: Real,
        out: &mut CandidatePairs,
    ) -> Result<DetectionStats, DetectError> {
        let mut stats = self.inner.detect(surfaces[0], surfaces[1], out)?;
        self.searches += 1;
        if self.skip > 0 {
            self.skip -= 1;
            return Ok(stats);
        }
        self.lists += 1;
        self.list_reuses = 0;
        let (size, min_area) = self.box_size(h);
        let sigma = self.skin * h;
        let mut zone = [Aabb::empty(); 2];
        for ((s, boxes), z) in surfaces.iter().zip(&mut self.skin_boxes).zip(&mut zone) {
            boxes.clear();
            boxes.extend((0..s.faces.len()).map(|f| {
                face_box_bound(s, f, &size, min_area).map_or(Aabb::empty(), |b| b.inflated(sigma))
            }));
            for b in boxes.iter() {
                z.merge(b);
            }
        }
        let zone = zone[0].intersection(&zone[1]);
        for ((boxes, leaves), faces) in self
            .skin_boxes
            .iter()
            .zip(&mut self.leaves)
            .zip(&mut self.leaf_faces)
        {
            leaves.clear();
            faces.clear();
            for (f, b) in boxes.iter().enumerate() {
                if b.intersects(&zone) {
                    leaves.push(PAabb::new(
                        PVector::new(b.min.x, b.min.y, b.min.z),
                        PVector::new(b.max.x, b.max.y, b.max.z),
                    ));
                    faces.push(f as u32);
                }
            }
        }
        self.pairs.clear();
        if !self.leaves[0].is_empty() && !self.leaves[1].is_empty() {
            let tm = Bvh::from_leaves(BvhBuildStrategy::Binned, &self.leaves[0]);
            let ts = Bvh::from_leaves(BvhBuildStrategy::Binned, &self.leaves[1]);
            let [fm, fs] = &self.leaf_faces;
            for (a, b) in tm.leaf_pairs(&ts, |x, y| x.intersects(y)) {
                if let (Some(&m), Some(&s)) = (fm.get(a as usize), fs.get(b as usize)) {
                    self.pairs.push((m, s));
                }
            }
        }
        self.pairs.sort_unstable();
        self.pairs.dedup();
        let nm = surfaces[0].faces.len();
        self.list.begin(nm);
        let mut i = 0;
        for m in 0..nm as u32 {
            while let Some(&(pm, s)) = self.pairs.get(i) {
                if pm != m {
                    break;
                }
                self.list.push(s);
                i += 1;
            }
            self.list.end_row();
        }
        debug_assert!(
            out.iter().all(|(m, s)| self.list.contains(m as usize, s)),
            "a pair of the search is not listed"
        );
        self.list_sizes = Some((nm, surfaces[1].faces.len()));
        stats.listed_pairs = self.list.n_pairs();
        self.search_stats = stats;
        Ok(stats)
    }

    /// A reuse: the listed pairs that pass the pair test now. Only the
    /// faces of listed pairs whose current bounds meet get boxes (a pair
    /// whose bounds are apart fails the first, AABB, step of the test).
    fn reuse(
        &mut self,
        surfaces: [&Surface; 2],
        h: Real,
        out: &mut CandidatePairs,
    ) -> DetectionStats {
        self.reuses += 1;
        let [bm, bs] = &self.bounds;
        for (flags, s) in self.near.iter_mut().zip(surfaces) {
            flags.clear();
            flags.resize(s.faces.len(), false);
        }
        for (m, s) in self.list.iter() {
            let (m, s) = (m as usize, s as usize);
            if bm[m].intersects(&bs[s]) {
                self.near[0][m] = true;
                self.near[1][s] = true;
            }
        }
        let [nm_flags, ns_flags] = &self.near;
        self.ws.prepare_listed(
            surfaces[0],
            surfaces[1],
            &self.params,
            h,
            [nm_flags, ns_flags],
        );
        // the zone and face counts of the last search; this call's tests
        let mut stats = DetectionStats {
            mean_cell_height: h,
            skipped_faces: self.search_stats.skipped_faces,
            master_faces_in_zone: self.search_stats.master_faces_in_zone,
            slave_faces_in_zone: self.search_stats.slave_faces_in_zone,
            listed_pairs: self.list.n_pairs(),
            reused: true,
            ..Default::default()
        };
        out.begin(surfaces[0].faces.len());
        for (m, bound) in bm.iter().enumerate() {
            for &s in self.list.slaves_of(m) {
                let su = s as usize;
                if bound.intersects(&bs[su]) && self.ws.is_pair(surfaces[1], m, su, &mut stats) {
                    out.push(s);
                }
            }
            out.end_row();
        }
        stats.pairs = out.n_pairs();
        stats
    }
}

impl Detector for PairReuse {
    fn detect(
        &mut self,
        master: &Surface,
        slave: &Surface,
        out: &mut CandidatePairs,
    ) -> Result<DetectionStats, DetectError> {
        if let Some(stats) = self.freeze.try_reuse(master, slave, out) {
            return Ok(stats);
        }
        self.params.validate()?;
        check_surface(master, "master")?;
        check_surface(slave, "slave")?;
        // h̄ as Workspace::prepare computes it
        let h = self
            .params
            .mean_cell_height
            .or_else(|| mean_face_size(master, slave))
            .unwrap_or(0.0);
        let surfaces = [master, slave];
        let stats = if self.list_holds(surfaces, h) {
            self.list_reuses += 1;
            self.reuse(surfaces, h, out)
        } else {
            if self.list_sizes.take().is_some() {
                // the list stopped holding: back off if it did not pay
                self.backoff = if self.list_reuses < MIN_REUSES {
                    (2 * self.backoff).clamp(1, MAX_BACKOFF)
                } else {
                    0
                };
                self.skip = self.backoff;
            }
            self.search(surfaces, h, out)?
        };
        self.freeze.store(master, slave, out, &stats);
        Ok(stats)
    }

    fn reset(&mut self) {
        self.inner.reset();
        self.freeze.clear();
        self.list_sizes = None;
        self.skip = 0;
        self.backoff = 0;
    }

    fn set_frozen(&mut self, frozen: bool) {
        self.freeze.frozen = frozen;
    }

    fn is_frozen(&self) -> bool {
        self.freeze.frozen
    }

    fn method(&self) -> DetectionMethod {
        self.inner.method()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BruteForce;
    use fv_mesh::generators::box_mesh;
    use fv_mesh::Vector;

    /// The top of a box below z = 0 (`master`) or the bottom of a box above.
    fn patch(n: usize, master: bool) -> Surface {
        let (min, max, name) = if master {
            (
                Vector::new(0.0, 0.0, -1.0),
                Vector::new(1.0, 1.0, 0.0),
                "zmax",
            )
        } else {
            (Vector::zeros(), Vector::repeat(1.0), "zmin")
        };
        let mesh = box_mesh(min, max, [n, n, 1], [1.0; 3]).unwrap();
        Surface::new(&mesh, mesh.patch_index(name).unwrap()).unwrap()
    }

    /// The slave patch moved rigidly (shift, rotation about z through the
    /// patch centre) and bent (z += κ r²/2), with a small per-point wobble.
    fn place(
        reference: &[Vector],
        shift: Vector,
        angle: f64,
        kappa: f64,
        wobble: f64,
    ) -> Vec<Vector> {
        let c = Vector::new(0.5, 0.5, 0.0);
        let (s, co) = angle.sin_cos();
        reference
            .iter()
            .enumerate()
            .map(|(i, x)| {
                let r = x - c;
                let w = wobble * (((i * 7919) % 17) as f64 / 17.0 - 0.5);
                let z = r.z + 0.5 * kappa * (r.x * r.x + r.y * r.y) + w;
                c + Vector::new(co * r.x - s * r.y, s * r.x + co * r.y, z) + shift
            })
            .collect()
    }

    /// Along a path of small motions (some within the skin, some beyond),
    /// the pairs equal a fresh brute-force detection on the moved surfaces
    /// at every call, and the list of the last search contains them.
    #[test]
    fn reused_pairs_equal_a_fresh_detection_on_moved_surfaces() {
        let h = 1.0 / 8.0;
        let params = DetectParams {
            mean_cell_height: Some(h),
            ..Default::default()
        };
        for method in DetectionMethod::ALL {
            let master = patch(8, true);
            let mut slave = patch(6, false);
            let reference = slave.points.clone();
            let mut reuse = PairReuse::new(method, params, DEFAULT_SKIN).unwrap();
            let mut bf = BruteForce::new(params);
            let (mut got, mut fresh) = (CandidatePairs::new(), CandidatePairs::new());
            let (mut moved_pairs, mut listed) = (0, 0);
            let mut x = 0.0;
            for k in 0..120 {
                let t = k as f64;
                // slides, sinks, turns and bends by about 0.005 h per call,
                // as between outer iterations, with a jump of 0.3 h (beyond
                // the skin) every 40 calls
                x += if k % 40 == 39 { 0.3 * h } else { 0.002 * h };
                let shift = Vector::new(x, 0.3 * x, 0.1 * h - 0.001 * h * t);
                let pts = place(
                    &reference,
                    shift,
                    0.0004 * t,
                    0.05 * (t / 40.0).sin(),
                    1e-3 * h,
                );
                slave.update_points(&pts);
                let stats = reuse.detect(&master, &slave, &mut got).unwrap();
                bf.detect(&master, &slave, &mut fresh).unwrap();
                assert_eq!(got, fresh, "{method}, call {k} (reused: {})", stats.reused);
                if let Some(list) = reuse.list() {
                    assert!(fresh.iter().all(|(m, s)| list.contains(m as usize, s)));
                    listed += 1;
                }
                assert_eq!(stats.pairs, fresh.n_pairs());
                moved_pairs += fresh.n_pairs();
            }
            assert!(moved_pairs > 1000, "the surfaces hardly met: {moved_pairs}");
            assert!(listed > 100, "{method}: a list held at {listed} calls");
            let (searches, _, reuses) = reuse.counts();
            assert!(
                reuses > 80 && searches >= 4,
                "{method}: {searches} searches, {reuses} reuses"
            );
        }
    }

    /// A face leaving its skin, a change of face counts or a reset forces a
    /// search; an unmoved surface is reused even with no skin; a list that
    /// served few calls makes the next search go without one.
    #[test]
    fn searches_when_the_list_may_not_hold() {
        let params = DetectParams::default();
        let master = patch(4, true);
        let mut slave = patch(4, false);
        let other = patch(3, false);
        let mut reuse = PairReuse::new(DetectionMethod::AdvancingFront, params, 0.0).unwrap();
        let mut out = CandidatePairs::new();
        let mut reused =
            |reuse: &mut PairReuse, s: &Surface| reuse.detect(&master, s, &mut out).unwrap().reused;
        assert!(!reused(&mut reuse, &slave));
        for _ in 0..MIN_REUSES {
            assert!(reused(&mut reuse, &slave));
        }
        // one point moved: no skin, so a search (and a list: the last paid)
        let mut pts = slave.points.clone();
        pts[0].z += 1e-6;
        slave.update_points(&pts);
        assert!(!reused(&mut reuse, &slave));
        assert!(reused(&mut reuse, &slave));
        // other face counts: a search; that list served one call, so this
        // search builds none, and the next one does
        assert!(!reused(&mut reuse, &other));
        assert!(!reused(&mut reuse, &slave));
        assert!(reused(&mut reuse, &slave));
        assert_eq!(reuse.counts(), (4, 3, MIN_REUSES + 2));
        reuse.reset();
        assert!(!reused(&mut reuse, &slave));
        assert_eq!(reuse.counts(), (5, 4, MIN_REUSES + 2));
        assert!(PairReuse::new(DetectionMethod::Bvh, params, -0.1).is_err());
        assert!(PairReuse::new(DetectionMethod::Bvh, params, f64::NAN).is_err());
    }

    /// Moving beyond the skin at every call: lists are built ever more
    /// rarely (doubling back-off), and the pairs stay exact.
    #[test]
    fn backs_off_when_lists_do_not_pay() {
        let params = DetectParams::default();
        let master = patch(6, true);
        let mut slave = patch(6, false);
        let reference = slave.points.clone();
        let mut reuse = PairReuse::new(DetectionMethod::AdvancingFront, params, 0.1).unwrap();
        let mut bf = BruteForce::new(params);
        let (mut got, mut fresh) = (CandidatePairs::new(), CandidatePairs::new());
        let h = 1.0 / 6.0;
        for k in 0..200 {
            let dx = if k % 2 == 0 { 0.0 } else { 0.3 * h };
            let pts = place(&reference, Vector::new(dx, 0.0, -0.1 * h), 0.0, 0.0, 0.0);
            slave.update_points(&pts);
            reuse.detect(&master, &slave, &mut got).unwrap();
            bf.detect(&master, &slave, &mut fresh).unwrap();
            assert_eq!(got, fresh, "call {k}");
        }
        let (searches, lists, reuses) = reuse.counts();
        assert_eq!((searches, reuses), (200, 0));
        assert!(lists <= 10, "{lists} lists");
    }
}
