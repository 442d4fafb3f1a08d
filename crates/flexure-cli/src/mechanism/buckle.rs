//! `flexure buckle`: the linear buckling factor on all of a mechanism's loads.

use clap::Args;
use serde_json::{Value, json};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct BuckleArgs {
    /// Mechanism file (TOML).
    file: PathBuf,
    #[command(flatten)]
    accuracy: crate::eigen::EigenAccuracyOptions,
}

/// Linear buckling factor on all loads, and the mode, with its error
/// estimate; flexures of `order = "auto"` raised until it meets the target.
pub fn buckle_cmd(args: &BuckleArgs) -> Result<Value, String> {
    let model = crate::input::read_model(&args.file)?;
    let target = args.accuracy.target();
    // Buckling about a preloaded assembly: the preload is told.
    let findings = crate::findings::open_at_rest(&model, &args.file)?;
    let found = model.buckle(&target).map_err(super::solver_error(&args.file))?;
    let b = &found.answer;
    let mut answer = json!({ "dimension": model.dimension(), "load_factor": b.load_factor, "mode": b.mode });
    crate::eigen::insert_mechanism_estimate(&mut answer, &found.model, &found.estimate, "load_factor");
    crate::eigen::warn_missed(
        &found.estimate,
        &target,
        &format!("{}: buckle", args.file.display()),
        |_| format!("the load factor {:.6}", b.load_factor),
        &found.model.reference_of(&found.estimate),
        &format!("{} in the file", crate::eigen::advice(&found.model)),
    );
    if !findings.is_empty() {
        answer["findings"] = json!(findings);
    }
    Ok(answer)
}
