//! The pointwise contact algorithm (thesis §4.3, eqs. 4.11–4.12; Cardiff
//! et al.): gaps at the slave points, pressure averaged to the slave faces,
//! tractions transferred to the master by GGI (eq. 4.5).
use crate::auxiliary_plane::{AuxiliaryPlane, MIN_FACING_COSINE};
use crate::contact_algorithm::{
    check_inputs, finish_stats, ContactAlgorithm, ContactAlgorithmKind,
};
use crate::contact_tractions::{ContactStats, ContactTractions, NO_GAP};
use crate::coulomb_friction::{face_friction, FrictionState, SlipHistory};
use crate::face_pairs::{FacePairs, PairsTranspose};
use crate::face_shifts::FaceShifts;
use crate::ggi::GgiScratch;
use crate::increment_state::{face_mean, IncrementState, Side};
use crate::penalty::{normal_pressure, ContactLaw};
use crate::segment_to_segment::valid_face;
use crate::smoothed_master::SmoothedMaster;
use crate::sutherland_hodgman::{clip_non_positive, signed_area, Point2};
use crate::ContactError;
use fv_mesh::{Real, Surface, Vector};

/// Pointwise contact (§4.3), the baseline the thesis compares against:
///
/// 1. gap at every slave point by closest-point projection (eq. 2.34) onto
///    the master faces paired with the point's faces, measured along the
///    master face normal; a point that faces no master face has no gap,
///    nor one whose closest point lies on the border of the master surface
///    farther than [`BORDER_REACH`] (beyond the thesis: nearer, it keeps
///    the gap to the border face's plane);
/// 2. slave face normal traction `−(1/n_p) Σ_p ε_n ⟨−g_p⟩ n_s` (eq. 4.11,
///    unit point weights; the printed `1/|Γ_bs|` factor is dimensionally a
///    misprint and is not applied, as in solids4foam), times the face's
///    GGI coverage where a point lies beyond the master's border;
/// 3. friction at the slave face centres with the slip of eq. 4.12, the
///    master increment interpolated by normalised GGI weights (eq. 4.6);
/// 4. master tractions `t_m = −Σ_k ω_{j,k} t_s,k` (eq. 4.5), normal and
///    tangential parts separately.
///
/// The contact fraction β of a slave face is the part of its centre
/// triangulation (centre value = mean of point gaps) where the linearly
/// interpolated gap is ≤ 0; on the master it is GGI-transferred.
///
/// With Nagata smoothing of the master ([`Pointwise::nagata`],
/// `"pointwise-nagata"`, thesis §4.6.1) step 1 projects each slave point
/// orthogonally onto the smoothed master (Newton–Raphson, eqs. 4.81–4.84,
/// at most 10 updates) among the patches around the closest flat face,
/// keeping the foot with the smallest gap among those inside their patch;
/// the gap is the signed distance along the smoothed normal. A point with
/// no such foot (beyond the master's border) keeps its flat gap. In step 2 the normal traction of a slave
/// point acts along the smoothed master normal at its foot, so eq. 4.11
/// reads `t_s = (1/n_p) Σ_p ε_n ⟨−g_p⟩ ν_p` (ν_p = n_bs for flat faces in
/// contact); the face pressure stays `(1/n_p) Σ_p ε_n ⟨−g_p⟩`. Points
/// farther out than twice the face's patch deviation bound (they cannot
/// touch the smoothed surface), or over a face whose patch and neighbours'
/// patches are all flat, keep their flat gap. A translated rigid master
/// is smoothed once; a deformable one is refreshed in place every call.
///
/// Cost per call O(pairs · points² + slave points · candidates), plus one
/// projection onto the ~9 patches around a face per slave point near
/// contact with smoothing.
#[derive(Debug, Clone, Default)]
pub struct Pointwise {
    smoothing: Option<SmoothedMaster>,
    point_normal: Vec<Vector>,
    state: IncrementState,
    transpose: PairsTranspose,
    ggi_scratch: GgiScratch,
    point_gap: Vec<Real>,
    /// Master face of each slave point's foot (`u32::MAX`: none).
    point_master: Vec<u32>,
    /// The slave point lies beyond the master surface's border
    /// ([`BORDER_REACH`]).
    point_beyond: Vec<bool>,
    /// GGI coverage of each slave face reaching beyond the master's border
    /// (1 for the others).
    coverage: Vec<Real>,
    /// Gaps of the points of one slave face with the face shifts.
    face_gaps: Vec<Real>,
    /// Smallest gap at the points of each slave face (+∞: none), for the
    /// friction's contact share (`IncrementState::share`).
    min_gaps: Vec<Real>,
    shifts: FaceShifts,
    /// The master's symmetry and wedge planes (point, unit normal): the
    /// surface continues across them in its mirror or rotated image.
    symmetry_planes: Vec<(Vector, Vector)>,
    candidates: Vec<u32>,
    master_du: Vec<Vector>,
    slave_du_hat: Vec<Vector>,
    slave_values: Vec<Vector>,
    tri: Vec<Point2>,
    tri_values: Vec<Real>,
    clipped: Vec<Point2>,
    clipped_values: Vec<Real>,
}

/// A slave point beyond the master surface's border keeps the gap to the
/// plane of the border face it is closest to, as long as it lies within
/// this many face sizes (√area; the larger of that master face and the
/// point's slave faces) of the border; its faces' pressure is then scaled
/// by the part of the face over the master ([`GgiWeights::slave_coverage`],
/// eq. 4.9). Beyond the thesis, whose points there have no gap and count
/// as open in the face's mean (eq. 4.11): a slave edge that overhung the
/// master's by 1.8 % of a face (two blocks of different Poisson's ratio
/// pressed together) lost half its last face's pressure (1.25 and 0.80
/// times the uniform pressure on the last two faces, contact area −10 %).
/// Scaled by the coverage, the pressure varies continuously as an edge
/// point crosses the border (equal blocks, whose edges lie on each other
/// within 1e-9 to 1e-5 of a face from one outer iteration to the next,
/// switched it on and off: twisting blocks never converged its last
/// increment).
///
/// [`GgiWeights::slave_coverage`]: crate::ggi::GgiWeights::slave_coverage
const BORDER_REACH: Real = 1.0;

/// A point lies on a symmetry or wedge plane within this fraction of the
/// master face's size (√area).
const SYMMETRY_PLANE_TOLERANCE: Real = 1e-6;

/// Closest point of face `f` to `x`: the orthogonal projection on the face
/// plane if it falls inside the (convex) face, else the closest point of
/// its boundary; with the index (in the face) of that boundary side.
fn closest_point_on_face(surface: &Surface, f: usize, x: &Vector) -> (Vector, Option<usize>) {
    let n = surface.face_normals[f];
    let c = surface.face_centres[f];
    let xp = x - n * n.dot(&(x - c));
    let fp = surface.face(f);
    let k = fp.len();
    let mut inside = true;
    for i in 0..k {
        let a = surface.points[fp[i] as usize];
        let b = surface.points[fp[(i + 1) % k] as usize];
        let e = b - a;
        if n.dot(&e.cross(&(xp - a))) < -1e-10 * e.norm_squared() {
            inside = false;
            break;
        }
    }
    if inside {
        return (xp, None);
    }
    let mut best = (xp, None, Real::INFINITY);
    for i in 0..k {
        let a = surface.points[fp[i] as usize];
        let b = surface.points[fp[(i + 1) % k] as usize];
        let e = b - a;
        let l2 = e.norm_squared();
        let t = if l2 > 0.0 {
            ((xp - a).dot(&e) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = a + e * t;
        let d = (xp - q).norm_squared();
        if d < best.2 {
            best = (q, Some(i), d);
        }
    }
    (best.0, best.1)
}

impl Pointwise {
    /// A new algorithm with no friction history.
    pub fn new() -> Self {
        Self::default()
    }

    /// The same against the Nagata-smoothed master (`"pointwise-nagata"`).
    pub fn nagata() -> Self {
        Pointwise {
            smoothing: Some(SmoothedMaster::default()),
            ..Self::default()
        }
    }

    /// How many times the master surface was smoothed (built or refreshed
    /// in place) so far; 0 without smoothing. A translated rigid master is
    /// smoothed once.
    pub fn smoothing_refreshes(&self) -> usize {
        self.smoothing.as_ref().map_or(0, SmoothedMaster::refreshes)
    }

    /// Step 1: gap at every slave point (NO_GAP where there is none), and
    /// the master normal at its foot.
    fn point_gaps(&mut self, master: &Surface, slave: &Surface) {
        let smooth = match self.smoothing.as_mut() {
            Some(sm) => sm.sync(master),
            None => false,
        };
        self.point_gap.clear();
        self.point_gap.resize(slave.n_points(), NO_GAP);
        self.point_normal.clear();
        self.point_normal.resize(slave.n_points(), Vector::zeros());
        self.point_master.clear();
        self.point_master.resize(slave.n_points(), u32::MAX);
        self.point_beyond.clear();
        self.point_beyond.resize(slave.n_points(), false);
        for p in 0..slave.n_points() {
            let x = slave.points[p];
            if !x.iter().all(|v| v.is_finite()) {
                continue;
            }
            self.candidates.clear();
            for &f in slave.faces_of_point(p) {
                self.candidates
                    .extend_from_slice(self.transpose.masters_of(f as usize));
            }
            self.candidates.sort_unstable();
            self.candidates.dedup();
            let np = slave.point_normals[p];
            // (distance², gap, on border, face, closest point)
            let mut best: Option<(Real, Real, bool, usize, Vector)> = None;
            for &m in &self.candidates {
                let mu = m as usize;
                if !valid_face(master, mu) {
                    continue;
                }
                let nm = master.face_normals[mu];
                if np.norm_squared() > 0.0 && !(nm.dot(&np) <= -MIN_FACING_COSINE) {
                    continue;
                }
                let (q, side) = closest_point_on_face(master, mu, &x);
                let d2 = (x - q).norm_squared();
                let border = side
                    .is_some_and(|i| master.is_border_edge(master.face_edge_ids(mu)[i] as usize));
                // ties (a point over a shared edge) go to the face containing the projection
                let better = match best {
                    None => true,
                    Some((bd, ..)) => d2 < bd * (1.0 - 1e-12) || (d2 <= bd && side.is_none()),
                };
                if better {
                    best = Some((d2, (x - q).dot(&nm), border, mu, q));
                }
            }
            if let Some((d2, g, border, m, q)) = best {
                // beyond the master surface's border: the gap to the border
                // face's plane within BORDER_REACH, the faces scaled by
                // their coverage (step 2)
                let beyond = border && !self.on_symmetry_plane(master, m, &x);
                if beyond {
                    // the foot's distance across the face plane
                    let outside = (d2 - g * g).max(0.0).sqrt();
                    let size = slave
                        .faces_of_point(p)
                        .iter()
                        .map(|&f| slave.face_mag[f as usize].sqrt())
                        .fold(master.face_mag[m].sqrt(), Real::max);
                    if !(outside <= BORDER_REACH * size) {
                        continue;
                    }
                }
                self.point_gap[p] = g;
                self.point_beyond[p] = beyond;
                self.point_normal[p] = master.face_normals[m];
                self.point_master[p] = m as u32;
                let Some(sm) = self.smoothing.as_ref().filter(|_| smooth) else {
                    continue;
                };
                if sm.clear_of(m, g) || sm.flat_around(m) {
                    continue;
                }
                // beyond the border: the smoothed gap where the point's
                // normal line meets the border (flat, the same gap)
                let probe = if beyond {
                    q + master.face_normals[m] * g
                } else {
                    x
                };
                if let Some(sg) = sm.gap_inside(&probe, m) {
                    self.point_gap[p] = sg.gap;
                    self.point_normal[p] = sg.normal;
                }
            }
        }
    }

    /// Whether slave point `x`, whose closest point on master face `m` is on
    /// the master surface's border, lies on a symmetry or wedge plane that
    /// also holds that border: the surface continues across the plane in
    /// its image, so the point is not beyond the surface. In a one-cell
    /// wedge every slave point lies on a wedge plane next to a border edge,
    /// and a face tilted by 10⁻⁵ put a penetrating point's projection a
    /// rounding error outside it: points lost their gaps at random from
    /// one outer iteration to the next, and implicit coupling under the
    /// NAFEMS punch never converged.
    fn on_symmetry_plane(&self, master: &Surface, m: usize, x: &Vector) -> bool {
        let size = master.face_mag[m].sqrt();
        let tol = SYMMETRY_PLANE_TOLERANCE * size;
        let fp = master.face(m);
        let edges = master.face_edge_ids(m);
        self.symmetry_planes.iter().any(|(origin, n)| {
            let on = |y: &Vector| (y - origin).dot(n).abs() <= tol;
            on(x)
                && (0..fp.len()).any(|i| {
                    master.is_border_edge(edges[i] as usize)
                        && on(&master.points[fp[i] as usize])
                        && on(&master.points[fp[(i + 1) % fp.len()] as usize])
                })
        })
    }

    /// The gaps of the points of slave face `s` into `self.face_gaps`, each
    /// with the face's shift relative to the master face of the point's foot
    /// ([`FaceShifts`]; along the master normal there).
    fn shifted_face_gaps(&mut self, slave: &Surface, s: usize) {
        self.face_gaps.clear();
        for &q in slave.face(s) {
            let q = q as usize;
            let (g, m) = (self.point_gap[q], self.point_master[q]);
            self.face_gaps.push(if g.is_finite() && m != u32::MAX {
                g + self.point_normal[q].dot(&self.shifts.relative(m as usize, s))
            } else {
                g
            });
        }
    }

    /// Contact fraction of slave face `s` from its point gaps
    /// (`self.face_gaps`, [`Self::shifted_face_gaps`]).
    fn slave_fraction(&mut self, slave: &Surface, s: usize) -> Real {
        let Some(plane) = AuxiliaryPlane::of_face(slave, s) else {
            return 0.0;
        };
        let fp = slave.face(s);
        let k = fp.len();
        let size = slave.face_mag[s].sqrt();
        let gaps = &self.face_gaps;
        let g = |i: usize| {
            let g = gaps[i];
            if g.is_finite() {
                g
            } else {
                size
            }
        };
        let gc = (0..k).map(g).sum::<Real>() / k as Real;
        let c = plane.project(&slave.face_centres[s]);
        let (mut total, mut contact) = (0.0, 0.0);
        for i in 0..k {
            let (a, b) = (fp[i], fp[(i + 1) % k]);
            self.tri.clear();
            self.tri.extend([
                c,
                plane.project(&slave.points[a as usize]),
                plane.project(&slave.points[b as usize]),
            ]);
            self.tri_values.clear();
            self.tri_values.extend([gc, g(i), g((i + 1) % k)]);
            total += signed_area(&self.tri).abs();
            clip_non_positive(
                &self.tri,
                &self.tri_values,
                &mut self.clipped,
                &mut self.clipped_values,
            );
            contact += signed_area(&self.clipped).abs();
        }
        if total > 0.0 {
            (contact / total).min(1.0)
        } else {
            0.0
        }
    }
}

impl ContactAlgorithm for Pointwise {
    fn compute(
        &mut self,
        master: &Surface,
        slave: &Surface,
        pairs: &dyn FacePairs,
        law: &ContactLaw,
        out: &mut ContactTractions,
    ) -> Result<ContactStats, ContactError> {
        check_inputs(master, slave, pairs, law)?;
        let (nm, ns) = (master.n_faces(), slave.n_faces());
        out.reset(nm, ns);
        self.state.prepare(master, slave);
        self.state
            .pending_master
            .iter_mut()
            .for_each(|v| *v = Vector::zeros());
        self.state
            .pending_slave
            .iter_mut()
            .for_each(|v| *v = Vector::zeros());
        self.transpose.build(pairs, ns);
        out.ggi.build(master, slave, pairs, &mut self.ggi_scratch);
        self.point_gaps(master, slave);

        // 2: slave normal traction (eq. 4.11), gap, contact fraction
        self.min_gaps.clear();
        self.min_gaps.resize(ns, Real::INFINITY);
        self.coverage.clear();
        self.coverage.resize(ns, 1.0);
        let mut contact_area = 0.0;
        let mut max_penetration: Real = 0.0;
        for s in 0..ns {
            if !valid_face(slave, s) {
                continue;
            }
            self.shifted_face_gaps(slave, s);
            let fp = slave.face(s);
            // a face reaching beyond the master's border presses with the
            // part of it over the master (BORDER_REACH)
            let coverage = if fp.iter().any(|&q| self.point_beyond[q as usize]) {
                out.ggi.slave_coverage(s).min(1.0)
            } else {
                1.0
            };
            self.coverage[s] = coverage;
            let inv = coverage / fp.len() as Real;
            let p = self
                .face_gaps
                .iter()
                .map(|&g| normal_pressure(law.normal_penalty, g))
                .sum::<Real>()
                * inv;
            let t = if self.smoothing.is_some() {
                // along the master normal at each foot (smoothed or flat)
                fp.iter()
                    .zip(&self.face_gaps)
                    .map(|(&q, &g)| {
                        self.point_normal[q as usize] * normal_pressure(law.normal_penalty, g)
                    })
                    .sum::<Vector>()
                    * inv
            } else {
                -slave.face_normals[s] * p
            };
            let (mut gsum, mut gn) = (0.0, 0usize);
            for &g in &self.face_gaps {
                if g.is_finite() {
                    gsum += g;
                    gn += 1;
                    max_penetration = max_penetration.max(-g);
                    self.min_gaps[s] = self.min_gaps[s].min(g);
                }
            }
            if gn > 0 {
                out.slave.gap[s] = gsum / gn as Real;
            }
            if p > 0.0 {
                out.slave.pressure[s] = p;
                out.slave.normal_traction[s] = t;
                let beta = self.slave_fraction(slave, s) * coverage;
                out.slave.contact_fraction[s] = beta;
                contact_area += beta * slave.face_mag[s];
            }
        }

        // 3: slave friction (eq. 4.12)
        self.state.record_gaps(&[], &self.min_gaps);
        let accumulated = law.slip_history == SlipHistory::Accumulated;
        self.master_du.clear();
        self.master_du
            .extend((0..nm).map(|m| face_mean(master, &self.state.du_master, m)));
        self.slave_du_hat.clear();
        self.slave_du_hat.resize(ns, Vector::zeros());
        out.ggi
            .to_slave(&self.master_du, &mut self.slave_du_hat, true);
        for s in 0..ns {
            let p = out.slave.pressure[s];
            if !(p > 0.0) {
                continue;
            }
            let share = self.state.share(
                Side::Slave,
                s,
                self.state.start_gap_slave[s],
                self.min_gaps[s],
            );
            let own = face_mean(slave, &self.state.du_slave, s) * share;
            let other = self.slave_du_hat[s] * share;
            let hist = if accumulated {
                self.state.elastic_slave[s]
            } else {
                Vector::zeros()
            };
            let ff = face_friction(
                &slave.face_normals[s],
                p,
                out.slave.contact_fraction[s],
                &own,
                &other,
                &hist,
                law.tangential_penalty,
                law.friction,
            );
            out.slave.tangential_traction[s] = ff.traction;
            out.slave.slip[s] = ff.slip;
            out.slave.friction_state[s] = ff.state;
            self.state.pending_slave[s] = ff.elastic_slip;
        }

        // 4: transfer to the master (eq. 4.5); a face partly beyond the
        // master's border passes on the traction of its covered part, so
        // that the master receives the force the slave face carries
        let covered = |(t, &c): (&Vector, &Real)| if c > 0.0 { -t / c } else { Vector::zeros() };
        self.slave_values.clear();
        self.slave_values.extend(
            out.slave
                .normal_traction
                .iter()
                .zip(&self.coverage)
                .map(covered),
        );
        out.ggi
            .to_master(&self.slave_values, &mut out.master.normal_traction, false);
        self.slave_values.clear();
        self.slave_values.extend(
            out.slave
                .tangential_traction
                .iter()
                .zip(&self.coverage)
                .map(covered),
        );
        out.ggi.to_master(
            &self.slave_values,
            &mut out.master.tangential_traction,
            false,
        );
        self.slave_values.clear();
        self.slave_values.extend(out.slave.slip.iter().map(|t| -t));
        out.ggi
            .to_master(&self.slave_values, &mut out.master.slip, true);
        out.ggi.to_master(
            &out.slave.contact_fraction,
            &mut out.master.contact_fraction,
            false,
        );
        for m in 0..nm {
            out.master.pressure[m] = -out.master.normal_traction[m].dot(&master.face_normals[m]);
            let (faces, areas) = out.ggi.master_row(m);
            let (mut gsum, mut asum, mut dominant) = (0.0, 0.0, (0.0, FrictionState::Inactive));
            for (&s, &a) in faces.iter().zip(areas) {
                let g = out.slave.gap[s as usize];
                if g.is_finite() {
                    gsum += g * a;
                    asum += a;
                }
                if a > dominant.0 {
                    dominant = (a, out.slave.friction_state[s as usize]);
                }
            }
            if asum > 0.0 {
                out.master.gap[m] = gsum / asum;
            }
            out.master.contact_fraction[m] = out.master.contact_fraction[m].min(1.0);
            if out.master.contact_fraction[m] > 0.0 {
                out.master.friction_state[m] = dominant.1;
            }
        }

        let mut stats = finish_stats(master, slave, out);
        stats.contact_area = contact_area;
        stats.max_penetration = max_penetration;
        stats.n_overlapping_pairs = out.ggi.n_pairs();
        Ok(stats)
    }

    fn commit_increment(&mut self, master: &Surface, slave: &Surface) {
        self.state.commit(master, slave);
    }

    fn reset(&mut self) {
        self.state.reset();
    }

    fn save_state(&self, prefix: &str, out: &mut fv_mesh::StateArrays) {
        self.state.save_state(prefix, out);
    }

    fn restore_state(&mut self, prefix: &str, s: &fv_mesh::StateArrays) -> Result<(), String> {
        self.state.restore_state(prefix, s)
    }

    fn set_face_shifts(&mut self, master: &[Vector], slave: &[Vector]) {
        self.shifts.set(master, slave);
    }

    fn freeze_friction_shares(&mut self, frozen: bool) {
        self.state.freeze_shares(frozen);
    }

    fn set_symmetry_planes(&mut self, planes: &[contact_smooth::SymmetryPlane]) {
        self.symmetry_planes = planes
            .iter()
            .filter_map(|p| {
                let n = p.normal.try_normalize(0.0)?;
                Some((p.origin, n))
            })
            .collect();
        if let Some(sm) = self.smoothing.as_mut() {
            sm.set_symmetry_planes(planes);
        }
    }

    fn kind(&self) -> ContactAlgorithmKind {
        if self.smoothing.is_some() {
            ContactAlgorithmKind::PointwiseNagata
        } else {
            ContactAlgorithmKind::Pointwise
        }
    }
}
