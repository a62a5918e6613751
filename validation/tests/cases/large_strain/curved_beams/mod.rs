//! curved-beams (thesis §5.3.3, issue 7; `../shared/benchmarks/README.md`):
//! two elastoplastic half-annuli slid past each other under the updated
//! Lagrangian form. Neto et al. (2016), as quoted by the benchmark table:
//! peak horizontal reaction 9.5 N at 7.0 mm for μ = 0 and 17.3 N for
//! μ = 0.3. The shipped case does not yet run to the end (it stops just
//! above the tolerance at 17.5 mm for μ = 0 and 21.5 mm for μ = 0.3), so
//! these tests check the Fx peak on the way there.
use validation::benchmarks::read_case;
use validation::run_toml_with_history;

/// Runs the shipped case with friction `mu` up to `until` mm of slide
/// (0.5 mm per increment, as shipped) and returns (|Fx| peak, at u).
fn fx_peak(mu: f64, until: f64) -> (f64, f64) {
    let (_, text) = read_case("curved-beams", "case.toml");
    let steps = (until / 0.5).round() as usize;
    let text = text
        .replace("friction = 0.3", &format!("friction = {mu:.1}"))
        .replace("end = 31.5", &format!("end = {until}"))
        .replace("steps = 63", &format!("steps = {steps}"));
    let (out, history) = run_toml_with_history(&text);
    assert!(out.converged, "μ = {mu}: {:?}", out.failure);
    let (a, b) = (
        history.column("upper/start:Fx"),
        history.column("upper/end:Fx"),
    );
    let t = history.column("time");
    let (k, peak) = a
        .iter()
        .zip(&b)
        .map(|(a, b)| (a + b).abs())
        .enumerate()
        .fold((0, 0.0), |m, (k, f)| if f > m.1 { (k, f) } else { m });
    eprintln!(
        "curved beams μ = {mu}: peak |Fx| {peak:.3} N at {:.1} mm; {} outer iterations, {:.0} s",
        t[k], out.summary.outer_iterations, out.summary.wall_seconds
    );
    (peak, t[k])
}

/// Measured: 9.556 N at 7.0 mm (Neto: 9.5 at 7.0), +0.6 %. Before the
/// traction offsets of the updated Lagrangian boundary faces it was 7–11 %
/// low.
#[test]
fn frictionless_fx_peak_within_three_percent_of_neto() {
    let (peak, at) = fx_peak(0.0, 10.0);
    assert!((peak / 9.5 - 1.0).abs() < 0.03, "{peak}");
    assert!((at - 7.0).abs() <= 1.0, "{at}");
}

/// Measured: 16.96 N at 18.0 mm (Neto: 17.3), −2.0 %. Slow (about
/// 40,000 outer iterations past 15 mm): `--ignored`.
#[test]
#[ignore]
fn frictional_fx_peak_within_three_percent_of_neto() {
    let (peak, _) = fx_peak(0.3, 19.0);
    assert!((peak / 17.3 - 1.0).abs() < 0.03, "{peak}");
}
