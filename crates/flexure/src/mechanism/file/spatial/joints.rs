//! The joints of a spatial file: the one place a `kind` becomes a spatial
//! joint, and the tree they form from the ground.

use super::{Error, Result, Sign, Source, Span, Spanned};
use crate::mechanism::file::flexures::report_keys;
use crate::mechanism::spatial::joints::unit_axis;
use crate::mechanism::spatial::{Prismatic, Revolute, SpatialJointKind, SpatialJointSpec, Spherical};
use crate::mechanism::{Fixed, ReportOptions};
use crate::spatial::SpatialSpec;
use nalgebra::Vector3;
use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct JointToml {
    pub(super) name: Spanned<String>,
    kind: Spanned<String>,
    parent: Spanned<String>,
    pub(super) child: Spanned<String>,
    origin: Option<Spanned<[f64; 3]>>,
    rpy: Option<Spanned<[f64; 3]>>,
    rpy_deg: Option<Spanned<[f64; 3]>>,
    damping: Option<Spanned<f64>>,
    // The spatial flexure (crate::spatial::SpatialSpec), with the planar
    // spellings `ei` (= ei_z) and `kappa` (= kappa_z).
    length: Option<Spanned<f64>>,
    gj: Option<Spanned<toml::Value>>,
    ei_y: Option<Spanned<toml::Value>>,
    ei_z: Option<Spanned<toml::Value>>,
    ei: Option<Spanned<toml::Value>>,
    modulus: Option<Spanned<f64>>,
    width: Option<Spanned<toml::Value>>,
    thickness: Option<Spanned<toml::Value>>,
    diameter: Option<Spanned<toml::Value>>,
    poisson: Option<Spanned<f64>>,
    shear_modulus: Option<Spanned<f64>>,
    // A whole number, or `"auto"`: read by `orders_of`.
    order: Option<Spanned<toml::Value>>,
    orders: Option<Spanned<[usize; 3]>>,
    subintervals: Option<Spanned<usize>>,
    twist: Option<Spanned<Vec<f64>>>,
    kappa_y: Option<Spanned<Vec<f64>>>,
    kappa_z: Option<Spanned<Vec<f64>>>,
    kappa: Option<Spanned<Vec<f64>>>,
    // The flexure's own mass: a density with the geometry, or a mass per length.
    density: Option<Spanned<f64>>,
    mass_per_length: Option<Spanned<toml::Value>>,
    // What the solve report adds (crate::mechanism::ReportOptions).
    yield_strength: Option<Spanned<f64>>,
    shape: Option<Spanned<usize>>,
    // Hinges, sliders and balls.
    axis: Option<Spanned<[f64; 3]>>,
    stiffness: Option<Spanned<f64>>,
    rest: Option<Spanned<toml::Value>>,
}

fn span_of<T>(v: &Option<Spanned<T>>) -> Option<Span> {
    v.as_ref().map(Spanned::span)
}

impl JointToml {
    /// The first key given that a `kind` does not take.
    fn foreign_key(&self, kind: &str) -> Option<(&'static str, Span)> {
        let flexure = [
            ("length", span_of(&self.length)),
            ("gj", span_of(&self.gj)),
            ("ei_y", span_of(&self.ei_y)),
            ("ei_z", span_of(&self.ei_z)),
            ("ei", span_of(&self.ei)),
            ("modulus", span_of(&self.modulus)),
            ("width", span_of(&self.width)),
            ("thickness", span_of(&self.thickness)),
            ("diameter", span_of(&self.diameter)),
            ("poisson", span_of(&self.poisson)),
            ("shear_modulus", span_of(&self.shear_modulus)),
            ("order", span_of(&self.order)),
            ("orders", span_of(&self.orders)),
            ("subintervals", span_of(&self.subintervals)),
            ("twist", span_of(&self.twist)),
            ("kappa_y", span_of(&self.kappa_y)),
            ("kappa_z", span_of(&self.kappa_z)),
            ("kappa", span_of(&self.kappa)),
            ("density", span_of(&self.density)),
            ("mass_per_length", span_of(&self.mass_per_length)),
            ("yield_strength", span_of(&self.yield_strength)),
            ("shape", span_of(&self.shape)),
        ];
        let axis = [("axis", span_of(&self.axis))];
        let spring = [("stiffness", span_of(&self.stiffness)), ("rest", span_of(&self.rest))];
        let damping = [("damping", span_of(&self.damping))];
        let foreign: Vec<(&'static str, Option<Span>)> = match kind {
            "flexure" => axis.iter().chain(&spring).cloned().collect(),
            "revolute" | "prismatic" => flexure.to_vec(),
            "spherical" => flexure.iter().chain(&axis).cloned().collect(),
            _ => flexure.iter().chain(&axis).chain(&spring).chain(&damping).cloned().collect(),
        };
        foreign.into_iter().find_map(|(k, s)| s.map(|s| (k, s)))
    }
}

/// A spatial flexure from its keys, built by [`SpatialSpec::build`]; an
/// error is placed at the key it names.
fn flexure(src: &Source, owner: &str, j: &JointToml) -> Result<SpatialJointKind> {
    let length =
        j.length.as_ref().ok_or_else(|| src.error(&j.name.span(), format!("{owner}a flexure needs a length")))?;
    let length = src.number(owner, "length", length, Sign::Positive)?;
    let profile = |key: &'static str, v: &Option<Spanned<toml::Value>>| {
        v.as_ref().map(|v| src.profile(owner, key, v)).transpose()
    };
    if let (Some(_), Some(z)) = (&j.ei, &j.ei_z) {
        return src.fail(&z.span(), format!("{owner}give ei (the planar spelling) or ei_z, not both"));
    }
    if let (Some(_), Some(z)) = (&j.kappa, &j.kappa_z) {
        return src.fail(&z.span(), format!("{owner}give kappa (the planar spelling) or kappa_z, not both"));
    }
    let orders = orders_of(src, owner, j)?.0;
    let rest = |key: &str, v: &Option<Spanned<Vec<f64>>>| -> Result<Option<Vec<f64>>> {
        match v {
            Some(v) => {
                src.numbers(owner, key, &v.span(), v.get_ref(), Sign::Any)?;
                Ok(Some(v.get_ref().clone()))
            }
            None => Ok(None),
        }
    };
    let number =
        |key: &str, v: &Option<Spanned<f64>>, sign| v.as_ref().map(|v| src.number(owner, key, v, sign)).transpose();
    let spec = SpatialSpec {
        length,
        gj: profile("gj", &j.gj)?,
        ei_y: profile("ei_y", &j.ei_y)?,
        ei_z: match &j.ei {
            Some(_) => profile("ei", &j.ei)?,
            None => profile("ei_z", &j.ei_z)?,
        },
        modulus: number("modulus", &j.modulus, Sign::Positive)?,
        width: profile("width", &j.width)?,
        thickness: profile("thickness", &j.thickness)?,
        diameter: profile("diameter", &j.diameter)?,
        poisson: number("poisson", &j.poisson, Sign::Any)?,
        shear_modulus: number("shear_modulus", &j.shear_modulus, Sign::Positive)?,
        orders,
        twist: rest("twist", &j.twist)?,
        kappa_y: rest("kappa_y", &j.kappa_y)?,
        kappa_z: if j.kappa.is_some() { rest("kappa", &j.kappa)? } else { rest("kappa_z", &j.kappa_z)? },
    };
    // The key an error names, placed there (the joint's name when absent).
    let key_span = |name: &str| -> Span {
        let given = match name {
            "gj" => span_of(&j.gj),
            "ei_y" => span_of(&j.ei_y),
            "ei_z" => span_of(&j.ei_z),
            "ei" => span_of(&j.ei),
            "modulus" => span_of(&j.modulus),
            "width" => span_of(&j.width),
            "thickness" => span_of(&j.thickness),
            "diameter" => span_of(&j.diameter),
            "poisson" => span_of(&j.poisson),
            "shear_modulus" => span_of(&j.shear_modulus),
            "twist" => span_of(&j.twist),
            "kappa_y" => span_of(&j.kappa_y),
            "kappa_z" => span_of(&j.kappa_z),
            "kappa" => span_of(&j.kappa),
            "subintervals" => span_of(&j.subintervals),
            "orders" => span_of(&j.orders),
            "order" => span_of(&j.order),
            _ => None,
        };
        given.unwrap_or(j.name.span())
    };
    // The library names `ei_z`, `kappa_z` and `order` (the three orders);
    // the error names the key as the file writes it, and its value so.
    let placed = |e: Error| match e {
        Error::InvalidParameter { name, value, reason } => {
            let (name, value) = match name {
                "ei_z" if j.ei.is_some() => ("ei", value),
                "kappa_z" if j.kappa.is_some() => ("kappa", value),
                "order" | "orders" => match (&j.order, &j.orders) {
                    (Some(n), _) => ("order", written(n.get_ref())),
                    (None, Some(o)) => ("orders", format!("{:?}", o.get_ref())),
                    (None, None) => (name, value),
                },
                _ => (name, value),
            };
            src.placed(owner, &key_span(name), Error::InvalidParameter { name, value, reason })
        }
        e => src.placed(owner, &j.name.span(), e),
    };
    let mut f = spec.build().map_err(placed)?;
    if let Some(m) = &j.subintervals {
        f = f.with_subintervals(*m.get_ref()).map_err(|e| src.placed(owner, &m.span(), e))?;
    }
    match (&j.density, &j.mass_per_length) {
        (Some(_), Some(mu)) => {
            return src.fail(&mu.span(), format!("{owner}give density or mass_per_length, not both"));
        }
        (Some(rho), None) => {
            let value = src.number(owner, "density", rho, Sign::Positive)?;
            f = f.with_density(value).map_err(|e| src.placed(owner, &rho.span(), e))?;
        }
        (None, Some(mu)) => {
            let value = src.profile(owner, "mass_per_length", mu)?;
            f = f.with_mass_per_length(value).map_err(|e| src.placed(owner, &mu.span(), e))?;
        }
        (None, None) => {}
    }
    Ok(SpatialJointKind::Flexure(Box::new(f)))
}

/// A flexure's three orders: `order` (all three: a whole number, or
/// `"auto"`, which starts at 3 and says so in the second value) or
/// `orders`, [3, 3, 3] when neither is given.
pub(super) fn orders_of(src: &Source, owner: &str, j: &JointToml) -> Result<([usize; 3], bool)> {
    match (&j.order, &j.orders) {
        (Some(_), Some(o)) => src.fail(&o.span(), format!("{owner}give order (all three) or orders, not both")),
        (Some(n), None) => match n.get_ref() {
            toml::Value::Integer(k) if *k >= 0 => Ok(([usize::try_from(*k).unwrap_or(usize::MAX); 3], false)),
            toml::Value::String(s) if s == "auto" => Ok(([3; 3], true)),
            v => src.fail(
                &n.span(),
                format!(
                    "{owner}order = {}: must be a whole number from 1 to {} or \"auto\" (raised by buckle and modes until their error estimate meets its target)",
                    written(v),
                    crate::flexure::MAX_ORDER
                ),
            ),
        },
        (None, Some(o)) => Ok((*o.get_ref(), false)),
        (None, None) => Ok(([3; 3], false)),
    }
}

/// A value as the file writes it: `3`, `2.5`, `"six"`, or its type.
fn written(v: &toml::Value) -> String {
    match v {
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(x) => format!("{x:?}"),
        toml::Value::String(s) => format!("{s:?}"),
        other => format!("a {}", other.type_str()),
    }
}

/// The joint's kind from its keys.
fn kind(src: &Source, owner: &str, j: &JointToml) -> Result<SpatialJointKind> {
    let kind = j.kind.get_ref().as_str();
    if !matches!(kind, "flexure" | "revolute" | "prismatic" | "spherical" | "fixed") {
        return src.fail(
            &j.kind.span(),
            format!("{owner}unknown kind {kind:?}; expected flexure, revolute, prismatic, spherical or fixed"),
        );
    }
    if let Some((key, span)) = j.foreign_key(kind) {
        return src.fail(&span, format!("{owner}`{key}` does not apply to a {kind} joint"));
    }
    let stiffness = j.stiffness.as_ref().map_or(Ok(0.0), |v| src.number(owner, "stiffness", v, Sign::NotNegative))?;
    let axis = |default: Vector3<f64>| -> Result<nalgebra::Unit<Vector3<f64>>> {
        let Some(a) = &j.axis else { return unit_axis("axis", default) };
        src.numbers(owner, "axis", &a.span(), a.get_ref(), Sign::Any)?;
        unit_axis("axis", Vector3::from(*a.get_ref())).map_err(|e| src.placed(owner, &a.span(), e))
    };
    let rest_number = || -> Result<f64> {
        match &j.rest {
            None => Ok(0.0),
            Some(r) => match r.get_ref() {
                toml::Value::Float(x) => src.numbers(owner, "rest", &r.span(), &[*x], Sign::Any).map(|_| *x),
                toml::Value::Integer(i) => Ok(*i as f64),
                _ => src.fail(&r.span(), format!("{owner}rest must be a number for a {kind} joint")),
            },
        }
    };
    match kind {
        "flexure" => flexure(src, owner, j),
        "revolute" => {
            Ok(SpatialJointKind::Revolute(Revolute { axis: axis(Vector3::z())?, stiffness, rest: rest_number()? }))
        }
        "prismatic" => {
            Ok(SpatialJointKind::Prismatic(Prismatic { axis: axis(Vector3::x())?, stiffness, rest: rest_number()? }))
        }
        "spherical" => {
            let rest = match &j.rest {
                None => [0.0; 3],
                Some(r) => {
                    let values: Option<Vec<f64>> = r.get_ref().as_array().and_then(|a| {
                        a.iter().map(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64))).collect()
                    });
                    match values.as_deref() {
                        Some([x, y, z]) => {
                            src.numbers(owner, "rest", &r.span(), &[*x, *y, *z], Sign::Any)?;
                            [*x, *y, *z]
                        }
                        _ => {
                            return src.fail(
                                &r.span(),
                                format!(
                                    "{owner}rest must be a rotation vector [θx, θy, θz] (rad) for a spherical joint"
                                ),
                            );
                        }
                    }
                }
            };
            Ok(SpatialJointKind::Spherical(Spherical { stiffness, rest }))
        }
        _ => Ok(SpatialJointKind::Fixed(Fixed)),
    }
}

/// The joints, in an order where every parent comes before its children
/// (file order where it already is), each with its kind and placement.
pub(super) fn joints(
    src: &Source,
    find: &dyn Fn(&Spanned<String>) -> Result<usize>,
    tables: &[JointToml],
) -> Result<Vec<SpatialJointSpec>> {
    for (i, j) in tables.iter().enumerate() {
        if tables[..i].iter().any(|k| k.name.get_ref() == j.name.get_ref()) {
            return src.fail(&j.name.span(), format!("duplicate joint name {:?}", j.name.get_ref()));
        }
    }
    let mut specs = Vec::with_capacity(tables.len());
    for (i, j) in tables.iter().enumerate() {
        let owner = format!("joint {:?}: ", j.name.get_ref());
        let parent = find(&j.parent)?;
        let kind = kind(src, &owner, j)?;
        let origin = src.placement(&owner, ["origin", "rpy", "rpy_deg"], &j.origin, &j.rpy, &j.rpy_deg)?;
        let damping = j.damping.as_ref().map_or(Ok(0.0), |d| src.number(&owner, "damping", d, Sign::NotNegative))?;
        // Only a flexure takes `order` (the others refuse it): read it so.
        let auto_order = orders_of(src, "", j)?.1;
        let report = match &kind {
            SpatialJointKind::Flexure(f) => {
                let keys = (&j.yield_strength, &j.shape);
                report_keys(src, &owner, keys, f.section().has_geometry())?
            }
            _ => ReportOptions::default(),
        };
        let spec = SpatialJointSpec {
            name: j.name.get_ref().clone(),
            kind,
            parent,
            child: i + 1,
            origin,
            offset: 0,
            damping,
            auto_order,
            report,
        };
        specs.push((spec, j));
    }
    // Parents first: place each joint once its parent body is placed (at most n passes).
    let mut placed = vec![false; tables.len() + 1];
    placed[0] = true;
    let mut order = Vec::with_capacity(specs.len());
    for _ in 0..=specs.len() {
        for (k, (s, _)) in specs.iter().enumerate() {
            if !placed[s.child] && placed[s.parent] {
                placed[s.child] = true;
                order.push(k);
            }
        }
    }
    if let Some((s, j)) = specs.iter().find(|(s, _)| !placed[s.child]) {
        return src.fail(
            &j.parent.span(),
            format!("joint {:?}: its parent {:?} is not reached from the ground (a loop of joints; close loops with [[weld]], [[pin]] or [[ball]])", s.name, j.parent.get_ref()),
        );
    }
    Ok(order.into_iter().map(|k| specs[k].0.clone()).collect())
}
