//! The command line run in-process, as the tests call it.

/// `flexure ARGS`: the exit status, stdout and stderr.
pub fn run(args: &[&str]) -> (u8, String, String) {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = flexure_cli::run(std::iter::once("flexure").chain(args.iter().copied()), &mut out, &mut err);
    (code, String::from_utf8_lossy(&out).into(), String::from_utf8_lossy(&err).into())
}

/// `flexure ARGS --json`, which must exit 0: the answer and stderr (its
/// warnings are the caller's to check).
pub fn answer(args: &[&str]) -> (serde_json::Value, String) {
    let mut a = args.to_vec();
    a.push("--json");
    let (code, out, err) = run(&a);
    assert_eq!(code, 0, "{args:?}: {err}");
    (serde_json::from_str(&out).unwrap(), err)
}
