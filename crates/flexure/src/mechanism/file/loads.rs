//! Loads: tendons along via points, forces and moments on bodies, and gravity.

use super::bodies::Find;
use super::document::{Sign, Source, Span};
use super::{Deserialize, PointLoad, Result, Spanned, Tendon};
use crate::space::Wrench;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TendonToml {
    pub(super) name: Spanned<String>,
    pub(super) tension: Spanned<f64>,
    pub(super) path: Spanned<Vec<Spanned<ViaToml>>>,
}

/// A via point: `[body, x, y]`.
pub(super) type ViaToml = (Spanned<String>, f64, f64);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ForceToml {
    pub(super) name: Option<Spanned<String>>,
    pub(super) body: Spanned<String>,
    pub(super) at: Spanned<[f64; 2]>,
    pub(super) force: Option<Spanned<[f64; 2]>>,
    pub(super) moment: Option<Spanned<f64>>,
}

/// The `[[tendon]]` tables, and the place of each via point (for the check
/// that consecutive ones do not coincide).
pub(super) fn tendons(src: &Source, find: &Find, tables: &[TendonToml]) -> Result<(Vec<Tendon>, Vec<Vec<Span>>)> {
    let mut tendons = Vec::new();
    let mut via_places: Vec<Vec<Span>> = Vec::new();
    for t in tables {
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
            path.push((find(body)?, nalgebra::Point2::new(*x, *y)));
            places.push(via.span());
        }
        tendons.push(Tendon { name: t.name.get_ref().clone(), tension, path });
        via_places.push(places);
    }
    Ok((tendons, via_places))
}

/// The `[[force]]` tables: a force and a moment at a point of a body, named
/// (by their index when unnamed) once each.
pub(super) fn forces(src: &Source, find: &Find, tables: &[ForceToml]) -> Result<Vec<PointLoad>> {
    let mut forces = Vec::new();
    for (i, f) in tables.iter().enumerate() {
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
        let wrench = Wrench { moment, fx: force[0], fy: force[1] };
        forces.push(PointLoad { name, body: find(&f.body)?, at: at.into(), wrench });
    }
    Ok(forces)
}

/// `gravity = [gx, gy]` (m/s²; none when absent).
pub(super) fn gravity(src: &Source, value: &Option<Spanned<[f64; 2]>>) -> Result<[f64; 2]> {
    src.array("", "gravity", value)
}
