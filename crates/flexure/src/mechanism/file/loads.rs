//! Loads: tendons along via points, forces and moments on bodies, and gravity.

use super::bodies::Find;
use super::dimension::FileDimension;
use super::document::{Numbers, Sign, Source, Span};
use super::{Deserialize, PointLoad, Result, Spanned, Tendon};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "")]
pub(super) struct TendonToml<D: FileDimension> {
    pub(super) name: Spanned<String>,
    pub(super) tension: Spanned<f64>,
    // Via points: `[body, x, y]`, in space `[body, x, y, z]`.
    pub(super) path: Spanned<Vec<Spanned<D::Via>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "")]
pub(super) struct ForceToml<D: FileDimension> {
    pub(super) name: Option<Spanned<String>>,
    pub(super) body: Spanned<String>,
    pub(super) at: Option<Spanned<D::Coords>>,
    pub(super) force: Option<Spanned<D::Coords>>,
    pub(super) moment: Option<Spanned<D::Moment>>,
}

/// Each tendon's via points' places in the file.
pub(super) type ViaPlaces = Vec<Vec<Span>>;

/// The `[[tendon]]` tables, and the place of each via point (for the check
/// that consecutive ones do not coincide at rest).
pub(super) fn tendons<D: FileDimension>(
    src: &Source,
    find: &Find,
    tables: &[TendonToml<D>],
) -> Result<(Vec<Tendon<D>>, ViaPlaces)> {
    let mut tendons: Vec<Tendon<D>> = Vec::new();
    let mut via_places: ViaPlaces = Vec::new();
    for t in tables {
        let owner = format!("tendon {:?}: ", t.name.get_ref());
        if tendons.iter().any(|u| &u.name == t.name.get_ref()) {
            return src.fail(&t.name.span(), format!("duplicate tendon name {:?}", t.name.get_ref()));
        }
        let tension = src.number(&owner, "tension", &t.tension, Sign::NotNegative)?;
        if t.path.get_ref().len() < 2 {
            return src.fail(&t.path.span(), format!("{owner}a path needs at least two via points"));
        }
        let mut path = Vec::new();
        let mut places = Vec::new();
        for (k, via) in t.path.get_ref().iter().enumerate() {
            let (body, at) = D::via(via.get_ref());
            src.array_numbers(&owner, &format!("path[{k}]"), &via.span(), at.numbers(), Sign::Any)?;
            path.push((find(&body)?, D::point(at)));
            places.push(via.span());
        }
        tendons.push(Tendon { name: t.name.get_ref().clone(), tension, path });
        via_places.push(places);
    }
    Ok((tendons, via_places))
}

/// The `[[force]]` tables: a force and a moment (in the ground frame) at a
/// point of a body, named (by their index when unnamed) once each.
pub(super) fn forces<D: FileDimension>(
    src: &Source,
    find: &Find,
    tables: &[ForceToml<D>],
) -> Result<Vec<PointLoad<D>>> {
    let mut forces: Vec<PointLoad<D>> = Vec::new();
    for (i, f) in tables.iter().enumerate() {
        let name = f.name.as_ref().map_or(i.to_string(), |n| n.get_ref().clone());
        let owner = format!("force {name:?}: ");
        if forces.iter().any(|g| g.name == name) {
            let span = f.name.as_ref().map_or(f.body.span(), |n| n.span());
            return src.fail(&span, format!("duplicate force name {name:?}"));
        }
        let at = src.array(&owner, "at", &f.at)?;
        let force = src.array(&owner, "force", &f.force)?;
        let moment = src.array(&owner, "moment", &f.moment)?;
        forces.push(PointLoad { name, body: find(&f.body)?, at: D::point(at), wrench: D::wrench(force, moment) });
    }
    Ok(forces)
}
