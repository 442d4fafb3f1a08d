//! The interrupt hook: a per-thread check that the solvers and the time
//! integrator poll, so bindings can honour Ctrl-C without the library
//! knowing about signals.

#[cfg(doc)]
use crate::error::Error;
use std::cell::Cell;

thread_local! {
    static INTERRUPT: Cell<Option<fn() -> bool>> = const { Cell::new(None) };
}

/// Runs `work` with `check` polled at every continuation step and Newton
/// iteration on this thread; when it returns `true` the solver stops with
/// [`Error::Interrupted`]. Bindings use it to honour Ctrl-C.
///
/// # Example
/// ```
/// use flexure::{deflect, solver::with_interrupt, Error, Flexure, StaticsData, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = StaticsData::new(&f);
/// let load = TipLoad { moment: 100.0, fx: 0.0, fy: 0.0 };
/// let r = with_interrupt(|| true, || deflect(&f, &load, &mut data, &Default::default()));
/// assert!(matches!(r, Err(Error::Interrupted { .. })));
/// ```
pub fn with_interrupt<R>(check: fn() -> bool, work: impl FnOnce() -> R) -> R {
    /// Restores the previous hook on every exit, unwinding included.
    struct Restore(Option<fn() -> bool>);
    impl Drop for Restore {
        fn drop(&mut self) {
            INTERRUPT.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(INTERRUPT.with(|c| c.replace(Some(check))));
    work()
}

/// Whether the hook set by [`with_interrupt`] asks to stop; also polled by
/// the time integrator ([`crate::dynamics::integrate`]).
pub(crate) fn interrupted() -> bool {
    INTERRUPT.with(|c| c.get()).is_some_and(|check| check())
}
