//! Subcommands on mechanism files: solve, buckle, draw.

use crate::analyses::{SweepSpec, sweep_values};
use crate::options::number;
use clap::Args;
use flexure::estimate::{Accuracy, ErrorEstimate, joint_error};
use flexure::mechanism::file::{Report, from_toml, reports};
use flexure::mechanism::statics::{Settings, Solution, body_frames, compliance, solve};
use flexure::mechanism::sweep::{Parameter, StabilityLimit, Sweep, sweep};
use flexure::mechanism::{JointKind, Mechanism};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

fn load(path: &Path) -> Result<Mechanism, String> {
    let text = crate::input::read_text(path, "")?;
    from_toml(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The mechanism, and each flexure joint's `yield_strength` and `shape`.
fn load_with_reports(path: &Path) -> Result<(Mechanism, Vec<(String, Report)>), String> {
    let text = crate::input::read_text(path, "")?;
    let m = from_toml(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let reports = reports(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((m, reports))
}

/// Each flexure joint of `m` with its coordinates in `s` and its report keys.
fn flexures<'a>(
    m: &'a Mechanism,
    s: &'a Solution,
    reports: &'a [(String, Report)],
) -> impl Iterator<Item = (&'a str, &'a flexure::Flexure, &'a [f64], Report)> {
    m.joints.iter().filter_map(move |j| match &j.kind {
        JointKind::Flexure(f) => {
            let r = reports.iter().find(|r| r.0 == j.name).map_or_else(Report::default, |r| r.1);
            Some((j.name.as_str(), &**f, &s.q[j.offset..j.offset + f.order()], r))
        }
        _ => None,
    })
}

/// Per flexure joint, by name: `stress` {max, at} (or `curvature_max` for
/// one given by ei alone), `safety_factor` with a `yield_strength`, and
/// `shape` with a `shape` key; each map left out when empty.
fn put_flexure_stress(v: &mut Value, m: &Mechanism, s: &Solution, reports: &[(String, Report)], file: &Path) {
    let mut maps: [(&str, serde_json::Map<String, Value>); 4] =
        ["stress", "curvature_max", "safety_factor", "shape"].map(|k| (k, serde_json::Map::new()));
    for (name, f, q, r) in flexures(m, s, reports) {
        let mut one = json!({});
        let what = format!("{}: flexure joint {name:?}", file.display());
        crate::stress::peak(&mut one, f, q, r.yield_strength, &what);
        if let Some(k) = r.shape {
            one["shape"] = crate::stress::shape(f, q, k);
        }
        for (key, map) in &mut maps {
            if let Some(x) = one.get(*key) {
                map.insert(name.to_string(), x.clone());
            }
        }
    }
    for (key, map) in maps {
        if !map.is_empty() {
            v[key] = Value::Object(map);
        }
    }
}

/// A point `X,Y`.
pub fn point_arg(s: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 2 {
        return Err(format!("{s:?} must be two values X,Y"));
    }
    Ok([number(parts[0])?, number(parts[1])?])
}

#[derive(Debug, Args)]
pub struct SolveArgs {
    /// Mechanism file (TOML).
    file: PathBuf,
    /// Report the compliance of a frame on this body…
    #[arg(long, requires = "at")]
    compliance: Option<String>,
    /// …at this point X,Y of the body's frame (m).
    #[arg(long, value_parser = point_arg, allow_hyphen_values = true, requires = "compliance")]
    at: Option<[f64; 2]>,
    /// Sweep one load, e.g. tendon.flexor.tension=0:30:31 (or force.NAME.fx|fy|moment, gravity.x|y):
    /// a table with one row per value reached stably, then `stability_limit` (value, fraction) if
    /// stability is lost between two values (found by bisection; a warning on stderr, exit 0).
    #[arg(long, value_parser = crate::analyses::sweep_spec, allow_hyphen_values = true)]
    sweep: Option<SweepSpec>,
    #[command(flatten)]
    accuracy: crate::options::AccuracyOptions,
}

fn solution_json(m: &Mechanism, s: &Solution) -> Value {
    let f = body_frames(m, s);
    let bodies: serde_json::Map<String, Value> = m
        .bodies
        .iter()
        .zip(&f.bodies)
        .map(|(b, fr)| (b.name.clone(), json!({ "x": fr.origin[0], "y": fr.origin[1], "phi": fr.angle })))
        .collect();
    let coordinates: serde_json::Map<String, Value> =
        m.joints.iter().map(|j| (j.name.clone(), json!(s.q[j.offset..j.offset + j.kind.joint().dof()]))).collect();
    json!({ "bodies": bodies, "coordinates": coordinates, "energy": s.energy, "stable": s.stable })
}

/// The error estimate of every flexure joint at `s`, in joint order: the
/// joint under the tip load it carries, against the refined model. A
/// failure names the joint and the file, and says it was the estimate's
/// own solve that failed (not the mechanism's).
fn joint_estimates(
    m: &Mechanism,
    s: &Solution,
    target: &Accuracy,
    file: &Path,
) -> Result<Vec<(&'static str, String, ErrorEstimate, f64)>, String> {
    let mut out = Vec::new();
    for j in &m.joints {
        if let JointKind::Flexure(fl) = &j.kind {
            let e = joint_error(fl, &s.q[j.offset..j.offset + fl.order()], target).map_err(|e| {
                format!(
                    "{}: flexure joint {:?}: its error estimate (the joint alone under the tip load it carries, against the refined model) failed: {e}",
                    file.display(),
                    j.name
                )
            })?;
            out.push(("flexure joint", j.name.clone(), e, fl.length()));
        }
    }
    Ok(out)
}

/// `error_estimate` {joint: {position, angle}} and `flagged` for a solution, warning per flagged joint.
fn put_joint_estimates(
    v: &mut Value,
    m: &Mechanism,
    s: &Solution,
    target: &Accuracy,
    file: &Path,
) -> Result<(), String> {
    let estimates = joint_estimates(m, s, target, file)?;
    let mut map = serde_json::Map::new();
    for (what, name, e, length) in &estimates {
        if e.flagged {
            crate::options::warn(format!(
                "{}: {what} {name:?}: {}; raise its order",
                file.display(),
                crate::joint::misses(e, *length, target),
            ));
        }
        let mut entry = json!({ "position": e.position, "angle": e.angle, "curvature": e.curvature });
        if let Some(stress) = e.stress {
            entry["stress"] = json!(stress);
        }
        map.insert(name.clone(), entry);
    }
    v["error_estimate"] = Value::Object(map);
    v["flagged"] = json!(estimates.iter().any(|e| e.2.flagged));
    Ok(())
}

/// A sweep as a table: the column names, then one row of numbers per
/// value: the value, each moving body's x, y, phi, each joint coordinate,
/// the energy, and the compliance entries if asked for.
fn sweep_table(m: &Mechanism, parameter: &str, with_compliance: bool) -> Vec<String> {
    let mut columns = vec![parameter.to_string()];
    for b in &m.bodies[1..] {
        columns.extend(["x", "y", "phi"].map(|c| format!("{}.{c}", b.name)));
    }
    for j in &m.joints {
        columns.extend((0..j.kind.joint().dof()).map(|i| format!("{}[{i}]", j.name)));
    }
    columns.push("energy".into());
    // The peak stress of each flexure joint that has a thickness (Pa).
    for j in &m.joints {
        if let JointKind::Flexure(f) = &j.kind
            && f.section().modulus().is_some()
        {
            columns.push(format!("{}.stress", j.name));
        }
    }
    if with_compliance {
        let axes = ["phi", "x", "y"];
        columns.extend(axes.iter().flat_map(|r| axes.iter().map(move |c| format!("compliance.{r}{c}"))));
    }
    columns
}

fn sweep_row(m: &Mechanism, value: f64, s: &Solution, compliance: Option<&nalgebra::Matrix3<f64>>) -> Vec<f64> {
    let f = body_frames(m, s);
    let mut row = vec![value];
    row.extend(f.bodies[1..].iter().flat_map(|b| [b.origin[0], b.origin[1], b.angle]));
    row.extend(&s.q);
    row.push(s.energy);
    for j in &m.joints {
        if let JointKind::Flexure(f) = &j.kind
            && let Some(p) = flexure::stress::peak_stress(f, &s.q[j.offset..j.offset + f.order()])
        {
            row.push(p.value);
        }
    }
    if let Some(c) = compliance {
        row.extend((0..3).flat_map(|i| (0..3).map(move |j| c[(i, j)])));
    }
    row
}

fn limit_json(l: &StabilityLimit) -> Value {
    json!({ "value": l.value, "fraction": l.fraction })
}

/// The warning for a sweep that lost stability, or `None`.
fn sweep_warning(file: &Path, parameter: &str, out: &Sweep, values: &[f64]) -> Option<String> {
    let l = out.stability_limit?;
    let beyond = match values.len() - out.rows.len() {
        0 => "the path snapped through to stable states beyond it".to_string(),
        1 => "the last value has no stable equilibrium reachable by loading and is not printed".to_string(),
        k => format!("the last {k} values have no stable equilibrium reachable by loading and are not printed"),
    };
    // Seven significant digits: the limit is found to a relative 1e-6.
    let magnitude = if l.value != 0.0 { l.value.abs().log10().floor().clamp(-300.0, 300.0) as i64 } else { 0 };
    let digits = (6 - magnitude).clamp(0, 17) as usize;
    Some(format!(
        "{}: stability is lost at {parameter} = {:.*} ({:.4} % along the sweep); {beyond}",
        file.display(),
        digits,
        l.value,
        100.0 * l.fraction
    ))
}

/// The checks `solve` makes of one solution, shared by `draw`: closures
/// open at rest and parts that cross (`findings`), each flexure joint's
/// estimate (a warning per flagged joint), its stress (a warning past its
/// yield strength), a snap-through on the way, and an unstable answer.
fn put_solution_checks(
    v: &mut Value,
    m: &Mechanism,
    s: &Solution,
    reports: &[(String, Report)],
    target: &Accuracy,
    file: &Path,
) -> Result<(), String> {
    let mut findings = crate::findings::closures(m, file)?;
    findings.extend(crate::findings::shape(m, &s.q, file));
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    put_joint_estimates(v, m, s, target, file)?;
    put_flexure_stress(v, m, s, reports, file);
    if let Some(limit) = s.limit {
        v["limit_fraction"] = json!(limit);
        crate::options::warn(format!(
            "{}: the loading path lost stability at {:.4} % of the load and snapped through to this stable equilibrium",
            file.display(),
            100.0 * limit
        ));
    }
    if !s.stable {
        crate::options::warn(format!(
            "{}: the equilibrium is unstable (`stable: false`): its constrained stiffness is not positive definite, so a small disturbance moves it away",
            file.display()
        ));
    }
    Ok(())
}

/// The checks `solve --sweep` makes of a sweep, shared by `draw --sweep`:
/// closures open at rest and rows whose parts cross (`findings`), where
/// stability is lost, the rows whose estimate is flagged, the first row past
/// each yield strength, and a sweep that stopped (`stopped`, which makes the
/// command exit 2 after printing its rows).
fn put_sweep_checks(
    v: &mut Value,
    m: &Mechanism,
    out: &Sweep,
    reports: &[(String, Report)],
    (target, file): (&Accuracy, &Path),
    (parameter, values): (&str, &[f64]),
) -> Result<(), String> {
    let mut findings = crate::findings::closures(m, file)?;
    let shapes: Vec<(f64, &[f64])> = out.rows.iter().map(|(v, s)| (*v, s.q.as_slice())).collect();
    findings.extend(crate::findings::along(m, &shapes, (parameter, "swept values"), "value", file));
    if !findings.is_empty() {
        v["findings"] = json!(findings);
    }
    if let Some(l) = &out.stability_limit {
        v["stability_limit"] = limit_json(l);
    }
    if let Some(w) = sweep_warning(file, parameter, out, values) {
        crate::options::warn(w);
    }
    let mut flagged = Vec::new();
    for (value, s) in &out.rows {
        if joint_estimates(m, s, target, file)?.iter().any(|e| e.2.flagged) {
            flagged.push(*value);
        }
    }
    if !flagged.is_empty() {
        v["flagged"] = json!(flagged);
        crate::options::warn(format!(
            "{}: at {} of the swept values a flexure joint's estimated error exceeds the accuracy target (listed in `flagged`); raise its order",
            file.display(),
            flagged.len()
        ));
    }
    for (k, r) in reports.iter().enumerate() {
        let Some(strength) = r.1.yield_strength else { continue };
        let over = out.rows.iter().find_map(|(value, s)| {
            let (_, f, q, _) = flexures(m, s, reports).nth(k)?;
            let p = flexure::stress::peak_stress(f, q)?;
            (p.value > strength).then_some((*value, p.value))
        });
        if let Some((value, sigma)) = over {
            crate::options::warn(format!(
                "{}: flexure joint {:?}: from {parameter} = {value} on, the peak bending stress ({sigma:.4e} Pa there) exceeds the yield strength {strength:e} Pa (column {}.stress)",
                file.display(),
                r.0,
                r.0
            ));
        }
    }
    if let Some((value, e)) = &out.stopped {
        let error = format!(
            "{}: the sweep stopped at {parameter} = {value} after {} of {} values (each printed above): {e}",
            file.display(),
            out.rows.len(),
            values.len()
        );
        v["stopped"] = json!({ "value": value, "error": error });
    }
    Ok(())
}

/// Equilibrium of a mechanism file, optionally with a compliance or a sweep.
pub fn solve_cmd(args: &SolveArgs) -> Result<Value, String> {
    let (m, reports) = load_with_reports(&args.file)?;
    let settings = Settings::default();
    let target = args.accuracy.target();
    let err = |e: flexure::Error| format!("{}: {e}", args.file.display());
    let body = match &args.compliance {
        Some(name) => Some(
            m.body(name).ok_or_else(|| format!("--compliance: no body named {name:?} in {}", args.file.display()))?,
        ),
        None => None,
    };
    let compliance_at = body.zip(args.at);
    match &args.sweep {
        Some(spec) => {
            let p = Parameter::parse(&m, &spec.parameter).map_err(crate::describe)?;
            let values = sweep_values(&spec.range);
            let out = sweep(&m, &p, &values, &settings).map_err(err)?;
            let rows: Vec<Value> = out
                .rows
                .iter()
                .map(|(v, s)| {
                    let c = compliance_at.map(|(b, at)| compliance(&m, s, b, at)).transpose().map_err(err)?;
                    Ok(json!(sweep_row(&m, *v, s, c.as_ref())))
                })
                .collect::<Result<_, String>>()?;
            let mut v = json!({
                "columns": sweep_table(&m, &spec.parameter, compliance_at.is_some()),
                "rows": rows,
            });
            put_sweep_checks(&mut v, &m, &out, &reports, (&target, &args.file), (&spec.parameter, &values))?;
            Ok(v)
        }
        None => {
            let s = solve(&m, &settings).map_err(err)?;
            let mut v = solution_json(&m, &s);
            if let Some((b, at)) = compliance_at {
                v["compliance"] = crate::joint::matrix(&compliance(&m, &s, b, at).map_err(err)?);
            }
            put_solution_checks(&mut v, &m, &s, &reports, &target, &args.file)?;
            Ok(v)
        }
    }
}

#[derive(Debug, Args)]
pub struct BuckleArgs {
    /// Mechanism file (TOML).
    file: PathBuf,
    #[command(flatten)]
    accuracy: crate::eigen::EigenAccuracyOptions,
}

/// The flexure joints' names, in joint order (the order of the library's
/// per-flexure lists, such as an estimate's reference orders).
pub fn flexure_names(m: &Mechanism) -> Vec<String> {
    m.joints.iter().filter(|j| matches!(j.kind, JointKind::Flexure(_))).map(|j| j.name.clone()).collect()
}

/// {joint: order} of the flexure joints.
pub fn flexure_orders(m: &Mechanism) -> Value {
    Value::Object(
        m.joints
            .iter()
            .filter_map(|j| match &j.kind {
                JointKind::Flexure(f) => Some((j.name.clone(), json!(f.order()))),
                _ => None,
            })
            .collect(),
    )
}

/// Linear buckling factor on all loads, and the mode, with its error
/// estimate; flexures of `order = "auto"` raised until it meets the target.
pub fn buckle_cmd(args: &BuckleArgs) -> Result<Value, String> {
    let m = load(&args.file)?;
    // Buckling about a preloaded assembly: the preload is told.
    let findings = crate::findings::closures(&m, &args.file)?;
    let target = args.accuracy.target();
    let (m, b, e) = flexure::estimate::buckle_auto(&m, &Settings::default(), &target)
        .map_err(|e| format!("{}: {e}", args.file.display()))?;
    let mut answer = json!({ "load_factor": b.load_factor, "mode": b.mode });
    let flexures = flexure_names(&m);
    let auto = m.joints.iter().any(|j| j.auto_order);
    if auto {
        answer["order"] = flexure_orders(&m);
    }
    crate::eigen::put(&mut answer, &e, &crate::eigen::Shape { key: "load_factor", one: true, flexures: &flexures });
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

#[derive(Debug, Args)]
pub struct DrawArgs {
    /// Mechanism file (TOML).
    file: PathBuf,
    /// SVG to write.
    #[arg(long)]
    out: PathBuf,
    /// Draw a loaded shape for each value of one load, e.g. tendon.flexor.tension=0:30:4.
    #[arg(long, value_parser = crate::analyses::sweep_spec, allow_hyphen_values = true)]
    sweep: Option<SweepSpec>,
    /// Simulate the motion over T seconds (as `flexure simulate`): draw five snapshots from 0 to T,
    /// and under them the bodies' angles and positions against time.
    #[arg(long, value_name = "T", value_parser = number, allow_hyphen_values = true, conflicts_with = "sweep")]
    simulate: Option<f64>,
    #[command(flatten)]
    motion: crate::simulate::MotionOptions,
    #[command(flatten)]
    accuracy: crate::options::AccuracyOptions,
}

/// An SVG of the unloaded and loaded shapes, to one scale on both axes,
/// with the warnings `solve` gives on the same file.
pub fn draw_cmd(args: &DrawArgs) -> Result<Value, String> {
    if let Some(duration) = args.simulate {
        return draw_motion(args, duration);
    }
    let (m, reports) = load_with_reports(&args.file)?;
    let settings = Settings::default();
    let target = args.accuracy.target();
    let err = |e: flexure::Error| format!("{}: {e}", args.file.display());
    let unloaded = flexure::mechanism::statics::assemble_unloaded(&m, &settings).map_err(err)?;
    let mut marks = drawing::Marks {
        yields: reports.iter().filter_map(|(name, r)| Some((name.clone(), r.yield_strength?))).collect(),
        limit: None,
    };
    // The checks' warnings are solve's; of their answer, draw keeps only the verdicts.
    let mut checks = json!({});
    let loaded: Vec<(String, Solution)> = match &args.sweep {
        Some(spec) => {
            let p = Parameter::parse(&m, &spec.parameter).map_err(crate::describe)?;
            let values = sweep_values(&spec.range);
            let out = sweep(&m, &p, &values, &settings).map_err(err)?;
            put_sweep_checks(&mut checks, &m, &out, &reports, (&target, &args.file), (&spec.parameter, &values))?;
            // Shapes past the limit (on its far side from the first value) are labelled so.
            let past =
                |value: f64| out.stability_limit.is_some_and(|l| (value - l.value) * (values[0] - l.value) < 0.0);
            marks.limit = out.stability_limit.map(|l| {
                let shapes = match out.rows.iter().filter(|(value, _)| past(*value)).count() {
                    0 => "no shape is drawn past it",
                    1 => "the last shape is past it, reached by snap-through",
                    _ => "the shapes marked past it were reached by snap-through",
                };
                format!("stability lost at {} = {}: {shapes}", spec.parameter, drawing::short(l.value))
            });
            let label = |v: f64| match past(v) {
                true => format!("{} (past the stability limit)", drawing::swept(&spec.parameter, v)),
                false => drawing::swept(&spec.parameter, v),
            };
            out.rows.iter().map(|(v, s)| (label(*v), s.clone())).collect()
        }
        None => {
            let s = solve(&m, &settings).map_err(err)?;
            put_solution_checks(&mut checks, &m, &s, &reports, &target, &args.file)?;
            vec![("loaded".into(), s)]
        }
    };
    let title = args.file.file_name().map_or("mechanism".into(), |n| n.to_string_lossy().into_owned());
    let (figure, per_newton) = drawing::figure(&m, &title, &unloaded, &loaded, &marks);
    crate::figures::write(&args.out, &figure)?;
    let mut v = json!({ "out": args.out.display().to_string(), "shapes": loaded.len() + 1 });
    for key in ["findings", "flagged", "limit_fraction", "stability_limit", "stopped"] {
        if let Some(x) = checks.get(key) {
            v[key] = x.clone();
        }
    }
    if let Some(k) = per_newton {
        v["force_scale_m_per_n"] = json!(k);
    }
    Ok(v)
}

/// Snapshots of a simulated motion over the rest shape, then the bodies'
/// angles and positions against time, as one SVG.
fn draw_motion(args: &DrawArgs, duration: f64) -> Result<Value, String> {
    use crate::figures::{COLORS, Chart, Dash, Series, chart_figure, write_stack};
    let (m, run) = crate::simulate::run_motion(&args.file, (duration, "--simulate"), &args.motion)?;
    // simulate's warnings; of its answer, draw keeps the findings.
    let mut checks = json!({});
    crate::simulate::put_motion_checks(&mut checks, &m, &run, &args.file)?;
    crate::simulate::put_stopped(&mut checks, &run, &args.file, duration);
    let err = |e: flexure::Error| format!("{}: {e}", args.file.display());
    let unloaded = flexure::mechanism::statics::assemble_unloaded(&m, &Settings::default()).map_err(err)?;
    let last = run.time.len() - 1;
    let mut picked: Vec<usize> = (0..5).map(|k| (k * last + 2) / 4).collect();
    picked.dedup();
    let snapshots: Vec<(String, Solution)> = picked
        .iter()
        .map(|&k| {
            let t = run.time[k];
            let s = Solution {
                q: run.q(k).to_vec(),
                multipliers: Vec::new(),
                loads: flexure::dynamics::schedule::loads_at(&m, t),
                energy: run.energy[k],
                stable: true,
                limit: None,
                residual: 0.0,
                load_steps: 0,
                iterations: 0,
            };
            (format!("t = {} s", drawing::short(t)), s)
        })
        .collect();
    let title = args.file.file_name().map_or("mechanism".into(), |n| n.to_string_lossy().into_owned());
    let (shapes, per_newton) = drawing::figure(
        &m,
        &format!("{title}: motion over {} s", drawing::short(duration)),
        &unloaded,
        &snapshots,
        &drawing::Marks::default(),
    );
    // Each body by colour; x solid, y dashed.
    let color = |i: usize| COLORS[i % COLORS.len()];
    let along =
        |v: &[f64], scale: f64| -> Vec<(f64, f64)> { run.time.iter().zip(v).map(|(t, x)| (*t, x * scale)).collect() };
    let angles: Vec<Series> = run
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| Series::line(&format!("{} φ", b.name), along(&b.phi, 1.0), color(i)))
        .collect();
    let positions: Vec<Series> = run
        .bodies
        .iter()
        .enumerate()
        .flat_map(|(i, b)| {
            [
                Series::line(&format!("{} x", b.name), along(&b.x, 1e3), color(i)),
                Series::line(&format!("{} y", b.name), along(&b.y, 1e3), color(i)).dashed(Dash::Dashed),
            ]
        })
        .collect();
    let chart = |title: &'static str, y: &'static str| Chart {
        title,
        x_label: "time (s)",
        y_label: y,
        log_y: false,
        equal_aspect: false,
    };
    let mut figures = vec![shapes];
    for (c, series) in [
        (chart("Body angles", "φ (rad), ground frame"), angles),
        (chart("Body origins", "x, y (mm), ground frame"), positions),
    ] {
        let mut fig = chart_figure(&c, &series)
            .map_err(|e| format!("drawing {}: {e}; nothing was written", args.out.display()))?;
        fig.width = 1200.0;
        fig.height = 420.0;
        fig.place = crate::figures::Place::Outside;
        figures.push(fig);
    }
    write_stack(&args.out, &figures)?;
    let mut v = json!({
        "out": args.out.display().to_string(),
        "shapes": snapshots.len() + 1,
        "snapshots": picked.iter().map(|&k| run.time[k]).collect::<Vec<_>>(),
        "steps": run.steps,
        "rejected": run.rejected,
    });
    if let Some(k) = per_newton {
        v["force_scale_m_per_n"] = json!(k);
    }
    for key in ["findings", "stopped"] {
        if let Some(x) = checks.get(key) {
            v[key] = x.clone();
        }
    }
    Ok(v)
}

/// `flexure draw`: a mechanism's shapes as one figure. Each shape has its
/// colour: its rigid links are filled hulls of every point attached to
/// them, its flexures thick curves, its tendons thin lines through marked
/// via points, its loads arrows (forces, weights, drawn to a stated scale)
/// and turning arrows (moments).
mod drawing {
    use crate::figures::{
        Anchor, COLORS, Color, ColorBar, Dash, Entry, Figure, Fill, GRAY, Mark, Marker, Place, Stroke, Swatch, ramp,
    };
    use flexure::kinematics::backbone;
    use flexure::mechanism::statics::{Solution, body_frames};
    use flexure::mechanism::{Closure, JointKind, Mechanism};
    use std::f64::consts::TAU;

    /// The colour of legend keys that stand for every shape.
    const KEY: Color = Color(60, 60, 60);
    const GROUND: Color = Color(90, 90, 90);
    /// The loaded shapes' colours, in order.
    const SHAPES: [Color; 5] = [COLORS[0], COLORS[2], COLORS[3], COLORS[1], COLORS[4]];
    /// Tendons are told apart by dash and via-point marker, not colour.
    const TENDON_DASH: [Dash; 3] = [Dash::Solid, Dash::Dashed, Dash::Chain];
    const VIA: [Marker; 4] = [Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond];
    const FLEXURE_WIDTH: f64 = 5.0;

    /// `x` to four significant digits, without trailing zeros, with a true minus sign.
    pub fn short(x: f64) -> String {
        if x == 0.0 {
            return "0".into();
        }
        let magnitude = x.abs().log10().floor();
        let text = if (-3.0..5.0).contains(&magnitude) {
            let t = format!("{x:.*}", (3.0 - magnitude).max(0.0) as usize);
            if t.contains('.') { t.trim_end_matches('0').trim_end_matches('.').to_string() } else { t }
        } else {
            format!("{x:.3e}")
        };
        text.replace('-', "−")
    }

    /// The unit of a swept parameter (`tendon.NAME.tension`, `force.NAME.fx|fy|moment`, `gravity.x|y`).
    fn unit(parameter: &str) -> &'static str {
        if parameter.ends_with(".moment") {
            "N·m"
        } else if parameter.starts_with("gravity.") {
            "m/s²"
        } else {
            "N"
        }
    }

    /// A swept shape's name: `tendon.flexor.tension = 4 N`.
    pub fn swept(parameter: &str, value: f64) -> String {
        format!("{parameter} = {} {}", short(value), unit(parameter))
    }

    /// Every point attached to body `b`, in its frame ([`Mechanism::attachments`]:
    /// the library's crossing test takes the same points as the link).
    pub(super) fn attachments(m: &Mechanism, b: usize) -> Vec<[f64; 2]> {
        m.attachments(b)
    }

    /// The convex hull, counter-clockwise: the library's, which the crossing test uses.
    pub(super) fn hull(p: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
        let points = p.into_iter().map(|(x, y)| [x, y]).collect();
        flexure::mechanism::findings::hull(points).into_iter().map(|[x, y]| (x, y)).collect()
    }

    /// A rigid link: the hull of its points grown by `r`, so that two
    /// points make a bar and one a disc.
    pub(super) fn slab(pts: &[[f64; 2]], r: f64) -> Vec<(f64, f64)> {
        let round = (0..16).map(|k| TAU * f64::from(k) / 16.0).map(|a| (r * a.cos(), r * a.sin()));
        hull(pts.iter().flat_map(|p| round.clone().map(move |d| (p[0] + d.0, p[1] + d.1))).collect())
    }

    /// The largest 1, 2 or 5 × 10ᵏ not above `x`.
    fn round_down(x: f64) -> f64 {
        let base = 10f64.powf(x.log10().floor());
        [5.0, 2.0, 1.0].into_iter().map(|m| m * base).find(|s| *s <= x * (1.0 + 1e-9)).unwrap_or(base)
    }

    /// The forces (N) a solution applies: each point load's, then each weight's.
    fn force_vectors(m: &Mechanism, s: &Solution) -> Vec<[f64; 2]> {
        let g = s.loads.gravity;
        let weights = m.bodies.iter().filter(|b| b.mass > 0.0).map(|b| [b.mass * g[0], b.mass * g[1]]);
        s.loads.force.iter().map(|l| [l[0], l[1]]).chain(weights).collect()
    }

    /// How a load reads in the legend: one value, or the range over the shapes.
    fn values(v: &[f64], unit: &str) -> String {
        let (lo, hi) = v.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        if v.is_empty() || lo == hi {
            format!("{} {unit}", short(v.first().copied().unwrap_or(0.0)))
        } else {
            format!("{} to {} {unit}", short(lo), short(hi))
        }
    }

    /// How a shape's loads are drawn: not at all (the unloaded shape), or
    /// with force arrows `per_newton` m long per N (none if no force acts).
    #[derive(Clone, Copy)]
    enum Loads {
        Hidden,
        /// `stress_top`: the stress (Pa) at the top of the colour bar, when
        /// flexures with a thickness are coloured by their stress.
        Drawn {
            per_newton: Option<f64>,
            stress_top: Option<f64>,
        },
    }

    /// Points along each drawn flexure.
    const FLEXURE_SAMPLES: usize = 41;

    /// The largest bending stress (Pa) of any flexure with a thickness in
    /// any of the shapes, or `None` if no flexure has a thickness.
    pub fn stress_max(m: &Mechanism, shapes: &[(String, Solution)]) -> Option<f64> {
        let mut top = None;
        for (_, s) in shapes {
            for j in &m.joints {
                if let JointKind::Flexure(fl) = &j.kind
                    && let Some(p) = flexure::stress::peak_stress(fl, &s.q[j.offset..j.offset + fl.order()])
                {
                    top = Some(p.value.max(top.unwrap_or(0.0)));
                }
            }
        }
        top
    }

    /// One shape's marks.
    fn shape(fig: &mut Figure, m: &Mechanism, s: &Solution, color: Color, thick: f64, loads: Loads) {
        let f = body_frames(m, s);
        let at = |b: usize, r: [f64; 2]| {
            let p = f.bodies[b].point(r);
            (p[0], p[1])
        };
        for b in 1..m.bodies.len() {
            let pts: Vec<[f64; 2]> = attachments(m, b).iter().map(|&r| f.bodies[b].point(r)).collect();
            fig.marks.push(Mark::Path {
                points: slab(&pts, thick),
                stroke: Some(Stroke::solid(color, 1.5)),
                fill: Some(Fill { color: color.tint(0.55), opacity: 0.55 }),
                closed: true,
            });
        }
        for (ji, j) in m.joints.iter().enumerate() {
            let root = f.roots[ji];
            let origin = (root.origin[0], root.origin[1]);
            match &j.kind {
                JointKind::Flexure(fl) => {
                    let q = &s.q[j.offset..j.offset + fl.order()];
                    let points: Vec<(f64, f64)> = backbone(fl, q, FLEXURE_SAMPLES)
                        .iter()
                        .map(|p| root.point([p.x, p.y]))
                        .map(|p| (p[0], p[1]))
                        .collect();
                    let top = match loads {
                        Loads::Drawn { stress_top: Some(top), .. } if fl.section().modulus().is_some() => top,
                        _ => {
                            let stroke = Some(Stroke::solid(color, FLEXURE_WIDTH));
                            fig.marks.push(Mark::Path { points, stroke, fill: None, closed: false });
                            continue;
                        }
                    };
                    // Each piece in the colour of its mean stress.
                    let ds = fl.length() / (FLEXURE_SAMPLES - 1) as f64;
                    let sigma = |i: usize| flexure::stress::stress(fl, q, i as f64 * ds).unwrap_or(0.0);
                    for (i, pair) in points.windows(2).enumerate() {
                        let stroke = Some(Stroke::solid(ramp(0.5 * (sigma(i) + sigma(i + 1)) / top), FLEXURE_WIDTH));
                        fig.marks.push(Mark::Path { points: pair.to_vec(), stroke, fill: None, closed: false });
                    }
                }
                JointKind::Revolute(_) => {
                    fig.marks.push(Mark::Dot { at: origin, shape: Marker::Circle, radius: 6.0, color, filled: false });
                }
                JointKind::Prismatic(_) => {
                    let points = vec![origin, at(j.child, [0.0, 0.0])];
                    let stroke = Some(Stroke { color, width: 2.0, dash: Dash::Dashed });
                    fig.marks.push(Mark::Path { points, stroke, fill: None, closed: false });
                    fig.marks.push(Mark::Dot { at: origin, shape: Marker::Square, radius: 6.0, color, filled: false });
                }
                JointKind::Fixed(_) => {}
            }
        }
        for c in &m.closures {
            if let Closure::Pin { a, a_at, .. } = c {
                fig.marks.push(Mark::Dot {
                    at: at(*a, *a_at),
                    shape: Marker::Circle,
                    radius: 5.0,
                    color,
                    filled: false,
                });
            }
        }
        for (k, t) in m.tendons.iter().enumerate() {
            let points: Vec<(f64, f64)> = t.path.iter().map(|&(b, r)| at(b, r)).collect();
            for &p in &points {
                fig.marks.push(Mark::Dot { at: p, shape: VIA[k % VIA.len()], radius: 4.0, color, filled: false });
            }
            let stroke = Some(Stroke { color, width: 1.5, dash: TENDON_DASH[k % TENDON_DASH.len()] });
            fig.marks.push(Mark::Path { points, stroke, fill: None, closed: false });
        }
        let Loads::Drawn { per_newton, .. } = loads else { return };
        for ((b, r), v) in load_places(m).into_iter().zip(force_vectors(m, s)) {
            let from = at(b, r);
            if let (Some(k), true) = (per_newton, v != [0.0, 0.0]) {
                let to = (from.0 + k * v[0], from.1 + k * v[1]);
                fig.marks.push(Mark::Arrow { from, to, color, width: 2.5 });
            }
        }
        for (p, l) in m.forces.iter().zip(&s.loads.force) {
            if l[2] != 0.0 {
                fig.marks.push(Mark::Turn { at: at(p.body, p.at), radius: 18.0, ccw: l[2] > 0.0, color, width: 2.0 });
            }
        }
    }

    /// Where each load of [`force_vectors`] acts: (body, point in its frame).
    fn load_places(m: &Mechanism) -> Vec<(usize, [f64; 2])> {
        let heavy = m.bodies.iter().enumerate().filter(|(_, b)| b.mass > 0.0).map(|(i, b)| (i, b.com));
        m.forces.iter().map(|p| (p.body, p.at)).chain(heavy).collect()
    }

    /// Names beside the last shape's loads: past a force's head, beside a moment's turn.
    fn load_names(fig: &mut Figure, m: &Mechanism, s: &Solution, color: Color, per_newton: Option<f64>) {
        let f = body_frames(m, s);
        let names = m
            .forces
            .iter()
            .map(|p| p.name.clone())
            .chain(m.bodies.iter().filter(|b| b.mass > 0.0).map(|b| format!("weight of {}", b.name)));
        let moments = s.loads.force.iter().map(|l| l[2]).chain(std::iter::repeat(0.0));
        for ((((b, r), name), v), moment) in load_places(m).into_iter().zip(names).zip(force_vectors(m, s)).zip(moments)
        {
            let p = f.bodies[b].point(r);
            let n = v[0].hypot(v[1]);
            let k = per_newton.unwrap_or(0.0);
            if n == 0.0 && moment == 0.0 {
                continue;
            }
            let (ux, uy) = if n > 0.0 { (v[0] / n, v[1] / n) } else { (0.7, 0.7) };
            let at = (p[0] + k * v[0], p[1] + k * v[1]);
            let anchor = if ux > 0.3 {
                Anchor::Start
            } else if ux < -0.3 {
                Anchor::End
            } else {
                Anchor::Middle
            };
            // Beyond the head (px: y down), or beside the moment's turn.
            let offset = if n > 0.0 { (10.0 * ux, -14.0 * uy + 6.0) } else { (24.0, -18.0) };
            fig.marks.push(Mark::Label { at, offset, text: name, color, anchor });
        }
    }

    /// What a figure marks beyond the shapes: each flexure's yield strength
    /// (Pa) on the stress colour bar, and where a sweep lost stability.
    #[derive(Default)]
    pub struct Marks {
        pub yields: Vec<(String, f64)>,
        pub limit: Option<String>,
    }

    /// The figure, and the arrows' scale (m per N) if any force is drawn.
    pub fn figure(
        m: &Mechanism,
        title: &str,
        unloaded: &Solution,
        loaded: &[(String, Solution)],
        marks: &Marks,
    ) -> (Figure, Option<f64>) {
        let mut fig = Figure::new(title, "x (m)", "y (m)");
        fig.equal_aspect = true;
        fig.width = 1200.0;
        fig.height = 760.0;
        fig.place = Place::Outside;
        fig.fit_height = true;

        // Sizes from the unloaded mechanism: links 2.4 % of it thick, the
        // longest force arrow about a quarter of it, at a round scale.
        let f0 = body_frames(m, unloaded);
        let mut pts: Vec<[f64; 2]> = (0..m.bodies.len())
            .flat_map(|b| attachments(m, b).into_iter().map(move |r| (b, r)))
            .map(|(b, r)| f0.bodies[b].point(r))
            .collect();
        pts.extend(m.joints.iter().zip(&f0.roots).map(|(_, r)| r.origin));
        pts.extend(f0.bodies.iter().map(|b| b.origin));
        let span = |i: usize| {
            let (lo, hi) = pts.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[i]), b.max(p[i])));
            if hi > lo { hi - lo } else { 0.0 }
        };
        let lengths = m.joints.iter().map(|j| if let JointKind::Flexure(fl) = &j.kind { fl.length() } else { 0.0 });
        let extent = span(0).max(span(1)).max(lengths.fold(0.0, f64::max)).max(1e-9);
        let thick = 0.012 * extent;
        let largest =
            loaded.iter().flat_map(|(_, s)| force_vectors(m, s)).map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
        let per_newton = (largest > 0.0).then(|| round_down(0.25 * extent / largest));
        // The colour bar runs from 0 to the largest stress (1 MPa if none is
        // loaded), and on past the highest yield strength, so that its mark shows.
        let highest_yield = marks.yields.iter().map(|y| y.1).fold(0.0, f64::max);
        let stress_top =
            stress_max(m, loaded).map(|top| if top > 0.0 { top } else { 1e6 }).map(|top| top.max(1.05 * highest_yield));

        // The ground, once: it does not move.
        let ground = attachments(m, 0);
        let (fill, stroke) = (Fill { color: GROUND.tint(0.4), opacity: 0.8 }, Stroke::solid(GROUND, 1.5));
        if !ground.is_empty() {
            let points = slab(&ground, thick);
            fig.marks.push(Mark::Path { points, stroke: Some(stroke), fill: Some(fill), closed: true });
        }
        fig.legend.push(Entry { swatch: Swatch::Area(fill, stroke), label: "ground".into() });
        let link = |c: Color| Swatch::Area(Fill { color: c.tint(0.55), opacity: 0.55 }, Stroke::solid(c, 1.5));
        shape(&mut fig, m, unloaded, GRAY, thick, Loads::Hidden);
        fig.legend.push(Entry { swatch: link(GRAY), label: "unloaded".into() });
        for (i, (label, s)) in loaded.iter().enumerate() {
            let color = SHAPES[i % SHAPES.len()];
            shape(&mut fig, m, s, color, thick, Loads::Drawn { per_newton, stress_top });
            fig.legend.push(Entry { swatch: link(color), label: label.clone() });
        }
        if let Some((_, s)) = loaded.last() {
            load_names(&mut fig, m, s, SHAPES[(loaded.len() - 1) % SHAPES.len()], per_newton);
        }

        // Keys for what every shape shows.
        if m.joints.iter().any(|j| matches!(j.kind, JointKind::Flexure(_))) {
            let swatch = Swatch::Line(Some(Stroke::solid(KEY, FLEXURE_WIDTH)), None);
            fig.legend.push(Entry { swatch, label: "flexure".into() });
        }
        let revolute = m.joints.iter().any(|j| matches!(j.kind, JointKind::Revolute(_)));
        let pin = m.closures.iter().any(|c| matches!(c, Closure::Pin { .. }));
        if revolute || pin {
            let swatch = Swatch::Line(None, Some((Marker::Circle, KEY, false)));
            let label = match (revolute, pin) {
                (true, true) => "revolute joint or pin",
                (true, false) => "revolute joint",
                _ => "pin",
            };
            fig.legend.push(Entry { swatch, label: label.into() });
        }
        if m.joints.iter().any(|j| matches!(j.kind, JointKind::Prismatic(_))) {
            let swatch = Swatch::Line(
                Some(Stroke { color: KEY, width: 2.0, dash: Dash::Dashed }),
                Some((Marker::Square, KEY, false)),
            );
            fig.legend.push(Entry { swatch, label: "slider (its travel dashed)".into() });
        }
        for (k, t) in m.tendons.iter().enumerate() {
            let tensions: Vec<f64> = loaded.iter().map(|(_, s)| s.loads.tension[k]).collect();
            let stroke = Stroke { color: KEY, width: 1.5, dash: TENDON_DASH[k % TENDON_DASH.len()] };
            fig.legend.push(Entry {
                swatch: Swatch::Line(Some(stroke), Some((VIA[k % VIA.len()], KEY, false))),
                label: format!("tendon {}: {}", t.name, values(&tensions, "N")),
            });
        }
        for (i, p) in m.forces.iter().enumerate() {
            let body = &m.bodies[p.body].name;
            let loads: Vec<[f64; 3]> = loaded.iter().map(|(_, s)| s.loads.force[i]).collect();
            let moments: Vec<f64> = loads.iter().map(|l| l[2]).collect();
            let pushes = loads.iter().any(|l| l[0] != 0.0 || l[1] != 0.0);
            if pushes || moments.iter().all(|&x| x == 0.0) {
                let same = loads.windows(2).all(|w| w[0][..2] == w[1][..2]);
                let value = match loads.first() {
                    Some(l) if same => format!("({}, {}) N", short(l[0]), short(l[1])),
                    _ => values(&loads.iter().map(|l| l[0].hypot(l[1])).collect::<Vec<_>>(), "N"),
                };
                let label = format!("force {} on {body}: {value}", p.name);
                fig.legend.push(Entry { swatch: Swatch::Arrow(KEY), label });
            }
            if moments.iter().any(|&x| x != 0.0) {
                let positive = moments.iter().all(|&x| x > 0.0);
                let value = if positive || moments.iter().all(|&x| x < 0.0) {
                    let sizes: Vec<f64> = moments.iter().map(|x| x.abs()).collect();
                    format!("{} {}", values(&sizes, "N·m"), if positive { "counter-clockwise" } else { "clockwise" })
                } else {
                    format!("{} (+: counter-clockwise)", values(&moments, "N·m"))
                };
                let label = format!("moment {} on {body}: {value}", p.name);
                fig.legend.push(Entry { swatch: Swatch::Turn(KEY), label });
            }
        }
        if loaded.iter().any(|(_, s)| s.loads.gravity != [0.0, 0.0]) {
            for b in m.bodies.iter().filter(|b| b.mass > 0.0) {
                let w: Vec<f64> =
                    loaded.iter().map(|(_, s)| b.mass * s.loads.gravity[0].hypot(s.loads.gravity[1])).collect();
                fig.legend.push(Entry {
                    swatch: Swatch::Arrow(KEY),
                    label: format!("weight of {}: {}", b.name, values(&w, "N")),
                });
            }
        }
        if let Some(k) = per_newton {
            fig.legend.push(Entry { swatch: Swatch::Note, label: format!("force arrows: {} m per N", short(k)) });
        }
        if let Some(limit) = &marks.limit {
            fig.legend.push(Entry { swatch: Swatch::Note, label: limit.clone() });
        }
        if let Some(top) = stress_top {
            let mut label = "flexures' bending stress (MPa)".to_string();
            if !marks.yields.is_empty() {
                let named: Vec<String> =
                    marks.yields.iter().map(|(name, y)| format!("{name} {} MPa", short(y / 1e6))).collect();
                label += &format!("; black line: yield strength ({})", named.join(", "));
            }
            let bar_marks = marks.yields.iter().map(|y| y.1 / 1e6).collect();
            fig.color_bar = Some(ColorBar { label, lo: 0.0, hi: top / 1e6, marks: bar_marks });
            let plain = m.joints.iter().any(|j| match &j.kind {
                JointKind::Flexure(fl) => fl.section().modulus().is_none(),
                _ => false,
            });
            let label = if plain {
                "loaded flexures coloured by stress; those given by ei alone (no thickness) in their shape's colour"
            } else {
                "loaded flexures coloured by bending stress"
            };
            fig.legend.push(Entry { swatch: Swatch::Note, label: label.into() });
        }
        (fig, per_newton)
    }
}

#[cfg(test)]
mod tests {
    use super::drawing::{attachments, hull, slab};
    use flexure::mechanism::file::from_toml;
    use flexure::mechanism::statics::{Settings, assemble_unloaded, body_frames};

    #[test]
    fn a_hull_keeps_the_corners_only() {
        let h = hull(vec![(0.0, 0.0), (1.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.0, 1.0), (0.5, 0.0)]);
        assert_eq!(h, [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
    }

    /// The parallelogram's stage is drawn across both flexure tips: the
    /// file puts them 0.04 m apart, at x = 0 and x = 0.04 when unloaded.
    #[test]
    fn a_stage_spans_every_leg() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/parallelogram.toml");
        let m = from_toml(&std::fs::read_to_string(path).unwrap()).unwrap();
        let s = assemble_unloaded(&m, &Settings::default()).unwrap();
        let f = body_frames(&m, &s);
        let stage = m.body("stage").unwrap();
        let pts: Vec<[f64; 2]> = attachments(&m, stage).iter().map(|&r| f.bodies[stage].point(r)).collect();
        let r = 1e-3;
        let xs: Vec<f64> = slab(&pts, r).iter().map(|p| p.0).collect();
        let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        // Closure solved to ~1e-12 m; the slab reaches r beyond each tip.
        assert!((lo + r).abs() < 1e-9 && (hi - 0.04 - r).abs() < 1e-9, "{lo} {hi}");
    }
}
