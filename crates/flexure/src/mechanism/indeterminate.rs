//! Statically indeterminate closure forces.
//!
//! Redundant closures (several legs welded to one stage) make rows of $G$
//! dependent: a part of the multipliers, the left null space of $G$, then
//! does no work and the joints, being inextensible, cannot fix it. This
//! module fixes it by the least transmitted force.

use super::kinematics::Frames;
use super::statics::Statics;
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
pub(super) fn settle<D: Statics>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    g: &DMatrix<f64>,
    mu: &[f64],
    loads: &Loads<D>,
) -> Vec<f64> {
    let rows = g.nrows();
    if rows == 0 || D::full_row_rank(g) {
        return mu.to_vec();
    }
    let free = linalg::null_space(&g.transpose());
    // Transmitted force = e + B μ, a position row each per flexure, weighted by √L.
    let flexures: Vec<(usize, f64)> = m
        .joints
        .iter()
        .enumerate()
        .filter_map(|(j, spec)| spec.kind.flexure().map(|fl| (j, D::flexure_length(fl))))
        .collect();
    if free.ncols() == 0 || flexures.is_empty() {
        return mu.to_vec();
    }
    // Body loads: point forces, weights, and tendons pulling each via point toward its neighbours.
    let mut body_forces: Vec<(usize, [f64; 3])> = Vec::new();
    for (p, w) in m.forces.iter().zip(&loads.force) {
        body_forces.push((p.body, D::force(w)));
    }
    for (i, body) in m.bodies.iter().enumerate() {
        body_forces.push((i, D::vector(&loads.gravity).map(|g| body.mass * g)));
    }
    for (t, &tension) in m.tendons.iter().zip(&loads.tension) {
        D::tendon_pulls(f, &t.path, tension, &mut body_forces);
    }
    let p = D::POSITION_ROWS;
    let (mut e, mut b) = (DVector::zeros(p * flexures.len()), DMatrix::zeros(p * flexures.len(), rows));
    for (k, &(j, length)) in flexures.iter().enumerate() {
        let inside: Vec<bool> = (0..m.bodies.len()).map(|body| m.path(body).contains(&j)).collect();
        let w = length.sqrt();
        for (body, force) in &body_forces {
            if inside[*body] {
                for i in 0..p {
                    e[p * k + i] += w * force[i];
                }
            }
        }
        // The closure term μᵀ(w_a − w_b) pushes a by −μ and b by +μ.
        let mut row = 0;
        for c in &m.closures {
            let sign = match (inside[c.a], inside[c.b]) {
                (true, false) => -1.0,
                (false, true) => 1.0,
                _ => 0.0,
            };
            for i in 0..p {
                b[(p * k + i, row + i)] = sign * w;
            }
            row += c.equations();
        }
    }
    let mu0 = DVector::from_column_slice(mu);
    let y = linalg::least_squares(&(&b * &free), &-(e + &b * &mu0));
    if y.iter().all(|v| v.is_finite()) { (mu0 + &free * y).iter().copied().collect() } else { mu.to_vec() }
}

/// Whether the rows of `g` are independent by a wide margin
/// ([`linalg::columns_independent`] of $G^T$). False leaves the decision
/// to the singular values.
pub(super) fn full_row_rank(g: &DMatrix<f64>) -> bool {
    let (m, n) = g.shape();
    linalg::columns_independent(g.transpose().as_slice(), n, m, &mut vec![0.0; m * m])
}
