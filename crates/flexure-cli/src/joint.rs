//! Subcommands on one flexure joint: kinematics, deflect, compliance,
//! buckling. The first three, planar or with `--spatial`, are one call each
//! of the library's door to one flexure ([`OneFlexure`]).

use crate::answer::{MAX_FACTOR, insert_limit, misses, serialized, warn_unstable};
use crate::joint_options::{BucklingArgs, ComplianceArgs, DeflectArgs, KinematicsArgs, SpatialOptions};
use crate::options::{FlexureOptions, StressOptions, warn};
use flexure::estimate::{Accuracy, ErrorEstimate};
use flexure::model::{Deflect, Deflection, FlexureAnalyses, Headroom, OneFlexure};
use flexure::reference;
use flexure::reference::elastica::Trace;
use flexure::space::Planar;
use flexure::spatial::{SpatialLoad, StabilityTest};
use flexure::{Error, Flexure, Pose, TipConstraint, buckling_load};
use serde_json::{Value, json};

/// Writes `error_estimate` and `flagged` of a planar answer into `answer`,
/// warning on stderr when the estimate misses `target` (`what` names the answer).
pub fn insert_estimate(answer: &mut Value, e: &ErrorEstimate, f: &Flexure, target: &Accuracy, what: &str) {
    warn_missed(e, f.length(), target, Planar::headroom(f, e), what);
    answer["error_estimate"] = serialized(e);
    answer["flagged"] = json!(e.flagged);
}

/// Warns when the estimate `e` of a flexure of `length` misses `target`,
/// with what is left to try (`what` names the answer).
fn warn_missed(e: &ErrorEstimate, length: f64, target: &Accuracy, headroom: Headroom, what: &str) {
    if !e.flagged {
        return;
    }
    let hint = match headroom {
        Headroom::Higher => "; try --order auto".to_string(),
        Headroom::Exhausted { order, against_exact: true } => format!(
            "; even order {order} misses it (estimated against the exact elastica): loosen --accuracy or reduce the load"
        ),
        Headroom::Exhausted { .. } => String::new(),
    };
    warn(format!("{what}: {}{hint}", misses(e, length, target)));
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

/// The flexure the options describe, through the door: planar, or with
/// `--spatial` two bendings and a twist. The planar options keep their
/// meaning in space: `--ei` is EI_z, `--kappa` the in-plane rest
/// curvature; planar-only options are refused by name.
fn one_flexure(f: &FlexureOptions, s: &SpatialOptions) -> flexure::Result<OneFlexure> {
    f.hint_units(s.diameter.as_ref());
    OneFlexure::build(&f.spec(), s.keys().as_ref())
}

/// Pose, Jacobian (in the plane also the transform and Hessians), energy
/// and gradient at α.
pub fn kinematics(args: &KinematicsArgs) -> flexure::Result<Value> {
    args.flexure.fixed("kinematics")?;
    let f = one_flexure(&args.flexure, &args.spatial)?;
    let alpha = args.alpha.as_ref().map(|a| a.0.clone()).unwrap_or_default();
    Ok(serialized(&f.kinematics(&alpha)?))
}

/// Equilibrium under a tip load (Eq. 22), and optionally the exact
/// reference (the elastica, the Kirchhoff rod), with the warnings its
/// answer calls for.
pub fn deflect_cmd(args: &DeflectArgs) -> flexure::Result<Value> {
    let (planar, extra) = (args.load.load(), &args.spatial_load);
    let options = Deflect {
        load: SpatialLoad {
            moment: [extra.mx.unwrap_or(0.0), extra.my.unwrap_or(0.0), planar.moment],
            force: [planar.fx, planar.fy, extra.fz.unwrap_or(0.0)],
        },
        settings: flexure::Settings {
            tolerance: args.tolerance,
            max_iterations: args.max_iterations,
            ..Default::default()
        },
        target: args.accuracy.target(),
        auto: args.flexure.auto(),
        limit: args.limit.then_some(MAX_FACTOR),
        exact: args.exact,
        yield_strength: args.stress.yield_strength,
        shape: args.stress.shape,
    };
    let answer = one_flexure(&args.flexure, &args.spatial)?.deflect(&options)?;
    let model = answer.model();
    match model.stability_test {
        StabilityTest::Static if !model.stable => warn(
            "deflect: the equilibrium is unstable (`stable: false`, `stability_test: static`): a neighbouring equilibrium branched off the loading path (a dead moment has no potential, so this is Euler's static test, not an energy minimum)".into(),
        ),
        _ => warn_unstable(model.stable, "deflect"),
    }
    crate::stress::warn_yield(&model.bending, options.yield_strength, "deflect");
    warn_missed(&model.error_estimate, model.length, &options.target, model.headroom, "deflect");
    let mut out = serialized(&answer);
    if let Some(limit) = &model.stability_limit {
        let at = if args.exact { &mut out["model"] } else { &mut out };
        insert_limit(at, limit, "deflect --limit");
    }
    if let Deflection::Exact(e) = &answer {
        crate::stress::warn_yield(&e.bending, options.yield_strength, "deflect (exact)");
    }
    Ok(out)
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

/// Small-load tip compliance at the rest shape: (φ, x, y) in the plane,
/// (rx, ry, rz, x, y, z) with `--spatial`; with `--exact` the compliance
/// ODE's (Eq. 34, with EI(s)) or the linearized rod's.
pub fn compliance(args: &ComplianceArgs) -> flexure::Result<Value> {
    args.flexure.fixed("compliance")?;
    let f = one_flexure(&args.flexure, &args.spatial)?;
    Ok(serialized(&f.compliance(args.exact)?))
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
        &crate::eigen::EigenKeys { key: "critical_load", one: true, flexures: &[] },
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
