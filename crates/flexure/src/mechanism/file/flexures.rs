//! A flexure joint's keys: its section (`ei`, or `modulus`, `width`,
//! `thickness` with `poisson`, `notch`, `density`; in space also `gj`,
//! `ei_y`, `ei_z`, `diameter`, `shear_modulus`), `order`, and what
//! `flexure solve` reports of it: the planar flexure's and the spatial
//! flexure's, each read into its spec and built by the library.

use super::dimension::Kind;
use super::document::{Sign, Source, Span, written};
use super::joints::span_of;
use super::{
    Error, FlexureSpec, JointKind, JointToml, MAX_SHAPE, Notch, Profile, ReportOptions, Result, SectionSpec, Spanned,
};
use crate::mechanism::spatial::SpatialJointKind;
use crate::space::{Planar, Spatial};
use crate::spatial::SpatialSpec;

impl Source<'_> {
    /// A quantity along a flexure, `key`: a number, `[root, tip]` (a linear
    /// taper) or a table `[[t, value], …]` over $t = s/L$; every value
    /// greater than zero, a table's $t$ from 0 to 1, increasing strictly.
    pub(super) fn profile(&self, owner: &str, key: &'static str, value: &Spanned<toml::Value>) -> Result<Profile> {
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
    pub(super) fn notch(&self, owner: &str, value: &Spanned<toml::Value>) -> Result<Notch> {
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
                written(v),
                crate::flexure::MAX_ORDER
            ),
        ),
    }
}

/// A planar flexure joint: its keys read into a [`FlexureSpec`] and built
/// by the library, which names the parameter of an error; the error is
/// placed at that parameter's key. Its stiffness is given at `ei` or `modulus`.
pub(super) fn planar_flexure(src: &Source, owner: &str, j: &JointToml) -> Result<Kind<Planar>> {
    let length =
        j.length.as_ref().ok_or_else(|| src.error(&j.name.span(), format!("{owner}a flexure needs a length")))?;
    let length_value = src.number(owner, "length", length, Sign::Positive)?;
    let (section, ei_span) = section(src, owner, j)?;
    let (order, auto_order) = flexure_order(src, owner, j)?;
    if let Some(k) = &j.kappa {
        src.numbers(owner, "kappa", &k.span(), k.get_ref(), Sign::Any)?;
    }
    let spec = FlexureSpec {
        length: length_value,
        section,
        order,
        quadrature: j.quadrature.as_ref().map(|q| *q.get_ref()),
        kappa: j.kappa.as_ref().map(|k| k.get_ref().clone()),
    };
    // The library names the parameter of an error: placed at its key (the
    // section's `notch.radius` at `notch`), or where the stiffness is given.
    let f = spec.build().map_err(|x| {
        let span = match &x {
            Error::InvalidParameter { name: "order", .. } => Some(j.span("order").unwrap_or(j.name.span())),
            Error::InvalidParameter { name, .. } => j.span(name.split('.').next().unwrap_or(name)),
            _ => None,
        };
        src.placed(owner, &span.unwrap_or(ei_span.clone()), x)
    })?;
    let report = report_keys(src, owner, (&j.yield_strength, &j.shape), f.section().modulus().is_some())?;
    Ok(Kind { kind: JointKind::Flexure(Box::new(f)), stiffness_place: ei_span, auto_order, report })
}

/// A flexure joint's section keys, each checked where it is written: `ei`,
/// or `modulus` with `width` and `thickness` (and `poisson`, `notch`,
/// `density`); `mass_per_length` with either. Also the place of the key
/// that sets the stiffness (`ei` or `modulus`).
fn section(src: &Source, owner: &str, j: &JointToml) -> Result<(SectionSpec, Span)> {
    let rectangle_keys = [
        ("width", span_of(&j.width)),
        ("thickness", span_of(&j.thickness)),
        ("poisson", span_of(&j.poisson)),
        ("notch", span_of(&j.notch)),
        ("density", span_of(&j.density)),
    ];
    let (mut spec, span) = match (&j.ei, &j.modulus) {
        (Some(ei), None) => {
            if let Some((key, Some(span))) = rectangle_keys.iter().find(|(_, v)| v.is_some()) {
                let hint = if *key == "density" { "; give mass_per_length with ei" } else { "" };
                return src.fail(span, format!("{owner}`{key}` goes with modulus, not with ei{hint}"));
            }
            (SectionSpec { ei: Some(src.profile(owner, "ei", ei)?), ..Default::default() }, ei.span())
        }
        (None, Some(e)) => {
            let modulus = src.number(owner, "modulus", e, Sign::Positive)?;
            let part = |key: &'static str, v: &Option<Spanned<toml::Value>>| -> Result<Profile> {
                let v = v.as_ref().ok_or_else(|| {
                    src.error(&e.span(), format!("{owner}modulus needs width and thickness; {key} is missing"))
                })?;
                src.profile(owner, key, v)
            };
            let (width, thickness) = (part("width", &j.width)?, part("thickness", &j.thickness)?);
            let poisson = j.poisson.as_ref().map(|p| src.number(owner, "poisson", p, Sign::Any)).transpose()?;
            let notch = j.notch.as_ref().map(|n| src.notch(owner, n)).transpose()?;
            let density = j.density.as_ref().map(|d| src.number(owner, "density", d, Sign::Positive)).transpose()?;
            let spec = SectionSpec {
                modulus: Some(modulus),
                width: Some(width),
                thickness: Some(thickness),
                poisson,
                notch,
                density,
                ..Default::default()
            };
            (spec, e.span())
        }
        (Some(ei), Some(_)) => {
            return src.fail(&ei.span(), format!("{owner}give ei or modulus, width, thickness, not both"));
        }
        (None, None) => {
            return src.fail(&j.name.span(), format!("{owner}a flexure needs ei, or modulus, width and thickness"));
        }
    };
    if let Some(mu) = &j.mass_per_length {
        if j.density.is_some() {
            return src.fail(&mu.span(), format!("{owner}give density or mass_per_length, not both"));
        }
        spec.mass_per_length = Some(src.profile(owner, "mass_per_length", mu)?);
    }
    Ok((spec, span))
}

/// Checks a flexure joint's `yield_strength` (greater than zero, and only
/// with a thickness, for a stress) and `shape` (2 to [`MAX_SHAPE`]), in a
/// file of either dimension; `stressed`: whether its section has the
/// geometry and material that give a stress.
fn report_keys(
    src: &Source,
    owner: &str,
    (yield_strength, shape): (&Option<Spanned<f64>>, &Option<Spanned<usize>>),
    stressed: bool,
) -> Result<ReportOptions> {
    let yield_strength = match yield_strength {
        Some(v) => {
            let s = src.number(owner, "yield_strength", v, Sign::Positive)?;
            if !stressed {
                return src.fail(
                    &v.span(),
                    format!(
                        "{owner}yield_strength needs a section to give a stress: give modulus with its width and thickness (or diameter) (a flexure given by its stiffnesses alone has no stress)"
                    ),
                );
            }
            Some(s)
        }
        None => None,
    };
    let shape = match shape {
        Some(k) if !(2..=MAX_SHAPE).contains(k.get_ref()) => {
            return src
                .fail(&k.span(), format!("{owner}shape = {}: must be from 2 to {MAX_SHAPE} points", k.get_ref()));
        }
        k => k.as_ref().map(|k| *k.get_ref()),
    };
    Ok(ReportOptions { yield_strength, shape })
}

/// A spatial flexure joint: its keys read into a [`SpatialSpec`] (with the
/// planar spellings `ei` = `ei_z` and `kappa` = `kappa_z`) and built by
/// the library; an error is placed at the key it names, as the file writes
/// it. Its stiffness is given at the first of `ei`, `ei_z`, `ei_y`, `gj`
/// and `modulus`.
pub(super) fn spatial_flexure(src: &Source, owner: &str, j: &JointToml) -> Result<Kind<Spatial>> {
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
    let (orders, auto_order) = match (&j.order, &j.orders) {
        (Some(_), Some(o)) => return src.fail(&o.span(), format!("{owner}give order (all three) or orders, not both")),
        (None, Some(o)) => {
            src.whole(owner, "orders", &o.span(), 3)?;
            (*o.get_ref(), false)
        }
        _ => flexure_order(src, owner, j).map(|(n, auto)| ([n; 3], auto))?,
    };
    let rest = |key: &str, v: &Option<Spanned<Vec<f64>>>| -> Result<Option<Vec<f64>>> {
        let Some(v) = v else { return Ok(None) };
        src.numbers(owner, key, &v.span(), v.get_ref(), Sign::Any)?;
        Ok(Some(v.get_ref().clone()))
    };
    let number =
        |key: &str, v: &Option<Spanned<f64>>, sign| v.as_ref().map(|v| src.number(owner, key, v, sign)).transpose();
    let spec = SpatialSpec {
        length,
        gj: profile("gj", &j.gj)?,
        ei_y: profile("ei_y", &j.ei_y)?,
        ei_z: if j.ei.is_some() { profile("ei", &j.ei)? } else { profile("ei_z", &j.ei_z)? },
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
            let span = j.span(name).unwrap_or(j.name.span());
            src.placed(owner, &span, Error::InvalidParameter { name, value, reason })
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
    if let Some(r) = &j.rotary_inertia_per_length {
        if j.mass_per_length.is_none() {
            return src.fail(
                &r.span(),
                format!("{owner}rotary_inertia_per_length needs mass_per_length (a density takes it from the section)"),
            );
        }
        src.whole(owner, "rotary_inertia_per_length", &r.span(), 3)?;
        f = f.with_rotary_inertia_per_length(*r.get_ref()).map_err(|e| src.placed(owner, &r.span(), e))?;
    }
    let report = report_keys(src, owner, (&j.yield_strength, &j.shape), f.section().has_geometry())?;
    let stiffness_place =
        ["ei", "ei_z", "ei_y", "gj", "modulus"].iter().find_map(|k| j.span(k)).unwrap_or(j.name.span());
    Ok(Kind { kind: SpatialJointKind::Flexure(Box::new(f)), stiffness_place, auto_order, report })
}
