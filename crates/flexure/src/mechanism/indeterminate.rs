//! Statically indeterminate closure forces.
//!
//! Redundant closures (several legs welded to one stage) make rows of $G$
//! dependent: a part of the multipliers, the left null space of $G$, then
//! does no work and the joints, being inextensible, cannot fix it. This
//! module fixes it by the least transmitted force.

use super::kinematics::Frames;
use super::{Loads, Mechanism};
use crate::linalg;
use nalgebra::{DMatrix, DVector};

/// The multipliers `mu` with their statically indeterminate part (the
/// left null space of $G$, where redundant closures leave $\mu$ free)
/// chosen to carry `loads` with the least transmitted force: the least
/// $\sum_j L_j\lvert F_j\rvert^2$ over the flexures $j$, $F_j$ the force the
/// bodies beyond flexure $j$ pass through it. That is the complementary
/// energy of equal axial compliance per unit length, and the limit the
/// model's own compatibility approaches as deflection vanishes (legs of a
/// stage then share a centred load equally, whichever leg carries the
/// stage in the tree). `mu` unchanged if no part is indeterminate.
pub(super) fn settle(m: &Mechanism, f: &Frames, g: &DMatrix<f64>, mu: &[f64], loads: &Loads) -> Vec<f64> {
    let rows = m.constraints();
    if rows == 0 || full_row_rank(g) {
        return mu.to_vec();
    }
    let free = linalg::null_space(&g.transpose());
    if free.ncols() == 0 {
        return mu.to_vec();
    }
    // Transmitted force = e + B μ, two rows per flexure, weighted by √L.
    let flexures: Vec<(usize, f64)> =
        m.joints.iter().enumerate().filter_map(|(j, spec)| spec.kind.flexure().map(|fl| (j, fl.length()))).collect();
    if flexures.is_empty() {
        return mu.to_vec();
    }
    let beyond: Vec<Vec<bool>> =
        flexures.iter().map(|&(j, _)| (0..m.bodies.len()).map(|b| m.path(b).contains(&j)).collect()).collect();
    let (mut e, mut b) = (DVector::zeros(2 * flexures.len()), DMatrix::zeros(2 * flexures.len(), rows));
    // Body loads: point forces, weights, and tendons pulling each via point toward its neighbours.
    let mut body_forces: Vec<(usize, [f64; 2])> = Vec::new();
    for (p, l) in m.forces.iter().zip(&loads.force) {
        body_forces.push((p.body, [l.fx, l.fy]));
    }
    for (i, body) in m.bodies.iter().enumerate() {
        body_forces.push((i, [body.mass * loads.gravity[0], body.mass * loads.gravity[1]]));
    }
    for (t, &tension) in m.tendons.iter().zip(&loads.tension) {
        let w: Vec<[f64; 2]> = t.path.iter().map(|(b, r)| f.bodies[*b].act_components([r.x, r.y])).collect();
        for (i, pair) in w.windows(2).enumerate() {
            let d = [pair[1][0] - pair[0][0], pair[1][1] - pair[0][1]];
            let len = d[0].hypot(d[1]);
            if len > 0.0 {
                let pull = [tension * d[0] / len, tension * d[1] / len];
                body_forces.push((t.path[i].0, pull));
                body_forces.push((t.path[i + 1].0, [-pull[0], -pull[1]]));
            }
        }
    }
    for (k, (inside, &(_, length))) in beyond.iter().zip(&flexures).enumerate() {
        let w = length.sqrt();
        for &(body, force) in &body_forces {
            if inside[body] {
                e[2 * k] += w * force[0];
                e[2 * k + 1] += w * force[1];
            }
        }
        // The closure term μᵀ(w_a − w_b) pushes a by −μ and b by +μ.
        let mut row = 0;
        for c in &m.closures {
            let (a, bb) = (c.a, c.b);
            let sign = match (inside[a], inside[bb]) {
                (true, false) => -1.0,
                (false, true) => 1.0,
                _ => 0.0,
            };
            b[(2 * k, row)] = sign * w;
            b[(2 * k + 1, row + 1)] = sign * w;
            row += c.equations();
        }
    }
    let mu0 = DVector::from_column_slice(mu);
    let bn = &b * &free;
    let y = crate::linalg::least_squares(&bn, &-(e + &b * &mu0));
    if y.iter().all(|v| v.is_finite()) { (mu0 + &free * y).iter().copied().collect() } else { mu.to_vec() }
}

/// Whether the rows of `g` are independent by a wide margin
/// ([`linalg::columns_independent`] of $G^T$). False leaves the decision
/// to the singular values.
pub(super) fn full_row_rank(g: &DMatrix<f64>) -> bool {
    let (m, n) = g.shape();
    linalg::columns_independent(g.transpose().as_slice(), n, m, &mut vec![0.0; m * m])
}
