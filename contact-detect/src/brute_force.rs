//! Brute-force detection: every master face against every slave face of the
//! contact zone (thesis §4.2.2, "naive brute force"); the reference.
use crate::freeze::FreezeState;
use crate::workspace::Workspace;
use crate::{CandidatePairs, DetectError, DetectParams, DetectionMethod, DetectionStats, Detector};
use fv_mesh::Surface;

/// All-to-all detection inside the contact zone: O(n_m · n_s) pair tests
/// (each starting with a cheap AABB test). The reference the other
/// detectors must reproduce exactly.
#[derive(Debug, Default, Clone)]
pub struct BruteForce {
    params: DetectParams,
    ws: Workspace,
    freeze: FreezeState,
}

impl BruteForce {
    /// A brute-force detector with the given parameters.
    pub fn new(params: DetectParams) -> Self {
        BruteForce {
            params,
            ..Default::default()
        }
    }
}

impl Detector for BruteForce {
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
        let nm = master.faces.len();
        out.begin(nm);
        for m in 0..nm {
            if ws.zone.master_in_zone[m] {
                for &s in &ws.zone.slave_faces {
                    if ws.is_pair(slave, m, s as usize, &mut stats) {
                        out.push(s);
                    }
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
        DetectionMethod::BruteForce
    }
}
