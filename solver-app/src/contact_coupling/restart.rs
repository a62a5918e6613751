//! Restart (`fvc run --restart`): the state of every contact pair at the
//! end of an accepted increment, as named arrays under `contact/<i>/`
//! (`i` the pair's place in the case):
//!
//! - per side: the contact surface's current points, the applied
//!   tractions (eq. 4.13), the contact fractions β and the opposite cells'
//!   reference displacement (eq. 4.69);
//! - the tractions of the last contact evaluation with their GGI weights,
//!   the accumulated relaxation, the augmented Lagrangian multipliers, the
//!   penalties in use, the friction history of the algorithm (reference
//!   positions, committed elastic slip, start gaps), and the scalars that
//!   carry over: the coupling (implicit or not, after a switch), the
//!   relaxation factors, the damping of the normal relaxation, the last
//!   force, the augmentation counts, the summary figures.
//!
//! Not kept: the candidate pairs and the detector's seeds. The first
//! contact update after a restart detects afresh, as the first update of
//! a run does; detection finds every pair within its search distance, so
//! the tractions computed from the pairs do not depend on the seeds (the
//! restart test compares a continued run with an uninterrupted one).
use super::{ContactSet, ContactSide};
use crate::model::Body;
use contact_force::ContactStats;
use fv_mesh::{StateArrays, Vector};

fn save_side(side: &ContactSide, prefix: &str, out: &mut StateArrays) {
    out.put_vectors(format!("{prefix}/points"), &side.current);
    out.put_vectors(format!("{prefix}/applied"), &side.applied);
    out.put_scalars(format!("{prefix}/beta"), &side.beta);
    out.put_vectors(
        format!("{prefix}/opposite_reference"),
        &side.opposite_reference,
    );
}

fn restore_side(side: &mut ContactSide, prefix: &str, s: &StateArrays) -> Result<(), String> {
    s.vectors_into(&format!("{prefix}/points"), &mut side.current)?;
    side.surface.update_points(&side.current);
    s.vectors_to_vec(&format!("{prefix}/applied"), &mut side.applied)?;
    s.scalars_to_vec(&format!("{prefix}/beta"), &mut side.beta)?;
    s.vectors_to_vec(
        &format!("{prefix}/opposite_reference"),
        &mut side.opposite_reference,
    )?;
    Ok(())
}

fn save_stats(st: &ContactStats, name: String, out: &mut StateArrays) {
    let v = |x: &Vector| [x.x, x.y, x.z];
    let mut row = vec![st.normal_force];
    row.extend(v(&st.tangential_force));
    row.extend(v(&st.master_force));
    row.extend(v(&st.slave_force));
    row.extend([
        st.max_pressure,
        st.contact_area,
        st.max_penetration,
        st.n_active as f64,
        st.n_stick as f64,
        st.n_slip as f64,
        st.n_overlapping_pairs as f64,
    ]);
    out.put_scalars(name, &row);
}

fn restore_stats(st: &mut ContactStats, name: &str, s: &StateArrays) -> Result<(), String> {
    let mut r = [0.0; 17];
    s.scalars_into(name, &mut r)?;
    let v = |i: usize| Vector::new(r[i], r[i + 1], r[i + 2]);
    *st = ContactStats {
        normal_force: r[0],
        tangential_force: v(1),
        master_force: v(4),
        slave_force: v(7),
        max_pressure: r[10],
        contact_area: r[11],
        max_penetration: r[12],
        n_active: r[13] as usize,
        n_stick: r[14] as usize,
        n_slip: r[15] as usize,
        n_overlapping_pairs: r[16] as usize,
    };
    Ok(())
}

impl ContactSet {
    /// Puts the state of every contact pair (see the module documentation).
    pub fn save_state(&self, out: &mut StateArrays) {
        for (i, ci) in self.interfaces.iter().enumerate() {
            let p = format!("contact/{i}");
            save_side(&ci.master, &format!("{p}/master"), out);
            save_side(&ci.slave, &format!("{p}/slave"), out);
            ci.tractions.save_state(&format!("{p}/tractions"), out);
            ci.coupling.save_state(&format!("{p}/relaxation"), out);
            ci.algorithm
                .save_state(&format!("{p}/friction_history"), out);
            out.put_scalars(format!("{p}/multiplier"), &ci.multiplier);
            save_stats(&ci.stats, format!("{p}/stats"), out);
            out.put_scalars(
                format!("{p}/scalars"),
                &[
                    f64::from(u8::from(ci.implicit)),
                    ci.normal_relaxation,
                    ci.tangential_relaxation,
                    ci.normal_damping,
                    ci.last_force,
                    ci.augmentation_updates_run as f64,
                    ci.first_update.0,
                    ci.first_update.1,
                    ci.last_update_penetration,
                    ci.law.normal_penalty,
                    ci.law.tangential_penalty,
                    f64::from(u8::from(ci.stiff)),
                ],
            );
        }
    }

    /// Restart, first step: the pairs that the saved run had switched to
    /// implicit coupling are switched again (their patches' conditions
    /// become linearised contact conditions, which the bodies then take
    /// back). Sets nothing else.
    pub fn restore_couplings(
        &mut self,
        bodies: &mut [Body],
        s: &StateArrays,
    ) -> Result<(), String> {
        for i in 0..self.interfaces.len() {
            let mut r = [0.0; 12];
            s.scalars_into(&format!("contact/{i}/scalars"), &mut r)?;
            if r[0] != 0.0 && !self.interfaces[i].implicit {
                self.couple_implicitly(&[i], bodies);
            }
        }
        Ok(())
    }

    /// Restart, last step: takes back the state of [`Self::save_state`]
    /// into pairs built for the same case, after the bodies took theirs
    /// back: the contact operators and reference surfaces follow the
    /// restored meshes first ([`Self::end_increment`]). The candidate
    /// pairs are detected afresh by the first update.
    pub fn restore_state(&mut self, bodies: &[Body], s: &StateArrays) -> Result<(), String> {
        self.end_increment(bodies);
        for i in 0..self.interfaces.len() {
            let p = format!("contact/{i}");
            let mut r = [0.0; 12];
            s.scalars_into(&format!("{p}/scalars"), &mut r)?;
            let ci = &mut self.interfaces[i];
            restore_side(&mut ci.master, &format!("{p}/master"), s)?;
            restore_side(&mut ci.slave, &format!("{p}/slave"), s)?;
            ci.tractions.restore_state(&format!("{p}/tractions"), s)?;
            ci.coupling.restore_state(&format!("{p}/relaxation"), s)?;
            ci.algorithm
                .restore_state(&format!("{p}/friction_history"), s)?;
            s.scalars_to_vec(&format!("{p}/multiplier"), &mut ci.multiplier)?;
            restore_stats(&mut ci.stats, &format!("{p}/stats"), s)?;
            ci.normal_relaxation = r[1];
            ci.tangential_relaxation = r[2];
            ci.normal_damping = r[3];
            ci.last_force = r[4];
            ci.augmentation_updates_run = r[5] as usize;
            ci.first_update = (r[6], r[7]);
            ci.last_update_penetration = r[8];
            ci.law.normal_penalty = r[9];
            ci.law.tangential_penalty = r[10];
            ci.stiff = r[11] != 0.0;
            ci.pairs = Default::default();
            ci.detected = Default::default();
            ci.penalty_localised = false;
        }
        Ok(())
    }
}
