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
//!    a fit more than 1 % of $L$ off is flagged, with a warning.
//! 3. **The rigid-body model** ([`model::build`]): bodies keep their names,
//!    frames, masses, inertias and centres of mass; each flexure becomes its
//!    hinges, with links `NAME_prbK` between them and its own mass lumped
//!    on the links it moves with; revolute joints are hinges, prismatic
//!    joints slides, fixed joints rigid attachments. The rest pose is the
//!    file's rest configuration.
//! 4. **The format** ([`mjcf`], [`sdf`], [`urdf`]): what a format cannot
//!    hold is named in a warning ([`Export::warnings`]); nothing is dropped
//!    silently.
//!
//! # Example
//! ```
//! use flexure::export::{export, Format, Options};
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
//! let e = export(&m, &Options { format: Format::Mjcf, ..Default::default() })?;
//! assert!(e.xml.contains(r#"<body name="arm""#) && e.xml.contains(r#"<joint name="hinge" type="hinge""#));
//! let fit = &e.report.joints[0].1;
//! // An end force across the strip: Howell's characteristic radius factor is
//! // near 0.85 (0.83 over this range), and the fit is good to 1 % of L.
//! assert!((fit.gamma[1] - 0.85).abs() < 0.05 && !fit.flagged);
//! # Ok::<(), flexure::Error>(())
//! ```

pub mod lump;
pub mod mjcf;
pub mod model;
mod range;
pub mod sdf;
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
    /// The PRB chain of every flexure.
    pub prb: PrbKind,
    /// The load range the chains are fitted over.
    pub range: LoadRange,
    /// Rotor inertia (kg·m²) added to every PRB hinge (MJCF's `armature`):
    /// a stiff hinge on light links rings faster than a simulator's step can
    /// follow, and an armature $I_a \ge k_1(n\Delta t/2\pi)^2$ slows it to a
    /// period of $n$ steps $\Delta t$. Zero by default: it changes the dynamics.
    pub armature: f64,
    /// The model's name (MJCF's `model`, SDFormat's world and model, URDF's robot).
    pub name: String,
    /// Settings of the mechanism's solves along the range.
    pub settings: Settings,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            format: Format::Mjcf,
            prb: PrbKind::OneR,
            range: LoadRange::default(),
            armature: 0.0,
            name: "mechanism".into(),
            settings: Settings::default(),
        }
    }
}

/// One flexure's fit, as reported.
#[derive(Debug, Clone, PartialEq)]
pub struct JointFit {
    /// The fitted chain.
    pub fit: PrbFit,
    /// The flexure's length (m), for the error relative to it.
    pub length: f64,
}

impl std::ops::Deref for JointFit {
    type Target = PrbFit;
    fn deref(&self) -> &PrbFit {
        &self.fit
    }
}

/// The fit report: each flexure joint's fit, by name in the file's order.
/// Serialized as `{"format", "prb", "range": {"from", "to", "count"},
/// "joints": {NAME: {"prb", "gamma", "k_theta", "stiffness", "pivots",
/// "error": {"position", "angle"}, "flagged", "samples", "length"}},
/// "warnings": [...], "notes": [...]}`.
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// The format written.
    pub format: Format,
    /// The chain.
    pub prb: PrbKind,
    /// The range fitted over.
    pub range: LoadRange,
    /// (joint name, its fit), in the file's order.
    pub joints: Vec<(String, JointFit)>,
    /// What the model or the format could not hold, and fits flagged: the
    /// same as [`Export::warnings`].
    pub warnings: Vec<String>,
    /// What was added to make the model loadable (the least mass of massless links).
    pub notes: Vec<String>,
}

struct Joints<'a>(&'a [(String, JointFit)]);

impl serde::Serialize for Joints<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (name, f) in self.0 {
            m.serialize_entry(name, &JointEntry(f))?;
        }
        m.end()
    }
}

struct JointEntry<'a>(&'a JointFit);

impl serde::Serialize for JointEntry<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let f = &self.0.fit;
        let stiffness: Vec<[f64; 3]> = f.joints.iter().map(|j| j.stiffness).collect();
        let pivots: Vec<[f64; 2]> = f.joints.iter().map(|j| [j.pivot.x, j.pivot.y]).collect();
        let mut m = s.serialize_struct("JointFit", 9)?;
        m.serialize_field("prb", &f.kind)?;
        m.serialize_field("gamma", &f.gamma)?;
        m.serialize_field("k_theta", &f.k_theta)?;
        m.serialize_field("stiffness", &stiffness)?;
        m.serialize_field("pivots", &pivots)?;
        m.serialize_field("error", &f.error)?;
        m.serialize_field("flagged", &f.flagged)?;
        m.serialize_field("samples", &f.samples)?;
        m.serialize_field("length", &self.0.length)?;
        m.end()
    }
}

impl serde::Serialize for FitReport {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        #[derive(serde::Serialize)]
        struct Range {
            from: f64,
            to: f64,
            count: usize,
        }
        let mut m = s.serialize_struct("FitReport", 6)?;
        m.serialize_field("format", self.format.name())?;
        m.serialize_field("prb", &self.prb)?;
        m.serialize_field("range", &Range { from: self.range.from, to: self.range.to, count: self.range.count })?;
        m.serialize_field("joints", &Joints(&self.joints))?;
        m.serialize_field("warnings", &self.warnings)?;
        m.serialize_field("notes", &self.notes)?;
        m.end()
    }
}

/// An exported model: the XML, the fit report, and the warnings.
#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The model, in the format asked for.
    pub xml: String,
    /// The fits and what was lost.
    pub report: FitReport,
    /// Every warning: flagged fits, and what the format cannot hold, each naming it.
    pub warnings: Vec<String>,
    /// The rigid-body model the XML writes.
    pub model: model::RigidModel,
}

/// Each flexure joint's tip wrenches along the range, and its fit.
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
        let fit = prb::fit_along(f, &loads, &shapes, kind).map_err(|e| match e {
            Error::Singular { what } => Error::Singular { what: format!("joint {:?}: {what}", spec.name) },
            other => other,
        })?;
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

fn fit_line(name: &str, f: &PrbFit, length: f64) -> String {
    use xml::number;
    let list = |v: &[f64]| v.iter().map(|x| number(*x)).collect::<Vec<_>>().join(", ");
    let k: Vec<String> = f.joints.iter().map(|j| format!("[{}]", list(&j.stiffness))).collect();
    format!(
        "{name}: {} gamma [{}], k_theta [{}], stiffness {}, error {} m ({:.3} % of L) and {} rad{}",
        f.kind,
        list(&f.gamma),
        list(&f.k_theta),
        k.join(" "),
        number(f.error.position),
        100.0 * f.error.position / length,
        number(f.error.angle),
        if f.flagged { ", FLAGGED" } else { "" }
    )
}

/// Every number the writers print must be finite: a fit or a pose that is
/// not is refused here, naming the link or joint, rather than written.
fn check_finite(model: &model::RigidModel) -> Result<()> {
    for l in &model.links {
        let i = &l.inertia;
        let mut values = vec![l.pose.phi, l.pose.x, l.pose.y, i.mass, i.inertia, i.com[0], i.com[1]];
        if let Some(j) = &l.joint {
            values.extend([j.at.x, j.at.y, j.reference, j.damping, j.armature]);
            values.extend(j.stiffness);
        }
        if values.iter().any(|v| !v.is_finite()) {
            return Err(Error::Singular { what: format!("export: link {:?} has a value that is not finite", l.name) });
        }
    }
    Ok(())
}

/// The armature (kg·m²) that slows the stiffest pseudo-rigid hinge (the
/// ones `--armature` applies to) of a model with links at the mass floor to
/// a period of 20 of MuJoCo's default 2 ms steps, $k_1(20\thinspace\Delta t/2\pi)^2$;
/// `None` when no link is at the floor or no flexure became hinges.
fn offered_armature(m: &Mechanism, model: &model::RigidModel) -> Option<f64> {
    const STEP: f64 = 0.002;
    const STEPS_PER_PERIOD: f64 = 20.0;
    if !model.links.iter().any(|l| l.floored) {
        return None;
    }
    let stiffest = model
        .links
        .iter()
        .filter_map(|l| l.joint.as_ref())
        .filter(|j| m.joints[j.source].kind.flexure().is_some())
        .map(|j| j.stiffness[0].abs())
        .fold(0.0, f64::max);
    (stiffest > 0.0).then(|| stiffest * (STEPS_PER_PERIOD * STEP / std::f64::consts::TAU).powi(2))
}

/// Exports `m` as `options` say: fits every flexure's chain over the load
/// range ([`fits`]), builds the rigid-body model ([`model::build`]) and
/// writes it ([`mjcf::write`], [`sdf::write`], [`urdf::write`]).
///
/// Errors: the range's ([`LoadRange::validate`]) or the armature's when
/// invalid; the mechanism's solves along the range (a load range past a
/// limit the mechanism cannot pass); a fit's; a body or joint named as a
/// generated link or hinge.
pub fn export(m: &Mechanism, options: &Options) -> Result<Export> {
    options.range.validate()?;
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
        if fit.flagged {
            warnings.push(format!(
                "joint {:?}: the {} fit's tip is up to {} m ({:.2} % of L) from the model's over the range, more than 1 % of L",
                spec.name,
                fit.kind,
                xml::number(fit.error.position),
                100.0 * fit.error.position / length
            ));
        }
        if wrench::weighs_itself(m, j) {
            warnings.push(format!(
                "joint {:?}: its own weight loads it along its length; the fit's tip wrenches are the least-squares ones",
                spec.name
            ));
        }
        comment.push(fit_line(&spec.name, &fit, length));
        chains.push(Some(chain(&fit, length)));
        joints.push((spec.name.clone(), JointFit { fit, length }));
    }
    if joints.is_empty() {
        comment.clear();
    }
    let model = model::build(m, &chains, options.armature)?;
    check_finite(&model)?;
    let mut notes = Vec::new();
    for l in model.links.iter().skip(1).filter(|l| l.floored) {
        notes.push(format!(
            "link {:?} had less than {} kg or {} kg·m²: given that much, as simulators need",
            l.name,
            xml::number(model::MIN_MASS),
            xml::number(model::MIN_INERTIA)
        ));
    }
    if let Some(offer) = offered_armature(m, &model).filter(|a| options.armature < *a) {
        // Two digits, rounded up, so the value given back meets the bound.
        let offer = format!("{:.1e}", offer * 1.05);
        notes.push(format!(
            "links at the mass floor ring on their springs far faster than a simulator steps (the model's statics are \
             right, its motion is not): for MuJoCo's default 2 ms step give --armature {offer} (k1·(20·Δt/2π)², the stiffest \
             hinge then ringing over 20 steps), which changes the dynamics but not the balance"
        ));
    }
    let (xml, lost) = match options.format {
        Format::Mjcf => (mjcf::write(&model, &options.name, &comment), Vec::new()),
        Format::Sdf => sdf::write(&model, &options.name, &comment),
        Format::Urdf => urdf::write(&model, &options.name, &comment, m.size()),
    };
    warnings.extend(lost);
    let report = FitReport {
        format: options.format,
        prb: options.prb,
        range: options.range,
        joints,
        warnings: warnings.clone(),
        notes,
    };
    Ok(Export { xml, report, warnings, model })
}
