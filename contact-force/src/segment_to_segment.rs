//! The segment-to-segment contact algorithm (thesis §4.4, eqs. 4.14–4.27).
use crate::auxiliary_plane::{AuxiliaryPlane, AREA_TOLERANCE, MIN_FACING_COSINE};
use crate::barycentric::{locate_in_polygon, Located};
use crate::contact_algorithm::{
    check_inputs, finish_stats, ContactAlgorithm, ContactAlgorithmKind,
};
use crate::contact_tractions::{ContactStats, ContactTractions};
use crate::coulomb_friction::{face_friction, SlipHistory};
use crate::face_pairs::{FacePairs, PairsTranspose};
use crate::face_shifts::FaceShifts;
use crate::increment_state::{face_mean, IncrementState, Side};
use crate::occluded_volume::central_integral;
use crate::penalty::ContactLaw;
use crate::smoothed_master::{SmoothedGap, SmoothedMaster};
use crate::sutherland_hodgman::{
    clip_convex, clip_non_positive, signed_area, Affine2, ClipScratch, Point2,
};
use crate::ContactError;
use fv_mesh::{Real, Surface, Vector};

/// Segment-to-segment contact (§4.4): the penalty pressure is integrated
/// over the segments into which the projected slave faces cut each master
/// face, so the normal traction of both sides comes from the same occluded
/// volumes (action = reaction to round-off).
///
/// For every candidate pair (master face m, slave face s):
///
/// a. auxiliary plane through the master face centre with its normal n_m;
/// b. master and slave polygons projected on it (the master to remove
///    warping); pairs that do not face each other are skipped
///    ([`crate::MIN_FACING_COSINE`]);
/// c. Sutherland–Hodgman intersection k = s̄ ∩ m̄ (its area is the GGI
///    weight, eq. 4.7);
/// c*. the gap, measured by ray tracing along n_m (eq. 4.14) to the slave
///    face plane, is evaluated at the points of k, and k is clipped to its
///    non-positive-gap part k';
/// d–e. centre triangulation of k' and the occluded volume
///    `ḡ_k Γ_k = Σ_i ⅓ (g_i + g_{i+1} + g_c) Γ_i` (eqs. 4.24–4.25).
///
/// Master face force `ε_n n_m Σ_k ḡ_k Γ_k` (eq. 4.19), traction = force /
/// |Γ_m| (eq. 4.16); each slave face receives the opposite of its segments'
/// forces, divided by its own area. For a gap linear over each segment (flat
/// faces) the integral is exact.
///
/// Friction is computed on both surfaces independently (eqs. 4.20–4.23):
/// the slip of a face is its centre's displacement increment minus the
/// opposite surface's, interpolated by barycentric coordinates on the
/// centre triangulation of the opposite face hit by the ray from the face
/// centre along the face normal (eq. 4.26); the face's own centre increment
/// is the mean of its point increments. Displacement increments are
/// positions minus the positions at the last [`ContactAlgorithm::commit_increment`].
///
/// # Against the smoothed master (`"segment-to-segment-nagata"`)
///
/// Beyond the thesis (its §6 outlook): [`SegmentToSegment::nagata`] keeps
/// steps a–c (the segments and their GGI areas) but integrates the gap to
/// the Nagata-smoothed master surface (§4.6.1). Each triangle of the centre
/// triangulation of a segment is split into four at its edge midpoints;
/// at the 3n + 1 points of that sub-triangulation (n = segment points) the
/// slave point hit by the ray along n_m (eq. 4.14) is projected onto the
/// smoothed master (eqs. 4.81–4.84, the patch of m, else the closest among
/// the patches around m), giving the gap g and the smoothed normal ν. A
/// centre triangle wholly in contact (g ≤ 0 at its six nodes) is
/// integrated by the quadratic rule (weights Γ/3 at the edge midpoints,
/// exact for a quadratic gap, the faceting error's form): force
/// `ε_n Σ Γ/3 g ν`. Otherwise g is taken linear over each of its four
/// sub-triangles and clipped to its non-positive part (c*), and the
/// occluded volume carries the mean ν of the sub-triangle's corners. The
/// master face gets the sum, the slave face the opposite. Segments
/// whose flat gap exceeds twice the master face's patch deviation bound
/// everywhere cannot touch, and segments on flat patches have the flat
/// gap: neither is projected. Friction is unchanged
/// (flat faces). A translated rigid master is smoothed once; a deformable
/// one is refreshed in place every call.
///
/// Cost per call O(pairs · points²); after the first call no allocation
/// unless the surfaces or pair counts grow. Smoothing adds 3n + 1
/// projections (about 1 µs each) per segment near contact.
#[derive(Debug, Clone, Default)]
pub struct SegmentToSegment {
    smoothing: Option<SmoothedMaster>,
    state: IncrementState,
    transpose: PairsTranspose,
    scratch: Scratch,
    acc: Accumulators,
    shifts: FaceShifts,
}

#[derive(Debug, Clone, Default)]
struct Scratch {
    master: Vec<Point2>,
    slave_raw: Vec<Point2>,
    slave: Vec<Point2>,
    segment: Vec<Point2>,
    values: Vec<Real>,
    contact: Vec<Point2>,
    contact_values: Vec<Real>,
    clip: ClipScratch,
    /// Sub-triangulation of a segment (smoothing): points and their gaps.
    nodes: Vec<Point2>,
    node_gaps: Vec<SmoothedGap>,
    tri: Vec<Point2>,
    tri_values: Vec<Real>,
}

/// Centroid of the area of a convex polygon (the mean of its vertices if
/// it has none). Not the vertex mean: the clipping repeats a vertex where
/// a slave corner lies on a master edge, or not, by round-off, and the
/// vertex mean — the centre of the sub-triangulation — jumped with it (a
/// Newton–Krylov Jacobian product saw a 2 % jump of a face force for a
/// perturbation of 10⁻¹⁰).
fn area_centroid(poly: &[Point2]) -> Point2 {
    let n = poly.len();
    let mean = poly.iter().sum::<Point2>() / n.max(1) as Real;
    let (mut area, mut moment) = (0.0, Point2::zeros());
    for i in 0..n {
        let (p, q) = (poly[i] - mean, poly[(i + 1) % n] - mean);
        let a = 0.5 * p.perp(&q);
        area += a;
        moment += (p + q) * (a / 3.0);
    }
    if area.abs() > 0.0 {
        mean + moment / area
    } else {
        mean
    }
}

/// Integrals over one segment against the smoothed master.
#[derive(Debug, Clone, Copy, Default)]
struct SmoothedIntegral {
    /// ∫ g dΓ.
    gap: Real,
    /// Area where g ≤ 0.
    contact_area: Real,
    /// ∫ g⁻ dΓ (≤ 0).
    volume: Real,
    /// Σ ν̄ ∫ g⁻ dΓ over the sub-triangles.
    force: Vector,
    /// Smallest node gap in contact.
    min_gap: Real,
}

impl Scratch {
    /// Integrates the smoothed gap over `self.segment` (see
    /// [`SegmentToSegment`]): nodes `c, p_i, mid(p_i, p_i+1), mid(c, p_i)`.
    fn integrate_smoothed(
        &mut self,
        sm: &SmoothedMaster,
        plane: &AuxiliaryPlane,
        ray: &Affine2,
        m: usize,
    ) -> SmoothedIntegral {
        let n = self.segment.len();
        let mut r = SmoothedIntegral::default();
        if n < 3 {
            return r;
        }
        let c = area_centroid(&self.segment);
        self.nodes.clear();
        self.nodes.push(c);
        self.nodes.extend_from_slice(&self.segment);
        for i in 0..n {
            self.nodes
                .push(0.5 * (self.segment[i] + self.segment[(i + 1) % n]));
        }
        for i in 0..n {
            self.nodes.push(0.5 * (c + self.segment[i]));
        }
        self.node_gaps.clear();
        self.node_gaps
            .extend(self.nodes.iter().map(|q| sm.gap_at(plane, ray, m, q)));
        // node indices: centre 0, corner 1 + i, side midpoint 1 + n + i,
        // spoke midpoint 1 + 2n + i
        let (corner, side, spoke) = (
            |i: usize| 1 + i % n,
            |i: usize| 1 + n + i % n,
            |i: usize| 1 + 2 * n + i % n,
        );
        for i in 0..n {
            let (j, mid) = ((i + 1) % n, [spoke(i), side(i), spoke(i + 1)]);
            let tri_area = 0.5 * (self.segment[i] - c).perp(&(self.segment[j] - c));
            // quadratic rule on the centre triangle (exact for quadratic g):
            // weights A/3 at the edge midpoints
            let g_mid = mid.map(|k| self.node_gaps[k].gap);
            r.gap += tri_area / 3.0 * g_mid.iter().sum::<Real>();
            let six = [0, corner(i), corner(i + 1), spoke(i), side(i), spoke(i + 1)];
            if six.iter().all(|&k| self.node_gaps[k].gap > 0.0) {
                continue;
            }
            // the quadratic rule
            let (mut q_volume, mut q_force) = (0.0, Vector::zeros());
            for k in mid {
                let g = self.node_gaps[k];
                let v = tri_area / 3.0 * g.gap;
                q_volume += v;
                q_force += g.normal * v;
            }
            r.min_gap = six
                .iter()
                .fold(r.min_gap, |a, &k| a.min(self.node_gaps[k].gap));
            if six.iter().all(|&k| self.node_gaps[k].gap <= 0.0) {
                // fully in contact: the quadratic rule is the integral
                r.contact_area += tri_area;
                r.volume += q_volume;
                r.force += q_force;
                continue;
            }
            // partly in contact (step c*): four linear sub-triangles, each
            // clipped to its non-positive part, plus the quadratic rule's
            // correction to their linear rule weighted by the share of the
            // closed part in ∫|g| — which tends to the quadratic rule as the
            // last node closes, without the jump of a switch between the two
            // (a weight by the closed area is not Lipschitz in g: nodes
            // closing together flip a sub-triangle's area at once)
            let (mut l_volume, mut l_force) = (0.0, Vector::zeros());
            let (mut closed, mut total) = (0.0, 0.0);
            let subs = [
                [0, spoke(i), spoke(i + 1)],
                [spoke(i), corner(i), side(i)],
                [spoke(i + 1), side(i), corner(i + 1)],
                [spoke(i), side(i), spoke(i + 1)],
            ];
            for t in subs {
                self.tri.clear();
                self.tri.extend(t.iter().map(|&k| self.nodes[k]));
                self.tri_values.clear();
                self.tri_values
                    .extend(t.iter().map(|&k| self.node_gaps[k].gap));
                let linear = 0.25 * tri_area / 3.0 * self.tri_values.iter().sum::<Real>();
                closed -= self.tri_values.iter().map(|g| g.min(0.0)).sum::<Real>();
                total += self.tri_values.iter().map(|g| g.abs()).sum::<Real>();
                clip_non_positive(
                    &self.tri,
                    &self.tri_values,
                    &mut self.contact,
                    &mut self.contact_values,
                );
                let (area, volume) = central_integral(&self.contact, &self.contact_values);
                let nu = t.iter().map(|&k| self.node_gaps[k].normal).sum::<Vector>();
                let nu = nu.try_normalize(1e-300).unwrap_or(plane.normal);
                if area > 0.0 && volume < 0.0 {
                    r.contact_area += area;
                    r.volume += volume;
                    r.force += nu * volume;
                    r.min_gap = self.contact_values.iter().fold(r.min_gap, |a, &g| a.min(g));
                }
                l_volume += linear;
                l_force += nu * linear;
            }
            let weight = if total > 0.0 { closed / total } else { 0.0 };
            r.volume += weight * (q_volume - l_volume);
            r.force += (q_force - l_force) * weight;
        }
        r
    }
}

/// Per-face sums over segments.
#[derive(Debug, Clone, Default)]
struct Accumulators {
    /// Σ ν ∫ g⁻ dΓ per master face (n_m × volume without smoothing).
    master_force: Vec<Vector>,
    master_contact: Vec<Real>,
    master_overlap: Vec<Real>,
    master_gap: Vec<Real>,
    master_located: Vec<Option<Located>>,
    slave_force: Vec<Vector>,
    slave_contact: Vec<Real>,
    slave_overlap: Vec<Real>,
    slave_gap: Vec<Real>,
    /// Smallest flat gap at the segment points of each face (+∞: none),
    /// for the friction's contact share (`IncrementState::share`).
    master_min_gap: Vec<Real>,
    slave_min_gap: Vec<Real>,
}

fn zeroed<T: Clone>(v: &mut Vec<T>, n: usize, zero: T) {
    v.clear();
    v.resize(n, zero);
}

impl Accumulators {
    fn reset(&mut self, nm: usize, ns: usize) {
        zeroed(&mut self.master_force, nm, Vector::zeros());
        zeroed(&mut self.master_contact, nm, 0.0);
        zeroed(&mut self.master_overlap, nm, 0.0);
        zeroed(&mut self.master_gap, nm, 0.0);
        zeroed(&mut self.master_located, nm, None);
        zeroed(&mut self.slave_force, ns, Vector::zeros());
        zeroed(&mut self.slave_contact, ns, 0.0);
        zeroed(&mut self.slave_overlap, ns, 0.0);
        zeroed(&mut self.slave_gap, ns, 0.0);
        zeroed(&mut self.master_min_gap, nm, Real::INFINITY);
        zeroed(&mut self.slave_min_gap, ns, Real::INFINITY);
    }
}

/// Whether face `f` has a positive, finite area (degenerate faces carry no traction).
#[inline]
pub(crate) fn valid_face(surface: &Surface, f: usize) -> bool {
    let a = surface.face_mag[f];
    a > 0.0 && a.is_finite() && surface.face_centres[f].iter().all(|x| x.is_finite())
}

/// Keeps the better of two locations (larger smallest barycentric coordinate).
#[inline]
pub(crate) fn keep_best(best: &mut Option<Located>, cand: Option<Located>) {
    if let Some(c) = cand {
        if best.is_none_or(|b| c.min_zeta() > b.min_zeta()) {
            *best = Some(c);
        }
    }
}

impl SegmentToSegment {
    /// A new algorithm with no friction history.
    pub fn new() -> Self {
        Self::default()
    }

    /// The same against the Nagata-smoothed master
    /// (`"segment-to-segment-nagata"`, see [`SegmentToSegment`]).
    pub fn nagata() -> Self {
        SegmentToSegment {
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

    /// Steps a–e for all pairs: fills the accumulators and the GGI weights;
    /// returns (max penetration, overlapping pairs).
    fn integrate_segments(
        &mut self,
        master: &Surface,
        slave: &Surface,
        pairs: &dyn FacePairs,
        out: &mut ContactTractions,
    ) -> (Real, usize) {
        let smooth = match self.smoothing.as_mut() {
            Some(sm) => sm.sync(master),
            None => false,
        };
        let smoothing = self.smoothing.as_ref().filter(|_| smooth);
        let sc = &mut self.scratch;
        let acc = &mut self.acc;
        let mut min_gap: Real = 0.0;
        let mut n_overlap = 0;
        out.ggi.begin(master, slave);
        let origin = Point2::zeros();
        for m in 0..master.n_faces() {
            let plane = if valid_face(master, m) {
                AuxiliaryPlane::of_face(master, m)
            } else {
                None
            };
            let Some(plane) = plane else {
                out.ggi.end_row();
                continue;
            };
            plane.project_face(master, m, &mut sc.master);
            let tol = AREA_TOLERANCE * master.face_mag[m];
            for &s in pairs.slaves_of(m) {
                let su = s as usize;
                if !valid_face(slave, su) {
                    continue;
                }
                // the slave face at its shift relative to the master face's
                let centre = slave.face_centres[su] + self.shifts.relative(m, su);
                let Some(gap) = plane.ray_gap(&centre, &slave.face_normals[su]) else {
                    continue;
                };
                // b: slave polygon in face order (for 4.26) and counter-clockwise (for c)
                let a_raw = plane.project_face(slave, su, &mut sc.slave_raw);
                sc.slave.clear();
                sc.slave.extend_from_slice(&sc.slave_raw);
                if a_raw < 0.0 {
                    // project_face reversed slave_raw to make it CCW; restore face order
                    sc.slave_raw.reverse();
                }
                keep_best(
                    &mut acc.master_located[m],
                    locate_in_polygon(s, &sc.slave_raw, &origin),
                );
                // c
                clip_convex(&sc.slave, &sc.master, &mut sc.segment, &mut sc.clip);
                let area = signed_area(&sc.segment);
                if !(area > tol) {
                    continue;
                }
                n_overlap += 1;
                out.ggi.push(s, area);
                sc.values.clear();
                sc.values.extend(sc.segment.iter().map(|p| gap.value(p)));
                let lowest = sc.values.iter().fold(Real::INFINITY, |a, &g| a.min(g));
                acc.master_min_gap[m] = acc.master_min_gap[m].min(lowest);
                acc.slave_min_gap[su] = acc.slave_min_gap[su].min(lowest);
                if let Some(sm) = smoothing {
                    let flat_min = sc.values.iter().fold(Real::INFINITY, |a, &g| a.min(g));
                    // a flat patch: the flat gap is the smoothed one
                    if !sm.clear_of(m, flat_min) && sm.deviation(m) > 0.0 {
                        let r = sc.integrate_smoothed(sm, &plane, &gap, m);
                        acc.master_overlap[m] += area;
                        acc.master_gap[m] += r.gap;
                        acc.slave_overlap[su] += area;
                        acc.slave_gap[su] += r.gap;
                        if r.contact_area > tol && r.volume < 0.0 {
                            min_gap = min_gap.min(r.min_gap);
                            acc.master_force[m] += r.force;
                            acc.master_contact[m] += r.contact_area;
                            acc.slave_contact[su] += r.contact_area;
                            acc.slave_force[su] -= r.force;
                        }
                        continue;
                    }
                }
                let (_, integral) = central_integral(&sc.segment, &sc.values);
                acc.master_overlap[m] += area;
                acc.master_gap[m] += integral;
                acc.slave_overlap[su] += area;
                acc.slave_gap[su] += integral;
                // c*, d, e
                clip_non_positive(
                    &sc.segment,
                    &sc.values,
                    &mut sc.contact,
                    &mut sc.contact_values,
                );
                let (contact_area, volume) = central_integral(&sc.contact, &sc.contact_values);
                if contact_area > tol && volume < 0.0 {
                    min_gap = sc.contact_values.iter().fold(min_gap, |a, &g| a.min(g));
                    acc.master_force[m] += plane.normal * volume;
                    acc.master_contact[m] += contact_area;
                    acc.slave_contact[su] += contact_area;
                    // force on the slave: the reaction of ε_n n_m ḡΓ (eq. 4.19)
                    acc.slave_force[su] -= plane.normal * volume;
                }
            }
            out.ggi.end_row();
        }
        out.ggi.finish();
        (-min_gap, n_overlap)
    }

    /// Normal tractions, pressures, gaps and contact fractions from the sums.
    fn normal_tractions(
        &self,
        master: &Surface,
        slave: &Surface,
        law: &ContactLaw,
        out: &mut ContactTractions,
    ) {
        let acc = &self.acc;
        let eps = law.normal_penalty;
        for m in 0..master.n_faces() {
            let a = master.face_mag[m];
            if acc.master_overlap[m] > 0.0 {
                out.master.gap[m] = acc.master_gap[m] / acc.master_overlap[m];
            }
            if acc.master_contact[m] > 0.0 {
                // eqs. 4.16, 4.19 (the force along the smoothed normals with smoothing)
                let t = acc.master_force[m] * (eps / a);
                out.master.normal_traction[m] = t;
                out.master.pressure[m] = -t.dot(&master.face_normals[m]);
                out.master.contact_fraction[m] = (acc.master_contact[m] / a).min(1.0);
            }
        }
        for s in 0..slave.n_faces() {
            let a = slave.face_mag[s];
            if acc.slave_overlap[s] > 0.0 {
                out.slave.gap[s] = acc.slave_gap[s] / acc.slave_overlap[s];
            }
            if acc.slave_contact[s] > 0.0 {
                let t = acc.slave_force[s] * (eps / a);
                out.slave.normal_traction[s] = t;
                out.slave.pressure[s] = -t.dot(&slave.face_normals[s]);
                out.slave.contact_fraction[s] = (acc.slave_contact[s] / a).min(1.0);
            }
        }
    }

    /// Friction on both surfaces (eqs. 4.20–4.23, 4.26).
    fn friction(
        &mut self,
        master: &Surface,
        slave: &Surface,
        law: &ContactLaw,
        out: &mut ContactTractions,
    ) {
        let accumulated = law.slip_history == SlipHistory::Accumulated;
        let zero = Vector::zeros();
        let st = &mut self.state;
        for m in 0..master.n_faces() {
            let p = out.master.pressure[m];
            let Some(loc) = self.acc.master_located[m] else {
                continue;
            };
            if !(p > 0.0) {
                continue;
            }
            let share = st.share(
                Side::Master,
                m,
                st.start_gap_master[m],
                self.acc.master_min_gap[m],
            );
            let own = face_mean(master, &st.du_master, m) * share;
            let other = loc.interpolate(slave, &st.du_slave) * share;
            let hist = if accumulated {
                st.elastic_master[m]
            } else {
                zero
            };
            let ff = face_friction(
                &master.face_normals[m],
                p,
                out.master.contact_fraction[m],
                &own,
                &other,
                &hist,
                law.tangential_penalty,
                law.friction,
            );
            out.master.tangential_traction[m] = ff.traction;
            out.master.slip[m] = ff.slip;
            out.master.friction_state[m] = ff.state;
            st.pending_master[m] = ff.elastic_slip;
        }
        let sc = &mut self.scratch;
        let origin = Point2::zeros();
        for s in 0..slave.n_faces() {
            let p = out.slave.pressure[s];
            if !(p > 0.0) {
                continue;
            }
            let Some(plane) = AuxiliaryPlane::of_face(slave, s) else {
                continue;
            };
            let mut best = None;
            for &m in self.transpose.masters_of(s) {
                let mu = m as usize;
                if !valid_face(master, mu)
                    || !(plane.normal.dot(&master.face_normals[mu]) <= -MIN_FACING_COSINE)
                {
                    continue;
                }
                sc.slave_raw.clear();
                sc.slave_raw.extend(
                    master
                        .face(mu)
                        .iter()
                        .map(|&q| plane.project(&master.points[q as usize])),
                );
                keep_best(&mut best, locate_in_polygon(m, &sc.slave_raw, &origin));
            }
            let Some(loc) = best else { continue };
            let share = st.share(
                Side::Slave,
                s,
                st.start_gap_slave[s],
                self.acc.slave_min_gap[s],
            );
            let own = face_mean(slave, &st.du_slave, s) * share;
            let other = loc.interpolate(master, &st.du_master) * share;
            let hist = if accumulated {
                st.elastic_slave[s]
            } else {
                zero
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
            st.pending_slave[s] = ff.elastic_slip;
        }
    }
}

impl ContactAlgorithm for SegmentToSegment {
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
        self.acc.reset(nm, ns);
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
        let (max_penetration, n_overlap) = self.integrate_segments(master, slave, pairs, out);
        self.normal_tractions(master, slave, law, out);
        self.state
            .record_gaps(&self.acc.master_min_gap, &self.acc.slave_min_gap);
        self.friction(master, slave, law, out);
        let mut stats = finish_stats(master, slave, out);
        stats.contact_area = self.acc.master_contact.iter().sum();
        stats.max_penetration = max_penetration;
        stats.n_overlapping_pairs = n_overlap;
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
        if let Some(sm) = self.smoothing.as_mut() {
            sm.set_symmetry_planes(planes);
        }
    }

    fn kind(&self) -> ContactAlgorithmKind {
        if self.smoothing.is_some() {
            ContactAlgorithmKind::SegmentToSegmentNagata
        } else {
            ContactAlgorithmKind::SegmentToSegment
        }
    }
}
