//! Penalty regularisation of the contact conditions (thesis §4.1.2): the
//! normal law (4.1–4.2), the penalty parameters (4.4a, 4.4b), and the
//! [`ContactLaw`] the algorithms evaluate.
use crate::coulomb_friction::SlipHistory;
use crate::ContactError;
use fv_mesh::{Real, Surface};

/// User parameters of the penalty contact law, as in the case file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PenaltyParams {
    /// f_n^scale of eq. 4.4a (typically 1).
    pub penalty_scale: Real,
    /// f_t^scale of eq. 4.4b (typically 1).
    pub tangential_penalty_scale: Real,
    /// Coulomb friction coefficient μ (0: frictionless).
    pub friction: Real,
    /// How the trial frictional traction remembers earlier increments.
    pub slip_history: SlipHistory,
}

impl Default for PenaltyParams {
    fn default() -> Self {
        PenaltyParams {
            penalty_scale: 1.0,
            tangential_penalty_scale: 1.0,
            friction: 0.0,
            slip_history: SlipHistory::Accumulated,
        }
    }
}

/// Material data of one deformable contact surface, one entry per face
/// (taken from the cell that owns the face), for eqs. 4.4a/4.4b. The crate
/// needs no mesh or material model: the caller extracts these.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceMaterial<'a> {
    /// Normal stiffness K of eq. 4.4a (e.g. the implicit stiffness 2μ+λ or
    /// the bulk modulus of the owner cell), Pa.
    pub stiffness: &'a [Real],
    /// Shear modulus G of eq. 4.4b, Pa.
    pub shear_modulus: &'a [Real],
    /// Owner cell volume / face area, m (so Ω = `cell_length` · |Γ|).
    pub cell_length: &'a [Real],
}

/// The evaluated contact law: penalty parameters and friction coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    /// ε_n, normal penalty parameter, Pa/m (pressure per unit penetration).
    pub normal_penalty: Real,
    /// ε_t, tangential penalty parameter, Pa/m (traction per unit slip).
    pub tangential_penalty: Real,
    /// Coulomb friction coefficient μ.
    pub friction: Real,
    /// Memory of the trial frictional traction.
    pub slip_history: SlipHistory,
}

impl ContactLaw {
    /// A law with given penalties and friction (validated).
    pub fn new(
        normal_penalty: Real,
        tangential_penalty: Real,
        friction: Real,
        slip_history: SlipHistory,
    ) -> Result<Self, ContactError> {
        let law = ContactLaw {
            normal_penalty,
            tangential_penalty,
            friction,
            slip_history,
        };
        law.validate()?;
        Ok(law)
    }

    /// Checks that the penalties are positive (ε_t may be 0) and finite
    /// and μ ≥ 0.
    pub fn validate(&self) -> Result<(), ContactError> {
        check_normal_tangential_friction(
            ("normal_penalty", self.normal_penalty),
            ("tangential_penalty", self.tangential_penalty),
            self.friction,
        )
    }

    /// Normal contact pressure for a gap (eq. 4.1), ≥ 0.
    #[inline]
    pub fn pressure(&self, gap: Real) -> Real {
        normal_pressure(self.normal_penalty, gap)
    }
}

/// Checks a (normal, tangential) pair of penalty quantities and μ: the
/// normal one positive and finite, the tangential one and μ non-negative
/// and finite.
fn check_normal_tangential_friction(
    (normal_name, normal): (&'static str, Real),
    (tangential_name, tangential): (&'static str, Real),
    friction: Real,
) -> Result<(), ContactError> {
    let bad = |name, value, reason| {
        Err(ContactError::InvalidParameter {
            name,
            value,
            reason,
        })
    };
    if !(normal > 0.0 && normal.is_finite()) {
        return bad(normal_name, normal, "must be positive and finite");
    }
    if !(tangential >= 0.0 && tangential.is_finite()) {
        return bad(
            tangential_name,
            tangential,
            "must be non-negative and finite",
        );
    }
    if !(friction >= 0.0 && friction.is_finite()) {
        return bad("friction", friction, "must be non-negative and finite");
    }
    Ok(())
}

/// The Macaulay bracket ⟨φ⟩ = (|φ| + φ)/2 (eq. 4.2).
#[inline]
pub fn macaulay(phi: Real) -> Real {
    phi.max(0.0)
}

/// Penalty-regularised normal contact pressure p_n = ε_n ⟨−g_n⟩ (eq. 4.1),
/// reported positive (compression); zero for a positive or non-finite gap.
#[inline]
pub fn normal_pressure(normal_penalty: Real, gap: Real) -> Real {
    if gap.is_finite() {
        normal_penalty * macaulay(-gap)
    } else {
        0.0
    }
}

impl PenaltyParams {
    /// Checks the scales (positive, finite; the tangential one may be 0)
    /// and μ ≥ 0.
    pub fn validate(&self) -> Result<(), ContactError> {
        check_normal_tangential_friction(
            ("penalty_scale", self.penalty_scale),
            ("tangential_penalty_scale", self.tangential_penalty_scale),
            self.friction,
        )
    }

    /// The penalty parameters of eqs. 4.4a and 4.4b,
    /// `ε_n = f_n K̄ Γ̄² / Ω̄ / Γ̄ = f_n K̄ Γ̄ / Ω̄`, `ε_t = f_t Ḡ Γ̄ / Ω̄` (the
    /// face stiffness of eqs. 4.4a/b divided by the face area, so that
    /// pressure = ε_n × penetration is dimensionally right), with the averages taken
    /// over the faces of the deformable surfaces (`None` marks a rigid
    /// surface, which contributes nothing): Γ̄ the mean face area, Ω̄ the
    /// mean owner-cell volume (`cell_length · |Γ|`), K̄ and Ḡ the mean
    /// moduli. Faces with zero or non-finite area are left out.
    ///
    /// Fails if both surfaces are rigid, an array does not have one entry
    /// per face, or no face has positive area, volume and moduli.
    /// Computed once per problem (or increment) by the caller; O(faces).
    pub fn contact_law(
        &self,
        master: &Surface,
        master_material: Option<&SurfaceMaterial<'_>>,
        slave: &Surface,
        slave_material: Option<&SurfaceMaterial<'_>>,
    ) -> Result<ContactLaw, ContactError> {
        self.validate()?;
        let (mut n, mut area, mut volume, mut k, mut g) = (0usize, 0.0, 0.0, 0.0, 0.0);
        for (surface, material) in [(master, master_material), (slave, slave_material)] {
            let Some(mat) = material else { continue };
            let nf = surface.n_faces();
            for (what, len) in [
                ("stiffness", mat.stiffness.len()),
                ("shear_modulus", mat.shear_modulus.len()),
                ("cell_length", mat.cell_length.len()),
            ] {
                if len != nf {
                    return Err(ContactError::SizeMismatch {
                        what,
                        expected: nf,
                        got: len,
                    });
                }
            }
            for f in 0..nf {
                let a = surface.face_mag[f];
                let v = mat.cell_length[f] * a;
                let (kf, gf) = (mat.stiffness[f], mat.shear_modulus[f]);
                let ok = a > 0.0 && a.is_finite() && v > 0.0 && v.is_finite();
                if ok && kf > 0.0 && kf.is_finite() && gf >= 0.0 && gf.is_finite() {
                    n += 1;
                    area += a;
                    volume += v;
                    k += kf;
                    g += gf;
                }
            }
        }
        if master_material.is_none() && slave_material.is_none() {
            return Err(ContactError::InvalidMaterial(
                "both contact surfaces are rigid: the penalty comes from the deformable side's material, so at least one of the two bodies must be deformable (rigid = false)".into(),
            ));
        }
        if n == 0 {
            return Err(ContactError::InvalidMaterial(
                "no contact face with positive area, cell volume and stiffness".into(),
            ));
        }
        let inv = 1.0 / n as Real;
        let (area, volume, k, g) = (area * inv, volume * inv, k * inv, g * inv);
        // Eq. 4.4a/b give K Γ²/Ω, a face stiffness (force per unit
        // penetration, N/m); the traction law needs it per unit face area,
        // K Γ/Ω = K/h̄ (Pa/m), which is what is returned here.
        let geometric = area / volume;
        ContactLaw::new(
            self.penalty_scale * k * geometric,
            self.tangential_penalty_scale * g * geometric,
            self.friction,
            self.slip_history,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fv_mesh::generators::box_mesh;
    use fv_mesh::Vector;

    #[test]
    fn normal_law_and_macaulay() {
        assert_eq!(normal_pressure(1e6, -2e-3), 2e3);
        assert_eq!(normal_pressure(1e6, 1e-3), 0.0);
        assert_eq!(normal_pressure(1e6, Real::INFINITY), 0.0);
        assert_eq!(normal_pressure(1e6, Real::NAN), 0.0);
        assert_eq!(macaulay(-1.0), 0.0);
        assert_eq!(macaulay(2.0), 2.0);
    }

    #[test]
    fn penalty_estimate_4_4() {
        // 4×2 faces of 0.25×0.5 on top of cells 0.25×0.5×0.1: Γ/Ω = 1/h = 1/0.1
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 1.0, 0.1),
            [4, 2, 1],
            [1.0; 3],
        )
        .unwrap();
        let s = fv_mesh::Surface::new(&m, m.patch_index("zmax").unwrap()).unwrap();
        let (k, g, h) = (vec![3.0e9; 8], vec![1.0e9; 8], vec![0.1; 8]);
        let mat = SurfaceMaterial {
            stiffness: &k,
            shear_modulus: &g,
            cell_length: &h,
        };
        let p = PenaltyParams {
            penalty_scale: 2.0,
            tangential_penalty_scale: 0.5,
            friction: 0.3,
            ..Default::default()
        };
        let law = p.contact_law(&s, Some(&mat), &s, None).unwrap();
        let geo = 1.0 / 0.1;
        assert!((law.normal_penalty / (2.0 * 3.0e9 * geo) - 1.0).abs() < 1e-14);
        assert!((law.tangential_penalty / (0.5 * 1.0e9 * geo) - 1.0).abs() < 1e-14);
        assert_eq!(law.friction, 0.3);
        // both sides: same averages
        let law2 = p.contact_law(&s, Some(&mat), &s, Some(&mat)).unwrap();
        assert!((law2.normal_penalty / law.normal_penalty - 1.0).abs() < 1e-14);
        assert!(p.contact_law(&s, None, &s, None).is_err());
        let short = SurfaceMaterial {
            cell_length: &h[..3],
            ..mat
        };
        assert!(matches!(
            p.contact_law(&s, Some(&short), &s, None),
            Err(ContactError::SizeMismatch { .. })
        ));
        let zero = vec![0.0; 8];
        let bad = SurfaceMaterial {
            stiffness: &zero,
            ..mat
        };
        assert!(p.contact_law(&s, Some(&bad), &s, None).is_err());
        let neg = PenaltyParams {
            friction: -1.0,
            ..p
        };
        assert!(neg.contact_law(&s, Some(&mat), &s, None).is_err());
        assert!(ContactLaw::new(0.0, 1.0, 0.0, SlipHistory::Incremental).is_err());
    }
}
