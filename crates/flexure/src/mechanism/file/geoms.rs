//! Geoms: the shapes on the ground and on bodies that parts may touch,
//! their keys checked shape by shape, and their `exclude` lists.

use super::bodies::Find;
use super::dimension::FileDimension;
use super::document::{Numbers, Sign, Source, Span, number};
use super::{Deserialize, Mechanism, Result, Spanned};
use crate::error::Error;
use crate::mechanism::JointKind;
use crate::mechanism::contact::{Geom, GeomShape, Toucher};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "")]
pub(super) struct GeomToml<D: FileDimension> {
    pub(super) name: Option<Spanned<String>>,
    pub(super) body: Spanned<String>,
    pub(super) shape: Spanned<String>,
    pub(super) origin: Option<Spanned<D::Coords>>,
    // In the plane the angle about z (rad); in space `rpy` or `rpy_deg`.
    pub(super) angle: Option<Spanned<f64>>,
    pub(super) rpy: Option<Spanned<[f64; 3]>>,
    pub(super) rpy_deg: Option<Spanned<[f64; 3]>>,
    pub(super) normal: Option<Spanned<D::Coords>>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) half_length: Option<Spanned<f64>>,
    pub(super) half_extents: Option<Spanned<D::Coords>>,
    pub(super) friction: Option<Spanned<f64>>,
    pub(super) exclude: Option<Vec<Spanned<String>>>,
}

/// The shapes a file names, and the keys each takes beyond `name`, `body`,
/// `shape`, `origin`, `friction` and `exclude`: (shape, needed, may turn).
const SHAPE_KEYS: &[(&str, &[&str], bool)] = &[
    ("plane", &["normal"], false),
    ("circle", &["radius"], false),
    ("sphere", &["radius"], false),
    ("capsule", &["radius", "half_length"], true),
    ("box", &["half_extents"], true),
    ("cylinder", &["radius", "half_length"], true),
];

/// The file's geoms, in its order, on the mechanism `m` whose bodies and
/// joints `find` and `m` name; each geom's place (its `shape`), for the
/// checks of the assembled mechanism.
pub(super) fn geoms<D: FileDimension>(
    src: &Source,
    find: &Find,
    m: &Mechanism<D>,
    tables: &[GeomToml<D>],
) -> Result<(Vec<Geom<D>>, Vec<Span>)> {
    let mut out: Vec<Geom<D>> = Vec::with_capacity(tables.len());
    for (i, g) in tables.iter().enumerate() {
        let name = match &g.name {
            Some(n) => {
                if out.iter().any(|o| &o.name == n.get_ref()) {
                    return src.fail(&n.span(), format!("geom {:?}: two geoms have this name", n.get_ref()));
                }
                n.get_ref().clone()
            }
            None => format!("geom {}", i + 1),
        };
        let owner = format!("geom {name:?}: ");
        // Named by its geom and key, as its other fields are.
        let body = find(&g.body).map_err(|e| match e {
            Error::File { place, message } => Error::File { place, message: format!("{owner}body: {message}") },
            e => e,
        })?;
        let shape = shape::<D>(src, &owner, g)?;
        let frame = D::geom_frame(src, &owner, g)?;
        let friction = g.friction.as_ref().map_or(Ok(0.0), |f| src.number(&owner, "friction", f, Sign::NotNegative))?;
        out.push(Geom { name, body, frame, shape, friction, exclude: Vec::new() });
    }
    for (i, g) in tables.iter().enumerate() {
        for e in g.exclude.iter().flatten() {
            let parts = excluded(src, m, &out, i, e)?;
            out[i].exclude.extend(parts);
        }
        out[i].exclude.sort();
        out[i].exclude.dedup();
    }
    Ok((out, tables.iter().map(|g| g.shape.span()).collect()))
}

/// The parts a geom's `exclude` entry names: a flexure joint, a body's geoms, or a geom.
fn excluded<D: FileDimension>(
    src: &Source,
    m: &Mechanism<D>,
    geoms: &[Geom<D>],
    own: usize,
    name: &Spanned<String>,
) -> Result<Vec<Toucher>> {
    let owner = format!("geom {:?}: exclude: ", geoms[own].name);
    let n = name.get_ref();
    if let Some(h) = geoms.iter().position(|g| &g.name == n) {
        if h == own {
            return src.fail(&name.span(), format!("{owner}{n:?} is this geom itself"));
        }
        return Ok(vec![Toucher::Geom(h)]);
    }
    if let Some(j) = m.joints.iter().position(|j| &j.name == n) {
        return match m.joints[j].kind {
            JointKind::Flexure(_) => Ok(vec![Toucher::Flexure(j)]),
            _ => src.fail(
                &name.span(),
                format!("{owner}joint {n:?} is not a flexure: of the joints only flexures touch geoms"),
            ),
        };
    }
    if let Some(b) = m.body(n) {
        return Ok(geoms.iter().enumerate().filter(|(_, g)| g.body == b).map(|(h, _)| Toucher::Geom(h)).collect());
    }
    src.fail(&name.span(), format!("{owner}unknown part {n:?}: name a flexure joint, a body (its geoms) or a geom"))
}

/// A geom's shape from its keys: those its shape needs, checked, and
/// none it does not take.
fn shape<D: FileDimension>(src: &Source, owner: &str, g: &GeomToml<D>) -> Result<GeomShape<D>> {
    let written = g.shape.get_ref().as_str();
    let span = g.shape.span();
    if let Some(why) = D::refused_shape(written) {
        return src.fail(&span, format!("{owner}shape = {written:?} is for {}: {why}", D::OTHER));
    }
    let Some((_, needed, turns)) = SHAPE_KEYS.iter().find(|(s, _, _)| *s == written && D::takes_shape(s)) else {
        let known: Vec<String> =
            SHAPE_KEYS.iter().filter(|(s, _, _)| D::takes_shape(s)).map(|(s, _, _)| format!("{s:?}")).collect();
        return src.fail(&span, format!("{owner}unknown shape {written:?}: must be one of {}", known.join(", ")));
    };
    let given: [(&str, Option<Span>); 4] = [
        ("normal", g.normal.as_ref().map(|v| v.span())),
        ("radius", g.radius.as_ref().map(|v| v.span())),
        ("half_length", g.half_length.as_ref().map(|v| v.span())),
        ("half_extents", g.half_extents.as_ref().map(|v| v.span())),
    ];
    for (key, at) in &given {
        match (needed.contains(key), at) {
            (true, None) => return src.fail(&span, format!("{owner}a {written} needs `{key}`")),
            (false, Some(at)) => return src.fail(at, format!("{owner}`{key}` does not apply to a {written}")),
            _ => {}
        }
    }
    let turn = [g.angle.as_ref().map(|v| ("angle", v.span())), g.rpy.as_ref().map(|v| ("rpy", v.span()))];
    let turn_deg = g.rpy_deg.as_ref().map(|v| ("rpy_deg", v.span()));
    if let (false, Some((key, at))) = (turns, turn.into_iter().chain([turn_deg]).flatten().next()) {
        return src.fail(
            &at,
            format!(
                "{owner}`{key}` does not apply to a {written}: it looks the same turned (a plane turns by its `normal`)"
            ),
        );
    }
    let positive = |key: &str, v: &Option<Spanned<f64>>| -> Result<f64> {
        src.number(owner, key, v.as_ref().expect("checked above"), Sign::Positive)
    };
    Ok(match written {
        "plane" => {
            let n = g.normal.as_ref().expect("checked above");
            src.array_numbers(owner, "normal", &n.span(), n.get_ref().numbers(), Sign::Any)?;
            let v = D::vector(*n.get_ref());
            let norm = n.get_ref().numbers().iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm == 0.0 {
                let shown: Vec<String> = n.get_ref().numbers().iter().map(|x| number(*x)).collect();
                return src.fail(
                    &n.span(),
                    format!("{owner}normal = [{}]: must not be zero: it points out of the solid", shown.join(", ")),
                );
            }
            let mut unit = v;
            for i in 0..D::POINT_DIM {
                unit[i] /= norm;
            }
            GeomShape::Plane { normal: unit }
        }
        "circle" | "sphere" => GeomShape::Ball { radius: positive("radius", &g.radius)? },
        "capsule" => {
            let radius = positive("radius", &g.radius)?;
            let h = g.half_length.as_ref().expect("checked above");
            GeomShape::Capsule { half_length: src.number(owner, "half_length", h, Sign::NotNegative)?, radius }
        }
        "box" => {
            let e = g.half_extents.as_ref().expect("checked above");
            src.array_numbers(owner, "half_extents", &e.span(), e.get_ref().numbers(), Sign::Positive)?;
            GeomShape::Box { half_extents: D::vector(*e.get_ref()) }
        }
        _ => {
            let radius = positive("radius", &g.radius)?;
            GeomShape::Cylinder { half_length: positive("half_length", &g.half_length)?, radius }
        }
    })
}
