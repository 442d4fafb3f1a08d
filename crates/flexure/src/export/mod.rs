//! Export a mechanism as a rigid-body model for simulators: MuJoCo's MJCF,
//! Gazebo's SDFormat and ROS's URDF, each flexure replaced by a
//! pseudo-rigid-body (PRB) chain fitted to the Smooth Curvature Model over
//! the loads the mechanism meets.
//!
//! [`export`] does it in four steps, and returns the XML as a `String` (the
//! library writes no file):
//!
//! 1. **The loads each flexure meets** ([`wrench`]): the mechanism is
//!    solved along its own loads times each fraction $\lambda$ of a
//!    [`LoadRange`] (by default 12 values from 0 to 1), each equilibrium
//!    continued from the last, and at each the wrench $w_j$ at flexure
//!    $j$'s tip, in its root frame, is the least-squares solution of
//!    $\nabla U_j(\alpha_j) = \mathcal J_j(\alpha_j)^T w_j$ (exact unless the
//!    flexure weighs itself, which is then warned of).
//! 2. **The fit** ([`crate::prb::fit_along`]): each flexure's chain (1R: Howell's
//!    characteristic pivot $\gamma L$ and spring $K_\Theta$; 3R: Su's) is
//!    fitted to the model's tip poses at those equilibria (the shapes the
//!    mechanism reaches, not each wrench held dead from rest), with the
//!    largest tip position and angle error of the chain against the model;
//!    a fit more than 1 % of $L$ or 1° off is flagged, with a warning.
//! 3. **The rigid-body model** ([`model::build`]): bodies keep their names,
//!    frames, masses, inertias and centres of mass; each flexure becomes its
//!    hinges, with links `NAME_prbK` between them and its own mass lumped
//!    on the links it moves with, or, massless in MJCF, its hinges all on
//!    the child body (its links merged away); revolute joints are hinges, prismatic
//!    joints slides, fixed joints rigid attachments. The rest pose is the
//!    file's rest configuration. Sized for a simulator's step
//!    ([`step::size`]): a sprung joint whose own link would ring faster than
//!    10 steps gets the armature that slows it to that.
//! 4. **The format** ([`mjcf`], [`sdf`], [`urdf`]): what a format cannot
//!    hold is named in a warning ([`Export::warnings`]); nothing is dropped
//!    silently.
//!
//! # Example
//! ```
//! use flexure::export::{export, Format, Options};
//! use flexure::prb::PrbKind;
//! use flexure::mechanism::file::from_toml;
//! let m = from_toml(r#"
//! [[joint]]
//! name = "hinge"
//! kind = "flexure"
//! parent = "ground"
//! child = "arm"
//! length = 0.02
//! ei = 1.0e-3
//!
//! [[force]]
//! name = "tip"
//! body = "arm"
//! at = [0.0, 0.0]
//! force = [0.0, -0.5]
//! "#)?;
//! let e = export(&m, &Options { format: Format::Mjcf, prb: PrbKind::OneR, ..Default::default() })?;
//! assert!(e.xml.contains(r#"<body name="arm""#) && e.xml.contains(r#"<joint name="hinge" type="hinge""#));
//! let fit = &e.report.joints[0].1;
//! // An end force across the strip: Howell's characteristic radius factor is
//! // near 0.85 (0.83 over this range), and the tip is within 1 % of L; its
//! // angle is Howell's Θ, not the strip's c_θ Θ, and past 1° off it is flagged.
//! assert!((fit.gamma[1] - 0.85).abs() < 0.05 && fit.error.position < 0.01 * 0.02);
//! assert_eq!(fit.flagged, fit.error.angle > flexure::export::ANGLE_FLAG);
//! // The default chain, 3R, holds both.
//! let e = export(&m, &Options::default())?;
//! assert!(!e.report.joints[0].1.flagged && e.xml.contains(r#"<joint name="hinge_3""#));
//! # Ok::<(), flexure::Error>(())
//! ```

pub mod lump;
pub mod mjcf;
pub mod model;
mod range;
pub mod sdf;
pub mod spatial;
pub mod step;
pub mod urdf;
pub mod wrench;
pub mod xml;

pub use range::{LoadRange, MAX_SAMPLES};

use crate::error::{Error, Result};
use crate::mechanism::Mechanism;
use crate::mechanism::statics::Settings;
use crate::prb::{self, PrbFit, PrbKind};
use model::Chain;
use serde::ser::{SerializeMap, SerializeStruct};

/// The formats written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Format {
    /// MuJoCo's MJCF.
    #[default]
    Mjcf,
    /// SDFormat 1.9 (Gazebo).
    Sdf,
    /// URDF (ROS).
    Urdf,
}

impl std::str::FromStr for Format {
    type Err = Error;

    /// `mjcf`, `sdf` or `urdf`.
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "mjcf" => Ok(Format::Mjcf),
            "sdf" => Ok(Format::Sdf),
            "urdf" => Ok(Format::Urdf),
            _ => Err(Error::invalid("to", format!("{s:?}"), "must be mjcf, sdf or urdf")),
        }
    }
}

impl Format {
    /// Its name, as [`std::str::FromStr`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            Format::Mjcf => "mjcf",
            Format::Sdf => "sdf",
            Format::Urdf => "urdf",
        }
    }
}

/// What to export, and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// The format.
    pub format: Format,
    /// The PRB chain of every flexure: 3R by default, whose fits are
    /// unflagged on every example (a 1R chain turns its tip by its hinge
    /// angle, not the strip's $c_\theta$ times it, and is flagged past 1°).
    pub prb: PrbKind,
    /// The load range the chains are fitted over.
    pub range: LoadRange,
    /// Rotor inertia (kg·m²) added to every PRB hinge (MJCF's `armature`),
    /// on top of what [`Options::step`] sizes. Zero by default.
    pub armature: f64,
    /// The simulator's time step (s) the model is sized for: every sprung
    /// joint whose own link would ring faster than [`step::STEPS_PER_PERIOD`]
    /// steps is given the armature that slows it to that ([`step::size`]),
    /// and MJCF's `timestep` and its closures' `solref` are set from it.
    /// MuJoCo's default, 2 ms, by default; zero sizes nothing. MJCF only:
    /// SDFormat and URDF hold no armature, and are not sized.
    pub step: f64,
    /// The model's name (MJCF's `model`, SDFormat's world and model, URDF's robot).
    pub name: String,
    /// Settings of the mechanism's solves along the range.
    pub settings: Settings,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            format: Format::Mjcf,
            prb: PrbKind::ThreeR,
            range: LoadRange::default(),
            armature: 0.0,
            step: step::DEFAULT_STEP,
            name: "mechanism".into(),
            settings: Settings::default(),
        }
    }
}

/// One flexure's fitted chain, as reported, in either dimension: the same
/// quantities in the plane and in space, with what only space has (the
/// springs out of the plane) in [`JointFit::out_of_plane`].
#[derive(Debug, Clone, PartialEq)]
pub struct JointFit {
    /// The chain.
    pub kind: PrbKind,
    /// The links' length fractions, root to tip: $[1-\gamma, \gamma]$ for
    /// 1R (Howell's $\gamma$ last; in space $[1-\gamma, \gamma, 0]$, its pivot
    /// $\gamma L$ from the tip and one at the tip), $[\gamma_0, \dots, \gamma_3]$ for 3R.
    pub gamma: Vec<f64>,
    /// Each hinge's nondimensional spring about $z$: Howell's $K_\Theta$ for
    /// 1R ($k_1 = \gamma K_\Theta EI/L$), $K_{\Theta i}$ for 3R
    /// ($k_{1,i} = K_{\Theta i}EI/L$); in space $EI$ is the flexure's
    /// $L/C_{\theta M}$ about $z$ at rest (its $EI_z$ when uniform).
    pub k_theta: Vec<f64>,
    /// The pivots at rest (m), in the flexure's root frame, root first
    /// ($z = 0$ in the plane).
    pub pivots: Vec<nalgebra::Point3<f64>>,
    /// Each pivot's spring about $z$ (the plane's hinge), $[k_1, k_2, k_3]$
    /// of $\tau = -(k_1\theta + k_2\theta^2 + k_3\theta^3)$ (N·m/rad,
    /// N·m/rad², N·m/rad³); linear in space.
    pub stiffness: Vec<[f64; 3]>,
    /// Space only (`None` in the plane): each pivot's linear springs out of
    /// the plane, $[k_y, k_x]$, bending about the local $y$ and twist about
    /// $x$ (N·m/rad).
    pub out_of_plane: Option<Vec<[f64; 2]>>,
    /// The largest tip position (m) and angle (rad) error of the chain
    /// against the model over the samples.
    pub error: prb::FitError,
    /// Whether the position error passes 1 % of L or the angle 1°.
    pub flagged: bool,
    /// Samples the error is taken over.
    pub samples: usize,
    /// The flexure's length (m), for the error relative to it.
    pub length: f64,
}

impl JointFit {
    /// A planar fit as reported.
    pub fn planar(fit: &PrbFit, length: f64) -> Self {
        JointFit {
            kind: fit.kind,
            gamma: fit.gamma.clone(),
            k_theta: fit.k_theta.clone(),
            pivots: fit.joints.iter().map(|j| nalgebra::Point3::new(j.pivot.x, j.pivot.y, 0.0)).collect(),
            stiffness: fit.joints.iter().map(|j| j.stiffness).collect(),
            out_of_plane: None,
            error: fit.error,
            flagged: fit.flagged,
            samples: fit.samples,
            length,
        }
    }

    /// The fit in a line, as the MJCF's comments and the command line's
    /// notes give it, named `name`: chain, $\gamma$, $K_\Theta$, springs and
    /// error, and `FLAGGED` past 1 % of L or 1°.
    pub fn line(&self, name: &str) -> String {
        use xml::number;
        let list = |v: &[f64]| v.iter().map(|x| number(*x)).collect::<Vec<_>>().join(", ");
        let k: Vec<String> = self.stiffness.iter().map(|k| format!("[{}]", list(k))).collect();
        let out = match &self.out_of_plane {
            None => String::new(),
            Some(o) => {
                let (y, x): (Vec<f64>, Vec<f64>) = o.iter().map(|k| (k[0], k[1])).unzip();
                format!(", stiffness_y [{}], stiffness_x [{}]", list(&y), list(&x))
            }
        };
        format!(
            "{name}: {} gamma [{}], k_theta [{}], stiffness {}{out}, error {} m ({:.3} % of L) and {} rad{}",
            self.kind,
            list(&self.gamma),
            list(&self.k_theta),
            k.join(" "),
            number(self.error.position),
            100.0 * self.error.position / self.length,
            number(self.error.angle),
            if self.flagged { ", FLAGGED" } else { "" }
        )
    }

    /// The warning of a flagged fit of joint `name`.
    fn flag_warning(&self, name: &str) -> String {
        format!(
            "joint {name:?}: the {} fit's tip is up to {} m ({:.2} % of L) and {} rad ({:.2}°) from the model's over the range, \
             more than 1 % of L or 1°",
            self.kind,
            xml::number(self.error.position),
            100.0 * self.error.position / self.length,
            xml::number(self.error.angle),
            self.error.angle.to_degrees()
        )
    }
}

/// The export report, one shape in both dimensions: each flexure joint's
/// fit, by name in the file's order, and what the model was given.
/// Serialized as `{"dimension", "format", "prb", "range": {"from", "to",
/// "count"}, "joints": {NAME: {"prb", "gamma", "k_theta", "stiffness",
/// "pivots", "error": {"position", "angle"}, "flagged", "samples",
/// "length"}}, "step", "armature": {HINGE: kg·m²}, "warnings": [...],
/// "notes": [...]}`; in space each joint adds `"stiffness_y"` and
/// `"stiffness_x"` ([`JointFit::out_of_plane`]), and its `pivots` are 3-D.
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// The mechanism's dimension, 2 or 3.
    pub dimension: usize,
    /// The format written.
    pub format: Format,
    /// The chain.
    pub prb: PrbKind,
    /// The range fitted over.
    pub range: LoadRange,
    /// (joint name, its fit), in the file's order.
    pub joints: Vec<(String, JointFit)>,
    /// The time step (s) the model is sized for ([`Options::step`]; 0 for SDFormat and URDF).
    pub step: f64,
    /// (model joint name, armature written on it, kg·m² or kg for a slide),
    /// in link order: the step's sizing plus [`Options::armature`].
    pub armature: Vec<(String, f64)>,
    /// What the model or the format could not hold, and fits flagged: the
    /// same as [`Export::warnings`].
    pub warnings: Vec<String>,
    /// What the model was given to simulate well (armature, limits), and
    /// how massless links were written.
    pub notes: Vec<String>,
}

impl FitReport {
    /// Each flexure joint's fit in a line ([`JointFit::line`]).
    pub fn fit_lines(&self) -> Vec<String> {
        self.joints.iter().map(|(name, f)| f.line(name)).collect()
    }
}

/// A list of (name, value) serialized as a map, each value through `.1`:
/// the report's `joints` and `armature`.
struct Map<'a, T, E>(&'a [(String, T)], fn(&'a T) -> E);

impl<'a, T, E: serde::Serialize> serde::Serialize for Map<'a, T, E> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (name, v) in self.0 {
            m.serialize_entry(name, &(self.1)(v))?;
        }
        m.end()
    }
}

/// A load range as the report writes it: `{"from", "to", "count"}`.
#[derive(serde::Serialize)]
struct RangeEntry {
    from: f64,
    to: f64,
    count: usize,
}

struct JointEntry<'a>(&'a JointFit);

impl serde::Serialize for JointEntry<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let f = self.0;
        let pivots: Vec<Vec<f64>> = f
            .pivots
            .iter()
            .map(|p| if f.out_of_plane.is_some() { vec![p.x, p.y, p.z] } else { vec![p.x, p.y] })
            .collect();
        let mut m = s.serialize_map(None)?;
        m.serialize_entry("prb", &f.kind)?;
        m.serialize_entry("gamma", &f.gamma)?;
        m.serialize_entry("k_theta", &f.k_theta)?;
        m.serialize_entry("stiffness", &f.stiffness)?;
        if let Some(o) = &f.out_of_plane {
            m.serialize_entry("stiffness_y", &o.iter().map(|k| k[0]).collect::<Vec<_>>())?;
            m.serialize_entry("stiffness_x", &o.iter().map(|k| k[1]).collect::<Vec<_>>())?;
        }
        m.serialize_entry("pivots", &pivots)?;
        m.serialize_entry("error", &f.error)?;
        m.serialize_entry("flagged", &f.flagged)?;
        m.serialize_entry("samples", &f.samples)?;
        m.serialize_entry("length", &f.length)?;
        m.end()
    }
}

impl serde::Serialize for FitReport {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut m = s.serialize_struct("FitReport", 10)?;
        m.serialize_field("dimension", &self.dimension)?;
        m.serialize_field("format", self.format.name())?;
        m.serialize_field("prb", &self.prb)?;
        let r = &self.range;
        m.serialize_field("range", &RangeEntry { from: r.from, to: r.to, count: r.count })?;
        m.serialize_field("joints", &Map(&self.joints, JointEntry))?;
        m.serialize_field("step", &self.step)?;
        m.serialize_field("armature", &Map(&self.armature, |a: &f64| *a))?;
        m.serialize_field("warnings", &self.warnings)?;
        m.serialize_field("notes", &self.notes)?;
        m.end()
    }
}

/// An exported model of either dimension: the XML, the report, and the
/// warnings ([`crate::model::Model::export`] answers it).
#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The model, in the format asked for.
    pub xml: String,
    /// The fits and what was lost.
    pub report: FitReport,
    /// Every warning: flagged fits, and what the format cannot hold, each naming it.
    pub warnings: Vec<String>,
    /// The planar rigid-body model the XML writes (`None` for a spatial mechanism).
    pub model: Option<model::RigidModel>,
}

/// The tip angle error (rad) past which a fit is flagged: 1°.
pub const ANGLE_FLAG: f64 = std::f64::consts::PI / 180.0;

/// Each flexure joint's tip wrenches along the range, and its fit, flagged
/// when its tip is more than 1 % of L ([`prb::FLAG_FRACTION`]) or more than
/// 1° ([`ANGLE_FLAG`]) from the model's.
///
/// # Example
/// ```
/// use flexure::export::{fits, LoadRange};
/// use flexure::prb::PrbKind;
/// let m = flexure::mechanism::file::from_toml(
///     "[[joint]]\nname = \"h\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"a\"\nlength = 1.0\nei = 1.0\n\
///      [[force]]\nbody = \"a\"\nat = [0.0, 0.0]\nmoment = 0.5\n",
/// )?;
/// let f = fits(&m, PrbKind::OneR, &LoadRange::default(), &Default::default())?;
/// // A pure moment bends a uniform strip into an arc; a 1R chain fits it to within 1 % of L.
/// assert_eq!(f.len(), 1);
/// assert!(f[0].as_ref().unwrap().error.position < 0.01);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn fits(m: &Mechanism, kind: PrbKind, range: &LoadRange, settings: &Settings) -> Result<Vec<Option<PrbFit>>> {
    let solutions = wrench::equilibria(m, range, settings)?;
    let mut out = Vec::with_capacity(m.joints.len());
    for (j, spec) in m.joints.iter().enumerate() {
        let Some(f) = spec.kind.flexure() else {
            out.push(None);
            continue;
        };
        let (mut loads, mut shapes) = (Vec::with_capacity(solutions.len()), Vec::with_capacity(solutions.len()));
        for s in &solutions {
            if let Some(w) = wrench::tip_wrench(m, j, s) {
                loads.push(w?);
                shapes.push(s.q[spec.offset..spec.offset + f.order()].to_vec());
            }
        }
        // To the shapes the mechanism reaches, not each wrench held dead from
        // rest: a tendon's or a closure's pull turns with the bodies.
        let mut fit = prb::fit_along(f, &loads, &shapes, kind).map_err(|e| match e {
            Error::Singular { what } => Error::Singular { what: format!("joint {:?}: {what}", spec.name) },
            other => other,
        })?;
        // A body on the tip points by the tip's angle: past 1° off, the fit
        // is flagged as for a position 1 % of L off.
        fit.flagged |= fit.error.angle > ANGLE_FLAG;
        out.push(Some(fit));
    }
    Ok(out)
}

/// The chain the model needs, from a fit: pivots, springs, and the pivots'
/// arc lengths from the fit's link fractions $\gamma$.
pub fn chain(fit: &PrbFit, length: f64) -> Chain {
    let mut arc = 0.0;
    let arcs = fit
        .gamma
        .iter()
        .take(fit.joints.len())
        .map(|g| {
            arc += g * length;
            arc
        })
        .collect();
    Chain {
        pivots: fit.joints.iter().map(|j| j.pivot).collect(),
        stiffness: fit.joints.iter().map(|j| j.stiffness).collect(),
        arcs,
    }
}

/// Every number the writers print must be finite: a fit or a pose that is
/// not is refused here, naming the link or joint, rather than written.
fn check_finite(model: &model::RigidModel) -> Result<()> {
    for l in &model.links {
        let i = &l.inertia;
        let mut values = vec![l.pose.phi, l.pose.x, l.pose.y, i.mass, i.inertia, i.com[0], i.com[1]];
        for j in &l.joints {
            values.extend([j.at.x, j.at.y, j.reference, j.damping, j.armature]);
            values.extend(j.stiffness);
        }
        if values.iter().any(|v| !v.is_finite()) {
            return Err(Error::Singular { what: format!("export: link {:?} has a value that is not finite", l.name) });
        }
    }
    Ok(())
}

/// Exports `m` as `options` say: fits every flexure's chain over the load
/// range ([`fits`]), builds the rigid-body model ([`model::build`]) and
/// writes it ([`mjcf::write`], [`sdf::write`], [`urdf::write`]).
///
/// Errors: the range's ([`LoadRange::validate`]), the armature's or the
/// step's when invalid; the mechanism's solves along the range (a load range past a
/// limit the mechanism cannot pass); a fit's; a body or joint named as a
/// generated link or hinge.
pub fn export(m: &Mechanism, options: &Options) -> Result<Export> {
    // A chain fitted without its contacts would pass through the shapes.
    crate::mechanism::contact::refuse_unsolved(m)?;
    options.range.validate()?;
    step::validate(options.step)?;
    let fitted = fits(m, options.prb, &options.range, &options.settings)?;
    let mut warnings = Vec::new();
    let mut joints = Vec::new();
    let mut chains = Vec::with_capacity(m.joints.len());
    let mut comment = vec![format!(
        "flexure export: each flexure is a {} pseudo-rigid-body chain fitted to the Smooth Curvature Model over the file's loads times {} to {} ({} samples)",
        options.prb, options.range.from, options.range.to, options.range.count
    )];
    for (j, (spec, fit)) in m.joints.iter().zip(fitted).enumerate() {
        let Some(fit) = fit else {
            chains.push(None);
            continue;
        };
        let length = spec.kind.flexure().map_or(1.0, |f| f.length());
        let reported = JointFit::planar(&fit, length);
        if fit.flagged {
            warnings.push(reported.flag_warning(&spec.name));
        }
        if wrench::weighs_itself(m, j) {
            warnings.push(format!(
                "joint {:?}: its own weight loads it along its length; the fit's tip wrenches are the least-squares ones",
                spec.name
            ));
        }
        comment.push(reported.line(&spec.name));
        chains.push(Some(chain(&fit, length)));
        joints.push((spec.name.clone(), reported));
    }
    if joints.is_empty() {
        comment.clear();
    }
    let mut model = model::build(m, &chains, options.armature, options.format == Format::Mjcf)?;
    // Only MJCF holds an armature: the other formats are not sized.
    let step = if options.format == Format::Mjcf { options.step } else { 0.0 };
    let sized = step::size(&mut model, step)?;
    check_finite(&model)?;
    let mut notes = Vec::new();
    let floor = format!("{} kg and {} kg·m²", xml::number(model::MIN_MASS), xml::number(model::MIN_INERTIA));
    let least = floor.replace(" and ", " or ");
    for (i, l) in model.links.iter().enumerate().skip(1).filter(|(_, l)| l.floored) {
        if model.body_link.contains(&i) {
            notes.push(format!(
                "body {:?} has less than {least} in the file: given that much, as simulators need",
                l.name
            ));
        } else {
            // SDFormat and URDF hold one joint a link: a massless flexure's links stay.
            warnings.push(format!(
                "link {:?}: a pseudo-rigid link of a massless flexure, kept because {} holds one joint a link, is given \
                 {floor} (the least simulators accept), so it rings far faster than the bodies; give the flexure its \
                 mass (density or mass_per_length) or export to mjcf, which merges such links away",
                l.name,
                if options.format == Format::Sdf { "SDFormat" } else { "URDF" }
            ));
        }
    }
    if options.format == Format::Mjcf {
        for l in model.links.iter().filter(|l| l.joints.len() > 1) {
            let names: Vec<&str> = l.joints.iter().map(|j| j.name.as_str()).collect();
            notes.push(format!(
                "body {:?} carries the hinges {} of a massless flexure, in order, each at its pivot: its links are merged \
                 away (MuJoCo applies a body's joints in order, each about its own pos), none at a mass floor",
                l.name,
                names.join(", ")
            ));
        }
    }
    if !sized.is_empty() {
        let list: Vec<String> = sized.iter().map(|(j, a)| format!("{j} {}", xml::number(*a))).collect();
        notes.push(format!(
            "sized for a {} s step: each sprung joint whose own link would ring faster than {} steps is given the armature \
             (rotor inertia, kg·m²; kg on a slide) that slows it to that, k1·({}·Δt/2π)² less the link's own inertia \
             (the balance is unchanged; the light parts' own modes come down to the step's reach): {}",
            xml::number(step),
            step::STEPS_PER_PERIOD,
            step::STEPS_PER_PERIOD,
            list.join(", ")
        ));
    }
    if options.format == Format::Mjcf {
        let limited: Vec<String> = model
            .joints()
            .filter_map(|(_, j)| {
                mjcf::hinge_range(j).map(|(lo, hi)| format!("{} [{}, {}]", j.name, xml::number(lo), xml::number(hi)))
            })
            .collect();
        if !limited.is_empty() {
            notes.push(format!(
                "hinges limited (MJCF range, rad) where their fitted spring's tangent stiffness vanishes, not met at rest: {}",
                limited.join(", ")
            ));
        }
    }
    let armature: Vec<(String, f64)> =
        model.joints().filter(|(_, j)| j.armature > 0.0).map(|(_, j)| (j.name.clone(), j.armature)).collect();
    let (xml, lost) = match options.format {
        Format::Mjcf => (mjcf::write(&model, &options.name, &comment, step), Vec::new()),
        Format::Sdf => sdf::write(&model, &options.name, &comment),
        Format::Urdf => urdf::write(&model, &options.name, &comment, m.size()),
    };
    warnings.extend(lost);
    let report = FitReport {
        dimension: 2,
        format: options.format,
        prb: options.prb,
        range: options.range,
        joints,
        step,
        armature,
        warnings: warnings.clone(),
        notes,
    };
    Ok(Export { xml, report, warnings, model: Some(model) })
}
