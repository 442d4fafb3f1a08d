//! The mechanism file (TOML; SI units; angles in radians).
//!
//! Parses text (the caller reads the file) and checks every name, number
//! and connection; every error names the key (or the entry) and its place,
//! line and column. Numbers must be finite and either zero or between
//! [`MIN_MAGNITUDE`] and [`MAX_MAGNITUDE`] in magnitude; keys that do not
//! apply to a joint's kind are refused rather than ignored.

use super::joints::{Fixed, Prismatic, Revolute};
use super::kinematics::frames;
use super::{Body, Closure, JointKind, JointSpec, Mechanism, PointLoad, Tendon};
use crate::error::{Error, Result};
use crate::joint::{Flexure, bending_stiffness};
use crate::kinematics::Pose;
use serde::Deserialize;
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
    ei: Option<Spanned<f64>>,
    modulus: Option<Spanned<f64>>,
    width: Option<Spanned<f64>>,
    thickness: Option<Spanned<f64>>,
    poisson: Option<Spanned<f64>>,
    order: Option<Spanned<usize>>,
    quadrature: Option<Spanned<usize>>,
    kappa: Option<Spanned<Vec<f64>>>,
    stiffness: Option<Spanned<f64>>,
    rest: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyToml {
    name: Spanned<String>,
    mass: Option<Spanned<f64>>,
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
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PinToml {
    a: Spanned<String>,
    a_at: Option<Spanned<[f64; 2]>>,
    b: Spanned<String>,
    b_at: Option<Spanned<[f64; 2]>>,
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

    /// A library error about `owner`'s value at `span`, placed.
    fn placed(&self, owner: &str, span: &Span, e: Error) -> Error {
        let message = match &e {
            Error::InvalidParameter { name, value, reason } => format!("{owner}{name} = {value}: {reason}"),
            other => format!("{owner}{other}"),
        };
        self.error(span, message)
    }
}

/// Parses and checks a mechanism file.
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
    let src = Source { text };
    let file: FileToml = toml::from_str(text).map_err(|e| {
        // Errors without a span (rare) concern the file as a whole.
        let at = place(text, e.span().map_or(0, |s| s.start));
        Error::File { place: at, message: e.message().trim().to_string() }
    })?;
    let mut bodies = vec![Body { name: "ground".into(), mass: 0.0, com: [0.0; 2] }];
    // Bodies are created by the joints that name them as child.
    for j in &file.joint {
        let name = j.child.get_ref();
        if name == "ground" {
            return src.fail(&j.child.span(), format!("joint {:?}: the ground cannot be a child", j.name.get_ref()));
        }
        if bodies.iter().any(|b| &b.name == name) {
            return src.fail(&j.child.span(), format!("body {name:?} is reached by two joints"));
        }
        bodies.push(Body { name: name.clone(), mass: 0.0, com: [0.0; 2] });
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
        let (kind, stiffness_place) = joint_kind(&src, &owner, j)?;
        let dof = kind.joint().dof();
        parent_joint[i + 1] = Some(joints.len());
        joints.push(JointSpec {
            name: j.name.get_ref().clone(),
            kind,
            parent: parents[i],
            child: i + 1,
            origin: Pose { x: origin[0], y: origin[1], phi: origin[2] },
            offset,
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
    let m = Mechanism { bodies, joints, tendons, forces, closures, gravity, parent_joint, dof: offset, closure_places };
    check_stiffness_ratio(&src, &m, &stiffness_places)?;
    check_tendon_directions(&src, &m, &via_places)?;
    Ok(m)
}

/// The joints' diagonal stiffnesses span at most [`MAX_STIFFNESS_RATIO`].
fn check_stiffness_ratio(src: &Source, m: &Mechanism, places: &[Span]) -> Result<()> {
    let rest = frames(m, &m.rest());
    let length: f64 = m
        .joints
        .iter()
        .map(|j| j.origin.x.hypot(j.origin.y) + if let JointKind::Flexure(f) = &j.kind { f.length() } else { 0.0 })
        .sum();
    let length = if length > 0.0 { length } else { 1.0 };
    // (joint, stiffness in N·m)
    let mut all: Vec<(usize, f64)> = Vec::new();
    for (i, (j, s)) in m.joints.iter().zip(&rest.joints).enumerate() {
        let unit = if let JointKind::Prismatic(_) = j.kind { length * length } else { 1.0 };
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
        ("order", j.order.as_ref().map(Spanned::span)),
        ("quadrature", j.quadrature.as_ref().map(Spanned::span)),
        ("kappa", j.kappa.as_ref().map(Spanned::span)),
    ];
    let spring = [("stiffness", j.stiffness.as_ref().map(Spanned::span)), ("rest", j.rest.as_ref().map(Spanned::span))];
    let foreign: Vec<(&'static str, Option<Span>)> = match kind {
        "flexure" => spring.to_vec(),
        "revolute" | "prismatic" => flexure.to_vec(),
        _ => flexure.iter().chain(&spring).cloned().collect(),
    };
    foreign.into_iter().find_map(|(k, s)| s.map(|s| (k, s)))
}

/// The joint's kind, and the place of the key that sets its stiffness.
fn joint_kind(src: &Source, owner: &str, j: &JointToml) -> Result<(JointKind, Span)> {
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
            let section = [("width", &j.width), ("thickness", &j.thickness), ("poisson", &j.poisson)];
            let (ei, ei_span) = match (&j.ei, &j.modulus) {
                (Some(ei), None) => {
                    if let Some((key, Some(v))) = section.iter().find(|(_, v)| v.is_some()) {
                        return src.fail(&v.span(), format!("{owner}`{key}` goes with modulus, not with ei"));
                    }
                    (src.number(owner, "ei", ei, Sign::Positive)?, ei.span())
                }
                (None, Some(e)) => {
                    let e_value = src.number(owner, "modulus", e, Sign::Positive)?;
                    let part = |key: &str, v: &Option<Spanned<f64>>| -> Result<f64> {
                        let v = v.as_ref().ok_or_else(|| {
                            src.error(&e.span(), format!("{owner}modulus needs width and thickness; {key} is missing"))
                        })?;
                        src.number(owner, key, v, Sign::Positive)
                    };
                    let (w, h) = (part("width", &j.width)?, part("thickness", &j.thickness)?);
                    let nu = match &j.poisson {
                        Some(p) => Some(src.number(owner, "poisson", p, Sign::Any)?),
                        None => None,
                    };
                    let ei = bending_stiffness(e_value, w, h, nu).map_err(|x| {
                        let span = match &x {
                            Error::InvalidParameter { name: "poisson", .. } => {
                                j.poisson.as_ref().map_or(e.span(), Spanned::span)
                            }
                            _ => e.span(),
                        };
                        src.placed(owner, &span, x)
                    })?;
                    // The product may leave the magnitudes its parts kept.
                    src.numbers(owner, "ei (from modulus, width, thickness)", &e.span(), &[ei], Sign::Positive)?;
                    (ei, e.span())
                }
                (Some(ei), Some(_)) => {
                    return src.fail(&ei.span(), format!("{owner}give ei or modulus, width, thickness, not both"));
                }
                (None, None) => {
                    return src
                        .fail(&j.name.span(), format!("{owner}a flexure needs ei, or modulus, width and thickness"));
                }
            };
            let order = j.order.as_ref().map_or(3, |o| *o.get_ref());
            let order_span = j.order.as_ref().map_or(j.name.span(), Spanned::span);
            let mut f = Flexure::new(l, ei, order).map_err(|x| {
                let span = match &x {
                    Error::InvalidParameter { name: "length", .. } => length.span(),
                    Error::InvalidParameter { name: "ei", .. } => ei_span.clone(),
                    _ => order_span.clone(),
                };
                src.placed(owner, &span, x)
            })?;
            if let Some(q) = &j.quadrature {
                f = f.with_quadrature(*q.get_ref()).map_err(|x| src.placed(owner, &q.span(), x))?;
            }
            if let Some(k) = &j.kappa {
                src.numbers(owner, "kappa", &k.span(), k.get_ref(), Sign::Any)?;
                f = f.with_rest(k.get_ref()).map_err(|x| src.placed(owner, &k.span(), x))?;
            }
            Ok((JointKind::Flexure(Box::new(f)), ei_span))
        }
        "revolute" => Ok((
            JointKind::Revolute(Revolute {
                stiffness: spring("stiffness", &j.stiffness, Sign::NotNegative)?,
                rest: spring("rest", &j.rest, Sign::Any)?,
            }),
            stiffness_place,
        )),
        "prismatic" => Ok((
            JointKind::Prismatic(Prismatic {
                stiffness: spring("stiffness", &j.stiffness, Sign::NotNegative)?,
                rest: spring("rest", &j.rest, Sign::Any)?,
            }),
            stiffness_place,
        )),
        _ => Ok((JointKind::Fixed(Fixed), j.name.span())),
    }
}
