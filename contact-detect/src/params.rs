//! Parameters of the bounding volumes and of the overlap tests.
use crate::DetectError;
use fv_mesh::Real;

/// Parameters of face bounding boxes (eq. 4.10) and of the overlap tests.
///
/// The defaults are the thesis values: e⁺ = 0.25 h̄, e⁻ = h̄, rectangle
/// inflated by 5 % (§4.2.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetectParams {
    /// h̄, the average height of the cells at the contact boundary (eq. 4.10),
    /// used as the maximum detectable penetration. `None`: estimated at every
    /// call as the mean face size √|Γ_f| over the valid faces of both
    /// surfaces (equal to the cell height for cubic cells); callers that know
    /// the cell heights (volume / face area) should pass them.
    pub mean_cell_height: Option<Real>,
    /// e⁺ / h̄: extrusion out of the body, along the face normal (eq. 4.10: 0.25).
    pub extrusion_out: Real,
    /// e⁻ / h̄: extrusion into the body, against the face normal (eq. 4.10: 1).
    pub extrusion_in: Real,
    /// Relative inflation of the minimum-area rectangle (§4.2.1: 0.05).
    pub inflation: Real,
    /// Relative tolerance of the local-phase 2-D SAT: projected polygons
    /// closer than `touch_tolerance ×` (longest side of the master face
    /// rectangle) count as overlapping, so touching polygons are pairs.
    pub touch_tolerance: Real,
}

impl Default for DetectParams {
    fn default() -> Self {
        DetectParams {
            mean_cell_height: None,
            extrusion_out: 0.25,
            extrusion_in: 1.0,
            inflation: 0.05,
            touch_tolerance: 1e-9,
        }
    }
}

impl DetectParams {
    /// Checks that every parameter is finite and in range.
    pub fn validate(&self) -> Result<(), DetectError> {
        let bad = |name, value, reason| {
            Err(DetectError::InvalidParameter {
                name,
                value,
                reason,
            })
        };
        if let Some(h) = self.mean_cell_height {
            if !(h.is_finite() && h > 0.0) {
                return bad("mean_cell_height", h, "must be positive and finite");
            }
        }
        for (name, v) in [
            ("extrusion_out", self.extrusion_out),
            ("extrusion_in", self.extrusion_in),
            ("inflation", self.inflation),
        ] {
            if !(v.is_finite() && (0.0..=100.0).contains(&v)) {
                return bad(name, v, "must be finite and in [0, 100]");
            }
        }
        let t = self.touch_tolerance;
        if !(t.is_finite() && (0.0..=0.1).contains(&t)) {
            return bad("touch_tolerance", t, "must be finite and in [0, 0.1]");
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_bad_values_rejected() {
        assert!(DetectParams::default().validate().is_ok());
        for p in [
            DetectParams {
                mean_cell_height: Some(0.0),
                ..Default::default()
            },
            DetectParams {
                mean_cell_height: Some(f64::NAN),
                ..Default::default()
            },
            DetectParams {
                extrusion_in: -1.0,
                ..Default::default()
            },
            DetectParams {
                inflation: f64::INFINITY,
                ..Default::default()
            },
            DetectParams {
                touch_tolerance: 0.5,
                ..Default::default()
            },
        ] {
            let e = p.validate().unwrap_err();
            assert!(matches!(e, DetectError::InvalidParameter { .. }), "{e}");
        }
    }
}
