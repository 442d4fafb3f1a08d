//! Ctrl-C and other signal handlers during a solve that runs without the GIL.

use crate::errors::to_py;
use flexure::Error;
use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use std::time::{Duration, Instant};

thread_local! {
    /// What a Python signal handler raised while an interruptible call ran on this thread.
    static RAISED: std::cell::RefCell<Option<PyErr>> = const { std::cell::RefCell::new(None) };
    /// When the interrupt check next runs Python's handlers.
    static NEXT_POLL: std::cell::Cell<Option<Instant>> = const { std::cell::Cell::new(None) };
}

/// How often a running solve hands control to Python's signal handlers:
/// taking the GIL at every Newton iteration would double the cost of a
/// small solve, and 10 ms is well below what a person pressing Ctrl-C notices.
pub const POLL: Duration = Duration::from_millis(10);

/// The solvers' interrupt check: at most every [`POLL`], runs Python's signal
/// handlers (only on the main thread; Ctrl-C's raises `KeyboardInterrupt`)
/// and keeps what they raised for [`interruptible`] to raise.
pub fn signalled() -> bool {
    let now = Instant::now();
    if NEXT_POLL.with(|t| t.get()).is_some_and(|next| now < next) {
        return false;
    }
    NEXT_POLL.with(|t| t.set(Some(now + POLL)));
    Python::attach(|py| match py.check_signals() {
        Ok(()) => false,
        Err(e) => {
            RAISED.with(|r| *r.borrow_mut() = Some(e));
            true
        }
    })
}

/// Starts an interruptible call: forgets what a handler raised before, and
/// first polls after [`POLL`], so a quick call never takes the GIL back.
pub fn clear_raised() {
    RAISED.with(|r| r.borrow_mut().take());
    NEXT_POLL.with(|t| t.set(Some(Instant::now() + POLL)));
}

/// What a signal handler raised during the work, if anything; a plain
/// `KeyboardInterrupt` is replaced by `interrupted`, which says how far the
/// work got.
pub fn raised_during(py: Python<'_>, interrupted: impl FnOnce() -> PyErr) -> Option<PyErr> {
    let raised = RAISED.with(|r| r.borrow_mut().take())?;
    if raised.is_instance_of::<PyKeyboardInterrupt>(py) { Some(interrupted()) } else { Some(raised) }
}

/// Runs a solve without the GIL, polling Python's signal handlers at every
/// continuation step and Newton iteration ([`flexure::solver::with_interrupt`]):
/// Ctrl-C stops it with `KeyboardInterrupt` saying the load fraction reached,
/// and an exception raised by any other handler propagates as it is.
pub fn interruptible<T: Send>(py: Python<'_>, work: impl FnOnce() -> flexure::Result<T> + Send) -> PyResult<T> {
    clear_raised();
    let out = py.detach(|| flexure::solver::with_interrupt(signalled, work));
    let message = match &out {
        Err(e @ (Error::Interrupted { .. } | Error::InterruptedAt { .. })) => e.to_string(),
        _ => "interrupted".to_string(),
    };
    // A handler that raised wins even over a result: Python would have raised it.
    match raised_during(py, || PyKeyboardInterrupt::new_err(message)) {
        Some(err) => Err(err),
        None => out.map_err(to_py),
    }
}
