//! Closed-form reference solutions.

/// Lamé solution of a thick-walled cylinder (inner radius `a`, outer `b`)
/// under internal pressure `p`: (σ_rr, σ_θθ) at radius `r`.
pub fn lame_cylinder_stress(a: f64, b: f64, p: f64, r: f64) -> (f64, f64) {
    let c = p * a * a / (b * b - a * a);
    let d = c * b * b / (r * r);
    (c - d, c + d)
}

/// Lamé solution of a thick-walled sphere (inner radius `a`, outer `b`)
/// under internal pressure `p`: (σ_rr, σ_θθ = σ_φφ) at radius `r`.
pub fn lame_sphere_stress(a: f64, b: f64, p: f64, r: f64) -> (f64, f64) {
    let c = p * a.powi(3) / (b.powi(3) - a.powi(3));
    let d = c * b.powi(3) / r.powi(3);
    (c - d, c + 0.5 * d)
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

    /// Tangential traction of Cattaneo–Mindlin partial slip (A10) under the
    /// friction coefficient `friction` with the stick half-width `c`:
    /// q = μ p0/b (√(b² − x²) − √(c² − x²)), the second root only for |x| ≤ c.
    pub fn tangential_traction(&self, x: f64, stick_half_width: f64, friction: f64) -> f64 {
        let b = self.half_width;
        let root = |a: f64| (a * a - x * x).max(0.0).sqrt();
        friction * self.peak_pressure / b * (root(b) - root(stick_half_width.min(b)))
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

/// Mean of `f` over the interval of width `w` centred on `x` (256-point
/// midpoint rule): an analytical profile as a face of that width sees it.
pub fn face_average(f: impl Fn(f64) -> f64, x: f64, w: f64) -> f64 {
    const N: usize = 256;
    (0..N)
        .map(|k| f(x + w * ((k as f64 + 0.5) / N as f64 - 0.5)))
        .sum::<f64>()
        / N as f64
}

/// Hertz contact of a sphere on a flat or of two spheres (point contact),
/// thesis appendix A2, eqs. A13–A19.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzPoint {
    /// Contact radius b = (3 F R / (4 E*))^(1/3) (A13).
    pub radius: f64,
    /// Peak pressure p0 = 3F / (2π b²) (A16).
    pub peak_pressure: f64,
}

impl HertzPoint {
    /// From the normal force `force`, the relative radius R (the sphere's
    /// on a flat) and the contact modulus E* (A3, [`contact_modulus`]).
    pub fn new(force: f64, radius: f64, contact_modulus: f64) -> Self {
        let b = (3.0 * force * radius / (4.0 * contact_modulus)).cbrt();
        HertzPoint {
            radius: b,
            peak_pressure: 3.0 * force / (2.0 * std::f64::consts::PI * b * b),
        }
    }

    /// Contact pressure p(r) = p0 √(1 − r²/b²) inside the contact, 0 outside (A15).
    pub fn pressure(&self, r: f64) -> f64 {
        let x = r / self.radius;
        if x.abs() < 1.0 {
            self.peak_pressure * (1.0 - x * x).sqrt()
        } else {
            0.0
        }
    }

    /// Stresses on the axis at depth `z` below the surface of a body with
    /// Poisson's ratio `nu` (A19), ζ = z/b:
    /// σ_rr = σ_θθ = −p0 [(1 + ν)(1 − ζ atan(1/ζ)) − 1/(2(1 + ζ²))],
    /// σ_zz = −p0 / (1 + ζ²). Returns (σ_rr, σ_zz).
    pub fn axis_stress(&self, z: f64, nu: f64) -> (f64, f64) {
        let zeta = z.abs() / self.radius;
        let zatan = if zeta > 0.0 {
            zeta * (1.0 / zeta).atan()
        } else {
            0.0
        };
        let s = 1.0 + zeta * zeta;
        (
            -self.peak_pressure * ((1.0 + nu) * (1.0 - zatan) - 0.5 / s),
            -self.peak_pressure / s,
        )
    }
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
    fn hertz_point_closed_forms() {
        // F = 10, R = 1, E* = 100: b = (0.075)^(1/3), p0 = 15/(π b²)
        let h = HertzPoint::new(10.0, 1.0, 100.0);
        let b = 0.075f64.cbrt();
        assert!((h.radius - b).abs() < 1e-12);
        assert!((h.peak_pressure - 15.0 / (std::f64::consts::PI * b * b)).abs() < 1e-9);
        // A14: F = (4/3) E* √R d^(3/2) with d = b²/R
        let d = b * b;
        assert!((4.0 / 3.0 * 100.0 * d.powf(1.5) - 10.0).abs() < 1e-9);
        // surface: σ_rr = −p0 (1 + 2ν)/2, σ_zz = −p0
        let (srr, szz) = h.axis_stress(0.0, 0.3);
        assert!((srr + 0.8 * h.peak_pressure).abs() < 1e-12);
        assert!((szz + h.peak_pressure).abs() < 1e-12);
        // ζ = 1: σ_zz = −p0/2, σ_rr = −p0 [1.3 (1 − π/4) − 1/4]
        let (srr, szz) = h.axis_stress(h.radius, 0.3);
        assert!((szz + 0.5 * h.peak_pressure).abs() < 1e-12);
        let e = 1.3 * (1.0 - std::f64::consts::FRAC_PI_4) - 0.25;
        assert!((srr + e * h.peak_pressure).abs() < 1e-12);
        assert_eq!(h.pressure(1.01 * h.radius), 0.0);
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

/// Cauchy stress (principal values) of the compressible neo-Hookean solid
/// of thesis eq. (2.25), τ = (K/2)(J² − 1) I + μ dev(b̄), for the principal
/// stretches `l`; written out here independently of `fv-materials`.
pub fn neo_hookean_principal_stress(mu: f64, bulk: f64, l: [f64; 3]) -> [f64; 3] {
    let j = l[0] * l[1] * l[2];
    let b: [f64; 3] = l.map(|x| x * x * j.powf(-2.0 / 3.0));
    let mean = (b[0] + b[1] + b[2]) / 3.0;
    b.map(|bi| (0.5 * bulk * (j * j - 1.0) + mu * (bi - mean)) / j)
}

/// Uniaxial stress of the neo-Hookean solid (eq. 2.25) at axial stretch
/// `stretch`: the lateral stretch s with σ_22 = σ_33 = 0 (bisection) and
/// the axial force per unit initial area, σ_11 s².
pub fn neo_hookean_uniaxial(mu: f64, bulk: f64, stretch: f64) -> (f64, f64) {
    let lateral = |s: f64| neo_hookean_principal_stress(mu, bulk, [stretch, s, s])[1];
    let (mut lo, mut hi) = (1e-3, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if lateral(lo) * lateral(mid) <= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let s = 0.5 * (lo + hi);
    let sigma = neo_hookean_principal_stress(mu, bulk, [stretch, s, s])[0];
    (s, sigma * s * s)
}

/// Simple shear F = I + γ e_x⊗e_y of the neo-Hookean solid (eq. 2.25):
/// J = 1, so σ = μ dev(F Fᵀ): returns (σ_xy, σ_xx, σ_yy, σ_zz) =
/// μ (γ, 2γ²/3, −γ²/3, −γ²/3).
pub fn neo_hookean_simple_shear(mu: f64, gamma: f64) -> [f64; 4] {
    let g2 = gamma * gamma;
    [
        mu * gamma,
        mu * 2.0 * g2 / 3.0,
        -mu * g2 / 3.0,
        -mu * g2 / 3.0,
    ]
}

/// Tip of an inextensible Euler–Bernoulli cantilever under a tip load of
/// fixed direction, perpendicular to the undeformed axis (the elastica):
/// EI θ'' = −P cos θ, θ(0) = 0, θ'(L) = 0, solved by shooting on θ'(0)
/// with RK4. Returns (axial shortening, transverse deflection) divided by
/// L for the load parameter k = PL²/EI (Mattiasson 1981 tabulates k = 1:
/// 0.05643, 0.30172).
pub fn elastica_cantilever_tip(k: f64) -> (f64, f64) {
    // nondimensional: s in [0, 1], θ'' = −k cos θ
    let n = 4000;
    let h = 1.0 / n as f64;
    let integrate = |kappa0: f64| -> (f64, f64, f64) {
        // state: θ, θ', x, y
        let mut y = [0.0, kappa0, 0.0, 0.0];
        let rhs = |y: &[f64; 4]| [y[1], -k * y[0].cos(), y[0].cos(), y[0].sin()];
        for _ in 0..n {
            let k1 = rhs(&y);
            let y2 = std::array::from_fn(|i| y[i] + 0.5 * h * k1[i]);
            let k2 = rhs(&y2);
            let y3 = std::array::from_fn(|i| y[i] + 0.5 * h * k2[i]);
            let k3 = rhs(&y3);
            let y4 = std::array::from_fn(|i| y[i] + h * k3[i]);
            let k4 = rhs(&y4);
            for i in 0..4 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        (y[1], y[2], y[3])
    };
    // θ'(1) = 0: bisection on θ'(0) in (0, k]
    let (mut lo, mut hi) = (0.0, k);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if integrate(mid).0 > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let (_, x, y) = integrate(0.5 * (lo + hi));
    (1.0 - x, y)
}

/// Thick-walled tube (inner radius `a`, outer `b`, plane strain) of the
/// neo-Hookean solid of eq. (2.25) under internal pressure `p` at finite
/// strain: the current radii (r(a), r(b)) of the inner and outer surface.
///
/// With r = f(R), stretches λ_r = f′ and λ_θ = f/R (λ_z = 1), the radial
/// balance in the reference configuration, dP_r/dR + (P_r − P_θ)/R = 0, of
/// the first Piola–Kirchhoff stresses P_r = λ_θ σ_r and P_θ = λ_r σ_θ, is
/// integrated from R = a (σ_r = −p) to R = b by RK4, λ_r following from
/// (f, P_r) by bisection; f(a) is shot (bisection) to P_r(b) = 0.
pub fn neo_hookean_pressurised_tube(mu: f64, bulk: f64, a: f64, b: f64, p: f64) -> (f64, f64) {
    let sigma = |lr: f64, lt: f64| neo_hookean_principal_stress(mu, bulk, [lr, lt, 1.0]);
    // λ_r from the radial first Piola–Kirchhoff stress at hoop stretch lt
    // (P_r grows with λ_r)
    let lambda_r = |pr: f64, lt: f64| {
        let (mut lo, mut hi) = (0.05, 20.0);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if lt * sigma(mid, lt)[0] < pr {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    // state (f, P_r) over R
    let rhs = |r: f64, y: [f64; 2]| {
        let lt = y[0] / r;
        let lr = lambda_r(y[1], lt);
        let s = sigma(lr, lt);
        [lr, -(y[1] - lr * s[1]) / r]
    };
    let n = 400;
    let h = (b - a) / n as f64;
    let shoot = |ra: f64| -> [f64; 2] {
        let lt = ra / a;
        let mut y = [ra, -p * lt];
        let mut r = a;
        for _ in 0..n {
            let k1 = rhs(r, y);
            let k2 = rhs(r + 0.5 * h, std::array::from_fn(|i| y[i] + 0.5 * h * k1[i]));
            let k3 = rhs(r + 0.5 * h, std::array::from_fn(|i| y[i] + 0.5 * h * k2[i]));
            let k4 = rhs(r + h, std::array::from_fn(|i| y[i] + h * k3[i]));
            for i in 0..2 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
            r += h;
        }
        y
    };
    // the more the inside opens, the more the outside is pulled: P_r(b)
    // grows with f(a)
    let (mut lo, mut hi) = if p >= 0.0 { (a, 3.0 * a) } else { (0.3 * a, a) };
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if shoot(mid)[1] > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let ra = 0.5 * (lo + hi);
    (ra, shoot(ra)[0])
}

#[cfg(test)]
mod large_strain_tests {
    use super::*;

    #[test]
    fn elastica_matches_mattiasson_table() {
        let (u, v) = elastica_cantilever_tip(1.0);
        assert!((u - 0.05643).abs() < 2e-4, "u/L = {u}");
        assert!((v - 0.30172).abs() < 2e-4, "v/L = {v}");
        let (u, v) = elastica_cantilever_tip(2.0);
        assert!((u - 0.16064).abs() < 2e-4, "u/L = {u}");
        assert!((v - 0.49346).abs() < 2e-4, "v/L = {v}");
    }

    #[test]
    fn pressurised_tube_small_pressure_limit_is_lame() {
        // plane-strain Lamé: u(a) = (1+ν) p a² / (E (b² − a²)) ((1−2ν) a + b²/a)
        let (e, nu, a, b, p) = (1.0, 0.3, 1.0, 2.0, 1e-6);
        let (mu, bulk) = (e / (2.0 * (1.0 + nu)), e / (3.0 * (1.0 - 2.0 * nu)));
        let (ra, rb) = neo_hookean_pressurised_tube(mu, bulk, a, b, p);
        let ua =
            (1.0 + nu) * p * a * a / (e * (b * b - a * a)) * ((1.0 - 2.0 * nu) * a + b * b / a);
        let ub = (1.0 + nu) * p * a * a / (e * (b * b - a * a)) * ((1.0 - 2.0 * nu) * b + b);
        assert!(
            ((ra - a) / ua - 1.0).abs() < 1e-4,
            "{} against {ua}",
            ra - a
        );
        assert!(
            ((rb - b) / ub - 1.0).abs() < 1e-4,
            "{} against {ub}",
            rb - b
        );
        // finite strain: an independent shooting (scipy solve_ivp, rtol
        // 1e-11, brentq) gives r(a) = 1.55562 at p = 0.15
        let (ra, _) = neo_hookean_pressurised_tube(mu, bulk, a, b, 0.15);
        assert!((ra - 1.55562).abs() < 2e-5, "{ra}");
    }

    #[test]
    fn neo_hookean_small_strain_limit_is_hooke() {
        // E = 1000, ν = 0.3: μ = 384.6, K = 833.3; uniaxial force ≈ E ε
        let (mu, bulk) = (1000.0 / 2.6, 1000.0 / 1.2);
        let (s, f) = neo_hookean_uniaxial(mu, bulk, 1.0 + 1e-6);
        assert!((f / 1e-6 - 1000.0).abs() < 0.01, "{f}");
        assert!(((1.0 - s) / 1e-6 - 0.3).abs() < 1e-4, "{s}");
    }
}

/// Thick-walled sphere (inner radius `a`, outer `b`) of an elastic–
/// perfectly plastic von Mises (= Tresca, σ_θθ = σ_φφ) solid under internal
/// pressure `p`, small strain (Hill 1950, ch. V; Chakrabarty, *Theory of
/// Plasticity*, §5.3). The plastic zone a ≤ r ≤ c has σ_θθ − σ_rr = σ_Y;
/// its radius c is the root of p = 2σ_Y ln(c/a) + (2σ_Y/3)(1 − c³/b³), and
/// the elastic shell c ≤ r ≤ b is the Lamé sphere at yield on its inside.
#[derive(Debug, Clone, Copy)]
pub struct PlasticSphere {
    /// Inner radius a.
    pub a: f64,
    /// Outer radius b.
    pub b: f64,
    /// Yield stress σ_Y.
    pub yield_stress: f64,
    /// Internal pressure p.
    pub p: f64,
    /// Radius c of the elastic–plastic boundary (a while elastic).
    pub c: f64,
}

impl PlasticSphere {
    /// The solution at pressure `p`; `None` at or beyond the limit pressure
    /// 2σ_Y ln(b/a), where the whole wall yields.
    pub fn new(a: f64, b: f64, yield_stress: f64, p: f64) -> Option<Self> {
        let sy = yield_stress;
        let pressure_at =
            |c: f64| 2.0 * sy * (c / a).ln() + 2.0 * sy / 3.0 * (1.0 - (c / b).powi(3));
        if !(p < pressure_at(b)) {
            return None;
        }
        let c = if p <= pressure_at(a) {
            a
        } else {
            // pressure_at increases with c: bisection
            let (mut lo, mut hi) = (a, b);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if pressure_at(mid) < p {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi)
        };
        Some(PlasticSphere {
            a,
            b,
            yield_stress: sy,
            p,
            c,
        })
    }

    /// (σ_rr, σ_θθ) at radius `r`.
    pub fn stress(&self, r: f64) -> (f64, f64) {
        let (a, b, c, sy) = (self.a, self.b, self.c, self.yield_stress);
        if self.c == a {
            return lame_sphere_stress(a, b, self.p, r);
        }
        if r < c {
            let srr = -self.p + 2.0 * sy * (r / a).ln();
            (srr, srr + sy)
        } else {
            let k = 2.0 * sy / 3.0 * c.powi(3);
            (
                -k * (r.powi(-3) - b.powi(-3)),
                k * (0.5 * r.powi(-3) + b.powi(-3)),
            )
        }
    }

    /// Radial displacement of the outer surface for Young's modulus `e` and
    /// Poisson's ratio `nu`: the Lamé shell c..b under the pressure
    /// (2σ_Y/3)(1 − c³/b³) on its inside, u(b) = σ_Y (1 − ν) c³/(E b²) once
    /// yielding (3 p a³ b (1 − ν)/(2 E (b³ − a³)) while elastic).
    pub fn outer_displacement(&self, e: f64, nu: f64) -> f64 {
        let (a, b, c) = (self.a, self.b, self.c);
        if c == a {
            3.0 * self.p * a.powi(3) * b * (1.0 - nu) / (2.0 * e * (b.powi(3) - a.powi(3)))
        } else {
            self.yield_stress * (1.0 - nu) * c.powi(3) / (e * b * b)
        }
    }
}
