//! Joints: the one place that maps a `kind` to a joint (in each dimension,
//! its table of kinds), and the tree they form from the ground.

use super::dimension::{FileDimension, Kind};
use super::document::{Sign, Source, Span};
use super::flexures::{planar_flexure, spatial_flexure};
use super::{Deserialize, JointKind, JointSpec, ReportOptions, Result, Spanned};
use super::{Fixed, Prismatic, Revolute};
use crate::mechanism::Dimension;
use crate::mechanism::spatial::joints::unit_axis;
use crate::mechanism::spatial::{self, SpatialJointKind, Spherical};
use crate::space::{Planar, Spatial};
use nalgebra::Vector3;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct JointToml {
    pub(super) name: Spanned<String>,
    pub(super) kind: Spanned<String>,
    pub(super) parent: Spanned<String>,
    pub(super) child: Spanned<String>,
    // In the plane `[x, y, phi]`; in space `[x, y, z]`, turned by `rpy` or `rpy_deg`.
    pub(super) origin: Option<Spanned<[f64; 3]>>,
    pub(super) rpy: Option<Spanned<[f64; 3]>>,
    pub(super) rpy_deg: Option<Spanned<[f64; 3]>>,
    pub(super) damping: Option<Spanned<f64>>,
    // A flexure. A quantity along it (`ei`, `width`, `thickness`,
    // `mass_per_length`, …) is a number, `[root, tip]` or a table
    // `[[t, value], …]`: read by `Source::profile`.
    pub(super) length: Option<Spanned<f64>>,
    pub(super) ei: Option<Spanned<toml::Value>>,
    pub(super) gj: Option<Spanned<toml::Value>>,
    pub(super) ei_y: Option<Spanned<toml::Value>>,
    pub(super) ei_z: Option<Spanned<toml::Value>>,
    pub(super) modulus: Option<Spanned<f64>>,
    pub(super) width: Option<Spanned<toml::Value>>,
    pub(super) thickness: Option<Spanned<toml::Value>>,
    pub(super) diameter: Option<Spanned<toml::Value>>,
    pub(super) poisson: Option<Spanned<f64>>,
    pub(super) shear_modulus: Option<Spanned<f64>>,
    // `{ radius = R, min_thickness = h }`: read by `Source::notch`.
    pub(super) notch: Option<Spanned<toml::Value>>,
    pub(super) density: Option<Spanned<f64>>,
    pub(super) mass_per_length: Option<Spanned<toml::Value>>,
    // `[twist, y, z]` (kg·m), in space only.
    pub(super) rotary_inertia_per_length: Option<Spanned<[f64; 3]>>,
    pub(super) yield_strength: Option<Spanned<f64>>,
    pub(super) shape: Option<Spanned<usize>>,
    // A whole number, or `"auto"`: read by `flexure_order`.
    pub(super) order: Option<Spanned<toml::Value>>,
    pub(super) orders: Option<Spanned<[usize; 3]>>,
    pub(super) quadrature: Option<Spanned<usize>>,
    pub(super) subintervals: Option<Spanned<usize>>,
    pub(super) kappa: Option<Spanned<Vec<f64>>>,
    pub(super) twist: Option<Spanned<Vec<f64>>>,
    pub(super) kappa_y: Option<Spanned<Vec<f64>>>,
    pub(super) kappa_z: Option<Spanned<Vec<f64>>>,
    // A hinge, slider or ball.
    pub(super) axis: Option<Spanned<[f64; 3]>>,
    pub(super) stiffness: Option<Spanned<f64>>,
    pub(super) rest: Option<Spanned<toml::Value>>,
}

pub(super) fn span_of<T>(v: &Option<Spanned<T>>) -> Option<Span> {
    v.as_ref().map(Spanned::span)
}

impl JointToml {
    /// Where a flexure's key `name` is written, if it is.
    pub(super) fn span(&self, name: &str) -> Option<Span> {
        flexure_keys(self).into_iter().find(|(k, _)| *k == name).and_then(|(_, s)| s)
    }
}

/// A flexure's keys, each with where it is written.
fn flexure_keys(j: &JointToml) -> [(&'static str, Option<Span>); 25] {
    [
        ("length", span_of(&j.length)),
        ("ei", span_of(&j.ei)),
        ("gj", span_of(&j.gj)),
        ("ei_y", span_of(&j.ei_y)),
        ("ei_z", span_of(&j.ei_z)),
        ("modulus", span_of(&j.modulus)),
        ("width", span_of(&j.width)),
        ("thickness", span_of(&j.thickness)),
        ("diameter", span_of(&j.diameter)),
        ("poisson", span_of(&j.poisson)),
        ("shear_modulus", span_of(&j.shear_modulus)),
        ("notch", span_of(&j.notch)),
        ("density", span_of(&j.density)),
        ("mass_per_length", span_of(&j.mass_per_length)),
        ("rotary_inertia_per_length", span_of(&j.rotary_inertia_per_length)),
        ("yield_strength", span_of(&j.yield_strength)),
        ("shape", span_of(&j.shape)),
        ("order", span_of(&j.order)),
        ("orders", span_of(&j.orders)),
        ("quadrature", span_of(&j.quadrature)),
        ("subintervals", span_of(&j.subintervals)),
        ("kappa", span_of(&j.kappa)),
        ("twist", span_of(&j.twist)),
        ("kappa_y", span_of(&j.kappa_y)),
        ("kappa_z", span_of(&j.kappa_z)),
    ]
}

/// The first key given that `kind` does not take (of the keys of the
/// file's dimension: the other's are refused before).
fn foreign_key(j: &JointToml, kind: &str) -> Option<(&'static str, Span)> {
    let flexure = flexure_keys(j);
    let axis = [("axis", span_of(&j.axis))];
    let spring = [("stiffness", span_of(&j.stiffness)), ("rest", span_of(&j.rest))];
    let damping = [("damping", span_of(&j.damping))];
    let foreign: Vec<(&'static str, Option<Span>)> = match kind {
        "flexure" => axis.iter().chain(&spring).cloned().collect(),
        "revolute" | "prismatic" => flexure.to_vec(),
        "spherical" => flexure.iter().chain(&axis).cloned().collect(),
        _ => flexure.iter().chain(&axis).chain(&spring).chain(&damping).cloned().collect(),
    };
    foreign.into_iter().find_map(|(k, s)| s.map(|s| (k, s)))
}

/// The joint's `kind`, one of `kinds`, with no key it does not take.
fn checked_kind<'j>(src: &Source, owner: &str, j: &'j JointToml, kinds: &[&str]) -> Result<&'j str> {
    let kind = j.kind.get_ref().as_str();
    if !kinds.contains(&kind) {
        let (last, first) = kinds.split_last().expect("a dimension has joint kinds");
        return src
            .fail(&j.kind.span(), format!("{owner}unknown kind {kind:?}; expected {} or {last}", first.join(", ")));
    }
    if let Some((key, span)) = foreign_key(j, kind) {
        return src.fail(&span, format!("{owner}`{key}` does not apply to a {kind} joint"));
    }
    Ok(kind)
}

/// A spring's `stiffness` (not negative; 0 when absent).
fn stiffness(src: &Source, owner: &str, j: &JointToml) -> Result<f64> {
    j.stiffness.as_ref().map_or(Ok(0.0), |v| src.number(owner, "stiffness", v, Sign::NotNegative))
}

/// A hinge's or slider's spring `rest`: a number (0 when absent).
fn rest_number(src: &Source, owner: &str, kind: &str, j: &JointToml) -> Result<f64> {
    match &j.rest {
        None => Ok(0.0),
        Some(r) => match r.get_ref() {
            toml::Value::Float(x) => src.numbers(owner, "rest", &r.span(), &[*x], Sign::Any).map(|_| *x),
            toml::Value::Integer(i) => Ok(*i as f64),
            _ => src.fail(&r.span(), format!("{owner}rest must be a number for a {kind} joint")),
        },
    }
}

/// A kind other than a flexure: its stiffness given at `stiffness` (the
/// joint's name when absent).
fn spring<D: Dimension>(j: &JointToml, kind: JointKind<D>) -> Kind<D> {
    let stiffness_place = j.stiffness.as_ref().map_or(j.name.span(), Spanned::span);
    Kind { kind, stiffness_place, auto_order: false, report: ReportOptions::default() }
}

/// The kinds of a planar file.
pub(super) fn planar_kind(src: &Source, owner: &str, j: &JointToml) -> Result<Kind<Planar>> {
    let kind = checked_kind(src, owner, j, &["flexure", "revolute", "prismatic", "fixed"])?;
    let (stiffness, rest) = match kind {
        "revolute" | "prismatic" => (stiffness(src, owner, j)?, rest_number(src, owner, kind, j)?),
        _ => (0.0, 0.0),
    };
    Ok(match kind {
        "flexure" => planar_flexure(src, owner, j)?,
        "revolute" => spring::<Planar>(j, JointKind::Revolute(Revolute { stiffness, rest })),
        "prismatic" => spring::<Planar>(j, JointKind::Prismatic(Prismatic { stiffness, rest })),
        _ => spring::<Planar>(j, JointKind::Fixed(Fixed)),
    })
}

/// The kinds of a spatial file: hinges and sliders along an `axis`, and balls.
pub(super) fn spatial_kind(src: &Source, owner: &str, j: &JointToml) -> Result<Kind<Spatial>> {
    let kind = checked_kind(src, owner, j, &["flexure", "revolute", "prismatic", "spherical", "fixed"])?;
    let axis = |default: Vector3<f64>| -> Result<nalgebra::Unit<Vector3<f64>>> {
        let Some(a) = &j.axis else { return unit_axis("axis", default) };
        src.array_numbers(owner, "axis", &a.span(), a.get_ref(), Sign::Any)?;
        unit_axis("axis", Vector3::from(*a.get_ref())).map_err(|e| src.placed(owner, &a.span(), e))
    };
    let (stiffness, rest) = match kind {
        "revolute" | "prismatic" => (stiffness(src, owner, j)?, rest_number(src, owner, kind, j)?),
        _ => (0.0, 0.0),
    };
    Ok(match kind {
        "flexure" => spatial_flexure(src, owner, j)?,
        "revolute" => spring(
            j,
            SpatialJointKind::Revolute(spatial::RevoluteUnaligned { axis: axis(Vector3::z())?, stiffness, rest }),
        ),
        "prismatic" => spring(
            j,
            SpatialJointKind::Prismatic(spatial::PrismaticUnaligned { axis: axis(Vector3::x())?, stiffness, rest }),
        ),
        "spherical" => {
            let rest = match &j.rest {
                None => [0.0; 3],
                Some(r) => {
                    let values: Option<Vec<f64>> = r.get_ref().as_array().and_then(|a| {
                        a.iter().map(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64))).collect()
                    });
                    let Some(&[x, y, z]) = values.as_deref() else {
                        return src.fail(
                            &r.span(),
                            format!("{owner}rest must be a rotation vector [θx, θy, θz] (rad) for a spherical joint"),
                        );
                    };
                    src.numbers(owner, "rest", &r.span(), &[x, y, z], Sign::Any)?;
                    [x, y, z]
                }
            };
            spring(j, SpatialJointKind::Spherical(Spherical { stiffness: self::stiffness(src, owner, j)?, rest }))
        }
        _ => spring(j, SpatialJointKind::Fixed(Fixed)),
    })
}

/// No two joints share a name.
pub(super) fn check_names(src: &Source, joints: &[JointToml]) -> Result<()> {
    for (i, j) in joints.iter().enumerate() {
        if joints[..i].iter().any(|k| k.name.get_ref() == j.name.get_ref()) {
            return src.fail(&j.name.span(), format!("duplicate joint name {:?}", j.name.get_ref()));
        }
    }
    Ok(())
}

/// The joints ordered from the ground outward (`parents[i]`: joint `i`'s
/// parent body; body `i + 1` is its child); a joint left over lies on a cycle.
pub(super) fn tree_order(src: &Source, joints: &[JointToml], parents: &[usize]) -> Result<Vec<usize>> {
    let mut order: Vec<usize> = Vec::new();
    let mut reached = vec![false; joints.len() + 1];
    reached[0] = true;
    loop {
        let before = order.len();
        for (i, &p) in parents.iter().enumerate() {
            if !reached[i + 1] && reached[p] {
                order.push(i);
                reached[i + 1] = true;
            }
        }
        if order.len() == before {
            break;
        }
    }
    if let Some(i) = (0..joints.len()).find(|i| !reached[i + 1]) {
        let j = &joints[i];
        return src.fail(
            &j.parent.span(),
            format!(
                "joint {:?} is on a cycle of joints, not reachable from ground (close loops with [[weld]] or [[pin]])",
                j.name.get_ref()
            ),
        );
    }
    Ok(order)
}

/// Each joint, in `order`: its origin, kind and damping, and where its
/// stiffness is given (for the check of the stiffness ratio).
pub(super) fn tree<D: FileDimension>(
    src: &Source,
    joints: &[JointToml],
    parents: &[usize],
    order: &[usize],
) -> Result<(Vec<JointSpec<D>>, Vec<Span>)> {
    let mut specs = Vec::new();
    let mut stiffness_places: Vec<Span> = Vec::new();
    for &i in order {
        let j = &joints[i];
        let owner = format!("joint {:?}: ", j.name.get_ref());
        let Kind { kind, stiffness_place, auto_order, report } = D::kind(src, &owner, j)?;
        let origin = D::pose(src, &owner, ["origin", "rpy", "rpy_deg"], [&j.origin, &j.rpy, &j.rpy_deg])?;
        let damping = j.damping.as_ref().map_or(Ok(0.0), |d| src.number(&owner, "damping", d, Sign::NotNegative))?;
        let spec = JointSpec {
            damping,
            auto_order,
            report,
            ..JointSpec::new(j.name.get_ref(), kind, parents[i], i + 1, origin)
        };
        specs.push(spec);
        stiffness_places.push(stiffness_place);
    }
    Ok((specs, stiffness_places))
}
