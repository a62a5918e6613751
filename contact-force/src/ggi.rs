//! Generalised grid interface (GGI) area weights (thesis §4.1.3, eqs.
//! 4.5–4.9): the intersection areas of master and slave faces, projected on
//! the auxiliary plane of the master face (steps a–c of §4.4).
use crate::auxiliary_plane::{AuxiliaryPlane, AREA_TOLERANCE, MIN_FACING_COSINE};
use crate::face_pairs::FacePairs;
use crate::sutherland_hodgman::{clip_convex, signed_area, ClipScratch, Point2};
use fv_mesh::{Real, Surface};
use std::ops::{AddAssign, Mul};

/// Intersection areas |Γ_m,j ∩ Γ_s,k| in compressed rows, both ways
/// (master → slaves and slave → masters), with the face areas that turn
/// them into the weights of eq. 4.7:
/// `ω_{j,k} = |Γ_m,j ∩ Γ_s,k| / |Γ_m,j|`, `ω_{k,j} = |Γ_s,k ∩ Γ_m,j| / |Γ_s,k|`.
///
/// The segment-to-segment algorithm fills it as a by-product; the
/// pointwise algorithm builds it with [`GgiWeights::build`]. Buffers are
/// reused from call to call.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GgiWeights {
    pub(crate) master_offsets: Vec<u32>,
    pub(crate) master_slaves: Vec<u32>,
    pub(crate) master_overlap: Vec<Real>,
    pub(crate) slave_offsets: Vec<u32>,
    pub(crate) slave_masters: Vec<u32>,
    pub(crate) slave_overlap: Vec<Real>,
    pub(crate) master_area: Vec<Real>,
    pub(crate) slave_area: Vec<Real>,
}

impl GgiWeights {
    /// Empty weights (no faces).
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of master faces.
    pub fn n_master(&self) -> usize {
        self.master_area.len()
    }

    /// Number of slave faces.
    pub fn n_slave(&self) -> usize {
        self.slave_area.len()
    }

    /// Number of overlapping pairs.
    pub fn n_pairs(&self) -> usize {
        self.master_slaves.len()
    }

    /// Slave faces overlapping master face `m` and the intersection areas.
    pub fn master_row(&self, m: usize) -> (&[u32], &[Real]) {
        match (self.master_offsets.get(m), self.master_offsets.get(m + 1)) {
            (Some(&a), Some(&b)) => (
                &self.master_slaves[a as usize..b as usize],
                &self.master_overlap[a as usize..b as usize],
            ),
            _ => (&[], &[]),
        }
    }

    /// Master faces overlapping slave face `s` and the intersection areas.
    pub fn slave_row(&self, s: usize) -> (&[u32], &[Real]) {
        match (self.slave_offsets.get(s), self.slave_offsets.get(s + 1)) {
            (Some(&a), Some(&b)) => (
                &self.slave_masters[a as usize..b as usize],
                &self.slave_overlap[a as usize..b as usize],
            ),
            _ => (&[], &[]),
        }
    }

    /// Σ_k ω_{j,k} for master face `m` (1 when fully covered, eq. 4.9).
    pub fn master_coverage(&self, m: usize) -> Real {
        let a = self.master_area.get(m).copied().unwrap_or(0.0);
        if a > 0.0 {
            self.master_row(m).1.iter().sum::<Real>() / a
        } else {
            0.0
        }
    }

    /// Σ_j ω_{k,j} for slave face `s` (eq. 4.9).
    pub fn slave_coverage(&self, s: usize) -> Real {
        let a = self.slave_area.get(s).copied().unwrap_or(0.0);
        if a > 0.0 {
            self.slave_row(s).1.iter().sum::<Real>() / a
        } else {
            0.0
        }
    }

    /// Master face values from slave face values (eq. 4.5):
    /// `φ_m,j = Σ_k ω_{j,k} φ_s,k`. With `normalise`, divided by Σ_k ω_{j,k}
    /// (the proportional correction for partial covering, §4.1.3); faces
    /// without overlap get `T::default()` (zero). O(pairs).
    pub fn to_master<T>(&self, slave_values: &[T], out: &mut [T], normalise: bool)
    where
        T: Copy + Default + AddAssign + Mul<Real, Output = T>,
    {
        for (m, o) in out.iter_mut().enumerate().take(self.n_master()) {
            let (faces, areas) = self.master_row(m);
            *o = interpolate(faces, areas, self.master_area[m], slave_values, normalise);
        }
    }

    /// Slave face values from master face values (eq. 4.6), as
    /// [`GgiWeights::to_master`].
    pub fn to_slave<T>(&self, master_values: &[T], out: &mut [T], normalise: bool)
    where
        T: Copy + Default + AddAssign + Mul<Real, Output = T>,
    {
        for (s, o) in out.iter_mut().enumerate().take(self.n_slave()) {
            let (faces, areas) = self.slave_row(s);
            *o = interpolate(faces, areas, self.slave_area[s], master_values, normalise);
        }
    }

    /// Starts a new set for the given surfaces (rows are then appended in
    /// master order with [`GgiWeights::push`] / [`GgiWeights::end_row`]).
    pub(crate) fn begin(&mut self, master: &Surface, slave: &Surface) {
        self.master_offsets.clear();
        self.master_offsets.push(0);
        self.master_slaves.clear();
        self.master_overlap.clear();
        self.master_area.clear();
        self.master_area.extend_from_slice(&master.face_mag);
        self.slave_area.clear();
        self.slave_area.extend_from_slice(&slave.face_mag);
    }

    /// Adds intersection area `area` between the current master face and slave face `s`.
    #[inline]
    pub(crate) fn push(&mut self, s: u32, area: Real) {
        self.master_slaves.push(s);
        self.master_overlap.push(area);
    }

    /// Closes the current master row.
    #[inline]
    pub(crate) fn end_row(&mut self) {
        self.master_offsets.push(self.master_slaves.len() as u32);
    }

    /// Pads missing master rows and builds the slave → master rows.
    pub(crate) fn finish(&mut self) {
        let nm = self.master_area.len();
        let last = *self.master_offsets.last().unwrap_or(&0);
        self.master_offsets.resize(nm + 1, last);
        let ns = self.slave_area.len();
        self.slave_offsets.clear();
        self.slave_offsets.resize(ns + 1, 0);
        for &s in &self.master_slaves {
            self.slave_offsets[s as usize + 1] += 1;
        }
        for s in 0..ns {
            self.slave_offsets[s + 1] += self.slave_offsets[s];
        }
        self.slave_masters.clear();
        self.slave_masters.resize(self.master_slaves.len(), 0);
        self.slave_overlap.clear();
        self.slave_overlap.resize(self.master_slaves.len(), 0.0);
        for m in 0..nm {
            let (a, b) = (
                self.master_offsets[m] as usize,
                self.master_offsets[m + 1] as usize,
            );
            for k in a..b {
                let s = self.master_slaves[k] as usize;
                let at = self.slave_offsets[s] as usize;
                self.slave_masters[at] = m as u32;
                self.slave_overlap[at] = self.master_overlap[k];
                self.slave_offsets[s] += 1;
            }
        }
        for s in (1..=ns).rev() {
            self.slave_offsets[s] = self.slave_offsets[s - 1];
        }
        self.slave_offsets[0] = 0;
    }

    /// Computes the weights from the geometry (steps a–c of §4.4 for every
    /// candidate pair): the slave face projected on the auxiliary plane of
    /// the master face, clipped by the projected master face. Pairs that do
    /// not face each other (see [`MIN_FACING_COSINE`]) or involve a
    /// degenerate face get no weight. `pairs` must have passed
    /// [`crate::check_pairs`]. O(pairs · points²).
    pub fn build(
        &mut self,
        master: &Surface,
        slave: &Surface,
        pairs: &dyn FacePairs,
        scratch: &mut GgiScratch,
    ) {
        self.begin(master, slave);
        for m in 0..master.n_faces() {
            if let Some(plane) = AuxiliaryPlane::of_face(master, m) {
                plane.project_face(master, m, &mut scratch.master);
                for &s in pairs.slaves_of(m) {
                    let su = s as usize;
                    if AuxiliaryPlane::of_face(slave, su).is_none()
                        || !(plane.normal.dot(&slave.face_normals[su]) <= -MIN_FACING_COSINE)
                    {
                        continue;
                    }
                    plane.project_face(slave, su, &mut scratch.slave);
                    clip_convex(
                        &scratch.slave,
                        &scratch.master,
                        &mut scratch.segment,
                        &mut scratch.clip,
                    );
                    let area = signed_area(&scratch.segment);
                    if area > AREA_TOLERANCE * master.face_mag[m] {
                        self.push(s, area);
                    }
                }
            }
            self.end_row();
        }
        self.finish();
    }
}

/// Buffers of [`GgiWeights::build`].
#[derive(Debug, Clone, Default)]
pub struct GgiScratch {
    master: Vec<Point2>,
    slave: Vec<Point2>,
    segment: Vec<Point2>,
    clip: ClipScratch,
}

fn interpolate<T>(faces: &[u32], areas: &[Real], own_area: Real, values: &[T], normalise: bool) -> T
where
    T: Copy + Default + AddAssign + Mul<Real, Output = T>,
{
    let mut acc = T::default();
    let mut sum = 0.0;
    for (&f, &a) in faces.iter().zip(areas) {
        if let Some(&v) = values.get(f as usize) {
            acc += v * a;
            sum += a;
        }
    }
    let denom = if normalise { sum } else { own_area };
    if denom > 0.0 {
        acc * (1.0 / denom)
    } else {
        T::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::face_pairs::all_pairs;
    use fv_mesh::generators::box_mesh;
    use fv_mesh::Vector;

    fn patch(n: [usize; 2], z0: Real, z1: Real, name: &str) -> Surface {
        let m = box_mesh(
            Vector::new(0.0, 0.0, z0),
            Vector::new(1.0, 1.0, z1),
            [n[0], n[1], 1],
            [1.0; 3],
        )
        .unwrap();
        Surface::new(&m, m.patch_index(name).unwrap()).unwrap()
    }

    #[test]
    fn weights_sum_to_one_on_matching_squares() {
        let master = patch([4, 4], -1.0, 0.0, "zmax");
        let slave = patch([7, 5], 0.0, 1.0, "zmin");
        let pairs = all_pairs(16, 35);
        let mut w = GgiWeights::new();
        w.build(&master, &slave, &pairs, &mut GgiScratch::default());
        for m in 0..16 {
            assert!((w.master_coverage(m) - 1.0).abs() < 1e-13);
        }
        for s in 0..35 {
            assert!((w.slave_coverage(s) - 1.0).abs() < 1e-13);
        }
        // a linear field is transferred with the face-centre error only; a
        // constant exactly, both ways
        let ones = vec![2.5; 35];
        let mut out = vec![0.0; 16];
        w.to_master(&ones, &mut out, false);
        assert!(out.iter().all(|&x| (x - 2.5).abs() < 1e-13));
        let vs = vec![Vector::new(1.0, -2.0, 3.0); 16];
        let mut back = vec![Vector::zeros(); 35];
        w.to_slave(&vs, &mut back, true);
        assert!(back.iter().all(|v| (v - vs[0]).norm() < 1e-13));
        // total area conserved
        let total: Real = (0..16)
            .map(|m| w.master_row(m).1.iter().sum::<Real>())
            .sum();
        assert!((total - 1.0).abs() < 1e-13);
        // facing the same way: no weights
        let wrong = patch([7, 5], 0.0, 1.0, "zmax");
        w.build(&master, &wrong, &pairs, &mut GgiScratch::default());
        assert_eq!(w.n_pairs(), 0);
        assert_eq!(w.master_coverage(0), 0.0);
    }
}
