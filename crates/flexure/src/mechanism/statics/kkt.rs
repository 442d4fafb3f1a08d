//! The KKT conditions of a mechanism as a solver problem, and its stability tests.

use super::Settings;
#[cfg(doc)]
use super::Solution;
use super::dimension::{PlanarOwn, Statics, parts};
use super::workspace::{Buffers, Spare, Workspace};
use crate::error::{Error, Result};
use crate::linalg;
use crate::mechanism::indeterminate::{full_row_rank, settle};
use crate::mechanism::kinematics::frames_into;
use crate::mechanism::lagrangian::{assemble_into, closure_hessian};
use crate::mechanism::{Loads, Mechanism};
use crate::solver;
use crate::space::Planar;
use nalgebra::DMatrix;

/// The shift of the multiplier block of the Newton matrix (see the module docs).
pub(super) const MULTIPLIER_SHIFT: f64 = 1e-10;

/// The share of the joints' elastic stiffness a state must keep to count
/// as far from instability ([`solver::Problem::far_from_instability`]).
pub(crate) const FAR_MARGIN: f64 = 0.5;

/// The KKT conditions of a mechanism under the loads
/// $\text{from} + \lambda(\text{to} - \text{from})$, as a [`solver::Problem`].
///
/// Unknowns $x = (q, \nu)$ with the multipliers scaled to the joints,
/// $\mu_i = s_i\nu_i$ ($s_i = k/\ell$ for position rows, $k$ for angle
/// rows; $k$ the stiffest joint's diagonal stiffness in N·m/rad, a slider's
/// N/m times $\ell^2$; $\ell$ the mechanism's length). Residual: each
/// coordinate's row of $\nabla V + G^T\mu$ divided by that coordinate's
/// stiffness (radians, or metres, of the joint alone; a free joint's by
/// $k$), each closure row divided by $\ell$ (position) or 1 (angle):
/// dimensionless, unit "relative". Arc-length weights: 1 for angles,
/// $1/\ell$ for slider travel, 0 for multipliers.
#[derive(Debug, Clone)]
pub struct Kkt<'a, D: Statics = Planar> {
    pub(crate) mechanism: &'a Mechanism<D>,
    pub(crate) from: Loads<D>,
    pub(crate) to: Loads<D>,
    pub(crate) change: Loads<D>,
    /// $1/k_i$ per coordinate row.
    pub(crate) row_scale: Vec<f64>,
    /// $1/\ell$ or 1 per closure row.
    pub(crate) closure_scale: Vec<f64>,
    /// $s_i$ per closure row.
    pub(crate) multiplier_scale: Vec<f64>,
    pub(super) weight: Vec<f64>,
    /// $k_{\max}$: the stiffest joint's stiffness as a moment (N·m/rad; a
    /// slider's $k\ell^2$), or the loads' moment where no joint is stiff.
    pub(super) stiffest: f64,
    pub(super) length: f64,
    pub(super) scale: f64,
    /// The scale of the assembly alone (the loads at $\lambda = 0$ at both
    /// ends), to whose tolerance a dimension with [`Statics::OWN_ASSEMBLY`] assembles.
    pub(super) start_scale: f64,
    /// Smallest relative stiffness of a stable state.
    pub(crate) margin: f64,
    /// Whether the Hessian has the tree's form ([`crate::mechanism::tree`]): no
    /// closures, no tendons. Then Newton steps, tangents and stability
    /// tests factor in $O(n)$.
    pub(crate) tree: bool,
    pub(crate) work: Buffers<'a, D>,
}

impl<'a, D: Statics> Kkt<'a, D> {
    /// The problem of moving `m` from `from` to `to` (both validated), for
    /// a solver run with `settings` (whose tolerance sets the stability margin).
    pub fn new(m: &'a Mechanism<D>, from: &Loads<D>, to: &Loads<D>, settings: &Settings) -> Result<Self> {
        Self::with_workspace(m, from, to, settings, Workspace::new(m))
    }

    /// [`Kkt::new`] with the buffers `work` (made for `m` by [`Workspace::new`]).
    pub fn with_workspace(
        m: &'a Mechanism<D>,
        from: &Loads<D>,
        to: &Loads<D>,
        settings: &Settings,
        work: Workspace<D>,
    ) -> Result<Self> {
        if !work.fits(m) {
            return Err(Error::invalid("workspace", work.dof, "was made for another mechanism"));
        }
        Self::fitted(m, from, to, settings, Buffers::Owned(Box::new(work)))
    }

    /// [`Kkt::with_workspace`] with `work` known to fit `m`.
    pub(super) fn fitted(
        m: &'a Mechanism<D>,
        from: &Loads<D>,
        to: &Loads<D>,
        settings: &Settings,
        work: Buffers<'a, D>,
    ) -> Result<Self> {
        settings.validate()?;
        if !work.touching {
            crate::mechanism::contact::refuse_unsolved(m)?;
        }
        D::check_loads(m, from)?;
        D::check_loads(m, to)?;
        let n = m.dof();
        let length = m.size();
        // Diagonal stiffness of each coordinate (constant for every joint
        // kind, so any state's), and the factor to N·m/rad: 1 for angles,
        // ℓ² for slider travel; in the buffers of the last problem.
        let mut work = work;
        let Spare {
            vectors: [mut row_scale, mut weight, mut closure_scale, mut multiplier_scale],
            loads: [mut from_, mut to_, mut change],
        } = std::mem::take(&mut work.spare);
        let (stiffness, unit) = (&mut row_scale, &mut weight);
        stiffness.clear();
        stiffness.resize(n, 0.0);
        unit.clear();
        unit.resize(n, 1.0);
        for (j, s) in m.joints.iter().zip(&work.frames.joints) {
            let translation = j.kind.joint().is_translation();
            for i in 0..s.gradient.len() {
                stiffness[j.offset + i] = s.stiffness[(i, i)];
                if translation {
                    unit[j.offset + i] = length * length;
                }
            }
        }
        let moments = || stiffness.iter().zip(unit.iter()).map(|(k, u)| k * u);
        // Largest load, as a moment, in radians of the softest joint.
        let magnitude = |l: &Loads<D>| D::load_size(m, l, length);
        let k_max = moments().fold(0.0, f64::max);
        // Without a stiff joint (bodies on free sliders held by a geom, a
        // pendulum) the loads set the scale: with a stand-in of 1 N·m, a
        // 1 g ball's weight was 1e-6 of it, Newton stopped at its first
        // guess below 1e-6 of the load, and the path read a loss of stability there.
        let loads = magnitude(from) + magnitude(to);
        let k_max = match (k_max > 0.0, loads > 0.0 && loads.is_finite()) {
            (true, _) => k_max,
            (false, true) => loads,
            (false, false) => 1.0,
        };
        let k_min = moments().filter(|&k| k > 0.0).fold(k_max, f64::min);
        // A free coordinate is measured against the stiffest joint.
        for (k, u) in row_scale.iter_mut().zip(weight.iter_mut()) {
            *k = if *k > 0.0 { 1.0 / *k } else { *u / k_max };
            *u = 1.0 / u.sqrt();
        }
        // S = diag(√(1/k_i)) of the stability tests, once per problem.
        work.root_scale.clear();
        work.root_scale.extend(row_scale.iter().map(|r| r.sqrt()));
        closure_scale.clear();
        multiplier_scale.clear();
        for c in &m.closures {
            for row in 0..c.equations() {
                let position = row < D::POSITION_ROWS;
                closure_scale.push(if position { 1.0 / length } else { 1.0 });
                multiplier_scale.push(if position { k_max / length } else { k_max });
            }
        }
        let scale = 1.0 + loads / k_min;
        let start_scale = 1.0 + (magnitude(from) + magnitude(from)) / k_min;
        if !scale.is_finite() {
            return Err(Error::invalid(
                "loads",
                format!("{:.3e}", scale - 1.0),
                "are too large for the joints' stiffness to be represented",
            ));
        }
        D::copy_loads(from, &mut from_);
        D::copy_loads(to, &mut to_);
        D::difference_into(from, to, &mut change);
        Ok(Self {
            mechanism: m,
            from: from_,
            to: to_,
            change,
            row_scale,
            closure_scale,
            multiplier_scale,
            weight,
            stiffest: k_max,
            length,
            scale,
            start_scale,
            margin: settings.tolerance.sqrt(),
            tree: D::tree(m),
            work,
        })
    }

    /// The buffers, for the next problem on the same mechanism.
    pub fn into_workspace(self) -> Workspace<D> {
        match self.release() {
            Buffers::Owned(w) => *w,
            Buffers::Borrowed(w) => w.clone(),
        }
    }

    /// The buffers, with this problem's scales and loads put back for the next problem.
    pub(super) fn release(self) -> Buffers<'a, D> {
        let mut work = self.work;
        work.spare = Spare {
            vectors: [self.row_scale, self.weight, self.closure_scale, self.multiplier_scale],
            loads: [self.from, self.to, self.change],
        };
        work
    }

    /// The unknowns $(q, \nu)$ of coordinates `q` and multipliers `mu`.
    pub fn state(&self, q: &[f64], mu: &[f64]) -> Vec<f64> {
        q.iter().copied().chain(mu.iter().zip(&self.multiplier_scale).map(|(m, s)| m / s)).collect()
    }

    /// The multipliers $\mu$ (N, N·m) of the unknowns `x`.
    pub fn multipliers(&self, x: &[f64]) -> Vec<f64> {
        x[self.mechanism.dof()..].iter().zip(&self.multiplier_scale).map(|(v, s)| v * s).collect()
    }

    /// The loads at load factor `lambda`.
    pub fn loads(&self, lambda: f64) -> Loads<D> {
        let mut out = self.from.clone();
        D::lerp_into(&self.from, &self.to, lambda, &mut out);
        out
    }

    /// $\partial_\lambda r$ into `d`, at the frames last evaluated, or at
    /// the kept start's (`StartCache`) if `at_start`: the gradient of the
    /// load change's potential, scaled as the residual.
    pub(super) fn load_derivative(&mut self, d: &mut [f64], at_start: bool) -> Result<()> {
        let m = self.mechanism;
        let n = m.dof();
        let Workspace { frames, start, assembly: a, load_gradient, .. } = &mut *self.work;
        let f = match &start.frames {
            Some(kept) if at_start => kept,
            _ => frames,
        };
        load_gradient.as_mut_slice().fill(0.0);
        D::load_terms(m, f, &self.change, load_gradient, None, &mut a.points, &mut a.kept)?;
        for i in 0..n {
            d[i] = load_gradient[i] * self.row_scale[i];
        }
        d[n..].fill(0.0);
        Ok(())
    }
}

impl Kkt<'_, Planar> {
    /// [`Statics::settled`]: the frames and $G$ of the last evaluation if it
    /// was at `q`; `mu` itself where $G$'s rows are independent.
    pub(super) fn settled_planar(&mut self, q: &[f64], mu: Vec<f64>, loads: &Loads) -> Vec<f64> {
        let m = self.mechanism;
        let n = m.dof();
        let Workspace { frames: f, assembly: a, assembled_at, assembled, closure_t, gram, .. } = &mut *self.work;
        if !(*assembled && assembled_at[..] == *q) {
            *assembled = false;
            frames_into(m, q, f);
            a.closures_at(m, f);
        }
        // settle changes nothing where G has independent rows: it need not be called.
        let g = &a.closure_jacobian;
        let rows = g.nrows();
        for i in 0..rows {
            for c in 0..n {
                closure_t[i * n + c] = g[(i, c)];
            }
        }
        if linalg::columns_independent(closure_t, n, rows, gram) { mu } else { settle(m, f, g, &mu, loads) }
    }

    /// [`solver::Problem::stable`] with closures on dense matrices, the
    /// null space by singular values: the test where $G$'s rows are not
    /// independent by a wide margin (redundant closures), and the
    /// reference of [`Kkt::constrained_definite`].
    pub(super) fn stable_dense(&mut self, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        let g = DMatrix::from_fn(rows, n, |i, c| jacobian[c * size + n + i] / self.closure_scale[i]);
        let mut h = DMatrix::from_fn(n, n, |r, c| jacobian[c * size + r] / self.row_scale[r]);
        // settle changes nothing where G has full row rank: skip its frames.
        if rows > 0 && !full_row_rank(&g) {
            let mu = self.multipliers(x);
            let Workspace { frames: f, loads, assembled, .. } = &mut *self.work;
            *assembled = false;
            frames_into(m, &x[..n], f);
            self.from.lerp_into(&self.to, lambda, loads);
            let settled = settle(m, f, &g, &mu, loads);
            if settled != mu {
                let change: Vec<f64> = settled.iter().zip(&mu).map(|(a, b)| a - b).collect();
                h += closure_hessian(m, f, &change);
            }
        }
        // In joint-relative coordinates: H̃ = S H S, G̃ = G S, S = diag(1/√k_i).
        let s: Vec<f64> = self.row_scale.iter().map(|r| r.sqrt()).collect();
        let h = DMatrix::from_fn(n, n, |r, c| h[(r, c)] * s[r] * s[c]);
        let g = DMatrix::from_fn(rows, n, |i, c| g[(i, c)] * s[c]);
        let z = linalg::null_space(&g);
        let mut k = constrained(&h, &z);
        for i in 0..k.nrows() {
            k[(i, i)] -= self.margin;
        }
        linalg::is_positive_definite(&k)
    }

    /// Whether the rows of $G$ (read from `jacobian`) are independent by a
    /// wide margin ([`linalg::columns_independent`]), so that no multiplier
    /// is indeterminate; leaves $G^T$ ($n\times$ rows) in the workspace.
    pub(super) fn closure_rows_independent(&mut self, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if rows > n {
            return false;
        }
        let Workspace { closure_t: a, gram, .. } = &mut *self.work;
        for i in 0..rows {
            for c in 0..n {
                a[i * n + c] = jacobian[c * size + n + i] / self.closure_scale[i];
            }
        }
        linalg::columns_independent(a, n, rows, gram)
    }

    /// $\tilde Z^T\thinspace S(H - wK)S\thinspace\tilde Z - \text{margin}\thinspace I$ positive
    /// definite, on the workspace's buffers without allocating: $H$ the
    /// Hessian block of `jacobian`, $K$ the joints' elastic stiffness,
    /// $S = \operatorname{diag}(1/\sqrt{k_i})$ and $\tilde Z$ the null space of
    /// $\tilde G = GS$ by Householder reflections. For a $G$ whose rows
    /// [`Kkt::closure_rows_independent`] has just found independent (its
    /// $G^T$ is read from the workspace); `None` unless $\tilde G$'s rows are
    /// independent by a wide margin too ([`linalg::columns_independent`]):
    /// then no multiplier is indeterminate and this is the test of [`Kkt::stable_dense`].
    pub(super) fn constrained_definite(&mut self, jacobian: &[f64], w: f64, margin: f64) -> Option<bool> {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if rows > n {
            return None;
        }
        let p = n - rows;
        let Workspace {
            closure_t: a,
            reflections,
            basis,
            product,
            hessian,
            gram,
            root_scale: s,
            stiffness: k,
            scratch,
            frames,
            joint_of,
            ..
        } = &mut *self.work;
        // G̃ᵀ = S Gᵀ.
        for i in 0..rows {
            for c in 0..n {
                a[i * n + c] *= s[c];
            }
        }
        if !linalg::columns_independent(a, n, rows, gram) {
            return None;
        }
        linalg::null_space_of_transpose(a, n, rows, basis, reflections);
        let elastic = |r: usize, c: usize| {
            let j = joint_of[r];
            if w == 0.0 || joint_of[c] != j {
                return 0.0;
            }
            let o = m.joints[j].offset;
            w * frames.joints[j].stiffness[(r - o, c - o)]
        };
        // H̃ = S(H − wK)S, H̃ Z̃, then Z̃ᵀ H̃ Z̃ symmetrized.
        for c in 0..n {
            for r in 0..n {
                hessian[c * n + r] = (jacobian[c * size + r] / self.row_scale[r] - elastic(r, c)) * s[r] * s[c];
            }
        }
        for j in 0..p {
            let z = &basis[j * n..(j + 1) * n];
            let hz = &mut product[j * n..(j + 1) * n];
            hz.fill(0.0);
            for (c, zc) in z.iter().enumerate() {
                for (v, h) in hz.iter_mut().zip(&hessian[c * n..(c + 1) * n]) {
                    *v += h * zc;
                }
            }
        }
        let k = &mut k[..p * p];
        for j in 0..p {
            for i in 0..p {
                k[j * p + i] = (0..n).map(|r| basis[i * n + r] * product[j * n + r]).sum();
            }
        }
        for j in 0..p {
            for i in 0..j {
                let v = (k[j * p + i] + k[i * p + j]) * 0.5;
                k[j * p + i] = v;
                k[i * p + j] = v;
            }
            k[j * p + j] -= margin;
        }
        Some(linalg::positive_definite(k, p, &mut scratch[..p * p]))
    }

    /// A sufficient condition for the closure stability test, in $O(n)$ by
    /// the tree's pivots ([`crate::mechanism::tree`]): $\tilde H - (\text{margin} + \epsilon)I$
    /// positive definite on every motion, not only the admissible ones.
    /// The smallest eigenvalue of $\tilde Z^T\tilde H\tilde Z$ ($\tilde Z$
    /// orthonormal) is at least that of $\tilde H$ (a Rayleigh quotient over
    /// a subspace), and $\epsilon = 10^{-12}\sum_i(\tilde H_{ii} - \text{margin})^+$
    /// bounds the rounding threshold of [`linalg::positive_definite`] on the
    /// projected matrix ($10^{-12}$ of its largest diagonal entry, at most
    /// its trace), so `true` is the verdict of [`Kkt::constrained_definite`]
    /// too. Applies where the Hessian has the tree's form (the closures'
    /// terms are point terms; tendons couple branches) and the rows of
    /// $G$ are independent by a wide margin, so no multiplier is
    /// indeterminate and the Hessian at the solver's multipliers is the
    /// one stability is judged at (the caller's check,
    /// [`Kkt::closure_rows_independent`]); `false` leaves the decision to
    /// the projected test.
    pub(super) fn hessian_definite(&mut self, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if !m.tendons.is_empty() {
            return false;
        }
        let Workspace { own: PlanarOwn { tree, .. }, root_scale: s, .. } = &mut *self.work;
        let s: &[f64] = s;
        let scaled = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r] * s[r] * s[c];
        let trace: f64 = (0..n).map(|i| (scaled(i, i) - self.margin).max(0.0)).sum();
        if !(trace > 0.0 && trace.is_finite()) {
            return false;
        }
        let shift = self.margin + 1e-12 * trace;
        tree.factor(|r, c| scaled(r, c) - if r == c { shift } else { 0.0 }, s, true) == Some(true)
    }

    /// $Z^T\nabla^2 L\thinspace Z$ positive definite with the margin of the module
    /// docs: in coordinates $\tilde q_i = \sqrt{k_i}\thinspace q_i$ (each joint's own
    /// stiffness 1), $\tilde Z^T\tilde H\tilde Z - \sqrt{\text{tolerance}}\thinspace I$
    /// positive definite, $\tilde Z$ = [`linalg::null_space`]$(\tilde G)$.
    /// Where redundant closures leave part of $\mu$ indeterminate, that
    /// part is taken with the least transmitted force first (see [`Solution::multipliers`]).
    /// A whole Hessian that passes the test passes it on every subspace:
    /// that is tried first, by the tree's pivots in $O(n)$.
    pub(super) fn stable_planar(&mut self, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        if rows == 0 && self.tree {
            // Z = I, and the tree's pivots: positive_definite's test of the
            // matrix below, in O(n).
            let Workspace { own: PlanarOwn { tree, .. }, root_scale: s, .. } = &mut *self.work;
            let s: &[f64] = s;
            let scaled = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r] * s[r] * s[c];
            let scale = (0..n).map(|i| scaled(i, i) - self.margin).fold(0.0_f64, f64::max);
            if n == 0 {
                return true;
            }
            if !(scale > 0.0 && scale.is_finite()) {
                return false;
            }
            let shift = self.margin + 1e-12 * scale;
            return tree.factor(|r, c| scaled(r, c) - if r == c { shift } else { 0.0 }, s, true) == Some(true);
        }
        if rows == 0 {
            // Z = I: the scaled, symmetrized Hessian itself, in the workspace.
            let Workspace { stiffness: k, scratch, root_scale: s, .. } = &mut *self.work;
            let scaled = |r: usize, c: usize| jacobian[c * size + r] / self.row_scale[r] * s[r] * s[c];
            for c in 0..n {
                for r in 0..n {
                    k[c * n + r] = (scaled(r, c) + scaled(c, r)) * 0.5;
                }
                k[c * n + c] -= self.margin;
            }
            return linalg::positive_definite(k, n, scratch);
        }
        if !self.closure_rows_independent(jacobian) {
            return self.stable_dense(x, lambda, jacobian);
        }
        if self.hessian_definite(jacobian) {
            return true;
        }
        if let Some(definite) = self.constrained_definite(jacobian, 0.0, self.margin) {
            return definite;
        }
        self.stable_dense(x, lambda, jacobian)
    }

    /// Without closures: $\nabla^2 V - \tfrac12 K$ positive definite, $K$
    /// the joints' elastic stiffness (as a single flexure's
    /// [`crate::statics`] does), by the tree's pivots or by Cholesky.
    pub(super) fn far_planar(&mut self, jacobian: &[f64]) -> bool {
        let m = self.mechanism;
        let n = m.dof();
        if m.constraints() > 0 || n == 0 {
            return false;
        }
        let Workspace { own: PlanarOwn { tree, .. }, frames, stiffness, joint_of, .. } = &mut *self.work;
        let elastic = |r: usize, c: usize| {
            let j = joint_of[r];
            if joint_of[c] != j {
                return 0.0;
            }
            let o = m.joints[j].offset;
            frames.joints[j].stiffness[(r - o, c - o)]
        };
        let entry = |r: usize, c: usize| jacobian[c * n + r] / self.row_scale[r] - FAR_MARGIN * elastic(r, c);
        if self.tree {
            return tree.factor(entry, &[], true) == Some(true);
        }
        for c in 0..n {
            for r in 0..n {
                stiffness[c * n + r] = entry(r, c);
            }
        }
        linalg::cholesky(stiffness, n)
    }
}

impl<D: Statics> solver::Problem<f64> for Kkt<'_, D> {
    fn dim(&self) -> usize {
        self.mechanism.dof() + self.mechanism.constraints()
    }

    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let m = self.mechanism;
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        let q = &x[..n];
        let Workspace { frames: f, assembly: a, mu, loads, assembled_at, assembled, .. } = &mut *self.work;
        for ((m, v), s) in mu.iter_mut().zip(&x[n..]).zip(&self.multiplier_scale) {
            *m = v * s;
        }
        *assembled = false;
        D::newton_frames(m, q, f);
        D::lerp_into(&self.from, &self.to, lambda, loads);
        assemble_into(m, f, mu, loads, jacobian.is_some(), a)?;
        assembled_at.copy_from_slice(q);
        *assembled = true;
        let a = parts(a);
        // Column-major: G's column i holds coordinate i's closure rows.
        let g = a.closure_jacobian.as_slice();
        for i in 0..n {
            let mut force = a.gradient[i];
            for (gk, mu) in g[i * rows..(i + 1) * rows].iter().zip(mu.iter()) {
                force += gk * mu;
            }
            residual[i] = force * self.row_scale[i];
        }
        for i in 0..rows {
            residual[n + i] = a.closure[i] * self.closure_scale[i];
        }
        if !residual.iter().all(|r| r.is_finite()) {
            return Err(Error::Singular { what: "mechanism equilibrium: a non-finite generalized force".into() });
        }
        // (Column chunks of size 0 would panic; a mechanism without coordinates has no Jacobian.)
        if let Some(jac) = jacobian.filter(|_| size > 0) {
            let hessian = a.hessian.as_slice();
            let (left, right) = jac.split_at_mut(n * size);
            for (c, column) in left.chunks_exact_mut(size).enumerate() {
                let (top, bottom) = column.split_at_mut(n);
                for ((j, h), s) in top.iter_mut().zip(&hessian[c * n..(c + 1) * n]).zip(&self.row_scale) {
                    *j = h * s;
                }
                for ((j, g), s) in bottom.iter_mut().zip(&g[c * rows..(c + 1) * rows]).zip(&self.closure_scale) {
                    *j = g * s;
                }
            }
            for (i, column) in right.chunks_exact_mut(size).enumerate() {
                let (top, bottom) = column.split_at_mut(n);
                let s = self.multiplier_scale[i];
                for (c, (j, r)) in top.iter_mut().zip(&self.row_scale).enumerate() {
                    *j = g[c * rows + i] * s * r;
                }
                bottom.fill(0.0);
                bottom[i] = -MULTIPLIER_SHIFT;
            }
        }
        if let Some(d) = dlambda {
            self.load_derivative(d, false)?;
        }
        Ok(())
    }

    /// $Z^T\nabla^2 L\thinspace Z$ positive definite with the margin of the
    /// module docs ([`Statics::stable`]).
    fn stable(&mut self, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        D::stable(self, x, lambda, jacobian)
    }

    /// Without closures: $\nabla^2 V - \tfrac12 K$ positive definite, $K$
    /// the joints' elastic stiffness (as a single flexure's [`crate::statics`] does).
    fn far_from_instability(&mut self, _x: &[f64], _lambda: f64, jacobian: &[f64]) -> bool {
        D::far_from_instability(self, jacobian)
    }

    fn factor(&mut self, jacobian: &[f64]) -> bool {
        D::factor(self, jacobian)
    }

    fn solve_factored(&mut self, b: &mut [f64]) {
        D::solve_factored(self, b)
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        D::distance(self, a, b)
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "relative"
    }

    fn name(&self) -> &'static str {
        "mechanism equilibrium"
    }

    fn weight(&self, i: usize) -> f64 {
        self.weight.get(i).copied().unwrap_or(0.0)
    }
}

/// $Z^T H Z$, symmetrized.
pub(in crate::mechanism) fn constrained(h: &DMatrix<f64>, z: &DMatrix<f64>) -> DMatrix<f64> {
    let k = z.transpose() * h * z;
    (&k + k.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::Problem;

    /// Seeded uniform numbers in [−1, 1) (xorshift64*).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    fn example(name: &str, push: [f64; 2]) -> Mechanism {
        let path = format!("{}/../../examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(path).unwrap();
        let text = text.replace("force = [0.0, -1.0]", &format!("force = [{:?}, {:?}]", push[0], push[1]));
        crate::mechanism::file::from_toml(&text).unwrap()
    }

    /// The closure stability test on the workspace's buffers (Householder
    /// null space) against the dense one (singular values), on seeded
    /// random states (coordinates, multipliers, load factor) of the
    /// parallelogram pushed to twice its 16 N buckling load, of the
    /// four-bar linkage and of the parallelogram under its 1 N push (with
    /// smaller multipliers, near its equilibria): the same verdict wherever the smallest eigenvalue
    /// of the dense $Z^T\tilde HZ$ − margin is not within 1e-9 of the
    /// largest diagonal entry of zero (where rounding may decide either way),
    /// from the projected test and from `stable` (which tries the whole
    /// Hessian first); the whole-Hessian test alone, a sufficient one,
    /// never says stable where the dense test does not.
    #[test]
    fn closure_stability_matches_the_dense_test() {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        let settings = Settings::default();
        // (mechanism, spread of the coordinates, spread of the multipliers in N).
        let cases = [
            (example("parallelogram", [0.3, -32.0]), 0.05, 2.0),
            (example("four_bar", [0.0, -1.0]), 0.3, 2.0),
            (example("parallelogram", [0.5, -1.0]), 0.05, 0.5),
        ];
        let (mut compared, mut stable, mut unstable, mut sufficient) = (0, 0, 0, 0);
        for (m, spread, forces) in &cases {
            let (n, rows) = (m.dof(), m.constraints());
            let zero = m.loads().zero_like();
            let mut kkt = Kkt::new(m, &zero, &m.loads(), &settings).unwrap();
            let size = n + rows;
            let (mut r, mut jac) = (vec![0.0; size], vec![0.0; size * size]);
            for _ in 0..400 {
                let q: Vec<f64> = m.rest().iter().map(|q| q + spread * rng.next()).collect();
                let mu: Vec<f64> = (0..rows).map(|_| forces * rng.next()).collect();
                let lambda = 0.5 * (1.0 + rng.next());
                let x = kkt.state(&q, &mu);
                kkt.evaluate(&x, lambda, &mut r, Some(&mut jac), None).unwrap();
                assert!(kkt.closure_rows_independent(&jac), "independent closure rows");
                let fast = kkt.constrained_definite(&jac, 0.0, kkt.margin).expect("independent scaled closure rows");
                let everywhere = kkt.hessian_definite(&jac);
                let verdict = kkt.stable(&x, lambda, &jac);
                let dense = kkt.stable_dense(&x, lambda, &jac);
                // The dense matrix's distance from the verdict's boundary.
                let g = DMatrix::from_fn(rows, n, |i, c| jac[c * size + n + i] / kkt.closure_scale[i]);
                let s: Vec<f64> = kkt.row_scale.iter().map(|r| r.sqrt()).collect();
                let h = DMatrix::from_fn(n, n, |r, c| jac[c * size + r] / kkt.row_scale[r] * s[r] * s[c]);
                let z = linalg::null_space(&DMatrix::from_fn(rows, n, |i, c| g[(i, c)] * s[c]));
                let k = constrained(&h, &z);
                let (softest, _) = linalg::softest_mode(&k).unwrap();
                let size_k = (0..k.nrows()).map(|i| k[(i, i)].abs()).fold(0.0, f64::max);
                if (softest - kkt.margin).abs() > 1e-9 * size_k {
                    assert_eq!(fast, dense, "q = {q:?}, mu = {mu:?}, lambda = {lambda}: softest {softest}");
                    assert_eq!(verdict, dense, "q = {q:?}, mu = {mu:?}, lambda = {lambda}: softest {softest}");
                    // The sufficient test never calls an unstable state stable.
                    assert!(!everywhere || dense, "q = {q:?}, mu = {mu:?}, lambda = {lambda}: softest {softest}");
                    sufficient += usize::from(everywhere);
                    compared += 1;
                    if dense { stable += 1 } else { unstable += 1 }
                }
            }
        }
        assert!(
            compared > 1000 && stable > 100 && unstable > 100 && sufficient > 100 && sufficient < stable,
            "{compared} compared: {stable} stable ({sufficient} by the whole Hessian), {unstable} not"
        );
    }
}
