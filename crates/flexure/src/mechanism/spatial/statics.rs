//! The spatial side of the one statics ([`crate::mechanism::statics`]):
//! the tests of [`Statics`](crate::mechanism::statics::Statics) that the
//! plane answers with its own fast paths (the tree's pivots, Householder
//! null spaces): stability and distance on dense matrices and pose-level
//! frames, the indeterminate closure forces, and each flexure's carried wrench.

use super::{SpatialLoads, SpatialMechanism};
use crate::kinematics::Level;
use crate::linalg;
use crate::mechanism::indeterminate::settle;
use crate::mechanism::kinematics::{Frames, distance_of, frames_level_into};
use crate::mechanism::lagrangian::{add_closure_hessian, assemble_into};
use crate::mechanism::statics::{FAR_MARGIN, Kkt, Solution};
use crate::space::Spatial;
use nalgebra::DMatrix;

impl Kkt<'_, Spatial> {
    /// $\tilde Z^T\tilde H\tilde Z - \sqrt{\text{tolerance}}\thinspace I$ positive
    /// definite, in coordinates scaled to each joint's stiffness, $H$
    /// symmetrized (a dead moment's part is not symmetric), at the
    /// multipliers of the last evaluation with their indeterminate part settled.
    pub(crate) fn stable_spatial(&mut self, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        if n == 0 {
            return true;
        }
        let size = n + rows;
        let w = &mut *self.work;
        let s = &w.root_scale;
        let entry = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r];
        if rows == 0 {
            // In the buffers: no allocation on the continuation's every step.
            let k = &mut w.stiffness;
            for c in 0..n {
                for r in 0..n {
                    k[c * n + r] = 0.5 * (entry(r, c) + entry(c, r)) * s[r] * s[c];
                }
                k[c * n + c] -= self.margin;
            }
            return linalg::positive_definite(k, n, &mut w.scratch);
        }
        let mut h = DMatrix::from_fn(n, n, |r, c| 0.5 * (entry(r, c) + entry(c, r)) * s[r] * s[c]);
        // Redundant closures: their indeterminate part of μ taken least (`mechanism::indeterminate`).
        let mu = &w.mu;
        let best = settle(m, &w.frames, &w.assembly.closure_jacobian, mu, &w.loads);
        if best != *mu {
            let change: Vec<f64> = best.iter().zip(mu).map(|(a, b)| a - b).collect();
            let mut extra = DMatrix::zeros(n, n);
            add_closure_hessian(m, &w.frames, &change, &mut extra);
            h += DMatrix::from_fn(n, n, |r, c| extra[(r, c)] * s[r] * s[c]);
        }
        let g = DMatrix::from_fn(rows, n, |i, c| jacobian[c * size + n + i] / self.closure_scale[i] * s[c]);
        let z = linalg::null_space(&g);
        let k = z.transpose() * h * &z;
        let mut k = (&k + k.transpose()) * 0.5;
        for i in 0..k.nrows() {
            k[(i, i)] -= self.margin;
        }
        linalg::is_positive_definite(&k)
    }

    /// Without closures: the symmetrized $H - \tfrac12 K$ positive definite,
    /// $K$ the joints' elastic stiffness.
    pub(crate) fn far_spatial(&mut self, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let n = m.dof();
        if m.constraints() > 0 || n == 0 {
            return false;
        }
        let w = &mut *self.work;
        let k = &mut w.stiffness;
        for c in 0..n {
            for r in 0..n {
                k[c * n + r] =
                    0.5 * (jacobian[c * n + r] / self.row_scale[r] + jacobian[r * n + c] / self.row_scale[c]);
            }
        }
        for (j, s) in m.joints.iter().zip(&w.frames.joints) {
            let (o, d) = (j.offset, s.gradient.len());
            for c in 0..d {
                for r in 0..d {
                    k[(o + c) * n + o + r] -= s.stiffness[(r, c)] * FAR_MARGIN;
                }
            }
        }
        linalg::positive_definite(k, n, &mut w.scratch)
    }

    /// [`crate::mechanism::kinematics::frame_distance`], with the frames at a configuration
    /// of the last call kept (the same coordinates, bit for bit, give the
    /// same frames).
    pub(crate) fn distance_spatial(&self, a: &[f64], b: &[f64]) -> f64 {
        let m = self.mechanism;
        let n = m.dof();
        let (a, b) = (&a[..n], &b[..n]);
        let (frames, held) = &mut *self.work.own.pair.borrow_mut();
        let holds = |f: &Frames<Spatial>, held: bool, q: &[f64]| {
            held && f.coordinates.iter().zip(q).all(|(x, y)| x.to_bits() == y.to_bits())
        };
        // Frames for `b` (slot 1 unless slot 0 already holds them), then for `a` in the other.
        let ib = usize::from(!holds(&frames[0], held[0], b));
        if !holds(&frames[ib], held[ib], b) {
            frames_level_into(m, b, Level::Pose, &mut frames[ib]);
            held[ib] = true;
        }
        let ia = 1 - ib;
        if !holds(&frames[ia], held[ia], a) {
            frames_level_into(m, a, Level::Pose, &mut frames[ia]);
            held[ia] = true;
        }
        distance_of(m, &frames[ia], &frames[ib])
    }

    /// The multipliers of a solution at `q` (`mechanism::indeterminate`), with the
    /// frames there: without closures, the energy alone needs them, at any
    /// level, so the last evaluation's if it was at `q`.
    pub(crate) fn settled_spatial(&mut self, q: &[f64], mu: Vec<f64>, loads: &SpatialLoads) -> Vec<f64> {
        let m = self.mechanism;
        let w = &mut *self.work;
        if mu.is_empty() {
            let at_q = w.frames.coordinates.iter().zip(q).all(|(a, b)| a.to_bits() == b.to_bits());
            if !at_q {
                frames_level_into(m, q, Level::Pose, &mut w.frames);
            }
            return mu;
        }
        frames_level_into(m, q, Level::Jacobian, &mut w.frames);
        // The closures' G alone is read: no load can make this fail.
        let _ = assemble_into(m, &w.frames, &mu, loads, false, &mut w.assembly);
        settle(m, &w.frames, &w.assembly.closure_jacobian, &mu, loads)
    }
}

/// The wrench each flexure joint carries at a solution: for joint `j`, the
/// tip load $w$ (moment and force in its root frame, at its tip) with which
/// the flexure alone is in equilibrium at its coordinates,
/// $S_j^Tw = \nabla U_j$, $S_j$ its motion subspace (least squares: every
/// load beyond the joint reaches it through its tip, so the equations are
/// consistent at an equilibrium). `None` for the other kinds.
pub fn flexure_loads(m: &SpatialMechanism, s: &Solution<Spatial>) -> Vec<Option<crate::spatial::SpatialLoad>> {
    let mut f = Frames::new(m);
    frames_level_into(m, &s.q, Level::Jacobian, &mut f);
    m.joints
        .iter()
        .zip(&f.joints)
        .map(|(j, state)| {
            j.kind.flexure()?;
            let w = linalg::least_squares(&state.jacobian.transpose(), &state.gradient);
            Some(crate::spatial::SpatialLoad { moment: [w[0], w[1], w[2]], force: [w[3], w[4], w[5]] })
        })
        .collect()
}
