//! `flexure export`: a mechanism as MJCF, SDFormat or URDF, each flexure a
//! pseudo-rigid-body chain fitted over the file's loads.

use clap::Args;
use flexure::export::{Format, LoadRange, Options};
use flexure::prb::PrbKind;
use serde_json::{Value, json};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ExportArgs {
    /// Mechanism file (TOML).
    file: PathBuf,
    /// The format: mjcf (MuJoCo), sdf (SDFormat 1.9, Gazebo) or urdf (ROS).
    #[arg(long, value_parser = format)]
    to: Format,
    /// Write the model to this file; without it the model goes to stdout (with --json, into the report's `model`).
    #[arg(long)]
    out: Option<PathBuf>,
    /// The loads the fits are made over, F0:F1:N: N fractions of all the file's loads from F0 to F1 (2 ≤ N ≤ 64).
    #[arg(long, value_parser = range, default_value = "0:1:12")]
    range: LoadRange,
    /// Each flexure's pseudo-rigid-body chain: 3R (Su's chain) or 1R (Howell's characteristic pivot, whose tip angle is flagged past 1°).
    #[arg(long, value_parser = prb, default_value = "3R")]
    prb: PrbKind,
    /// Rotor inertia (kg·m²) added to every pseudo-rigid hinge (MJCF's armature), on top of what --step sizes.
    #[arg(long, value_parser = crate::options::number, default_value = "0")]
    armature: f64,
    /// The simulator's time step (s) the model is sized for: a sprung joint whose own link would ring faster than 10 steps gets the armature that slows it to that, and MJCF's timestep and closures' solref are set from it (0: no sizing).
    #[arg(long, value_parser = crate::options::number, default_value = "0.002")]
    step: f64,
    /// The model's name.
    #[arg(long)]
    name: Option<String>,
}

fn format(s: &str) -> Result<Format, String> {
    s.parse().map_err(|e: flexure::Error| crate::describe(e))
}

fn range(s: &str) -> Result<LoadRange, String> {
    s.parse().map_err(|e: flexure::Error| crate::describe(e))
}

fn prb(s: &str) -> Result<PrbKind, String> {
    s.parse().map_err(|e: flexure::Error| crate::describe(e))
}

/// What `export` answers: the report, and the model if it goes to stdout.
pub struct Exported {
    /// The fit report (JSON).
    pub report: Value,
    /// The model, when no `--out` was given.
    pub model: Option<String>,
}

/// Fits, builds and writes the model; warnings (flagged fits, what the
/// format cannot hold) and notes are queued for stderr.
pub fn export_cmd(args: &ExportArgs, json: bool) -> Result<Exported, String> {
    let model = crate::input::read_model(&args.file)?;
    let name = args.name.clone().unwrap_or_else(|| {
        args.file.file_stem().map_or_else(|| "mechanism".into(), |s| s.to_string_lossy().into_owned())
    });
    let options = Options {
        format: args.to,
        prb: args.prb,
        range: args.range,
        armature: args.armature,
        step: args.step,
        name,
        ..Default::default()
    };
    let e = model.export(&options).map_err(|e| format!("{}: {}", args.file.display(), crate::describe(e)))?;
    for w in &e.warnings {
        crate::options::warn(w.clone());
    }
    for n in &e.report.notes {
        crate::options::note(n.clone());
    }
    let mut report = json!(e.report);
    if !json {
        // The table form: warnings and notes are on stderr already, one a line.
        if let Some(r) = report.as_object_mut() {
            r.remove("warnings");
            r.remove("notes");
        }
    }
    match &args.out {
        Some(path) => {
            std::fs::write(path, &e.xml).map_err(|err| format!("--out {}: {err}", path.display()))?;
            report["out"] = json!(path.display().to_string());
            Ok(Exported { report, model: None })
        }
        None if json => {
            report["model"] = json!(e.xml);
            Ok(Exported { report, model: None })
        }
        None => {
            // The model on stdout; the fits told on stderr.
            for line in e.report.fit_lines() {
                crate::options::note(line);
            }
            Ok(Exported { report, model: Some(e.xml) })
        }
    }
}
