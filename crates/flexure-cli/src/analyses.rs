//! Subcommands for the paper's analyses: connect and tendon.

use crate::answer::{MAX_FACTOR, insert_limit, serialized, warn_unstable};
use crate::joint::{chosen, insert_estimate};
use crate::options::{AccuracyOptions, FlexureOptions, StressOptions, angle_of, count, number, segments, warn};
use clap::Args;
use flexure::connect::{Connection, connect};
use flexure::estimate::Accuracy;
use flexure::reference::elastica;
use flexure::tendon::{TendonData, TendonOffsets, equilibrium};
use flexure::{Error, Flexure, Pose, TipLoad};
use serde_json::{Value, json};

/// A tip pose `PHI,X,Y`; PHI may end in `deg`.
#[derive(Debug, Clone, Copy)]
pub struct PoseArg(pub Pose);

pub fn pose_arg(s: &str) -> Result<PoseArg, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("{s:?} must be three values PHI,X,Y"));
    }
    Ok(PoseArg(Pose { phi: angle_of("--pose PHI", parts[0])?, x: number(parts[1])?, y: number(parts[2])? }))
}

#[derive(Debug, Args)]
pub struct ConnectArgs {
    #[command(flatten)]
    flexure: FlexureOptions,
    /// Tip pose PHI,X,Y in the root frame (PHI in radians, or e.g. 90deg).
    #[arg(long, value_parser = pose_arg, allow_hyphen_values = true)]
    pose: PoseArg,
    /// Solve the exact elastica through the pose instead (shooting on three unknowns).
    #[arg(long, conflicts_with = "segments")]
    exact: bool,
    /// Use a chain of K constant-curvature segments instead of the model (1 to 64).
    #[arg(long, value_parser = segments, allow_hyphen_values = true)]
    segments: Option<usize>,
    #[command(flatten)]
    accuracy: AccuracyOptions,
    #[command(flatten)]
    stress: StressOptions,
    /// Also find the factor on the tip load that holds the pose (`load`),
    /// applied from rest as a dead load, up to 1000, at which its equilibrium
    /// stops being stable, or up to which it stays stable: `stability_limit`
    /// {factor, status: lost | stable_up_to}.
    #[arg(long, conflicts_with_all = ["exact", "segments"])]
    limit: bool,
}

/// The exact connection, seeded by the order-3 model's multipliers (on the
/// same section, when order 3 can hold it).
pub fn exact_connection(flexure: &Flexure, target: &Pose) -> flexure::Result<elastica::ElasticaConnection> {
    // The seed is the order-3 model of the same flexure: its section and its
    // rest shape (the basis is nested, so the first three coefficients).
    let seed = match flexure.order() {
        3 => flexure.clone(),
        _ => {
            let mut kappa = flexure.rest().to_vec();
            kappa.resize(3, 0.0);
            Flexure::new(flexure.length(), flexure.ei(), 3)?
                .with_rest(&kappa)?
                .with_section(flexure.section().clone())?
        }
    };
    let c: Connection = connect(&seed, target)?;
    let m0 = c.load.moment + target.x * c.load.fy - target.y * c.load.fx;
    elastica::connect(flexure, target, [m0, c.load.fx, c.load.fy], &Default::default())
}

/// Minimum-energy shape to a tip pose (Sec. II-E), with η against the exact elastica when it can be found.
pub fn connect_cmd(args: &ConnectArgs) -> flexure::Result<Value> {
    let target = args.pose.0;
    let accuracy = args.accuracy.target();
    if args.segments.is_some() && args.flexure.auto() {
        return Err(Error::invalid("order", "auto", "--segments compares a chain of its own: give no --order auto"));
    }
    let model = chosen(&args.flexure, |f| Ok(flexure::estimate::connect_auto(f, &target, &accuracy)?.0))?;
    crate::stress::check(&model, &args.stress)?;
    if args.exact {
        let e = exact_connection(&model, &target)?;
        let c = connect(&model, &target)?;
        let mut reported = json!({});
        crate::stress::insert_stress(&mut reported, &model, &c.alpha, &args.stress, "connect (model)");
        let mut answer = json!({
            "energy": e.energy,
            "loads": TipLoad { moment: e.root_moment, fx: e.fx, fy: e.fy },
            "model_energy": c.energy,
            "eta": c.eta(e.energy),
            "model": reported,
        });
        let trace = e.trace(&model, &Default::default())?;
        crate::joint::insert_exact_stress(&mut answer, &trace, &args.stress, "connect (exact)")?;
        return Ok(answer);
    }
    if let Some(k) = args.segments {
        // A chain's rest shape lives in its own basis; the CLI builds straight chains only.
        if model.rest().iter().any(|&r| r != 0.0) {
            return Err(Error::invalid(
                "kappa",
                format!("{:?}", model.rest()),
                "--segments compares straight chains; drop --kappa",
            ));
        }
        let chain = Flexure::segments(model.length(), model.ei(), k)?.with_section(model.section().clone())?;
        let c = connect(&chain, &target)?;
        let curvatures: Vec<f64> = c.alpha.iter().map(|a| a * k as f64 / model.length()).collect();
        let mut out = json!({ "energy": c.energy, "curvatures": curvatures });
        crate::stress::insert_stress(&mut out, &chain, &c.alpha, &args.stress, "connect (segments)");
        if let Ok(e) = exact_connection(&model, &target) {
            out["eta"] = json!(c.eta(e.energy));
        }
        return Ok(out);
    }
    let c = connect(&model, &target)?;
    let e = flexure::estimate::connect_error(&model, &target, &c.alpha, &accuracy)?;
    let mut out = serialized(&c);
    if args.flexure.auto() {
        out["order"] = json!(model.order());
        out["quadrature"] = json!(model.quadrature_points());
    }
    insert_estimate(&mut out, &e, &model, &accuracy, "connect");
    crate::stress::insert_stress(&mut out, &model, &c.alpha, &args.stress, "connect");
    if args.limit {
        insert_limit(&mut out, &flexure::statics::stability_limit(&model, &c.load, MAX_FACTOR)?, "connect --limit");
    }
    if let Ok(e) = exact_connection(&model, &target) {
        out["eta"] = json!(c.eta(e.energy));
    }
    Ok(out)
}

/// A sweep `F0:F1:COUNT` of tendon tension.
#[derive(Debug, Clone, Copy)]
pub struct SweepRange {
    pub from: f64,
    pub to: f64,
    pub count: usize,
}

/// Most values in one sweep: every value is a full solve, and each is kept for the answer.
pub const MAX_SWEEP: usize = 10_000;

/// Parses `F0:F1:COUNT` with finite ends and 2 to [`MAX_SWEEP`] values.
fn range(s: &str) -> Result<SweepRange, String> {
    let parts: Vec<&str> = s.split(':').collect();
    if parts.len() != 3 {
        return Err(format!("{s:?} must be F0:F1:COUNT"));
    }
    let count = count(parts[2], 2, MAX_SWEEP).map_err(|e| format!("COUNT {e}"))?;
    Ok(SweepRange { from: number(parts[0])?, to: number(parts[1])?, count })
}

/// A tendon-tension sweep: a range whose ends are not negative.
pub fn sweep_arg(s: &str) -> Result<SweepRange, String> {
    let sweep = range(s)?;
    if sweep.from < 0.0 || sweep.to < 0.0 {
        return Err(format!("{s:?}: a tendon's tension cannot be negative"));
    }
    Ok(sweep)
}

#[derive(Debug, Args)]
pub struct TendonArgs {
    #[command(flatten)]
    flexure: FlexureOptions,
    /// Tendon tension f in N.
    #[arg(long, value_parser = number, allow_hyphen_values = true, required_unless_present_any = ["sweep", "force"])]
    tension: Option<f64>,
    /// Deprecated: the old name of --tension (warns).
    #[arg(long, value_parser = number, allow_hyphen_values = true, conflicts_with = "tension")]
    force: Option<f64>,
    /// Tendon offset from the neutral axis at the root, m (T1 = translation (0, D1)).
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    root_offset: f64,
    /// Tendon offset from the neutral axis at the tip, m (T2 = translation (0, D2)).
    #[arg(long, value_parser = number, allow_hyphen_values = true)]
    tip_offset: f64,
    /// Sweep the tension F0:F1:COUNT, following the loading path.
    #[arg(long, value_parser = sweep_arg, allow_hyphen_values = true, conflicts_with_all = ["tension", "force"])]
    sweep: Option<SweepRange>,
    #[command(flatten)]
    accuracy: AccuracyOptions,
    #[command(flatten)]
    stress: StressOptions,
    /// Also find the factor on the tension, up to 1000, at which the joint's
    /// equilibrium followed from rest stops being stable, or up to which it
    /// stays stable: `stability_limit` {factor, status: lost | stable_up_to}.
    #[arg(long, conflicts_with = "sweep")]
    limit: bool,
}

impl TendonArgs {
    /// The tension given by `--tension`, or by the deprecated `--force` (with a warning).
    fn tension(&self) -> Option<f64> {
        if self.force.is_some() {
            warn("--force is deprecated for tendon; use --tension".into());
        }
        self.tension.or(self.force)
    }
}

fn tendon_row(
    f: &Flexure,
    t: &TendonOffsets,
    tension: f64,
    data: &mut TendonData,
    target: &Accuracy,
    stress: &StressOptions,
) -> flexure::Result<Value> {
    let eq = equilibrium(f, t, tension, data)?;
    let mut row = serialized(&eq);
    warn_unstable(eq.stable, &format!("tendon at {tension} N"));
    let e = flexure::estimate::tendon_error(f, t, tension, &eq.alpha, target)?;
    insert_estimate(&mut row, &e, f, target, &format!("tendon at {tension} N"));
    crate::stress::insert_stress(&mut row, f, &eq.alpha, stress, &format!("tendon at {tension} N"));
    Ok(row)
}

/// Tendon-driven joint equilibrium (Sec. III-D), or a sweep of tensions.
pub fn tendon_cmd(args: &TendonArgs) -> flexure::Result<Value> {
    let t = TendonOffsets { root_offset: args.root_offset, tip_offset: args.tip_offset };
    let target = args.accuracy.target();
    if args.sweep.is_some() && args.flexure.auto() {
        return Err(Error::invalid("order", "auto", "a sweep's rows share one order: give a number with --sweep"));
    }
    let tension = args.tension();
    if let Some(bad) = tension.filter(|t| !(t.is_finite() && *t >= 0.0)) {
        return Err(Error::invalid("tension", bad, "a tendon's tension must be finite and not negative"));
    }
    let f = chosen(&args.flexure, |f| match tension {
        Some(tension) => Ok(flexure::estimate::tendon_auto(f, &t, tension, &target)?.0),
        None => Ok(f.clone()),
    })?;
    crate::stress::check(&f, &args.stress)?;
    let mut data = TendonData::new(&f);
    match (args.sweep, tension) {
        (Some(s), _) => {
            // Every row reached is printed; a failure ends the sweep in its
            // place (each value is continued from the last, so none after it is tried).
            let mut rows = Vec::new();
            for tension in sweep_values(&s) {
                match tendon_row(&f, &t, tension, &mut data, &target, &args.stress) {
                    Ok(row) => rows.push(row),
                    Err(e) => {
                        let reached = rows.len();
                        let error = format!(
                            "tendon --sweep: stopped at tension = {tension} N after {reached} of {} values: {}",
                            s.count,
                            crate::describe(e)
                        );
                        return Ok(json!({ "rows": rows, "stopped": { "tension": tension, "error": error } }));
                    }
                }
            }
            Ok(json!({ "rows": rows }))
        }
        (None, Some(tension)) => {
            let mut row = tendon_row(&f, &t, tension, &mut data, &target, &args.stress)?;
            if args.flexure.auto() {
                row["order"] = json!(f.order());
                row["quadrature"] = json!(f.quadrature_points());
            }
            if let Some(map) = row.as_object_mut() {
                map.remove("tension");
            }
            if args.limit {
                let limit = flexure::tendon::stability_limit(&f, &t, tension, MAX_FACTOR)?;
                insert_limit(&mut row, &limit, "tendon --limit");
            }
            Ok(row)
        }
        (None, None) => Err(Error::invalid("tension", "nothing", "give --tension or --sweep")),
    }
}

/// A sweep of one mechanism load: `PARAMETER=F0:F1:COUNT`.
#[derive(Debug, Clone)]
pub struct SweepSpec {
    pub parameter: String,
    pub range: SweepRange,
}

pub fn sweep_spec(s: &str) -> Result<SweepSpec, String> {
    let (parameter, values) = s.split_once('=').ok_or_else(|| format!("{s:?} must be PARAMETER=F0:F1:COUNT"))?;
    Ok(SweepSpec { parameter: parameter.trim().to_string(), range: range(values)? })
}

/// The values of a sweep, ends included.
pub fn sweep_values(s: &SweepRange) -> Vec<f64> {
    (0..s.count).map(|i| s.from + (s.to - s.from) * i as f64 / (s.count - 1) as f64).collect()
}
