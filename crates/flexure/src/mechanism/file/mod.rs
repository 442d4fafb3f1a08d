//! The mechanism file (TOML; SI units; angles in radians).
//!
//! Parses text (the caller reads the file) and checks every name, number
//! and connection; every error names the key (or the entry) and its place,
//! line and column. Numbers must be finite and either zero or between
//! [`MIN_MAGNITUDE`] and [`MAX_MAGNITUDE`] in magnitude; keys that do not
//! apply to a joint's kind are refused rather than ignored.
//!
//! One part of the document per module: the document and its placed errors,
//! bodies, joints (and a flexure joint's keys), closures, loads, schedules
//! and the initial state, and the checks of the assembled mechanism.

use super::joints::{Fixed, Prismatic, Revolute};
use super::kinematics::frames;
use super::schedule::{Schedule, Waveform};
use super::sweep::Parameter;
use super::{Body, Closure, JointKind, JointSpec, Mechanism, PointLoad, ReportOptions, Tendon};
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::flexure::FlexureSpec;
use crate::kinematics::Pose;
use crate::section::{Notch, Profile, SectionSpec};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;

mod bodies;
mod closures;
mod document;
mod flexures;
mod joints;
mod loads;
mod schedules;
mod spatial;
mod validation;

pub use super::hints::{habits, loads_placed};
use bodies::{BodyToml, Find};
use closures::{PinToml, WeldToml};
use document::Source;
pub(super) use document::place;
use joints::JointToml;
use loads::{ForceToml, TendonToml};
use schedules::ScheduleToml;
pub use spatial::spatial_from_toml;

/// The largest magnitude of a number in a file. The model forms products of
/// a few of them ($L^3/EI$, $F L^2$, …); 1e30 keeps any product of ten
/// within the range of floating point.
pub const MAX_MAGNITUDE: f64 = 1e30;

/// The smallest magnitude of a non-zero number in a file (see [`MAX_MAGNITUDE`]).
pub const MIN_MAGNITUDE: f64 = 1e-30;

/// The largest ratio between the stiffest and the softest joint (diagonal
/// stiffness; a slider's N/m times the mechanism's length squared). Double
/// precision resolves the softer joint's forces beside the stiffer one's
/// to about 1e-16 × 1e12 = 1e-4 of themselves; beyond, no equilibrium is meaningful.
pub const MAX_STIFFNESS_RATIO: f64 = 1e12;

/// The most points a flexure joint's `shape` may ask for: enough to plot
/// any deflection line smoothly, few enough to print.
pub const MAX_SHAPE: usize = 10_000;

/// The longest mechanism text [`from_toml`] reads (64 MiB, far beyond any
/// mechanism): a longer one is refused with its length, not parsed.
pub const MAX_TEXT_BYTES: usize = 64 << 20;

/// Parses and checks a mechanism file (at most [`MAX_TEXT_BYTES`]).
///
/// # Example
/// ```
/// let m = flexure::mechanism::file::from_toml(r#"
/// [[joint]]
/// name = "hinge"
/// kind = "flexure"
/// parent = "ground"
/// child = "link"
/// length = 0.02
/// ei = 1e-3
/// "#).unwrap();
/// assert_eq!(m.dof(), 3);
/// assert!(flexure::mechanism::file::from_toml("[[joint]]\nname = 1").is_err());
/// let e = flexure::mechanism::file::from_toml("[[joint]]\nname = \"a\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"b\"\nstiffness = 5e-324\n");
/// assert!(e.unwrap_err().to_string().starts_with("line 6, column 13: joint \"a\": stiffness = 5e-324"));
/// ```
pub fn from_toml(text: &str) -> Result<Mechanism> {
    if text.len() > MAX_TEXT_BYTES {
        return Err(Error::File {
            place: "the whole file".into(),
            message: format!(
                "{} bytes, more than the {} MiB a mechanism file may hold",
                text.len(),
                MAX_TEXT_BYTES >> 20
            ),
        });
    }
    let src = Source { text };
    if let (3, at) = spatial::dimension(text)? {
        return Err(Error::File {
            place: place(text, at),
            message: "dimension = 3: a spatial mechanism; read it with `Model::from_toml` (or `spatial_from_toml`)"
                .into(),
        });
    }
    let file = document::parse(text)?;
    let mut bodies = bodies::from_joints(&src, &file.joint)?;
    let names: Vec<String> = bodies.iter().map(|b| b.name.clone()).collect();
    let find: &Find = &|name| bodies::find(&src, &names, name);
    joints::check_names(&src, &file.joint)?;
    let parents: Vec<usize> = file.joint.iter().map(|j| find(&j.parent)).collect::<Result<_>>()?;
    let order = joints::tree_order(&src, &file.joint, &parents)?;
    let tree = joints::tree(&src, &file.joint, &parents, &order)?;
    bodies::describe(&src, find, &mut bodies, &file.body)?;
    let (tendons, via_places) = loads::tendons(&src, find, &file.tendon)?;
    let forces = loads::forces(&src, find, &file.force)?;
    let closures = closures::closures(&src, find, &file.weld, &file.pin)?;
    let gravity = loads::gravity(&src, &file.gravity)?;
    let mut m = Mechanism {
        bodies,
        joints: tree.joints,
        tendons,
        forces,
        closures,
        gravity: gravity.into(),
        parent_joint: tree.parent_joint,
        dof: tree.dof,
        closure_places: closures::places(text, &file.weld, &file.pin),
        closure_preloads: closures::preloads(&file.weld, &file.pin),
        schedules: Vec::new(),
        initial: Vec::new(),
        initial_velocity: Vec::new(),
    };
    validation::check_stiffness_ratio(&src, &m, &tree.stiffness_places)?;
    validation::check_tendon_directions(&src, &m, &via_places)?;
    m.schedules = schedules::schedules(
        &src,
        &file.schedule,
        |load| Parameter::parse(&m, load),
        |p| matches!(p, Parameter::Tension(_)),
    )?;
    m.initial = schedules::initial_state(&src, &m, "initial", file.initial.as_ref())?;
    m.initial_velocity = schedules::initial_state(&src, &m, "initial_velocity", file.initial_velocity.as_ref())?;
    Ok(m)
}

/// The file's `dimension`: 2 (a planar mechanism, also when absent) or 3
/// (a spatial one); any other value is an error at its place. The
/// mechanism of either is read by [`crate::model::Model::from_toml`].
///
/// # Example
/// ```
/// use flexure::mechanism::file::dimension;
/// assert_eq!((dimension("").unwrap(), dimension("dimension = 3").unwrap()), (2, 3));
/// assert!(dimension("dimension = 4").unwrap_err().to_string().contains("dimension = 4"));
/// ```
pub fn dimension(text: &str) -> Result<u8> {
    spatial::dimension(text).map(|d| d.0)
}
