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
        let (extrude_out, extrude_in, inflation) =
            (params.extrusion_out, params.extrusion_in, params.inflation);
        let nf = s.faces.len();
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
        let size = FaceBoxSize {
            extrude_out: extrude_out * h,
            extrude_in: extrude_in * h,
            inflation,
        };
        let min_area = DEGENERATE_AREA * h * h;
        let null = Obb {
            centre: Vector::zeros(),
            axes: [Vector::x(), Vector::y(), Vector::z()],
            half: [0.0; 3],
        };
        for f in 0..nf {
            let pts = s.face(f);
            let n = s.face_normals[f];
            let c = s.face_centres[f];
            let area = s.face_mag[f];
            let mut ok = pts.len() >= 3
                && area.is_finite()
                && area > min_area
                && n.iter().all(|x| x.is_finite())
                && (n.norm_squared() - 1.0).abs() < 1e-6
                && c.iter().all(|x| x.is_finite())
                && pts
                    .iter()
                    .all(|&p| s.points[p as usize].iter().all(|x| x.is_finite()));
            let mut obb = null;
            if ok {
                let start = self.polygon.len();
                match face_obb(
                    pts.iter().map(|&p| s.points[p as usize]),
                    &n,
                    &c,
                    &size,
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
