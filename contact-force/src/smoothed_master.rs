//! The Nagata-smoothed master surface shared by the smoothed algorithm
//! variants (thesis §4.6.1, eqs. 4.76–4.84): built from the master
//! [`Surface`] on the first call, kept in step with it on later calls, and
//! queried for the gap of a point by orthogonal projection.
//!
//! # Keeping in step without re-smoothing a rigid master
//!
//! Every call compares the master's current points with the points the
//! surface was smoothed at:
//!
//! * unchanged, or all moved by one translation (a rigid master pressed or
//!   slid along, within 10⁻¹² of the surface's extent): the smoothed
//!   surface is reused and the query points are shifted by the
//!   translation — a translated rigid master is smoothed once per run;
//! * otherwise (a deformable master, a rotating rigid one):
//!   [`NagataSurface::update_points`] refreshes normals and patches in
//!   place, without allocating.
//!
//! If the surface cannot be smoothed (non-finite points), the algorithms
//! fall back to the flat faces for that call.
use crate::auxiliary_plane::AuxiliaryPlane;
use crate::sutherland_hodgman::{Affine2, Point2};
use contact_smooth::{
    curvature_parameter, NagataSurface, PatchKind, SmoothingOptions, SymmetryPlane,
};
use fv_mesh::{Real, Surface, Vector};

/// A point's gap to the smoothed master surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SmoothedGap {
    /// Signed distance along the smoothed normal, positive outside the master.
    pub gap: Real,
    /// Unit normal of the smoothed master surface at the foot.
    pub normal: Vector,
}

/// Flat-gap band outside which the smoothed surface cannot be touched:
/// a point whose flat gap exceeds `BAND_FACTOR ×` the face's deviation
/// bound is not projected (see [`SmoothedMaster::deviation`]).
const BAND_FACTOR: Real = 2.0;

thread_local! { pub(crate) static FALLBACKS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) }; }
/// The smoothed master and what the algorithms need around it.
#[derive(Debug, Clone, Default)]
pub(crate) struct SmoothedMaster {
    options: SmoothingOptions,
    /// Symmetry planes of the master's body: normals of points on them are
    /// projected into them (thesis Fig. 4.40).
    planes: Vec<SymmetryPlane>,
    surface: Option<NagataSurface>,
    /// Current master points = smoothed points + shift.
    shift: Vector,
    /// Faces sharing a point with each face (CSR), including the face.
    ring_offsets: Vec<usize>,
    ring: Vec<usize>,
    /// The face and the faces sharing an edge with it (CSR).
    edge_ring_offsets: Vec<usize>,
    edge_ring: Vec<usize>,
    /// Per face: bound on the distance of its patch from its plane.
    deviation: Vec<Real>,
    /// Per face: whether the patches of the face and all around it are flat.
    flat_around: Vec<bool>,
    /// Per face: whether an edge of it is the master surface's border.
    border: Vec<bool>,
    /// Times the surface was built or refreshed (not counting reuse).
    refreshes: usize,
    /// Whether the surface is in step with the master of this call.
    active: bool,
}

impl SmoothedMaster {
    /// Sets the symmetry planes; the surface is smoothed anew at the next call.
    pub(crate) fn set_symmetry_planes(&mut self, planes: &[SymmetryPlane]) {
        self.planes = planes.to_vec();
        self.surface = None;
    }

    /// Brings the smoothed surface in step with `master` (see the module
    /// documentation). Returns whether smoothing is available for this call.
    pub(crate) fn sync(&mut self, master: &Surface) -> bool {
        self.active = false;
        let same_topology = self
            .surface
            .as_ref()
            .is_some_and(|s| s.n_points() == master.n_points() && s.n_faces() == master.n_faces());
        if !same_topology {
            self.surface = None;
            let Ok(s) = NagataSurface::from_surface(master, &self.planes, self.options) else {
                return false;
            };
            self.ring_offsets.clear();
            self.ring.clear();
            self.ring_offsets.push(0);
            self.edge_ring_offsets.clear();
            self.edge_ring.clear();
            self.edge_ring_offsets.push(0);
            self.border.clear();
            let mut around = Vec::new();
            for f in 0..s.n_faces() {
                if s.faces_around_face(f, &mut around).is_ok() {
                    self.ring.extend_from_slice(&around);
                }
                self.ring_offsets.push(self.ring.len());
                self.edge_ring.push(f);
                let neighbours = master.neighbours_of_face(f);
                self.edge_ring
                    .extend(neighbours.iter().map(|&g| g as usize));
                self.border.push(neighbours.len() < master.face(f).len());
                self.edge_ring_offsets.push(self.edge_ring.len());
            }
            self.surface = Some(s);
            self.shift = Vector::zeros();
            self.refreshes += 1;
            self.update_deviation();
            self.active = true;
            return true;
        }
        let Some(s) = self.surface.as_mut() else {
            return false;
        };
        if let Some(d) = uniform_translation(s.points(), &master.points) {
            self.shift = d;
            self.active = true;
            return true;
        }
        if s.update_points(&master.points).is_err() {
            return false;
        }
        self.shift = Vector::zeros();
        self.refreshes += 1;
        self.update_deviation();
        self.active = true;
        true
    }

    /// Whether the last [`SmoothedMaster::sync`] succeeded.
    #[cfg(test)]
    pub(crate) fn is_active(&self) -> bool {
        self.active
    }

    /// Times the surface was smoothed (built or refreshed) so far.
    pub(crate) fn refreshes(&self) -> usize {
        self.refreshes
    }

    /// Bound on the distance between the patch of face `f` and the face's
    /// plane (through its centre, along its normal): `¼ Σ |c|` over the
    /// edge curvature parameters (each quadratic term of eqs. 4.78–4.79 is
    /// a curvature parameter times a product of two barycentric-like
    /// coordinates, at most ¼) plus the corners' distance from the plane
    /// (warping); infinite for fans (their lifted centre is not bounded by
    /// this) so they are always projected. Exactly 0 for a flat patch
    /// (bound below 10⁻¹² of the longest side), where the smoothed gap is
    /// the flat one.
    pub(crate) fn deviation(&self, f: usize) -> Real {
        self.deviation.get(f).copied().unwrap_or(Real::INFINITY)
    }

    /// Whether the patches of face `f` and of every face around it are
    /// flat: the smoothed surface there is the faceted one.
    pub(crate) fn flat_around(&self, f: usize) -> bool {
        self.flat_around.get(f).copied().unwrap_or(false)
    }

    /// Whether a point with flat gap `flat_gap` to face `f` is too far out
    /// to touch the smoothed surface.
    pub(crate) fn clear_of(&self, f: usize, flat_gap: Real) -> bool {
        flat_gap > BAND_FACTOR * self.deviation(f)
    }

    fn update_deviation(&mut self) {
        let Some(s) = self.surface.as_ref() else {
            return;
        };
        let (x, n) = (s.points(), s.point_normals());
        let edge = s.options().edge;
        self.deviation.clear();
        for f in 0..s.n_faces() {
            let poly = s.table().face(f);
            let k = poly.len();
            let bound = match s.kind(f) {
                Some(PatchKind::Triangle) | Some(PatchKind::Quad) => {
                    let nf = s.face_normals()[f];
                    let centre = poly.iter().map(|&p| x[p]).sum::<Vector>() / k as Real;
                    let (mut b, mut size) = (0.0, 0.0);
                    for i in 0..k {
                        let (p, q) = (poly[i], poly[(i + 1) % k]);
                        size = Real::max(size, (x[q] - x[p]).norm());
                        b += 0.25 * curvature_parameter(&(x[q] - x[p]), &n[p], &n[q], &edge).norm();
                        b += (x[p] - centre).dot(&nf).abs();
                    }
                    // a flat patch (round-off aside): exactly 0
                    if b <= 1e-12 * size {
                        0.0
                    } else {
                        b
                    }
                }
                Some(PatchKind::Degenerate) => 0.0,
                _ => Real::INFINITY,
            };
            self.deviation.push(bound);
        }
        self.flat_around.clear();
        for f in 0..s.n_faces() {
            let ring = &self.ring[self.ring_offsets[f]..self.ring_offsets[f + 1]];
            self.flat_around
                .push(ring.iter().all(|&g| self.deviation[g] == 0.0));
        }
    }

    /// The faces whose patches are searched around face `f`.
    fn ring_of(&self, f: usize) -> Option<&[usize]> {
        self.ring
            .get(*self.ring_offsets.get(f)?..*self.ring_offsets.get(f + 1)?)
    }

    /// Gap of `x` (current coordinates) by the closest projection onto the
    /// patches of the faces around face `near` (thesis §4.6.1: the
    /// neighbouring patches of the face found by detection, the foot with
    /// the smallest gap). `None` when smoothing is off or every candidate
    /// is degenerate.
    pub(crate) fn gap_near(&self, x: &Vector, near: usize) -> Option<SmoothedGap> {
        let s = self.surface.as_ref().filter(|_| self.active)?;
        let ring = self.ring_of(near)?;
        let p = s.closest_projection(&(x - self.shift), ring).ok()??;
        Some(SmoothedGap {
            gap: p.signed_distance,
            normal: p.normal,
        })
    }

    /// Gap of `x` on the patches around face `f` whose orthogonal foot lies
    /// inside its patch (Newton–Raphson converged), the closest such foot;
    /// `None` if no foot does — beyond the border of the master surface,
    /// where a patch's quadratic extrapolated outside its triangle strays
    /// (1e-2 from the flat surface over faces of 0.125 at a block's edge).
    pub(crate) fn gap_inside(&self, x: &Vector, f: usize) -> Option<SmoothedGap> {
        let s = self.surface.as_ref().filter(|_| self.active)?;
        let xr = x - self.shift;
        let ring = self.ring_of(f)?;
        let mut best: Option<SmoothedGap> = None;
        for c in ring {
            if let Ok(Some(p)) = s.closest_projection(&xr, std::slice::from_ref(c)) {
                if p.inside
                    && p.converged
                    && best.is_none_or(|b| p.signed_distance.abs() < b.gap.abs())
                {
                    best = Some(SmoothedGap {
                        gap: p.signed_distance,
                        normal: p.normal,
                    });
                }
            }
        }
        best
    }

    /// Gap of `x` preferring the patch of face `f`: its orthogonal foot if
    /// it lies inside the patch, else the closest orthogonal foot on the
    /// patches sharing an edge with it, else the closest among all the
    /// faces around `f` ([`SmoothedMaster::gap_near`]) — except at the
    /// master's border, where only a foot inside its patch counts
    /// ([`SmoothedMaster::gap_inside`]): there the closest foot may lie on a
    /// patch extrapolated beyond the surface (a shallow-ironing block as
    /// master: foundation faces past the end of its arc read 0.113 mm of
    /// penetration against 0.0067 mm, flickered in and out of contact and
    /// stalled the indentation at t = 0.585).
    pub(crate) fn gap_on(&self, x: &Vector, f: usize) -> Option<SmoothedGap> {
        let s = self.surface.as_ref().filter(|_| self.active)?;
        let xr = x - self.shift;
        let edge_ring = self
            .edge_ring
            .get(*self.edge_ring_offsets.get(f)?..*self.edge_ring_offsets.get(f + 1)?)?;
        for candidates in [&edge_ring[..1], edge_ring] {
            if let Ok(Some(p)) = s.closest_projection(&xr, candidates) {
                if p.inside && p.converged {
                    return Some(SmoothedGap {
                        gap: p.signed_distance,
                        normal: p.normal,
                    });
                }
            }
        }
        if self.border.get(f).copied().unwrap_or(false) {
            self.gap_inside(x, f)
        } else {
            self.gap_near(x, f)
        }
    }

    /// Gap at the point of the auxiliary plane of master face `m` with
    /// coordinates `q`: the slave point hit by the ray along the plane's
    /// normal (flat gap `ray`, eq. 4.14) projected onto the smoothed
    /// master; the flat gap and the plane's normal where no patch is usable.
    pub(crate) fn gap_at(
        &self,
        plane: &AuxiliaryPlane,
        ray: &Affine2,
        m: usize,
        q: &Point2,
    ) -> SmoothedGap {
        let g = ray.value(q);
        let xs = plane.lift(q) + plane.normal * g;
        match self.gap_on(&xs, m) {
            Some(v) => v,
            None => {
                FALLBACKS.with(|c| c.set(c.get() + 1));
                SmoothedGap {
                    gap: g,
                    normal: plane.normal,
                }
            }
        }
    }
}

/// `Some(d)` if `now[i] = then[i] + d` for every point within a few units
/// of round-off of the coordinates (4 ε max |x|): a rigid translation
/// computed as `x₀ + d`. A looser bound (10⁻¹² of the extent) would take
/// the perturbation of a deformable master by a Newton–Krylov Jacobian
/// product (10⁻¹⁰ per point, less where the direction is small) for a
/// translation, and the product would miss the master's deformation.
fn uniform_translation(then: &[Vector], now: &[Vector]) -> Option<Vector> {
    if then.len() != now.len() {
        return None;
    }
    let (Some(a0), Some(b0)) = (then.first(), now.first()) else {
        return Some(Vector::zeros());
    };
    let d = b0 - a0;
    let magnitude = then
        .iter()
        .chain(now)
        .fold(0.0, |e: Real, x| e.max(x.amax()))
        .max(Real::MIN_POSITIVE);
    let tol = 4.0 * Real::EPSILON * magnitude;
    // written so that a NaN anywhere fails
    let small = |v: Vector| v.iter().all(|c| c.abs() <= tol);
    (magnitude.is_finite() && then.iter().zip(now).all(|(a, b)| small(b - a - d))).then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fv_mesh::generators::annulus_mesh;

    fn arc() -> Surface {
        let m = annulus_mesh(0.5, 1.0, 0.2, 1.2, 0.0, 0.1, [1, 10, 1], 1.0).unwrap();
        Surface::new(&m, m.patch_index("outer").unwrap()).unwrap()
    }

    #[test]
    fn translation_reuses_rotation_refreshes() {
        let mut s = arc();
        let mut sm = SmoothedMaster::default();
        assert!(sm.sync(&s));
        assert_eq!(sm.refreshes(), 1);
        // a point outside the unit cylinder, between two facets
        let x = Vector::new(1.1 * 0.7f64.cos(), 1.1 * 0.7f64.sin(), 0.05);
        let g0 = sm.gap_near(&x, 5).unwrap();
        assert!((g0.gap - 0.1).abs() < 1e-4, "{}", g0.gap);
        let d = Vector::new(0.3, -0.2, 0.1);
        let moved: Vec<Vector> = s.points.iter().map(|p| p + d).collect();
        s.update_points(&moved);
        assert!(sm.sync(&s));
        assert_eq!(sm.refreshes(), 1);
        let g1 = sm.gap_near(&(x + d), 5).unwrap();
        assert!((g1.gap - g0.gap).abs() < 1e-13);
        assert!((g1.normal - g0.normal).norm() < 1e-13);
        // a rotation about z: refreshed in place
        let (c, si) = (0.1f64.cos(), 0.1f64.sin());
        let rotated: Vec<Vector> = moved
            .iter()
            .map(|p| Vector::new(c * p.x - si * p.y, si * p.x + c * p.y, p.z))
            .collect();
        s.update_points(&rotated);
        assert!(sm.sync(&s));
        assert_eq!(sm.refreshes(), 2);
        // non-finite points: smoothing off for this call, no panic
        let mut bad = rotated.clone();
        bad[0].x = Real::NAN;
        s.update_points(&bad);
        assert!(!sm.sync(&s) && !sm.is_active());
        assert!(sm.gap_near(&x, 5).is_none());
    }

    /// Past the end of the arc (θ from 0.2 to 1.2) the closest foot is on
    /// the end face's patch extrapolated beyond it; the end face is at the
    /// border, so `gap_on` takes only feet inside their patch (none here),
    /// and the algorithms use the flat gap. Inside the arc both agree.
    #[test]
    fn border_faces_take_only_feet_inside_their_patch() {
        let s = arc();
        let mut sm = SmoothedMaster::default();
        assert!(sm.sync(&s));
        let at = |theta: f64, r: f64| Vector::new(r * theta.cos(), r * theta.sin(), 0.05);
        let end = (0..s.n_faces())
            .max_by(|&a, &b| {
                let angle = |f: usize| s.face_centres[f].y.atan2(s.face_centres[f].x);
                angle(a).total_cmp(&angle(b))
            })
            .unwrap();
        let beyond = at(1.3, 0.99);
        assert!(sm.gap_near(&beyond, end).is_some());
        assert!(sm.gap_on(&beyond, end).is_none());
        let inside = at(0.7, 0.99);
        let (on, near) = (
            sm.gap_on(&inside, 5).unwrap(),
            sm.gap_near(&inside, 5).unwrap(),
        );
        assert!((on.gap - near.gap).abs() < 1e-12, "{} {}", on.gap, near.gap);
        assert!(on.gap < 0.0, "{}", on.gap);
    }

    #[test]
    fn symmetry_plane_normals_lie_in_the_plane() {
        // an arc of the unit cylinder from θ = 0: its end is on the plane y = 0
        let m = annulus_mesh(0.5, 1.0, 0.0, 1.0, 0.0, 0.1, [1, 10, 1], 1.0).unwrap();
        let s = Surface::new(&m, m.patch_index("outer").unwrap()).unwrap();
        let on_plane = |sm: &SmoothedMaster| -> Vec<Vector> {
            let ns = sm.surface.as_ref().unwrap();
            (0..ns.n_points())
                .filter(|&p| ns.points()[p].y.abs() < 1e-12)
                .map(|p| ns.point_normals()[p])
                .collect()
        };
        let mut free = SmoothedMaster::default();
        assert!(free.sync(&s));
        // one facet's normal: tilted by half the facet angle, 0.05 rad
        for n in on_plane(&free) {
            assert!((n.y - 0.05f64.sin()).abs() < 1e-6, "{n:?}");
        }
        let mut sym = SmoothedMaster::default();
        sym.set_symmetry_planes(&[SymmetryPlane::new(Vector::zeros(), Vector::y())]);
        assert!(sym.sync(&s));
        let normals = on_plane(&sym);
        assert_eq!(normals.len(), 2);
        for n in normals {
            // the cylinder's own normal (1, 0, 0)
            assert!((n - Vector::x()).norm() < 1e-12, "{n:?}");
        }
    }

    #[test]
    fn deviation_bounds_the_patch() {
        let s = arc();
        let mut sm = SmoothedMaster::default();
        assert!(sm.sync(&s));
        let ns = sm.surface.as_ref().unwrap();
        for f in 0..s.n_faces() {
            let (c, n) = (s.face_centres[f], s.face_normals[f]);
            let dev = sm.deviation(f);
            // inside the arc: twice the sagitta h²/8R of its chord h = 0.1;
            // the end faces' border point normals are their face normals,
            // not symmetric about the chord, and the capped curvature
            // parameter makes their bound (not their patch) large
            if f > 0 && f + 1 < s.n_faces() {
                assert!((dev - 2.0 * 0.01 / 8.0).abs() < 1e-5, "{dev}");
            }
            for i in 0..=10 {
                for j in 0..=10 {
                    let local = contact_smooth::LocalCoords {
                        sub: 0,
                        eta: i as Real / 10.0,
                        zeta: j as Real / 10.0,
                    };
                    let p = ns.point_at(f, local).unwrap();
                    assert!((p - c).dot(&n).abs() <= dev * (1.0 + 1e-12));
                }
            }
        }
    }
}
