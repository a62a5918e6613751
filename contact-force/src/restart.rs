//! Restart (`fvc run --restart`): the contact state that the next
//! increment starts from, as named arrays ([`fv_mesh::StateArrays`]):
//! the friction history of the algorithms ([`IncrementState`]: the
//! surfaces' reference positions, the committed elastic slip, the start
//! gaps), the last tractions with their GGI weights
//! ([`ContactTractions`]), and the tractions accumulated by the explicit
//! relaxation ([`ExplicitRelaxation`], eq. 4.13).
use crate::coulomb_friction::FrictionState;
use crate::increment_state::IncrementState;
use crate::{ContactTractions, ExplicitRelaxation, GgiWeights, SurfaceContact};
use fv_mesh::StateArrays;

impl IncrementState {
    /// Puts the committed friction history under `prefix`.
    pub(crate) fn save_state(&self, prefix: &str, out: &mut StateArrays) {
        out.put_vectors(format!("{prefix}/reference_master"), &self.reference_master);
        out.put_vectors(format!("{prefix}/reference_slave"), &self.reference_slave);
        out.put_vectors(
            format!("{prefix}/elastic_slip_master"),
            &self.elastic_master,
        );
        out.put_vectors(format!("{prefix}/elastic_slip_slave"), &self.elastic_slave);
        out.put_scalars(format!("{prefix}/start_gap_master"), &self.start_gap_master);
        out.put_scalars(format!("{prefix}/start_gap_slave"), &self.start_gap_slave);
        out.put_scalar(
            format!("{prefix}/start_known"),
            f64::from(u8::from(self.start_known)),
        );
    }

    /// Takes back the history of [`Self::save_state`].
    pub(crate) fn restore_state(&mut self, prefix: &str, s: &StateArrays) -> Result<(), String> {
        s.vectors_to_vec(
            &format!("{prefix}/reference_master"),
            &mut self.reference_master,
        )?;
        s.vectors_to_vec(
            &format!("{prefix}/reference_slave"),
            &mut self.reference_slave,
        )?;
        s.vectors_to_vec(
            &format!("{prefix}/elastic_slip_master"),
            &mut self.elastic_master,
        )?;
        s.vectors_to_vec(
            &format!("{prefix}/elastic_slip_slave"),
            &mut self.elastic_slave,
        )?;
        s.scalars_to_vec(
            &format!("{prefix}/start_gap_master"),
            &mut self.start_gap_master,
        )?;
        s.scalars_to_vec(
            &format!("{prefix}/start_gap_slave"),
            &mut self.start_gap_slave,
        )?;
        self.start_known = s.scalar(&format!("{prefix}/start_known"))? != 0.0;
        // the last call's values start as the committed ones
        self.pending_master.clone_from(&self.elastic_master);
        self.pending_slave.clone_from(&self.elastic_slave);
        self.gap_master.clone_from(&self.start_gap_master);
        self.gap_slave.clone_from(&self.start_gap_slave);
        Ok(())
    }
}

fn state_code(s: FrictionState) -> f64 {
    match s {
        FrictionState::Inactive => 0.0,
        FrictionState::Stick => 1.0,
        FrictionState::Slip => 2.0,
    }
}

fn save_surface(c: &SurfaceContact, prefix: &str, out: &mut StateArrays) {
    out.put_vectors(format!("{prefix}/normal_traction"), &c.normal_traction);
    out.put_vectors(
        format!("{prefix}/tangential_traction"),
        &c.tangential_traction,
    );
    out.put_scalars(format!("{prefix}/pressure"), &c.pressure);
    out.put_scalars(format!("{prefix}/gap"), &c.gap);
    out.put_scalars(format!("{prefix}/contact_fraction"), &c.contact_fraction);
    out.put_vectors(format!("{prefix}/slip"), &c.slip);
    let states: Vec<f64> = c.friction_state.iter().map(|&s| state_code(s)).collect();
    out.put_scalars(format!("{prefix}/friction_state"), &states);
}

fn restore_surface(c: &mut SurfaceContact, prefix: &str, s: &StateArrays) -> Result<(), String> {
    s.vectors_to_vec(&format!("{prefix}/normal_traction"), &mut c.normal_traction)?;
    s.vectors_to_vec(
        &format!("{prefix}/tangential_traction"),
        &mut c.tangential_traction,
    )?;
    s.scalars_to_vec(&format!("{prefix}/pressure"), &mut c.pressure)?;
    s.scalars_to_vec(&format!("{prefix}/gap"), &mut c.gap)?;
    s.scalars_to_vec(
        &format!("{prefix}/contact_fraction"),
        &mut c.contact_fraction,
    )?;
    s.vectors_to_vec(&format!("{prefix}/slip"), &mut c.slip)?;
    let mut codes = Vec::new();
    s.scalars_to_vec(&format!("{prefix}/friction_state"), &mut codes)?;
    c.friction_state.clear();
    c.friction_state
        .extend(codes.iter().map(|&x| match x as u8 {
            1 => FrictionState::Stick,
            2 => FrictionState::Slip,
            _ => FrictionState::Inactive,
        }));
    Ok(())
}

fn save_u32(name: String, v: &[u32], out: &mut StateArrays) {
    out.put(name, 1, v.iter().map(|&x| f64::from(x)).collect());
}

fn restore_u32(name: &str, s: &StateArrays, out: &mut Vec<u32>) -> Result<(), String> {
    let mut v = Vec::new();
    s.scalars_to_vec(name, &mut v)?;
    out.clear();
    out.extend(v.iter().map(|&x| x as u32));
    Ok(())
}

impl GgiWeights {
    /// Restart: puts the weights under `prefix`.
    pub fn save_state(&self, prefix: &str, out: &mut StateArrays) {
        save_u32(
            format!("{prefix}/master_offsets"),
            &self.master_offsets,
            out,
        );
        save_u32(format!("{prefix}/master_slaves"), &self.master_slaves, out);
        out.put_scalars(format!("{prefix}/master_overlap"), &self.master_overlap);
        save_u32(format!("{prefix}/slave_offsets"), &self.slave_offsets, out);
        save_u32(format!("{prefix}/slave_masters"), &self.slave_masters, out);
        out.put_scalars(format!("{prefix}/slave_overlap"), &self.slave_overlap);
        out.put_scalars(format!("{prefix}/master_area"), &self.master_area);
        out.put_scalars(format!("{prefix}/slave_area"), &self.slave_area);
    }

    /// Restart: takes back the weights of [`Self::save_state`].
    pub fn restore_state(&mut self, prefix: &str, s: &StateArrays) -> Result<(), String> {
        restore_u32(
            &format!("{prefix}/master_offsets"),
            s,
            &mut self.master_offsets,
        )?;
        restore_u32(
            &format!("{prefix}/master_slaves"),
            s,
            &mut self.master_slaves,
        )?;
        s.scalars_to_vec(
            &format!("{prefix}/master_overlap"),
            &mut self.master_overlap,
        )?;
        restore_u32(
            &format!("{prefix}/slave_offsets"),
            s,
            &mut self.slave_offsets,
        )?;
        restore_u32(
            &format!("{prefix}/slave_masters"),
            s,
            &mut self.slave_masters,
        )?;
        s.scalars_to_vec(&format!("{prefix}/slave_overlap"), &mut self.slave_overlap)?;
        s.scalars_to_vec(&format!("{prefix}/master_area"), &mut self.master_area)?;
        s.scalars_to_vec(&format!("{prefix}/slave_area"), &mut self.slave_area)?;
        // no weights at all (no search yet) is consistent too
        let rows = |offsets: &[u32], n: usize, len: usize| {
            (offsets.is_empty() && n == 0 && len == 0)
                || offsets.len() == n + 1
                    && offsets.windows(2).all(|w| w[0] <= w[1])
                    && offsets.last().map_or(len == 0, |&l| l as usize == len)
        };
        if !rows(
            &self.master_offsets,
            self.master_area.len(),
            self.master_slaves.len(),
        ) || !rows(
            &self.slave_offsets,
            self.slave_area.len(),
            self.slave_masters.len(),
        ) || self.master_slaves.len() != self.master_overlap.len()
            || self.slave_masters.len() != self.slave_overlap.len()
        {
            *self = GgiWeights::default();
            return Err(format!(
                "restart state '{prefix}': inconsistent GGI weights"
            ));
        }
        Ok(())
    }
}

impl ContactTractions {
    /// Restart: puts the tractions of both surfaces and the GGI weights
    /// under `prefix`.
    pub fn save_state(&self, prefix: &str, out: &mut StateArrays) {
        save_surface(&self.master, &format!("{prefix}/master"), out);
        save_surface(&self.slave, &format!("{prefix}/slave"), out);
        self.ggi.save_state(&format!("{prefix}/ggi"), out);
    }

    /// Restart: takes back what [`Self::save_state`] put.
    pub fn restore_state(&mut self, prefix: &str, s: &StateArrays) -> Result<(), String> {
        restore_surface(&mut self.master, &format!("{prefix}/master"), s)?;
        restore_surface(&mut self.slave, &format!("{prefix}/slave"), s)?;
        self.ggi.restore_state(&format!("{prefix}/ggi"), s)
    }
}

impl ExplicitRelaxation {
    /// Restart: puts the factors and the accumulated tractions under
    /// `prefix`.
    pub fn save_state(&self, prefix: &str, out: &mut StateArrays) {
        out.put_scalars(
            format!("{prefix}/factors"),
            &[self.normal_factor(), self.tangential_factor()],
        );
        for (side, a) in [("master", &self.master), ("slave", &self.slave)] {
            out.put_vectors(format!("{prefix}/{side}/normal"), &a.normal);
            out.put_vectors(format!("{prefix}/{side}/tangential"), &a.tangential);
        }
    }

    /// Restart: takes back what [`Self::save_state`] put.
    pub fn restore_state(&mut self, prefix: &str, s: &StateArrays) -> Result<(), String> {
        let mut f = [0.0; 2];
        s.scalars_into(&format!("{prefix}/factors"), &mut f)?;
        self.set_normal_factor(f[0]);
        self.set_tangential_factor(f[1]);
        for (side, a) in [("master", &mut self.master), ("slave", &mut self.slave)] {
            s.vectors_to_vec(&format!("{prefix}/{side}/normal"), &mut a.normal)?;
            s.vectors_to_vec(&format!("{prefix}/{side}/tangential"), &mut a.tangential)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fv_mesh::Vector;

    #[test]
    fn tractions_and_relaxation_round_trip() {
        let mut t = ContactTractions::new();
        t.reset(2, 3);
        t.master.pressure[1] = 4.5;
        t.slave.slip[2] = Vector::new(1e-3, 0.0, -2e-3);
        t.slave.friction_state[0] = FrictionState::Slip;
        let mut out = StateArrays::new();
        t.save_state("c", &mut out);
        let mut back = ContactTractions::new();
        back.restore_state("c", &out).unwrap();
        assert_eq!(back.master.pressure, t.master.pressure);
        assert_eq!(back.slave.slip, t.slave.slip);
        assert_eq!(back.slave.friction_state, t.slave.friction_state);
        let mut r = ExplicitRelaxation::new(0.3, 0.2).unwrap();
        r.master.normal = vec![Vector::zeros(); 2];
        r.master.normal[0] = Vector::new(0.0, -7.0, 0.0);
        let mut out = StateArrays::new();
        r.save_state("r", &mut out);
        let mut back = ExplicitRelaxation::new(1.0, 1.0).unwrap();
        back.restore_state("r", &out).unwrap();
        assert_eq!(back.normal_factor(), 0.3);
        assert_eq!(back.tangential_factor(), 0.2);
        assert_eq!(back.master.normal, r.master.normal);
    }
}
