//! The rest of a spatial file: bodies' inertia, tendons, forces and
//! moments, and the weld, pin and ball closures.

use super::{Result, Sign, Source, Spanned};
use crate::mechanism::Holds;
use crate::mechanism::file::document::place;
use crate::mechanism::spatial::joints::unit_axis;
use crate::mechanism::spatial::{SpatialBody, SpatialClosure, SpatialPointLoad, SpatialTendon};
use nalgebra::{Isometry3, Matrix3, Point3, Vector3, Vector6};
use serde::Deserialize;

type Find<'a> = dyn Fn(&Spanned<String>) -> Result<usize> + 'a;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BodyToml {
    name: Spanned<String>,
    mass: Option<Spanned<f64>>,
    com: Option<Spanned<[f64; 3]>>,
    inertia: Option<Spanned<[[f64; 3]; 3]>>,
    ixx: Option<Spanned<f64>>,
    iyy: Option<Spanned<f64>>,
    izz: Option<Spanned<f64>>,
    ixy: Option<Spanned<f64>>,
    ixz: Option<Spanned<f64>>,
    iyz: Option<Spanned<f64>>,
}

/// A via point: `[body, x, y, z]`.
type ViaToml = (Spanned<String>, f64, f64, f64);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TendonToml {
    name: Spanned<String>,
    tension: Spanned<f64>,
    path: Spanned<Vec<Spanned<ViaToml>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ForceToml {
    name: Option<Spanned<String>>,
    body: Spanned<String>,
    at: Option<Spanned<[f64; 3]>>,
    force: Option<Spanned<[f64; 3]>>,
    moment: Option<Spanned<[f64; 3]>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct WeldToml {
    a: Spanned<String>,
    a_origin: Option<Spanned<[f64; 3]>>,
    a_rpy: Option<Spanned<[f64; 3]>>,
    a_rpy_deg: Option<Spanned<[f64; 3]>>,
    b: Spanned<String>,
    b_origin: Option<Spanned<[f64; 3]>>,
    b_rpy: Option<Spanned<[f64; 3]>>,
    b_rpy_deg: Option<Spanned<[f64; 3]>>,
    preload: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PinToml {
    a: Spanned<String>,
    a_at: Option<Spanned<[f64; 3]>>,
    axis: Option<Spanned<[f64; 3]>>,
    b: Spanned<String>,
    b_at: Option<Spanned<[f64; 3]>>,
    b_axis: Option<Spanned<[f64; 3]>>,
    preload: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BallToml {
    a: Spanned<String>,
    a_at: Option<Spanned<[f64; 3]>>,
    b: Spanned<String>,
    b_at: Option<Spanned<[f64; 3]>>,
    preload: Option<Spanned<bool>>,
}

/// Each `[[body]]` table's mass, centre of mass and inertia about it: a
/// 3 × 3 `inertia`, or MuJoCo's `fullinertia` components `ixx … iyz`;
/// symmetric positive semi-definite, with the triangle inequalities of a
/// rigid body's principal moments.
pub(super) fn describe(src: &Source, find: &Find, bodies: &mut [SpatialBody], tables: &[BodyToml]) -> Result<()> {
    let mut described = vec![false; bodies.len()];
    for b in tables {
        let idx = find(&b.name)?;
        let owner = format!("body {:?}: ", b.name.get_ref());
        if idx == 0 {
            return src.fail(&b.name.span(), format!("{owner}the ground does not move; give mass to a moving body"));
        }
        if described[idx] {
            return src.fail(&b.name.span(), format!("{owner}described twice"));
        }
        described[idx] = true;
        if let Some(mass) = &b.mass {
            bodies[idx].mass = src.number(&owner, "mass", mass, Sign::NotNegative)?;
        }
        bodies[idx].com = Point3::from(src.array(&owner, "com", &b.com)?);
        let parts = [&b.ixx, &b.iyy, &b.izz, &b.ixy, &b.ixz, &b.iyz];
        let names = ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"];
        let (inertia, span, key) = match (&b.inertia, parts.iter().zip(names).find(|(p, _)| p.is_some())) {
            (Some(_), Some((p, key))) => {
                let span = p.as_ref().map(|p| p.span()).unwrap_or(b.name.span());
                return src
                    .fail(&span, format!("{owner}give inertia (3 × 3) or {key} and the other components, not both"));
            }
            (Some(i), None) => {
                let rows = i.get_ref();
                for (r, row) in rows.iter().enumerate() {
                    src.numbers(&owner, &format!("inertia[{r}]"), &i.span(), row, Sign::Any)?;
                }
                let m = Matrix3::from_fn(|r, c| rows[r][c]);
                if (m - m.transpose()).amax() > 1e-12 * m.amax() {
                    return src.fail(&i.span(), format!("{owner}inertia must be symmetric"));
                }
                (m, i.span(), "inertia")
            }
            (None, Some(_)) => {
                let mut v = [0.0; 6];
                for ((p, key), out) in parts.iter().zip(names).zip(v.iter_mut()) {
                    if let Some(p) = p {
                        *out = src.number(
                            &owner,
                            key,
                            p,
                            if key.len() == 3 && key[1..2] == key[2..3] { Sign::NotNegative } else { Sign::Any },
                        )?;
                    }
                }
                let [xx, yy, zz, xy, xz, yz] = v;
                let span = parts.iter().find_map(|p| p.as_ref().map(|p| p.span())).unwrap_or(b.name.span());
                (Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz), span, "ixx … iyz")
            }
            (None, None) => (Matrix3::zeros(), b.name.span(), "inertia"),
        };
        let eig = inertia.symmetric_eigenvalues();
        let scale = eig.amax();
        if eig.iter().any(|e| *e < -1e-12 * scale) {
            return src.fail(
                &span,
                format!(
                    "{owner}{key} must be positive semi-definite (its principal moments are {:.4e}, {:.4e}, {:.4e})",
                    eig[0], eig[1], eig[2]
                ),
            );
        }
        let (a, b2, c) = (eig[0], eig[1], eig[2]);
        if a + b2 < c * (1.0 - 1e-9) || a + c < b2 * (1.0 - 1e-9) || b2 + c < a * (1.0 - 1e-9) {
            return src.fail(&span, format!("{owner}{key}: its principal moments {a:.4e}, {b2:.4e}, {c:.4e} break the triangle inequality (no rigid body has them)"));
        }
        bodies[idx].inertia = inertia;
    }
    Ok(())
}

/// The `[[tendon]]` tables: `path = [["body", x, y, z], …]`, two via points or more.
pub(super) fn tendons(src: &Source, find: &Find, tables: &[TendonToml]) -> Result<Vec<SpatialTendon>> {
    let mut tendons: Vec<SpatialTendon> = Vec::new();
    for t in tables {
        let owner = format!("tendon {:?}: ", t.name.get_ref());
        if tendons.iter().any(|u| &u.name == t.name.get_ref()) {
            return src.fail(&t.name.span(), format!("duplicate tendon name {:?}", t.name.get_ref()));
        }
        let tension = src.number(&owner, "tension", &t.tension, Sign::NotNegative)?;
        if t.path.get_ref().len() < 2 {
            return src.fail(&t.path.span(), format!("{owner}a path needs at least two via points"));
        }
        let mut path: Vec<(usize, Point3<f64>)> = Vec::new();
        for (k, via) in t.path.get_ref().iter().enumerate() {
            let (body, x, y, z) = via.get_ref();
            src.numbers(&owner, &format!("path[{k}]"), &via.span(), &[*x, *y, *z], Sign::Any)?;
            let b = find(body)?;
            let p = Point3::new(*x, *y, *z);
            if let Some(last) = path.last()
                && last.0 == b
                && last.1 == p
            {
                return src.fail(
                    &via.span(),
                    format!("{owner}path[{k}] is the via point before it: a segment of no length has no direction"),
                );
            }
            path.push((b, p));
        }
        tendons.push(SpatialTendon { name: t.name.get_ref().clone(), tension, path });
    }
    Ok(tendons)
}

/// The `[[force]]` tables: a force and a moment (ground frame) at a point of a body.
pub(super) fn forces(src: &Source, find: &Find, tables: &[ForceToml]) -> Result<Vec<SpatialPointLoad>> {
    let mut forces: Vec<SpatialPointLoad> = Vec::new();
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
        let wrench = Vector6::new(moment[0], moment[1], moment[2], force[0], force[1], force[2]);
        forces.push(SpatialPointLoad { name, body: find(&f.body)?, at: Point3::from(at), wrench });
    }
    Ok(forces)
}

/// A closure's place in the file, and whether it says `preload = true`.
pub(super) type Placed = (String, bool);

/// The closures (welds, then pins, then balls) and where each is written.
/// A pin's axis on `b` is, unless `b_axis` gives it, where its `axis` (in
/// `a`'s frame) lies at rest (`rest`: the bodies' frames at the joints' rest).
pub(super) fn closures(
    src: &Source,
    find: &Find,
    rest: &[Isometry3<f64>],
    (welds, pins, balls): (&[WeldToml], &[PinToml], &[BallToml]),
) -> Result<(Vec<SpatialClosure>, Vec<Placed>)> {
    let mut closures = Vec::new();
    // Each closure's place in the file, and whether it says `preload = true`.
    let mut places = Vec::new();
    let preload = |p: &Option<Spanned<bool>>| p.as_ref().is_some_and(|p| *p.get_ref());
    let distinct = |a: &Spanned<String>, b: &Spanned<String>, what: &str| -> Result<(usize, usize)> {
        let (ia, ib) = (find(a)?, find(b)?);
        if ia == ib {
            return src.fail(&b.span(), format!("a {what} joins body {:?} to itself", b.get_ref()));
        }
        Ok((ia, ib))
    };
    for w in welds {
        let owner = format!("weld of {:?} and {:?}: ", w.a.get_ref(), w.b.get_ref());
        let (a, b) = distinct(&w.a, &w.b, "weld")?;
        let a_origin =
            src.placement(&owner, ["a_origin", "a_rpy", "a_rpy_deg"], &w.a_origin, &w.a_rpy, &w.a_rpy_deg)?;
        let b_origin =
            src.placement(&owner, ["b_origin", "b_rpy", "b_rpy_deg"], &w.b_origin, &w.b_rpy, &w.b_rpy_deg)?;
        closures.push(SpatialClosure { holds: Holds::Weld, a, a_origin, b, b_origin });
        places.push((place(src.text, w.a.span().start), preload(&w.preload)));
    }
    for p in pins {
        let owner = format!("pin of {:?} and {:?}: ", p.a.get_ref(), p.b.get_ref());
        let (a, b) = distinct(&p.a, &p.b, "pin")?;
        let (a_at, b_at) = (src.array(&owner, "a_at", &p.a_at)?, src.array(&owner, "b_at", &p.b_at)?);
        let axis = p
            .axis
            .as_ref()
            .ok_or_else(|| src.error(&p.a.span(), format!("{owner}a pin needs its axis (in a's frame)")))?;
        src.numbers(&owner, "axis", &axis.span(), axis.get_ref(), Sign::Any)?;
        let a_axis = unit_axis("axis", Vector3::from(*axis.get_ref()))
            .map_err(|e| src.placed(&owner, &axis.span(), e))?
            .into_inner();
        let b_axis = match &p.b_axis {
            Some(v) => {
                src.numbers(&owner, "b_axis", &v.span(), v.get_ref(), Sign::Any)?;
                unit_axis("b_axis", Vector3::from(*v.get_ref()))
                    .map_err(|e| src.placed(&owner, &v.span(), e))?
                    .into_inner()
            }
            None => rest[b].rotation.inverse() * (rest[a].rotation * a_axis),
        };
        let c = SpatialClosure::pin(a, Point3::from(a_at), a_axis, b, Point3::from(b_at), b_axis)
            .map_err(|e| src.placed(&owner, &axis.span(), e))?;
        closures.push(c);
        places.push((place(src.text, p.a.span().start), preload(&p.preload)));
    }
    for ball in balls {
        let owner = format!("ball of {:?} and {:?}: ", ball.a.get_ref(), ball.b.get_ref());
        let (a, b) = distinct(&ball.a, &ball.b, "ball")?;
        let (a_at, b_at) = (src.array(&owner, "a_at", &ball.a_at)?, src.array(&owner, "b_at", &ball.b_at)?);
        closures.push(SpatialClosure::at_points(Holds::Ball, a, Point3::from(a_at), b, Point3::from(b_at)));
        places.push((place(src.text, ball.a.span().start), preload(&ball.preload)));
    }
    Ok((closures, places))
}
