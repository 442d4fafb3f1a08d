//! The one door: a mechanism of either dimension, as its file's
//! `dimension` says, with every analysis the command line and Python call.
//! [`Model`] is the only code above the dimension that matches on it: each
//! method sends its mechanism to one function written once over
//! [`Analyses`], and every answer it gives is the same type in both
//! dimensions, serialized in one shape.

mod analyses;

pub use analyses::Analyses;

use crate::error::{Error, Result};
use crate::estimate::{Accuracy, ValueEstimate};
use crate::mechanism::buckling::Buckling;
use crate::mechanism::findings::{Crossing, OpenClosure};
use crate::mechanism::statics::Settings;
use crate::mechanism::{Mechanism, file};
use crate::report::{EstimateFailed, Named, SolveReport, solve_report};
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
        if text.len() <= file::MAX_TEXT_BYTES && file::dimension(text)? == 3 {
            return file::spatial_from_toml(text).map(Model::Spatial);
        }
        file::from_toml(text).map(Model::Planar)
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
    /// ```
    pub fn solve(&self, target: &Accuracy, compliance: Option<(&str, &[f64])>) -> Result<Solved> {
        each!(self, m => solve(m, target, compliance))
    }

    /// Linear buckling on all loads, with its estimate ([`Analyses::buckle`]).
    pub fn buckle(&self, target: &Accuracy) -> Result<Eigen<Buckling>> {
        each!(self, m => {
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
        each!(self, m => coordinates(m))
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

fn coordinates<D: Analyses>(m: &Mechanism<D>) -> Vec<(String, std::ops::Range<usize>)> {
    let dof = |j: &crate::mechanism::JointSpec<D>| D::joint(&j.kind).dof();
    m.joints.iter().filter(|j| dof(j) > 0).map(|j| (j.name.clone(), j.offset..j.offset + dof(j))).collect()
}

fn refined<D: Analyses>(_: &Mechanism<D>) -> [&'static str; 2] {
    D::REFINED
}

fn flexure_names<D: Analyses>(m: &Mechanism<D>) -> Vec<String> {
    m.joints.iter().filter(|j| D::flexure(&j.kind).is_some()).map(|j| j.name.clone()).collect()
}

fn flexure_length<D: Analyses>(m: &Mechanism<D>, name: &str) -> Option<f64> {
    m.joints.iter().find(|j| j.name == name).and_then(|j| D::flexure(&j.kind)).map(D::flexure_length)
}

fn orders<D: Analyses>(m: &Mechanism<D>) -> Named<Vec<usize>> {
    Named(m.joints.iter().filter_map(|j| Some((j.name.clone(), D::orders(D::flexure(&j.kind)?)))).collect())
}

fn open_closures<D: Analyses>(m: &Mechanism<D>) -> Result<Vec<OpenClosure>> {
    D::open_closures(m, &Settings::default())
}

fn solve<D: Analyses>(m: &Mechanism<D>, target: &Accuracy, compliance: Option<(&str, &[f64])>) -> Result<Solved> {
    let body = match compliance {
        Some((name, at)) => Some((m.body(name).ok_or_else(|| no_body(name))?, at)),
        None => None,
    };
    let s = D::solve(m, &Settings::default())?;
    let crossings = D::crossings(m, &s.q);
    let report = solve_report(m, &s, target);
    let compliance = body.map(|(b, at)| D::compliance(m, &s, b, at)).transpose()?;
    Ok(Solved { q: s.q, report, compliance, crossings })
}

fn no_body(name: &str) -> Error {
    Error::invalid("compliance", format!("{name:?}"), "names no body of the mechanism")
}
