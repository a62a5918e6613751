//! Isotropic hardening σ_Y(ε̄_p) of the J2 model (eqs. 2.28, 2.30) and the
//! scalar equation of its radial return.
use crate::MaterialError;

/// Yield stress as a function of the equivalent plastic strain ε̄_p (eq. 2.28).
///
/// The yield stress is compared with the Kirchhoff stress, as in eq. 2.28
/// (‖dev τ‖ − √(2/3) σ_Y); under the small elastic volume changes of metals
/// Kirchhoff and Cauchy stress differ by |J − 1| ≈ σ/K (about 0.2 % for steel
/// at yield).
#[derive(Debug, Clone, PartialEq)]
pub enum Hardening {
    /// σ_Y = `yield_stress` + `modulus` ε̄_p (case file: `yield`, `hardening`).
    Linear {
        /// Initial yield stress σ_Y(0) (case file: `yield`).
        yield_stress: f64,
        /// Hardening modulus H' = dσ_Y/dε̄_p (case file: `hardening`).
        modulus: f64,
    },
    /// Piecewise-linear rows (ε̄_p, σ_Y) (case file: `hardening_table`): the
    /// plastic strains strictly increase from 0, the stresses are positive;
    /// beyond the last row the yield stress stays constant (perfect
    /// plasticity, no extrapolation). One row is perfect plasticity.
    Table(Vec<(f64, f64)>),
}

impl Hardening {
    /// Validated linear hardening.
    pub fn linear(yield_stress: f64, modulus: f64) -> Result<Self, MaterialError> {
        let h = Hardening::Linear {
            yield_stress,
            modulus,
        };
        h.validate()?;
        Ok(h)
    }

    /// Validated tabulated hardening.
    pub fn table(rows: Vec<(f64, f64)>) -> Result<Self, MaterialError> {
        let h = Hardening::Table(rows);
        h.validate()?;
        Ok(h)
    }

    /// Checks the parameters; errors name them as in the case file.
    pub fn validate(&self) -> Result<(), MaterialError> {
        match self {
            Hardening::Linear {
                yield_stress,
                modulus,
            } => {
                if !(*yield_stress > 0.0 && yield_stress.is_finite()) {
                    return Err(MaterialError::OutOfRange {
                        name: "yield",
                        value: *yield_stress,
                        requirement: "must be positive and finite",
                    });
                }
                if !(*modulus >= 0.0 && modulus.is_finite()) {
                    return Err(MaterialError::OutOfRange {
                        name: "hardening",
                        value: *modulus,
                        requirement: "must be non-negative and finite",
                    });
                }
            }
            Hardening::Table(rows) => {
                if rows.is_empty() {
                    return Err(MaterialError::EmptyTable {
                        name: "hardening_table",
                    });
                }
                for (i, &(e, s)) in rows.iter().enumerate() {
                    if i == 0 && e != 0.0 {
                        return Err(MaterialError::InvalidTableEntry {
                            name: "hardening_table",
                            row: 0,
                            column: 0,
                            value: e,
                            requirement: "the first plastic strain must be 0",
                        });
                    }
                    if i > 0 && !(e > rows[i - 1].0 && e.is_finite()) {
                        return Err(MaterialError::InvalidTableEntry {
                            name: "hardening_table",
                            row: i,
                            column: 0,
                            value: e,
                            requirement: "plastic strains must be finite and strictly increasing",
                        });
                    }
                    if !(s > 0.0 && s.is_finite()) {
                        return Err(MaterialError::InvalidTableEntry {
                            name: "hardening_table",
                            row: i,
                            column: 1,
                            value: s,
                            requirement: "yield stresses must be positive and finite",
                        });
                    }
                }
            }
        }
        Ok(())
    }

    /// Initial yield stress σ_Y(0).
    pub fn initial_yield_stress(&self) -> f64 {
        self.yield_stress(0.0)
    }

    /// σ_Y(ε̄_p) (eq. 2.28). Cost: O(log n) for an n-row table.
    #[inline]
    pub fn yield_stress(&self, eps_p: f64) -> f64 {
        match self {
            Hardening::Linear {
                yield_stress,
                modulus,
            } => yield_stress + modulus * eps_p,
            Hardening::Table(rows) => {
                let k = segment(rows, eps_p);
                let (e0, s0) = rows[k];
                s0 + segment_slope(rows, k) * (eps_p - e0)
            }
        }
    }

    /// Slope dσ_Y/dε̄_p to the right of ε̄_p (0 beyond the last table row).
    pub fn slope(&self, eps_p: f64) -> f64 {
        match self {
            Hardening::Linear { modulus, .. } => *modulus,
            Hardening::Table(rows) => segment_slope(rows, segment(rows, eps_p)),
        }
    }

    /// Smallest slope dσ_Y/dε̄_p anywhere (negative for a softening table).
    pub fn min_slope(&self) -> f64 {
        match self {
            Hardening::Linear { modulus, .. } => *modulus,
            Hardening::Table(rows) => (0..rows.len())
                .map(|k| segment_slope(rows, k))
                .fold(f64::INFINITY, f64::min),
        }
    }

    /// Increment Δε̄_p ≥ 0 of the radial return from ε̄_p = `eps_p`: the root of
    ///
    /// q_trial − 3μ̄ Δε̄_p = σ_Y(ε̄_p + Δε̄_p),
    ///
    /// which is the consistency condition f = 0 of eq. 2.28 after the return
    /// s = s_trial − 2μ̄ Δγ n with Δε̄_p = √(2/3) Δγ (eq. 2.30) and
    /// q = √(3/2) ‖s‖ (Simo 1988). Exact for piecewise-linear σ_Y: the
    /// segments are walked until the root lies in one, so at most one pass
    /// over the table; no iteration tolerance. Requires 3μ̄ + dσ_Y/dε̄_p > 0
    /// everywhere (checked when the model is built) for a unique root;
    /// returns 0 when q_trial ≤ σ_Y(eps_p).
    pub fn plastic_increment(&self, eps_p: f64, q_trial: f64, three_mu_bar: f64) -> f64 {
        match self {
            Hardening::Linear {
                yield_stress,
                modulus,
            } => ((q_trial - yield_stress - modulus * eps_p) / (three_mu_bar + modulus)).max(0.0),
            Hardening::Table(rows) => {
                let mut k = segment(rows, eps_p);
                loop {
                    let (e0, s0) = rows[k];
                    let h = segment_slope(rows, k);
                    // φ(Δ) = q_trial − 3μ̄Δ − [s0 + h (eps_p + Δ − e0)] is linear here
                    let d = (q_trial - s0 - h * (eps_p - e0)) / (three_mu_bar + h);
                    match rows.get(k + 1) {
                        Some(&(e1, _)) if eps_p + d > e1 => k += 1,
                        _ => return d.max(0.0),
                    }
                }
            }
        }
    }
}

/// Index of the table segment containing ε̄_p: the last row with ε_k ≤ ε̄_p
/// (row 0 for ε̄_p < 0).
#[inline]
fn segment(rows: &[(f64, f64)], eps_p: f64) -> usize {
    rows.partition_point(|r| r.0 <= eps_p).saturating_sub(1)
}

/// Slope of segment k (0 for the open segment after the last row).
#[inline]
fn segment_slope(rows: &[(f64, f64)], k: usize) -> f64 {
    match rows.get(k + 1) {
        Some(&(e1, s1)) => (s1 - rows[k].1) / (e1 - rows[k].0),
        None => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Root of φ(Δ) = q − 3μ̄Δ − σ_Y(ε + Δ) by bisection (independent check).
    fn bisect(h: &Hardening, eps: f64, q: f64, three_mu_bar: f64) -> f64 {
        let phi = |d: f64| q - three_mu_bar * d - h.yield_stress(eps + d);
        let (mut lo, mut hi) = (0.0, 1.0);
        assert!(phi(lo) > 0.0 && phi(hi) < 0.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if phi(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn table_interpolates_and_is_constant_beyond_last_row() {
        let h = Hardening::table(vec![(0.0, 100.0), (0.1, 150.0), (0.3, 170.0)]).unwrap();
        assert_eq!(h.initial_yield_stress(), 100.0);
        assert!((h.yield_stress(0.05) - 125.0).abs() < 1e-12);
        assert!((h.yield_stress(0.2) - 160.0).abs() < 1e-12);
        assert_eq!(h.yield_stress(0.3), 170.0);
        assert_eq!(h.yield_stress(5.0), 170.0);
        assert!((h.slope(0.05) - 500.0).abs() < 1e-9);
        assert!((h.slope(0.1) - 100.0).abs() < 1e-9);
        assert_eq!(h.slope(1.0), 0.0);
        assert_eq!(h.min_slope(), 0.0);
    }

    #[test]
    fn linear_table_equals_linear_law() {
        let lin = Hardening::linear(250e6, 1e9).unwrap();
        // collinear rows, including a last row far beyond the strains used
        let tab = Hardening::table(vec![
            (0.0, 250e6),
            (0.01, 260e6),
            (0.05, 300e6),
            (10.0, 10.25e9),
        ])
        .unwrap();
        for &e in &[0.0, 0.003, 0.01, 0.02, 0.3, 2.0] {
            assert!((lin.yield_stress(e) - tab.yield_stress(e)).abs() < 1e-6);
            for &q in &[300e6, 2e9, 20e9] {
                let (a, b) = (
                    lin.plastic_increment(e, q, 3.0 * 80e9),
                    tab.plastic_increment(e, q, 3.0 * 80e9),
                );
                assert!((a - b).abs() < 1e-15 + 1e-12 * a, "{a} {b}");
            }
        }
    }

    #[test]
    fn return_crosses_segments_exactly() {
        // the thesis wire-rolling table (Table 5.4, GPa) includes a softening segment
        let h = Hardening::table(vec![
            (0.0, 1.3),
            (0.01, 1.5),
            (0.1, 1.69),
            (0.5, 1.64),
            (0.88, 2.11),
        ])
        .unwrap();
        let three_mu = 3.0 * 80.77;
        for &eps in &[0.0, 0.005, 0.05, 0.3, 0.7, 1.5] {
            for &dq in &[0.01, 0.5, 3.0, 30.0, 200.0] {
                let q = h.yield_stress(eps) + dq;
                let d = h.plastic_increment(eps, q, three_mu);
                let r = bisect(&h, eps, q, three_mu);
                assert!((d - r).abs() < 1e-12, "eps {eps} dq {dq}: {d} vs {r}");
                // consistency: q − 3μΔ = σ_Y(ε + Δ)
                assert!((q - three_mu * d - h.yield_stress(eps + d)).abs() < 1e-12);
            }
        }
        // elastic trial: no increment
        assert_eq!(h.plastic_increment(0.0, 1.0, three_mu), 0.0);
    }

    #[test]
    fn rejects_bad_parameters_by_name() {
        let msg = |h: Result<Hardening, MaterialError>| h.unwrap_err().to_string();
        assert!(msg(Hardening::linear(0.0, 1.0)).starts_with("yield = 0"));
        assert!(msg(Hardening::linear(f64::NAN, 1.0)).starts_with("yield = NaN"));
        assert!(msg(Hardening::linear(1.0, -1.0)).starts_with("hardening = -1"));
        assert!(msg(Hardening::table(vec![])).contains("hardening_table"));
        let m = msg(Hardening::table(vec![(0.1, 1.0)]));
        assert!(m.starts_with("hardening_table[0][0] = 0.1"), "{m}");
        let m = msg(Hardening::table(vec![(0.0, 1.0), (0.2, 2.0), (0.2, 3.0)]));
        assert!(m.starts_with("hardening_table[2][0] = 0.2"), "{m}");
        let m = msg(Hardening::table(vec![(0.0, 1.0), (0.2, -2.0)]));
        assert!(m.starts_with("hardening_table[1][1] = -2"), "{m}");
        assert!(Hardening::table(vec![(0.0, 1.0)]).is_ok());
    }
}
