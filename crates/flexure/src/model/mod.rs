//! The one door: a mechanism of either dimension, as its file's
//! `dimension` says, with every analysis the command line and Python call.
//! [`Model`] is the only code above the dimension that matches on it: each
//! method sends its mechanism to one function written once over
//! [`Analyses`], and every answer it gives is the same type in both
//! dimensions, serialized in one shape.

mod analyses;
mod flexure;
mod motion_error;
mod raise;

pub use analyses::Analyses;
pub use flexure::{
    Alpha, Bending, Compared, Deflect, Deflected, Deflection, ExactDeflected, ExactReference, FlexureAnalyses, Found,
    Headroom, OneFlexure, Posed, Refinement, RestCompliance, SpatialKeys, TipMotion, check_yield,
};
pub use motion_error::MotionEstimate;

use crate::dynamics::integrate::{MotionSettings, Trajectory};
use crate::dynamics::simulation::{SimulationSettings, Start};
use crate::error::{Error, Result};
use crate::estimate::{Accuracy, ValueEstimate};
use crate::mechanism::buckling::Buckling;
use crate::mechanism::contact::refuse_unsolved;
use crate::mechanism::findings::{Crossing, OpenClosure};
use crate::mechanism::statics::Settings;
use crate::mechanism::sweep::SweepLimit;
use crate::mechanism::{Dimension, Mechanism, file};
use crate::report::{BodyPose, EstimateFailed, Named, SolveReport, solve_report};
use crate::space::{Planar, Spatial};
use nalgebra::DMatrix;

/// A mechanism of either dimension.
#[derive(Debug, Clone, PartialEq)]
pub enum Model {
    /// A planar mechanism (no `dimension`, or `dimension = 2`).
    Planar(Mechanism<Planar>),
    /// A spatial mechanism (`dimension = 3`).
    Spatial(Mechanism<Spatial>),
}

/// `$body` for the model's mechanism, with `D` its dimension: the one match.
macro_rules! each {
    ($model:expr, $m:ident => $body:expr) => {
        match $model {
            Model::Planar($m) => $body,
            Model::Spatial($m) => $body,
        }
    };
}

/// What a front end does with a model's mechanism, written once over the
/// dimension and handed to [`Model::visit`], which matches on the
/// dimension for it: a front end's own work that needs the mechanism's
/// type (the CLI's picture), so that the door stays the one match. A
/// visitor is usually one generic impl, `impl<D: Bound> Visit<D> for V`,
/// bounded by what its work needs.
pub trait Visit<D: Dimension> {
    /// What the visit answers, the same in both dimensions.
    type Output;
    /// The work on the mechanism.
    fn visit(self, m: &Mechanism<D>) -> Self::Output;
}

/// What [`Model::solve`] answers.
#[derive(Debug)]
pub struct Solved {
    /// The equilibrium's coordinates.
    pub q: Vec<f64>,
    /// The solve report, or the flexure joint whose error estimate failed.
    pub report: std::result::Result<SolveReport, EstimateFailed>,
    /// The compliance asked for: (3 × 3, rows φ, x, y) or (6 × 6, rows rx, ry, rz, x, y, z).
    pub compliance: Option<DMatrix<f64>>,
    /// The parts that cross in the answer.
    pub crossings: Vec<Crossing<Vec<f64>>>,
    /// The model the answer was found with: the one solved, its flexure
    /// joints of `order = "auto"` raised where their estimate missed the
    /// target (`q` is its coordinates; [`Model::orders`] says the orders used).
    pub model: Model,
    /// The flexure joints of `order = "auto"` whose estimate still misses
    /// the target at the cap (order 64): flagged, with nothing left to raise.
    pub capped: Vec<String>,
}

/// What [`Model::sweep`] answers: a table of one row per value reached
/// stably, and what the rows say.
#[derive(Debug)]
pub struct Swept {
    /// The columns: the swept load, each moving body's pose coordinates
    /// (`NAME.x`, …), each joint's coordinates (`JOINT[i]`), `energy`, the
    /// peak stress of each flexure with a section (`JOINT.stress`, Pa), and
    /// the compliance's entries if asked for (`compliance.RC`).
    pub columns: Vec<String>,
    /// One row of numbers per value reached, in the columns' order.
    pub rows: Vec<Vec<f64>>,
    /// Each row's coordinates (what a picture draws).
    pub q: Vec<Vec<f64>>,
    /// Each row's contacts (what a picture draws of them), as
    /// [`SolveReport::contacts`]: `None` where no pair may touch.
    pub contacts: Option<Vec<Vec<crate::mechanism::contact::Contact>>>,
    /// Each moving body (the ground left out) by name, with its pose at each row.
    pub bodies: Vec<(String, Vec<BodyPose>)>,
    /// The parts that cross, by row, where any do.
    pub crossings: Vec<(usize, Vec<Crossing<Vec<f64>>>)>,
    /// Where stability was first lost, if it was.
    pub stability_limit: Option<SweepLimit>,
    /// The value at which a solve failed and ended the sweep, and why.
    pub stopped: Option<(f64, Error)>,
    /// The values at which a flexure's error estimate misses the target.
    pub flagged: Vec<f64>,
    /// Each flexure joint with a `yield_strength` that a row stresses past
    /// it: the joint, the first such value, and its peak stress there (Pa).
    pub yielded: Vec<(String, f64, f64)>,
    /// The model every row was found with, as [`Solved::model`]: a flexure
    /// joint of `order = "auto"` raised where its estimate missed at a row,
    /// to the order the row that asks for most needs, the same for all rows.
    pub model: Model,
    /// The flexure joints of `order = "auto"` whose estimate still misses
    /// the target at a row at the cap (order 64), as [`Solved::capped`].
    pub capped: Vec<String>,
}

/// What [`Model::simulate`] answers: the integrator's samples, every
/// moving body's pose at each, and the parts that cross.
#[derive(Debug)]
pub struct Motion {
    /// The samples: times, coordinates, rates, energy, counts.
    pub trajectory: Trajectory,
    /// Why the run ended before its duration, if it did; the samples are those reached.
    pub stopped: Option<Error>,
    /// Each moving body (the ground left out) by name, with its pose at each sample.
    pub bodies: Vec<(String, Vec<BodyPose>)>,
    /// The parts that cross, by sample, where any do.
    pub crossings: Vec<(usize, Vec<Crossing<Vec<f64>>>)>,
    /// The contacts at each sample, where the mechanism has geoms a part may touch.
    pub contacts: Vec<Vec<crate::mechanism::contact::Contact>>,
    /// Where contacts touched and opened, in time.
    pub changes: Vec<crate::dynamics::contact::ContactChange>,
}

/// What [`Model::buckle`] and [`Model::modes`] answer: the analysis on the
/// mechanism it was found with (flexures of `order = "auto"` raised) and
/// its estimate. The closures open at rest are [`Model::open_closures`],
/// which a caller tells before the analysis, whether it succeeds or not.
#[derive(Debug)]
pub struct Eigen<T> {
    /// The answer.
    pub answer: T,
    /// Its error estimate.
    pub estimate: ValueEstimate,
    /// The model it was found with.
    pub model: Model,
}

impl Model {
    /// Parses a mechanism file of either dimension: [`file::from_toml`] or
    /// [`file::spatial_from_toml`], as its `dimension` says.
    ///
    /// # Example
    /// ```
    /// use flexure::model::Model;
    /// let m = Model::from_toml("dimension = 3\n[[joint]]\nname = \"ball\"\nkind = \"spherical\"\nparent = \"ground\"\nchild = \"bob\"\n").unwrap();
    /// assert_eq!((m.dimension(), m.dof()), (3, 3));
    /// assert!(Model::from_toml("dimension = 4").unwrap_err().to_string().contains("dimension = 4"));
    /// ```
    pub fn from_toml(text: &str) -> Result<Self> {
        Self::from_document(file::Document::parse(text)?)
    }

    /// The mechanism of a file already parsed, as its `dimension` says.
    pub fn from_document(document: file::Document<'_>) -> Result<Self> {
        match document.dimension() {
            3 => document.spatial().map(Model::Spatial),
            _ => document.planar().map(Model::Planar),
        }
    }

    /// `visitor`'s work on the mechanism, whichever its dimension.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::{Dimension, Mechanism};
    /// use flexure::model::{Model, Visit};
    /// struct Twists;
    /// impl<D: Dimension> Visit<D> for Twists {
    ///     type Output = usize;
    ///     fn visit(self, m: &Mechanism<D>) -> usize {
    ///         D::TWIST_DIM * m.bodies.len()
    ///     }
    /// }
    /// let m = Model::from_toml("dimension = 3\n[[joint]]\nname = \"ball\"\nkind = \"spherical\"\nparent = \"ground\"\nchild = \"bob\"\n").unwrap();
    /// assert_eq!(m.visit(Twists), 12);
    /// ```
    pub fn visit<V, T>(&self, visitor: V) -> T
    where
        V: Visit<Planar, Output = T> + Visit<Spatial, Output = T>,
    {
        each!(self, m => visitor.visit(m))
    }

    /// 2 or 3.
    pub fn dimension(&self) -> u8 {
        match self {
            Model::Planar(_) => 2,
            Model::Spatial(_) => 3,
        }
    }

    /// The number of generalized coordinates.
    pub fn dof(&self) -> usize {
        each!(self, m => m.dof())
    }

    /// The flexure joints' names, in joint order (the order of an
    /// estimate's per-flexure lists).
    pub fn flexure_names(&self) -> Vec<String> {
        each!(self, m => flexure_names(m))
    }

    /// A flexure joint's length (m), by name.
    pub fn flexure_length(&self, name: &str) -> Option<f64> {
        each!(self, m => flexure_length(m, name))
    }

    /// Each flexure joint's orders, by name: one number in the plane, three
    /// (twist, bendings about y and z) in space.
    pub fn orders(&self) -> Named<Vec<usize>> {
        each!(self, m => orders(m))
    }

    /// Whether a flexure has `order = "auto"`.
    pub fn auto_order(&self) -> bool {
        each!(self, m => m.joints.iter().any(|j| j.auto_order))
    }

    /// Whether a flexure joint asks for a yield strength's check, and which.
    pub fn yield_strength(&self, name: &str) -> Option<f64> {
        each!(self, m => m.joints.iter().find(|j| j.name == name).and_then(|j| j.report.yield_strength))
    }

    /// The body named `name`, if any.
    pub fn body(&self, name: &str) -> Option<usize> {
        each!(self, m => m.body(name))
    }

    /// The bodies' names, the ground first.
    pub fn body_names(&self) -> Vec<String> {
        each!(self, m => m.bodies.iter().map(|b| b.name.clone()).collect())
    }

    /// The column of each pair that may touch, `contact.GEOM.PART.normal_force`,
    /// in the order of [`crate::mechanism::contact::column_pairs`] (a sweep's, and
    /// a motion's [`crate::dynamics::integrate::Sample::columns`]).
    pub fn contact_columns(&self) -> Vec<String> {
        use crate::mechanism::contact::{column, column_pairs};
        each!(self, m => column_pairs(m).iter().map(|p| format!("{}.normal_force", column(m, p))).collect())
    }

    /// Each body's pose in the world at coordinates `q`, the ground first,
    /// as [`Model::simulate`] gives them at each sample.
    pub fn body_poses(&self, q: &[f64]) -> Vec<BodyPose> {
        each!(self, m => body_poses(m, q))
    }

    /// The compliance of the frame at point `at` (2 or 3 numbers, as the
    /// dimension) of body `body` at the loaded equilibrium, as
    /// [`Model::solve`] gives it, without the report.
    pub fn compliance(&self, body: &str, at: &[f64]) -> Result<DMatrix<f64>> {
        each!(self, m => {
            let b = m.body(body).ok_or_else(|| no_body(body))?;
            let s = Analyses::solve(m, &Settings::default())?;
            Analyses::compliance(m, &s, b, at)
        })
    }

    /// The closures open at rest ([`crate::mechanism::findings::open_closures`]).
    pub fn open_closures(&self) -> Result<Vec<OpenClosure>> {
        each!(self, m => open_closures(m))
    }

    /// The equilibrium's report against `target`, with the compliance of the
    /// frame at point `at` (2 or 3 numbers, as the dimension) of body
    /// `compliance` and the parts that cross.
    ///
    /// # Example
    /// ```
    /// use flexure::model::Model;
    /// let text = "[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"link\"\nlength = 0.05\nei = 0.01\n\
    ///             [[force]]\nbody = \"link\"\nat = [0.05, 0.0]\nforce = [0.0, 0.1]\n";
    /// let m = Model::from_toml(text).unwrap();
    /// let s = m.solve(&Default::default(), Some(("link", &[0.0, 0.0]))).unwrap();
    /// let r = s.report.unwrap();
    /// assert!(r.stable && r.dimension == 2 && s.crossings.is_empty());
    /// // The tip's compliance along y (the link's frame is the tip's) is L³/3EI to first order.
    /// assert!((s.compliance.unwrap()[(2, 2)] / (0.05f64.powi(3) / 0.03) - 1.0).abs() < 0.05);
    /// // With order = "auto", under 8 N across the tip of a unit strip: order 3 misses the
    /// // target, so the joint is raised until it meets it.
    /// let text = "[[joint]]\nname = \"f\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\n\
    ///             order = \"auto\"\n[[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\nforce = [0.0, 8.0]\n";
    /// let s = Model::from_toml(text).unwrap().solve(&Default::default(), None).unwrap();
    /// let order = s.model.orders().get("f").unwrap()[0];
    /// assert!(!s.report.unwrap().flagged && order > 3 && s.q.len() == order && s.capped.is_empty());
    /// ```
    ///
    /// A flexure joint of `order = "auto"` whose estimate misses `target` is
    /// raised (to its reference's order and quadrature, or orders and
    /// subintervals, up to 64), and the mechanism solved again, until it
    /// meets it: only such joints, with contact too ([`crate::estimate::contact_estimates`]).
    /// [`Solved::model`] is the mechanism the answer was found with;
    /// [`Solved::capped`] names those still missing at the cap.
    pub fn solve(&self, target: &Accuracy, compliance: Option<(&str, &[f64])>) -> Result<Solved> {
        each!(self, m => solve(m, target, compliance))
    }

    /// Equilibria along `values` of the load named `parameter` (as
    /// `tendon.NAME.tension`, `force.NAME.fx`, `gravity.y`: the dimension's
    /// names), each row with its estimate against `target` and, with
    /// `compliance`, the compliance of that frame ([`Model::solve`]). The
    /// outer error is the sweep's (bad input); the inner, a flexure joint
    /// whose error estimate failed at a row. A flexure joint of
    /// `order = "auto"` that misses at a row is raised as [`Model::solve`]
    /// raises it, once for all rows (every row then has the same columns),
    /// to the order the row that asks most needs, and the sweep run again.
    ///
    /// # Example
    /// ```
    /// use flexure::model::Model;
    /// let text = "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
    ///             [[force]]\nname = \"push\"\nbody = \"arm\"\nat = [0.1, 0.0]\n";
    /// let m = Model::from_toml(text).unwrap();
    /// // A sprung arm (k = 1 N·m/rad, l = 0.1 m) pushed along itself loses stability at P = k/l = 10 N.
    /// let s = m.sweep("force.push.fx", &[0.0, -4.0, -8.0, -12.0], &Default::default(), None).unwrap().unwrap();
    /// assert_eq!(s.columns[..4], ["force.push.fx", "arm.x", "arm.y", "arm.phi"]);
    /// assert_eq!(s.rows.len(), 3);
    /// assert!((s.stability_limit.unwrap().value + 10.0).abs() < 1e-4);
    /// ```
    pub fn sweep(
        &self,
        parameter: &str,
        values: &[f64],
        target: &Accuracy,
        compliance: Option<(&str, &[f64])>,
    ) -> Result<std::result::Result<Swept, EstimateFailed>> {
        each!(self, m => sweep(m, (parameter, values), target, compliance))
    }

    /// The motion under the loads and their schedules from `start` (the
    /// file's `[initial]` and `[initial_velocity]` override it), with every
    /// moving body's pose and the parts that cross at each sample.
    ///
    /// # Example
    /// ```
    /// use flexure::dynamics::integrate;
    /// use flexure::dynamics::simulation::{SimulationSettings, Start};
    /// use flexure::model::Model;
    /// // A sprung arm (k = 1 N·m/rad) carrying 0.1 kg at 0.1 m, let go from 0.1 rad:
    /// // it swings about its rest with ω² = k/(m l²) = 1000 rad²/s².
    /// let m = Model::from_toml("[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
    ///     [[body]]\nname = \"arm\"\nmass = 0.1\ncom = [0.1, 0.0]\n[initial]\npivot = [0.1]\n").unwrap();
    /// let half = std::f64::consts::PI / 1000f64.sqrt();
    /// let motion = integrate::MotionSettings { duration: half, every: half, ..Default::default() };
    /// let run = m.simulate(&SimulationSettings { motion, ..Default::default() }, Start::Rest).unwrap();
    /// assert!((run.trajectory.q(1)[0] + 0.1).abs() < 1e-5 && run.stopped.is_none());
    /// assert_eq!((run.bodies[0].0.as_str(), run.bodies[0].1.len()), ("arm", 2));
    /// ```
    pub fn simulate(&self, settings: &SimulationSettings, start: Start) -> Result<Motion> {
        each!(self, m => simulate(m, settings, start, true))
    }

    /// The error estimate of `run`, a [`Model::simulate`] of this model
    /// with `settings` from `start`: against a reference run at a tenth of
    /// its tolerances ([`MotionEstimate`]), held to `target` with positions
    /// scaled by the mechanism's size.
    ///
    /// # Errors
    /// A tolerance below 1e-13 (no tighter run is left) or an invalid
    /// target, by name; the reference run's failure to start.
    ///
    /// # Example
    /// ```
    /// use flexure::dynamics::integrate::MotionSettings;
    /// use flexure::dynamics::simulation::{SimulationSettings, Start};
    /// use flexure::model::Model;
    /// // A sprung arm released from 0.1 rad: 20 s at a coarse tolerance.
    /// let m = Model::from_toml(
    ///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\n\
    ///      stiffness = 2.0\n[[body]]\nname = \"arm\"\ninertia = 0.5\ncom = [0.1, 0.0]\n[initial]\npin = 0.1\n",
    /// )?;
    /// let motion = MotionSettings { duration: 20.0, every: 2.0, tolerance: 1e-3, absolute: 1e-3, ..Default::default() };
    /// let settings = SimulationSettings { motion, ..Default::default() };
    /// let run = m.simulate(&settings, Start::Equilibrium)?;
    /// let e = m.motion_error(&settings, Start::Equilibrium, &run, &Default::default())?;
    /// // The closed form: φ(t) = 0.1 cos 2t (ω² = k/I = 4). The estimate is
    /// // near the run's true largest angle error.
    /// let truth = (0..run.trajectory.time.len())
    ///     .map(|k| (run.trajectory.q(k)[0] - 0.1 * (2.0 * run.trajectory.time[k]).cos()).abs())
    ///     .fold(0.0, f64::max);
    /// assert!(e.complete && e.samples == 11 && e.angle > 0.5 * truth && e.angle < 2.0 * truth, "{e:?} {truth}");
    /// # Ok::<(), flexure::Error>(())
    /// ```
    pub fn motion_error(
        &self,
        settings: &SimulationSettings,
        start: Start,
        run: &Motion,
        target: &Accuracy,
    ) -> Result<MotionEstimate> {
        target.validate()?;
        let motion = settings.motion;
        if motion.tolerance / 10.0 < 1e-14 {
            return Err(Error::invalid(
                "tolerance",
                motion.tolerance,
                "leaves the error estimate no run at a tenth of it (the finest is 1e-14): at least 1e-13",
            ));
        }
        let max_steps = motion.max_steps.map(|n| n.saturating_mul(3).min(crate::dynamics::integrate::MAX_STEPS));
        let reference = MotionSettings {
            tolerance: motion.tolerance / 10.0,
            absolute: motion.absolute / 10.0,
            max_steps,
            ..motion
        };
        // The reference needs only its bodies' poses, not the parts that cross.
        let reference_settings = SimulationSettings { motion: reference, ..*settings };
        let reference_run = each!(self, m => simulate(m, &reference_settings, start, false))?;
        let size = each!(self, m => m.size());
        Ok(motion_error::motion_error(run, &reference_run, (reference.tolerance, size), target))
    }

    /// The factor on all loads, up to `max_factor`, at which the
    /// equilibrium followed from no load stops being stable, or up to which
    /// it stays stable; with contact, the load followed in order, its
    /// contacts sticking and sliding as they do along it
    /// ([`crate::mechanism::stability_limit::stability_limit`]). It is the
    /// limit of this mechanism at its flexures' orders: call it on
    /// [`Solved::model`] for those `solve` raised to.
    ///
    /// # Example
    /// ```
    /// use flexure::model::Model;
    /// // A sprung arm (k = 1 N·m/rad, l = 0.1 m) pushed along itself by 4 N
    /// // loses stability at P = k/l = 10 N, 2.5 times the load.
    /// let text = "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
    ///             [[force]]\nname = \"push\"\nbody = \"arm\"\nat = [0.1, 0.0]\nforce = [-4.0, 0.0]\n";
    /// let limit = Model::from_toml(text).unwrap().stability_limit(1000.0).unwrap();
    /// assert!((limit.factor() - 2.5).abs() < 1e-5);
    /// ```
    pub fn stability_limit(&self, max_factor: f64) -> Result<crate::StabilityLimit> {
        each!(self, m => crate::mechanism::stability_limit::stability_limit(m, &Settings::default(), max_factor))
    }

    /// Linear buckling on all loads, with its estimate ([`Analyses::buckle`]).
    pub fn buckle(&self, target: &Accuracy) -> Result<Eigen<Buckling>> {
        each!(self, m => {
            refuse_unsolved(m)?;
            let (used, answer, estimate) = Analyses::buckle(m, &Settings::default(), target)?;
            Ok(Eigen { answer, estimate, model: used.into() })
        })
    }

    /// `count` vibration modes about the loaded equilibrium, with their estimate ([`Analyses::modes`]).
    pub fn modes(&self, count: usize, target: &Accuracy) -> Result<Eigen<crate::dynamics::modes::Modes>> {
        each!(self, m => {
            let (used, answer, estimate) = Analyses::modes(m, &Settings::default(), count, target)?;
            Ok(Eigen { answer, estimate, model: used.into() })
        })
    }

    /// The mechanism as a rigid-body model for a simulator ([`crate::export::export`];
    /// a spatial one to MJCF only, [`crate::export::spatial::export`]).
    pub fn export(&self, options: &crate::export::Options) -> Result<crate::export::Export> {
        each!(self, m => refuse_unsolved(m))?;
        match self {
            Model::Planar(m) => crate::export::export(m, options),
            Model::Spatial(m) => crate::export::spatial::export(m, options),
        }
    }

    /// The reference model of an eigenvalue estimate `e` of this model, in
    /// words: each flexure at the order(s) and points or subintervals it was refined to.
    pub fn reference_of(&self, e: &ValueEstimate) -> String {
        if e.reference_orders.is_empty() {
            return "the same mechanism: it has no flexure to refine".into();
        }
        let [order, count] = each!(self, m => refined(m));
        let parts: Vec<String> = (self.flexure_names().iter().zip(&e.reference_orders))
            .map(|(n, (o, q))| format!("{n:?} at {order} {o} with {q} {count}"))
            .collect();
        format!("the mechanism with {}", parts.join(", "))
    }

    /// Each joint with coordinates: its name and its coordinates' range in `q`.
    pub fn coordinates(&self) -> Vec<(String, std::ops::Range<usize>)> {
        self.joints().into_iter().filter(|(_, r)| !r.is_empty()).collect()
    }

    /// Every joint, in joint order: its name and its coordinates' range in `q` (empty for a fixed joint).
    pub fn joints(&self) -> Vec<(String, std::ops::Range<usize>)> {
        each!(self, m => joints(m))
    }
}

impl From<Mechanism<Planar>> for Model {
    fn from(m: Mechanism<Planar>) -> Self {
        Model::Planar(m)
    }
}

impl From<Mechanism<Spatial>> for Model {
    fn from(m: Mechanism<Spatial>) -> Self {
        Model::Spatial(m)
    }
}

fn joints<D: Analyses>(m: &Mechanism<D>) -> Vec<(String, std::ops::Range<usize>)> {
    m.joints.iter().map(|j| (j.name.clone(), j.offset..j.offset + j.kind.joint().dof())).collect()
}

fn refined<D: Analyses>(_: &Mechanism<D>) -> [&'static str; 2] {
    D::REFINED
}

fn flexure_names<D: Analyses>(m: &Mechanism<D>) -> Vec<String> {
    m.joints.iter().filter(|j| j.kind.flexure().is_some()).map(|j| j.name.clone()).collect()
}

fn flexure_length<D: Analyses>(m: &Mechanism<D>, name: &str) -> Option<f64> {
    m.joints.iter().find(|j| j.name == name).and_then(|j| j.kind.flexure()).map(D::flexure_length)
}

fn orders<D: Analyses>(m: &Mechanism<D>) -> Named<Vec<usize>> {
    Named(m.joints.iter().filter_map(|j| Some((j.name.clone(), D::orders(j.kind.flexure()?)))).collect())
}

fn open_closures<D: Analyses>(m: &Mechanism<D>) -> Result<Vec<OpenClosure>> {
    D::open_closures(m, &Settings::default())
}

fn solve<D: Analyses>(m: &Mechanism<D>, target: &Accuracy, compliance: Option<(&str, &[f64])>) -> Result<Solved>
where
    Model: From<Mechanism<D>>,
{
    let body = match compliance {
        Some((name, at)) => Some((m.body(name).ok_or_else(|| no_body(name))?, at)),
        None => None,
    };
    let (used, (s, report)) = raise::raising(m, |m| {
        let s = D::solve(m, &Settings::default())?;
        let report = solve_report(m, &s, target);
        Ok((s, report))
    })?;
    let capped = raise::capped(&used, &report.iter().map(|r| (s.q.as_slice(), r)).collect::<Vec<_>>());
    let crossings = D::crossings(&used, &s.q);
    let compliance = body.map(|(b, at)| D::compliance(&used, &s, b, at)).transpose()?;
    Ok(Solved { q: s.q, report, compliance, crossings, model: used.into_owned().into(), capped })
}

fn sweep<D: Analyses>(
    m: &Mechanism<D>,
    (parameter, values): (&str, &[f64]),
    target: &Accuracy,
    compliance: Option<(&str, &[f64])>,
) -> Result<std::result::Result<Swept, EstimateFailed>>
where
    Model: From<Mechanism<D>>,
{
    let frame = match compliance {
        Some((name, at)) => Some((m.body(name).ok_or_else(|| no_body(name))?, at)),
        None => None,
    };
    let (used, (out, reports)) = raise::raising(m, |m| {
        let out = D::sweep(m, parameter, values, &Settings::default())?;
        let reports = out.rows.iter().map(|(_, s)| solve_report(m, s, target)).collect();
        Ok((out, reports))
    })?;
    let reports = match reports {
        Ok(reports) => reports,
        Err(failed) => return Ok(Err(failed)),
    };
    let capped = raise::capped(&used, &out.rows.iter().map(|(_, s)| s.q.as_slice()).zip(&reports).collect::<Vec<_>>());
    let m = used.as_ref();
    let touching = crate::mechanism::contact::column_pairs(m);
    let mut columns = vec![parameter.to_string()];
    let poses = <D as crate::report::Reported>::poses(m, &m.rest());
    for (b, pose) in m.bodies.iter().zip(&poses).skip(1) {
        columns.extend(pose.columns().iter().map(|c| format!("{}.{c}", b.name)));
    }
    for j in &m.joints {
        columns.extend((0..j.kind.joint().dof()).map(|i| format!("{}[{i}]", j.name)));
    }
    columns.push("energy".into());
    // Each pair's normal force (N), summed over its contacts: 0 while open.
    columns.extend(touching.iter().map(|p| format!("{}.normal_force", crate::mechanism::contact::column(m, p))));
    let (mut rows, mut flagged, mut yielded) = (Vec::new(), Vec::new(), Vec::<(String, f64, f64)>::new());
    let mut bodies: Vec<(String, Vec<BodyPose>)> = m.bodies[1..].iter().map(|b| (b.name.clone(), Vec::new())).collect();
    for (k, ((value, s), report)) in out.rows.iter().zip(&reports).enumerate() {
        if k == 0 {
            columns.extend(report.stress.0.iter().map(|(name, _)| format!("{name}.stress")));
        }
        let mut row = vec![*value];
        row.extend(report.bodies.0.iter().skip(1).flat_map(|(_, p)| p.coordinates()));
        for (body, (_, pose)) in bodies.iter_mut().zip(report.bodies.0.iter().skip(1)) {
            body.1.push(*pose);
        }
        row.extend(&s.q);
        row.push(s.energy);
        // + 0.0: an empty sum is −0.
        row.extend(
            touching
                .iter()
                .map(|p| s.contacts.iter().filter(|c| c.pair.parts(p)).map(|c| c.normal_force).sum::<f64>() + 0.0),
        );
        row.extend(report.stress.0.iter().map(|(_, p)| p.max));
        if let Some((b, at)) = frame {
            let c = D::compliance(m, s, b, at)?;
            row.extend(c.row_iter().flat_map(|r| r.iter().copied().collect::<Vec<_>>()));
        }
        rows.push(row);
        if report.flagged {
            flagged.push(*value);
        }
        for (name, p) in &report.stress.0 {
            let strength = m.joints.iter().find(|j| &j.name == name).and_then(|j| j.report.yield_strength);
            if strength.is_some_and(|y| p.max > y) && !yielded.iter().any(|(n, ..)| n == name) {
                yielded.push((name.clone(), *value, p.max));
            }
        }
    }
    if frame.is_some() {
        let axes = D::COMPLIANCE_AXES;
        columns.extend(axes.iter().flat_map(|r| axes.iter().map(move |c| format!("compliance.{r}{c}"))));
    }
    let shapes: Vec<&[f64]> = out.rows.iter().map(|(_, s)| s.q.as_slice()).collect();
    let crossings = D::crossings_along(m, &shapes);
    let q = shapes.iter().map(|q| q.to_vec()).collect();
    let contacts = (!touching.is_empty()).then(|| out.rows.iter().map(|(_, s)| s.contacts.clone()).collect());
    let (stability_limit, stopped) = (out.stability_limit, out.stopped);
    let model = used.into_owned().into();
    Ok(Ok(Swept {
        columns,
        rows,
        q,
        contacts,
        bodies,
        crossings,
        stability_limit,
        stopped,
        flagged,
        yielded,
        model,
        capped,
    }))
}

/// The motion of `m`, with the parts that cross at its samples when `crossings`.
fn simulate<D: Analyses>(
    m: &Mechanism<D>,
    settings: &SimulationSettings,
    start: Start,
    crossings: bool,
) -> Result<Motion> {
    let crate::dynamics::Simulation { trajectory, stopped, contacts, changes, .. } = D::simulate(m, settings, start)?;
    let samples: Vec<&[f64]> = (0..trajectory.time.len()).map(|k| trajectory.q(k)).collect();
    let mut bodies: Vec<(String, Vec<BodyPose>)> = m.bodies[1..].iter().map(|b| (b.name.clone(), Vec::new())).collect();
    for q in &samples {
        for (body, pose) in bodies.iter_mut().zip(body_poses(m, q).into_iter().skip(1)) {
            body.1.push(pose);
        }
    }
    let crossings = if crossings { D::crossings_along(m, &samples) } else { Vec::new() };
    Ok(Motion { trajectory, stopped, bodies, crossings, contacts, changes })
}

fn body_poses<D: Analyses>(m: &Mechanism<D>, q: &[f64]) -> Vec<BodyPose> {
    <D as crate::report::Reported>::poses(m, q)
}

fn no_body(name: &str) -> Error {
    Error::invalid("compliance", format!("{name:?}"), "names no body of the mechanism")
}
