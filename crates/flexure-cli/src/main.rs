//! `flexure`: the command-line face of the flexure library. The work is in
//! the `flexure_cli` library target, so tests can run it in-process.

use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

/// Set by the first Ctrl-C (SIGINT) or SIGTERM: the running solve or
/// simulation stops at its next step and the command prints what it reached.
static STOP: AtomicBool = AtomicBool::new(false);

/// The library's interrupt hook ([`flexure::solver::with_interrupt`]).
fn stop_asked() -> bool {
    STOP.load(Ordering::Relaxed)
}

fn main() -> ExitCode {
    // The first Ctrl-C (or SIGTERM, as a job scheduler sends it) asks the work to stop and keep what it reached
    // (`simulate` prints its samples, a sweep its rows, then `stopped`, exit
    // 2); a second ends the process at once, as Ctrl-C did without a handler
    // (130 = 128 + SIGINT). Without a handler (it could not be installed)
    // Ctrl-C simply ends the process.
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
    let status = flexure::solver::with_interrupt(stop_asked, || {
        flexure_cli::run(std::env::args_os(), &mut std::io::stdout().lock(), &mut std::io::stderr().lock())
    });
    ExitCode::from(status)
}
