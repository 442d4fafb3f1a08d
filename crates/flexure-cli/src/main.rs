//! `flexure`: the command-line face of the flexure library. The work is in
//! the `flexure_cli` library target, so tests can run it in-process.

use std::process::ExitCode;

fn main() -> ExitCode {
    let status = flexure_cli::run(std::env::args_os(), &mut std::io::stdout().lock(), &mut std::io::stderr().lock());
    ExitCode::from(status)
}
