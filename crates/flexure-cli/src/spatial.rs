//! `--spatial`: the joint subcommands (deflect, compliance, kinematics) on a
//! spatial flexure, two bendings and a twist in SE(3) (issue 23).
//!
//! The planar options keep their meaning: `--ei` is EI_z, `--kappa` the
//! in-plane rest curvature, `--moment`, `--fx` and `--fy` are M_z, F_x and
//! F_y. `--ei-y`, `--gj`, `--kappa-y`, `--twist`, `--mx`, `--my` and `--fz`
//! add the rest; `--modulus` with `--width --thickness` (a strip) or
//! `--diameter` (a round rod) gives all three stiffnesses, `G` from
//! `--poisson` (0.3 if not given) or `--shear-modulus`.

use crate::answer::{MAX_FACTOR, insert_limit, matrix, warn_unstable};
use crate::joint_options::{DeflectArgs, KinematicsArgs, SpatialOptions};
use crate::options::{FlexureOptions, List, Order, ProfileArg, warn};
use flexure::Error;
use flexure::estimate::{self, Accuracy, ErrorEstimate};
use flexure::reference::rod::{self, Rod};
use flexure::spatial::{self, SpatialFlexure, SpatialLoad, SpatialPoint, SpatialSpec, SpatialStatics, StabilityTest};
use nalgebra::{Matrix3, Vector3};
use serde_json::{Value, json};

/// The spatial flexure the options describe, built by the library
/// ([`SpatialSpec`]); planar-only options are refused by name.
pub fn build(f: &FlexureOptions, s: &SpatialOptions) -> flexure::Result<SpatialFlexure> {
    let planar_only = [
        ("notch", f.notch.is_some()),
        ("quadrature", f.quadrature.is_some()),
        ("density", f.density.is_some()),
        ("mass_per_length", f.mass_per_length.is_some()),
    ];
    if let Some((name, _)) = planar_only.iter().find(|(_, given)| *given) {
        return Err(Error::invalid(name, "given with --spatial", "is for planar flexures only"));
    }
    f.hint_units(s.diameter.as_ref());
    let profile = |p: &Option<ProfileArg>| p.as_ref().map(|p| p.0.clone());
    let list = |l: &Option<List>| l.as_ref().map(|l| l.0.clone());
    let n = match f.order {
        Order::Fixed(n) => n,
        Order::Auto => 3,
    };
    SpatialSpec {
        length: f.length,
        gj: profile(&s.gj),
        ei_y: profile(&s.ei_y),
        ei_z: profile(&f.ei),
        modulus: f.modulus,
        width: profile(&f.width),
        thickness: profile(&f.thickness),
        diameter: profile(&s.diameter),
        poisson: f.poisson,
        shear_modulus: s.shear_modulus,
        orders: [n; 3],
        twist: list(&s.twist),
        kappa_y: list(&s.kappa_y),
        kappa_z: list(&f.kappa),
    }
    .build()
}

/// `pose: {position: [x, y, z], rotation: [[…], […], […]]}`: the rotation's
/// columns are the tip frame's axes in the root frame.
pub fn pose(r: &Matrix3<f64>, p: &Vector3<f64>) -> Value {
    json!({ "position": [p.x, p.y, p.z], "rotation": matrix(r) })
}

/// The coordinates by component.
fn alpha(f: &SpatialFlexure, alpha: &[f64]) -> Value {
    let [a, b, _] = f.orders();
    json!({ "twist": &alpha[..a], "kappa_y": &alpha[a..a + b], "kappa_z": &alpha[a + b..] })
}

/// `error_estimate` and `flagged`, with a warning when it misses `target`.
fn insert_estimate(answer: &mut Value, e: &ErrorEstimate, f: &SpatialFlexure, target: &Accuracy, what: &str) {
    if e.flagged {
        let hint =
            if f.orders().iter().all(|&n| n >= estimate::spatial::MAX_AUTO_ORDER) { "" } else { "; try --order auto" };
        warn(format!("{what}: {}{hint}", crate::answer::misses(e, f.length(), target)));
    }
    answer["error_estimate"] = crate::answer::estimate(e);
    answer["flagged"] = json!(e.flagged);
}

/// The peak stress, with `safety_factor` from `--yield-strength`, for a section with geometry.
fn insert_stress(
    answer: &mut Value,
    f: &SpatialFlexure,
    alpha: &[f64],
    yield_strength: Option<f64>,
    what: &str,
) -> flexure::Result<()> {
    let Ok(p) = spatial::peak_stress(f, alpha) else {
        if let Some(s) = yield_strength {
            return Err(Error::invalid(
                "yield_strength",
                s,
                "needs a section with a shape to give a stress: give --modulus with --width and --thickness, or --diameter",
            ));
        }
        return Ok(());
    };
    answer["stress"] = json!({
        "max": p.stress.von_mises, "at": p.at, "bending_y": p.stress.bending_y,
        "bending_z": p.stress.bending_z, "shear": p.stress.shear, "point": p.stress.at,
    });
    if let Some(s) = yield_strength
        && p.stress.von_mises > 0.0
    {
        let factor = p.stress.safety_factor(s)?;
        answer["safety_factor"] = json!(factor);
        if factor < 1.0 {
            warn(format!(
                "{what}: the peak von Mises stress {:.4e} Pa (at s = {:.4e} m) exceeds the yield strength {s:e} Pa: safety factor {factor:.3}",
                p.stress.von_mises, p.at
            ));
        }
    }
    Ok(())
}

/// `shape: [{s, position, rotation, curvature: {twist, kappa_y, kappa_z}, stress}]`:
/// the deformed flexure at `count` sections evenly spaced in arc length, ends
/// included ([`spatial::shape`]); `stress`, the peak von Mises stress over
/// the section, only for a section with a shape, as the planar `--shape`.
fn shape(f: &SpatialFlexure, alpha: &[f64], count: usize) -> flexure::Result<Value> {
    Ok(points(&spatial::shape(f, alpha, count)?))
}

/// The exact rod's sections at the arc lengths of the model's `shape` (as
/// [`shape`] prints them): each carried from the rod's nearest frame
/// ([`rod::sections`]), its curvature $K^{-1}R^Tm + u^0$ from its moment,
/// and its stress that of the change $K^{-1}R^Tm$.
fn rod_shape(rod: &Rod, load: &SpatialLoad, exact: &rod::RodSolution, model: &Value) -> flexure::Result<Value> {
    let at: Vec<f64> = model.as_array().into_iter().flatten().filter_map(|p| p["s"].as_f64()).collect();
    let (l, section) = (rod.length(), rod.section());
    let sections = rod::sections(rod, load, exact, &at, &Default::default())?;
    let out: Vec<SpatialPoint> = sections
        .iter()
        .map(|q| {
            let t = (q.s / l).clamp(0.0, 1.0);
            let k = section.stiffness(t);
            let body = q.rotation.tr_mul(&q.moment);
            let change: [f64; 3] = std::array::from_fn(|c| body[c] / k[c]);
            let rest = rod.rest_at(q.s);
            SpatialPoint {
                s: q.s,
                position: q.position.into(),
                rotation: std::array::from_fn(|i| std::array::from_fn(|j| q.rotation[(i, j)])),
                curvature: std::array::from_fn(|c| change[c] + rest[c]),
                stress: section.stress(t, change).ok().map(|x| x.von_mises),
            }
        })
        .collect();
    Ok(points(&out))
}

/// Sections as `shape` prints them.
fn points(points: &[SpatialPoint]) -> Value {
    Value::Array(
        points
            .iter()
            .map(|p| {
                let [twist, kappa_y, kappa_z] = p.curvature;
                let mut point = json!({
                    "s": p.s,
                    "position": p.position,
                    "rotation": p.rotation,
                    "curvature": { "twist": twist, "kappa_y": kappa_y, "kappa_z": kappa_z },
                });
                if let Some(sigma) = p.stress {
                    point["stress"] = json!(sigma);
                }
                point
            })
            .collect(),
    )
}

/// `deflect --spatial`.
pub fn deflect(args: &DeflectArgs) -> flexure::Result<Value> {
    if args.input.is_some() {
        return Err(Error::invalid("input", "given with --spatial", "batches are for planar flexures only"));
    }
    let planar = args.load.load();
    let extra = &args.spatial_load;
    let load = SpatialLoad {
        moment: [extra.mx.unwrap_or(0.0), extra.my.unwrap_or(0.0), planar.moment],
        force: [planar.fx, planar.fy, extra.fz.unwrap_or(0.0)],
    };
    let target = args.accuracy.target();
    let given = build(&args.flexure, &args.spatial)?;
    let f = if args.flexure.auto() { estimate::spatial::deflect_auto(&given, &load, &target)?.0 } else { given };
    let settings =
        flexure::Settings { tolerance: args.tolerance, max_iterations: args.max_iterations, ..Default::default() };
    let mut data = SpatialStatics::new(&f);
    let eq = spatial::deflect(&f, &load, &mut data, &settings)?;
    let (r, p) = spatial::pose_root_tip(&f, data.alpha());
    let mut model = json!({
        "alpha": alpha(&f, data.alpha()),
        "pose": pose(&r, &p),
        "stiffness": matrix(&data.stiffness),
        "stable": eq.stable,
        "stability_test": load.stability_test().name(),
        "residual": eq.residual,
    });
    if let Some(limit) = eq.limit.filter(|_| !args.limit) {
        model["limit_fraction"] = json!(limit);
    }
    match load.stability_test() {
        StabilityTest::Energy => warn_unstable(eq.stable, "deflect"),
        StabilityTest::Static if !eq.stable => warn(
            "deflect: the equilibrium is unstable (`stable: false`, `stability_test: static`): a neighbouring equilibrium branched off the loading path (a dead moment has no potential, so this is Euler's static test, not an energy minimum)".into(),
        ),
        StabilityTest::Static => {}
    }
    insert_stress(&mut model, &f, data.alpha(), args.stress.yield_strength, "deflect")?;
    if let Some(k) = args.stress.shape {
        model["shape"] = shape(&f, data.alpha(), k)?;
    }
    if args.flexure.auto() {
        model["orders"] = json!(f.orders());
        model["subintervals"] = json!(f.subintervals());
    }
    let e = estimate::spatial::deflect_error(&f, &load, data.alpha(), &target)?;
    insert_estimate(&mut model, &e, &f, &target, "deflect");
    if args.limit {
        insert_limit(&mut model, &spatial::stability_limit(&f, &load, MAX_FACTOR)?, "deflect --limit");
    }
    if !args.exact {
        return Ok(model);
    }
    let (fl, rest) = (f.clone(), f.rest().to_vec());
    let exact_rod = Rod::new(f.length(), f.section().clone())?.with_rest(move |s| fl.curvature(&rest, s))?;
    let exact = rod::deflect(&exact_rod, &load, &Default::default())?;
    let angle = flexure::space::rotation_angle(&r, &exact.rotation);
    let off = (p - exact.position).norm();
    let exact_shape = match model.get("shape") {
        Some(m) => Some(rod_shape(&exact_rod, &load, &exact, m)?),
        None => None,
    };
    let mut answer = json!({
        "pose": pose(&exact.rotation, &exact.position),
        "root_moment": [exact.root_moment.x, exact.root_moment.y, exact.root_moment.z],
        "stable": exact.stable,
        "stability_test": load.stability_test().name(),
        "model": model,
        "error": {
            "position": off,
            "position_over_length": off / f.length(),
            "angle": angle,
            "angle_degrees": angle.to_degrees(),
        },
    });
    if let Some(sections) = exact_shape {
        answer["shape"] = sections;
    }
    Ok(answer)
}

/// `compliance --spatial`: the 6 × 6 at rest, order (rx, ry, rz, x, y, z);
/// with `--exact` the linearized rod's.
pub fn compliance(flexure: &FlexureOptions, s: &SpatialOptions, exact: bool) -> flexure::Result<Value> {
    let f = build(flexure, s)?;
    let c = if exact {
        let (fl, rest) = (f.clone(), f.rest().to_vec());
        let r = Rod::new(f.length(), f.section().clone())?.with_rest(move |s| fl.curvature(&rest, s))?;
        rod::compliance_rest(&r, &Default::default())?
    } else {
        let mut data = SpatialStatics::new(&f);
        spatial::correct(&f, &SpatialLoad::default(), f.rest(), &mut data, &Default::default())?;
        spatial::compliance(&f, &data)?
    };
    Ok(json!({ "compliance": matrix(&c), "order": ["rx", "ry", "rz", "x", "y", "z"] }))
}

/// `kinematics --spatial`: the tip pose, the body Jacobian (6 × n, rows rx,
/// ry, rz, x, y, z in the tip frame), energy and gradient at α.
pub fn kinematics(args: &KinematicsArgs, s: &SpatialOptions) -> flexure::Result<Value> {
    if args.flexure.auto() {
        return Err(Error::invalid("order", "auto", "kinematics takes coordinates of a given order: give a number"));
    }
    let f = build(&args.flexure, s)?;
    let a = args.alpha.as_ref().map(|a| a.0.clone()).unwrap_or_default();
    f.check_coordinates("alpha", &a)?;
    let mut k = spatial::SpatialKinematics::new(&f);
    spatial::update(&f, &a, flexure::Level::Jacobian, &mut k);
    let mut gradient = vec![0.0; f.coordinates()];
    spatial::energy_gradient(&f, &a, &mut gradient);
    Ok(json!({
        "pose": pose(&k.rotation, &k.position),
        "jacobian": matrix(&k.jacobian),
        "energy": spatial::energy(&f, &a),
        "gradient": gradient,
    }))
}
