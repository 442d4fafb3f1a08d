//! Subcommands on mechanism files: solve, buckle, draw.

use crate::analyses::{SweepSpec, sweep_values};
use crate::figures::{COLORS, Chart, Series, draw};
use crate::options::number;
use clap::Args;
use flexure::estimate::{Accuracy, ErrorEstimate, joint_error};
use flexure::kinematics::backbone;
use flexure::mechanism::buckling::buckle;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::kinematics::Frames;
use flexure::mechanism::statics::{Settings, Solution, body_frames, compliance, solve};
use flexure::mechanism::sweep::{Parameter, StabilityLimit, Sweep, sweep};
use flexure::mechanism::{JointKind, Mechanism};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

fn load(path: &Path) -> Result<Mechanism, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    from_toml(&text).map_err(|e| format!("{}: {e}", path.display()))
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
/// joint under the tip load it carries, against the refined model.
fn joint_estimates(
    m: &Mechanism,
    s: &Solution,
    target: &Accuracy,
) -> flexure::Result<Vec<(&'static str, String, ErrorEstimate, f64)>> {
    let mut out = Vec::new();
    for j in &m.joints {
        if let JointKind::Flexure(fl) = &j.kind {
            let e = joint_error(fl, &s.q[j.offset..j.offset + fl.order()], target)?;
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
    let estimates = joint_estimates(m, s, target).map_err(|e| format!("{}: {e}", file.display()))?;
    let mut map = serde_json::Map::new();
    for (what, name, e, length) in &estimates {
        if e.flagged {
            crate::options::warn(format!(
                "{}: {what} {name:?}: the estimated error ({:.3e} m = {:.3} % of its length, {:.3}°) exceeds the accuracy target; raise its order",
                file.display(),
                e.position,
                100.0 * e.position / length,
                e.angle.to_degrees()
            ));
        }
        map.insert(name.clone(), json!({ "position": e.position, "angle": e.angle }));
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

/// Equilibrium of a mechanism file, optionally with a compliance or a sweep.
pub fn solve_cmd(args: &SolveArgs) -> Result<Value, String> {
    let m = load(&args.file)?;
    let settings = Settings::default();
    let err = |e: flexure::Error| format!("{}: {e}", args.file.display());
    let body = match &args.compliance {
        Some(name) => Some(
            m.body(name).ok_or_else(|| format!("--compliance: no body named {name:?} in {}", args.file.display()))?,
        ),
        None => None,
    };
    let with_compliance = |s: &Solution, mut v: Value| -> Result<Value, String> {
        if let (Some(b), Some(at)) = (body, args.at) {
            let c = compliance(&m, s, b, at).map_err(err)?;
            v["compliance"] = crate::joint::matrix(&c);
        }
        Ok(v)
    };
    let value = match &args.sweep {
        Some(spec) => {
            let p = Parameter::parse(&m, &spec.parameter).map_err(crate::describe)?;
            let values = sweep_values(&spec.range);
            let out = sweep(&m, &p, &values, &settings).map_err(err)?;
            let compliance_at = body.zip(args.at);
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
            if let Some(l) = &out.stability_limit {
                v["stability_limit"] = limit_json(l);
            }
            if let Some(w) = sweep_warning(&args.file, &spec.parameter, &out, &values) {
                crate::options::warn(w);
            }
            // Each row's flexure joints, held to the accuracy target.
            let target = args.accuracy.target();
            let mut flagged = Vec::new();
            for (value, s) in &out.rows {
                if joint_estimates(&m, s, &target).map_err(err)?.iter().any(|e| e.2.flagged) {
                    flagged.push(*value);
                }
            }
            v["flagged"] = json!(flagged);
            if !flagged.is_empty() {
                crate::options::warn(format!(
                    "{}: at {} of the swept values a flexure joint's estimated error exceeds the accuracy target (listed in `flagged`); raise its order",
                    args.file.display(),
                    flagged.len()
                ));
            }
            return Ok(v);
        }
        None => {
            let s = solve(&m, &settings).map_err(err)?;
            let mut v = with_compliance(&s, solution_json(&m, &s))?;
            put_joint_estimates(&mut v, &m, &s, &args.accuracy.target(), &args.file)?;
            if let Some(limit) = s.limit {
                v["limit_fraction"] = json!(limit);
            }
            if let Some(limit) = s.limit {
                crate::options::warn(format!(
                    "{}: the loading path lost stability at {:.4} % of the load and snapped through to this stable equilibrium",
                    args.file.display(),
                    100.0 * limit
                ));
            }
            v
        }
    };
    Ok(value)
}

#[derive(Debug, Args)]
pub struct BuckleArgs {
    /// Mechanism file (TOML).
    file: PathBuf,
}

/// Linear buckling factor on all loads, and the mode.
pub fn buckle_cmd(args: &BuckleArgs) -> Result<Value, String> {
    let m = load(&args.file)?;
    let b = buckle(&m, &Settings::default()).map_err(|e| format!("{}: {e}", args.file.display()))?;
    Ok(json!({ "load_factor": b.load_factor, "mode": b.mode }))
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
}

/// Every drawable line of the mechanism in one configuration.
fn shape(m: &Mechanism, s: &Solution, color: plotters::style::RGBColor, label: &str) -> Vec<Series> {
    let f: Frames = body_frames(m, s);
    let mut out = Vec::new();
    let mut named = false;
    let mut line = |points: Vec<(f64, f64)>, out: &mut Vec<Series>| {
        let name = if named { "" } else { label };
        named = true;
        out.push(Series::line(name, points, color));
    };
    for (ji, j) in m.joints.iter().enumerate() {
        let root = f.roots[ji];
        // Parent body outline: from its frame origin to this joint's root.
        let parent = f.bodies[j.parent].origin;
        line(vec![(parent[0], parent[1]), (root.origin[0], root.origin[1])], &mut out);
        if let JointKind::Flexure(fl) = &j.kind {
            let q = &s.q[j.offset..j.offset + fl.order()];
            let pts = backbone(fl, q, 41).iter().map(|p| root.point([p.x, p.y])).map(|p| (p[0], p[1])).collect();
            line(pts, &mut out);
        } else {
            let c = f.bodies[j.child].origin;
            line(vec![(root.origin[0], root.origin[1]), (c[0], c[1])], &mut out);
        }
    }
    // Bodies reach out to every point attached to them.
    let attach = |b: usize, r: [f64; 2]| {
        let o = f.bodies[b].origin;
        let p = f.bodies[b].point(r);
        vec![(o[0], o[1]), (p[0], p[1])]
    };
    for t in &m.tendons {
        for &(b, r) in &t.path {
            line(attach(b, r), &mut out);
        }
        out.push(Series::line(
            "",
            t.path.iter().map(|&(b, r)| f.bodies[b].point(r)).map(|p| (p[0], p[1])).collect(),
            COLORS[4],
        ));
    }
    let scale = m
        .joints
        .iter()
        .map(|j| if let JointKind::Flexure(fl) = &j.kind { fl.length() } else { 0.01 })
        .fold(0.0, f64::max);
    for (p, l) in m.forces.iter().zip(&s.loads.force) {
        let at = f.bodies[p.body].point(p.at);
        line(attach(p.body, p.at), &mut out);
        let n = l[0].hypot(l[1]);
        if n > 0.0 {
            let tip = [at[0] + scale * l[0] / n, at[1] + scale * l[1] / n];
            let (dx, dy) = ((tip[0] - at[0]) * 0.25, (tip[1] - at[1]) * 0.25);
            out.push(Series::line(
                "",
                vec![
                    (at[0], at[1]),
                    (tip[0], tip[1]),
                    (tip[0] - dx - dy * 0.5, tip[1] - dy + dx * 0.5),
                    (tip[0], tip[1]),
                    (tip[0] - dx + dy * 0.5, tip[1] - dy - dx * 0.5),
                ],
                COLORS[1],
            ));
        }
    }
    out
}

/// An SVG of the unloaded and loaded shapes.
pub fn draw_cmd(args: &DrawArgs) -> Result<Value, String> {
    let m = load(&args.file)?;
    let settings = Settings::default();
    let err = |e: flexure::Error| format!("{}: {e}", args.file.display());
    let unloaded = flexure::mechanism::statics::assemble_unloaded(&m, &settings).map_err(err)?;
    let mut series = shape(&m, &unloaded, plotters::style::RGBColor(160, 160, 160), "unloaded");
    let mut limit = None;
    let loaded: Vec<(String, Solution)> = match &args.sweep {
        Some(spec) => {
            let p = Parameter::parse(&m, &spec.parameter).map_err(crate::describe)?;
            let values = sweep_values(&spec.range);
            let out = sweep(&m, &p, &values, &settings).map_err(err)?;
            if let Some(w) = sweep_warning(&args.file, &spec.parameter, &out, &values) {
                crate::options::warn(w);
            }
            limit = out.stability_limit;
            out.rows.into_iter().map(|(v, s)| (format!("{} = {v}", spec.parameter), s)).collect()
        }
        None => vec![("loaded".into(), solve(&m, &settings).map_err(err)?)],
    };
    for (i, (label, s)) in loaded.iter().enumerate() {
        series.extend(shape(&m, s, COLORS[[0, 2, 3, 5][i % 4]], label));
    }
    let title = format!("{}", args.file.file_name().map_or("mechanism".into(), |n| n.to_string_lossy()));
    draw(
        &args.out,
        &Chart { title: &title, x_label: "x (m)", y_label: "y (m)", log_y: false, equal_aspect: true },
        &series,
    )?;
    let mut v = json!({ "out": args.out.display().to_string(), "shapes": loaded.len() + 1 });
    if let Some(l) = &limit {
        v["stability_limit"] = limit_json(l);
    }
    Ok(v)
}
