//! Closures: welds and pins that join two bodies beyond the tree.

use super::bodies::Find;
use super::document::{Source, place};
use super::{Closure, Deserialize, Pose, Result, Spanned};
use crate::mechanism::Holds;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct WeldToml {
    pub(super) a: Spanned<String>,
    pub(super) a_origin: Option<Spanned<[f64; 3]>>,
    pub(super) b: Spanned<String>,
    pub(super) b_origin: Option<Spanned<[f64; 3]>>,
    pub(super) preload: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PinToml {
    pub(super) a: Spanned<String>,
    pub(super) a_at: Option<Spanned<[f64; 2]>>,
    pub(super) b: Spanned<String>,
    pub(super) b_at: Option<Spanned<[f64; 2]>>,
    pub(super) preload: Option<Spanned<bool>>,
}

/// The `[[weld]]` tables, then the `[[pin]]` tables, each joining two distinct bodies.
pub(super) fn closures(src: &Source, find: &Find, welds: &[WeldToml], pins: &[PinToml]) -> Result<Vec<Closure>> {
    let mut closures = Vec::new();
    let distinct = |a: usize, b: &Spanned<String>, what: &str| -> Result<()> {
        if a == find(b)? {
            return src.fail(&b.span(), format!("a {what} joins body {:?} to itself", b.get_ref()));
        }
        Ok(())
    };
    for w in welds {
        let owner = format!("weld of {:?} and {:?}: ", w.a.get_ref(), w.b.get_ref());
        let (ao, bo) = (src.array(&owner, "a_origin", &w.a_origin)?, src.array(&owner, "b_origin", &w.b_origin)?);
        let a = find(&w.a)?;
        distinct(a, &w.b, "weld")?;
        let pose = |o: [f64; 3]| Pose { x: o[0], y: o[1], phi: o[2] };
        closures.push(Closure { holds: Holds::Weld, a, a_origin: pose(ao), b: find(&w.b)?, b_origin: pose(bo) });
    }
    for p in pins {
        let owner = format!("pin of {:?} and {:?}: ", p.a.get_ref(), p.b.get_ref());
        let (a_at, b_at) = (src.array(&owner, "a_at", &p.a_at)?, src.array(&owner, "b_at", &p.b_at)?);
        let a = find(&p.a)?;
        distinct(a, &p.b, "pin")?;
        closures.push(Closure::at_points(Holds::Pin, a, a_at.into(), find(&p.b)?, b_at.into()));
    }
    Ok(closures)
}

/// Where each closure is written ("line L, column C" of its `a`), in the order of [`closures`].
pub(super) fn places(text: &str, welds: &[WeldToml], pins: &[PinToml]) -> Vec<String> {
    welds.iter().map(|w| &w.a).chain(pins.iter().map(|p| &p.a)).map(|a| place(text, a.span().start)).collect()
}

/// Each closure's `preload` (false when absent), in the order of [`closures`].
pub(super) fn preloads(welds: &[WeldToml], pins: &[PinToml]) -> Vec<bool> {
    welds
        .iter()
        .map(|w| &w.preload)
        .chain(pins.iter().map(|p| &p.preload))
        .map(|p| p.as_ref().is_some_and(|p| *p.get_ref()))
        .collect()
}
