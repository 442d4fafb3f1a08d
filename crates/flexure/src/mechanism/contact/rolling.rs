//! What friction needs where a contact rolls: the two material points that
//! touch (the toucher's and the geom body's), the surface's tangents there,
//! and how far the surfaces have turned under the contact since they were
//! pinned. Statics holds a rolling stuck contact by pinning these points
//! along the surface, set anew as it rolls; motion holds their relative
//! velocity at zero along the tangents (`dynamics/contact.rs`).

use super::{Geom, Pair, PointJet, Touch, corner, dot, scaled, vector};
use crate::error::Result;
use crate::mechanism::Mechanism;
use crate::mechanism::kinematics::{FrameChain, Frames};

/// The geom whose surface `pair` touches: its geom, or between two geoms
/// the one its corner touches.
pub(crate) fn touched<'m, D: Touch>(m: &'m Mechanism<D>, pair: &Pair) -> &'m Geom<D> {
    match corner(m, pair) {
        Ok(c) => c.flat,
        Err(_) => &m.geoms[pair.geom],
    }
}

/// A flexure's material point where it touches at `s`, $h$ off its
/// centreline against the `normal` (world), its section's axes `frame`
/// there (world, [`super::SectionJet::frame`]): the arc length, then the
/// offset in those axes ([`super::jet::Material`]).
pub(crate) fn on_flexure<D: Touch>(s: f64, frame: &[D::Vector], normal: &D::Vector, half: f64) -> [f64; 4] {
    let offset = scaled::<D>(normal, -half);
    let mut out = [s, 0.0, 0.0, 0.0];
    for (o, e) in out[1..].iter_mut().zip(frame) {
        *o = dot::<D>(e, &offset);
    }
    out
}

/// Unit tangents of the surface with normal `n` (world), orthogonal to it
/// and to each other: one in the plane, two in space; the `previous`
/// tangents kept in the new plane where given, so the basis turns with it.
pub(crate) fn tangents<D: Touch>(n: &[f64; 3], previous: Option<&[[f64; 3]; 2]>) -> [[f64; 3]; 2] {
    let n = vector::<D>(n);
    let mut axes: Vec<usize> = (0..D::POINT_DIM).collect();
    axes.sort_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()));
    let mut basis = vec![n];
    let old = previous.map_or(Vec::new(), |p| p[..D::POINT_DIM - 1].iter().map(vector::<D>).collect());
    let units = axes.into_iter().map(|i| {
        let mut e = D::Vector::default();
        e[i] = 1.0;
        e
    });
    for mut e in old.into_iter().chain(units) {
        for b in &basis {
            e = e - scaled::<D>(b, dot::<D>(b, &e));
        }
        let size = dot::<D>(&e, &e).sqrt();
        if basis.len() < D::POINT_DIM && size > 1e-3 {
            basis.push(scaled::<D>(&e, 1.0 / size));
        }
    }
    let mut out = [[0.0; 3]; 2];
    for (k, u) in basis[1..].iter().enumerate() {
        out[k] = super::array::<D>(u);
    }
    out
}

/// The most either surface turned under a rolling contact of `pair` since
/// its material points were pinned (rad): the geom's normal at the anchor
/// `from` (its body's frame) against the `normal` now, and the toucher's,
/// its pinned point `p` ([`super::material_jet`]) against the contact now
/// at `point`. `length` (m) scales the step off a corner (frames `f` at the state).
pub(crate) fn turned<D: Touch + FrameChain>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    (pair, from): (&Pair, &[f64; 3]),
    p: &PointJet<'_, D>,
    (point, normal): (&D::Point, &D::Vector),
    length: f64,
) -> Result<f64> {
    let angle = |a: &D::Vector, b: &D::Vector| dot::<D>(a, b).clamp(-1.0, 1.0).acos();
    // The geom's normal where the anchor is, seen from just outside it
    // along the normal now, so that a box's corner, whose normal is any
    // between its faces', has that one.
    let geom = touched(m, pair);
    let body = &f.bodies[geom.body];
    let anchor = D::act(body, &D::moved(&D::origin(&D::identity()), &vector::<D>(from), 1.0));
    let outside = D::moved(&anchor, normal, 1e-3 * length);
    let there = geom.gap(body, &outside, 0.0).1;
    let off = dot::<D>(&p.offset, &p.offset).sqrt();
    // The toucher's: a strip's surface point's offset against the normal,
    // a centreline's tilt out of the surface, or the arc of a ball between
    // its point and the contact (none on a sharp corner, which does not roll).
    let toucher = match (p.tangent(), corner(m, pair)) {
        (Some(_), _) if off > 0.0 => angle(&scaled::<D>(&p.offset, -1.0 / off), normal),
        (Some(u), _) => dot::<D>(&u, normal).abs().min(1.0).asin(),
        (None, Ok(c)) if c.radius == 0.0 => 0.0,
        (None, Ok(c)) => {
            let chord = D::position(&p.x) - D::position(point);
            2.0 * (0.5 * dot::<D>(&chord, &chord).sqrt() / c.radius).min(1.0).asin()
        }
        (None, Err(e)) => return Err(e),
    };
    Ok(angle(&there, normal).max(toucher))
}
