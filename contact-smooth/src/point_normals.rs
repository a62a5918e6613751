//! Point normals for the Nagata patches (thesis eq. 4.80, Table 4.10,
//! Fig. 4.40).
//!
//! `n_p = Σ ωᵢ n_b,i / |Σ ωᵢ n_b,i|` over the faces around the point, `n_b,i`
//! the unit face normal by central decomposition and `ωᵢ` one of the
//! weightings of Table 4.10 ([`NormalWeighting`]), computed from the two
//! sides `eᵢ`, `eᵢ₊₁` of face `i` leaving the point and the angle `αᵢ`
//! between them (Fig. 4.39).
//!
//! Default (not the thesis's): Max's weighting `sin αᵢ / (|eᵢ||eᵢ₊₁|)` of
//! the *corner* normals `eᵢ × eᵢ₊₁ / |eᵢ × eᵢ₊₁|`, exact on a sphere for any
//! closed fan of triangles or quadrilaterals; the thesis's equal weights of
//! face normals are [`PointNormalParams::thesis`]. Measured on spheres
//! meshed irregularly, equal weights give first-order normals and a
//! second-order Nagata surface, the default fourth order
//! (`tests/suite/accuracy.rs`).
//!
//! Then two corrections (Fig. 4.40):
//!
//! * **Flat/curved transition** ([`TransitionCorrection`]): a point on the
//!   border of a flat zone of a tangent-continuous surface gets the normal
//!   of the flat zone. Rule (ours): a point is *inside a flat zone* when it
//!   has at least two valid faces, all coplanar (normals within
//!   `coplanar_angle`). A point not inside a flat zone is a *transition
//!   point* when the faces around it that touch a point inside a flat zone
//!   are all coplanar (one plane, not two: a sharp corner between two flat
//!   zones is left alone), not all of its faces lie in that plane, and the
//!   averaged normal is within `max_angle` of the plane normal (a sharp edge
//!   between a flat and a curved zone is left alone). Its normal becomes the
//!   mean normal of its faces in that plane. A surface without two coplanar
//!   neighbouring faces (a sphere, a cylinder meshed along its axis) is
//!   never touched.
//! * **Symmetry planes** ([`SymmetryPlane`]): the normal of a point on a
//!   symmetry plane is projected into the plane (on two planes: onto their
//!   intersection line), as the mirrored faces beyond the plane would do.
//!   Points on a plane are found once, from the positions given to
//!   [`PointNormals::new`], within `symmetry_tolerance ×` the mean edge
//!   length.
use crate::face_table::FaceTable;
use crate::normal_fit::{FitWorkspace, NormalFit};
use crate::SmoothError;
use fv_mesh::{Real, Vector};
use std::fmt;
use std::str::FromStr;

/// Weighting factor ωᵢ of the face normals (Table 4.10).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum NormalWeighting {
    /// `ωᵢ = 1` (Gouraud), the thesis's choice.
    #[default]
    Equal,
    /// `ωᵢ = αᵢ` (Thürrner & Wüthrich).
    Angle,
    /// `ωᵢ = |eᵢ × eᵢ₊₁|` (Max).
    Area,
    /// `ωᵢ = (|eᵢ| |eᵢ₊₁|)⁻¹` (Max).
    EdgeLengthReciprocal,
    /// `ωᵢ = sin αᵢ (|eᵢ| |eᵢ₊₁|)⁻¹` (Max; exact on a sphere for triangles).
    AngleEdgeLengthReciprocal,
    /// `ωᵢ = αᵢ (sin αᵢ / |eᵢ₊₁ − eᵢ|)²` (Ubach et al.): the angle over the
    /// area of the circle circumscribed to the corner triangle (`|eᵢ₊₁ − eᵢ|`
    /// is the side opposite the point; Table 4.10 prints this garbled).
    AngleCircumcircle,
}

impl NormalWeighting {
    /// Every weighting, in the order of [`NormalWeighting::valid_names`].
    pub const ALL: [NormalWeighting; 6] = [
        NormalWeighting::Equal,
        NormalWeighting::Angle,
        NormalWeighting::Area,
        NormalWeighting::EdgeLengthReciprocal,
        NormalWeighting::AngleEdgeLengthReciprocal,
        NormalWeighting::AngleCircumcircle,
    ];

    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            NormalWeighting::Equal => "equal",
            NormalWeighting::Angle => "angle",
            NormalWeighting::Area => "area",
            NormalWeighting::EdgeLengthReciprocal => "edge-length-reciprocal",
            NormalWeighting::AngleEdgeLengthReciprocal => "angle-edge-length-reciprocal",
            NormalWeighting::AngleCircumcircle => "angle-circumcircle",
        }
    }

    /// The valid names, comma separated.
    pub fn valid_names() -> String {
        Self::ALL.map(|w| w.name()).join(", ")
    }

    /// Parses a name; an unknown name is rejected with the list of valid ones.
    pub fn from_name(name: &str) -> Result<Self, SmoothError> {
        Self::ALL
            .into_iter()
            .find(|w| w.name() == name.trim())
            .ok_or_else(|| SmoothError::UnknownWeighting {
                name: name.to_string(),
                valid: Self::valid_names(),
            })
    }

    /// ωᵢ for the corner with sides `e1`, `e2` leaving the point; 0 for a
    /// degenerate corner (zero side, non-finite value).
    pub fn weight(self, e1: &Vector, e2: &Vector) -> Real {
        let angle = || e1.cross(e2).norm().atan2(e1.dot(e2));
        let w = match self {
            NormalWeighting::Equal => 1.0,
            NormalWeighting::Angle => angle(),
            NormalWeighting::Area => e1.cross(e2).norm(),
            NormalWeighting::EdgeLengthReciprocal => 1.0 / (e1.norm() * e2.norm()),
            // sin α = |e₁ × e₂| / (|e₁||e₂|)
            NormalWeighting::AngleEdgeLengthReciprocal => {
                e1.cross(e2).norm() / (e1.norm_squared() * e2.norm_squared())
            }
            NormalWeighting::AngleCircumcircle => {
                let sin = e1.cross(e2).norm() / (e1.norm() * e2.norm());
                angle() * (sin / (e2 - e1).norm()).powi(2)
            }
        };
        if w.is_finite() && w > 0.0 {
            w
        } else {
            0.0
        }
    }
}

impl fmt::Display for NormalWeighting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for NormalWeighting {
    type Err = SmoothError;
    fn from_str(s: &str) -> Result<Self, SmoothError> {
        Self::from_name(s)
    }
}

impl From<fv_mesh::PointNormalWeighting> for NormalWeighting {
    /// `Unweighted` → `Equal`, `Angle` → `Angle`; fv-mesh's `Area` (whole
    /// face area) has no exact counterpart and maps to the corner `Area`.
    fn from(w: fv_mesh::PointNormalWeighting) -> Self {
        match w {
            fv_mesh::PointNormalWeighting::Unweighted => NormalWeighting::Equal,
            fv_mesh::PointNormalWeighting::Angle => NormalWeighting::Angle,
            fv_mesh::PointNormalWeighting::Area => NormalWeighting::Area,
        }
    }
}

/// Correction at flat/curved transitions (Fig. 4.40, rule in the module
/// documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransitionCorrection {
    /// Faces whose normals are within this angle (radians) are coplanar.
    /// Default 10⁻⁵.
    pub coplanar_angle: Real,
    /// Largest angle (radians) between the averaged normal and the flat
    /// zone's normal for the correction to apply. Default 30°.
    pub max_angle: Real,
}

impl Default for TransitionCorrection {
    fn default() -> Self {
        TransitionCorrection {
            coplanar_angle: 1e-5,
            max_angle: 30_f64.to_radians(),
        }
    }
}

/// A symmetry plane: points on it get normals projected into it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetryPlane {
    /// A point of the plane.
    pub origin: Vector,
    /// The plane normal (any length but zero).
    pub normal: Vector,
}

impl SymmetryPlane {
    /// The plane through `origin` with normal `normal`.
    pub fn new(origin: Vector, normal: Vector) -> Self {
        SymmetryPlane { origin, normal }
    }
}

/// How point normals are computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointNormalParams {
    /// Face weighting (Table 4.10). Default
    /// [`NormalWeighting::AngleEdgeLengthReciprocal`] (Max); the thesis uses
    /// [`NormalWeighting::Equal`] ([`PointNormalParams::thesis`]).
    pub weighting: NormalWeighting,
    /// Flat/curved transition correction; `None` switches it off.
    /// Default on.
    pub transition: Option<TransitionCorrection>,
    /// A point is on a symmetry plane within this fraction of the mean edge
    /// length. Default 10⁻⁶.
    pub symmetry_tolerance: Real,
    /// Average the unit *corner* normals `eᵢ × eᵢ₊₁ / |eᵢ × eᵢ₊₁|` instead of
    /// the face normals `n_b,i` (the same for triangles; the face normal is
    /// kept at a reflex, collapsed or nearly straight corner, sin α ≤ 10⁻⁶). Max's weighting
    /// ([`NormalWeighting::AngleEdgeLengthReciprocal`]) with corner normals
    /// is exact for any closed fan of points on a sphere, quadrilaterals
    /// included. Default `true`; `false` is eq. 4.80 as printed.
    pub corner_normals: bool,
    /// Refine the weighted normals by a local quadric fit
    /// ([`NormalFit`], the fitting approach of §4.6.1); `None` keeps eq.
    /// 4.80. Applied before the two corrections.
    pub fit: Option<NormalFit>,
}

impl Default for PointNormalParams {
    /// Max's weighting of the corner normals, both corrections on.
    ///
    /// Not the thesis's choice ([`PointNormalParams::thesis`]): on spheres
    /// meshed with irregular triangles or quadrilaterals, equally weighted
    /// face normals are only first-order accurate, which limits the Nagata
    /// surface to second order (measured in `tests/suite/accuracy.rs`), while
    /// this default gives exact normals on a sphere and fourth order.
    fn default() -> Self {
        PointNormalParams {
            weighting: NormalWeighting::AngleEdgeLengthReciprocal,
            transition: Some(TransitionCorrection::default()),
            symmetry_tolerance: 1e-6,
            corner_normals: true,
            fit: Some(NormalFit::default()),
        }
    }
}

impl PointNormalParams {
    /// The thesis's choice: equally weighted face normals (eq. 4.80 with
    /// `ωᵢ = 1`), both corrections on.
    pub fn thesis() -> Self {
        PointNormalParams {
            weighting: NormalWeighting::Equal,
            corner_normals: false,
            fit: None,
            ..Self::default()
        }
    }

    /// Checks the tolerances.
    pub fn validate(&self) -> Result<(), SmoothError> {
        let bad = |name, value, reason| {
            Err(SmoothError::InvalidParameter {
                name,
                value,
                reason,
            })
        };
        if let Some(t) = self.transition {
            if !(t.coplanar_angle >= 0.0 && t.coplanar_angle < 0.1) {
                return bad(
                    "coplanar_angle",
                    t.coplanar_angle,
                    "must be in [0, 0.1) rad",
                );
            }
            if !(t.max_angle >= 0.0 && t.max_angle < std::f64::consts::FRAC_PI_2) {
                return bad("max_angle", t.max_angle, "must be in [0, π/2) rad");
            }
        }
        if !(self.symmetry_tolerance >= 0.0 && self.symmetry_tolerance < 1.0) {
            return bad(
                "symmetry_tolerance",
                self.symmetry_tolerance,
                "must be in [0, 1)",
            );
        }
        Ok(())
    }
}

/// Largest number of symmetry planes.
pub const MAX_SYMMETRY_PLANES: usize = 32;

/// Point-normal calculator: symmetry-plane membership found once, workspace
/// allocated once, [`PointNormals::compute`] allocation-free.
#[derive(Debug, Clone)]
pub struct PointNormals {
    params: PointNormalParams,
    /// Unit plane normals.
    planes: Vec<Vector>,
    /// Bit `k` set: the point is on plane `k`.
    on_planes: Vec<u32>,
    /// Workspace: the point is inside a flat zone.
    flat: Vec<bool>,
    /// Workspace of the quadric fit.
    fit: FitWorkspace,
}

impl PointNormals {
    /// Validates the parameters and planes and finds the points on the
    /// symmetry planes.
    pub fn new(
        table: &FaceTable,
        points: &[Vector],
        planes: &[SymmetryPlane],
        params: PointNormalParams,
    ) -> Result<Self, SmoothError> {
        params.validate()?;
        if points.len() != table.n_points() {
            return Err(SmoothError::InvalidSurface(format!(
                "{} points given for a face table over {} points",
                points.len(),
                table.n_points()
            )));
        }
        if planes.len() > MAX_SYMMETRY_PLANES {
            return Err(SmoothError::InvalidSurface(format!(
                "{} symmetry planes; at most {MAX_SYMMETRY_PLANES}",
                planes.len()
            )));
        }
        let mut units = Vec::with_capacity(planes.len());
        for (k, pl) in planes.iter().enumerate() {
            let m = pl.normal.norm();
            if !(m > 0.0 && m.is_finite() && pl.origin.iter().all(|v| v.is_finite())) {
                return Err(SmoothError::InvalidSurface(format!(
                    "symmetry plane {k}: origin and non-zero normal must be finite"
                )));
            }
            units.push(pl.normal / m);
        }
        // mean edge length
        let (mut sum, mut count) = (0.0, 0usize);
        for f in 0..table.n_faces() {
            let poly = table.face(f);
            let k = poly.len();
            if k < 2 {
                continue;
            }
            for i in 0..k {
                sum += (points[poly[(i + 1) % k]] - points[poly[i]]).norm();
                count += 1;
            }
        }
        let h = if count > 0 { sum / count as Real } else { 1.0 };
        let tol = params.symmetry_tolerance * h;
        let on_planes = points
            .iter()
            .map(|x| {
                let mut mask = 0u32;
                for (k, (pl, m)) in planes.iter().zip(&units).enumerate() {
                    if (x - pl.origin).dot(m).abs() <= tol {
                        mask |= 1 << k;
                    }
                }
                mask
            })
            .collect();
        Ok(PointNormals {
            params,
            planes: units,
            on_planes,
            flat: vec![false; table.n_points()],
            fit: FitWorkspace::new(table.n_points(), table.n_faces()),
        })
    }

    /// The parameters.
    pub fn params(&self) -> &PointNormalParams {
        &self.params
    }

    /// Bit `k` set: point `p` is on symmetry plane `k` (0 if `p` is out of range).
    pub fn symmetry_planes_of(&self, p: usize) -> u32 {
        self.on_planes.get(p).copied().unwrap_or(0)
    }

    /// Unit point normals into `out` (eq. 4.80 and the corrections).
    ///
    /// `face_normals` are the unit face normals, zero for a degenerate face
    /// (which is then ignored). A point whose weighted sum vanishes gets the
    /// unweighted sum of its face normals, and zero if that vanishes too (no
    /// valid face).
    ///
    /// Fails if the array lengths do not match the table.
    pub fn compute(
        &mut self,
        table: &FaceTable,
        points: &[Vector],
        face_normals: &[Vector],
        out: &mut [Vector],
    ) -> Result<(), SmoothError> {
        let np = table.n_points();
        if points.len() != np
            || out.len() != np
            || face_normals.len() != table.n_faces()
            || self.flat.len() != np
        {
            return Err(SmoothError::InvalidSurface(format!(
                "point normals: {} points, {} outputs, {} face normals for a table of {} points and {} faces",
                points.len(),
                out.len(),
                face_normals.len(),
                np,
                table.n_faces()
            )));
        }
        let weighting = self.params.weighting;
        let corner = self.params.corner_normals;
        for (p, n_out) in out.iter_mut().enumerate() {
            let (mut sum, mut plain) = (Vector::zeros(), Vector::zeros());
            for c in table.corners(p) {
                let nf = face_normals[c.face];
                let poly = table.face(c.face);
                let k = poly.len();
                if k < 3 || nf == Vector::zeros() {
                    continue;
                }
                let x = points[p];
                let e1 = points[poly[(c.index + k - 1) % k]] - x;
                let e2 = points[poly[(c.index + 1) % k]] - x;
                // e₂ × e₁: the right-hand rule of the face's vertex order;
                // the face normal at a straight, reflex or collapsed corner
                let n = match corner_normal(&e1, &e2) {
                    Some(m) if corner && m.dot(&nf) > 0.0 => m,
                    _ => nf,
                };
                sum += weighting.weight(&e1, &e2) * n;
                plain += nf;
            }
            *n_out = unit_or_zero(sum)
                .or_else(|| unit_or_zero(plain))
                .unwrap_or_default();
        }
        if let Some(fit) = self.params.fit {
            fit.refine(table, points, face_normals, out, &mut self.fit);
        }
        if let Some(t) = self.params.transition {
            self.correct_transitions(&t, table, face_normals, out);
        }
        if !self.planes.is_empty() {
            self.correct_symmetry(out);
        }
        Ok(())
    }

    /// Fig. 4.40, right: normals of transition points (rule in the module docs).
    fn correct_transitions(
        &mut self,
        t: &TransitionCorrection,
        table: &FaceTable,
        face_normals: &[Vector],
        out: &mut [Vector],
    ) {
        let cos_tol = t.coplanar_angle.cos();
        let cos_max = t.max_angle.cos();
        let valid = |f: usize| table.face(f).len() >= 3 && face_normals[f] != Vector::zeros();
        for p in 0..table.n_points() {
            let mut first: Option<Vector> = None;
            let mut count = 0;
            let mut all = true;
            for c in table.corners(p) {
                if !valid(c.face) {
                    continue;
                }
                let nf = face_normals[c.face];
                count += 1;
                match first {
                    None => first = Some(nf),
                    Some(m) => all &= m.dot(&nf) >= cos_tol,
                }
            }
            self.flat[p] = all && count >= 2;
        }
        for (p, n_out) in out.iter_mut().enumerate() {
            if self.flat[p] {
                continue;
            }
            let mut plane: Option<Vector> = None;
            let mut ambiguous = false;
            for c in table.corners(p) {
                if !valid(c.face) {
                    continue;
                }
                let nf = face_normals[c.face];
                if !table.face(c.face).iter().any(|&q| q != p && self.flat[q]) {
                    continue;
                }
                match plane {
                    None => plane = Some(nf),
                    Some(m) => ambiguous |= m.dot(&nf) < cos_tol,
                }
            }
            let Some(m) = plane else { continue };
            if ambiguous {
                continue;
            }
            let mut group = Vector::zeros();
            let mut outside = false;
            for c in table.corners(p) {
                if !valid(c.face) {
                    continue;
                }
                let nf = face_normals[c.face];
                if m.dot(&nf) >= cos_tol {
                    group += nf;
                } else {
                    outside = true;
                }
            }
            let Some(g) = unit_or_zero(group) else {
                continue;
            };
            if outside && n_out.dot(&g) >= cos_max {
                *n_out = g;
            }
        }
    }

    /// Fig. 4.40, left: normals of points on symmetry planes projected into them.
    fn correct_symmetry(&self, out: &mut [Vector]) {
        for (n, &mask) in out.iter_mut().zip(&self.on_planes) {
            if mask == 0 {
                continue;
            }
            let mut it = (0..self.planes.len()).filter(|k| mask & (1 << k) != 0);
            let (Some(a), b) = (it.next(), it.next()) else {
                continue;
            };
            let m1 = self.planes[a];
            let projected = match b.map(|b| m1.cross(&self.planes[b])) {
                Some(line) if line.norm() > 1e-6 => {
                    let l = line.normalize();
                    l * n.dot(&l)
                }
                _ => *n - m1 * n.dot(&m1),
            };
            if let Some(u) = unit_or_zero(projected) {
                *n = u;
            }
        }
    }
}

/// Smallest sine of a corner angle for its own normal to be used: below
/// it the direction of `e₂ × e₁` is dominated by rounding.
const MIN_CORNER_SINE: Real = 1e-6;

/// Unit `e₂ × e₁`, `None` at a (nearly) straight or collapsed corner.
fn corner_normal(e1: &Vector, e2: &Vector) -> Option<Vector> {
    let c = e2.cross(e1);
    (c.norm() > MIN_CORNER_SINE * e1.norm() * e2.norm())
        .then(|| unit_or_zero(c))
        .flatten()
}

/// `v / |v|`, or `None` if `|v|` is zero or not finite (or tiny: below 10⁻³⁰⁰).
fn unit_or_zero(v: Vector) -> Option<Vector> {
    let m = v.norm();
    (m > 1e-300 && m.is_finite()).then(|| v / m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::face_geometry::polygon_centre_area;

    fn face_normals(table: &FaceTable, points: &[Vector]) -> Vec<Vector> {
        (0..table.n_faces())
            .map(|f| {
                polygon_centre_area(points, table.face(f))
                    .1
                    .try_normalize(0.0)
                    .unwrap_or_default()
            })
            .collect()
    }

    #[test]
    fn names_round_trip_and_unknown_lists_valid() {
        for w in NormalWeighting::ALL {
            assert_eq!(NormalWeighting::from_name(w.name()).unwrap(), w);
            assert_eq!(w.to_string().parse::<NormalWeighting>().unwrap(), w);
        }
        let e = NormalWeighting::from_name("gouraud").unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("gouraud") && msg.contains("angle-circumcircle"),
            "{msg}"
        );
        assert!(msg.contains("equal, angle, area, edge-length-reciprocal"));
    }

    #[test]
    fn weights_of_a_right_corner() {
        let e1 = Vector::new(2.0, 0.0, 0.0);
        let e2 = Vector::new(0.0, 1.0, 0.0);
        let half_pi = std::f64::consts::FRAC_PI_2;
        let w = |k: NormalWeighting| k.weight(&e1, &e2);
        assert_eq!(w(NormalWeighting::Equal), 1.0);
        assert!((w(NormalWeighting::Angle) - half_pi).abs() < 1e-15);
        assert!((w(NormalWeighting::Area) - 2.0).abs() < 1e-15);
        assert!((w(NormalWeighting::EdgeLengthReciprocal) - 0.5).abs() < 1e-15);
        assert!((w(NormalWeighting::AngleEdgeLengthReciprocal) - 0.5).abs() < 1e-15);
        assert!((w(NormalWeighting::AngleCircumcircle) - half_pi / 5.0).abs() < 1e-15);
        assert_eq!(NormalWeighting::Angle.weight(&e1, &Vector::zeros()), 0.0);
        assert_eq!(
            NormalWeighting::EdgeLengthReciprocal.weight(&e1, &Vector::zeros()),
            0.0
        );
    }

    /// A cube corner, unevenly meshed: equal weights are pulled towards the
    /// side with more faces, angle weights are not.
    #[test]
    fn weighting_changes_the_average() {
        let points = vec![
            Vector::new(0.0, 0.0, 0.0),
            Vector::new(1.0, 0.0, 0.0),
            Vector::new(0.0, 1.0, 0.0),
            Vector::new(0.0, 0.0, 1.0),
            Vector::new(1.0, 1.0, 0.0),
            Vector::new(1.0, 0.0, 1.0),
            Vector::new(0.0, 1.0, 1.0),
        ];
        // outward normals −z (two triangles), −y, −x
        let faces = vec![
            vec![0, 2, 4],
            vec![0, 4, 1],
            vec![0, 1, 5, 3],
            vec![0, 3, 6, 2],
        ];
        let table = FaceTable::new(points.len(), &faces).unwrap();
        let fnorm = face_normals(&table, &points);
        let mut out = vec![Vector::zeros(); points.len()];
        let mut pn = |w| {
            let prm = PointNormalParams {
                weighting: w,
                transition: None,
                ..Default::default()
            };
            let mut pn = PointNormals::new(&table, &points, &[], prm).unwrap();
            pn.compute(&table, &points, &fnorm, &mut out).unwrap();
            out[0]
        };
        let equal = pn(NormalWeighting::Equal);
        assert!((equal - Vector::new(-1.0, -1.0, -2.0).normalize()).norm() < 1e-15);
        let angle = pn(NormalWeighting::Angle);
        assert!((angle - Vector::new(-1.0, -1.0, -1.0).normalize()).norm() < 1e-15);
    }

    #[test]
    fn symmetry_plane_projects_normals() {
        // a strip of faces tilted towards +x ending on the plane x = 0
        let points = vec![
            Vector::new(0.0, 0.0, 0.0),
            Vector::new(0.0, 1.0, 0.0),
            Vector::new(1.0, 0.0, 0.2),
            Vector::new(1.0, 1.0, 0.2),
        ];
        let faces = vec![vec![0, 2, 3, 1]];
        let table = FaceTable::new(4, &faces).unwrap();
        let fnorm = face_normals(&table, &points);
        let plane = SymmetryPlane::new(Vector::zeros(), Vector::new(2.0, 0.0, 0.0));
        let mut pn = PointNormals::new(&table, &points, &[plane], Default::default()).unwrap();
        assert_eq!(pn.symmetry_planes_of(0), 1);
        assert_eq!(pn.symmetry_planes_of(2), 0);
        let mut out = vec![Vector::zeros(); 4];
        pn.compute(&table, &points, &fnorm, &mut out).unwrap();
        assert!((out[0] - Vector::z()).norm() < 1e-15, "{:?}", out[0]);
        assert!((out[2] - fnorm[0]).norm() < 1e-15);
        // two orthogonal planes: the normal lies along their intersection
        let planes = [
            plane,
            SymmetryPlane::new(Vector::zeros(), Vector::new(0.0, 1.0, 0.0)),
        ];
        let mut pn = PointNormals::new(&table, &points, &planes, Default::default()).unwrap();
        assert_eq!(pn.symmetry_planes_of(0), 3);
        pn.compute(&table, &points, &fnorm, &mut out).unwrap();
        assert!((out[0] - Vector::z()).norm() < 1e-15);
        let bad = SymmetryPlane::new(Vector::zeros(), Vector::zeros());
        assert!(PointNormals::new(&table, &points, &[bad], Default::default()).is_err());
    }

    /// Flat plate z = 0 for x ≤ 0, tangent-continuous into a cylinder of
    /// radius 1 for x > 0 (Fig. 4.40, right).
    #[test]
    fn transition_point_gets_the_flat_normal() {
        let xs = [-2.0, -1.0, 0.0];
        let phis = [0.3, 0.6];
        let mut row: Vec<Vector> = xs.iter().map(|&x| Vector::new(x, 0.0, 0.0)).collect();
        row.extend(
            phis.iter()
                .map(|&p: &Real| Vector::new(p.sin(), 0.0, p.cos() - 1.0)),
        );
        let nx = row.len();
        let mut points = Vec::new();
        for y in [0.0, 1.0, 2.0] {
            points.extend(row.iter().map(|r| r + Vector::new(0.0, y, 0.0)));
        }
        let mut faces = Vec::new();
        for j in 0..2 {
            for i in 0..nx - 1 {
                let a = j * nx + i;
                faces.push(vec![a, a + 1, a + 1 + nx, a + nx]);
            }
        }
        let table = FaceTable::new(points.len(), &faces).unwrap();
        let fnorm = face_normals(&table, &points);
        let mut out = vec![Vector::zeros(); points.len()];
        let transition = nx + 2; // x = 0, y = 1
        let mut off = PointNormals::new(
            &table,
            &points,
            &[],
            PointNormalParams {
                transition: None,
                ..Default::default()
            },
        )
        .unwrap();
        off.compute(&table, &points, &fnorm, &mut out).unwrap();
        assert!((out[transition] - Vector::z()).norm() > 0.05);
        let mut on = PointNormals::new(&table, &points, &[], Default::default()).unwrap();
        on.compute(&table, &points, &fnorm, &mut out).unwrap();
        assert!((out[transition] - Vector::z()).norm() < 1e-15);
        // the curved points are left alone (two coplanar groups, no flat zone)
        assert!(out[nx + 3].dot(&Vector::z()) < 0.99);
    }
}
