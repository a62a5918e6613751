//! Restart (`fvc run --restart`): the fields of a body that the next
//! increment starts from, at the end of an accepted increment (after
//! [`SolidMomentum::commit_increment`]), as named arrays
//! ([`fv_mesh::StateArrays`]).
//!
//! Kept: the total displacement of cells and boundary faces, the normal
//! derivatives and the cell gradient (small strain: they seed the next
//! boundary update), the committed material state of cells and of the
//! boundary faces that carry their own (`face_state`), the carried face
//! tractions and Rhie–Chow forces (updated Lagrangian), the time levels
//! of the temporal term, and the values of the contact patches'
//! conditions (applied tractions, linearised springs). The boundary-face
//! arrays leave out the faces of `empty` patches (half the boundary faces
//! of a plane model, one cell thick), whose value is their owner's.
//!
//! Recomputed: the cell stress, from the gradient (small strain: the same
//! numbers) or from the committed state at a zero increment (updated
//! Lagrangian, as a redone attempt starts; it would double the state, and
//! the first residual evaluation of the next increment recomputes it
//! anyway); the geometry, from the restored mesh
//! ([`SolidMomentum::update_geometry`]); workspaces that every residual
//! evaluation overwrites.
use super::SolidMomentum;
use crate::{PatchCondition, StressLaw};
use fv_mesh::{PolyMesh, StateArrays, Tensor, Vector};

/// A material state's committed F, b̄_e and ε̄_p, as read back.
type MaterialParts = (Vec<Tensor>, Vec<Tensor>, Vec<f64>);

/// The values of the boundary faces `faces` (indices from the first
/// boundary face).
fn pick(v: &[Vector], faces: &[usize]) -> Vec<Vector> {
    faces.iter().map(|&b| v[b]).collect()
}

/// Puts `kept` (as [`pick`] took them) back at `faces`.
fn place(kept: &[Vector], faces: &[usize], out: &mut [Vector]) {
    for (&b, v) in faces.iter().zip(kept) {
        out[b] = *v;
    }
}

impl SolidMomentum {
    /// The boundary faces (from the first) whose values the state keeps:
    /// those of every patch but the `empty` ones.
    fn kept_faces(&self, mesh: &PolyMesh) -> Vec<usize> {
        let ni = mesh.n_internal_faces();
        mesh.patches
            .iter()
            .zip(&self.conditions)
            .filter(|(_, c)| !matches!(c, PatchCondition::Empty))
            .flat_map(|(p, _)| p.faces().map(move |f| f - ni))
            .collect()
    }

    /// Puts the state under `prefix` (`mesh` names the patches).
    pub fn save_state(&self, mesh: &PolyMesh, prefix: &str, out: &mut StateArrays) {
        out.put_vectors(format!("{prefix}/u"), &self.u);
        let faces = self.kept_faces(mesh);
        out.put_vectors(format!("{prefix}/u_b"), &pick(&self.u_b, &faces));
        if !self.law.is_updated_lagrangian() {
            // zero at the start of an updated Lagrangian increment
            out.put_vectors(format!("{prefix}/snd_b"), &pick(&self.snd_b, &faces));
        }
        match &self.law {
            StressLaw::Small(_) => out.put_tensors(format!("{prefix}/grad_u"), &self.grad_u),
            StressLaw::UpdatedLagrangian { state, .. } => {
                let (f, be_bar, eps_p) = state.committed_parts();
                out.put_tensors(format!("{prefix}/material/f"), f);
                out.put_tensors(format!("{prefix}/material/be_bar"), be_bar);
                out.put_scalars(format!("{prefix}/material/eps_p"), eps_p);
            }
        }
        if let Some(fs) = &self.face_state {
            let (f, be_bar, eps_p) = fs.committed_parts();
            out.put_tensors(format!("{prefix}/face_material/f"), f);
            out.put_tensors(format!("{prefix}/face_material/be_bar"), be_bar);
            out.put_scalars(format!("{prefix}/face_material/eps_p"), eps_p);
        }
        if !self.traction_offset.is_empty() {
            out.put_vectors(
                format!("{prefix}/traction_offset"),
                &pick(&self.traction_offset, &faces),
            );
        }
        if !self.rc_carried.is_empty() {
            out.put_vectors(format!("{prefix}/rhie_chow_carried"), &self.rc_carried);
        }
        if !self.eps_p_before.is_empty() {
            out.put_scalars(
                format!("{prefix}/material/eps_p_before"),
                &self.eps_p_before,
            );
        }
        if let Some(i) = &self.inertia {
            out.put_vectors(format!("{prefix}/inertia/u_prev"), &i.u_prev);
            out.put_vectors(format!("{prefix}/inertia/u_prev2"), &i.u_prev2);
            out.put_scalars(format!("{prefix}/inertia/dt"), &[i.dt, i.dt_prev]);
        }
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            let c = format!("{prefix}/conditions/{}", p.name);
            match cond {
                PatchCondition::Traction(t) => out.put_vectors(format!("{c}/traction"), t),
                PatchCondition::LinearisedContact(lc) => {
                    out.put_vectors(format!("{c}/traction"), &lc.traction);
                    out.put_scalars(format!("{c}/stiffness"), &lc.stiffness);
                    out.put_scalars(
                        format!("{c}/tangential_stiffness"),
                        &lc.tangential_stiffness,
                    );
                    out.put_vectors(format!("{c}/normal"), &lc.normal);
                    out.put_vectors(format!("{c}/reference"), &lc.reference);
                    out.put_vectors(format!("{c}/opposite_shift"), &lc.opposite_shift);
                    out.put_scalars(format!("{c}/area_ratio"), &lc.area_ratio);
                }
                _ => {}
            }
        }
    }

    /// Takes back the state of [`Self::save_state`] (`mesh` is the
    /// restored current configuration, on which [`Self::update_geometry`]
    /// was called). An array missing or of another size is an error
    /// naming it.
    pub fn restore_state(
        &mut self,
        mesh: &PolyMesh,
        prefix: &str,
        state: &StateArrays,
    ) -> Result<(), String> {
        let faces = self.kept_faces(mesh);
        let ni = mesh.n_internal_faces();
        state.vectors_into(&format!("{prefix}/u"), &mut self.u)?;
        let mut kept = vec![Vector::zeros(); faces.len()];
        state.vectors_into(&format!("{prefix}/u_b"), &mut kept)?;
        for (b, u) in self.u_b.iter_mut().enumerate() {
            *u = self.u[mesh.owner[ni + b] as usize];
        }
        place(&kept, &faces, &mut self.u_b);
        self.snd_b.iter_mut().for_each(|g| *g = Vector::zeros());
        if !self.law.is_updated_lagrangian() {
            state.vectors_into(&format!("{prefix}/snd_b"), &mut kept)?;
            place(&kept, &faces, &mut self.snd_b);
        }
        let material = |name: &str| -> Result<MaterialParts, String> {
            let (mut f, mut b, mut e) = (Vec::new(), Vec::new(), Vec::new());
            let n = |s: &str| {
                state
                    .get(&format!("{prefix}/{name}/{s}"))
                    .map_or(0, |a| a.values.len() / a.columns.max(1))
            };
            f.resize(n("f"), Tensor::zeros());
            b.resize(n("be_bar"), Tensor::zeros());
            e.resize(n("eps_p"), 0.0);
            state.tensors_into(&format!("{prefix}/{name}/f"), &mut f)?;
            state.tensors_into(&format!("{prefix}/{name}/be_bar"), &mut b)?;
            state.scalars_into(&format!("{prefix}/{name}/eps_p"), &mut e)?;
            Ok((f, b, e))
        };
        match &mut self.law {
            StressLaw::Small(m) => {
                state.tensors_into(&format!("{prefix}/grad_u"), &mut self.grad_u)?;
                for (s, g) in self.sigma.iter_mut().zip(&self.grad_u) {
                    *s = m.stress(g);
                }
            }
            StressLaw::UpdatedLagrangian { law, state: ms } => {
                let (f, b, e) = material("material")?;
                ms.restore_committed(&f, &b, &e)
                    .map_err(|e| format!("restart state '{prefix}/material': {e}"))?;
                // the start of an increment: no increment yet, the stress
                // of the committed state, and the surface-force tensor of a
                // zero increment is σ itself
                self.u_old.copy_from_slice(&self.u);
                self.u_b_old.copy_from_slice(&self.u_b);
                self.grad_u.iter_mut().for_each(|g| *g = Tensor::zeros());
                for (i, (s, h)) in self
                    .sigma
                    .iter_mut()
                    .zip(self.sigma_hat.iter_mut())
                    .enumerate()
                {
                    if let Some((c, _)) = law.update_point(&ms.committed(i), &Tensor::zeros()) {
                        *s = c;
                        *h = c;
                    }
                }
            }
        }
        if let Some(fs) = &mut self.face_state {
            let (f, b, e) = material("face_material")?;
            fs.restore_committed(&f, &b, &e)
                .map_err(|e| format!("restart state '{prefix}/face_material': {e}"))?;
        }
        if !self.traction_offset.is_empty() {
            state.vectors_into(&format!("{prefix}/traction_offset"), &mut kept)?;
            self.traction_offset
                .iter_mut()
                .for_each(|t| *t = Vector::zeros());
            place(&kept, &faces, &mut self.traction_offset);
        }
        let rc = format!("{prefix}/rhie_chow_carried");
        if state.has(&rc) {
            state.vectors_to_vec(&rc, &mut self.rc_carried)?;
        }
        let before = format!("{prefix}/material/eps_p_before");
        if state.has(&before) {
            self.eps_p_before.resize(mesh.n_cells, 0.0);
            state.scalars_into(&before, &mut self.eps_p_before)?;
        } else {
            self.eps_p_before.clear();
        }
        if let Some(i) = &mut self.inertia {
            state.vectors_into(&format!("{prefix}/inertia/u_prev"), &mut i.u_prev)?;
            state.vectors_into(&format!("{prefix}/inertia/u_prev2"), &mut i.u_prev2)?;
            let mut dt = [0.0; 2];
            state.scalars_into(&format!("{prefix}/inertia/dt"), &mut dt)?;
            (i.dt, i.dt_prev) = (dt[0], dt[1]);
        }
        for (p, cond) in mesh.patches.iter().zip(self.conditions.iter_mut()) {
            let c = format!("{prefix}/conditions/{}", p.name);
            match cond {
                PatchCondition::Traction(t) => state.vectors_into(&format!("{c}/traction"), t)?,
                PatchCondition::LinearisedContact(lc) => {
                    state.vectors_into(&format!("{c}/traction"), &mut lc.traction)?;
                    state.scalars_into(&format!("{c}/stiffness"), &mut lc.stiffness)?;
                    state.scalars_into(
                        &format!("{c}/tangential_stiffness"),
                        &mut lc.tangential_stiffness,
                    )?;
                    state.vectors_into(&format!("{c}/normal"), &mut lc.normal)?;
                    state.vectors_into(&format!("{c}/reference"), &mut lc.reference)?;
                    state.vectors_into(&format!("{c}/opposite_shift"), &mut lc.opposite_shift)?;
                    state.scalars_into(&format!("{c}/area_ratio"), &mut lc.area_ratio)?;
                }
                _ => {}
            }
        }
        self.du.iter_mut().for_each(|d| *d = Vector::zeros());
        self.du_b.iter_mut().for_each(|d| *d = Vector::zeros());
        self.forget_moved_areas();
        Ok(())
    }
}
