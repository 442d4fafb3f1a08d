//! Progress of a run, reported to a hook the caller sets: the library
//! itself prints nothing.

thread_local! {
    static PROGRESS: std::cell::Cell<Option<fn(f64)>> = const { std::cell::Cell::new(None) };
}

/// Runs `work` with `report` called on this thread after every accepted
/// step of [`integrate`](super::integrate), with the fraction of the duration reached (from 0
/// to 1): a command line shows progress with it. The library itself prints
/// nothing.
///
/// # Example
/// ```
/// use flexure::dynamics::{integrate::with_progress, simulate, SimulationSettings, Start};
/// use std::sync::atomic::{AtomicU64, Ordering};
/// static LAST: AtomicU64 = AtomicU64::new(0);
/// // A sprung arm released from 0.1 rad, simulated for the default second.
/// let m = flexure::mechanism::file::from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[body]]\nname = \"arm\"\ninertia = 0.5\n[initial]\npin = 0.1\n",
/// )
/// .unwrap();
/// let report = |f: f64| LAST.store(f.to_bits(), Ordering::Relaxed);
/// let run = with_progress(report, || simulate(&m, &SimulationSettings::default(), Start::Equilibrium)).unwrap();
/// // The last report is the whole duration.
/// assert!(run.steps > 0 && f64::from_bits(LAST.load(Ordering::Relaxed)) == 1.0);
/// ```
pub fn with_progress<R>(report: fn(f64), work: impl FnOnce() -> R) -> R {
    /// Restores the previous hook on every exit, unwinding included.
    struct Restore(Option<fn(f64)>);
    impl Drop for Restore {
        fn drop(&mut self) {
            PROGRESS.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(PROGRESS.with(|c| c.replace(Some(report))));
    work()
}

/// Calls the hook of [`with_progress`], if one is set, with the fraction
/// of the duration reached.
pub(super) fn report(fraction: f64) {
    if let Some(report) = PROGRESS.with(|c| c.get()) {
        report(fraction);
    }
}
