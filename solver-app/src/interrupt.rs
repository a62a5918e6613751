//! Stopping a run on SIGINT (Ctrl-C) or SIGTERM without losing its
//! results (issue 45).
//!
//! The signal handler only stores the signal's number in an atomic; the
//! time loop reads it between increments and, through the nonlinear
//! solver's per-iteration callback, within one. The run then ends the way
//! a failure does: the increment in progress is dropped (the state goes
//! back to the last converged one), the files are closed after the write
//! under way, `summary.json` says `"interrupted": true`, and `fvc` exits
//! with 128 + the signal's number (130, 143), as a shell reports a process
//! ended by that signal. A second signal ends the process at once (the
//! increment being written may then be incomplete) — unless it comes
//! within [`REPEAT_WINDOW_NS`] of the first: GNU `timeout` sends its
//! signal to the process and then to its process group, which holds the
//! process, so one request arrives twice within microseconds (found by a
//! probe: `timeout 60 fvc run …` ended without `summary.json`).
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// A signal this soon after the first is the same request delivered
/// twice, not a second one (a person pressing Ctrl-C twice takes longer).
#[cfg(unix)]
const REPEAT_WINDOW_NS: u64 = 100_000_000;

/// Monotonic clock in nanoseconds (clock_gettime is async-signal-safe).
#[cfg(unix)]
fn monotonic_ns() -> u64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes the timespec it is given
    unsafe { libc::clock_gettime(libc::CLOCK_MONOTONIC, &mut ts) };
    (ts.tv_sec as u64)
        .saturating_mul(1_000_000_000)
        .saturating_add(ts.tv_nsec as u64)
}

/// The stop request of a run: none until a signal arrived.
#[derive(Debug, Clone, Default)]
pub struct Interrupt {
    /// The signal's number, 0 while none arrived.
    signal: Arc<AtomicUsize>,
}

impl Interrupt {
    /// A request that only [`Self::request`] sets (library use, tests).
    pub fn new() -> Self {
        Self::default()
    }

    /// Routes SIGINT and SIGTERM of this process to a new request: the
    /// first of them asks the run to stop, the next one exits at once with
    /// 128 + its number. For `fvc run`; a library caller keeps the
    /// default handlers.
    #[cfg(unix)]
    pub fn install() -> std::io::Result<Self> {
        use signal_hook::consts::{SIGINT, SIGTERM};
        use std::sync::atomic::AtomicU64;
        let me = Self::new();
        // when the first signal came (0: none yet)
        let first = Arc::new(AtomicU64::new(0));
        for sig in [SIGINT, SIGTERM] {
            let (first, signal) = (first.clone(), me.signal.clone());
            let action = move || {
                let now = monotonic_ns().max(1);
                match first.compare_exchange(0, now, Ordering::SeqCst, Ordering::SeqCst) {
                    Ok(_) => signal.store(sig as usize, Ordering::SeqCst),
                    Err(t0) if now.saturating_sub(t0) > REPEAT_WINDOW_NS => {
                        signal_hook::low_level::exit(128 + sig)
                    }
                    Err(_) => {}
                }
            };
            // SAFETY: the action is async-signal-safe: atomics, the
            // monotonic clock and _exit only
            unsafe { signal_hook::low_level::register(sig, action) }?;
        }
        Ok(me)
    }

    /// Without Unix signals: a request nothing sets.
    #[cfg(not(unix))]
    pub fn install() -> std::io::Result<Self> {
        Ok(Self::new())
    }

    /// Asks the run to stop as if signal `sig` had arrived.
    pub fn request(&self, sig: i32) {
        self.signal.store(sig.max(1) as usize, Ordering::SeqCst);
    }

    /// The signal that asked the run to stop, if one did.
    pub fn requested(&self) -> Option<i32> {
        match self.signal.load(Ordering::Relaxed) {
            0 => None,
            s => Some(s as i32),
        }
    }
}

/// The conventional name of a stop signal, for messages and the summary.
pub fn signal_name(sig: i32) -> String {
    match sig {
        2 => "SIGINT".to_owned(),
        15 => "SIGTERM".to_owned(),
        s => format!("signal {s}"),
    }
}

/// Exit code of a run that signal `sig` stopped: 128 + its number (130
/// for SIGINT, 143 for SIGTERM), as shells report it.
pub fn exit_code(sig: i32) -> u8 {
    (128 + sig).clamp(0, 255) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_is_seen_by_every_clone_and_maps_to_the_shell_exit_code() {
        let a = Interrupt::new();
        let b = a.clone();
        assert_eq!(b.requested(), None);
        a.request(15);
        assert_eq!(b.requested(), Some(15));
        assert_eq!(exit_code(2), 130);
        assert_eq!(exit_code(15), 143);
        assert_eq!(signal_name(2), "SIGINT");
    }
}
