//! Subcommands on one flexure joint: kinematics, deflect, compliance, buckling.

use crate::answer::{MAX_FACTOR, estimate, insert_limit, matrix, misses, serialized, warn_unstable};
use crate::joint_options::{BucklingArgs, ComplianceArgs, DeflectArgs, KinematicsArgs};
use crate::options::{FlexureOptions, StressOptions, warn};
use flexure::Flexure;
use flexure::estimate::{Accuracy, ErrorEstimate};
use flexure::kinematics::TipKinematics;
use flexure::reference::elastica::Trace;
use flexure::reference::{self, elastica};
use flexure::{
    Error, Pose, StaticsData, TipConstraint, buckling_load, compliance_tip_rest, deflect, energy, energy_gradient,
};
use serde_json::{Value, json};

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

/// Equilibrium under a tip load (Eq. 22), and optionally the exact elastica.
pub fn deflect_cmd(args: &DeflectArgs) -> flexure::Result<Value> {
    if args.spatial.spatial {
        return crate::spatial::deflect(args);
    }
    let load = args.load.load();
    let target = args.accuracy.target();
    let f = chosen(&args.flexure, |f| Ok(flexure::estimate::deflect_auto(f, &load, &target)?.0))?;
    crate::stress::check(&f, &args.stress)?;
    let mut data = StaticsData::new(&f);
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
