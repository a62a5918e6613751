//! Frozen pairs: reuse the last result near convergence (thesis §4.2.2).
use crate::{CandidatePairs, DetectionStats};
use fv_mesh::Surface;

/// The last result of a detector and whether it is to be reused.
///
/// Once the outer residual is below a threshold (the thesis suggests
/// 5·10⁻⁶) the caller sets `frozen`; the detector then copies the last pairs
/// instead of searching, as long as the face counts are unchanged (otherwise
/// it searches anew and stores the new result).
#[derive(Debug, Default, Clone)]
pub struct FreezeState {
    /// Whether to reuse the last pairs.
    pub frozen: bool,
    last: CandidatePairs,
    last_sizes: Option<(usize, usize)>,
    last_stats: DetectionStats,
}

impl FreezeState {
    /// If frozen and a compatible last result exists, copies it into `out`.
    pub fn try_reuse(
        &self,
        master: &Surface,
        slave: &Surface,
        out: &mut CandidatePairs,
    ) -> Option<DetectionStats> {
        if self.frozen && self.last_sizes == Some((master.faces.len(), slave.faces.len())) {
            out.copy_from(&self.last);
            return Some(DetectionStats {
                frozen: true,
                aabb_tests: 0,
                obb_tests: 0,
                polygon_tests: 0,
                seed_searches: 0,
                repairs: 0,
                front_tests: 0,
                ..self.last_stats
            });
        }
        None
    }

    /// Records the result of a search.
    pub fn store(
        &mut self,
        master: &Surface,
        slave: &Surface,
        out: &CandidatePairs,
        stats: &DetectionStats,
    ) {
        self.last.copy_from(out);
        self.last_sizes = Some((master.faces.len(), slave.faces.len()));
        self.last_stats = *stats;
    }

    /// Forgets the last result (the frozen flag is kept).
    pub fn clear(&mut self) {
        self.last_sizes = None;
    }
}
