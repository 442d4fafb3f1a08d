//! The Hessian of a tree mechanism's potential, factored in $O(n)$ by
//! elimination from the leaves (a Riccati recursion).
//!
//! Every joint's angle is linear in its coordinates,
//! $\phi_j = d_j^T q_j$ (a flexure's tip-angle row, 1 for a pin, 0 for a
//! slider), so the Hessian of a point load's potential couples a
//! coordinate $a$ of joint $i$ with a coordinate $b$ of a joint $j$ below
//! it only through $\partial_a\phi_i\thinspace W\cdot\mathrm J\thinspace\partial_b w$ ([`super::kinematics`]),
//! the same for every ancestor $i$ of $j$. Summed over the points below
//! $j$ (forces, weights, closure multipliers' point terms), the Hessian is
//! $$H = \operatorname{blockdiag}(D_j) + \sum_{i \text{ above } j}\left(d_i g_j^T + g_j d_i^T\right),$$
//! zero between joints on different branches: semiseparable. Symmetric
//! block elimination from the leaves keeps that form. With
//! $B_j = \sum_{c \text{ child of } j}\beta_c$, joint $j$'s pivot and coupling are
//! $$M_j = D_j - B_j d_j d_j^T,\qquad h_j = g_j - B_j d_j,\qquad
//! \beta_j = h_j^T M_j^{-1} h_j + B_j,$$
//! and a solve $H\delta = r$ is one pass up ($u_j = M_j^{-1}(r_j - d_jA_j)$,
//! $\alpha_j = h_j^Tu_j + A_j$, $A_j = \sum_c\alpha_c$) and one pass down
//! ($\delta_j = u_j - M_j^{-1}h_j\thinspace\Theta_j$, $\Theta$ the sum of
//! $d_i^T\delta_i$ over the joints above). The elimination is a congruence,
//! so $H$ is positive definite exactly when every pivot $M_j$ is (Sylvester's
//! law of inertia): the definiteness test is the factorization itself.
//!
//! Tendons (whose length couples branches) break this form, and closures
//! break it in the KKT matrix: their problems keep the dense
//! factorization. A closure's own Hessian terms are point terms, though,
//! so the Hessian of a closed mechanism without tendons keeps the form,
//! and its definiteness is tested here too (a sufficient test of stability,
//! [`super::statics`]).

use super::Mechanism;
use crate::linalg;

/// The structure of a mechanism's tree and the buffers of one factorization
/// (allocation-free once made).
#[derive(Debug, Clone, Default)]
pub(super) struct Tree {
    /// Per joint: first coordinate, number of coordinates, parent joint.
    offset: Vec<usize>,
    dof: Vec<usize>,
    parent: Vec<Option<usize>>,
    /// Per joint: the coordinate above it (of the nearest ancestor whose
    /// angle row is not zero) whose Hessian row reads $g_j$, if any.
    anchor: Vec<Option<usize>>,
    /// The angle rows $d$, unscaled, per coordinate.
    angle: Vec<f64>,
    /// Per coordinate: $d$ (scaled), $h$, $M^{-1}h$.
    d: Vec<f64>,
    h: Vec<f64>,
    w: Vec<f64>,
    /// Per joint: $\beta$ (during factoring: $B$), then $A$/$\alpha$ and $\Theta$ during solves.
    beta: Vec<f64>,
    alpha: Vec<f64>,
    theta: Vec<f64>,
    /// The pivots' LU factors (Cholesky's, in a definiteness test),
    /// $\sum_j k_j^2$ entries, and their row swaps.
    pivots: Vec<f64>,
    block: Vec<usize>,
    swaps: Vec<usize>,
}

impl Tree {
    /// Whether the factorization applies to `m`'s joints: every joint's
    /// rotation is linear in its coordinates ([`super::Joint::angle_row`]),
    /// as for every planar kind.
    pub fn applies(m: &Mechanism) -> bool {
        m.joints.iter().all(|j| j.kind.joint().angle_row().is_some())
    }

    /// The tree of `m`, for which [`Tree::applies`].
    pub fn new(m: &Mechanism) -> Self {
        let joints = m.joints.len();
        let n = m.dof();
        let mut t = Tree {
            offset: m.joints.iter().map(|j| j.offset).collect(),
            dof: m.joints.iter().map(|j| j.kind.joint().dof()).collect(),
            parent: m.joints.iter().map(|j| m.parent_joint(j.parent)).collect(),
            anchor: vec![None; joints],
            angle: vec![0.0; n],
            d: vec![0.0; n],
            h: vec![0.0; n],
            w: vec![0.0; n],
            beta: vec![0.0; joints],
            alpha: vec![0.0; joints],
            theta: vec![0.0; joints],
            pivots: Vec::new(),
            block: Vec::with_capacity(joints),
            swaps: vec![0; n],
        };
        let mut size = 0;
        for (j, spec) in m.joints.iter().enumerate() {
            let k = t.dof[j];
            // A kind without a linear rotation leaves zeros: then the tree
            // does not apply and is not used.
            if let Some(row) = spec.kind.joint().angle_row() {
                t.angle[spec.offset..spec.offset + k].copy_from_slice(row);
            }
            t.block.push(size);
            size += k * k;
        }
        t.pivots = vec![0.0; size];
        for j in 0..joints {
            // The nearest ancestor that turns what lies beyond it.
            let mut up = t.parent[j];
            while let Some(i) = up {
                let row = &t.angle[t.offset[i]..t.offset[i] + t.dof[i]];
                let best = (0..row.len()).max_by(|&a, &b| row[a].abs().total_cmp(&row[b].abs()));
                if let Some(a) = best.filter(|&a| row[a] != 0.0) {
                    t.anchor[j] = Some(t.offset[i] + a);
                    break;
                }
                up = t.parent[i];
            }
        }
        t
    }

    /// Factors the symmetric $H$ with entries `entry(r, c)` (read on the
    /// diagonal blocks and on one row above each joint), its angle rows
    /// scaled by `scale` (coordinates $\tilde q = q/s$: pass the scale of
    /// a matrix $SHS$, or an empty slice), for [`Tree::solve`]: `None` if
    /// a pivot is singular, else `Some(false)`. When `definite` is asked,
    /// only whether $H$ is positive definite (every pivot passes Cholesky):
    /// `Some(true)` or `Some(false)` (`None` if a coupling overflows), and
    /// the factors are not kept for solving. Then the pivots' Cholesky
    /// factors serve the couplings, and elimination stops at the first
    /// pivot that fails (Sylvester: $H$ is then not definite).
    pub fn factor(&mut self, entry: impl Fn(usize, usize) -> f64, scale: &[f64], definite: bool) -> Option<bool> {
        for (i, (d, a)) in self.d.iter_mut().zip(&self.angle).enumerate() {
            *d = a * scale.get(i).copied().unwrap_or(1.0);
        }
        self.beta.fill(0.0);
        for j in (0..self.offset.len()).rev() {
            let (o, k) = (self.offset[j], self.dof[j]);
            let b = self.beta[j];
            let p = &mut self.pivots[self.block[j]..self.block[j] + k * k];
            for c in 0..k {
                for r in 0..k {
                    p[c * k + r] = entry(o + r, o + c) - b * self.d[o + r] * self.d[o + c];
                }
            }
            if definite && !linalg::cholesky(p, k) {
                return Some(false);
            }
            // A joint at the root passes nothing up: a definiteness test needs no more of it.
            if definite && self.parent[j].is_none() {
                continue;
            }
            for r in 0..k {
                let g = match self.anchor[j] {
                    Some(a) => entry(a, o + r) / self.d[a],
                    None => 0.0,
                };
                self.h[o + r] = g - b * self.d[o + r];
            }
            self.w[o..o + k].copy_from_slice(&self.h[o..o + k]);
            if definite {
                linalg::cholesky_solve(p, k, &mut self.w[o..o + k]);
            } else {
                if !linalg::lu(p, k, &mut self.swaps[o..o + k]) {
                    return None;
                }
                linalg::lu_solve(p, k, &self.swaps[o..o + k], &mut self.w[o..o + k]);
            }
            let beta = b + (o..o + k).map(|i| self.h[i] * self.w[i]).sum::<f64>();
            if !beta.is_finite() {
                return None;
            }
            if let Some(up) = self.parent[j] {
                self.beta[up] += beta;
            }
            self.beta[j] = beta;
        }
        Some(definite)
    }

    /// Solves $H\delta = $ `x` in place with the last [`Tree::factor`]
    /// (in the coordinates it was given).
    pub fn solve(&mut self, x: &mut [f64]) {
        self.alpha.fill(0.0);
        for j in (0..self.offset.len()).rev() {
            let (o, k) = (self.offset[j], self.dof[j]);
            let a = self.alpha[j];
            let u = &mut x[o..o + k];
            for (u, d) in u.iter_mut().zip(&self.d[o..o + k]) {
                *u -= d * a;
            }
            linalg::lu_solve(&self.pivots[self.block[j]..self.block[j] + k * k], k, &self.swaps[o..o + k], u);
            let alpha = a + u.iter().zip(&self.h[o..o + k]).map(|(u, h)| u * h).sum::<f64>();
            if let Some(up) = self.parent[j] {
                self.alpha[up] += alpha;
            }
        }
        for j in 0..self.offset.len() {
            let (o, k) = (self.offset[j], self.dof[j]);
            let above = self.parent[j].map_or(0.0, |p| self.theta[p]);
            let mut turn = above;
            for i in o..o + k {
                x[i] -= self.w[i] * above;
                turn += self.d[i] * x[i];
            }
            self.theta[j] = turn;
        }
    }
}
