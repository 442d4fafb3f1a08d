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
    /// The tests' trigger: polls left until [`signalled`] simulates Ctrl-C (0: none).
    static CTRL_C_AT_POLL: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// For the tests (`flexure._flexure._ctrl_c_at_poll`): simulates Ctrl-C
/// (`_thread.interrupt_main`, SIGINT's Python handler) at the `polls`-th
/// solver poll of the interruptible calls that follow on this thread, and
/// runs the handlers at once; 0 disarms. A trigger counted in the solvers'
/// own iterations, which no machine outruns, where a timer fires only after
/// a fast machine has finished the call.
#[pyfunction(name = "_ctrl_c_at_poll")]
pub fn ctrl_c_at_poll(polls: u64) {
    CTRL_C_AT_POLL.with(|n| n.set(polls));
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
    let ctrl_c = CTRL_C_AT_POLL.with(|n| {
        let left = n.get();
        n.set(left.saturating_sub(1));
        left == 1
    });
    if !ctrl_c && NEXT_POLL.with(|t| t.get()).is_some_and(|next| now < next) {
        return false;
    }
    NEXT_POLL.with(|t| t.set(Some(now + POLL)));
    Python::attach(|py| {
        let checked = if ctrl_c {
            py.import("_thread").and_then(|t| t.call_method0("interrupt_main")).and_then(|_| py.check_signals())
        } else {
            py.check_signals()
        };
        match checked {
            Ok(()) => false,
            Err(e) => {
                RAISED.with(|r| *r.borrow_mut() = Some(e));
                true
            }
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
