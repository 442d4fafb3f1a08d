//! A flexure joint's keys: its section (`ei`, or `modulus`, `width`,
//! `thickness` with `poisson`, `notch`, `density`), `order`, and what
//! `flexure solve` reports of it.

use super::document::{Sign, Source, Span};
use super::{Error, Flexure, JointToml, MAX_SHAPE, Notch, Profile, Result, Section, Spanned, bending_stiffness};

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
pub(super) fn flexure_order(src: &Source, owner: &str, j: &JointToml) -> Result<(usize, bool)> {
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

/// A flexure joint's bending stiffness: the uniform $EI$ to build it with,
/// the place of the key that sets it, and the [`Section`] that replaces it
/// when $EI$ varies, a thickness gives stress, or a density gives mass.
pub(super) fn flexure_section(src: &Source, owner: &str, j: &JointToml) -> Result<(f64, Span, Option<Section>)> {
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
pub(super) fn report(src: &Source, owner: &str, j: &JointToml, f: &Flexure) -> Result<Report> {
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
