//! Explicit Neumann–Neumann coupling (thesis §4.1.3): the traction applied
//! as the boundary condition of the contact faces is the under-relaxed
//! accumulation of the computed tractions (eq. 4.13).
use crate::contact_tractions::{ContactTractions, SurfaceContact};
use crate::ContactError;
use fv_mesh::{Real, Vector};

/// How computed contact tractions become the tractions applied to the bodies.
/// (The implicit coupling of §4.5 will be a second implementation.)
pub trait Coupling {
    /// Updates the applied tractions of both surfaces from the newly
    /// computed ones; `master_applied` / `slave_applied` have one entry per
    /// face. Returns how much the applied tractions changed.
    fn apply(
        &mut self,
        new: &ContactTractions,
        master_applied: &mut [Vector],
        slave_applied: &mut [Vector],
    ) -> Result<CouplingInfo, ContactError>;

    /// Forgets the accumulated tractions (they restart from zero).
    fn reset(&mut self);
}

/// Change of the applied tractions in one [`Coupling::apply`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CouplingInfo {
    /// max_f |t_applied,new − t_applied,old| over both surfaces, Pa.
    pub max_change: Real,
    /// max_f |t_applied,new| over both surfaces, Pa.
    pub max_traction: Real,
}

impl CouplingInfo {
    /// `max_change / max_traction` (0 if there is no traction): a contact
    /// residual for the outer-loop convergence test.
    pub fn relative_change(&self) -> Real {
        if self.max_traction > 0.0 {
            self.max_change / self.max_traction
        } else {
            0.0
        }
    }
}

/// The accumulated (applied) tractions λ_n, λ_t of one surface (eq. 4.13).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AppliedTraction {
    /// Accumulated normal traction λ_n per face.
    pub normal: Vec<Vector>,
    /// Accumulated tangential traction λ_t per face.
    pub tangential: Vec<Vector>,
}

impl AppliedTraction {
    /// Relaxes towards `new` and writes λ_n + λ_t into `out`; returns
    /// (max change, max traction).
    fn relax(
        &mut self,
        alpha_n: Real,
        alpha_t: Real,
        new: &SurfaceContact,
        out: &mut [Vector],
    ) -> Result<(Real, Real), ContactError> {
        let n = new.n_faces();
        if out.len() != n {
            return Err(ContactError::SizeMismatch {
                what: "applied contact traction",
                expected: n,
                got: out.len(),
            });
        }
        if self.normal.len() != n || self.tangential.len() != n {
            self.normal.clear();
            self.normal.resize(n, Vector::zeros());
            self.tangential.clear();
            self.tangential.resize(n, Vector::zeros());
        }
        let (mut change, mut max) = (0.0, 0.0);
        for (f, o) in out.iter_mut().enumerate() {
            let ln = &mut self.normal[f];
            *ln += (new.normal_traction[f] - *ln) * alpha_n;
            let lt = &mut self.tangential[f];
            *lt += (new.tangential_traction[f] - *lt) * alpha_t;
            let t = *ln + *lt;
            change = Real::max(change, (t - *o).norm());
            max = Real::max(max, t.norm());
            *o = t;
        }
        Ok((change, max))
    }
}

/// Under-relaxed explicit coupling (eq. 4.13):
/// `t = α_n t_n + (1 − α_n) λ_n + α_t t_t + (1 − α_t) λ_t`, the normal and
/// tangential parts relaxed separately; λ are the accumulated tractions,
/// kept here from call to call (and across increments).
///
/// With a fixed target the applied traction converges geometrically: the
/// error is multiplied by (1 − α) per call.
#[derive(Debug, Clone, PartialEq)]
pub struct ExplicitRelaxation {
    normal: Real,
    tangential: Real,
    /// Accumulated tractions of the master surface.
    pub master: AppliedTraction,
    /// Accumulated tractions of the slave surface.
    pub slave: AppliedTraction,
}

impl ExplicitRelaxation {
    /// Relaxation factors α_n, α_t, each in (0, 1].
    pub fn new(normal: Real, tangential: Real) -> Result<Self, ContactError> {
        for (name, v) in [
            ("normal_relaxation", normal),
            ("tangential_relaxation", tangential),
        ] {
            if !(v > 0.0 && v <= 1.0) {
                return Err(ContactError::InvalidParameter {
                    name,
                    value: v,
                    reason: "must be in (0, 1]",
                });
            }
        }
        Ok(ExplicitRelaxation {
            normal,
            tangential,
            master: AppliedTraction::default(),
            slave: AppliedTraction::default(),
        })
    }

    /// α_n.
    pub fn normal_factor(&self) -> Real {
        self.normal
    }

    /// α_t.
    pub fn tangential_factor(&self) -> Real {
        self.tangential
    }

    /// Sets α_n (clamped to (0, 1]), e.g. to damp an open–close cycle of
    /// the contact set.
    pub fn set_normal_factor(&mut self, normal: Real) {
        if normal > 0.0 {
            self.normal = normal.min(1.0);
        }
    }

    /// Sets α_t (clamped to (0, 1]), e.g. to damp a stick–slip cycle.
    pub fn set_tangential_factor(&mut self, tangential: Real) {
        if tangential > 0.0 {
            self.tangential = tangential.min(1.0);
        }
    }
}

impl Coupling for ExplicitRelaxation {
    /// Eq. 4.13 on every face of both surfaces; the accumulated tractions
    /// start from zero (and restart if a surface changes its face count).
    /// Fails if an output slice does not have one entry per face.
    fn apply(
        &mut self,
        new: &ContactTractions,
        master_applied: &mut [Vector],
        slave_applied: &mut [Vector],
    ) -> Result<CouplingInfo, ContactError> {
        let (a, b) = (self.normal, self.tangential);
        let (cm, tm) = self.master.relax(a, b, &new.master, master_applied)?;
        let (cs, ts) = self.slave.relax(a, b, &new.slave, slave_applied)?;
        Ok(CouplingInfo {
            max_change: cm.max(cs),
            max_traction: tm.max(ts),
        })
    }

    fn reset(&mut self) {
        self.master = AppliedTraction::default();
        self.slave = AppliedTraction::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn converges_geometrically_to_a_fixed_target() {
        let mut new = ContactTractions::new();
        new.reset(2, 1);
        let tn = Vector::new(0.0, 0.0, -100.0);
        let tt = Vector::new(8.0, 0.0, 0.0);
        new.master.normal_traction[1] = tn;
        new.master.tangential_traction[1] = tt;
        new.slave.normal_traction[0] = -tn;
        let (an, at) = (0.5, 0.25);
        let mut r = ExplicitRelaxation::new(an, at).unwrap();
        let mut master = vec![Vector::zeros(); 2];
        let mut slave = vec![Vector::zeros(); 1];
        for k in 1..=6 {
            let info = r.apply(&new, &mut master, &mut slave).unwrap();
            let en = (1.0 - an).powi(k);
            let et = (1.0 - at).powi(k);
            let expect = tn * (1.0 - en) + tt * (1.0 - et);
            assert!((master[1] - expect).norm() < 1e-12, "{k}");
            assert!((slave[0] + tn * (1.0 - en)).norm() < 1e-12);
            assert_eq!(master[0], Vector::zeros());
            assert!((r.master.normal[1] - tn * (1.0 - en)).norm() < 1e-12);
            assert!((r.master.tangential[1] - tt * (1.0 - et)).norm() < 1e-12);
            assert!(info.relative_change() > 0.0);
        }
        // two applications with α = 0.5: 0.5, then 0.75 of the target
        let mut r = ExplicitRelaxation::new(0.5, 0.5).unwrap();
        r.apply(&new, &mut master, &mut slave).unwrap();
        assert!((master[1] - (tn + tt) * 0.5).norm() < 1e-12);
        r.apply(&new, &mut master, &mut slave).unwrap();
        assert!((master[1] - (tn + tt) * 0.75).norm() < 1e-12);
        r.reset();
        r.apply(&new, &mut master, &mut slave).unwrap();
        assert!((master[1] - (tn + tt) * 0.5).norm() < 1e-12);
        // wrong output length, bad factors
        assert!(r.apply(&new, &mut master[..1], &mut slave).is_err());
        assert!(ExplicitRelaxation::new(0.0, 0.5).is_err());
        assert!(ExplicitRelaxation::new(0.5, 1.5).is_err());
        assert!(ExplicitRelaxation::new(Real::NAN, 0.5).is_err());
    }
}
