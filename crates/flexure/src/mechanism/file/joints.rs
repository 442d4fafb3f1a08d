//! Joints: the one place that maps a `kind` to a joint, and the tree they form from the ground.

use super::document::{Sign, Source, Span};
use super::flexures::flexure;
use super::{Deserialize, JointKind, JointSpec, Pose, ReportOptions, Result, Spanned};
use super::{Fixed, Prismatic, Revolute};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct JointToml {
    pub(super) name: Spanned<String>,
    pub(super) kind: Spanned<String>,
    pub(super) parent: Spanned<String>,
    pub(super) child: Spanned<String>,
    pub(super) origin: Option<Spanned<[f64; 3]>>,
    pub(super) length: Option<Spanned<f64>>,
    // A quantity along the flexure (`ei`, `width`, `thickness`,
    // `mass_per_length`) is a number, `[root, tip]` or a table
    // `[[t, value], …]`: read by `Source::profile`.
    pub(super) ei: Option<Spanned<toml::Value>>,
    pub(super) modulus: Option<Spanned<f64>>,
    pub(super) width: Option<Spanned<toml::Value>>,
    pub(super) thickness: Option<Spanned<toml::Value>>,
    pub(super) poisson: Option<Spanned<f64>>,
    // `{ radius = R, min_thickness = h }`: read by `Source::notch`.
    pub(super) notch: Option<Spanned<toml::Value>>,
    pub(super) density: Option<Spanned<f64>>,
    pub(super) mass_per_length: Option<Spanned<toml::Value>>,
    pub(super) yield_strength: Option<Spanned<f64>>,
    pub(super) shape: Option<Spanned<usize>>,
    // A whole number, or `"auto"`: read by `flexure_order`.
    pub(super) order: Option<Spanned<toml::Value>>,
    pub(super) quadrature: Option<Spanned<usize>>,
    pub(super) kappa: Option<Spanned<Vec<f64>>>,
    pub(super) stiffness: Option<Spanned<f64>>,
    pub(super) rest: Option<Spanned<f64>>,
    pub(super) damping: Option<Spanned<f64>>,
}

/// The keys a kind does not take, given in `j`.
pub(super) fn foreign_keys(j: &JointToml, kind: &str) -> Option<(&'static str, Span)> {
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

/// The joint's kind, the place of the key that sets its stiffness, and
/// whether it is a flexure of `order = "auto"`.
/// A joint's kind, where its stiffness is given, whether its order is
/// `"auto"`, and (a flexure's) report keys.
type Kind = (JointKind, Span, bool, ReportOptions);

pub(super) fn joint_kind(src: &Source, owner: &str, j: &JointToml) -> Result<Kind> {
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
            let (f, stiffness_place, auto_order, report) = flexure(src, owner, j)?;
            Ok((JointKind::Flexure(Box::new(f)), stiffness_place, auto_order, report))
        }
        "revolute" => Ok((
            JointKind::Revolute(Revolute {
                stiffness: spring("stiffness", &j.stiffness, Sign::NotNegative)?,
                rest: spring("rest", &j.rest, Sign::Any)?,
            }),
            stiffness_place,
            false,
            ReportOptions::default(),
        )),
        "prismatic" => Ok((
            JointKind::Prismatic(Prismatic {
                stiffness: spring("stiffness", &j.stiffness, Sign::NotNegative)?,
                rest: spring("rest", &j.rest, Sign::Any)?,
            }),
            stiffness_place,
            false,
            ReportOptions::default(),
        )),
        _ => Ok((JointKind::Fixed(Fixed), j.name.span(), false, ReportOptions::default())),
    }
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
            if !order.contains(&i) && reached[p] {
                order.push(i);
                reached[i + 1] = true;
            }
        }
        if order.len() == before {
            break;
        }
    }
    if let Some(i) = (0..joints.len()).find(|i| !order.contains(i)) {
        let j = &joints[i];
        return src.fail(
            &j.parent.span(),
            format!("joint {:?} is on a cycle of joints, not reachable from ground", j.name.get_ref()),
        );
    }
    Ok(order)
}

/// The joints of the tree, in `order`.
pub(super) struct Tree {
    pub(super) joints: Vec<JointSpec>,
    /// Where each joint's stiffness was given, for the stiffness-ratio check.
    pub(super) stiffness_places: Vec<Span>,
    /// `parent_joint[b]`: the joint whose child is body `b`.
    pub(super) parent_joint: Vec<Option<usize>>,
    /// The number of coordinates.
    pub(super) dof: usize,
}

/// Builds each joint, in `order`: its origin, kind and damping.
pub(super) fn tree(src: &Source, joints: &[JointToml], parents: &[usize], order: &[usize]) -> Result<Tree> {
    let mut specs = Vec::new();
    let mut stiffness_places: Vec<Span> = Vec::new();
    let mut parent_joint = vec![None; joints.len() + 1];
    let mut offset = 0;
    for &i in order {
        let j = &joints[i];
        let owner = format!("joint {:?}: ", j.name.get_ref());
        let origin = src.array(&owner, "origin", &j.origin)?;
        let (kind, stiffness_place, auto_order, report) = joint_kind(src, &owner, j)?;
        let damping = j.damping.as_ref().map_or(Ok(0.0), |d| src.number(&owner, "damping", d, Sign::NotNegative))?;
        let dof = kind.joint().dof();
        parent_joint[i + 1] = Some(specs.len());
        specs.push(JointSpec {
            name: j.name.get_ref().clone(),
            kind,
            parent: parents[i],
            child: i + 1,
            origin: Pose { x: origin[0], y: origin[1], phi: origin[2] },
            offset,
            damping,
            auto_order,
            report,
        });
        stiffness_places.push(stiffness_place);
        offset += dof;
    }
    Ok(Tree { joints: specs, stiffness_places, parent_joint, dof: offset })
}
