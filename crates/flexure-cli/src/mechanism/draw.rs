//! `flexure draw`: a mechanism's unloaded and loaded shapes (or a
//! simulated motion) as one SVG, with the warnings `solve` gives.

use super::checks::solve_answer;
use super::drawing::{self, Marks, Track, View, snapshot_samples, swept};
use super::scene::{self, Drawn, Scene, Shapes, Snapshot};
use crate::analyses::{SweepSpec, sweep_values};
use crate::options::number;
use clap::Args;
use flexure::mechanism::Mechanism;
use flexure::mechanism::contact::pairs;
use flexure::mechanism::statics::{Settings, Solution, Workspace, assemble_unloaded, follow_touching};
use flexure::mechanism::sweep::Parameter;
use flexure::model::{Model, Visit};
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
    rest: Snapshot,
    shapes: Vec<(String, Snapshot)>,
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

/// `draw` of a mechanism of either dimension: its shapes, with the
/// warnings and verdicts solve (sweep, simulate) gives, the yield strengths
/// asked for, and a sweep's shapes past its stability limit marked.
fn picture<D: Drawn>(args: &DrawArgs, model: &Model, m: &Mechanism<D>) -> Result<Picture, String> {
    let target = args.accuracy.target();
    // The checks' warnings are solve's (sweep's, simulate's); of their answer, draw keeps only the verdicts.
    let mut checks = json!({});
    let mut marks = Marks {
        yields: m.joints.iter().filter_map(|j| Some((j.name.clone(), j.report.yield_strength?))).collect(),
        limit: None,
    };
    let mut motion = None;
    let shapes: Shapes = if let Some(duration) = args.simulate {
        let run = crate::simulate::run_motion(m, &args.file, (duration, "--simulate"), &args.motion)?;
        (checks["steps"], checks["rejected"]) = (json!(run.steps), json!(run.rejected));
        crate::simulate::insert_motion_checks(&mut checks, m, &run, &args.file)?;
        crate::simulate::insert_stopped(&mut checks, (&run.trajectory, &run.stopped), &args.file, duration);
        let picked = snapshot_samples(run.time.len());
        let (shapes, tracks) = scene::motion(m, &run, &picked)?;
        motion = Some((run.time.clone(), tracks, picked));
        shapes
    } else if let Some(spec) = &args.sweep {
        let values = sweep_values(&spec.range);
        let out;
        (checks, out) = super::checks::sweep_table(model, (&spec.parameter, &values), None, &target, &args.file)?;
        if out.model.dof() != model.dof() {
            return raised(args, &out.model);
        }
        if out.rows.is_empty() {
            let why = out.stopped.as_ref().map_or("no value was reached".into(), |(v, e)| format!("at {v}: {e}"));
            return Err(format!("{}: --sweep {}: nothing to draw: {why}", args.file.display(), spec.parameter));
        }
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
        out.rows
            .iter()
            .zip(&out.q)
            .enumerate()
            .map(|(k, (r, q))| {
                let shape = D::pose(m, &label(r[0]), q, &p.apply(&m.loads(), r[0]))?;
                let contacts = out.contacts.as_ref().map_or(&[][..], |c| c[k].as_slice());
                Ok((label(r[0]), shape.with_contacts(contacts)))
            })
            .collect::<Result<_, String>>()?
    } else {
        let findings = crate::findings::open_at_rest(model, &args.file)?;
        let solved = model.solve(&target, None).map_err(super::solver_error(&args.file))?;
        if solved.model.dof() != model.dof() {
            return raised(args, &solved.model);
        }
        let q = solved.q.clone();
        let contacts = solved.report.as_ref().ok().and_then(|r| r.contacts.clone()).unwrap_or_default();
        checks = solve_answer(model, findings, solved, &target, &args.file)?;
        vec![("loaded".into(), D::pose(m, "loaded", &q, &m.loads())?.with_contacts(&contacts))]
    };
    let mut answer = json!({});
    for key in ["steps", "rejected", "findings", "flagged", "limit_fraction", "stability_limit", "stopped"] {
        if let Some(x) = checks.get(key) {
            answer[key] = x.clone();
        }
    }
    // Last, so that the closures open at rest are told before an assembly they keep from closing fails.
    let unloaded = unloaded(m, args.simulate.is_some()).map_err(|e| super::file_error(&args.file, e))?;
    let rest = D::pose(m, "unloaded", &unloaded.q, &unloaded.loads)?;
    Ok(Picture { scene: scene::scene(m), rest, shapes, marks, motion, answer, view: D::VIEW })
}

/// The picture of an answer found with an `order = "auto"` flexure raised:
/// drawn on the mechanism it was found with, whose own solve meets the
/// target at those orders (or stops at the cap), so it is not raised again.
fn raised(args: &DrawArgs, used: &Model) -> Result<Picture, String> {
    used.visit(Draw(args, used))
}

/// The unloaded, assembled mechanism; with geoms that may touch, followed
/// to no load with its contacts (where the library checks that nothing
/// starts inside a geom), which the plain assembly refuses. A motion's
/// picture draws the assembly without its geoms: the motion checked its
/// start, and a body it drops on free sliders has no one equilibrium.
fn unloaded<D: Drawn>(m: &Mechanism<D>, motion: bool) -> flexure::Result<Solution<D>> {
    if pairs(m).is_empty() {
        return assemble_unloaded(m, &Settings::default());
    }
    if motion {
        let mut bare = m.clone();
        bare.geoms.clear();
        return assemble_unloaded(&bare, &Settings::default());
    }
    let zero = D::zero(&m.loads());
    follow_touching(m, None, &zero, &Settings::default(), &mut Workspace::new(m)).map(|(s, _)| s)
}

/// [`picture`] of the model's mechanism, which the door sends it of either dimension.
struct Draw<'a>(&'a DrawArgs, &'a Model);

impl<D: Drawn> Visit<D> for Draw<'_> {
    type Output = Result<Picture, String>;

    fn visit(self, m: &Mechanism<D>) -> Result<Picture, String> {
        picture(self.0, self.1, m)
    }
}

/// An SVG of the unloaded and loaded shapes (or a motion's snapshots and
/// charts), to one scale on both axes, with the warnings `solve` (or
/// `simulate`) gives on the same file.
pub fn draw_cmd(args: &DrawArgs) -> Result<Value, String> {
    let model = crate::input::read_model(&args.file)?;
    let p = model.visit(Draw(args, &model))?;
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
