//! `flexure draw`: a mechanism's unloaded and loaded shapes (or a
//! simulated motion) as one SVG, with the warnings `solve` gives.

use super::checks::{insert_sweep_checks, solved_answer};
use super::drawing;
use crate::analyses::{SweepSpec, sweep_values};
use crate::options::{number, warn};
use clap::Args;
use flexure::mechanism::statics::{Settings, Solution, solve};
use flexure::mechanism::sweep::{Parameter, sweep};
use serde_json::{Value, json};
use std::path::PathBuf;

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
    /// Spatial files (dimension = 3): where the picture is seen from.
    #[arg(long, value_enum, default_value_t = super::projection::View::Iso)]
    view: super::projection::View,
}

/// `draw` of a spatial file: its unloaded and loaded shapes (or a
/// simulation's snapshots) projected from `--view`, flexures coloured by stress.
fn draw_spatial(args: &DrawArgs, m: &flexure::mechanism::spatial::SpatialMechanism) -> Result<Value, String> {
    use super::spatial_drawing as sd;
    let settings = Settings::default();
    let err = |e: flexure::Error| super::file_error(&args.file, e);
    let title = args.file.file_name().map_or("mechanism".into(), |n| n.to_string_lossy().into_owned());
    // solve's and simulate's findings, told on stderr and kept in the answer;
    // first, so that an open closure that keeps the mechanism from assembling is told.
    let mut findings = crate::findings::spatial_closures(m, &args.file)?;
    let unloaded =
        flexure::mechanism::spatial::statics::assemble_unloaded(m, &m.loads().zero_like(), &settings).map_err(err)?;
    if let Some(spec) = &args.sweep {
        let p =
            flexure::mechanism::spatial::sweep::SpatialParameter::parse(m, &spec.parameter).map_err(crate::describe)?;
        let values = sweep_values(&spec.range);
        let out = flexure::mechanism::spatial::sweep::sweep(m, &p, &values, &settings).map_err(err)?;
        if out.rows.is_empty() {
            let why = out.stopped.as_ref().map_or("no value was reached".into(), |(v, e)| format!("at {v}: {e}"));
            return Err(format!("{}: --sweep {}: nothing to draw: {why}", args.file.display(), spec.parameter));
        }
        // Shapes past the limit (on its far side from the first value) are labelled so, as in the plane.
        let past = |value: f64| out.stability_limit.is_some_and(|l| (value - l.value) * (values[0] - l.value) < 0.0);
        let marks = drawing::Marks {
            yields: Vec::new(),
            limit: out.stability_limit.map(|l| {
                warn(format!(
                    "{}: the sweep of {} lost stability at {} = {:.6e} ({:.4} % of the way)",
                    args.file.display(),
                    spec.parameter,
                    spec.parameter,
                    l.value,
                    100.0 * l.fraction
                ));
                format!("stability lost at {} = {}", spec.parameter, drawing::short(l.value))
            }),
        };
        let label = |v: f64| match past(v) {
            true => format!("{} (past the stability limit)", drawing::swept(&spec.parameter, v)),
            false => drawing::swept(&spec.parameter, v),
        };
        let shapes: Vec<(f64, &[f64])> = out.rows.iter().map(|(v, s)| (*v, s.q.as_slice())).collect();
        findings.extend(crate::findings::spatial_along(
            m,
            &shapes,
            (&spec.parameter, "swept values"),
            "value",
            &args.file,
        ));
        let loaded: Vec<(String, flexure::mechanism::spatial::statics::SpatialSolution)> =
            out.rows.iter().map(|(v, s)| (label(*v), s.clone())).collect();
        let (fig, k) = sd::spatial_figure(m, &title, &unloaded, &loaded, &marks, args.view, true)?;
        flexure_chart::write(&args.out, &fig)?;
        let mut v = json!({ "out": args.out.display().to_string(), "shapes": loaded.len() + 1 });
        if let Some(l) = &out.stability_limit {
            v["stability_limit"] = json!(l);
        }
        if let Some((value, e)) = &out.stopped {
            v["stopped"] = json!({ "value": value, "error": format!("{}: {e}", args.file.display()) });
        }
        if let Some(k) = k {
            v["force_scale_m_per_n"] = json!(k);
        }
        super::spatial::insert_findings(&mut v, findings);
        return Ok(v);
    }
    if let Some(duration) = args.simulate {
        let sim = crate::mechanism::spatial::simulate(m, &args.file, duration, &args.motion)?;
        let samples: Vec<(f64, &[f64])> = (0..sim.time.len()).map(|k| (sim.time[k], sim.q(k))).collect();
        findings.extend(crate::findings::spatial_along(m, &samples, ("t (s)", "samples"), "time", &args.file));
        let drawn = sd::spatial_motion_figures(m, &title, &unloaded, &sim, args.view, true)?;
        flexure_chart::write_stack(&args.out, &drawn.figures)?;
        let mut v = json!({ "out": args.out.display().to_string(), "shapes": drawn.snapshots.len() + 1,
                          "snapshots": drawn.snapshots, "force_scale_m_per_n": drawn.per_newton });
        super::spatial::insert_findings(&mut v, findings);
        return Ok(v);
    }
    let s = flexure::mechanism::spatial::statics::solve(m, &settings).map_err(err)?;
    findings.extend(crate::findings::spatial_shape(m, &s.q, &args.file));
    let (fig, k) =
        sd::spatial_figure(m, &title, &unloaded, &[("loaded".into(), s)], &drawing::Marks::default(), args.view, true)?;
    flexure_chart::write(&args.out, &fig)?;
    let mut v = json!({ "out": args.out.display().to_string(), "shapes": 2 });
    if let Some(k) = k {
        v["force_scale_m_per_n"] = json!(k);
    }
    super::spatial::insert_findings(&mut v, findings);
    Ok(v)
}

/// An SVG of the unloaded and loaded shapes, to one scale on both axes,
/// with the warnings `solve` gives on the same file.
pub fn draw_cmd(args: &DrawArgs) -> Result<Value, String> {
    let model = super::read_model(&args.file)?;
    let m = match &model {
        flexure::model::Model::Planar(m) => m,
        flexure::model::Model::Spatial(m) => return draw_spatial(args, m),
    };
    if let Some(duration) = args.simulate {
        return draw_motion(args, duration);
    }
    let settings = Settings::default();
    let target = args.accuracy.target();
    let err = |e: flexure::Error| super::file_error(&args.file, e);
    let unloaded = flexure::mechanism::statics::assemble_unloaded(m, &settings).map_err(err)?;
    let mut marks = drawing::Marks {
        yields: m.joints.iter().filter_map(|j| Some((j.name.clone(), j.report.yield_strength?))).collect(),
        limit: None,
    };
    // The checks' warnings are solve's; of their answer, draw keeps only the verdicts.
    let mut checks = json!({});
    let loaded: Vec<(String, Solution)> = match &args.sweep {
        Some(spec) => {
            let p = Parameter::parse(m, &spec.parameter).map_err(crate::describe)?;
            let values = sweep_values(&spec.range);
            let out = sweep(m, &p, &values, &settings).map_err(err)?;
            insert_sweep_checks(&mut checks, m, &out, (&target, &args.file), (&spec.parameter, &values))?;
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
            let s = solve(m, &settings).map_err(err)?;
            // TODO(draw): the drawing's own solve, until it draws from the door's.
            let findings = super::told_closures(&model, &args.file)?;
            let solved = model.solve(&target, None).map_err(err)?;
            checks = solved_answer(&model, findings, solved, &target, &args.file)?;
            vec![("loaded".into(), s)]
        }
    };
    let title = args.file.file_name().map_or("mechanism".into(), |n| n.to_string_lossy().into_owned());
    let (figure, per_newton) = drawing::figure(m, &title, &unloaded, &loaded, &marks);
    flexure_chart::write(&args.out, &figure)?;
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
    use flexure_chart::{COLORS, Chart, Dash, Series, chart_figure, write_stack};
    let (m, run) = crate::simulate::run_motion(&args.file, (duration, "--simulate"), &args.motion)?;
    // simulate's warnings; of its answer, draw keeps the findings.
    let mut checks = json!({});
    crate::simulate::insert_motion_checks(&mut checks, &m, &run, &args.file)?;
    crate::simulate::insert_stopped(&mut checks, &run, &args.file, duration);
    let err = |e: flexure::Error| super::file_error(&args.file, e);
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
        fig.place = flexure_chart::Place::Outside;
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
