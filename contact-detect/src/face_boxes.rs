//! Bounding boxes and local-frame polygons of all faces of one surface.
use crate::aabb::Aabb;
use crate::convex_hull_2d::V2;
use crate::obb::{face_obb, FaceBoxSize, Obb, ObbScratch};
use crate::sat_polygon_polygon::{prepare_polygon, PreparedPolygon};
use crate::DetectParams;
use fv_mesh::{Real, Surface, Vector};

/// A face is degenerate, and skipped, when its area is at most this
/// fraction of h̄² (a face of size 10⁻⁶ h̄).
pub const DEGENERATE_AREA: Real = 1e-12;

/// h̄ estimated as the mean face size √|Γ_f| over the faces of both surfaces
/// with finite positive area; `None` if there is no such face.
pub fn mean_face_size(a: &Surface, b: &Surface) -> Option<Real> {
    let (mut sum, mut n) = (0.0, 0usize);
    for &m in a.face_mag.iter().chain(&b.face_mag) {
        if m.is_finite() && m > 0.0 {
            sum += m.sqrt();
            n += 1;
        }
    }
    (n > 0 && sum.is_finite()).then(|| sum / n as Real)
}

/// The validity conditions of a face that do not need its box (see
/// [`FaceBoxes`]): at least three points, all finite, a finite centre, a
/// finite unit normal and an area above `min_area`.
pub(crate) fn face_data_valid(s: &Surface, f: usize, min_area: Real) -> bool {
    let pts = s.face(f);
    let n = s.face_normals[f];
    let area = s.face_mag[f];
    pts.len() >= 3
        && area.is_finite()
        && area > min_area
        && n.iter().all(|x| x.is_finite())
        && (n.norm_squared() - 1.0).abs() < 1e-6
        && s.face_centres[f].iter().all(|x| x.is_finite())
        && pts
            .iter()
            .all(|&p| s.points[p as usize].iter().all(|x| x.is_finite()))
}

/// Box of an invalid face (never tested: its AABB is empty).
const NULL_OBB: Obb = Obb {
    centre: Vector::new(0.0, 0.0, 0.0),
    axes: [
        Vector::new(1.0, 0.0, 0.0),
        Vector::new(0.0, 1.0, 0.0),
        Vector::new(0.0, 0.0, 1.0),
    ],
    half: [0.0; 3],
};

/// Oriented and axis-aligned boxes of every face of a surface, with each
/// face polygon in its box frame; buffers are reused between calls.
///
/// A face is *valid* when it has at least three points, all finite, a
/// finite unit normal, a finite centre and an area above
/// [`DEGENERATE_AREA`]` · h̄²`. Invalid faces get an empty AABB, no
/// polygon, and take part in no pair.
#[derive(Debug, Default, Clone)]
pub struct FaceBoxes {
    /// OBB of every face (eq. 4.10; meaningless for invalid faces).
    pub obb: Vec<Obb>,
    /// AABB of every OBB (empty for invalid faces).
    pub aabb: Vec<Aabb>,
    /// Whether the face is valid.
    pub valid: Vec<bool>,
    /// Longest side of the face's (uninflated) minimum-area rectangle.
    pub scale: Vec<Real>,
    /// `polygon_offsets[f]..polygon_offsets[f+1]` indexes `polygon`.
    pub polygon_offsets: Vec<u32>,
    /// Face points in the in-plane axes of the face OBB, relative to its centre.
    pub polygon: Vec<V2>,
    /// Unit edge normals of each polygon (indexed like `polygon`).
    pub polygon_axes: Vec<V2>,
    /// Extent of each polygon along its edge normals (indexed like `polygon`).
    pub polygon_extents: Vec<[Real; 2]>,
    /// Bounding box of each polygon in its frame, `[x_min, x_max, y_min, y_max]`.
    pub polygon_box: Vec<[Real; 4]>,
    /// Largest distance from the face centre to a face point.
    pub radius: Vec<Real>,
    /// Number of invalid faces.
    pub n_invalid: usize,
    scratch: ObbScratch,
}

impl FaceBoxes {
    /// Recomputes all boxes of `s` for mean cell height `h` (eq. 4.10);
    /// the polygons (needed on the master side only) if `polygons`.
    pub fn update(&mut self, s: &Surface, h: Real, params: &DetectParams, polygons: bool) {
        self.update_listed(s, h, params, polygons, None);
    }

    /// As [`FaceBoxes::update`], but only for the faces flagged in `listed`
    /// (all faces if `None`): the others get the box of an invalid face
    /// (not counted in [`FaceBoxes::n_invalid`]). A listed face's box is
    /// the one [`FaceBoxes::update`] computes, to the bit.
    pub fn update_listed(
        &mut self,
        s: &Surface,
        h: Real,
        params: &DetectParams,
        polygons: bool,
        listed: Option<&[bool]>,
    ) {
        self.clear();
        let size = FaceBoxSize {
            extrude_out: params.extrusion_out * h,
            extrude_in: params.extrusion_in * h,
            inflation: params.inflation,
        };
        let min_area = DEGENERATE_AREA * h * h;
        for f in 0..s.faces.len() {
            if listed.is_none_or(|l| l.get(f).copied().unwrap_or(false)) {
                self.push_face(s, f, &size, min_area, polygons);
            } else {
                self.push_invalid();
            }
        }
    }

    fn clear(&mut self) {
        self.obb.clear();
        self.aabb.clear();
        self.valid.clear();
        self.scale.clear();
        self.polygon_offsets.clear();
        self.polygon.clear();
        self.polygon_axes.clear();
        self.polygon_extents.clear();
        self.polygon_box.clear();
        self.radius.clear();
        self.polygon_offsets.push(0);
        self.n_invalid = 0;
    }

    /// Appends the entries of a face that takes part in no pair (no box,
    /// no polygon).
    fn push_invalid(&mut self) {
        self.obb.push(NULL_OBB);
        self.aabb.push(Aabb::empty());
        self.valid.push(false);
        self.scale.push(0.0);
        self.polygon_box.push(prepare_polygon(
            &[],
            &mut self.polygon_axes,
            &mut self.polygon_extents,
        ));
        self.radius.push(0.0);
        self.polygon_offsets.push(self.polygon.len() as u32);
    }

    /// Appends the box of face `f` (invalid faces counted).
    fn push_face(
        &mut self,
        s: &Surface,
        f: usize,
        size: &FaceBoxSize,
        min_area: Real,
        polygons: bool,
    ) {
        let inflation = size.inflation;
        let pts = s.face(f);
        let n = s.face_normals[f];
        let c = s.face_centres[f];
        let mut ok = face_data_valid(s, f, min_area);
        let mut obb = NULL_OBB;
        if ok {
            let start = self.polygon.len();
            match face_obb(
                pts.iter().map(|&p| s.points[p as usize]),
                &n,
                &c,
                size,
                &mut self.scratch,
                polygons.then_some(&mut self.polygon),
            ) {
                Some(b) => obb = b,
                None => {
                    self.polygon.truncate(start);
                    ok = false;
                }
            }
        }
        let start = self.polygon_offsets[f] as usize;
        let bbox = prepare_polygon(
            &self.polygon[start..],
            &mut self.polygon_axes,
            &mut self.polygon_extents,
        );
        self.polygon_box.push(bbox);
        let r2 = if ok {
            pts.iter()
                .map(|&p| (s.points[p as usize] - c).norm_squared())
                .fold(0.0, Real::max)
        } else {
            0.0
        };
        self.radius.push(r2.sqrt());
        if ok {
            let k = 2.0 / (1.0 + inflation);
            self.scale.push(k * obb.half[0].max(obb.half[1]));
            self.aabb.push(obb.aabb());
        } else {
            self.n_invalid += 1;
            self.scale.push(0.0);
            self.aabb.push(Aabb::empty());
        }
        self.obb.push(obb);
        self.valid.push(ok);
        self.polygon_offsets.push(self.polygon.len() as u32);
    }

    /// Polygon of face `f` with its separating axes (empty for invalid faces).
    #[inline]
    pub fn prepared_polygon(&self, f: usize) -> PreparedPolygon<'_> {
        let r = self.polygon_offsets[f] as usize..self.polygon_offsets[f + 1] as usize;
        PreparedPolygon {
            points: &self.polygon[r.clone()],
            axes: &self.polygon_axes[r.clone()],
            extents: &self.polygon_extents[r],
            bbox: self.polygon_box[f],
        }
    }

    /// Polygon of face `f` in its OBB frame (empty for invalid faces).
    #[inline]
    pub fn polygon(&self, f: usize) -> &[V2] {
        &self.polygon[self.polygon_offsets[f] as usize..self.polygon_offsets[f + 1] as usize]
    }
}
