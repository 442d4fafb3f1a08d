//! The spatial mechanism file (`dimension = 3`): the same tables as the
//! planar file, with 3-D points, URDF placements (`origin`, `rpy` or
//! `rpy_deg`), 3 × 3 inertias, hinge and slider axes, ball joints,
//! spatial flexures, `[[ball]]` closures beside `[[weld]]` and `[[pin]]`,
//! and the planar `[[schedule]]` tables with the spatial loads' names.
//! One part of the document per module, as for the planar file.

mod joints;
mod parts;

use super::document::{Sign, Source, Span, place};
use super::schedules::ScheduleToml;
use super::{Error, Result, Spanned};
use crate::mechanism::spatial::{SpatialBody, SpatialMechanism};
use crate::mechanism::sweep::SpatialParameter;
use joints::JointToml;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use parts::{BallToml, BodyToml, ForceToml, PinToml, TendonToml, WeldToml};
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileToml {
    #[allow(dead_code)]
    dimension: Spanned<toml::Value>,
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
    #[serde(default)]
    ball: Vec<BallToml>,
    gravity: Option<Spanned<[f64; 3]>>,
    #[serde(default)]
    schedule: Vec<ScheduleToml>,
    initial: Option<BTreeMap<String, Spanned<toml::Value>>>,
    initial_velocity: Option<BTreeMap<String, Spanned<toml::Value>>>,
}

impl Source<'_> {
    /// A placement: `origin = [x, y, z]` (m) and `rpy = [roll, pitch, yaw]`
    /// (rad) or `rpy_deg` (degrees), URDF's fixed-axis convention
    /// $R = R_z(\text{yaw})R_y(\text{pitch})R_x(\text{roll})$; the keys named by `keys`.
    fn placement(
        &self,
        owner: &str,
        keys: [&str; 3],
        origin: &Option<Spanned<[f64; 3]>>,
        rpy: &Option<Spanned<[f64; 3]>>,
        rpy_deg: &Option<Spanned<[f64; 3]>>,
    ) -> Result<Isometry3<f64>> {
        let p = self.array(owner, keys[0], origin)?;
        let angles = match (rpy, rpy_deg) {
            (Some(_), Some(d)) => {
                return self
                    .fail(&d.span(), format!("{owner}give {} (rad) or {} (degrees), not both", keys[1], keys[2]));
            }
            (Some(_), None) => self.array(owner, keys[1], rpy)?,
            (None, Some(_)) => self.array(owner, keys[2], rpy_deg)?.map(f64::to_radians),
            (None, None) => [0.0; 3],
        };
        Ok(Isometry3::from_parts(
            Translation3::new(p[0], p[1], p[2]),
            UnitQuaternion::from_euler_angles(angles[0], angles[1], angles[2]),
        ))
    }
}

/// The planar file's keys that a spatial file does not take, each with why
/// and what to write instead.
const PLANAR_ONLY: [(&str, &str); 2] = [
    (
        "notch",
        "a circular notch hinge: the spatial section's thickness is constant, linear or a table, not yet a circle's arc; give `thickness` as a table of points along the notch",
    ),
    (
        "quadrature",
        "the planar flexure's Gauss rule: a spatial flexure integrates by Magnus steps, whose number `subintervals` sets",
    ),
];

/// A TOML or serde error of `text`, placed. A message that names no key
/// (a wrong type, an array's length) is given the key its line starts
/// with (`at: invalid length 2, expected an array of length 3`), and a
/// planar key the spatial file does not take yet is said to be one.
fn toml_error(text: &str, e: toml::de::Error) -> Error {
    let at = e.span().map_or(0, |s| s.start).min(text.len());
    let message = e.message().trim().to_string();
    let line = &text[text[..at].rfind('\n').map_or(0, |n| n + 1)..at];
    let key = line.split_once('=').map(|(k, _)| k.trim()).filter(|k| {
        !k.is_empty()
            && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !["unknown field", "missing field", "duplicate"].iter().any(|p| message.starts_with(p))
    });
    let unknown = message.strip_prefix("unknown field `").and_then(|m| m.split('`').next());
    let message = match (key, unknown.and_then(|u| PLANAR_ONLY.iter().find(|(k, _)| *k == u))) {
        (_, Some((k, why))) => format!("`{k}` is for planar mechanisms: {why}"),
        (Some(k), None) => format!("{k}: {message}"),
        (None, None) => message,
    };
    Error::File { place: place(text, at), message }
}

/// The file's `dimension` and the offset of its value (0 when absent): 2
/// when absent; an error naming it unless 2 or 3.
pub(super) fn dimension(text: &str) -> Result<(u8, usize)> {
    // Every top-level value with its place: only `dimension` is read here.
    // (Placed as the planar parser places its own errors: a planar file reads as before.)
    let top: BTreeMap<String, Spanned<toml::Value>> = toml::from_str(text).map_err(|e| Error::File {
        place: place(text, e.span().map_or(0, |s| s.start)),
        message: e.message().trim().to_string(),
    })?;
    match top.get("dimension") {
        None => Ok((2, 0)),
        Some(d) => match d.get_ref() {
            toml::Value::Integer(2) => Ok((2, d.span().start)),
            toml::Value::Integer(3) => Ok((3, d.span().start)),
            v => Err(Error::File {
                place: place(text, d.span().start),
                message: format!(
                    "dimension = {}: must be 2 (a planar mechanism, the default) or 3 (a spatial one)",
                    shown(v)
                ),
            }),
        },
    }
}

/// A TOML value as the file writes it.
fn shown(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => format!("{s:?}"),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(x) => format!("{x:?}"),
        other => format!("a {}", other.type_str()),
    }
}

/// Parses and checks a spatial mechanism file (one with `dimension = 3`).
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
pub fn spatial_from_toml(text: &str) -> Result<SpatialMechanism> {
    if text.len() > super::MAX_TEXT_BYTES {
        return Err(Error::File {
            place: "the whole file".into(),
            message: format!(
                "{} bytes, more than the {} MiB a mechanism file may hold",
                text.len(),
                super::MAX_TEXT_BYTES >> 20
            ),
        });
    }
    if dimension(text)?.0 != 3 {
        return Err(Error::File {
            place: place(text, 0),
            message:
                "a planar mechanism (no `dimension = 3`): read it with `from_toml`, or `Model::from_toml` for either"
                    .into(),
        });
    }
    let src = Source { text };
    let file: FileToml = toml::from_str(text).map_err(|e| toml_error(text, e))?;
    // Bodies: the ground and each joint's child, in file order.
    let mut names = vec!["ground".to_string()];
    for j in &file.joint {
        let name = j.child.get_ref();
        if name == "ground" {
            return src.fail(&j.child.span(), format!("joint {:?}: the ground cannot be a child", j.name.get_ref()));
        }
        if names.contains(name) {
            return src.fail(&j.child.span(), format!("body {name:?} is reached by two joints"));
        }
        names.push(name.clone());
    }
    let find = |name: &Spanned<String>| -> Result<usize> {
        names.iter().position(|b| b == name.get_ref()).ok_or_else(|| {
            src.error(
                &name.span(),
                format!("unknown body {:?}: bodies are ground and the joints' children", name.get_ref()),
            )
        })
    };
    let mut bodies: Vec<SpatialBody> = names.iter().map(|n| SpatialBody::massless(n)).collect();
    let joints = joints::joints(&src, &find, &file.joint)?;
    parts::describe(&src, &find, &mut bodies, &file.body)?;
    let tendons = parts::tendons(&src, &find, &file.tendon)?;
    let forces = parts::forces(&src, &find, &file.force)?;
    let gravity = Vector3::from(src.array("", "gravity", &file.gravity)?);
    let (mut m, places) = {
        // The pins' axes on `b` are where they lie at rest: the tree's rest frames first.
        let tree = SpatialMechanism::new(bodies.clone(), joints.clone(), vec![], vec![], vec![], gravity)
            .map_err(|e| Error::File { place: place(text, 0), message: e.to_string() })?;
        // At the pose level: the bodies' frames are the same at every level,
        // and the Hessians cost most at high orders.
        let mut rest = crate::mechanism::spatial::kinematics::SpatialFrames::new(&tree);
        crate::mechanism::spatial::kinematics::frames_level_into(&tree, &tree.rest(), crate::Level::Pose, &mut rest);
        let (closures, places) = parts::closures(&src, &find, &rest.bodies, (&file.weld, &file.pin, &file.ball))?;
        let m = SpatialMechanism::new(bodies, joints, tendons, forces, closures, gravity)
            .map_err(|e| Error::File { place: place(text, 0), message: e.to_string() })?;
        (m, places)
    };
    let (places, preloads) = places.into_iter().unzip();
    m = m.with_closure_places(places, preloads);
    m.schedules = super::schedules::schedules(
        &src,
        &file.schedule,
        |load| SpatialParameter::parse(&m, load),
        |p| matches!(p, SpatialParameter::Tension(_)),
    )?;
    m.initial = initial_state(&src, &m, "initial", file.initial.as_ref())?;
    m.initial_velocity = initial_state(&src, &m, "initial_velocity", file.initial_velocity.as_ref())?;
    Ok(m)
}

/// `[initial]` or `[initial_velocity]`: joint name → a number (a joint of
/// one coordinate) or an array of as many numbers as it has coordinates.
fn initial_state(
    src: &Source,
    m: &SpatialMechanism,
    key: &str,
    table: Option<&BTreeMap<String, Spanned<toml::Value>>>,
) -> Result<Vec<(usize, Vec<f64>)>> {
    let Some(table) = table else { return Ok(Vec::new()) };
    let mut out = Vec::new();
    for (name, value) in table {
        let span: Span = value.span();
        let Some(j) = m.joints.iter().position(|j| &j.name == name) else {
            return src.fail(&span, format!("[{key}]: unknown joint {name:?}"));
        };
        let dof = m.joints[j].kind.joint().dof();
        let number = |v: &toml::Value| match v {
            toml::Value::Float(x) => Some(*x),
            toml::Value::Integer(i) => Some(*i as f64),
            _ => None,
        };
        let values: Option<Vec<f64>> = match value.get_ref() {
            toml::Value::Array(a) => a.iter().map(number).collect(),
            v => number(v).map(|x| vec![x]),
        };
        let Some(values) = values.filter(|v| v.len() == dof) else {
            return src
                .fail(&span, format!("[{key}] {name}: must be {dof} number(s), one per coordinate of the joint"));
        };
        src.numbers(&format!("[{key}] "), name, &span, &values, Sign::Any)?;
        out.push((j, values));
    }
    Ok(out)
}
