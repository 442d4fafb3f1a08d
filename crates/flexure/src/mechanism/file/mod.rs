//! The mechanism file (TOML; SI units; angles in radians).
//!
//! Parses text (the caller reads the file) and checks every name, number
//! and connection; every error names the key (or the entry) and its place,
//! line and column. Numbers must be finite and either zero or between
//! [`MIN_MAGNITUDE`] and [`MAX_MAGNITUDE`] in magnitude; keys that do not
//! apply to a joint's kind are refused rather than ignored, and so, with
//! why, are the keys only the other dimension takes ([`SPATIAL_ONLY`],
//! [`PLANAR_ONLY`]).
//!
//! One reader for both dimensions: `dimension` (2, the default, or 3)
//! picks the space, and what differs between the plane and space (a
//! point's numbers, a frame's keys, the joint kinds' tables, a body's
//! inertia, a pin's axis) is one small trait, implemented for both side by
//! side in `dimension.rs`. One part of the document per module: the
//! document and its placed errors, bodies, joints (and a flexure joint's
//! keys), closures, loads, schedules and the initial state, and the checks
//! of the assembled mechanism.

use super::joints::{Fixed, JointState, Prismatic, Revolute};
use super::schedule::{Schedule, Waveform};
use super::{Body, Closure, JointKind, JointSpec, Mechanism, PointLoad, ReportOptions, Tendon};
use crate::error::{Error, Result};
use crate::flexure::FlexureSpec;
use crate::section::{Notch, Profile, SectionSpec};
use crate::space::{Planar, Spatial};
use dimension::FileDimension;
pub use document::Document;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;

mod bodies;
mod closures;
mod dimension;
mod document;
mod flexures;
mod geoms;
mod joints;
mod loads;
mod schedules;
mod validation;

pub use super::hints::{habits, loads_placed};
use bodies::{BodyToml, Find};
use document::Source;
pub(super) use document::place;
use joints::JointToml;
use loads::{ForceToml, TendonToml};
use schedules::ScheduleToml;

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

/// The keys only a spatial file takes, which a planar one refuses, naming
/// the key and saying why: (table, `""` for the top level; keys; why).
pub const SPATIAL_ONLY: &[(&str, &[&str], &str)] = &[
    ("", &["ball"], "in the plane a [[pin]] holds what a ball would"),
    ("joint", &["rpy", "rpy_deg"], "a planar origin's angle is its third number, origin = [x, y, phi]"),
    (
        "joint",
        &["axis"],
        "a planar hinge turns about z and a slider moves along its origin's x; turn the origin's phi to aim it",
    ),
    (
        "joint",
        &["gj", "ei_y", "twist", "kappa_y", "shear_modulus"],
        "a planar flexure bends in its plane only, with no twist",
    ),
    ("joint", &["ei_z"], "in the plane the one bending stiffness is `ei`"),
    (
        "joint",
        &["rotary_inertia_per_length"],
        "a planar flexure's rotary inertia per length is ρI of its rectangle, with density or mass_per_length",
    ),
    ("joint", &["kappa_z"], "in the plane the rest curvature is `kappa`"),
    ("joint", &["orders"], "a planar flexure has one `order`"),
    ("joint", &["subintervals"], "a planar flexure integrates by its Gauss rule, whose points `quadrature` sets"),
    ("joint", &["diameter"], "a planar flexure's section is a rectangle of `width` and `thickness`"),
    ("body", &["ixx", "iyy", "izz", "ixy", "ixz", "iyz"], "a planar body's inertia is one number, about z"),
    (
        "weld",
        &["a_rpy", "a_rpy_deg", "b_rpy", "b_rpy_deg"],
        "a planar weld's frame is [x, y, phi], its angle the third number",
    ),
    ("pin", &["axis", "b_axis"], "a planar pin turns about z"),
    ("geom", &["rpy", "rpy_deg"], "a planar geom turns by `angle` (rad) about z"),
];

/// The keys only a planar file takes, which a spatial one refuses (as [`SPATIAL_ONLY`]).
pub const PLANAR_ONLY: &[(&str, &[&str], &str)] = &[
    (
        "joint",
        &["notch"],
        "a circular notch hinge: the spatial section's thickness is constant, linear or a table, not yet a circle's arc; give `thickness` as a table of points along the notch",
    ),
    (
        "joint",
        &["quadrature"],
        "the planar flexure's Gauss rule: a spatial flexure integrates by Magnus steps, whose number `subintervals` sets",
    ),
    ("geom", &["angle"], "a spatial geom turns by `rpy` (rad) or `rpy_deg` (degrees)"),
];

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
    Document::parse(text)?.planar()
}

/// Parses and checks a spatial mechanism file (one with `dimension = 3`),
/// as [`from_toml`] a planar one.
///
/// # Example
/// ```
/// let m = flexure::mechanism::file::spatial_from_toml(r#"
/// dimension = 3
/// gravity = [0.0, 0.0, -9.81]
/// [[joint]]
/// name = "ball"
/// kind = "spherical"
/// parent = "ground"
/// child = "bob"
/// [[body]]
/// name = "bob"
/// mass = 0.1
/// com = [0.0, 0.0, -0.5]
/// "#).unwrap();
/// assert_eq!((m.dof(), m.bodies[1].mass), (3, 0.1));
/// let e = flexure::mechanism::file::spatial_from_toml("dimension = 3\n[[joint]]\nname = \"h\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"a\"\naxis = [0.0, 0.0, 0.0]\n");
/// assert!(e.unwrap_err().to_string().starts_with("line 7, column 8: joint \"h\": axis"));
/// ```
pub fn spatial_from_toml(text: &str) -> Result<Mechanism<Spatial>> {
    Document::parse(text)?.spatial()
}

impl Document<'_> {
    /// The planar mechanism of this file: the tree of joints and its bodies,
    /// the loads, the closures, the checks of the whole, the schedules and
    /// the initial state; an error at its `dimension` if it is 3.
    pub fn planar(self) -> Result<Mechanism<Planar>> {
        self.read()
    }

    /// The spatial mechanism of this file, as [`Document::planar`] a planar one.
    pub fn spatial(self) -> Result<Mechanism<Spatial>> {
        self.read()
    }

    /// The mechanism of this file in the dimension `D`: the tree of joints
    /// and its bodies, the loads, the closures, the checks of the whole, the
    /// schedules and the initial state; an error placed at the file's
    /// `dimension` if it is the other one.
    fn read<D: FileDimension>(self) -> Result<Mechanism<D>> {
        let Document { text, doc, dimension } = self;
        match dimension {
            (d, _) if d == D::DIMENSION => {}
            (3, at) => {
                return Err(Error::File {
                    place: place(text, at),
                    message:
                        "dimension = 3: a spatial mechanism; read it with `Model::from_toml` (or `spatial_from_toml`)"
                            .into(),
                });
            }
            _ => {
                return Err(Error::File {
                    place: place(text, 0),
                    message: "a planar mechanism (no `dimension = 3`): read it with `from_toml`, or `Model::from_toml` for either"
                        .into(),
                });
            }
        }
        let (file, counts) = document::parse::<D>(text, doc)?;
        read_tables(&Source { text, counts: &counts }, file)
    }
}

/// The mechanism of the tables `file` of `src`'s text, in the dimension `D`.
fn read_tables<D: FileDimension>(src: &Source, file: document::FileToml<D>) -> Result<Mechanism<D>> {
    let text = src.text;
    let mut bodies = bodies::from_joints(src, &file.joint)?;
    let names: Vec<String> = bodies.iter().map(|b| b.name.clone()).collect();
    let find: &Find = &|name| bodies::find(src, &names, name);
    joints::check_names(src, &file.joint)?;
    let parents: Vec<usize> = file.joint.iter().map(|j| find(&j.parent)).collect::<Result<_>>()?;
    let order = joints::tree_order(src, &file.joint, &parents)?;
    let (joints, stiffness_places) = joints::tree::<D>(src, &file.joint, &parents, &order)?;
    bodies::describe(src, find, &mut bodies, &file.body)?;
    let (tendons, via_places) = loads::tendons(src, find, &file.tendon)?;
    let forces = loads::forces(src, find, &file.force)?;
    let gravity = D::vector(src.array("", "gravity", &file.gravity)?);
    let mut m = Mechanism::new(bodies, joints, tendons, forces, Vec::new(), gravity)
        .map_err(|e| Error::File { place: place(text, 0), message: e.to_string() })?;
    let (rest, states) = D::rest(&m);
    let (closures, written) = closures::closures(src, find, &rest, (&file.weld, &file.pin, &file.ball))?;
    let (places, preloads) = closures::places(text, &written);
    m.closures = closures;
    m = m.with_closure_places(places, preloads);
    validation::check_stiffness_ratio(src, &m, &states, &stiffness_places)?;
    validation::check_tendon_directions(src, &m, &rest, &via_places)?;
    let (geoms, geom_places) = geoms::geoms(src, find, &m, &file.geom)?;
    m.geoms = geoms;
    validation::check_geoms_clear(src, &m, &rest, &geom_places)?;
    m.schedules = schedules::schedules(src, &m, &file.schedule)?;
    (m.initial, m.initial_places) = schedules::initial_state(src, &m, "initial", file.initial.as_ref())?;
    m.initial_velocity = schedules::initial_state(src, &m, "initial_velocity", file.initial_velocity.as_ref())?.0;
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
    Document::parse(text).map(|d| d.dimension())
}
