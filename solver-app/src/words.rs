//! Counts, numbers and durations as a person writes them in the terminal
//! and the log: "1 increment", "3 increments", t = 0.125, 2 min 05 s.

/// `n` and the noun in the number it takes: `count(1, "body", "bodies")`
/// is "1 body", `count(2, …)` "2 bodies".
///
/// ```
/// use solver_app::words::count;
/// assert_eq!(count(1, "increment", "increments"), "1 increment");
/// assert_eq!(count(0, "increment", "increments"), "0 increments");
/// ```
pub fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// A number to six significant digits without trailing zeros: plain
/// between 0.001 and 1,000,000 (0.125, 4.5, 1200), in scientific notation
/// otherwise (2.5e-5, 3.2e7).
///
/// ```
/// use solver_app::words::number;
/// assert_eq!(number(0.125), "0.125");
/// assert_eq!(number(1.0), "1");
/// assert_eq!(number(0.5666666666666667), "0.566667");
/// assert_eq!(number(2.5e-5), "2.5e-5");
/// assert_eq!(number(-1200.0), "-1200");
/// ```
pub fn number(x: f64) -> String {
    // + 0.0: −0 prints as 0
    let x = x + 0.0;
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return x.to_string();
    }
    let a = x.abs();
    if (1e-3..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        trim(format!("{x:.decimals$}"))
    } else {
        let s = format!("{x:.5e}");
        match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m.to_owned())),
            None => s,
        }
    }
}

/// [`number`] as a `Display` value, for format strings:
/// `format!("t = {}", Num(t))`.
#[derive(Debug, Clone, Copy)]
pub struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(&number(self.0))
    }
}

/// Drops the trailing zeros of a decimal fraction (and a bare point).
fn trim(s: String) -> String {
    if !s.contains('.') {
        return s;
    }
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// Wall time: "0.42 s", "12.3 s", "2 min 05 s", "1 h 02 min".
///
/// ```
/// use solver_app::words::duration;
/// assert_eq!(duration(0.4234), "0.42 s");
/// assert_eq!(duration(12.34), "12.3 s");
/// assert_eq!(duration(125.0), "2 min 05 s");
/// assert_eq!(duration(3720.0), "1 h 02 min");
/// ```
pub fn duration(seconds: f64) -> String {
    let s = seconds.max(0.0);
    if s < 9.995 {
        return format!("{s:.2} s");
    }
    if s < 59.95 {
        return format!("{s:.1} s");
    }
    let whole = s.round() as u64;
    if whole < 3600 {
        return format!("{} min {:02} s", whole / 60, whole % 60);
    }
    let minutes = (s / 60.0).round() as u64;
    format!("{} h {:02} min", minutes / 60, minutes % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_six_significant_digits() {
        assert_eq!(number(1.0 / 3.0), "0.333333");
        assert_eq!(number(123456.7), "123457");
        assert_eq!(number(1e-3), "0.001");
        assert_eq!(number(9.99e-4), "9.99e-4");
        assert_eq!(number(1e6), "1e6");
        assert_eq!(number(f64::NAN), "NaN");
        assert_eq!(duration(9.999), "10.0 s");
        assert_eq!(duration(59.96), "1 min 00 s");
        assert_eq!(duration(3599.6), "1 h 00 min");
    }
}
