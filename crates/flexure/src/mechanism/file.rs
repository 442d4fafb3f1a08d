//! The mechanism file (TOML; SI units; angles in radians).
//!
//! Parses text (the caller reads the file) and checks every name, number
//! and connection; errors name the place, with line and column.

use super::joints::{Fixed, Prismatic, Revolute};
use super::{Body, Closure, JointKind, JointSpec, Mechanism, PointLoad, Tendon};
use crate::error::{Error, Result};
use crate::joint::{Flexure, bending_stiffness};
use crate::kinematics::Pose;
use serde::Deserialize;
use toml::Spanned;

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
    #[serde(default)]
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
    #[serde(default)]
    mass: f64,
    #[serde(default)]
    com: [f64; 2],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TendonToml {
    name: Spanned<String>,
    tension: Spanned<f64>,
    path: Spanned<Vec<(Spanned<String>, f64, f64)>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ForceToml {
    name: Option<Spanned<String>>,
    body: Spanned<String>,
    at: Spanned<[f64; 2]>,
    #[serde(default)]
    force: [f64; 2],
    #[serde(default)]
    moment: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WeldToml {
    a: Spanned<String>,
    #[serde(default)]
    a_origin: [f64; 3],
    b: Spanned<String>,
    #[serde(default)]
    b_origin: [f64; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PinToml {
    a: Spanned<String>,
    #[serde(default)]
    a_at: [f64; 2],
    b: Spanned<String>,
    #[serde(default)]
    b_at: [f64; 2],
}

/// "line L, column C" of a byte offset.
fn place(text: &str, offset: usize) -> String {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    format!("line {line}, column {column}")
}

fn err<T>(text: &str, span: std::ops::Range<usize>, message: String) -> Result<T> {
    Err(Error::File { place: place(text, span.start), message })
}

fn finite(text: &str, span: std::ops::Range<usize>, what: &str, values: &[f64]) -> Result<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        err(text, span, format!("{what} must be finite numbers, got {values:?}"))
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
/// ```
pub fn from_toml(text: &str) -> Result<Mechanism> {
    let file: FileToml = toml::from_str(text).map_err(|e| {
        let at = e.span().map(|s| place(text, s.start)).unwrap_or_else(|| "the file".into());
        Error::File { place: at, message: e.message().trim().to_string() }
    })?;
    let mut bodies = vec![Body { name: "ground".into(), mass: 0.0, com: [0.0; 2] }];
    // Bodies are created by the joints that name them as child.
    for j in &file.joint {
        let name = j.child.get_ref();
        if name == "ground" {
            return err(text, j.child.span(), format!("joint {:?}: the ground cannot be a child", j.name.get_ref()));
        }
        if bodies.iter().any(|b| &b.name == name) {
            return err(text, j.child.span(), format!("body {name:?} is reached by two joints"));
        }
        bodies.push(Body { name: name.clone(), mass: 0.0, com: [0.0; 2] });
    }
    let names: Vec<String> = bodies.iter().map(|b| b.name.clone()).collect();
    let find = |name: &Spanned<String>| -> Result<usize> {
        names.iter().position(|b| b == name.get_ref()).map_or_else(
            || {
                err(
                    text,
                    name.span(),
                    format!("unknown body {:?}: bodies are ground and the joints' children", name.get_ref()),
                )
            },
            Ok,
        )
    };
    for (i, j) in file.joint.iter().enumerate() {
        if file.joint[..i].iter().any(|k| k.name.get_ref() == j.name.get_ref()) {
            return err(text, j.name.span(), format!("duplicate joint name {:?}", j.name.get_ref()));
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
        return err(
            text,
            j.parent.span(),
            format!("joint {:?} is on a cycle of joints, not reachable from ground", j.name.get_ref()),
        );
    }
    let mut joints = Vec::new();
    let mut parent_joint = vec![None; bodies.len()];
    let mut offset = 0;
    for &i in &order {
        let j = &file.joint[i];
        let origin = j.origin.as_ref().map_or([0.0; 3], |o| *o.get_ref());
        if let Some(o) = &j.origin {
            finite(text, o.span(), "origin", &origin)?;
        }
        let kind = joint_kind(text, j)?;
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
        offset += dof;
    }
    for b in &file.body {
        let idx = find(&b.name)?;
        if !(b.mass.is_finite() && b.mass >= 0.0 && b.com.iter().all(|c| c.is_finite())) {
            return err(
                text,
                b.name.span(),
                format!("body {:?}: mass must be finite and not negative, com finite", b.name.get_ref()),
            );
        }
        bodies[idx].mass = b.mass;
        bodies[idx].com = b.com;
    }
    let mut tendons = Vec::new();
    for t in &file.tendon {
        if tendons.iter().any(|u: &Tendon| &u.name == t.name.get_ref()) {
            return err(text, t.name.span(), format!("duplicate tendon name {:?}", t.name.get_ref()));
        }
        if !(t.tension.get_ref().is_finite() && *t.tension.get_ref() >= 0.0) {
            return err(
                text,
                t.tension.span(),
                format!("tendon {:?}: tension must be finite and not negative", t.name.get_ref()),
            );
        }
        if t.path.get_ref().len() < 2 {
            return err(
                text,
                t.path.span(),
                format!("tendon {:?}: a path needs at least two via points", t.name.get_ref()),
            );
        }
        let mut path = Vec::new();
        for (body, x, y) in t.path.get_ref() {
            finite(text, body.span(), "via point", &[*x, *y])?;
            path.push((find(body)?, [*x, *y]));
        }
        tendons.push(Tendon { name: t.name.get_ref().clone(), tension: *t.tension.get_ref(), path });
    }
    let mut forces = Vec::new();
    for (i, f) in file.force.iter().enumerate() {
        let name = f.name.as_ref().map_or(i.to_string(), |n| n.get_ref().clone());
        if forces.iter().any(|g: &PointLoad| g.name == name) {
            let span = f.name.as_ref().map_or(f.body.span(), |n| n.span());
            return err(text, span, format!("duplicate force name {name:?}"));
        }
        finite(
            text,
            f.at.span(),
            "force at, force and moment",
            &[f.at.get_ref()[0], f.at.get_ref()[1], f.force[0], f.force[1], f.moment],
        )?;
        forces.push(PointLoad { name, body: find(&f.body)?, at: *f.at.get_ref(), force: f.force, moment: f.moment });
    }
    let mut closures = Vec::new();
    for w in &file.weld {
        finite(text, w.a.span(), "weld origins", &[w.a_origin, w.b_origin].concat())?;
        let pose = |o: [f64; 3]| Pose { x: o[0], y: o[1], phi: o[2] };
        closures.push(Closure::Weld {
            a: find(&w.a)?,
            a_origin: pose(w.a_origin),
            b: find(&w.b)?,
            b_origin: pose(w.b_origin),
        });
    }
    for p in &file.pin {
        finite(text, p.a.span(), "pin points", &[p.a_at, p.b_at].concat())?;
        closures.push(Closure::Pin { a: find(&p.a)?, a_at: p.a_at, b: find(&p.b)?, b_at: p.b_at });
    }
    let gravity = match &file.gravity {
        Some(g) => {
            finite(text, g.span(), "gravity", g.get_ref())?;
            *g.get_ref()
        }
        None => [0.0; 2],
    };
    let m = Mechanism { bodies, joints, tendons, forces, closures, gravity, parent_joint, dof: offset };
    Ok(m)
}

fn joint_kind(text: &str, j: &JointToml) -> Result<JointKind> {
    let name = j.name.get_ref();
    let at = |e: Error, span: std::ops::Range<usize>| -> Error {
        let what = match &e {
            Error::InvalidParameter { name: p, value, reason } => format!("joint {name:?}: {p} = {value}: {reason}"),
            other => format!("joint {name:?}: {other}"),
        };
        Error::File { place: place(text, span.start), message: what }
    };
    let spring = |v: &Option<Spanned<f64>>, what: &str| -> Result<f64> {
        match v {
            Some(s) if !(s.get_ref().is_finite() && (what == "rest" || *s.get_ref() >= 0.0)) => err(
                text,
                s.span(),
                format!(
                    "joint {name:?}: {what} must be finite{}",
                    if what == "rest" { "" } else { " and not negative" }
                ),
            ),
            Some(s) => Ok(*s.get_ref()),
            None => Ok(0.0),
        }
    };
    match j.kind.get_ref().as_str() {
        "flexure" => {
            let length = j
                .length
                .as_ref()
                .ok_or_else(|| at(Error::invalid("length", "nothing", "a flexure needs a length"), j.name.span()))?;
            let ei = match (&j.ei, &j.modulus) {
                (Some(ei), None) => *ei.get_ref(),
                (None, Some(e)) => {
                    let w = j.width.as_ref().map_or(f64::NAN, |v| *v.get_ref());
                    let h = j.thickness.as_ref().map_or(f64::NAN, |v| *v.get_ref());
                    bending_stiffness(*e.get_ref(), w, h, j.poisson.as_ref().map(|p| *p.get_ref()))
                        .map_err(|x| at(x, e.span()))?
                }
                (Some(ei), Some(_)) => {
                    return err(
                        text,
                        ei.span(),
                        format!("joint {name:?}: give ei or modulus, width, thickness, not both"),
                    );
                }
                (None, None) => {
                    return err(
                        text,
                        j.name.span(),
                        format!("joint {name:?}: a flexure needs ei, or modulus, width and thickness"),
                    );
                }
            };
            let order = j.order.as_ref().map_or(3, |o| *o.get_ref());
            let span = j.ei.as_ref().map_or(length.span(), |e| e.span());
            let mut f = Flexure::new(*length.get_ref(), ei, order)
                .map_err(|x| at(x, if ei > 0.0 { length.span() } else { span }))?;
            if let Some(q) = &j.quadrature {
                f = f.with_quadrature(*q.get_ref()).map_err(|x| at(x, q.span()))?;
            }
            if let Some(k) = &j.kappa {
                f = f.with_rest(k.get_ref()).map_err(|x| at(x, k.span()))?;
            }
            Ok(JointKind::Flexure(Box::new(f)))
        }
        "revolute" => Ok(JointKind::Revolute(Revolute {
            stiffness: spring(&j.stiffness, "stiffness")?,
            rest: spring(&j.rest, "rest")?,
        })),
        "prismatic" => Ok(JointKind::Prismatic(Prismatic {
            stiffness: spring(&j.stiffness, "stiffness")?,
            rest: spring(&j.rest, "rest")?,
        })),
        "fixed" => Ok(JointKind::Fixed(Fixed)),
        other => err(
            text,
            j.kind.span(),
            format!("joint {name:?}: unknown kind {other:?}; expected flexure, revolute, prismatic or fixed"),
        ),
    }
}
