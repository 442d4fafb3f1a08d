//! Subcommands on one flexure joint: kinematics, deflect, compliance, buckling.

use crate::options::{
    AccuracyOptions, FlexureOptions, List, StressOptions, angle, iterations, number, numbers, tolerance, warn,
};
use crate::spatial::{SpatialLoadOptions, SpatialOptions};
use clap::{Args, ValueEnum};
use flexure::Flexure;
use flexure::estimate::{Accuracy, ErrorEstimate};
use flexure::kinematics::TipKinematics;
use flexure::reference::elastica::Trace;
use flexure::reference::{self, elastica};
use flexure::{
    Error, Pose, Statics, TipConstraint, TipLoad, buckling_load, compliance_tip_rest, deflect, energy, energy_gradient,
};
use nalgebra::{Dim, Matrix, RawStorage};
use serde_json::{Value, json};

/// A library result as JSON: its `serde::Serialize` output, so the keys
/// the command prints are the library's field names.
pub fn serialized(result: &impl serde::Serialize) -> Value {
    // The results' keys are names and their numbers map to JSON (a NaN to
    // null, which `emit` refuses), so serializing them cannot fail.
    serde_json::to_value(result).unwrap_or(Value::Null)
}

/// The one JSON shape of an error estimate, batch rows and mechanism joints
/// included: the library's serialization of it.
pub fn estimate(e: &ErrorEstimate) -> Value {
    serialized(e)
}

/// Writes `error_estimate` and `flagged` into `answer`, warning on stderr
/// when the estimate misses `target` (`what` names the answer).
pub fn insert_estimate(answer: &mut Value, e: &ErrorEstimate, f: &Flexure, target: &Accuracy, what: &str) {
    if e.flagged {
        // At the highest order no order is left to try: the estimate is against the exact elastica.
        let hint = if e.exact {
            format!(
                "even order {} misses it (estimated against the exact elastica): loosen --accuracy or reduce the load",
                f.order()
            )
        } else {
            "try --order auto".into()
        };
        warn(format!("{what}: {}; {hint}", misses(e, f.length(), target)));
    }
    answer["error_estimate"] = estimate(e);
    answer["flagged"] = json!(e.flagged);
}

/// The largest factor `--limit` tries on a load.
pub const MAX_FACTOR: f64 = 1000.0;

/// Writes `--limit`'s answer into `answer`: `stability_limit`, the
/// library's serialization `{factor, status}`, `status` "lost" (stability is
/// lost at `factor` times the load) or "stable_up_to" (the path holds to
/// `factor`, and `stalled` says why it could not be followed further, if it
/// could not); such a stall is also said on stderr (`what` names the answer).
pub fn insert_limit(answer: &mut Value, limit: &flexure::StabilityLimit, what: &str) {
    if let flexure::StabilityLimit::StableUpTo { factor, stalled: Some(why) } = limit {
        warn(format!(
            "{what}: the loading path stays stable up to {factor:.6} times the load, as far as it could be followed (of the {MAX_FACTOR} tried); beyond it stability is unknown: {why}"
        ));
    }
    let mut v = json!(limit);
    // The library writes `stalled: null` when `max_factor` was reached; a
    // null in an answer reads as a non-finite number, so the key is left out.
    if let Some(o) = v.as_object_mut().filter(|o| o.get("stalled").is_some_and(Value::is_null)) {
        o.remove("stalled");
    }
    answer["stability_limit"] = v;
}

/// Warns that an answer is not a stable equilibrium (`what` names it).
pub fn warn_unstable(stable: bool, what: &str) {
    if !stable {
        warn(format!(
            "{what}: the equilibrium is unstable (`stable: false`): the stiffness is not positive definite, so a small disturbance moves it away; it is not a state the joint can rest in"
        ));
    }
}

/// Which parts of a flagged estimate miss `target`, and by how much, with
/// the parts that meet it: for warnings.
pub fn misses(e: &ErrorEstimate, length: f64, target: &Accuracy) -> String {
    let peak = if e.stress.is_some() { "peak stress" } else { "peak curvature" };
    let parts = [
        ("tip position", 100.0 * e.position / length, 100.0 * target.position, "% of L"),
        ("tip angle", e.angle.to_degrees(), target.angle.to_degrees(), "°"),
        (peak, 100.0 * e.peak, 100.0 * target.stress, "%"),
    ];
    let show =
        |(name, value, goal, unit): &(&str, f64, f64, &str)| format!("{name} {value:.3}{unit} (target {goal}{unit})");
    let (miss, meet): (Vec<_>, Vec<_>) = parts.iter().partition(|p| p.1 > p.2);
    let mut text = format!(
        "the estimated error exceeds the accuracy target: {}",
        miss.into_iter().map(show).collect::<Vec<_>>().join(", ")
    );
    if !meet.is_empty() {
        text += &format!("; within it: {}", meet.into_iter().map(show).collect::<Vec<_>>().join(", "));
    }
    text
}

/// The flexure to answer with: as given, or with `--order auto` the lowest
/// order meeting the target, found by `auto` (which returns it).
pub fn chosen(
    options: &FlexureOptions,
    auto: impl FnOnce(&Flexure) -> flexure::Result<Flexure>,
) -> flexure::Result<Flexure> {
    let f = options.build()?;
    if options.auto() { auto(&f) } else { Ok(f) }
}

/// A pose as JSON, `{phi, x, y}`: the library's serialization of it.
pub fn pose(p: &Pose) -> Value {
    serialized(p)
}

/// Any matrix as JSON rows.
pub fn matrix<R: Dim, C: Dim, S: RawStorage<f64, R, C>>(m: &Matrix<f64, R, C, S>) -> Value {
    json!(m.row_iter().map(|r| r.iter().copied().collect::<Vec<_>>()).collect::<Vec<_>>())
}

#[derive(Debug, Args)]
pub struct KinematicsArgs {
    #[command(flatten)]
    pub(crate) flexure: FlexureOptions,
    #[command(flatten)]
    pub(crate) spatial: SpatialOptions,
    /// Joint coordinates α1,α2,… (one per order; with --spatial the twist's, then κ_y's, then κ_z's).
    #[arg(long, value_parser = numbers, allow_hyphen_values = true, required_unless_present = "input")]
    pub(crate) alpha: Option<List>,
    /// A CSV of α rows with header a1,a2,…: one output line per row.
    #[arg(long, conflicts_with = "alpha")]
    pub input: Option<std::path::PathBuf>,
}

impl KinematicsArgs {
    pub fn flexure(&self) -> flexure::Result<flexure::Flexure> {
        if self.spatial.spatial {
            return Err(Error::invalid("input", "given with --spatial", "batches are for planar flexures only"));
        }
        self.flexure.build_fixed("kinematics")
    }
}

/// Pose, transform, Jacobian, Hessians, energy and gradient at α.
pub fn kinematics(args: &KinematicsArgs) -> flexure::Result<Value> {
    if args.spatial.spatial {
        return crate::spatial::kinematics(args, &args.spatial);
    }
    let f = args.flexure.build_fixed("kinematics")?;
    let alpha = args.alpha.as_ref().map(|a| a.0.clone()).unwrap_or_default();
    let mut out = serialized(&TipKinematics::at(&f, &alpha)?);
    let mut gradient = vec![0.0; f.order()];
    energy_gradient(&f, &alpha, &mut gradient);
    out["energy"] = json!(energy(&f, &alpha));
    out["gradient"] = json!(gradient);
    Ok(out)
}

/// A tip load: `--moment`, and `--force P --angle θ` or `--fx --fy`.
#[derive(Debug, Clone, Args)]
pub struct LoadOptions {
    /// Tip moment M in N·m (counter-clockwise positive).
    #[arg(long, default_value = "0", value_parser = number, allow_hyphen_values = true)]
    pub moment: f64,
    /// Tip force magnitude P in N, at --angle θ: Fx = −P sin θ, Fy = P cos θ (paper Sec. III-C).
    #[arg(long, value_parser = number, allow_hyphen_values = true, conflicts_with_all = ["fx", "fy"])]
    pub force: Option<f64>,
    /// Angle θ of --force, radians or e.g. 45deg [default: 0, across the flexure].
    #[arg(long, value_parser = angle, allow_hyphen_values = true, requires = "force")]
    pub angle: Option<f64>,
    /// Tip force along the root's x axis, N.
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    pub fx: Option<f64>,
    /// Tip force along the root's y axis, N.
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    pub fy: Option<f64>,
}

impl LoadOptions {
    pub fn load(&self) -> TipLoad {
        match self.force {
            Some(p) => TipLoad::polar(self.moment, p, self.angle.unwrap_or(0.0)),
            None => TipLoad { moment: self.moment, fx: self.fx.unwrap_or(0.0), fy: self.fy.unwrap_or(0.0) },
        }
    }
}

#[derive(Debug, Args)]
pub struct DeflectArgs {
    #[command(flatten)]
    pub(crate) flexure: FlexureOptions,
    #[command(flatten)]
    pub(crate) spatial: SpatialOptions,
    #[command(flatten)]
    pub(crate) load: LoadOptions,
    #[command(flatten)]
    pub(crate) spatial_load: SpatialLoadOptions,
    #[command(flatten)]
    pub accuracy: AccuracyOptions,
    #[command(flatten)]
    pub(crate) stress: StressOptions,
    /// Also solve the exact elastica (shooting); `pose` is then the exact one,
    /// and the model's stress and shape sit under `model`.
    #[arg(long)]
    pub(crate) exact: bool,
    /// Also find the factor on the load, up to 1000, at which the equilibrium
    /// followed from rest stops being stable, or up to which it stays stable
    /// (1000, or as far as the path could be followed, with a warning):
    /// `stability_limit` {factor, status: lost | stable_up_to}.
    #[arg(long)]
    pub(crate) limit: bool,
    /// Relative tolerance on the generalized-force residual, in (0, 1).
    #[arg(long, default_value = "1e-12", value_parser = tolerance, allow_hyphen_values = true)]
    pub(crate) tolerance: f64,
    /// Newton iterations allowed per load step, 1 to 10000.
    #[arg(long, default_value = "50", value_parser = iterations, allow_hyphen_values = true)]
    pub(crate) max_iterations: usize,
    /// A CSV of loads with header among moment,fx,fy (or moment,force,angle): one line per row.
    #[arg(
        long,
        conflicts_with_all = ["moment", "force", "angle", "fx", "fy", "exact", "limit", "yield_strength", "shape"]
    )]
    pub input: Option<std::path::PathBuf>,
}

impl DeflectArgs {
    /// The flexure for `--input` rows, which share one order.
    pub fn flexure(&self) -> flexure::Result<flexure::Flexure> {
        if self.spatial.spatial {
            return Err(Error::invalid("input", "given with --spatial", "batches are for planar flexures only"));
        }
        self.flexure.build_fixed("deflect --input")
    }
}

/// Equilibrium under a tip load (Eq. 22), and optionally the exact elastica.
pub fn deflect_cmd(args: &DeflectArgs) -> flexure::Result<Value> {
    if args.spatial.spatial {
        return crate::spatial::deflect(args);
    }
    let load = args.load.load();
    let target = args.accuracy.target();
    let f = chosen(&args.flexure, |f| Ok(flexure::estimate::deflect_auto(f, &load, &target)?.0))?;
    crate::stress::check(&f, &args.stress)?;
    let mut data = Statics::new(&f);
    let settings =
        flexure::Settings { tolerance: args.tolerance, max_iterations: args.max_iterations, ..Default::default() };
    let eq = deflect(&f, &load, &mut data, &settings)?;
    let mut model = json!({
        "alpha": data.alpha(),
        "pose": data.pose_root_tip(),
        "stiffness": matrix(&data.stiffness),
        "stable": eq.stable,
        "residual": eq.residual,
    });
    // With --limit, its refined factor is the one number printed.
    if let Some(limit) = eq.limit.filter(|_| !args.limit) {
        model["limit_fraction"] = json!(limit);
    }
    warn_unstable(eq.stable, "deflect");
    crate::stress::insert_stress(&mut model, &f, data.alpha(), &args.stress, "deflect");
    if args.flexure.auto() {
        model["order"] = json!(f.order());
        model["quadrature"] = json!(f.quadrature_points());
    }
    let e = flexure::estimate::deflect_error(&f, &load, data.alpha(), &target)?;
    insert_estimate(&mut model, &e, &f, &target, "deflect");
    if args.limit {
        insert_limit(&mut model, &flexure::statics::stability_limit(&f, &load, MAX_FACTOR)?, "deflect --limit");
    }
    if !args.exact {
        return Ok(model);
    }
    let (exact, trace) = elastica::deflect_traced(&f, &load, &Default::default())?;
    let (m, e) = (data.pose_root_tip(), exact.pose);
    let mut answer = json!({
        "pose": e,
        "root_moment": exact.root_moment,
        "stable": exact.stable,
        "model": model,
        "error": {
            "position": (m.x - e.x).hypot(m.y - e.y),
            "position_over_length": (m.x - e.x).hypot(m.y - e.y) / f.length(),
            "angle": (m.phi - e.phi).abs(),
            "angle_degrees": (m.phi - e.phi).abs().to_degrees(),
        },
    });
    insert_exact_stress(&mut answer, &trace, &args.stress, "deflect (exact)")?;
    Ok(answer)
}

/// The exact answer's bending, from its [`Trace`], as
/// [`crate::stress::insert_stress`] writes the model's: `stress: {max, at}` (or,
/// without a thickness, `curvature_max`), `safety_factor` with a warning
/// naming `what` below 1, and `shape` when asked for.
pub fn insert_exact_stress(
    answer: &mut Value,
    trace: &Trace,
    options: &StressOptions,
    what: &str,
) -> flexure::Result<()> {
    crate::stress::insert_peak(answer, trace.peak_stress()?, || trace.peak_curvature(), options.yield_strength, what)?;
    if let Some(k) = options.shape {
        let points: Vec<Value> = trace
            .shape(k)?
            .iter()
            .map(|p| {
                let mut point = json!({ "s": p.s, "x": p.x, "y": p.y, "phi": p.phi, "curvature": p.curvature });
                if let Some(sigma) = p.stress {
                    point["stress"] = json!(sigma);
                }
                point
            })
            .collect();
        answer["shape"] = json!(points);
    }
    Ok(())
}

#[derive(Debug, Args)]
pub struct ComplianceArgs {
    #[command(flatten)]
    flexure: FlexureOptions,
    #[command(flatten)]
    spatial: SpatialOptions,
    /// Integrate the compliance ODE (Eq. 34, with EI(s)) instead of the model's J K⁻¹ Jᵀ.
    #[arg(long)]
    exact: bool,
}

/// Small-load tip compliance at the rest shape, order (φ, x, y).
pub fn compliance(args: &ComplianceArgs) -> flexure::Result<Value> {
    if args.spatial.spatial {
        return crate::spatial::compliance(&args.flexure, &args.spatial, args.exact);
    }
    let f = args.flexure.build_fixed("compliance")?;
    let c = if args.exact {
        reference::compliance::compliance_tip(&f, &Default::default())?
    } else {
        compliance_tip_rest(&f)
    };
    Ok(json!({ "compliance": matrix(&c) }))
}

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Tip {
    Free,
    Guided,
    Pinned,
    Clamped,
}

impl From<Tip> for TipConstraint {
    fn from(t: Tip) -> Self {
        match t {
            Tip::Free => TipConstraint::Free,
            Tip::Guided => TipConstraint::Guided,
            Tip::Pinned => TipConstraint::Pinned,
            Tip::Clamped => TipConstraint::Clamped,
        }
    }
}

#[derive(Debug, Args)]
pub struct BucklingArgs {
    #[command(flatten)]
    flexure: FlexureOptions,
    /// How the tip is held.
    #[arg(long, value_enum)]
    tip: Tip,
    /// The exact load of a straight column instead of the model: Euler's
    /// closed form for a uniform one, shooting on the load for EI(s).
    #[arg(long)]
    exact: bool,
    #[command(flatten)]
    accuracy: crate::eigen::EigenAccuracyOptions,
}

/// Critical compressive tip load under a tip constraint, with its error
/// estimate (`--order auto`: at the lowest order that meets the target).
pub fn buckling(args: &BucklingArgs) -> flexure::Result<Value> {
    let tip = TipConstraint::from(args.tip);
    if args.exact {
        let f = args.flexure.build_fixed("buckling --exact")?;
        if f.rest().iter().any(|&k| k != 0.0) {
            return Err(Error::invalid(
                "kappa",
                format!("{:?}", f.rest()),
                "the exact buckling load is for a straight flexure",
            ));
        }
        let p = if f.section().is_uniform() {
            reference::euler::buckling_load(tip, f.length(), f.ei())
        } else {
            reference::column::buckling_load(&f, tip, &Default::default())?
        };
        return Ok(json!({ "critical_load": p, "tip": tip.name() }));
    }
    let target = args.accuracy.target();
    let given = args.flexure.build()?;
    let (f, b, e) = if args.flexure.auto() {
        flexure::estimate::buckling_auto(&given, tip, &target)?
    } else {
        let b = buckling_load(&given, tip)?;
        let e = flexure::estimate::buckling_error(&given, tip, &b, &target)?;
        (given, b, e)
    };
    let mut answer = serialized(&b);
    answer["tip"] = json!(tip.name());
    if args.flexure.auto() {
        answer["order"] = json!(f.order());
        answer["quadrature"] = json!(f.quadrature_points());
    }
    crate::eigen::insert_eigen_estimate(
        &mut answer,
        &e,
        &crate::eigen::Shape { key: "critical_load", one: true, flexures: &[] },
    );
    let hint = if !args.flexure.auto() {
        "try --order auto".to_string()
    } else {
        format!("--order auto stopped at the cap, order {}: this is the best the model can do", f.order())
    };
    crate::eigen::warn_missed(
        &e,
        &target,
        &format!("buckling ({} tip)", tip.name()),
        |_| format!("the critical load {:.6} N", b.critical_load),
        &crate::eigen::reference_of_joint(&e),
        &hint,
    );
    Ok(answer)
}
