//! The smoothed surface: one Nagata patch per face, built from points, face
//! polygons and optional symmetry planes; refreshed in place by
//! [`NagataSurface::update_points`] (a rigid master is smoothed once).
//!
//! # Which patch a face gets
//!
//! | face (after removal of repeated indices)            | patch                                   |
//! |-----------------------------------------------------|-----------------------------------------|
//! | fewer than 3 points, or area ≤ 10⁻¹² × (longest side)² | [`PatchKind::Degenerate`]: skipped      |
//! | triangle                                            | [`TrianglePatch`] (eq. 4.78)            |
//! | quadrilateral, every corner convex (sin α > 10⁻⁴)   | [`QuadPatch`] (eq. 4.79)                |
//! | other quadrilaterals, polygons of 5+ points          | fan of triangles around a centre ([`crate::fan_centre`]) |
//!
//! The kind can change at an update (a quadrilateral folding into a dart
//! becomes a fan); storage for all kinds a face can take is allocated at
//! construction, so updates do not allocate.
//!
//! Orientation: patch normals follow the right-hand rule of the face's
//! vertex order, as the face area vectors do (out of the body for
//! `fv_mesh` boundary faces).
use crate::edge_curve::EdgeCurveParams;
use crate::face_geometry::polygon_centre_area;
use crate::face_table::FaceTable;
use crate::patch::NagataPatch;
use crate::point_normals::{PointNormalParams, PointNormals, SymmetryPlane};
use crate::polygon_fan::fan_centre;
use crate::projection::{project_onto_patch, PatchProjection, ProjectionParams};
use crate::quad_patch::QuadPatch;
use crate::triangle_patch::TrianglePatch;
use crate::SmoothError;
use fv_mesh::{Real, Vector};

/// Relative area below which a face (or fan triangle) is degenerate.
pub const DEGENERATE_AREA: Real = 1e-12;
/// Smallest sine of a quadrilateral's corner angle (measured about the face
/// normal) for the quadrilateral patch; below it, or at a reflex corner,
/// the face is fanned.
pub const QUAD_MIN_CORNER_SINE: Real = 1e-4;

/// All the knobs of the smoothed surface.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SmoothingOptions {
    /// Point normals (Table 4.10 weighting, corrections).
    pub normals: PointNormalParams,
    /// Edge curves near their singular cases.
    pub edge: EdgeCurveParams,
    /// Projection (eqs. 4.81–4.84).
    pub projection: ProjectionParams,
}

impl SmoothingOptions {
    /// Checks every parameter.
    pub fn validate(&self) -> Result<(), SmoothError> {
        self.normals.validate()?;
        self.edge.validate()?;
        self.projection.validate()
    }
}

/// The patch a face currently has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PatchKind {
    /// Triangular Nagata patch.
    Triangle,
    /// Quadrilateral Nagata patch.
    Quad,
    /// Fan of triangular patches around the face centre.
    Fan,
    /// No patch: the face is skipped.
    Degenerate,
}

/// Local coordinates on a face: sub-triangle `sub` of a fan (0 otherwise)
/// and `(η, ζ)` in its domain.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LocalCoords {
    /// Fan triangle `(x_c, x_sub, x_sub+1)`; 0 for triangles and quadrilaterals.
    pub sub: usize,
    /// η.
    pub eta: Real,
    /// ζ.
    pub zeta: Real,
}

/// Borrowed view of the patch of one face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PatchRef<'a> {
    /// A triangular patch.
    Triangle(&'a TrianglePatch),
    /// A quadrilateral patch.
    Quad(&'a QuadPatch),
    /// The fan triangles; `valid[k]` is false for a degenerate one.
    Fan {
        /// Triangle `k` is `(x_c, x_k, x_k+1)`.
        patches: &'a [TrianglePatch],
        /// Whether each triangle is usable.
        valid: &'a [bool],
    },
    /// No patch.
    Degenerate,
}

/// Closest projection of a point onto the smoothed surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceProjection {
    /// Face of the foot.
    pub face: usize,
    /// Local coordinates of the foot on that face.
    pub local: LocalCoords,
    /// The foot.
    pub point: Vector,
    /// Unit normal of the patch at the foot.
    pub normal: Vector,
    /// Signed distance, positive on the side the normal points to
    /// (see [`PatchProjection::signed_distance`]).
    pub signed_distance: Real,
    /// Newton–Raphson updates on the chosen patch.
    pub iterations: usize,
    /// Whether the Newton–Raphson iteration converged on the chosen patch.
    pub converged: bool,
    /// Whether the foot is an orthogonal projection inside the patch.
    pub inside: bool,
}

impl SurfaceProjection {
    /// `|x_s − foot|`.
    pub fn distance(&self) -> Real {
        self.signed_distance.abs()
    }
}

/// A Nagata-smoothed surface.
///
/// ```
/// use contact_smooth::{NagataSurface, SmoothingOptions};
/// use fv_mesh::Vector;
/// // an octahedron inscribed in the unit sphere
/// let points = vec![
///     Vector::x(), Vector::y(), -Vector::x(), -Vector::y(), Vector::z(), -Vector::z(),
/// ];
/// let faces = vec![
///     vec![0, 1, 4], vec![1, 2, 4], vec![2, 3, 4], vec![3, 0, 4],
///     vec![1, 0, 5], vec![2, 1, 5], vec![3, 2, 5], vec![0, 3, 5],
/// ];
/// let mut s = NagataSurface::new(&points, &faces, &[], SmoothingOptions::default())?;
/// let xs = Vector::new(1.0, 1.0, 1.0);
/// let p = s.closest_projection(&xs, &[0, 1, 2, 3])?.expect("a foot");
/// assert_eq!(p.face, 0);
/// assert!(p.inside && p.converged && p.signed_distance > 0.0);
/// // rigid motion: coefficients refreshed in place
/// let moved: Vec<Vector> = points.iter().map(|x| x + Vector::new(0.0, 0.0, 1.0)).collect();
/// s.update_points(&moved)?;
/// # Ok::<(), contact_smooth::SmoothError>(())
/// ```
#[derive(Debug, Clone)]
pub struct NagataSurface {
    options: SmoothingOptions,
    table: FaceTable,
    points: Vec<Vector>,
    normals: Vec<Vector>,
    face_normals: Vec<Vector>,
    kinds: Vec<PatchKind>,
    /// Index into `tris` (triangles) or `quads` (quadrilaterals).
    slots: Vec<usize>,
    tris: Vec<TrianglePatch>,
    quads: Vec<QuadPatch>,
    /// `fan_offsets[f]..fan_offsets[f+1]` indexes `fans`: one triangle per
    /// side for faces of 4+ points, none otherwise.
    fan_offsets: Vec<usize>,
    fans: Vec<TrianglePatch>,
    fan_valid: Vec<bool>,
    point_normals: PointNormals,
}

impl NagataSurface {
    /// Smoothed surface over `points` with one index list per face.
    ///
    /// Fails on an invalid parameter, an index out of range, a non-finite
    /// point or an invalid symmetry plane. Cost: linear in the surface
    /// size; all workspaces are allocated here.
    pub fn new<F: AsRef<[usize]>>(
        points: &[Vector],
        faces: &[F],
        symmetry: &[SymmetryPlane],
        options: SmoothingOptions,
    ) -> Result<Self, SmoothError> {
        let table = FaceTable::new(points.len(), faces)?;
        Self::from_table(points, table, symmetry, options)
    }

    /// Smoothed surface of an `fv_mesh` boundary surface (its local points
    /// and faces; face `f` here is face `f` of the surface).
    pub fn from_surface(
        surface: &fv_mesh::Surface,
        symmetry: &[SymmetryPlane],
        options: SmoothingOptions,
    ) -> Result<Self, SmoothError> {
        let table = FaceTable::from_csr(
            surface.points.len(),
            &surface.face_offsets,
            &surface.face_points,
        )?;
        Self::from_table(&surface.points, table, symmetry, options)
    }

    fn from_table(
        points: &[Vector],
        table: FaceTable,
        symmetry: &[SymmetryPlane],
        options: SmoothingOptions,
    ) -> Result<Self, SmoothError> {
        options.validate()?;
        check_finite(points)?;
        let nf = table.n_faces();
        let mut kinds = Vec::with_capacity(nf);
        let mut slots = Vec::with_capacity(nf);
        let mut fan_offsets = Vec::with_capacity(nf + 1);
        let (mut n_tri, mut n_quad, mut n_fan) = (0, 0, 0);
        fan_offsets.push(0);
        for f in 0..nf {
            let k = table.face(f).len();
            let (kind, slot) = match k {
                0..=2 => (PatchKind::Degenerate, usize::MAX),
                3 => {
                    n_tri += 1;
                    (PatchKind::Triangle, n_tri - 1)
                }
                4 => {
                    n_quad += 1;
                    (PatchKind::Quad, n_quad - 1)
                }
                _ => (PatchKind::Fan, usize::MAX),
            };
            if k >= 4 {
                n_fan += k;
            }
            kinds.push(kind);
            slots.push(slot);
            fan_offsets.push(n_fan);
        }
        let point_normals = PointNormals::new(&table, points, symmetry, options.normals)?;
        let mut s = NagataSurface {
            options,
            points: points.to_vec(),
            normals: vec![Vector::zeros(); points.len()],
            face_normals: vec![Vector::zeros(); nf],
            kinds,
            slots,
            tris: vec![TrianglePatch::default(); n_tri],
            quads: vec![QuadPatch::default(); n_quad],
            fan_offsets,
            fans: vec![TrianglePatch::default(); n_fan],
            fan_valid: vec![false; n_fan],
            table,
            point_normals,
        };
        s.refresh(false)?;
        Ok(s)
    }

    /// New positions of the same points (same order): face normals, point
    /// normals and patch coefficients are recomputed in place, without
    /// allocating. Fails (leaving the surface unchanged) on a length
    /// mismatch or a non-finite point.
    pub fn update_points(&mut self, points: &[Vector]) -> Result<(), SmoothError> {
        self.check_len(points, "points")?;
        check_finite(points)?;
        self.points.copy_from_slice(points);
        self.refresh(false)
    }

    /// Like [`NagataSurface::update_points`] with point normals given by the
    /// caller (e.g. exact normals of an analytical rigid body, §4.6.1);
    /// they are normalised, and no correction is applied.
    pub fn update_with_normals(
        &mut self,
        points: &[Vector],
        normals: &[Vector],
    ) -> Result<(), SmoothError> {
        self.check_len(points, "points")?;
        self.check_len(normals, "normals")?;
        check_finite(points)?;
        check_finite(normals)?;
        self.points.copy_from_slice(points);
        for (n, m) in self.normals.iter_mut().zip(normals) {
            *n = m.try_normalize(1e-300).unwrap_or_default();
        }
        self.refresh(true)
    }

    fn check_len(&self, v: &[Vector], what: &str) -> Result<(), SmoothError> {
        if v.len() != self.points.len() {
            return Err(SmoothError::InvalidSurface(format!(
                "{} {what} given for a surface of {} points",
                v.len(),
                self.points.len()
            )));
        }
        Ok(())
    }

    /// Face normals, point normals (unless given) and patches from `self.points`.
    fn refresh(&mut self, normals_given: bool) -> Result<(), SmoothError> {
        for f in 0..self.table.n_faces() {
            self.face_normals[f] = face_unit_normal(&self.points, self.table.face(f));
        }
        if !normals_given {
            self.point_normals.compute(
                &self.table,
                &self.points,
                &self.face_normals,
                &mut self.normals,
            )?;
        }
        let params = self.options.edge;
        for f in 0..self.table.n_faces() {
            let poly = self.table.face(f);
            let k = poly.len();
            let nf = self.face_normals[f];
            let x = |i: usize| self.points[poly[i % k]];
            let n = |i: usize| self.normals[poly[i % k]];
            self.kinds[f] = if k < 3 || nf == Vector::zeros() {
                PatchKind::Degenerate
            } else if k == 3 {
                self.tris[self.slots[f]] =
                    TrianglePatch::new([x(0), x(1), x(2)], [n(0), n(1), n(2)], &params);
                PatchKind::Triangle
            } else if k == 4 && quad_is_regular(&[x(0), x(1), x(2), x(3)], &nf) {
                self.quads[self.slots[f]] =
                    QuadPatch::new([x(0), x(1), x(2), x(3)], [n(0), n(1), n(2), n(3)], &params);
                PatchKind::Quad
            } else if let Some((xc, nc)) = fan_centre(&self.points, &self.normals, poly, &params) {
                let start = self.fan_offsets[f];
                for i in 0..k {
                    let corners = [xc, x(i), x(i + 1)];
                    self.fans[start + i] =
                        TrianglePatch::new(corners, [nc, n(i), n(i + 1)], &params);
                    self.fan_valid[start + i] = !triangle_is_degenerate(&corners);
                }
                PatchKind::Fan
            } else {
                PatchKind::Degenerate
            };
        }
        Ok(())
    }

    /// The options.
    pub fn options(&self) -> &SmoothingOptions {
        &self.options
    }

    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.table.n_faces()
    }

    /// Number of points.
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// The face table (polygons after removal of repeated indices, corners
    /// around every point).
    pub fn table(&self) -> &FaceTable {
        &self.table
    }

    /// Current point positions.
    pub fn points(&self) -> &[Vector] {
        &self.points
    }

    /// Current unit point normals (zero for a point without a valid face).
    pub fn point_normals(&self) -> &[Vector] {
        &self.normals
    }

    /// Current unit face normals by central decomposition (zero for a degenerate face).
    pub fn face_normals(&self) -> &[Vector] {
        &self.face_normals
    }

    /// Bit `k` set: point `p` is on symmetry plane `k`.
    pub fn symmetry_planes_of(&self, p: usize) -> u32 {
        self.point_normals.symmetry_planes_of(p)
    }

    /// The kind of patch of face `f` (`None` if out of range).
    pub fn kind(&self, f: usize) -> Option<PatchKind> {
        self.kinds.get(f).copied()
    }

    /// The patch of face `f` (`None` if out of range).
    pub fn patch(&self, f: usize) -> Option<PatchRef<'_>> {
        Some(match *self.kinds.get(f)? {
            PatchKind::Triangle => PatchRef::Triangle(&self.tris[self.slots[f]]),
            PatchKind::Quad => PatchRef::Quad(&self.quads[self.slots[f]]),
            PatchKind::Fan => {
                let r = self.fan_offsets[f]..self.fan_offsets[f + 1];
                PatchRef::Fan {
                    patches: &self.fans[r.clone()],
                    valid: &self.fan_valid[r],
                }
            }
            PatchKind::Degenerate => PatchRef::Degenerate,
        })
    }

    /// Calls `visit` with the patch (and `sub` index) of every usable
    /// piece of face `f`.
    fn with_pieces<R>(
        &self,
        f: usize,
        mut visit: impl FnMut(usize, &dyn NagataPatch) -> Option<R>,
        mut keep: impl FnMut(R),
    ) -> Result<(), SmoothError> {
        let patch = self.patch(f).ok_or_else(|| {
            SmoothError::InvalidSurface(format!("face {f} out of range ({} faces)", self.n_faces()))
        })?;
        match patch {
            PatchRef::Triangle(t) => visit(0, t).into_iter().for_each(&mut keep),
            PatchRef::Quad(q) => visit(0, q).into_iter().for_each(&mut keep),
            PatchRef::Fan { patches, valid } => {
                for (k, (t, &ok)) in patches.iter().zip(valid).enumerate() {
                    if ok {
                        visit(k, t).into_iter().for_each(&mut keep);
                    }
                }
            }
            PatchRef::Degenerate => {}
        }
        Ok(())
    }

    /// Position at local coordinates on face `f` (`None` if the face or
    /// fan triangle is out of range or degenerate).
    pub fn point_at(&self, f: usize, local: LocalCoords) -> Option<Vector> {
        self.piece(f, local.sub)
            .map(|p| p.point(local.eta, local.zeta))
    }

    /// Unit normal at local coordinates on face `f` (eq. 4.82).
    pub fn normal_at(&self, f: usize, local: LocalCoords) -> Option<Vector> {
        self.piece(f, local.sub)?.normal(local.eta, local.zeta)
    }

    fn piece(&self, f: usize, sub: usize) -> Option<&dyn NagataPatch> {
        match self.patch(f)? {
            PatchRef::Triangle(t) if sub == 0 => Some(t),
            PatchRef::Quad(q) if sub == 0 => Some(q),
            PatchRef::Fan { patches, valid } if valid.get(sub).copied().unwrap_or(false) => {
                Some(&patches[sub])
            }
            _ => None,
        }
    }

    /// Projection of `xs` onto face `f` (the best piece for a fan);
    /// `Ok(None)` for a degenerate face. Fails if `f` is out of range.
    pub fn project_onto_face(
        &self,
        f: usize,
        xs: &Vector,
    ) -> Result<Option<SurfaceProjection>, SmoothError> {
        self.closest_projection(xs, &[f])
    }

    /// The closest projection of `xs` onto the candidate faces (thesis
    /// §4.6.1: "the projection point with the minimum normal gap"): every
    /// candidate is projected ([`project_onto_patch`]) and the foot closest
    /// to `xs` wins; at equal distance (within 10⁻⁹ relative) an
    /// orthogonal foot inside its patch wins over a boundary foot.
    ///
    /// `Ok(None)` if every candidate is degenerate (or the list is empty);
    /// fails if a candidate is out of range or `xs` is not finite.
    /// Allocation-free.
    pub fn closest_projection(
        &self,
        xs: &Vector,
        candidates: &[usize],
    ) -> Result<Option<SurfaceProjection>, SmoothError> {
        if !xs.iter().all(|v| v.is_finite()) {
            return Err(SmoothError::InvalidSurface(format!(
                "projected point {xs:?} is not finite"
            )));
        }
        let prm = self.options.projection;
        let mut best: Option<SurfaceProjection> = None;
        for &f in candidates {
            self.with_pieces(
                f,
                |sub, patch| project_onto_patch(patch, xs, &prm).map(|p| (sub, p)),
                |(sub, p): (usize, PatchProjection)| {
                    let cand = SurfaceProjection {
                        face: f,
                        local: LocalCoords {
                            sub,
                            eta: p.eta,
                            zeta: p.zeta,
                        },
                        point: p.point,
                        normal: p.normal,
                        signed_distance: p.signed_distance,
                        iterations: p.iterations,
                        converged: p.converged,
                        inside: p.inside,
                    };
                    if best.is_none_or(|b| better(&cand, &b)) {
                        best = Some(cand);
                    }
                },
            )?;
        }
        Ok(best)
    }

    /// Faces sharing a point with face `f` (including `f`), sorted, into
    /// `out` (cleared first): the usual candidate list around a face found
    /// by contact detection. Fails if `f` is out of range.
    pub fn faces_around_face(&self, f: usize, out: &mut Vec<usize>) -> Result<(), SmoothError> {
        if f >= self.n_faces() {
            return Err(SmoothError::InvalidSurface(format!(
                "face {f} out of range ({} faces)",
                self.n_faces()
            )));
        }
        out.clear();
        for &p in self.table.face(f) {
            out.extend(self.table.corners(p).iter().map(|c| c.face));
        }
        out.push(f);
        out.sort_unstable();
        out.dedup();
        Ok(())
    }
}

/// Whether `a` is a better foot than `b`.
fn better(a: &SurfaceProjection, b: &SurfaceProjection) -> bool {
    let (da, db) = (a.signed_distance.abs(), b.signed_distance.abs());
    let tie = 1e-9 * (da + db);
    if (da - db).abs() <= tie {
        a.inside && !b.inside
    } else {
        da < db
    }
}

fn check_finite(v: &[Vector]) -> Result<(), SmoothError> {
    match v.iter().position(|x| !x.iter().all(|c| c.is_finite())) {
        Some(i) => Err(SmoothError::InvalidSurface(format!(
            "point {i} is not finite: {:?}",
            v[i]
        ))),
        None => Ok(()),
    }
}

/// Unit normal by central decomposition; zero for a degenerate polygon.
fn face_unit_normal(points: &[Vector], poly: &[usize]) -> Vector {
    let k = poly.len();
    if k < 3 {
        return Vector::zeros();
    }
    let (_, a) = polygon_centre_area(points, poly);
    let longest = (0..k)
        .map(|i| (points[poly[(i + 1) % k]] - points[poly[i]]).norm_squared())
        .fold(0.0, Real::max);
    let m = a.norm();
    if m > DEGENERATE_AREA * longest && m.is_finite() {
        a / m
    } else {
        Vector::zeros()
    }
}

fn triangle_is_degenerate(x: &[Vector; 3]) -> bool {
    let a = 0.5 * (x[1] - x[0]).cross(&(x[2] - x[0])).norm();
    let longest = (x[1] - x[0])
        .norm_squared()
        .max((x[2] - x[1]).norm_squared())
        .max((x[0] - x[2]).norm_squared());
    !(a > DEGENERATE_AREA * longest)
}

/// Every corner of the quadrilateral convex about `n` with sin α above
/// [`QUAD_MIN_CORNER_SINE`].
fn quad_is_regular(x: &[Vector; 4], n: &Vector) -> bool {
    (0..4).all(|i| {
        let e1 = x[(i + 1) % 4] - x[i];
        let e2 = x[(i + 3) % 4] - x[i];
        e1.cross(&e2).dot(n) > QUAD_MIN_CORNER_SINE * e1.norm() * e2.norm()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plate(nx: usize, ny: usize) -> (Vec<Vector>, Vec<Vec<usize>>) {
        let mut pts = Vec::new();
        for j in 0..=ny {
            for i in 0..=nx {
                pts.push(Vector::new(i as Real, j as Real, 0.0));
            }
        }
        let mut faces = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let a = j * (nx + 1) + i;
                faces.push(vec![a, a + 1, a + nx + 2, a + nx + 1]);
            }
        }
        (pts, faces)
    }

    #[test]
    fn kinds_and_fallbacks() {
        let (mut pts, mut faces) = plate(2, 1);
        pts.push(Vector::new(1.0, 2.0, 0.0));
        let top = pts.len() - 1;
        // a quadrilateral with a straight corner (at point 4), written with
        // the first point repeated at the end
        faces.push(vec![3, 4, 5, top, 3]);
        // a quadrilateral collapsed by index, a segment
        faces.push(vec![0, 1, 1, 4]);
        faces.push(vec![2, 5, 5]);
        // a dart-shaped quadrilateral (reflex corner at point 4), a hexagon
        faces.push(vec![3, 5, 1, 4]);
        faces.push(vec![0, 1, 2, 5, 4, 3]);
        let s = NagataSurface::new(&pts, &faces, &[], SmoothingOptions::default()).unwrap();
        assert_eq!(s.kind(0), Some(PatchKind::Quad));
        assert_eq!(s.kind(2), Some(PatchKind::Fan));
        assert_eq!(s.kind(3), Some(PatchKind::Triangle));
        assert_eq!(s.kind(4), Some(PatchKind::Degenerate));
        assert_eq!(s.kind(5), Some(PatchKind::Fan));
        assert_eq!(s.kind(6), Some(PatchKind::Fan));
        assert_eq!(s.kind(7), None);
        assert!(matches!(s.patch(4), Some(PatchRef::Degenerate)));
        let Some(PatchRef::Fan { valid, .. }) = s.patch(2) else {
            panic!("fan expected");
        };
        assert_eq!(valid.len(), 4);
        assert!(s
            .closest_projection(&Vector::zeros(), &[4])
            .unwrap()
            .is_none());
        assert!(s.closest_projection(&Vector::zeros(), &[7]).is_err());
        // the hexagon's fan covers it: a point above its middle projects inside
        let p = s
            .closest_projection(&Vector::new(1.0, 0.5, 1.0), &[6])
            .unwrap()
            .unwrap();
        assert!(p.inside && (p.point - Vector::new(1.0, 0.5, 0.0)).norm() < 1e-14);
        assert!(s
            .closest_projection(&Vector::new(Real::NAN, 0.0, 0.0), &[0])
            .is_err());
    }

    #[test]
    fn update_validates_and_keeps_storage() {
        let (pts, faces) = plate(3, 2);
        let mut s = NagataSurface::new(&pts, &faces, &[], SmoothingOptions::default()).unwrap();
        let ptr = s.quads.as_ptr();
        let moved: Vec<Vector> = pts.iter().map(|x| x + Vector::new(0.5, 0.0, 2.0)).collect();
        s.update_points(&moved).unwrap();
        assert_eq!(ptr, s.quads.as_ptr());
        assert!(s.update_points(&moved[1..]).is_err());
        let mut bad = moved.clone();
        bad[0].x = Real::INFINITY;
        assert!(s.update_points(&bad).is_err());
        assert_eq!(s.points()[0], moved[0]);
        let p = s
            .closest_projection(&Vector::new(1.7, 0.4, 3.0), &[0, 1, 2, 3, 4, 5])
            .unwrap()
            .unwrap();
        assert_eq!(p.face, 1);
        assert!((p.signed_distance - 1.0).abs() < 1e-14);
        assert!((p.normal - Vector::z()).norm() < 1e-15);
        let mut around = Vec::new();
        s.faces_around_face(0, &mut around).unwrap();
        assert_eq!(around, vec![0, 1, 3, 4]);
        assert!(s.faces_around_face(6, &mut around).is_err());
    }
}
