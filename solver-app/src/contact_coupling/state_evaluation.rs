//! Contact inside the residual of Newton's method: the contact tractions
//! as a function of the state, nothing relaxed, nothing remembered from
//! one evaluation to the next but what the increment freezes (the
//! friction history of its start, the augmented multipliers, the penalty
//! localised at its first evaluation) and, through the Jacobian products
//! of one Newton step, the candidate pairs.
//!
//! Every evaluation moves the contact surfaces to the bodies' current
//! boundary values (cell-to-point least squares, eqs. 3.31–3.32, or the
//! rigid motion), computes the tractions of both surfaces with the case's
//! algorithm (§4.3–4.4) and writes them, without a spring, into the
//! deformable sides' contact conditions, where the face balance of the
//! state takes them (`SolidMomentum::compute_residual_with_face_rows`).
//! Between two deformable bodies under the updated Lagrangian form each
//! face carries its traction over the moved surface's area, as implicit
//! coupling does, so the two bodies receive equal and opposite forces.
use super::{transmitted_forces, ContactSet, ContactSide};
use crate::model::Body;
use crate::profile::Phase;
use fv_discretise::PatchCondition;
use fv_mesh::Vector;
use fv_nonlinear::Frozen;

/// The contact state of a face, compared between renewals: no pressure,
/// pressure without friction, sticking, slipping.
fn face_state(pressure: f64, stick: bool, slip: bool) -> u8 {
    match (pressure > 0.0, stick, slip) {
        (false, _, _) => 0,
        (true, true, _) => 2,
        (true, _, true) => 3,
        (true, false, false) => 1,
    }
}

impl ContactSet {
    /// Turns every contact patch of a deformable body into a contact
    /// condition that the state's face balance reads (once, after the
    /// bodies are built).
    pub fn prepare_state_conditions(&self, bodies: &mut [Body]) {
        for ci in &self.interfaces {
            ci.linearise_patches(bodies);
        }
    }

    /// The contact tractions of the bodies' current state (their boundary
    /// values set): with [`Frozen::Renew`] the candidate pairs are detected
    /// anew (and, at the first such call of an increment, the penalty
    /// localised to the contacting faces); with [`Frozen::Keep`] those of
    /// the last renewal are used. Returns, for a renewal, how many faces
    /// changed their contact state (open, pressed, sticking, slipping)
    /// against the last renewal.
    pub fn evaluate_state(&mut self, bodies: &mut [Body], frozen: Frozen) -> Result<usize, String> {
        if frozen == Frozen::Renew {
            self.deepest_penetration = 0.0;
        }
        // a patch in several pairs sums their tractions
        for ci in &self.interfaces {
            for side in [&ci.master, &ci.slave].into_iter().filter(|s| s.shared) {
                if let PatchCondition::LinearisedContact(lc) =
                    &mut bodies[side.body].momentum.conditions[side.patch]
                {
                    lc.traction.fill(Vector::zeros());
                }
            }
        }
        let mut changes = 0;
        for ci in &mut self.interfaces {
            let start = std::time::Instant::now();
            Self::move_side(&mut ci.master, bodies, &self.cell_to_point);
            Self::move_side(&mut ci.slave, bodies, &self.cell_to_point);
            ci.apply_face_shifts(bodies);
            if frozen == Frozen::Renew {
                ci.detector
                    .detect(&ci.master.surface, &ci.slave.surface, &mut ci.detected)
                    .map_err(|e| format!("contact {}: detection: {e}", ci.slave_name))?;
                accumulate_pairs(ci);
            }
            let force_start = self.times.lap(Phase::ContactDetection, start);
            if frozen == Frozen::Renew && !ci.penalty_localised && !ci.pairs.is_empty() {
                if let Ok(law) = super::penalty_law(
                    &ci.params,
                    &ci.master.surface,
                    &ci.slave.surface,
                    &ci.materials,
                    Some(&ci.pairs),
                ) {
                    ci.law = law;
                }
                ci.penalty_localised = true;
            }
            ci.algorithm.freeze_friction_shares(frozen == Frozen::Keep);
            ci.compute_tractions()?;
            transmitted_forces(&mut ci.stats, &ci.tractions, &ci.master, &ci.slave, bodies);
            if self.trace && frozen == Frozen::Renew {
                eprintln!(
                    "    contact {}: force {:.6e} pairs {} active {} stick {} slip {} max pen {:.4e} area {:.4e} eps {:.3e}",
                    ci.slave_name,
                    ci.stats.normal_force,
                    ci.pairs.n_pairs(),
                    ci.stats.n_active,
                    ci.stats.n_stick,
                    ci.stats.n_slip,
                    ci.stats.max_penetration,
                    ci.stats.contact_area,
                    ci.law.normal_penalty
                );
                let gmin = ci
                    .tractions
                    .slave
                    .gap
                    .iter()
                    .copied()
                    .filter(|g| g.is_finite())
                    .fold(f64::INFINITY, f64::min);
                let gmin_m = ci
                    .tractions
                    .master
                    .gap
                    .iter()
                    .copied()
                    .filter(|g| g.is_finite())
                    .fold(f64::INFINITY, f64::min);
                let disp =
                    |side: &ContactSide| side.point_u.iter().map(|u| u.norm()).fold(0.0, f64::max);
                eprintln!("      min gap slave {gmin:.4e} master {gmin_m:.4e}; max point motion master {:.3e} slave {:.3e}", disp(&ci.master), disp(&ci.slave));
            }
            if frozen == Frozen::Renew {
                for (side, contact) in [
                    (&ci.master, &ci.tractions.master),
                    (&ci.slave, &ci.tractions.slave),
                ] {
                    let b = &bodies[side.body];
                    if b.rigid {
                        continue;
                    }
                    let first = b.mesh.patches[side.patch].start;
                    for (i, &g) in contact.gap.iter().enumerate() {
                        let height = 2.0 * b.momentum.normal_distance(first + i);
                        if g < 0.0 && height > 0.0 {
                            self.deepest_penetration = self.deepest_penetration.max(-g / height);
                        }
                    }
                }
            }
            let deformable_pair = ci.deformable_pair;
            for (side, contact) in [
                (&mut ci.master, &ci.tractions.master),
                (&mut ci.slave, &ci.tractions.slave),
            ] {
                if frozen == Frozen::Renew {
                    changes += count_changes(side, contact);
                }
                // the traction each side receives: the state's own (the
                // segregated method's relaxed one has no place here); the
                // results' `contact_traction` is written from it
                contact.tractions_into(&mut side.applied);
                let b = &mut bodies[side.body];
                if b.rigid {
                    continue;
                }
                let ul = b.momentum.law.is_updated_lagrangian();
                let first = b.mesh.patches[side.patch].start;
                let n = side.surface.n_faces();
                let PatchCondition::LinearisedContact(lc) = &mut b.momentum.conditions[side.patch]
                else {
                    continue;
                };
                for i in 0..n {
                    let t = contact.traction(i);
                    if side.shared {
                        lc.traction[i] += t;
                    } else {
                        lc.traction[i] = t;
                    }
                    lc.stiffness[i] = 0.0;
                    lc.tangential_stiffness[i] = 0.0;
                    lc.normal[i] = side.surface.face_normals[i];
                    lc.opposite_shift[i] = Vector::zeros();
                    // between deformable bodies each receives the force the
                    // contact computed, over the moved surface's areas
                    lc.area_ratio[i] = if deformable_pair && ul {
                        let r = side.surface.face_mag[i] / b.geom.face_mag(first + i);
                        if r.is_finite() {
                            r
                        } else {
                            0.0
                        }
                    } else {
                        0.0
                    };
                }
            }
            self.times.lap(Phase::ContactForce, force_start);
        }
        Ok(changes)
    }
}

impl super::ContactInterface {
    /// The algorithm's tractions at the surfaces' current positions, into
    /// `tractions`, and their statistics into `stats`; the augmented shift
    /// taken back out of the gaps (and the deepest penetration).
    pub(super) fn compute_tractions(&mut self) -> Result<(), String> {
        self.stats = self
            .algorithm
            .compute(
                &self.master.surface,
                &self.slave.surface,
                &self.pairs,
                &self.law,
                &mut self.tractions,
            )
            .map_err(|e| format!("contact {}: {e}", self.slave_name))?;
        if self.augmentation.is_some() {
            self.unshift_augmented_gaps();
        }
        Ok(())
    }

    /// Hands the algorithm the faces' shifts: the boundary-value faces'
    /// (`face_position = "boundary-value"`) and, with augmentation, the
    /// slave faces moved on by λ/ε_n along their current normals (the
    /// penalty then adds ε_n times the penetration to λ).
    pub(super) fn apply_face_shifts(&mut self, bodies: &[Body]) {
        if self.face_shifts {
            ContactSet::face_shifts(&mut self.master, bodies);
            ContactSet::face_shifts(&mut self.slave, bodies);
        }
        let eps = self.law.normal_penalty;
        if self.augmentation.is_some() && eps > 0.0 && self.multiplier.iter().any(|&l| l > 0.0) {
            let slave = &self.slave;
            self.augmented_shift.clear();
            self.augmented_shift
                .extend((0..slave.surface.n_faces()).map(|f| {
                    let base = slave
                        .face_shift
                        .get(f)
                        .copied()
                        .unwrap_or_else(Vector::zeros);
                    base + slave.surface.face_normals[f] * (self.multiplier[f] / eps)
                }));
            self.algorithm
                .set_face_shifts(&self.master.face_shift, &self.augmented_shift);
        } else if self.face_shifts || self.augmentation.is_some() {
            self.algorithm
                .set_face_shifts(&self.master.face_shift, &self.slave.face_shift);
        }
    }
}

impl ContactSet {
    /// The deepest penetration of a deformable contact face at the last
    /// renewal ([`ContactSet::evaluate_state`]), as a fraction of its
    /// cell's height (2 × the normal distance of its owner's centre).
    pub fn deepest_penetration(&self) -> f64 {
        self.deepest_penetration
    }
}

/// The candidate pairs of an attempt at an increment grow with every
/// renewal: the last detection's pairs join those of the attempt's earlier
/// base points. A pair the detection finds at one iterate and not at the
/// next changed the frictional tractions (the master face a slave face's
/// ray hits is chosen among its pairs), and Newton oscillated between the
/// two sets (curved beams: 15 and 16 pairs, contact force 5.3 and 4.7 N,
/// no convergence at any cut-back); a pair in the set that does not
/// overlap adds nothing.
fn accumulate_pairs(ci: &mut super::ContactInterface) {
    if !ci.pairs_this_attempt {
        ci.pairs.copy_from(&ci.detected);
        ci.pairs_this_attempt = true;
        return;
    }
    let before = ci.pairs.n_pairs();
    let grows = ci
        .detected
        .iter()
        .any(|(m, s)| !ci.pairs.contains(m as usize, s));
    if grows {
        let mut all: Vec<(u32, u32)> = ci.pairs.iter().collect();
        all.extend(ci.detected.iter());
        let n = ci.detected.n_master().max(ci.pairs.n_master());
        ci.pairs = contact_detect::CandidatePairs::from_pairs(n, &all);
    }
    debug_assert!(ci.pairs.n_pairs() >= before);
}

/// Faces of `side` that are pressed now and were not at the last renewal;
/// records the new states (open, pressed, sticking, slipping).
fn count_changes(side: &mut ContactSide, contact: &contact_force::SurfaceContact) -> usize {
    let n = contact.n_faces();
    if side.state_signature.len() != n {
        side.state_signature.clear();
        side.state_signature.resize(n, 0);
    }
    let mut changed = 0;
    for (i, s) in side.state_signature.iter_mut().enumerate() {
        let st = contact.friction_state[i];
        let new = face_state(
            contact.pressure[i],
            st == contact_force::FrictionState::Stick,
            st == contact_force::FrictionState::Slip,
        );
        // a face that came into contact (a step that ran into a contact
        // its linear model did not have); faces that open or change
        // between stick and slip are not counted
        changed += usize::from(*s == 0 && new != 0);
        *s = new;
    }
    changed
}
