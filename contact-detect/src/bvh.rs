//! BVH broad phase (parry3d) followed by the OBB and local tests.
use crate::aabb::Aabb;
use crate::freeze::FreezeState;
use crate::workspace::Workspace;
use crate::{CandidatePairs, DetectError, DetectParams, DetectionMethod, DetectionStats, Detector};
use fv_mesh::Surface;
use parry3d_f64::bounding_volume::Aabb as PAabb;
use parry3d_f64::math::Vector as PVector;
use parry3d_f64::partitioning::{Bvh, BvhBuildStrategy};

/// Detection with a bounding-volume hierarchy over the AABBs of the face
/// OBBs of each surface (binned SAH build, parry3d-f64), traversed
/// simultaneously to list the overlapping leaf pairs; each is then tested
/// like in [`crate::BruteForce`] (OBB SAT, then the local phase).
///
/// Both trees are rebuilt every call (O(n log n)); expected cost
/// O(n log n + k) for k overlapping box pairs. No state is carried between
/// calls except buffers.
#[derive(Debug, Default, Clone)]
pub struct BvhDetector {
    params: DetectParams,
    ws: Workspace,
    freeze: FreezeState,
    leaves_m: Vec<PAabb>,
    leaves_s: Vec<PAabb>,
    pairs: Vec<(u32, u32)>,
}

impl BvhDetector {
    /// A BVH detector with the given parameters.
    pub fn new(params: DetectParams) -> Self {
        BvhDetector {
            params,
            ..Default::default()
        }
    }
}

fn leaves(faces: &[u32], boxes: &[Aabb], out: &mut Vec<PAabb>) {
    out.clear();
    out.extend(faces.iter().map(|&f| {
        let b = &boxes[f as usize];
        PAabb::new(
            PVector::new(b.min.x, b.min.y, b.min.z),
            PVector::new(b.max.x, b.max.y, b.max.z),
        )
    }));
}

impl Detector for BvhDetector {
    fn detect(
        &mut self,
        master: &Surface,
        slave: &Surface,
        out: &mut CandidatePairs,
    ) -> Result<DetectionStats, DetectError> {
        if let Some(stats) = self.freeze.try_reuse(master, slave, out) {
            return Ok(stats);
        }
        let ws = &mut self.ws;
        ws.prepare(master, slave, &self.params)?;
        let mut stats = ws.base_stats();
        let zm = &ws.zone.master_faces;
        let zs = &ws.zone.slave_faces;
        self.pairs.clear();
        if !zm.is_empty() && !zs.is_empty() {
            leaves(zm, &ws.master.aabb, &mut self.leaves_m);
            leaves(zs, &ws.slave.aabb, &mut self.leaves_s);
            let tm = Bvh::from_leaves(BvhBuildStrategy::Binned, &self.leaves_m);
            let ts = Bvh::from_leaves(BvhBuildStrategy::Binned, &self.leaves_s);
            for (a, b) in tm.leaf_pairs(&ts, |x, y| x.intersects(y)) {
                if let (Some(&m), Some(&s)) = (zm.get(a as usize), zs.get(b as usize)) {
                    self.pairs.push((m, s));
                }
            }
        }
        self.pairs.sort_unstable();
        self.pairs.dedup();
        let nm = master.faces.len();
        out.begin(nm);
        let mut i = 0;
        for m in 0..nm as u32 {
            while let Some(&(pm, s)) = self.pairs.get(i) {
                if pm != m {
                    break;
                }
                i += 1;
                if ws.is_pair(slave, m as usize, s as usize, &mut stats) {
                    out.push(s);
                }
            }
            out.end_row();
        }
        stats.pairs = out.n_pairs();
        self.freeze.store(master, slave, out, &stats);
        Ok(stats)
    }

    fn reset(&mut self) {
        self.freeze.clear();
    }

    fn set_frozen(&mut self, frozen: bool) {
        self.freeze.frozen = frozen;
    }

    fn is_frozen(&self) -> bool {
        self.freeze.frozen
    }

    fn method(&self) -> DetectionMethod {
        DetectionMethod::Bvh
    }
}
