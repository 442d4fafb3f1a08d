//! Closures: welds, pins and (in space) balls that join two bodies beyond the tree.

use super::bodies::Find;
use super::dimension::FileDimension;
use super::document::{Source, place};
use super::{Closure, Deserialize, Result, Spanned};
use crate::mechanism::Holds;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct WeldToml {
    pub(super) a: Spanned<String>,
    pub(super) a_origin: Option<Spanned<[f64; 3]>>,
    pub(super) a_rpy: Option<Spanned<[f64; 3]>>,
    pub(super) a_rpy_deg: Option<Spanned<[f64; 3]>>,
    pub(super) b: Spanned<String>,
    pub(super) b_origin: Option<Spanned<[f64; 3]>>,
    pub(super) b_rpy: Option<Spanned<[f64; 3]>>,
    pub(super) b_rpy_deg: Option<Spanned<[f64; 3]>>,
    pub(super) preload: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "")]
pub(super) struct PinToml<D: FileDimension> {
    pub(super) a: Spanned<String>,
    pub(super) a_at: Option<Spanned<D::Coords>>,
    pub(super) axis: Option<Spanned<[f64; 3]>>,
    pub(super) b: Spanned<String>,
    pub(super) b_at: Option<Spanned<D::Coords>>,
    pub(super) b_axis: Option<Spanned<[f64; 3]>>,
    pub(super) preload: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[serde(bound = "")]
pub(super) struct BallToml<D: FileDimension> {
    pub(super) a: Spanned<String>,
    pub(super) a_at: Option<Spanned<D::Coords>>,
    pub(super) b: Spanned<String>,
    pub(super) b_at: Option<Spanned<D::Coords>>,
    pub(super) preload: Option<Spanned<bool>>,
}

/// A closure as the file writes it, for its place and `preload`.
pub(super) struct Written<'a> {
    a: &'a Spanned<String>,
    preload: &'a Option<Spanned<bool>>,
}

/// The closures (welds, then pins, then balls) and each one's table; `rest`:
/// the bodies' frames at rest (where a spatial pin's axis lies on `b`).
pub(super) fn closures<'f, D: FileDimension>(
    src: &Source,
    find: &Find,
    rest: &[D::Pose],
    (welds, pins, balls): (&'f [WeldToml], &'f [PinToml<D>], &'f [BallToml<D>]),
) -> Result<(Vec<Closure<D>>, Vec<Written<'f>>)> {
    let mut closures = Vec::new();
    let mut written = Vec::new();
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
        let a_origin = D::pose(src, &owner, ["a_origin", "a_rpy", "a_rpy_deg"], [&w.a_origin, &w.a_rpy, &w.a_rpy_deg])?;
        let b_origin = D::pose(src, &owner, ["b_origin", "b_rpy", "b_rpy_deg"], [&w.b_origin, &w.b_rpy, &w.b_rpy_deg])?;
        closures.push(Closure { holds: Holds::Weld, a, a_origin, b, b_origin });
        written.push(Written { a: &w.a, preload: &w.preload });
    }
    for p in pins {
        let owner = format!("pin of {:?} and {:?}: ", p.a.get_ref(), p.b.get_ref());
        let (a, b) = distinct(&p.a, &p.b, "pin")?;
        let (a_at, b_at) = (src.array(&owner, "a_at", &p.a_at)?, src.array(&owner, "b_at", &p.b_at)?);
        closures.push(D::pin(src, &owner, p, (a, D::point(a_at)), (b, D::point(b_at)), rest)?);
        written.push(Written { a: &p.a, preload: &p.preload });
    }
    for ball in balls {
        let owner = format!("ball of {:?} and {:?}: ", ball.a.get_ref(), ball.b.get_ref());
        let (a, b) = distinct(&ball.a, &ball.b, "ball")?;
        let (a_at, b_at) = (src.array(&owner, "a_at", &ball.a_at)?, src.array(&owner, "b_at", &ball.b_at)?);
        closures.push(Closure::at_points(Holds::Ball, a, D::point(a_at), b, D::point(b_at)));
        written.push(Written { a: &ball.a, preload: &ball.preload });
    }
    Ok((closures, written))
}

/// Where each closure is written ("line L, column C" of its `a`) and whether
/// it says `preload = true`, in the order of [`closures`].
pub(super) fn places(text: &str, written: &[Written]) -> (Vec<String>, Vec<bool>) {
    written.iter().map(|w| (place(text, w.a.span().start), w.preload.as_ref().is_some_and(|p| *p.get_ref()))).unzip()
}
