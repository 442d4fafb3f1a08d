//! Bodies: the ground, one per joint's child, and what `[[body]]` tables
//! say of their mass.

use super::document::{Sign, Source};
use super::{Body, Deserialize, Result, Spanned};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BodyToml {
    pub(super) name: Spanned<String>,
    pub(super) mass: Option<Spanned<f64>>,
    pub(super) inertia: Option<Spanned<f64>>,
    pub(super) com: Option<Spanned<[f64; 2]>>,
}

/// The ground and the joints' children, in file order: each body is created
/// by the one joint that names it as child.
pub(super) fn from_joints(src: &Source, joints: &[super::JointToml]) -> Result<Vec<Body>> {
    let mut bodies = vec![Body { name: "ground".into(), mass: 0.0, inertia: 0.0, com: nalgebra::Point2::origin() }];
    for j in joints {
        let name = j.child.get_ref();
        if name == "ground" {
            return src.fail(&j.child.span(), format!("joint {:?}: the ground cannot be a child", j.name.get_ref()));
        }
        if bodies.iter().any(|b| &b.name == name) {
            return src.fail(&j.child.span(), format!("body {name:?} is reached by two joints"));
        }
        bodies.push(Body { name: name.clone(), mass: 0.0, inertia: 0.0, com: nalgebra::Point2::origin() });
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

/// Each `[[body]]` table's mass, inertia and centre of mass, given to a moving body at most once.
pub(super) fn describe(src: &Source, find: &Find, bodies: &mut [Body], tables: &[BodyToml]) -> Result<()> {
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
        if let Some(inertia) = &b.inertia {
            bodies[idx].inertia = src.number(&owner, "inertia", inertia, Sign::NotNegative)?;
        }
        bodies[idx].com = src.array(&owner, "com", &b.com)?.into();
    }
    Ok(())
}
