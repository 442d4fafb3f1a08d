//! A spatial flexure's section at any arc length, with the derivatives of
//! its pose in the coordinates: the tip pass of [`super::update`] stopped at
//! $s$, its last step a partial one (as the mass stations take theirs), so
//! a contact anywhere along the flexure has the exact Jacobian and Hessian
//! of the integration its shape uses.

use super::SpatialFlexure;
use super::kinematics::{SpatialKinematics, advance, row_curvature};
use super::magnus::NODES;
use crate::basis;
use nalgebra::{Matrix3, Vector3, Vector6};

/// The section at arc length `s` (m, in $[0, L]$) at coordinates `alpha`:
/// its rotation $R$ and position $p$ in the root frame, with `data`'s body
/// Jacobian columns $J_a = g^{-1}\partial_a g$ and their derivatives
/// $H_{ab} = \partial_b J_a$ (in the section's frame) at $s$, by the
/// recursion of [`super::update`] over the subintervals before $s$ and one
/// partial step of the same Magnus rule from the last one's start to $s$.
///
/// # Panics
/// If `alpha` does not have [`SpatialFlexure::coordinates`] entries or
/// `data` was made for another flexure.
///
/// # Example
/// ```
/// use flexure::{Level, section::SpatialSection, spatial::{SpatialFlexure, SpatialKinematics, section_at, update}};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [2, 2, 2]).unwrap();
/// let alpha = [0.1, 0.2, -0.3, 0.1, 0.4, -0.2];
/// // At the tip it is the tip pass.
/// let (mut at, mut tip) = (SpatialKinematics::new(&f), SpatialKinematics::new(&f));
/// let (r, p) = section_at(&f, &alpha, 1.0, &mut at);
/// update(&f, &alpha, Level::Hessian, &mut tip);
/// assert!((p - tip.position).norm() < 1e-15 && (r - tip.rotation).norm() < 1e-15);
/// let column = at.jacobian_columns()[4];
/// assert!((0..6).all(|i| (column[i] - tip.jacobian[(i, 4)]).abs() < 1e-15));
/// ```
pub fn section_at(
    flexure: &SpatialFlexure,
    alpha: &[f64],
    s: f64,
    data: &mut SpatialKinematics,
) -> (Matrix3<f64>, Vector3<f64>) {
    assert_eq!(alpha.len(), flexure.coordinates(), "alpha must have one entry per coordinate");
    assert!(data.fits(flexure), "SpatialKinematics buffers were made for a flexure with another number of coordinates");
    let (m, w, l, orders) = (flexure.subintervals(), flexure.width(), flexure.length(), flexure.orders());
    let h = l / m as f64;
    let (mut r, mut p) = (Matrix3::identity(), Vector3::zeros());
    data.columns.fill(Vector6::zeros());
    data.hessian.fill(Vector6::zeros());
    let full = ((s / h).floor().max(0.0) as usize).min(m);
    let mut partial = vec![0.0; w];
    let mut rows = vec![0.0; 3 * w];
    for k in 0..=full {
        let (start, length) = (k as f64 * h, if k < full { h } else { s - full as f64 * h });
        if length <= 0.0 {
            break;
        }
        if k < full {
            rows.copy_from_slice(flexure.shapes(k));
        } else {
            for (g, t) in NODES.iter().enumerate() {
                basis::shifted_legendre((start + t * length) / l, &mut partial);
                for (v, b) in rows[g * w..(g + 1) * w].iter_mut().zip(&partial) {
                    *v = b / l;
                }
            }
        }
        let xi: [Vector6<f64>; 3] = std::array::from_fn(|g| {
            let u = row_curvature(&rows[g * w..(g + 1) * w], orders, alpha);
            Vector6::new(u[0], u[1], u[2], 1.0, 0.0, 0.0)
        });
        let derivative = |a: usize| {
            let (c, i) = flexure.component(a);
            std::array::from_fn(|g| {
                let mut d = Vector6::zeros();
                d[c] = rows[g * w + i];
                d
            })
        };
        let step = advance(data, &xi, derivative, length, 2);
        p += r * step.p;
        r *= step.r;
    }
    (r, p)
}

impl SpatialKinematics {
    /// The body Jacobian's columns $J_a$ of the last pass (6-vectors,
    /// angular then linear, in the frame reached), one per coordinate.
    pub fn jacobian_columns(&self) -> &[Vector6<f64>] {
        &self.columns
    }

    /// $H_{ab} = \partial_bJ_a$ of the last pass at [`crate::Level::Hessian`] (in the frame reached).
    pub fn column_derivative(&self, a: usize, b: usize) -> &Vector6<f64> {
        &self.hessian[a * self.columns.len() + b]
    }
}
