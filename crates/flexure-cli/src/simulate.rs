//! `flexure simulate`: the motion of a mechanism file over time.

use crate::options::number;
use clap::{Args, ValueEnum};
use flexure::dynamics::integrate;
use flexure::dynamics::integrate::Trajectory;
use flexure::dynamics::simulation::{Simulation, SimulationSettings, Start, simulate};
use flexure::mechanism::Mechanism;
use flexure::model::{Model, Motion};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde_json::{Value, json};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// Where the motion starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum StartArg {
    /// The static equilibrium under the loads at t = 0, at rest (the default).
    Equilibrium,
    /// The unloaded rest shape, at rest (massless flexures on their equilibrium under the loads at t = 0).
    Rest,
}

#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Mechanism file (TOML), with its `[[schedule]]`, `[initial]` and `[initial_velocity]`.
    file: PathBuf,
    /// Duration T (s): the motion over [0, T].
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    duration: f64,
    #[command(flatten)]
    motion: MotionOptions,
    /// Write one CSV row per sample: time, each moving body's x, y, phi (a spatial file's: x, y, z and its
    /// rotation's unit quaternion qw, qx, qy, qz, MuJoCo's order), each joint's coordinates and rates, energy,
    /// and with geoms each pair's push contact.GEOM.PART.normal_force.
    #[arg(long)]
    out: Option<PathBuf>,
    /// The error estimate's target: the motion is run again at a tenth of `--tolerance`, and the
    /// largest difference of a body's position (as a fraction of the mechanism's size) or angle is held to it.
    #[command(flatten)]
    accuracy: crate::options::AccuracyOptions,
}

/// The options of a simulation, shared with `draw --simulate`.
#[derive(Debug, Args, Clone)]
pub struct MotionOptions {
    /// Sample interval (s): samples at 0, DT, 2DT, … and T [default: T/100].
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    pub every: Option<f64>,
    /// Relative (and absolute) tolerance of each step's local error.
    #[arg(long, value_parser = number, allow_hyphen_values = true, default_value = "1e-8")]
    pub tolerance: f64,
    /// Where the motion starts; the file's [initial] and [initial_velocity] override it.
    #[arg(long, value_enum, default_value = "equilibrium")]
    pub start: StartArg,
    /// Steps the integrator may try, 1 to 1e9 [default: 1e6 plus 10 per sample].
    #[arg(long, value_parser = crate::options::steps, allow_hyphen_values = true)]
    pub max_steps: Option<usize>,
}

impl MotionOptions {
    /// The library's settings over `duration` (checked by the library, by name).
    pub fn settings(&self, duration: f64) -> SimulationSettings {
        let motion = integrate::MotionSettings {
            duration,
            every: self.every.unwrap_or(duration / 100.0),
            tolerance: self.tolerance,
            absolute: self.tolerance,
            max_steps: self.max_steps,
            ..Default::default()
        };
        SimulationSettings { motion, ..Default::default() }
    }

    pub fn start(&self) -> Start {
        match self.start {
            StartArg::Equilibrium => Start::Equilibrium,
            StartArg::Rest => Start::Rest,
        }
    }
}

/// The library's settings of `options` over `duration` (set by the option
/// `duration_option`), checked first: a bad one is named before any solve.
fn checked_settings(
    options: &MotionOptions,
    (duration, duration_option): (f64, &str),
) -> Result<SimulationSettings, String> {
    let settings = options.settings(duration);
    settings.motion.validate().map_err(|e| match e {
        flexure::Error::InvalidParameter { name: "duration", value, reason } => {
            format!("{duration_option} = {value}: {reason}")
        }
        e => crate::describe(e),
    })?;
    Ok(settings)
}

/// The motion of `m` (read from `file`) over `duration` (set by the option
/// `duration_option`) with `options`; a bad setting is named as its option.
pub fn run_motion<D: flexure::dynamics::Dynamics>(
    m: &Mechanism<D>,
    file: &Path,
    (duration, duration_option): (f64, &str),
    options: &MotionOptions,
) -> Result<Simulation<D>, String> {
    let settings = checked_settings(options, (duration, duration_option))?;
    with_progress_bar(duration, "simulated", || simulate(m, &settings, options.start()))
        .map_err(|e| format!("{}: {}", file.display(), simulation_error(e, duration)))
}

/// The library's error as `simulate` says it: options by their names, and
/// an interrupt at its time, not at a fraction of a load.
pub fn simulation_error(e: flexure::Error, duration: f64) -> String {
    match e {
        flexure::Error::InterruptedAt { time, .. } => {
            format!(
                "interrupted at t = {time:.6e} s of {duration:e} s ({:.2} % of the duration)",
                100.0 * time / duration
            )
        }
        e @ flexure::Error::InvalidParameter { .. } => crate::describe(e),
        e => e.to_string(),
    }
}

/// `stopped` for a run that ended early: its time and the error, which
/// makes the command exit 2 after printing the samples it reached.
pub fn insert_stopped(
    v: &mut Value,
    (run, stopped): (&Trajectory, &Option<flexure::Error>),
    file: &Path,
    duration: f64,
) {
    if let Some(e) = stopped {
        let reached = run.time.last().copied().unwrap_or(0.0);
        let error = format!(
            "{}: the run stopped after {} samples (to t = {reached:e} s of {duration:e} s, each printed above): {}",
            file.display(),
            run.time.len(),
            simulation_error(e.clone(), duration)
        );
        v["stopped"] = json!({ "time": reached, "error": error });
    }
}

thread_local! {
    /// The bar [`with_progress_bar`] shows; hidden unless stderr is a terminal.
    static BAR: ProgressBar = ProgressBar::hidden();
}

/// Runs `work` (a simulation of `duration` seconds) with a progress bar on
/// stderr when it is a terminal: the simulated time reached, updated after
/// every step (indicatif limits the redraws), cleared at the end.
fn with_progress_bar<R>(duration: f64, what: &str, work: impl FnOnce() -> R) -> R {
    if !std::io::stderr().is_terminal() {
        return work();
    }
    BAR.with(|bar| {
        // Style and length before the target, so no default frame is drawn.
        if let Ok(style) = ProgressStyle::with_template(&format!("{{bar:30}} {{percent}} % of {duration} s {what}")) {
            bar.set_style(style);
        }
        bar.set_length(1000);
        // In progress again after an earlier bar of this thread finished.
        bar.reset();
        bar.set_draw_target(ProgressDrawTarget::stderr());
    });
    let result =
        integrate::with_progress(|fraction| BAR.with(|bar| bar.set_position((fraction * 1000.0) as u64)), work);
    BAR.with(|bar| bar.finish_and_clear());
    result
}

/// `dimension`, `time`, `bodies` {name: {each pose key: one value per
/// sample}} (planar x, y, phi; spatial x, y, z, roll, pitch, yaw and
/// rotation), `coordinates` {joint: one row per sample}, `energy`, `steps`,
/// `rejected` and `violation`; `contacts` (each sample's) and `changes`
/// (where contacts touched and opened) where the mechanism has geoms; with
/// `findings`, and `stopped` after a run that ended early.
pub fn simulate_cmd(args: &SimulateArgs) -> Result<Value, String> {
    // The output file is opened before the run, so a path that cannot be
    // written is said before the work, not after it.
    let out = match &args.out {
        Some(path) => Some((
            path,
            std::fs::File::create(path).map_err(|e| format!("--out {}: {e} (nothing was run)", path.display()))?,
        )),
        None => None,
    };
    let settings = checked_settings(&args.motion, (args.duration, "--duration"))?;
    let model = crate::input::read_model(&args.file)?;
    let mut findings = crate::findings::open_at_rest(&model, &args.file)?;
    let work = || with_progress_bar(args.duration, "simulated", || model.simulate(&settings, args.motion.start()));
    let (run, written) = match out {
        Some((path, file)) => crate::samples::written_as_reached(&model, (path, file), work),
        None => (work(), Ok(())),
    };
    let run = run.map_err(|e| format!("{}: {}", args.file.display(), simulation_error(e, args.duration)))?;
    written?;
    let samples: Vec<(f64, &[f64])> =
        (0..run.trajectory.time.len()).map(|k| (run.trajectory.time[k], run.trajectory.q(k))).collect();
    let crossings = run.crossings.clone();
    findings.extend(crate::findings::crossing_answers_along(
        crossings,
        &samples,
        ("t (s)", "samples"),
        "time",
        &args.file,
    ));
    let mut v = motion_json(&model, &run);
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    if let Some(path) = &args.out {
        v["out"] = json!(path.display().to_string());
    }
    if run.stopped.is_none() {
        insert_motion_error(&mut v, &model, (&settings, args.motion.start()), &run, &args.accuracy.target());
    }
    insert_stopped(&mut v, (&run.trajectory, &run.stopped), &args.file, args.duration);
    Ok(v)
}

/// `error_estimate` and `flagged` of a run that reached its duration,
/// against a reference run at a tenth of its tolerance (a progress bar of
/// its own on a terminal), with a warning when it misses `target` or
/// cannot be made (then flagged, without `error_estimate`).
fn insert_motion_error(
    v: &mut Value,
    model: &Model,
    (settings, start): (&SimulationSettings, Start),
    run: &Motion,
    target: &flexure::estimate::Accuracy,
) {
    let duration = settings.motion.duration;
    let estimate = with_progress_bar(duration, "simulated again for the error estimate", || {
        model.motion_error(settings, start, run, target)
    });
    match estimate {
        Ok(e) => {
            if !e.complete {
                crate::options::warn(format!(
                    "simulate: the error estimate's reference run stopped after {} of {} samples: it covers t ≤ {:e} s only",
                    e.samples,
                    run.trajectory.time.len(),
                    run.trajectory.time[e.samples.saturating_sub(1)]
                ));
            } else if e.flagged {
                crate::options::warn(format!(
                    "simulate: estimated error {:.3e} m (tolerance {:.3e} m) and {:.3e} rad (tolerance {:.3e} rad), largest at t = {:e} s, misses --accuracy: tighten --tolerance",
                    e.position, e.position_tolerance, e.angle, target.angle, e.at
                ));
            }
            v["flagged"] = json!(e.flagged);
            v["error_estimate"] = json!(e);
        }
        Err(e) => {
            crate::options::warn(format!("simulate: no error estimate: {}", simulation_error(e, duration)));
            // No `error_estimate` key: an answer holds finite numbers only.
            v["flagged"] = json!(true);
        }
    }
}

/// The checks `simulate` makes of a run, shared by `draw --simulate`:
/// closures open at rest, and parts that cross at a sample (`findings`,
/// each told on stderr).
pub fn insert_motion_checks<D: flexure::model::Analyses>(
    v: &mut Value,
    m: &Mechanism<D>,
    run: &Simulation<D>,
    file: &Path,
) -> Result<(), String> {
    let mut findings = crate::findings::closures(m, file)?;
    let samples: Vec<(f64, &[f64])> = (0..run.time.len()).map(|k| (run.time[k], run.q(k))).collect();
    findings.extend(crate::findings::along(m, &samples, ("t (s)", "samples"), "time", file));
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    Ok(())
}

fn motion_json(model: &Model, run: &Motion) -> Value {
    // Each body's pose keys, each one value per sample.
    let bodies: serde_json::Map<String, Value> = run
        .bodies
        .iter()
        .map(|(name, poses)| {
            let mut series = serde_json::Map::new();
            for pose in poses {
                if let Ok(Value::Object(keys)) = serde_json::to_value(pose) {
                    for (key, x) in keys {
                        if let Value::Array(list) = series.entry(key).or_insert_with(|| json!([])) {
                            list.push(x);
                        }
                    }
                }
            }
            (name.clone(), Value::Object(series))
        })
        .collect();
    let t = &run.trajectory;
    let coordinates: serde_json::Map<String, Value> = model
        .joints()
        .into_iter()
        .map(|(name, range)| {
            let rows: Vec<&[f64]> = (0..t.time.len()).map(|s| &t.q(s)[range.clone()]).collect();
            (name, json!(rows))
        })
        .collect();
    let mut v = json!({
        "dimension": model.dimension(),
        "time": t.time,
        "bodies": bodies,
        "coordinates": coordinates,
        "energy": t.energy,
        "steps": t.steps,
        "rejected": t.rejected,
        "violation": t.violation,
    });
    if !run.contacts.is_empty() {
        v["contacts"] = json!(run.contacts);
        v["changes"] = json!(run.changes);
    }
    v
}
