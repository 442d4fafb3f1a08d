//! `flexure modes`: natural frequencies and mode shapes about the loaded
//! equilibrium, of a mechanism file or of one flexure joint carrying an
//! optional tip body, with the exact beam's frequencies beside the model's.

use crate::joint_options::LoadOptions;
use crate::mechanism::point_arg;
use crate::options::{FlexureOptions, count, number};
use clap::Args;
use flexure::dynamics::{self, Modes};
use flexure::estimate::Accuracy;
use flexure::inertia::RigidInertia;
use flexure::reference::vibration;
use flexure::{Error, TipLoad};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// Modes reported when `--count` is not given (fewer if the model has fewer
/// coordinates): the lowest, which a reduced model resolves best.
const DEFAULT_COUNT: usize = 3;

/// The largest `--count` parsed; it is then held to the model's coordinates.
const MAX_COUNT: usize = 10_000;

/// Parses `--count K`: a whole number from 1 to [`MAX_COUNT`].
fn mode_count(s: &str) -> Result<usize, String> {
    count(s, 1, MAX_COUNT)
}

/// Parses a finite number zero or greater (a mass, an inertia).
fn nonnegative(s: &str) -> Result<f64, String> {
    let v = number(s)?;
    if v >= 0.0 { Ok(v) } else { Err(format!("{s:?} must be zero or greater")) }
}

#[derive(Debug, Args)]
#[command(after_help = "Modes are taken about the loaded equilibrium (reached from rest under the \
    file's loads, or under --moment/--fx/--fy for one joint), with the loads' stiffness included, so \
    a frequency falls to zero at a buckling load and a load past it is refused as unstable. Closures \
    (welds, pins) are respected. Directions without inertia (a massless flexure's coordinates beyond \
    what its tip body moves) follow quasi-statically: they are condensed out, counted in \
    `quasi_static`, and never reported as infinite frequencies. Only finite modes are reported; \
    shapes are normalized to vᵀMv = 1. Each mode's estimated relative error, against the same \
    analysis with every flexure at twice the order, is in error_estimate.omega; a mode above \
    --accuracy is flagged with a warning, and --order auto (order = \"auto\" on a file's \
    flexures) raises the order until every mode meets it.")]
pub struct ModesArgs {
    /// Mechanism file (TOML). Without it: one flexure joint, from the options below.
    file: Option<PathBuf>,
    #[command(flatten)]
    flexure: FlexureOptions,
    #[command(flatten)]
    load: LoadOptions,
    /// Mass m (kg) of a rigid body fixed to the flexure's tip, zero or more.
    #[arg(long, value_parser = nonnegative, allow_hyphen_values = true)]
    tip_mass: Option<f64>,
    /// Rotary inertia (kg·m²) of the tip body about its centre of mass, zero or more.
    #[arg(long, value_parser = nonnegative, allow_hyphen_values = true)]
    tip_inertia: Option<f64>,
    /// Centre of mass X,Y (m) of the tip body, in the tip frame (x along the tip's tangent) [default: 0,0].
    #[arg(long, value_parser = point_arg, allow_hyphen_values = true)]
    tip_com: Option<[f64; 2]>,
    /// How many of the lowest modes to report, from 1 to the model's number of
    /// coordinates [default: 3, or fewer coordinates]. The highest modes of a
    /// model of order N are its least accurate: compare with --exact, or raise --order.
    #[arg(long, value_parser = mode_count, allow_hyphen_values = true)]
    count: Option<usize>,
    /// Also the exact linear vibration of the straight beam (Euler–Bernoulli
    /// with rotary inertia, EI(s), μ(s) and the tip body; every mode counted by
    /// the Wittrick–Williams argument, none skipped), and the model's relative error. Only about a straight
    /// equilibrium: no --kappa, and no load but an axial --fx.
    #[arg(long)]
    exact: bool,
    #[command(flatten)]
    accuracy: crate::eigen::EigenAccuracyOptions,
}

impl ModesArgs {
    /// The single-joint options given beside a file, by name.
    fn joint_options_given(&self) -> Vec<&'static str> {
        let f = &self.flexure;
        let mut given = Vec::new();
        let flags: [(&'static str, bool); 21] = [
            ("--length", f.length != 1.0),
            ("--ei", f.ei.is_some()),
            ("--modulus", f.modulus.is_some()),
            ("--width", f.width.is_some()),
            ("--thickness", f.thickness.is_some()),
            ("--poisson", f.poisson.is_some()),
            ("--notch", f.notch.is_some()),
            ("--density", f.density.is_some()),
            ("--mass-per-length", f.mass_per_length.is_some()),
            ("--kappa", f.kappa.is_some()),
            ("--order", f.order != crate::options::Order::Fixed(3)),
            ("--quadrature", f.quadrature.is_some()),
            ("--moment", self.load.moment != 0.0),
            ("--force", self.load.force.is_some()),
            ("--angle", self.load.angle.is_some()),
            ("--fx", self.load.fx.is_some()),
            ("--fy", self.load.fy.is_some()),
            ("--tip-mass", self.tip_mass.is_some()),
            ("--tip-inertia", self.tip_inertia.is_some()),
            ("--tip-com", self.tip_com.is_some()),
            ("--exact", self.exact),
        ];
        for (name, on) in flags {
            if on {
                given.push(name);
            }
        }
        given
    }

    /// The tip body, if any of its options is given.
    fn body(&self) -> Option<RigidInertia> {
        if self.tip_mass.is_none() && self.tip_inertia.is_none() && self.tip_com.is_none() {
            return None;
        }
        Some(RigidInertia {
            mass: self.tip_mass.unwrap_or(0.0),
            inertia: self.tip_inertia.unwrap_or(0.0),
            com: self.tip_com.unwrap_or([0.0, 0.0]),
        })
    }
}

/// `--count`, held to the model's `coordinates`: the default is at most
/// [`DEFAULT_COUNT`]; a larger explicit count is refused.
fn wanted(count: Option<usize>, coordinates: usize, what: &str) -> Result<usize, String> {
    if coordinates == 0 {
        return Err(nothing_moves(what));
    }
    match count {
        None => Ok(DEFAULT_COUNT.min(coordinates)),
        Some(k) if k > coordinates => Err(format!(
            "--count = {k}: must be from 1 to {coordinates}: {what} has {coordinates} coordinates, so at most that many modes"
        )),
        Some(k) => Ok(k),
    }
}

/// The error for a model with no coordinate: nothing to vibrate, whatever
/// `--count` (given or not) asked.
pub fn nothing_moves(what: &str) -> String {
    format!("{what} has no coordinates (no flexure or moving joint), so it has no vibration modes")
}

/// `quasi_static` and, when there is something to explain, a `note`: the
/// directions without inertia, and fewer finite modes than `--count` asked for.
fn insert_note(answer: &mut Value, modes: &Modes, asked: usize, explicit: bool) {
    answer["quasi_static"] = json!(modes.quasi_static);
    let mut notes = Vec::new();
    if modes.quasi_static > 0 {
        notes.push(format!(
            "{} direction(s) carry no inertia (a massless flexure's coordinates beyond what its bodies move): they follow the modes quasi-statically, with no frequency of their own, and are not reported",
            modes.quasi_static
        ));
    }
    if explicit && modes.omega.len() < asked {
        notes.push(format!(
            "{} finite mode(s) of the {asked} asked for: the model has no more finite modes resolved (frequencies above 1e6 times the lowest are not)",
            modes.omega.len()
        ));
    }
    if !notes.is_empty() {
        answer["note"] = json!(notes.join("; "));
    }
}

/// The modes of a mechanism file, or of one flexure joint.
pub fn modes_cmd(args: &ModesArgs) -> Result<Value, String> {
    match &args.file {
        Some(file) => {
            let given = args.joint_options_given();
            if !given.is_empty() {
                return Err(format!(
                    "{}: {} {} for one flexure joint, not for a mechanism file, whose joints, bodies and loads come from the file: leave {} out",
                    file.display(),
                    given.join(", "),
                    if given.len() == 1 { "is" } else { "are" },
                    if given.len() == 1 { "it" } else { "them" }
                ));
            }
            mechanism_modes(file, args.count, &args.accuracy.target())
        }
        None => joint_modes(args),
    }
}

fn mechanism_modes(file: &Path, count: Option<usize>, target: &Accuracy) -> Result<Value, String> {
    let model = crate::input::read_model(file)?;
    let err = |e: Error| match e {
        Error::Unstable { .. } => format!(
            "{}: unstable: {e}{}; an unstable equilibrium has no vibration modes (a frequency would be imaginary)",
            file.display(),
            crate::mechanism::loads_named(file, &e)
        ),
        e => crate::mechanism::solver_error(file)(e),
    };
    let asked = wanted(count, model.dof(), "the mechanism").map_err(|e| format!("{}: {e}", file.display()))?;
    let findings = crate::findings::open_at_rest(&model, file)?;
    let found = model.modes(asked, target).map_err(err)?;
    let (modes, used) = (&found.answer, &found.model);
    let shapes: Vec<Value> = (0..modes.omega.len())
        .map(|k| {
            let v = modes.shapes.column(k);
            let by_joint: serde_json::Map<String, Value> =
                used.coordinates().into_iter().map(|(name, range)| (name, json!(v.as_slice()[range]))).collect();
            Value::Object(by_joint)
        })
        .collect();
    let mut answer = json!({
        "dimension": model.dimension(),
        "omega": modes.omega,
        "frequency": modes.frequency,
        "shapes": shapes,
    });
    insert_note(&mut answer, modes, asked, count.is_some());
    crate::eigen::insert_mechanism_estimate(&mut answer, used, &found.estimate, "omega");
    crate::eigen::warn_missed(
        &found.estimate,
        target,
        &format!("{}: modes", file.display()),
        |k| format!("mode {} ({:.6} rad/s)", k + 1, modes.omega[k]),
        &used.reference_of(&found.estimate),
        &format!("{}, or ask fewer --count", crate::eigen::advice(used)),
    );
    // A loading path that snapped through a limit load is said, as `solve` says it.
    if let Some(limit) = modes.limit {
        answer["limit_fraction"] = json!(limit);
        crate::options::warn(format!(
            "{}: the loading path lost stability at {:.4} % of the load and snapped through: these are the modes about the stable equilibrium beyond it",
            file.display(),
            100.0 * limit
        ));
    }
    if !findings.is_empty() {
        answer["findings"] = json!(findings);
    }
    Ok(answer)
}

/// The library's error with the option that set it: the mass options for
/// `mass`, the statics' instability as such.
fn joint_error(e: Error) -> String {
    match e {
        Error::InvalidParameter { name: "mass", value, reason } => format!(
            "mass = {value}: {reason}; give --density (with --modulus --width --thickness) or --mass-per-length, or --tip-mass/--tip-inertia"
        ),
        e @ Error::Unstable { .. } => {
            format!("unstable: {e}; an unstable equilibrium has no vibration modes (a frequency would be imaginary)")
        }
        // The exact reference's axial compression is −fx.
        Error::InvalidParameter { name: "compression", value, reason } => {
            format!("--fx: a compression of {value}: {reason}")
        }
        e => crate::describe(e),
    }
}

/// The axial compression (N) the exact reference takes for `load`, or the
/// option that makes the equilibrium bent, which it does not cover.
fn compression(args: &ModesArgs, load: &TipLoad) -> Result<f64, String> {
    let refuse = |option: &str, value: f64| {
        format!(
            "{option} = {value}: --exact is the linear vibration of a straight beam, so about a straight equilibrium: only an axial --fx (compression or tension) is covered; leave {option} out or drop --exact"
        )
    };
    if load.moment != 0.0 {
        return Err(refuse("--moment", load.moment));
    }
    if load.fy != 0.0 {
        return match args.load.force {
            Some(p) => Err(refuse("--force/--angle (a force across the flexure)", p)),
            None => Err(refuse("--fy", load.fy)),
        };
    }
    Ok(-load.fx)
}

fn joint_modes(args: &ModesArgs) -> Result<Value, String> {
    let given = args.flexure.build().map_err(crate::describe)?;
    let load = args.load.load();
    let body = args.body();
    let target = args.accuracy.target();
    let auto = args.flexure.auto();
    // With --order auto the order rises to at least the count.
    let (limit, what) = if auto {
        (flexure::flexure::MAX_ORDER, "a flexure of the highest order, 64,")
    } else {
        (given.order(), "a flexure of this order")
    };
    let asked = wanted(args.count, limit, what)?;
    let f = &given;
    // Checked before the model solves, so a refused --exact costs nothing.
    let exact_compression = if args.exact {
        if let Some(k) = f.rest().iter().find(|&&k| k != 0.0) {
            return Err(format!(
                "--kappa: a rest curvature coefficient is {k}: --exact is the vibration of a straight beam; leave --kappa out or drop --exact"
            ));
        }
        Some(compression(args, &load)?)
    } else {
        None
    };
    let (f, modes, estimate) = if auto {
        flexure::estimate::modes_auto(f, &load, body.as_ref(), asked, &target).map_err(joint_error)?
    } else {
        let modes = dynamics::modes(f, &load, body.as_ref(), asked).map_err(joint_error)?;
        let e = flexure::estimate::modes_error(f, &load, body.as_ref(), &modes, &target).map_err(joint_error)?;
        (f.clone(), modes, e)
    };
    let shapes: Vec<Vec<f64>> =
        (0..modes.omega.len()).map(|k| modes.shapes.column(k).iter().copied().collect()).collect();
    let mut answer = json!({ "omega": modes.omega, "frequency": modes.frequency, "shapes": shapes });
    insert_note(&mut answer, &modes, asked, args.count.is_some());
    if auto {
        answer["order"] = json!(f.order());
        answer["quadrature"] = json!(f.quadrature_points());
    }
    crate::eigen::insert_eigen_estimate(
        &mut answer,
        &estimate,
        &crate::eigen::EigenKeys { key: "omega", one: false, flexures: &[] },
    );
    let hint = if !auto {
        "try --order auto, or fewer --count".to_string()
    } else {
        format!("--order auto stopped at the cap, order {}: ask fewer --count", f.order())
    };
    crate::eigen::warn_missed(
        &estimate,
        &target,
        "modes",
        |k| format!("mode {} ({:.6} rad/s)", k + 1, modes.omega[k]),
        &crate::eigen::reference_of_joint(&estimate),
        &hint,
    );
    let Some(p) = exact_compression else { return Ok(answer) };
    let exact = vibration::frequencies(&f, body.as_ref(), p, asked, &Default::default()).map_err(joint_error)?;
    let pairs = modes.omega.len().min(exact.omega.len());
    let error: Vec<f64> = (0..pairs).map(|k| modes.omega[k] / exact.omega[k] - 1.0).collect();
    answer["exact"] = json!({
        "omega": exact.omega,
        "frequency": exact.frequency,
        "beta_l": exact.scaled,
        "mass_per_length": exact.mass_per_length,
    });
    answer["error"] = json!({ "relative": error, "largest": error.iter().fold(0.0_f64, |m, e| m.max(e.abs())) });
    Ok(answer)
}
