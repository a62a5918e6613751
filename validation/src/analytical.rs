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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lame_boundary_values() {
        let (srr, _) = lame_cylinder_stress(1.0, 2.0, 10.0, 1.0);
        assert!((srr + 10.0).abs() < 1e-12);
        let (srr, stt) = lame_cylinder_stress(1.0, 2.0, 10.0, 2.0);
        assert!(srr.abs() < 1e-12);
        assert!((stt - 20.0 / 3.0).abs() < 1e-12);
    }
}
