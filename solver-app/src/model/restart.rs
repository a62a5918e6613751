//! Restart (`fvc run --restart`): a body's state at the end of an
//! accepted increment, as named arrays under `body/<name>/`: the current
//! mesh points (updated Lagrangian: the mesh moves), the momentum
//! balance's fields and material state
//! (`fv_discretise::SolidMomentum::save_state`), and the force controls'
//! secant state (Algorithm 1). A rigid body has none: its motion follows
//! from the time.
use super::{Body, ForceControl};
use fv_mesh::{StateArrays, Tensor, Vector};

/// Values per force control: displacement, accepted, force (3 each),
/// secant stiffness (9), whether a previous correction exists, and its
/// displacement and force (3 each).
const FORCE_CONTROL_VALUES: usize = 25;

fn save_force_control(fc: &ForceControl) -> Vec<f64> {
    let mut v = Vec::with_capacity(FORCE_CONTROL_VALUES);
    for x in [&fc.displacement, &fc.accepted, &fc.force] {
        v.extend(x.iter());
    }
    v.extend(fc.stiffness.iter());
    let (pd, pf) = fc.previous.unwrap_or((Vector::zeros(), Vector::zeros()));
    v.push(f64::from(u8::from(fc.previous.is_some())));
    v.extend(pd.iter());
    v.extend(pf.iter());
    v
}

fn restore_force_control(fc: &mut ForceControl, v: &[f64]) {
    let vec3 = |i: usize| Vector::new(v[i], v[i + 1], v[i + 2]);
    fc.displacement = vec3(0);
    fc.accepted = vec3(3);
    fc.force = vec3(6);
    fc.stiffness = Tensor::from_column_slice(&v[9..18]);
    fc.previous = (v[18] != 0.0).then(|| (vec3(19), vec3(22)));
}

impl Body {
    /// Puts the body's state under `body/<name>/`.
    pub fn save_state(&self, out: &mut StateArrays) {
        if self.rigid {
            return;
        }
        let p = format!("body/{}", self.name);
        if self.mesh_motion.is_some() {
            out.put_vectors(format!("{p}/points"), &self.mesh.points);
        }
        // the cell displacement `momentum/u` is the increment's
        // `displacement` field: the results writer leaves it out where
        // that field is stored in double precision
        // (`crate::output::ResultsWriter::write_restart`)
        self.momentum
            .save_state(&self.mesh, &format!("{p}/momentum"), out);
        for fc in &self.force_controls {
            let name = &self.mesh.patches[fc.patch].name;
            out.put_scalars(format!("{p}/force_control/{name}"), &save_force_control(fc));
        }
    }

    /// Moves the mesh to the saved points (updated Lagrangian) and
    /// recomputes its geometry and the operators on it, as the end of an
    /// increment does. Call before the contact pairs take their state
    /// back, which follows the restored meshes.
    pub fn restore_mesh(&mut self, s: &StateArrays) -> Result<(), String> {
        if self.rigid || self.mesh_motion.is_none() {
            return Ok(());
        }
        let p = format!("body/{}/points", self.name);
        s.vectors_into(&p, &mut self.mesh.points)?;
        self.geom
            .update(&self.mesh)
            .map_err(|e| format!("body '{}': the restored mesh is invalid: {e}", self.name))?;
        if let Some(op) = &mut self.mesh_motion {
            op.update_weights(&self.mesh, &self.geom);
        }
        self.momentum.update_geometry(&self.mesh, &self.geom);
        Ok(())
    }

    /// Takes back the fields and force controls of [`Self::save_state`]
    /// (after [`Self::restore_mesh`], and after the contact pairs switched
    /// to implicit coupling were switched again: the contact patches'
    /// conditions must be of the kind saved).
    pub fn restore_state(&mut self, s: &StateArrays) -> Result<(), String> {
        if self.rigid {
            return Ok(());
        }
        let p = format!("body/{}", self.name);
        self.momentum
            .restore_state(&self.mesh, &format!("{p}/momentum"), s)?;
        for fc in &mut self.force_controls {
            let name = &self.mesh.patches[fc.patch].name;
            let mut v = [0.0; FORCE_CONTROL_VALUES];
            s.scalars_into(&format!("{p}/force_control/{name}"), &mut v)?;
            restore_force_control(fc, &v);
        }
        Ok(())
    }
}
