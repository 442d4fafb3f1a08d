//! `flexure draw`: a mechanism's unloaded and loaded shapes (or a
//! simulated motion) as one SVG, with the warnings `solve` gives.

use super::checks::solved_answer;
use super::drawing::{self, Marks, Track, View, snapshot_samples, swept};
use super::scene::{self, Pose, Scene};
use crate::analyses::{SweepSpec, sweep_values};
use crate::options::number;
use clap::Args;
use flexure::mechanism::Mechanism;
use flexure::mechanism::statics::{Settings, Solution};
use flexure::mechanism::sweep::Parameter;
use flexure::model::Model;
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
    /// Where the picture is seen from [default: top for a planar file (x right, y up), iso for a spatial one].
    #[arg(long, value_enum)]
    view: Option<View>,
}

/// What `draw` draws, whichever the dimension: the scene, its rest shape,
/// the shapes (a sweep's, a solve's or a motion's snapshots), and the answer
/// so far (the checks' verdicts and findings).
struct Picture {
    scene: Scene,
    rest: Pose,
    shapes: Vec<(String, Pose)>,
    marks: Marks,
    /// A motion's sample times, its bodies' tracks and the samples drawn.
    motion: Option<(Vec<f64>, Vec<Track>, Vec<usize>)>,
    answer: Value,
    /// The view when `--view` is not given.
    view: View,
}

/// Shapes past a sweep's stability limit (on its far side from the first
/// value) are labelled so.
fn sweep_label(parameter: &str, limit: Option<f64>, first: f64) -> impl Fn(f64) -> String + '_ {
    move |v: f64| match limit.is_some_and(|l| (v - l) * (first - l) < 0.0) {
        true => format!("{} (past the stability limit)", swept(parameter, v)),
        false => swept(parameter, v),
    }
}

/// `draw` of a spatial file: its shapes, with the findings solve and simulate give.
fn spatial_picture(
    args: &DrawArgs,
    model: &Model,
    m: &flexure::mechanism::spatial::SpatialMechanism,
) -> Result<Picture, String> {
    use flexure::mechanism::{statics, sweep};
    let settings = Settings::default();
    let err = |e: flexure::Error| super::file_error(&args.file, e);
    // First, so that an open closure that keeps the mechanism from assembling is told.
    let mut findings = crate::findings::closures(m, &args.file)?;
    let unloaded = statics::assemble_unloaded(m, &settings).map_err(err)?;
    let mut answer = json!({});
    let mut marks = Marks::default();
    let mut motion = None;
    let shapes: Vec<(String, Pose)> = if let Some(spec) = &args.sweep {
        let values = sweep_values(&spec.range);
        let target = args.accuracy.target();
        let (checks, out) = super::checks::sweep_answer(model, (&spec.parameter, &values), None, &target, &args.file)?;
        let none = Vec::new();
        if out.rows.is_empty() {
            let why = out.stopped.as_ref().map_or("no value was reached".into(), |(v, e)| format!("at {v}: {e}"));
            return Err(format!("{}: --sweep {}: nothing to draw: {why}", args.file.display(), spec.parameter));
        }
        findings = checks.get("findings").and_then(Value::as_array).unwrap_or(&none).clone();
        for key in ["flagged", "stability_limit", "stopped"] {
            if let Some(x) = checks.get(key) {
                answer[key] = x.clone();
            }
        }
        if let Some(l) = &out.stability_limit {
            marks.limit = Some(format!("stability lost at {} = {}", spec.parameter, drawing::short(l.value)));
        }
        let p = sweep::SpatialParameter::parse(m, &spec.parameter).map_err(crate::describe)?;
        let label = sweep_label(&spec.parameter, out.stability_limit.map(|l| l.value), values[0]);
        out.rows
            .iter()
            .zip(&out.q)
            .map(|(r, q)| Ok((label(r[0]), scene::spatial(m, &label(r[0]), q, &p.apply(&m.loads(), r[0]))?)))
            .collect::<Result<_, String>>()?
    } else if let Some(duration) = args.simulate {
        let settings = args.motion.settings(duration);
        let sim = flexure::dynamics::simulation::simulate(m, &settings, args.motion.start())
            .map_err(|e| format!("{}: {}", args.file.display(), crate::simulate::simulation_error(e, duration)))?;
        let samples: Vec<(f64, &[f64])> = (0..sim.time.len()).map(|k| (sim.time[k], sim.q(k))).collect();
        findings.extend(crate::findings::along(m, &samples, ("t (s)", "samples"), "time", &args.file));
        let picked = snapshot_samples(sim.time.len());
        let (snapshots, tracks) = scene::spatial_motion(m, &sim, &picked)?;
        (answer["steps"], answer["rejected"]) = (json!(sim.steps), json!(sim.rejected));
        motion = Some((sim.time.clone(), tracks, picked));
        snapshots
    } else {
        let s = statics::solve(m, &settings).map_err(err)?;
        findings.extend(crate::findings::shape(m, &s.q, &args.file));
        vec![("loaded".into(), scene::spatial(m, "loaded", &s.q, &s.loads)?)]
    };
    if !findings.is_empty() {
        answer["findings"] = Value::Array(findings);
    }
    let rest = scene::spatial(m, "unloaded", &unloaded.q, &unloaded.loads)?;
    Ok(Picture { scene: scene::spatial_scene(m), rest, shapes, marks, motion, answer, view: View::Iso })
}

/// `draw` of a planar file: its shapes, with the warnings and verdicts solve and simulate give.
fn planar_picture(args: &DrawArgs, model: &Model, m: &Mechanism) -> Result<Picture, String> {
    let settings = Settings::default();
    let err = |e: flexure::Error| super::file_error(&args.file, e);
    // The checks' warnings are solve's (simulate's); of their answer, draw keeps only the verdicts.
    let mut checks = json!({});
    if let Some(duration) = args.simulate {
        let run = crate::simulate::run_motion(m, &args.file, (duration, "--simulate"), &args.motion)?;
        crate::simulate::insert_motion_checks(&mut checks, m, &run, &args.file)?;
        crate::simulate::insert_stopped(&mut checks, (&run.trajectory, &run.stopped), &args.file, duration);
        let unloaded = flexure::mechanism::statics::assemble_unloaded(m, &settings).map_err(err)?;
        let picked = snapshot_samples(run.time.len());
        let (shapes, tracks) = scene::planar_motion(m, &run, &picked);
        let mut answer = json!({ "steps": run.steps, "rejected": run.rejected });
        for key in ["findings", "stopped"] {
            if let Some(x) = checks.get(key) {
                answer[key] = x.clone();
            }
        }
        let motion = Some((run.time.clone(), tracks, picked));
        let (scene, rest) = (scene::planar_scene(m), scene::planar(m, &unloaded.q, &unloaded.loads));
        return Ok(Picture { scene, rest, shapes, marks: Marks::default(), motion, answer, view: View::Top });
    }
    let target = args.accuracy.target();
    let unloaded = flexure::mechanism::statics::assemble_unloaded(m, &settings).map_err(err)?;
    let mut marks = Marks {
        yields: m.joints.iter().filter_map(|j| Some((j.name.clone(), j.report.yield_strength?))).collect(),
        limit: None,
    };
    let loaded: Vec<(String, (Vec<f64>, flexure::mechanism::Loads))> = match &args.sweep {
        Some(spec) => {
            let values = sweep_values(&spec.range);
            let out;
            (checks, out) = super::checks::sweep_answer(model, (&spec.parameter, &values), None, &target, &args.file)?;
            let p = Parameter::parse(m, &spec.parameter).map_err(crate::describe)?;
            let limit = out.stability_limit.map(|l| l.value);
            let past = |value: f64| limit.is_some_and(|l| (value - l) * (values[0] - l) < 0.0);
            marks.limit = limit.map(|l| {
                let shapes = match out.rows.iter().filter(|r| past(r[0])).count() {
                    0 => "no shape is drawn past it",
                    1 => "the last shape is past it, reached by snap-through",
                    _ => "the shapes marked past it were reached by snap-through",
                };
                format!("stability lost at {} = {}: {shapes}", spec.parameter, drawing::short(l))
            });
            let label = sweep_label(&spec.parameter, limit, values[0]);
            out.rows.iter().zip(out.q).map(|(r, q)| (label(r[0]), (q, p.apply(&m.loads(), r[0])))).collect()
        }
        None => {
            let findings = crate::findings::open_at_rest(model, &args.file)?;
            let solved = model.solve(&target, None).map_err(super::solver_error(&args.file))?;
            let q = solved.q.clone();
            checks = solved_answer(model, findings, solved, &target, &args.file)?;
            vec![("loaded".into(), (q, m.loads()))]
        }
    };
    Ok(planar_shapes(m, &unloaded, loaded, marks, &checks))
}

/// A planar picture of the unloaded assembly and the `loaded` shapes
/// (coordinates and loads, by label), with the verdicts of `checks`.
fn planar_shapes(
    m: &Mechanism,
    unloaded: &Solution,
    loaded: Vec<(String, (Vec<f64>, flexure::mechanism::Loads))>,
    marks: Marks,
    checks: &Value,
) -> Picture {
    let mut answer = json!({});
    for key in ["findings", "flagged", "limit_fraction", "stability_limit", "stopped"] {
        if let Some(x) = checks.get(key) {
            answer[key] = x.clone();
        }
    }
    let shapes = loaded.iter().map(|(label, (q, loads))| (label.clone(), scene::planar(m, q, loads))).collect();
    let (scene, rest) = (scene::planar_scene(m), scene::planar(m, &unloaded.q, &unloaded.loads));
    Picture { scene, rest, shapes, marks, motion: None, answer, view: View::Top }
}

/// An SVG of the unloaded and loaded shapes (or a motion's snapshots and
/// charts), to one scale on both axes, with the warnings `solve` (or
/// `simulate`) gives on the same file. The one place that asks the dimension.
pub fn draw_cmd(args: &DrawArgs) -> Result<Value, String> {
    let model = crate::input::read_model(&args.file)?;
    let p = match &model {
        Model::Planar(m) => planar_picture(args, &model, m)?,
        Model::Spatial(m) => spatial_picture(args, &model, m)?,
    };
    let title = args.file.file_name().map_or("mechanism".into(), |n| n.to_string_lossy().into_owned());
    let view = args.view.unwrap_or(p.view);
    let mut v = json!({ "out": args.out.display().to_string(), "shapes": p.shapes.len() + 1 });
    let per_newton = match &p.motion {
        Some((time, tracks, picked)) => {
            let drawn =
                drawing::motion_figures(&p.scene, &title, (&p.rest, &p.shapes), (time, tracks), picked, view, true)
                    .map_err(|e| format!("drawing {}: {e}; nothing was written", args.out.display()))?;
            flexure_chart::write_stack(&args.out, &drawn.figures)?;
            v["snapshots"] = json!(drawn.snapshots);
            drawn.per_newton
        }
        None => {
            let (fig, k) = drawing::figure(&p.scene, &title, &p.rest, &p.shapes, &p.marks, view, true);
            flexure_chart::write(&args.out, &fig)?;
            k
        }
    };
    if let Some(k) = per_newton {
        v["force_scale_m_per_n"] = json!(k);
    }
    if let (Value::Object(v), Value::Object(a)) = (&mut v, p.answer) {
        v.extend(a);
    }
    Ok(v)
}
