//! Per-call data shared by all detectors: h̄, face boxes, contact zone,
//! and the pair test that defines a candidate pair.
use crate::contact_zone::ContactZone;
use crate::convex_hull_2d::V2;
use crate::face_boxes::{mean_face_size, FaceBoxes};
use crate::sat_obb_obb::obb_overlap;
use crate::sat_polygon_polygon::prepared_polygons_overlap;
use crate::surface_check::check_surface;
use crate::{DetectError, DetectParams, DetectionStats};
use fv_mesh::{Real, Surface};

/// Faces of both surfaces from which their boxes are built on two threads
/// ([`Workspace::prepare`]).
const PARALLEL_FACES: usize = 2048;

/// Largest slave polygon projected on the stack; larger ones allocate.
const STACK_POLYGON: usize = 16;

/// Boxes, zone and parameters of one detection call (allocated once,
/// refilled every call).
#[derive(Debug, Default, Clone)]
pub struct Workspace {
    /// Parameters in force.
    pub params: DetectParams,
    /// h̄ used for this call (eq. 4.10).
    pub h: Real,
    /// Master face boxes.
    pub master: FaceBoxes,
    /// Slave face boxes.
    pub slave: FaceBoxes,
    /// Contact zone and the faces in it (Fig. 4.11).
    pub zone: ContactZone,
}

impl Workspace {
    /// Checks the inputs, then builds h̄, every face box and the contact zone.
    /// Cost O(faces) with a small constant (rotating calipers per face); the
    /// master and slave boxes are built in parallel (rayon).
    pub fn prepare(
        &mut self,
        master: &Surface,
        slave: &Surface,
        params: &DetectParams,
    ) -> Result<(), DetectError> {
        params.validate()?;
        check_surface(master, "master")?;
        check_surface(slave, "slave")?;
        self.params = *params;
        self.h = params
            .mean_cell_height
            .or_else(|| mean_face_size(master, slave))
            .unwrap_or(0.0);
        let (h, mb, sb) = (self.h, &mut self.master, &mut self.slave);
        // the two surfaces are independent: one thread each when there are
        // enough faces to pay for the hand-off (a join from outside the pool
        // costs tens of µs: 65 % of the detection time of curved beams'
        // 50-face surfaces)
        if master.n_faces() + slave.n_faces() >= PARALLEL_FACES {
            rayon::join(
                || mb.update(master, h, params, true),
                || sb.update(slave, h, params, false),
            );
        } else {
            mb.update(master, h, params, true);
            sb.update(slave, h, params, false);
        }
        self.zone.update(&self.master, &self.slave);
        Ok(())
    }

    /// Boxes of the listed faces only, for `h` given (the caller computed
    /// it as [`Workspace::prepare`] does): pair tests on a known list of
    /// candidates ([`crate::PairReuse`]). Serial; the contact zone is not
    /// updated (the pair test does not read it).
    pub fn prepare_listed(
        &mut self,
        master: &Surface,
        slave: &Surface,
        params: &DetectParams,
        h: Real,
        listed: [&[bool]; 2],
    ) {
        self.params = *params;
        self.h = h;
        self.master
            .update_listed(master, h, params, true, Some(listed[0]));
        self.slave
            .update_listed(slave, h, params, false, Some(listed[1]));
    }

    /// Statistics of the prepared call, before any pair test.
    pub fn base_stats(&self) -> DetectionStats {
        DetectionStats {
            mean_cell_height: self.h,
            master_faces_in_zone: self.zone.master_faces.len(),
            slave_faces_in_zone: self.zone.slave_faces.len(),
            skipped_faces: self.master.n_invalid + self.slave.n_invalid,
            ..Default::default()
        }
    }

    /// Whether the AABBs of the OBBs of `(m, s)` meet (necessary for a pair;
    /// invalid faces have empty AABBs).
    #[inline]
    pub fn aabb_test(&self, m: usize, s: usize, stats: &mut DetectionStats) -> bool {
        stats.aabb_tests += 1;
        self.master.aabb[m].intersects(&self.slave.aabb[s])
    }

    /// Whether the OBBs of `(m, s)` overlap (3-D SAT).
    #[inline]
    pub fn obb_test(&self, m: usize, s: usize, stats: &mut DetectionStats) -> bool {
        stats.obb_tests += 1;
        obb_overlap(&self.master.obb[m], &self.slave.obb[s])
    }

    /// Front condition of the advancing front: valid slave face `s`,
    /// projected onto the plane of master face `m`, overlaps its polygon
    /// (the local phase alone, blind to the distance along the normal).
    /// Faces whose bounding disc (centre, [`FaceBoxes::radius`]) projects
    /// clear of the polygon's bounding box are rejected first.
    #[inline]
    pub fn front_test(
        &self,
        slave: &Surface,
        m: usize,
        s: usize,
        stats: &mut DetectionStats,
    ) -> bool {
        stats.front_tests += 1;
        if !self.slave.valid[s] {
            return false;
        }
        let b = &self.master.obb[m];
        let r = slave.face_centres[s] - b.centre;
        let (x, y) = (r.dot(&b.axes[0]), r.dot(&b.axes[1]));
        let rho = self.slave.radius[s];
        let bb = &self.master.polygon_box[m];
        let slack = rho
            + self.params.touch_tolerance * self.master.scale[m]
            + 1e-9 * (rho + self.master.scale[m]);
        if x - slack > bb[1] || x + slack < bb[0] || y - slack > bb[3] || y + slack < bb[2] {
            return false;
        }
        self.local_test(slave, m, s, stats)
    }

    /// Global phase for `(m, s)`: the AABBs of the OBBs meet, then the OBBs
    /// overlap (3-D SAT).
    #[inline]
    pub fn global_test(&self, m: usize, s: usize, stats: &mut DetectionStats) -> bool {
        self.aabb_test(m, s, stats) && self.obb_test(m, s, stats)
    }

    /// Local phase for `(m, s)`: slave polygon projected onto the plane of
    /// master face `m` overlaps polygon `m` (2-D SAT with the touch tolerance).
    #[inline]
    pub fn local_test(
        &self,
        slave: &Surface,
        m: usize,
        s: usize,
        stats: &mut DetectionStats,
    ) -> bool {
        stats.polygon_tests += 1;
        let b = &self.master.obb[m];
        let (u, v, c) = (b.axes[0], b.axes[1], b.centre);
        let project = |p: &u32| {
            let r = slave.points[*p as usize] - c;
            V2::new(r.dot(&u), r.dot(&v))
        };
        let tol = self.params.touch_tolerance * self.master.scale[m];
        let mpoly = self.master.prepared_polygon(m);
        let pts = slave.face(s);
        if pts.len() <= STACK_POLYGON {
            let mut buf = [V2::zeros(); STACK_POLYGON];
            for (q, p) in buf.iter_mut().zip(pts) {
                *q = project(p);
            }
            prepared_polygons_overlap(&mpoly, &buf[..pts.len()], tol)
        } else {
            let poly: Vec<V2> = pts.iter().map(project).collect();
            prepared_polygons_overlap(&mpoly, &poly, tol)
        }
    }

    /// The pair definition: global phase and local phase (see the crate docs).
    #[inline]
    pub fn is_pair(&self, slave: &Surface, m: usize, s: usize, stats: &mut DetectionStats) -> bool {
        self.global_test(m, s, stats) && self.local_test(slave, m, s, stats)
    }
}
