//! The command line run in-process, as the tests call it.

/// `flexure ARGS`: the exit status, stdout and stderr.
pub fn run(args: &[&str]) -> (u8, String, String) {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = flexure_cli::run(std::iter::once("flexure").chain(args.iter().copied()), &mut out, &mut err);
    (code, String::from_utf8_lossy(&out).into(), String::from_utf8_lossy(&err).into())
}
