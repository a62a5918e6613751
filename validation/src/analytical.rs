//! Closed-form reference solutions.

/// Lamé solution of a thick-walled cylinder (inner radius `a`, outer `b`)
/// under internal pressure `p`: (σ_rr, σ_θθ) at radius `r`.
pub fn lame_cylinder_stress(a: f64, b: f64, p: f64, r: f64) -> (f64, f64) {
    let c = p * a * a / (b * b - a * a);
    let d = c * b * b / (r * r);
    (c - d, c + d)
}

/// Tip deflection of a cantilever of length `l`, depth `d`, thickness `t`
/// under an end shear force `p` by Timoshenko beam theory:
/// δ = P L³/(3 E I) + P L/(κ G A), κ = 5/6 (rectangular section).
pub fn timoshenko_cantilever_tip(p: f64, l: f64, d: f64, t: f64, e: f64, nu: f64) -> f64 {
    let i = t * d.powi(3) / 12.0;
    let g = e / (2.0 * (1.0 + nu));
    let a = t * d;
    p * l.powi(3) / (3.0 * e * i) + p * l / (5.0 / 6.0 * g * a)
}

/// Plane Hertz contact of two parallel cylinders (or a cylinder on a flat),
/// thesis appendix A1, eqs. A1–A6.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzLine {
    /// Contact half-width b = √(4 F R / (π E*)) (A4).
    pub half_width: f64,
    /// Peak pressure p0 = 2F / (π b) (A5).
    pub peak_pressure: f64,
}

impl HertzLine {
    /// From the normal force per unit length `force`, the relative radius
    /// R = R1 R2 / (R1 + R2) and the contact modulus
    /// E* with 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (A1–A3).
    pub fn new(force: f64, radius: f64, contact_modulus: f64) -> Self {
        let b = (4.0 * force * radius / (std::f64::consts::PI * contact_modulus)).sqrt();
        HertzLine {
            half_width: b,
            peak_pressure: 2.0 * force / (std::f64::consts::PI * b),
        }
    }

    /// Contact pressure p(x) = p0 √(1 − x²/b²) inside the contact, 0 outside (A5).
    pub fn pressure(&self, x: f64) -> f64 {
        let r = x / self.half_width;
        if r.abs() < 1.0 {
            self.peak_pressure * (1.0 - r * r).sqrt()
        } else {
            0.0
        }
    }

    /// Stresses on the symmetry axis at depth `z` below the surface (A6):
    /// (σ_x, σ_z) = −p0 [(1 + 2ζ²)/√(1 + ζ²) − 2ζ, 1/√(1 + ζ²)], ζ = z/b.
    pub fn axis_stress(&self, z: f64) -> (f64, f64) {
        let zeta = z.abs() / self.half_width;
        let root = (1.0 + zeta * zeta).sqrt();
        (
            -self.peak_pressure * ((1.0 + 2.0 * zeta * zeta) / root - 2.0 * zeta),
            -self.peak_pressure / root,
        )
    }

    /// Half-width of the stick zone under a tangential force Q < μF
    /// (Cattaneo–Mindlin, A11): c = b √(1 − Q/(μF)).
    pub fn stick_half_width(&self, tangential: f64, friction: f64, force: f64) -> f64 {
        self.half_width * (1.0 - tangential / (friction * force)).max(0.0).sqrt()
    }
}

/// Contact modulus E* of two elastic bodies (A3); `None` = rigid.
pub fn contact_modulus(a: Option<(f64, f64)>, b: Option<(f64, f64)>) -> f64 {
    let c = |m: Option<(f64, f64)>| m.map_or(0.0, |(e, nu): (f64, f64)| (1.0 - nu * nu) / e);
    1.0 / (c(a) + c(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hertz_line_matches_the_benchmark_numbers() {
        // benchmarks/README.md, parallel-cylinders: F = 10, R_r = 4,
        // E_c = 109.9 → b = 0.681, p0 = 9.35; c = 0.7293 b for Q/μF = 0.4681
        let e = contact_modulus(Some((200.0, 0.3)), Some((200.0, 0.3)));
        assert!((e - 109.89).abs() < 0.01, "{e}");
        let h = HertzLine::new(10.0, 4.0, e);
        assert!((h.half_width - 0.681).abs() < 5e-4, "{h:?}");
        assert!((h.peak_pressure - 9.35).abs() < 5e-3, "{h:?}");
        assert!((h.pressure(0.0) - h.peak_pressure).abs() < 1e-12);
        assert_eq!(h.pressure(0.7), 0.0);
        let c = h.stick_half_width(0.05851 * 16.0, 0.2, 10.0);
        assert!(
            (c / h.half_width - 0.7293).abs() < 1e-3,
            "{}",
            c / h.half_width
        );
        let (sx, sz) = h.axis_stress(0.0);
        assert!((sx + h.peak_pressure).abs() < 1e-12 && (sz + h.peak_pressure).abs() < 1e-12);
    }

    #[test]
    fn lame_boundary_values() {
        let (srr, _) = lame_cylinder_stress(1.0, 2.0, 10.0, 1.0);
        assert!((srr + 10.0).abs() < 1e-12);
        let (srr, stt) = lame_cylinder_stress(1.0, 2.0, 10.0, 2.0);
        assert!(srr.abs() < 1e-12);
        assert!((stt - 20.0 / 3.0).abs() < 1e-12);
    }
}
