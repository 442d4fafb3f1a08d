//! Bodies: the ground, one per joint's child, and what `[[body]]` tables
//! say of their mass.

use super::dimension::FileDimension;
use super::document::{Sign, Source, Span};
use super::{Body, Deserialize, Result, Spanned};
use nalgebra::Matrix3;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "")]
pub(super) struct BodyToml<D: FileDimension> {
    pub(super) name: Spanned<String>,
    pub(super) mass: Option<Spanned<f64>>,
    pub(super) com: Option<Spanned<D::Coords>>,
    // In the plane a number (about z); in space 3 × 3, or MuJoCo's
    // `fullinertia` components `ixx … iyz`.
    pub(super) inertia: Option<Spanned<D::Inertia>>,
    pub(super) ixx: Option<Spanned<f64>>,
    pub(super) iyy: Option<Spanned<f64>>,
    pub(super) izz: Option<Spanned<f64>>,
    pub(super) ixy: Option<Spanned<f64>>,
    pub(super) ixz: Option<Spanned<f64>>,
    pub(super) iyz: Option<Spanned<f64>>,
}

/// The ground and the joints' children, in file order: each body is created
/// by the one joint that names it as child.
pub(super) fn from_joints<D: FileDimension>(src: &Source, joints: &[super::JointToml]) -> Result<Vec<Body<D>>> {
    let mut bodies = vec![Body::massless("ground")];
    for j in joints {
        let name = j.child.get_ref();
        if name == "ground" {
            return src.fail(&j.child.span(), format!("joint {:?}: the ground cannot be a child", j.name.get_ref()));
        }
        if bodies.iter().any(|b| &b.name == name) {
            return src.fail(&j.child.span(), format!("body {name:?} is reached by two joints"));
        }
        bodies.push(Body::massless(name));
    }
    Ok(bodies)
}

/// The index of the body `name` among `names`.
pub(super) fn find(src: &Source, names: &[String], name: &Spanned<String>) -> Result<usize> {
    names.iter().position(|b| b == name.get_ref()).ok_or_else(|| {
        src.error(
            &name.span(),
            format!("unknown body {:?}: bodies are ground and the joints' children", name.get_ref()),
        )
    })
}

/// Finds a body by its name in the file, placing the error when there is none.
pub(super) type Find<'a> = dyn Fn(&Spanned<String>) -> Result<usize> + 'a;

/// Each `[[body]]` table's mass, centre of mass and inertia about it, given
/// to a moving body at most once.
pub(super) fn describe<D: FileDimension>(
    src: &Source,
    find: &Find,
    bodies: &mut [Body<D>],
    tables: &[BodyToml<D>],
) -> Result<()> {
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
        bodies[idx].com = D::point(src.array(&owner, "com", &b.com)?);
        bodies[idx].inertia = D::inertia(src, &owner, b)?;
    }
    Ok(())
}

/// A spatial body's inertia about its centre of mass: a 3 × 3 `inertia`,
/// or the components `ixx … iyz`; symmetric positive semi-definite, with
/// the triangle inequalities of a rigid body's principal moments.
pub(super) fn inertia_matrix(src: &Source, owner: &str, b: &BodyToml<crate::space::Spatial>) -> Result<Matrix3<f64>> {
    let parts = [&b.ixx, &b.iyy, &b.izz, &b.ixy, &b.ixz, &b.iyz];
    let names = ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"];
    let (inertia, span, key): (Matrix3<f64>, Span, &str) =
        match (&b.inertia, parts.iter().zip(names).find(|(p, _)| p.is_some())) {
            (Some(_), Some((p, key))) => {
                let span = p.as_ref().map(|p| p.span()).unwrap_or(b.name.span());
                return src
                    .fail(&span, format!("{owner}give inertia (3 × 3) or {key} and the other components, not both"));
            }
            (Some(i), None) => {
                let rows = i.get_ref();
                src.whole(owner, "inertia", &i.span(), 9)?;
                for (r, row) in rows.iter().enumerate() {
                    src.numbers(owner, &format!("inertia[{r}]"), &i.span(), row, Sign::Any)?;
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
                        let diagonal = key[1..2] == key[2..3];
                        *out = src.number(owner, key, p, if diagonal { Sign::NotNegative } else { Sign::Any })?;
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
    Ok(inertia)
}
