//! The mechanism file (TOML; SI units; angles in radians).
//!
//! Parses text (the caller reads the file) and checks every name, number
//! and connection; every error names the key (or the entry) and its place,
//! line and column. Numbers must be finite and either zero or between
//! [`MIN_MAGNITUDE`] and [`MAX_MAGNITUDE`] in magnitude; keys that do not
//! apply to a joint's kind are refused rather than ignored.

use super::joints::{Fixed, Prismatic, Revolute};
use super::kinematics::frames;
use super::schedule::{Schedule, Waveform};
use super::sweep::Parameter;
use super::{Body, Closure, JointKind, JointSpec, Mechanism, PointLoad, Tendon};
use crate::error::{Error, Result};
use crate::joint::{Flexure, bending_stiffness};
use crate::kinematics::Pose;
use crate::section::{Notch, Profile, Section};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;

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

type Span = Range<usize>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileToml {
    #[serde(default)]
    joint: Vec<JointToml>,
    #[serde(default)]
    body: Vec<BodyToml>,
    #[serde(default)]
    tendon: Vec<TendonToml>,
    #[serde(default)]
    force: Vec<ForceToml>,
    #[serde(default)]
    weld: Vec<WeldToml>,
    #[serde(default)]
    pin: Vec<PinToml>,
    gravity: Option<Spanned<[f64; 2]>>,
    #[serde(default)]
    schedule: Vec<ScheduleToml>,
    // `[initial]` and `[initial_velocity]`: joint name → coordinates (a
    // number or an array): read by `initial_state`.
    initial: Option<BTreeMap<String, Spanned<toml::Value>>>,
    initial_velocity: Option<BTreeMap<String, Spanned<toml::Value>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ScheduleToml {
    load: Spanned<String>,
    points: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
    harmonic: Option<Spanned<HarmonicToml>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct HarmonicToml {
    amplitude: Spanned<f64>,
    frequency: Spanned<f64>,
    phase: Option<Spanned<f64>>,
    offset: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JointToml {
    name: Spanned<String>,
    kind: Spanned<String>,
    parent: Spanned<String>,
    child: Spanned<String>,
    origin: Option<Spanned<[f64; 3]>>,
    length: Option<Spanned<f64>>,
    // A quantity along the flexure (`ei`, `width`, `thickness`,
    // `mass_per_length`) is a number, `[root, tip]` or a table
    // `[[t, value], …]`: read by `Source::profile`.
    ei: Option<Spanned<toml::Value>>,
    modulus: Option<Spanned<f64>>,
    width: Option<Spanned<toml::Value>>,
    thickness: Option<Spanned<toml::Value>>,
    poisson: Option<Spanned<f64>>,
    // `{ radius = R, min_thickness = h }`: read by `Source::notch`.
    notch: Option<Spanned<toml::Value>>,
    density: Option<Spanned<f64>>,
    mass_per_length: Option<Spanned<toml::Value>>,
    yield_strength: Option<Spanned<f64>>,
    shape: Option<Spanned<usize>>,
    // A whole number, or `"auto"`: read by `flexure_order`.
    order: Option<Spanned<toml::Value>>,
    quadrature: Option<Spanned<usize>>,
    kappa: Option<Spanned<Vec<f64>>>,
    stiffness: Option<Spanned<f64>>,
    rest: Option<Spanned<f64>>,
    damping: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyToml {
    name: Spanned<String>,
    mass: Option<Spanned<f64>>,
    inertia: Option<Spanned<f64>>,
    com: Option<Spanned<[f64; 2]>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TendonToml {
    name: Spanned<String>,
    tension: Spanned<f64>,
    path: Spanned<Vec<Spanned<ViaToml>>>,
}

/// A via point: `[body, x, y]`.
type ViaToml = (Spanned<String>, f64, f64);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ForceToml {
    name: Option<Spanned<String>>,
    body: Spanned<String>,
    at: Spanned<[f64; 2]>,
    force: Option<Spanned<[f64; 2]>>,
    moment: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WeldToml {
    a: Spanned<String>,
    a_origin: Option<Spanned<[f64; 3]>>,
    b: Spanned<String>,
    b_origin: Option<Spanned<[f64; 3]>>,
    preload: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PinToml {
    a: Spanned<String>,
    a_at: Option<Spanned<[f64; 2]>>,
    b: Spanned<String>,
    b_at: Option<Spanned<[f64; 2]>>,
    preload: Option<Spanned<bool>>,
}

/// "line L, column C" of a byte offset.
fn place(text: &str, offset: usize) -> String {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.chars().count() - before.rfind('\n').map_or(0, |i| before[..=i].chars().count()) + 1;
    format!("line {line}, column {column}")
}

/// A number as the file would write it: plain, or in exponent form when extreme.
fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&v.abs()) { format!("{v}") } else { format!("{v:e}") }
}

/// What a number may be, beyond finite and within the magnitudes.
#[derive(Clone, Copy, PartialEq)]
enum Sign {
    Any,
    /// Greater than zero.
    Positive,
    /// Zero or greater.
    NotNegative,
}

/// Checks against the text they came from.
struct Source<'t> {
    text: &'t str,
}

impl Source<'_> {
    fn error(&self, span: &Span, message: String) -> Error {
        Error::File { place: place(self.text, span.start), message }
    }

    fn fail<T>(&self, span: &Span, message: String) -> Result<T> {
        Err(self.error(span, message))
    }

    /// `values` (shown as `key`, in `owner`'s entry) are finite, within the magnitudes, of `sign`.
    fn numbers(&self, owner: &str, key: &str, span: &Span, values: &[f64], sign: Sign) -> Result<()> {
        for (i, &v) in values.iter().enumerate() {
            let shown = if values.len() > 1 { format!("{key}[{i}]") } else { key.to_string() };
            let reason = if !v.is_finite() {
                Some("must be a finite number")
            } else if v != 0.0 && !(MIN_MAGNITUDE..=MAX_MAGNITUDE).contains(&v.abs()) {
                Some(
                    "must be zero or between 1e-30 and 1e30 in magnitude (SI units): beyond, the products the model forms leave the range of floating point",
                )
            } else if sign == Sign::Positive && v <= 0.0 {
                Some("must be greater than zero")
            } else if sign == Sign::NotNegative && v < 0.0 {
                Some("must not be negative")
            } else {
                None
            };
            if let Some(reason) = reason {
                return self.fail(span, format!("{owner}{shown} = {}: {reason}", number(v)));
            }
        }
        Ok(())
    }

    fn number(&self, owner: &str, key: &str, value: &Spanned<f64>, sign: Sign) -> Result<f64> {
        self.numbers(owner, key, &value.span(), &[*value.get_ref()], sign)?;
        Ok(*value.get_ref())
    }

    fn array<const N: usize>(&self, owner: &str, key: &str, value: &Option<Spanned<[f64; N]>>) -> Result<[f64; N]> {
        match value {
            Some(v) => {
                self.numbers(owner, key, &v.span(), v.get_ref(), Sign::Any)?;
                Ok(*v.get_ref())
            }
            None => Ok([0.0; N]),
        }
    }

    /// A quantity along a flexure, `key`: a number, `[root, tip]` (a linear
    /// taper) or a table `[[t, value], …]` over $t = s/L$; every value
    /// greater than zero, a table's $t$ from 0 to 1, increasing strictly.
    fn profile(&self, owner: &str, key: &'static str, value: &Spanned<toml::Value>) -> Result<Profile> {
        let span = value.span();
        let number = |v: &toml::Value| match v {
            toml::Value::Float(x) => Some(*x),
            toml::Value::Integer(i) => Some(*i as f64),
            _ => None,
        };
        let pair = |v: &toml::Value| match v.as_array().map(Vec::as_slice) {
            Some([a, b]) => Some([number(a)?, number(b)?]),
            _ => None,
        };
        let items = value.get_ref().as_array();
        let profile = if let Some(v) = number(value.get_ref()) {
            Profile::Constant(v)
        } else if let Some([root, tip]) = pair(value.get_ref()) {
            Profile::Linear { root, tip }
        } else if let Some(points) = items.and_then(|a| a.iter().map(pair).collect::<Option<Vec<_>>>()) {
            Profile::Table(points)
        } else {
            return self.fail(
                &span,
                format!(
                    "{owner}{key} must be a number, [root, tip] or a table [[t, value], …] with t = s/L from 0 to 1"
                ),
            );
        };
        match &profile {
            Profile::Constant(v) => self.numbers(owner, key, &span, &[*v], Sign::Positive)?,
            Profile::Linear { root, tip } => self.numbers(owner, key, &span, &[*root, *tip], Sign::Positive)?,
            Profile::Table(points) => {
                for (k, [t, v]) in points.iter().enumerate() {
                    self.numbers(owner, &format!("{key}[{k}][0]"), &span, &[*t], Sign::NotNegative)?;
                    self.numbers(owner, &format!("{key}[{k}][1]"), &span, &[*v], Sign::Positive)?;
                }
            }
        }
        profile.check(key).map_err(|e| self.placed(owner, &span, e))?;
        Ok(profile)
    }

    /// A circular notch, `{ radius = R, min_thickness = h }` (m, each greater than zero).
    fn notch(&self, owner: &str, value: &Spanned<toml::Value>) -> Result<Notch> {
        let span = value.span();
        let expected = "notch must be { radius = R, min_thickness = h } (m)";
        let Some(table) = value.get_ref().as_table() else {
            return self.fail(&span, format!("{owner}{expected}"));
        };
        if let Some(key) = table.keys().find(|k| !matches!(k.as_str(), "radius" | "min_thickness")) {
            return self.fail(&span, format!("{owner}unknown key `{key}` in notch: {expected}"));
        }
        let part = |key: &str| -> Result<f64> {
            let v = match table.get(key) {
                Some(toml::Value::Float(x)) => *x,
                Some(toml::Value::Integer(i)) => *i as f64,
                Some(_) => return self.fail(&span, format!("{owner}notch.{key} must be a number")),
                None => return self.fail(&span, format!("{owner}notch.{key} is missing: {expected}")),
            };
            self.numbers(owner, &format!("notch.{key}"), &span, &[v], Sign::Positive)?;
            Ok(v)
        };
        Ok(Notch { radius: part("radius")?, min_thickness: part("min_thickness")? })
    }

    /// A library error about `owner`'s value at `span`, placed.
    fn placed(&self, owner: &str, span: &Span, e: Error) -> Error {
        let message = match &e {
            Error::InvalidParameter { name, value, reason } => format!("{owner}{name} = {value}: {reason}"),
            other => format!("{owner}{other}"),
        };
        self.error(span, message)
    }
}

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
    let file: FileToml = toml::from_str(text).map_err(|e| {
        // Errors without a span (rare) concern the file as a whole.
        let at = place(text, e.span().map_or(0, |s| s.start));
        Error::File { place: at, message: e.message().trim().to_string() }
    })?;
    let mut bodies = vec![Body { name: "ground".into(), mass: 0.0, inertia: 0.0, com: [0.0; 2] }];
    // Bodies are created by the joints that name them as child.
    for j in &file.joint {
        let name = j.child.get_ref();
        if name == "ground" {
            return src.fail(&j.child.span(), format!("joint {:?}: the ground cannot be a child", j.name.get_ref()));
        }
        if bodies.iter().any(|b| &b.name == name) {
            return src.fail(&j.child.span(), format!("body {name:?} is reached by two joints"));
        }
        bodies.push(Body { name: name.clone(), mass: 0.0, inertia: 0.0, com: [0.0; 2] });
    }
    let names: Vec<String> = bodies.iter().map(|b| b.name.clone()).collect();
    let find = |name: &Spanned<String>| -> Result<usize> {
        names.iter().position(|b| b == name.get_ref()).ok_or_else(|| {
            src.error(
                &name.span(),
                format!("unknown body {:?}: bodies are ground and the joints' children", name.get_ref()),
            )
        })
    };
    for (i, j) in file.joint.iter().enumerate() {
        if file.joint[..i].iter().any(|k| k.name.get_ref() == j.name.get_ref()) {
            return src.fail(&j.name.span(), format!("duplicate joint name {:?}", j.name.get_ref()));
        }
    }
    // Order joints from the ground outward; what is left over lies on a cycle.
    let mut order: Vec<usize> = Vec::new();
    let mut reached = vec![false; bodies.len()];
    reached[0] = true;
    let parents: Vec<usize> = file.joint.iter().map(|j| find(&j.parent)).collect::<Result<_>>()?;
    loop {
        let before = order.len();
        for (i, &p) in parents.iter().enumerate() {
            if !order.contains(&i) && reached[p] {
                order.push(i);
                reached[i + 1] = true;
            }
        }
        if order.len() == before {
            break;
        }
    }
    if let Some(i) = (0..file.joint.len()).find(|i| !order.contains(i)) {
        let j = &file.joint[i];
        return src.fail(
            &j.parent.span(),
            format!("joint {:?} is on a cycle of joints, not reachable from ground", j.name.get_ref()),
        );
    }
    let mut joints = Vec::new();
    // Where each joint's stiffness was given, for the stiffness-ratio check.
    let mut stiffness_places: Vec<Span> = Vec::new();
    let mut parent_joint = vec![None; bodies.len()];
    let mut offset = 0;
    for &i in &order {
        let j = &file.joint[i];
        let owner = format!("joint {:?}: ", j.name.get_ref());
        let origin = src.array(&owner, "origin", &j.origin)?;
        let (kind, stiffness_place, auto_order) = joint_kind(&src, &owner, j)?;
        let damping = j.damping.as_ref().map_or(Ok(0.0), |d| src.number(&owner, "damping", d, Sign::NotNegative))?;
        let dof = kind.joint().dof();
        parent_joint[i + 1] = Some(joints.len());
        joints.push(JointSpec {
            name: j.name.get_ref().clone(),
            kind,
            parent: parents[i],
            child: i + 1,
            origin: Pose { x: origin[0], y: origin[1], phi: origin[2] },
            offset,
            damping,
            auto_order,
        });
        stiffness_places.push(stiffness_place);
        offset += dof;
    }
    let mut described = vec![false; bodies.len()];
    for b in &file.body {
        let idx = find(&b.name)?;
        let owner = format!("body {:?}: ", b.name.get_ref());
        if idx == 0 {
            return src.fail(&b.name.span(), format!("{owner}the ground does not move; give mass to a moving body"));
        }
        if described[idx] {
            return src.fail(&b.name.span(), format!("{owner}described twice"));
        }
        described[idx] = true;
        if let Some(mass) = &b.mass {
            bodies[idx].mass = src.number(&owner, "mass", mass, Sign::NotNegative)?;
        }
        if let Some(inertia) = &b.inertia {
            bodies[idx].inertia = src.number(&owner, "inertia", inertia, Sign::NotNegative)?;
        }
        bodies[idx].com = src.array(&owner, "com", &b.com)?;
    }
    let mut tendons = Vec::new();
    let mut via_places: Vec<Vec<Span>> = Vec::new();
    for t in &file.tendon {
        let owner = format!("tendon {:?}: ", t.name.get_ref());
        if tendons.iter().any(|u: &Tendon| &u.name == t.name.get_ref()) {
            return src.fail(&t.name.span(), format!("duplicate tendon name {:?}", t.name.get_ref()));
        }
        let tension = src.number(&owner, "tension", &t.tension, Sign::NotNegative)?;
        if t.path.get_ref().len() < 2 {
            return src.fail(&t.path.span(), format!("{owner}a path needs at least two via points"));
        }
        let mut path = Vec::new();
        let mut places = Vec::new();
        for (k, via) in t.path.get_ref().iter().enumerate() {
            let (body, x, y) = via.get_ref();
            src.numbers(&owner, &format!("path[{k}]"), &via.span(), &[*x, *y], Sign::Any)?;
            path.push((find(body)?, [*x, *y]));
            places.push(via.span());
        }
        tendons.push(Tendon { name: t.name.get_ref().clone(), tension, path });
        via_places.push(places);
    }
    let mut forces = Vec::new();
    for (i, f) in file.force.iter().enumerate() {
        let name = f.name.as_ref().map_or(i.to_string(), |n| n.get_ref().clone());
        let owner = format!("force {name:?}: ");
        if forces.iter().any(|g: &PointLoad| g.name == name) {
            let span = f.name.as_ref().map_or(f.body.span(), |n| n.span());
            return src.fail(&span, format!("duplicate force name {name:?}"));
        }
        let at = src.array(&owner, "at", &Some(f.at.clone()))?;
        let force = src.array(&owner, "force", &f.force)?;
        let moment = match &f.moment {
            Some(v) => src.number(&owner, "moment", v, Sign::Any)?,
            None => 0.0,
        };
        forces.push(PointLoad { name, body: find(&f.body)?, at, force, moment });
    }
    let mut closures = Vec::new();
    let distinct = |a: usize, b: &Spanned<String>, what: &str| -> Result<()> {
        if a == find(b)? {
            return src.fail(&b.span(), format!("a {what} joins body {:?} to itself", b.get_ref()));
        }
        Ok(())
    };
    for w in &file.weld {
        let owner = format!("weld of {:?} and {:?}: ", w.a.get_ref(), w.b.get_ref());
        let (ao, bo) = (src.array(&owner, "a_origin", &w.a_origin)?, src.array(&owner, "b_origin", &w.b_origin)?);
        let a = find(&w.a)?;
        distinct(a, &w.b, "weld")?;
        let pose = |o: [f64; 3]| Pose { x: o[0], y: o[1], phi: o[2] };
        closures.push(Closure::Weld { a, a_origin: pose(ao), b: find(&w.b)?, b_origin: pose(bo) });
    }
    for p in &file.pin {
        let owner = format!("pin of {:?} and {:?}: ", p.a.get_ref(), p.b.get_ref());
        let (a_at, b_at) = (src.array(&owner, "a_at", &p.a_at)?, src.array(&owner, "b_at", &p.b_at)?);
        let a = find(&p.a)?;
        distinct(a, &p.b, "pin")?;
        closures.push(Closure::Pin { a, a_at, b: find(&p.b)?, b_at });
    }
    let gravity = src.array("", "gravity", &file.gravity)?;
    let closure_places = file
        .weld
        .iter()
        .map(|w| &w.a)
        .chain(file.pin.iter().map(|p| &p.a))
        .map(|a| place(text, a.span().start))
        .collect();
    let closure_preloads = file
        .weld
        .iter()
        .map(|w| &w.preload)
        .chain(file.pin.iter().map(|p| &p.preload))
        .map(|p| p.as_ref().is_some_and(|p| *p.get_ref()))
        .collect();
    let mut m = Mechanism {
        bodies,
        joints,
        tendons,
        forces,
        closures,
        gravity,
        parent_joint,
        dof: offset,
        closure_places,
        closure_preloads,
        schedules: Vec::new(),
        initial: Vec::new(),
        initial_velocity: Vec::new(),
    };
    check_stiffness_ratio(&src, &m, &stiffness_places)?;
    check_tendon_directions(&src, &m, &via_places)?;
    m.schedules = schedules(&src, &m, &file.schedule)?;
    m.initial = initial_state(&src, &m, "initial", file.initial.as_ref())?;
    m.initial_velocity = initial_state(&src, &m, "initial_velocity", file.initial_velocity.as_ref())?;
    Ok(m)
}

/// The `[[schedule]]` tables: each names a load of the mechanism (as
/// sweeps do) at most once, with either points `[t, value]` of finite
/// numbers whose times do not decrease, at most two at one time (a step),
/// or a `harmonic` (amplitude, frequency in Hz, phase in rad, offset).
fn schedules(src: &Source, m: &Mechanism, tables: &[ScheduleToml]) -> Result<Vec<Schedule>> {
    let mut out: Vec<Schedule> = Vec::new();
    for s in tables {
        let load = s.load.get_ref();
        let owner = format!("schedule {load:?}: ");
        let parameter = Parameter::parse(m, load).map_err(|e| match e {
            Error::InvalidParameter { reason, .. } => {
                src.error(&s.load.span(), format!("{owner}load {load:?} {reason}"))
            }
            other => src.placed(&owner, &s.load.span(), other),
        })?;
        if out.iter().any(|o| o.parameter == parameter) {
            return src.fail(&s.load.span(), format!("{owner}load {load:?} is scheduled twice"));
        }
        let tension = matches!(parameter, Parameter::Tension(_));
        let waveform = match (&s.points, &s.harmonic) {
            (Some(points), None) => Waveform::Points(schedule_points(src, &owner, points, tension)?),
            (None, Some(h)) => schedule_harmonic(src, &owner, h, tension)?,
            (Some(_), Some(h)) => {
                return src.fail(&h.span(), format!("{owner}give points or harmonic, not both"));
            }
            (None, None) => {
                return src.fail(
                    &s.load.span(),
                    format!(
                        "{owner}give points = [[t, value], …] or harmonic = {{ amplitude, frequency, phase, offset }}"
                    ),
                );
            }
        };
        out.push(Schedule { load: load.clone(), parameter, waveform });
    }
    Ok(out)
}

/// A schedule's `points`: at least one, times not decreasing, at most two
/// at one time; a tension's values not negative.
fn schedule_points(
    src: &Source,
    owner: &str,
    points: &Spanned<Vec<Spanned<[f64; 2]>>>,
    tension: bool,
) -> Result<Vec<[f64; 2]>> {
    let list = points.get_ref();
    if list.is_empty() {
        return src.fail(&points.span(), format!("{owner}points is empty: give at least one [t, value]"));
    }
    let sign = if tension { Sign::NotNegative } else { Sign::Any };
    for (k, p) in list.iter().enumerate() {
        let [t, v] = *p.get_ref();
        src.numbers(owner, &format!("points[{k}] time"), &p.span(), &[t], Sign::Any)?;
        src.numbers(owner, &format!("points[{k}] value"), &p.span(), &[v], sign)?;
        let before = |j: usize| list[j].get_ref()[0];
        if k > 0 && t < before(k - 1) {
            return src.fail(
                &p.span(),
                format!(
                    "{owner}points[{k}] has time {} after points[{}] at {}: the times of points must not decrease (two points at one time make a step)",
                    number(t),
                    k - 1,
                    number(before(k - 1))
                ),
            );
        }
        if k > 1 && t == before(k - 1) && t == before(k - 2) {
            return src.fail(
                &p.span(),
                format!(
                    "{owner}points[{k}] is the third point at time {}: a step is two points at one time, the value before and the value after",
                    number(t)
                ),
            );
        }
    }
    Ok(list.iter().map(|p| *p.get_ref()).collect())
}

/// A schedule's `harmonic`: a finite amplitude and offset, a frequency
/// (Hz) greater than zero, a phase (rad); a tension's offset at least its
/// amplitude, so that it is never negative.
fn schedule_harmonic(src: &Source, owner: &str, h: &Spanned<HarmonicToml>, tension: bool) -> Result<Waveform> {
    let t = h.get_ref();
    let amplitude = src.number(owner, "harmonic.amplitude", &t.amplitude, Sign::Any)?;
    let frequency = src.number(owner, "harmonic.frequency", &t.frequency, Sign::Positive)?;
    let phase = t.phase.as_ref().map_or(Ok(0.0), |p| src.number(owner, "harmonic.phase", p, Sign::Any))?;
    let offset = t.offset.as_ref().map_or(Ok(0.0), |o| src.number(owner, "harmonic.offset", o, Sign::Any))?;
    if tension && offset < amplitude.abs() {
        return src.fail(
            &h.span(),
            format!(
                "{owner}harmonic has offset {} below its amplitude {}: a tendon's tension cannot be negative",
                number(offset),
                number(amplitude.abs())
            ),
        );
    }
    Ok(Waveform::Harmonic { amplitude, frequency, phase, offset })
}

/// `[initial]` or `[initial_velocity]` (`key`): joint name → its
/// coordinates, a number for a joint of one coordinate or an array of as
/// many numbers as the joint has coordinates.
fn initial_state(
    src: &Source,
    m: &Mechanism,
    key: &str,
    table: Option<&BTreeMap<String, Spanned<toml::Value>>>,
) -> Result<Vec<(usize, Vec<f64>)>> {
    let mut out = Vec::new();
    for (name, value) in table.into_iter().flatten() {
        let span = value.span();
        let Some(j) = m.joints.iter().position(|j| &j.name == name) else {
            return src.fail(&span, format!("{key}: unknown joint {name:?}"));
        };
        let owner = format!("{key}: joint {name:?}: ");
        let number = |v: &toml::Value| match v {
            toml::Value::Float(x) => Some(*x),
            toml::Value::Integer(i) => Some(*i as f64),
            _ => None,
        };
        let values = match value.get_ref() {
            toml::Value::Array(items) => items.iter().map(number).collect::<Option<Vec<f64>>>(),
            v => number(v).map(|x| vec![x]),
        };
        let dof = m.joints[j].kind.joint().dof();
        let Some(values) = values else {
            return src.fail(&span, format!("{owner}must be a number or an array of {dof} numbers"));
        };
        if values.len() != dof {
            return src.fail(&span, format!("{owner}the joint has {dof} coordinates and {} were given", values.len()));
        }
        src.numbers(&owner, "coordinates", &span, &values, Sign::Any)?;
        // Bounded as every coordinate is (rad, m, and per second for rates).
        let bound = crate::joint::MAX_COORDINATE;
        if let Some((i, x)) = values.iter().enumerate().find(|(_, x)| x.abs() > bound) {
            return src.fail(
                &span,
                format!("{owner}coordinates[{i}] = {}: must be at most {bound:e} in magnitude", self::number(*x)),
            );
        }
        out.push((j, values));
    }
    Ok(out)
}

/// The joints' diagonal stiffnesses span at most [`MAX_STIFFNESS_RATIO`].
fn check_stiffness_ratio(src: &Source, m: &Mechanism, places: &[Span]) -> Result<()> {
    let rest = frames(m, &m.rest());
    let length = m.size();
    // (joint, stiffness in N·m)
    let mut all: Vec<(usize, f64)> = Vec::new();
    for (i, (j, s)) in m.joints.iter().zip(&rest.joints).enumerate() {
        let unit = if j.kind.joint().is_translation() { length * length } else { 1.0 };
        all.extend((0..s.gradient.len()).map(|k| (i, s.stiffness[(k, k)] * unit)).filter(|&(_, k)| k > 0.0));
    }
    let (Some(stiff), Some(soft)) = (
        all.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1)),
        all.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1)),
    ) else {
        return Ok(());
    };
    if stiff.1 > MAX_STIFFNESS_RATIO * soft.1 {
        return src.fail(
            &places[soft.0],
            format!(
                "joint {:?}: stiffness {:.3e} N·m is {:.1e} times softer than joint {:?} ({:.3e} N·m); double precision cannot weigh their forces together beyond a ratio of 1e12",
                m.joints[soft.0].name,
                soft.1,
                stiff.1 / soft.1,
                m.joints[stiff.0].name,
                stiff.1
            ),
        );
    }
    Ok(())
}

/// No two consecutive via points of a tendon coincide at rest: the tendon
/// would have no direction there.
fn check_tendon_directions(src: &Source, m: &Mechanism, places: &[Vec<Span>]) -> Result<()> {
    let rest = frames(m, &m.rest());
    for (t, spans) in m.tendons.iter().zip(places) {
        let w: Vec<[f64; 2]> = t.path.iter().map(|&(b, r)| rest.bodies[b].point(r)).collect();
        for (k, pair) in w.windows(2).enumerate() {
            let size = pair.iter().flatten().map(|v| v.abs()).sum::<f64>();
            if (pair[1][0] - pair[0][0]).hypot(pair[1][1] - pair[0][1]) <= 1e-12 * size {
                return src.fail(
                    &spans[k + 1],
                    format!(
                        "tendon {:?}: via points {} and {} coincide at rest, so the tendon has no direction there",
                        t.name,
                        k + 1,
                        k + 2
                    ),
                );
            }
        }
    }
    Ok(())
}

/// The keys a kind does not take, given in `j`.
fn foreign_keys(j: &JointToml, kind: &str) -> Option<(&'static str, Span)> {
    let flexure = [
        ("length", j.length.as_ref().map(Spanned::span)),
        ("ei", j.ei.as_ref().map(Spanned::span)),
        ("modulus", j.modulus.as_ref().map(Spanned::span)),
        ("width", j.width.as_ref().map(Spanned::span)),
        ("thickness", j.thickness.as_ref().map(Spanned::span)),
        ("poisson", j.poisson.as_ref().map(Spanned::span)),
        ("notch", j.notch.as_ref().map(Spanned::span)),
        ("density", j.density.as_ref().map(Spanned::span)),
        ("mass_per_length", j.mass_per_length.as_ref().map(Spanned::span)),
        ("yield_strength", j.yield_strength.as_ref().map(Spanned::span)),
        ("shape", j.shape.as_ref().map(Spanned::span)),
        ("order", j.order.as_ref().map(Spanned::span)),
        ("quadrature", j.quadrature.as_ref().map(Spanned::span)),
        ("kappa", j.kappa.as_ref().map(Spanned::span)),
    ];
    let spring = [("stiffness", j.stiffness.as_ref().map(Spanned::span)), ("rest", j.rest.as_ref().map(Spanned::span))];
    let foreign: Vec<(&'static str, Option<Span>)> = match kind {
        "flexure" => spring.to_vec(),
        "revolute" | "prismatic" => flexure.to_vec(),
        _ => {
            flexure.iter().chain(&spring).cloned().chain([("damping", j.damping.as_ref().map(Spanned::span))]).collect()
        }
    };
    foreign.into_iter().find_map(|(k, s)| s.map(|s| (k, s)))
}

/// A flexure's `order`: a whole number (3 when absent), or `"auto"`, which
/// starts at 3 (the second value says so).
fn flexure_order(src: &Source, owner: &str, j: &JointToml) -> Result<(usize, bool)> {
    let Some(o) = &j.order else { return Ok((3, false)) };
    match o.get_ref() {
        toml::Value::Integer(n) if *n >= 0 => Ok((usize::try_from(*n).unwrap_or(usize::MAX), false)),
        toml::Value::String(s) if s == "auto" => Ok((3, true)),
        v => src.fail(
            &o.span(),
            format!(
                "{owner}order = {}: must be a whole number from 1 to {} or \"auto\" (raised until an analysis's error estimate meets its target)",
                match v {
                    toml::Value::String(s) => format!("{s:?}"),
                    toml::Value::Integer(i) => i.to_string(),
                    toml::Value::Float(x) => format!("{x:?}"),
                    other => format!("a {}", other.type_str()),
                },
                crate::joint::MAX_ORDER
            ),
        ),
    }
}

/// The joint's kind, the place of the key that sets its stiffness, and
/// whether it is a flexure of `order = "auto"`.
fn joint_kind(src: &Source, owner: &str, j: &JointToml) -> Result<(JointKind, Span, bool)> {
    let kind = j.kind.get_ref().as_str();
    if !matches!(kind, "flexure" | "revolute" | "prismatic" | "fixed") {
        return src.fail(
            &j.kind.span(),
            format!("{owner}unknown kind {kind:?}; expected flexure, revolute, prismatic or fixed"),
        );
    }
    if let Some((key, span)) = foreign_keys(j, kind) {
        return src.fail(&span, format!("{owner}`{key}` does not apply to a {kind} joint"));
    }
    let spring = |key: &str, v: &Option<Spanned<f64>>, sign: Sign| -> Result<f64> {
        v.as_ref().map_or(Ok(0.0), |v| src.number(owner, key, v, sign))
    };
    let stiffness_place = j.stiffness.as_ref().map_or(j.name.span(), Spanned::span);
    match kind {
        "flexure" => {
            let length = j
                .length
                .as_ref()
                .ok_or_else(|| src.error(&j.name.span(), format!("{owner}a flexure needs a length")))?;
            let l = src.number(owner, "length", length, Sign::Positive)?;
            let (ei, ei_span, mut section) = flexure_section(src, owner, j)?;
            let (order, auto_order) = flexure_order(src, owner, j)?;
            let order_span = j.order.as_ref().map_or(j.name.span(), Spanned::span);
            let mut f = Flexure::new(l, ei, order).map_err(|x| {
                let span = match &x {
                    Error::InvalidParameter { name: "length", .. } => length.span(),
                    Error::InvalidParameter { name: "ei", .. } => ei_span.clone(),
                    _ => order_span.clone(),
                };
                src.placed(owner, &span, x)
            })?;
            if let Some(mu) = &j.mass_per_length {
                if j.density.is_some() {
                    return src.fail(&mu.span(), format!("{owner}give density or mass_per_length, not both"));
                }
                let p = src.profile(owner, "mass_per_length", mu)?;
                let s = section
                    .take()
                    .map_or_else(|| Section::uniform(ei), Ok)
                    .map_err(|x| src.placed(owner, &ei_span, x))?;
                section = Some(s.with_mass_per_length(p).map_err(|x| src.placed(owner, &mu.span(), x))?);
            }
            if let Some(s) = section {
                f = f.with_section(s).map_err(|x| src.placed(owner, &ei_span, x))?;
            }
            report(src, owner, j, &f)?;
            if let Some(q) = &j.quadrature {
                f = f.with_quadrature(*q.get_ref()).map_err(|x| src.placed(owner, &q.span(), x))?;
            }
            if let Some(k) = &j.kappa {
                src.numbers(owner, "kappa", &k.span(), k.get_ref(), Sign::Any)?;
                f = f.with_rest(k.get_ref()).map_err(|x| src.placed(owner, &k.span(), x))?;
            }
            Ok((JointKind::Flexure(Box::new(f)), ei_span, auto_order))
        }
        "revolute" => Ok((
            JointKind::Revolute(Revolute {
                stiffness: spring("stiffness", &j.stiffness, Sign::NotNegative)?,
                rest: spring("rest", &j.rest, Sign::Any)?,
            }),
            stiffness_place,
            false,
        )),
        "prismatic" => Ok((
            JointKind::Prismatic(Prismatic {
                stiffness: spring("stiffness", &j.stiffness, Sign::NotNegative)?,
                rest: spring("rest", &j.rest, Sign::Any)?,
            }),
            stiffness_place,
            false,
        )),
        _ => Ok((JointKind::Fixed(Fixed), j.name.span(), false)),
    }
}

/// A flexure joint's bending stiffness: the uniform $EI$ to build it with,
/// the place of the key that sets it, and the [`Section`] that replaces it
/// when $EI$ varies, a thickness gives stress, or a density gives mass.
fn flexure_section(src: &Source, owner: &str, j: &JointToml) -> Result<(f64, Span, Option<Section>)> {
    let span_of = |v: &Option<Spanned<toml::Value>>| v.as_ref().map(Spanned::span);
    let rectangle_keys = [
        ("width", span_of(&j.width)),
        ("thickness", span_of(&j.thickness)),
        ("poisson", j.poisson.as_ref().map(Spanned::span)),
        ("notch", span_of(&j.notch)),
        ("density", j.density.as_ref().map(Spanned::span)),
    ];
    match (&j.ei, &j.modulus) {
        (Some(ei), None) => {
            if let Some((key, Some(span))) = rectangle_keys.iter().find(|(_, v)| v.is_some()) {
                let hint = if *key == "density" { "; give mass_per_length with ei" } else { "" };
                return src.fail(span, format!("{owner}`{key}` goes with modulus, not with ei{hint}"));
            }
            match src.profile(owner, "ei", ei)? {
                Profile::Constant(v) => Ok((v, ei.span(), None)),
                p => {
                    let s = Section::given(p).map_err(|x| src.placed(owner, &ei.span(), x))?;
                    Ok((1.0, ei.span(), Some(s)))
                }
            }
        }
        (None, Some(e)) => {
            let e_value = src.number(owner, "modulus", e, Sign::Positive)?;
            let part = |key: &'static str, v: &Option<Spanned<toml::Value>>| -> Result<(Profile, Span)> {
                let v = v.as_ref().ok_or_else(|| {
                    src.error(&e.span(), format!("{owner}modulus needs width and thickness; {key} is missing"))
                })?;
                Ok((src.profile(owner, key, v)?, v.span()))
            };
            let ((w, w_span), (h, h_span)) = (part("width", &j.width)?, part("thickness", &j.thickness)?);
            let nu = match &j.poisson {
                Some(p) => Some(src.number(owner, "poisson", p, Sign::Any)?),
                None => None,
            };
            let place = |x: Error| {
                let span = match &x {
                    Error::InvalidParameter { name: "poisson", .. } => {
                        j.poisson.as_ref().map_or(e.span(), Spanned::span)
                    }
                    Error::InvalidParameter { name: "width", .. } => w_span.clone(),
                    Error::InvalidParameter { name: "thickness", .. } => h_span.clone(),
                    Error::InvalidParameter { name, .. } if name.starts_with("notch") => {
                        span_of(&j.notch).unwrap_or(e.span())
                    }
                    Error::InvalidParameter { name: "density", .. } => {
                        j.density.as_ref().map_or(e.span(), Spanned::span)
                    }
                    _ => e.span(),
                };
                src.placed(owner, &span, x)
            };
            // A uniform rectangle keeps Eq. 25, and its product's magnitude check.
            let ei = match (&w, &h) {
                (Profile::Constant(b), Profile::Constant(t)) => {
                    let ei = bending_stiffness(e_value, *b, *t, nu).map_err(place)?;
                    // The product may leave the magnitudes its parts kept.
                    src.numbers(owner, "ei (from modulus, width, thickness)", &e.span(), &[ei], Sign::Positive)?;
                    ei
                }
                _ => 1.0,
            };
            let mut section = Section::rectangle(e_value, nu, w, h).map_err(place)?;
            if let Some(n) = &j.notch {
                section = section.with_notch(src.notch(owner, n)?).map_err(place)?;
            }
            if let Some(rho) = &j.density {
                section = section.with_density(src.number(owner, "density", rho, Sign::Positive)?).map_err(place)?;
            }
            Ok((ei, e.span(), Some(section)))
        }
        (Some(ei), Some(_)) => src.fail(&ei.span(), format!("{owner}give ei or modulus, width, thickness, not both")),
        (None, None) => src.fail(&j.name.span(), format!("{owner}a flexure needs ei, or modulus, width and thickness")),
    }
}

/// What `flexure solve` reports of a flexure joint beyond its coordinates.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Report {
    /// `yield_strength` (Pa): the safety factor is this over the peak stress.
    pub yield_strength: Option<f64>,
    /// `shape`: the number of points, evenly spaced in arc length, at which to print the deformed flexure.
    pub shape: Option<usize>,
}

/// Checks a flexure joint's `yield_strength` (greater than zero, and only
/// with a thickness, for a stress) and `shape` (2 to [`MAX_SHAPE`]).
fn report(src: &Source, owner: &str, j: &JointToml, f: &Flexure) -> Result<Report> {
    let yield_strength = match &j.yield_strength {
        Some(v) => {
            let s = src.number(owner, "yield_strength", v, Sign::Positive)?;
            if f.section().modulus().is_none() {
                return src.fail(
                    &v.span(),
                    format!(
                        "{owner}yield_strength needs a thickness to give a stress: give modulus, width and thickness (a flexure given by ei alone has no stress)"
                    ),
                );
            }
            Some(s)
        }
        None => None,
    };
    let shape = match &j.shape {
        Some(k) if !(2..=MAX_SHAPE).contains(k.get_ref()) => {
            return src
                .fail(&k.span(), format!("{owner}shape = {}: must be from 2 to {MAX_SHAPE} points", k.get_ref()));
        }
        k => k.as_ref().map(|k| *k.get_ref()),
    };
    Ok(Report { yield_strength, shape })
}

/// Each flexure joint's [`Report`] keys, by joint name in file order. The
/// file is checked first, as by [`from_toml`].
///
/// # Example
/// ```
/// let text = "[[joint]]\nname = \"hinge\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"arm\"\n\
///             length = 0.02\nmodulus = 2e11\nwidth = 0.01\nthickness = [4e-4, 2e-4]\nyield_strength = 5e8\nshape = 11\n";
/// let r = flexure::mechanism::file::reports(text).unwrap();
/// assert_eq!(r[0].0, "hinge");
/// assert_eq!((r[0].1.yield_strength, r[0].1.shape), (Some(5e8), Some(11)));
/// ```
pub fn reports(text: &str) -> Result<Vec<(String, Report)>> {
    let m = from_toml(text)?;
    let file: FileToml = toml::from_str(text)
        .map_err(|e| Error::File { place: place(text, 0), message: e.message().trim().to_string() })?;
    let flexures = m.joints.iter().filter(|j| matches!(j.kind, JointKind::Flexure(_)));
    Ok(flexures
        .map(|spec| {
            let j = file.joint.iter().find(|j| j.name.get_ref() == &spec.name);
            let r = j.map_or_else(Report::default, |j| Report {
                yield_strength: j.yield_strength.as_ref().map(|v| *v.get_ref()),
                shape: j.shape.as_ref().map(|v| *v.get_ref()),
            });
            (spec.name.clone(), r)
        })
        .collect())
}
