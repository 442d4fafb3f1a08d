//! Progress of a run, and each sample as it is reached, reported to hooks
//! the caller sets: the library itself prints and writes nothing.

/// One sample of a run, as [`with_samples`] reports it the moment it is recorded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<'a> {
    /// Time (s).
    pub time: f64,
    /// The coordinates $q$.
    pub coordinates: &'a [f64],
    /// The rates $\dot q$.
    pub velocities: &'a [f64],
    /// Kinetic plus potential energy (J).
    pub energy: f64,
    /// The system's own numbers there ([`crate::dynamics::System::sample_columns`]):
    /// with contact, each pair's push (N).
    pub columns: &'a [f64],
}

thread_local! {
    static PROGRESS: std::cell::Cell<Option<fn(f64)>> = const { std::cell::Cell::new(None) };
    static SAMPLES: std::cell::Cell<Option<fn(&Sample)>> = const { std::cell::Cell::new(None) };
}

/// Runs `work` with `hook` called on this thread with every sample that
/// [`integrate`](super::integrate) records, as it records it: a command
/// line writes its rows with it, so a run stopped by a signal or a crash
/// keeps on disk the samples it reached.
///
/// # Example
/// ```
/// use flexure::dynamics::{integrate::{with_samples, Sample}, simulate, SimulationSettings, Start};
/// use std::sync::atomic::{AtomicUsize, Ordering};
/// static SEEN: AtomicUsize = AtomicUsize::new(0);
/// let m = flexure::mechanism::file::from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n\
///      [[body]]\nname = \"arm\"\ninertia = 0.5\n[initial]\npin = 0.1\n",
/// )
/// .unwrap();
/// let hook = |s: &Sample| _ = SEEN.fetch_add(s.coordinates.len(), Ordering::Relaxed);
/// let run = with_samples(hook, || simulate(&m, &SimulationSettings::default(), Start::Equilibrium)).unwrap();
/// // One coordinate at each of the 101 samples, each reported once.
/// assert_eq!((run.trajectory.time.len(), SEEN.load(Ordering::Relaxed)), (101, 101));
/// ```
pub fn with_samples<R>(hook: fn(&Sample), work: impl FnOnce() -> R) -> R {
    /// Restores the previous hook on every exit, unwinding included.
    struct Restore(Option<fn(&Sample)>);
    impl Drop for Restore {
        fn drop(&mut self) {
            SAMPLES.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(SAMPLES.with(|c| c.replace(Some(hook))));
    work()
}

/// Calls the hook of [`with_samples`], if one is set, with `sample`.
pub(super) fn sampled(sample: &Sample) {
    if let Some(hook) = SAMPLES.with(|c| c.get()) {
        hook(sample);
    }
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
