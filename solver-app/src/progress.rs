//! The progress bar of `fvc run` on a terminal (standard error): the
//! increments done, the time elapsed, an estimate of the time left, and
//! the current nonlinear iteration.
//!
//! The estimate is the increments left times the mean wall time of the
//! last [`WINDOW`] increments of this run: an increment's cost, not its
//! share of the simulated time, is what stays roughly the same along a
//! run (the shallow ironing's 20 indentation increments span t = 0–1 and
//! its 500 sliding ones t = 1–6), and the recent ones follow the run into
//! its harder part (contact, sliding). None is shown before the first
//! increment is done.
use std::time::Duration;

use crate::words::duration;

/// Increments the estimate averages over.
pub const WINDOW: usize = 10;

/// The bar, or nothing when standard error is not a terminal (or with
/// `--quiet`).
pub struct Progress {
    bar: Option<indicatif::ProgressBar>,
    n: usize,
    /// Wall seconds of the last increments, oldest first overwritten.
    recent: [f64; WINDOW],
    done: usize,
}

impl Progress {
    /// A bar for increments `first + 1..=n` when `show`.
    pub fn new(show: bool, first: usize, n: usize) -> Self {
        let bar = show.then(|| {
            let pb = indicatif::ProgressBar::new(n as u64);
            pb.set_style(
                indicatif::ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {bar:30} {prefix} {msg}",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            pb.set_position(first as u64);
            pb.set_prefix(format!("increment {first}/{n}"));
            pb.enable_steady_tick(Duration::from_millis(250));
            pb
        });
        Progress {
            bar,
            n,
            recent: [0.0; WINDOW],
            done: 0,
        }
    }

    /// Whether the bar is shown.
    pub fn is_shown(&self) -> bool {
        self.bar.is_some()
    }

    /// Nonlinear iteration `outer` of the current increment ended with
    /// `residual` (shown every tenth).
    pub fn iteration(&self, outer: usize, residual: f64) {
        if let Some(pb) = &self.bar {
            if outer.is_multiple_of(10) {
                pb.set_message(format!("iteration {outer}, residual {residual:.2e}"));
            }
        }
    }

    /// Increment `k` is done, in `seconds` of wall time.
    pub fn increment_done(&mut self, k: usize, seconds: f64) {
        self.recent[self.done % WINDOW] = seconds;
        self.done += 1;
        let Some(pb) = &self.bar else {
            return;
        };
        pb.set_position(k as u64);
        pb.set_message("");
        let left = self.n.saturating_sub(k);
        let prefix = match estimate(&self.recent, self.done, left) {
            Some(s) if left > 0 => format!("increment {k}/{}, about {} left", self.n, duration(s)),
            _ => format!("increment {k}/{}", self.n),
        };
        pb.set_prefix(prefix);
    }

    /// Takes the bar off the terminal.
    pub fn finish(&self) {
        if let Some(pb) = &self.bar {
            pb.finish_and_clear();
        }
    }
}

/// Seconds for `left` more increments at the mean of the last `done`
/// (at most [`WINDOW`]) increments' `recent` wall times; `None` before
/// the first.
pub fn estimate(recent: &[f64; WINDOW], done: usize, left: usize) -> Option<f64> {
    let m = done.min(WINDOW);
    if m == 0 {
        return None;
    }
    let mean = recent[..m].iter().sum::<f64>() / m as f64;
    Some(mean * left as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimate_follows_the_recent_increments() {
        let mut p = Progress::new(false, 0, 100);
        assert_eq!(estimate(&p.recent, p.done, 100), None);
        // ten cheap increments, then ten that cost ten times more: the
        // estimate is that of the expensive ones
        for k in 1..=10 {
            p.increment_done(k, 0.1);
        }
        assert!((estimate(&p.recent, p.done, 90).unwrap() - 9.0).abs() < 1e-9);
        for k in 11..=20 {
            p.increment_done(k, 1.0);
        }
        assert!((estimate(&p.recent, p.done, 80).unwrap() - 80.0).abs() < 1e-9);
        for k in 21..=25 {
            p.increment_done(k, 2.0);
        }
        // five at 1 s and five at 2 s in the window
        assert!((estimate(&p.recent, p.done, 75).unwrap() - 112.5).abs() < 1e-9);
    }
}
