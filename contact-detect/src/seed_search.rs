//! Exhaustive seed search for the advancing front, restricted by a sorted
//! sweep along one axis (thesis Algorithm 2, line 14).
use crate::aabb::Aabb;
use crate::workspace::Workspace;
use fv_mesh::Real;

/// Slave faces of the contact zone sorted by the lower bound of their box
/// along the longest zone axis.
///
/// A seed search for master face `m` has to find every slave face whose
/// box (and so OBB) can meet `m`'s. Those faces satisfy
/// `s.min ≤ m.max` and `s.min ≥ m.min − w` along the sweep axis, `w` being
/// the largest slave box extent on it, so only that slice of the sorted
/// list is scanned: the search visits the same overlapping faces as a
/// brute-force scan of the zone, at a fraction of its cost (a strip one
/// box wide instead of the whole zone). The order is kept between calls
/// and re-sorted with an adaptive stable sort, linear for the nearly sorted
/// lists that small motions leave.
#[derive(Debug, Default, Clone)]
pub struct SeedSearch {
    entries: Vec<(Real, u32)>,
    listed: Vec<bool>,
    axis: usize,
    max_extent: Real,
    ready: bool,
}

impl SeedSearch {
    /// Marks the index stale (call at the start of every detection).
    pub fn invalidate(&mut self) {
        self.ready = false;
    }

    /// Forgets the order kept between calls.
    pub fn clear(&mut self) {
        self.entries.clear();
        self.ready = false;
    }

    /// Sorts the zone's slave faces (once per call, on first use).
    pub fn prepare(&mut self, ws: &Workspace) {
        if self.ready {
            return;
        }
        self.ready = true;
        let zone = &ws.zone;
        let ext = zone.zone.max - zone.zone.min;
        self.axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        let ns = zone.slave_in_zone.len();
        self.listed.clear();
        self.listed.resize(ns, false);
        // keep the previous order of faces still in the zone, append new ones
        let (listed, in_zone) = (&mut self.listed, &zone.slave_in_zone);
        self.entries.retain(|&(_, f)| {
            let keep = in_zone.get(f as usize).copied().unwrap_or(false) && !listed[f as usize];
            if keep {
                listed[f as usize] = true;
            }
            keep
        });
        for &f in &zone.slave_faces {
            if !self.listed[f as usize] {
                self.entries.push((0.0, f));
            }
        }
        let axis = self.axis;
        self.max_extent = 0.0;
        for e in &mut self.entries {
            let b: &Aabb = &ws.slave.aabb[e.1 as usize];
            e.0 = b.min[axis];
            self.max_extent = self.max_extent.max(b.max[axis] - b.min[axis]);
        }
        self.entries.sort_by(|a, b| a.0.total_cmp(&b.0));
    }

    /// Slave faces whose box can meet `b` along the sweep axis (a superset
    /// of those whose box meets `b`), in sweep order.
    pub fn candidates(&self, b: &Aabb) -> impl Iterator<Item = u32> + '_ {
        let lo = b.min[self.axis] - self.max_extent;
        let hi = b.max[self.axis];
        let start = self.entries.partition_point(|e| e.0 < lo);
        self.entries[start..]
            .iter()
            .take_while(move |e| e.0 <= hi)
            .map(|e| e.1)
    }
}
