//! `flexure buckle`: the linear buckling factor on all of a mechanism's loads.

use super::{flexure_names, flexure_orders, load};
use clap::Args;
use flexure::mechanism::statics::Settings;
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
    if let Some(m) = super::spatial::read(&args.file)? {
        return super::spatial::buckle_cmd(&m, &args.file, &args.accuracy.target());
    }
    let m = load(&args.file)?;
    // Buckling about a preloaded assembly: the preload is told.
    let findings = crate::findings::closures(&m, &args.file)?;
    let target = args.accuracy.target();
    let (m, b, e) = flexure::estimate::buckle_auto(&m, &Settings::default(), &target)
        .map_err(|e| super::file_error(&args.file, e))?;
    let mut answer = json!(b);
    let flexures = flexure_names(&m);
    let auto = m.joints.iter().any(|j| j.auto_order);
    if auto {
        answer["order"] = flexure_orders(&m);
    }
    crate::eigen::insert_eigen_estimate(
        &mut answer,
        &e,
        &crate::eigen::Shape { key: "load_factor", one: true, flexures: &flexures },
    );
    let hint = if auto {
        "the flexures of order = \"auto\" are at the cap of 64: give the others order = \"auto\" too"
    } else {
        "give the flexures order = \"auto\" (or a higher order) in the file"
    };
    crate::eigen::warn_missed(
        &e,
        &target,
        &format!("{}: buckle", args.file.display()),
        |_| format!("the load factor {:.6}", b.load_factor),
        &crate::eigen::reference_of_mechanism(&e, &flexures),
        hint,
    );
    if !findings.is_empty() {
        answer["findings"] = json!(findings);
    }
    Ok(answer)
}
