//! The generalized mass matrix $M(\alpha)$ of a flexure and its tip body,
//! and the velocity-product terms $h(\alpha, \dot\alpha)$, by nested
//! Gauss–Legendre quadrature.
//!
//! A point of the backbone is $r(s) = \int_0^s(\cos\phi, \sin\phi)\thinspace ds^{\prime}$
//! with $\phi(s) = \sum_i\alpha_i\psi_i(s/L)$, so its velocity is $\dot r(s) = J_r(s)\dot\alpha$ with
//!
//! $$J_r(s) = \frac{\partial r}{\partial\alpha} = \int_0^s\begin{pmatrix}-\sin\phi\cr\cos\phi\end{pmatrix}\psi^T ds^{\prime},$$
//!
//! and its velocity-product acceleration is
//! $\dot J_r\dot\alpha = \dot\alpha^T\nabla\nabla r\thinspace\dot\alpha = -\int_0^s\dot\phi^2\begin{pmatrix}\cos\phi\cr\sin\phi\end{pmatrix}ds^{\prime}$,
//! $\dot\phi = \psi^T\dot\alpha$. The kinetic energy $T = \frac12\dot\alpha^TM\dot\alpha$ gives
//!
//! $$M = \int_0^L \mu J_r^TJ_r\thinspace ds + \int_0^L\rho I\thinspace\psi\psi^T ds +
//! m J_c^TJ_c + I_c\thinspace\psi(L)\psi(L)^T,$$
//!
//! $$h = \dot M\dot\alpha - \tfrac12\nabla_\alpha(\dot\alpha^TM\dot\alpha) =
//! \int_0^L\mu J_r^T(\dot J_r\dot\alpha)\thinspace ds + m J_c^T(\dot J_c\dot\alpha),$$
//!
//! where the body's centre of mass is $r_c = r(L) + R(\phi_{tip})c$, so
//! $J_c = J_r(L) + ER(\phi_{tip})c\thinspace\psi(L)^T$ ($E$ the quarter turn) and
//! $\dot J_c\dot\alpha = \dot J_r(L)\dot\alpha - \dot\phi_{tip}^2R(\phi_{tip})c$.
//! The rotary terms do not depend on $\alpha$ and add nothing to $h$.
//!
//! The outer integral over $s$ takes a Gauss–Legendre rule on each smooth
//! piece of the section; the inner integrals for $J_r$ and $\dot J_r\dot\alpha$ run
//! from node to node (panels between consecutive outer nodes, each with its
//! own Gauss rule), accumulating, so every position is integrated to the
//! same accuracy as the tip. The discrete $h$ is the exact derivative of the
//! discrete $M$ (the same nodes), not an approximation of it.

use crate::error::{Error, Result};
use crate::flexure::{Basis, Flexure};
use crate::inertia::RigidInertia;
use crate::quadrature::GaussLegendre;
use crate::scalar::Scalar;
use nalgebra::{DMatrix, DVector};

/// The most sub-pieces each smooth piece of a non-polynomial section (a
/// notch) is cut into while the mass integrals are refined.
const MAX_SUBDIVISIONS: usize = 64;

/// Relative accuracy the mass moments of a non-polynomial section must
/// reach against an adaptive integral before the tables are accepted.
const MOMENT_ACCURACY: f64 = 1e-11;

/// The tabulated inertia of one flexure and its tip body (the Model):
/// immutable, built once, shared by every evaluation ([`update`]).
///
/// # Example
/// ```
/// use flexure::mass::{update, MassData, MassModel};
/// use flexure::section::{Profile, Section};
/// let s = Section::given(Profile::Constant(1.0)).unwrap().with_mass_per_length(Profile::Constant(2.0)).unwrap();
/// let f = flexure::Flexure::new(1.0, 1.0, 1).unwrap().with_section(s).unwrap();
/// let model = MassModel::new(&f, None).unwrap();
/// let mut data = MassData::new(&model);
/// update(&model, &[0.0], None, &mut data);
/// // A straight uniform beam in constant-curvature motion: y = α s²/2L, so M = μL³/20.
/// assert!((data.mass_matrix[(0, 0)] - 2.0 / 20.0).abs() < 1e-14);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct MassModel {
    order: usize,
    /// $\psi_i$ at the inner nodes, `[j * n + i]`.
    inner_psi: Vec<f64>,
    /// $L\thinspace\Delta\tau_j$: the inner weights, scaled to the panel and the length.
    inner_weight: Vec<f64>,
    /// $L\thinspace\Delta_k\mu(t_k)$ of the outer node that ends each panel
    /// (zero for a panel that ends at a break or at the tip).
    panel_mass: Vec<f64>,
    /// Inner nodes per panel.
    per_panel: usize,
    /// The part of $M$ that does not depend on $\alpha$: rotary inertia of
    /// the sections and of the body (row-major, symmetric).
    constant: Vec<f64>,
    tip_row: Vec<f64>,
    body: Option<RigidInertia>,
    distributed: bool,
    outer_points: usize,
    inner_points: usize,
    subdivisions: usize,
}

impl MassModel {
    /// The default outer rule per smooth piece: $N + 6$ points for the
    /// Legendre basis (the straight beam's $\mu\thinspace J_r^TJ_r$ is a
    /// polynomial of degree $2N + 2$, exact from $N + 2$; the rest absorbs
    /// the bending), 8 per segment of a constant-curvature chain. With the
    /// inner rule below, M and h meet a rule twelve times finer to 1.2e-12
    /// of their largest entry at N = 3, 6 and 10, tapered or not, at tip
    /// angles to 3 rad with S-bends (N + 4 and ⌈N/2⌉ + 3 reach only 2.3e-9):
    /// four orders inside the 1e-8 asked.
    pub fn default_outer_points(flexure: &Flexure) -> usize {
        match flexure.basis() {
            Basis::Legendre => flexure.order() + 6,
            Basis::Segments => 8,
        }
    }

    /// The default inner rule per panel: $\lceil N/2\rceil + 3$ points for
    /// the Legendre basis (exact for the straight beam's $\psi_i$, of degree
    /// $N$, from $\lceil (N+1)/2\rceil$), 4 for a chain of segments.
    pub fn default_inner_points(flexure: &Flexure) -> usize {
        match flexure.basis() {
            Basis::Legendre => flexure.order().div_ceil(2) + 3,
            Basis::Segments => 4,
        }
    }

    /// The model of `flexure` (its section's mass per length and rotary
    /// inertia, none without a density or mass per length) with an optional
    /// tip `body`, with the default rules. Fails on an invalid body.
    pub fn new(flexure: &Flexure, body: Option<&RigidInertia>) -> Result<Self> {
        Self::with_points(flexure, body, Self::default_outer_points(flexure), Self::default_inner_points(flexure))
    }

    /// As [`MassModel::new`] with `outer` points per smooth piece and
    /// `inner` points per panel (each from 1 to
    /// [`crate::quadrature::MAX_POINTS`]). For a section that is not a
    /// polynomial between its breakpoints (a notch), each piece is cut in
    /// 2, 4, … up to 64 sub-pieces until the mass moments
    /// $\int\mu\thinspace t^e dt$, $e \le 2N + 2$, agree with an adaptive
    /// integral to $10^{-11}$; beyond that it fails, saying what was reached.
    pub fn with_points(flexure: &Flexure, body: Option<&RigidInertia>, outer: usize, inner: usize) -> Result<Self> {
        if let Some(b) = body {
            b.validate()?;
        }
        let outer_rule = GaussLegendre::new(outer)?;
        let inner_rule = GaussLegendre::new(inner)?;
        let mut breaks = flexure.section().breakpoints(flexure.length());
        if flexure.basis() == Basis::Segments {
            let n = flexure.order();
            breaks.extend((1..n).map(|j| j as f64 / n as f64));
            breaks.sort_by(f64::total_cmp);
            breaks.dedup();
        }
        if flexure.section().polynomial() {
            return Ok(build(flexure, body, &outer_rule, &inner_rule, &breaks, 1));
        }
        let exact = moments_adaptive(flexure, &breaks)?;
        let mut error = f64::INFINITY;
        let mut sub = 1;
        while sub <= MAX_SUBDIVISIONS {
            let model = build(flexure, body, &outer_rule, &inner_rule, &breaks, sub);
            error = moments_error(flexure, &outer_rule, &breaks, sub, &exact);
            if error <= MOMENT_ACCURACY {
                return Ok(model);
            }
            sub *= 2;
        }
        Err(Error::Singular {
            what: format!(
                "the mass integrals along the flexure reached a relative error of {error:.3e}, not {MOMENT_ACCURACY:e}, with {MAX_SUBDIVISIONS} sub-pieces of {outer} points per smooth piece; try more points"
            ),
        })
    }

    /// Order $N$ of the coordinates.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The tip body, if any.
    pub fn body(&self) -> Option<&RigidInertia> {
        self.body.as_ref()
    }

    /// Whether the flexure itself has mass (a density or mass per length).
    pub fn distributed(&self) -> bool {
        self.distributed
    }

    /// Whether anything has inertia: the flexure or the body.
    pub fn has_inertia(&self) -> bool {
        self.distributed || self.body.is_some_and(|b| b.has_inertia())
    }

    /// Outer points per smooth piece, inner points per panel, and the
    /// sub-pieces each smooth piece was cut into.
    pub fn rule(&self) -> (usize, usize, usize) {
        (self.outer_points, self.inner_points, self.subdivisions)
    }
}

impl MassModel {
    /// Each panel's $\psi$ at its inner nodes (`[node * n + i]`), their
    /// weights, and the mass weight of the outer node that ends it.
    fn panels(&self) -> impl Iterator<Item = (&[f64], &[f64], f64)> {
        let (n, q) = (self.order, self.per_panel);
        self.inner_psi
            .chunks_exact(q * n)
            .zip(self.inner_weight.chunks_exact(q))
            .zip(&self.panel_mass)
            .map(|((psis, weights), &mass)| (psis, weights, mass))
    }
}

/// $\phi = \psi\cdot\alpha$ at one node.
fn angle<T: Scalar>(psi: &[f64], alpha: &[T]) -> T {
    let mut phi = T::zero();
    for (&p, &a) in psi.iter().zip(alpha) {
        phi += T::c(p) * a;
    }
    phi
}

/// The pieces $[a, b]$ of $[0, 1]$ between `breaks`, each cut into `sub`.
fn pieces(breaks: &[f64], sub: usize) -> impl Iterator<Item = (f64, f64)> + '_ {
    let ends: Vec<f64> = std::iter::once(0.0).chain(breaks.iter().copied()).chain(std::iter::once(1.0)).collect();
    (0..ends.len() - 1).flat_map(move |p| {
        let (a, b) = (ends[p], ends[p + 1]);
        (0..sub).map(move |q| (a + (b - a) * q as f64 / sub as f64, a + (b - a) * (q + 1) as f64 / sub as f64))
    })
}

fn build(
    flexure: &Flexure,
    body: Option<&RigidInertia>,
    outer: &GaussLegendre,
    inner: &GaussLegendre,
    breaks: &[f64],
    sub: usize,
) -> MassModel {
    let (n, l) = (flexure.order(), flexure.length());
    let section = flexure.section();
    let distributed = section.mass_per_length(0.5, l).is_some();
    // Points along the flexure: each outer node with its mass weight, and
    // each piece's end with none.
    let mut points: Vec<(f64, f64)> = Vec::new();
    let mut constant = vec![0.0; n * n];
    let mut psi = vec![0.0; n];
    for (a, b) in pieces(breaks, sub) {
        for (&x, &w) in outer.nodes().iter().zip(outer.weights()) {
            let t = a + (b - a) * x;
            let weight = l * (b - a) * w;
            points.push((t, section.mass_per_length(t, l).map_or(0.0, |mu| weight * mu)));
            let rho_i = section.rotary_inertia_per_length(t, l).unwrap_or(0.0);
            if rho_i > 0.0 {
                flexure.angle_shapes(t, &mut psi);
                for i in 0..n {
                    for j in 0..n {
                        constant[i * n + j] += weight * rho_i * psi[i] * psi[j];
                    }
                }
            }
        }
        points.push((b, 0.0));
    }
    let tip_row = flexure.tip_angle_row().to_vec();
    if let Some(b) = body {
        for i in 0..n {
            for j in 0..n {
                constant[i * n + j] += b.inertia * tip_row[i] * tip_row[j];
            }
        }
    }
    let per_panel = inner.len();
    let mut inner_psi = Vec::with_capacity(points.len() * per_panel * n);
    let mut inner_weight = Vec::with_capacity(points.len() * per_panel);
    let mut panel_mass = Vec::with_capacity(points.len());
    let mut start = 0.0;
    for &(end, mass) in &points {
        for (&x, &w) in inner.nodes().iter().zip(inner.weights()) {
            flexure.angle_shapes(start + (end - start) * x, &mut psi);
            inner_psi.extend_from_slice(&psi);
            inner_weight.push(l * (end - start) * w);
        }
        panel_mass.push(mass);
        start = end;
    }
    MassModel {
        order: n,
        inner_psi,
        inner_weight,
        panel_mass,
        per_panel,
        constant,
        tip_row,
        body: body.copied(),
        distributed,
        outer_points: outer.len(),
        inner_points: inner.len(),
        subdivisions: sub,
    }
}

/// Number of mass moments checked: $\int\mu\thinspace t^e$, $\int\rho I\thinspace t^e$ for $e \le 2N + 2$.
fn moment_count(flexure: &Flexure) -> usize {
    2 * flexure.order() + 3
}

fn moments_adaptive(flexure: &Flexure, breaks: &[f64]) -> Result<Vec<f64>> {
    let (l, e) = (flexure.length(), moment_count(flexure));
    let section = flexure.section();
    crate::quadrature::integrate(breaks, 16, false, 1e-14, 2 * e, |t, out| {
        let mu = section.mass_per_length(t, l).unwrap_or(0.0);
        let rho_i = section.rotary_inertia_per_length(t, l).unwrap_or(0.0);
        let mut p = 1.0;
        for k in 0..e {
            out[k] = mu * p;
            out[e + k] = rho_i * p;
            p *= t;
        }
    })
}

fn moments_error(flexure: &Flexure, outer: &GaussLegendre, breaks: &[f64], sub: usize, exact: &[f64]) -> f64 {
    let (l, e) = (flexure.length(), moment_count(flexure));
    let section = flexure.section();
    let mut sum = vec![0.0; 2 * e];
    for (a, b) in pieces(breaks, sub) {
        for (&x, &w) in outer.nodes().iter().zip(outer.weights()) {
            let t = a + (b - a) * x;
            let mu = section.mass_per_length(t, l).unwrap_or(0.0);
            let rho_i = section.rotary_inertia_per_length(t, l).unwrap_or(0.0);
            let mut p = (b - a) * w;
            for k in 0..e {
                sum[k] += mu * p;
                sum[e + k] += rho_i * p;
                p *= t;
            }
        }
    }
    sum.iter()
        .zip(exact)
        .fold(0.0_f64, |m, (s, x)| if *x == 0.0 { m.max(s.abs()) } else { m.max((s - x).abs() / x.abs()) })
}

/// Results of [`update`] for one [`MassModel`], reused across evaluations (the Data).
#[derive(Debug, Clone)]
pub struct MassData<T: Scalar = f64> {
    /// $M(\alpha)$ ($N\times N$, kg·m² per rad², symmetric, positive semi-definite).
    pub mass_matrix: DMatrix<T>,
    /// $h(\alpha, \dot\alpha) = \dot M\dot\alpha - \frac12\nabla(\dot\alpha^TM\dot\alpha)$ (N·m);
    /// zero unless [`update`] was given $\dot\alpha$.
    pub velocity_product: DVector<T>,
    /// $J_r$ at the current point, one $(x, y)$ pair per coordinate.
    jacobian: Vec<[T; 2]>,
}

impl<T: Scalar> MassData<T> {
    /// Buffers sized for `model`.
    pub fn new(model: &MassModel) -> Self {
        let n = model.order;
        Self {
            mass_matrix: DMatrix::zeros(n, n),
            velocity_product: DVector::zeros(n),
            jacobian: vec![[T::zero(); 2]; n],
        }
    }

    /// The kinetic energy $T = \frac12\dot\alpha^TM\dot\alpha$ (J) of the last [`update`]'s $M$.
    ///
    /// # Panics
    /// If `alpha_dot` does not have one entry per coordinate.
    pub fn kinetic_energy(&self, alpha_dot: &[T]) -> T {
        let n = self.mass_matrix.nrows();
        assert!(alpha_dot.len() == n, "alpha_dot must have {n} entries, got {}", alpha_dot.len());
        let mut t = T::zero();
        for i in 0..n {
            for j in 0..n {
                t += alpha_dot[i] * self.mass_matrix[(i, j)] * alpha_dot[j];
            }
        }
        t * T::c(0.5)
    }
}

/// Fills `data` with $M(\alpha)$ and, given `alpha_dot`, with $h(\alpha,\dot\alpha)$
/// (module docs), in one pass over the nested quadrature nodes: at each inner node
/// $\tau_j$ of a panel,
///
/// $$J_r \mathrel{+}= L\Delta\tau_j\begin{pmatrix}-\sin\phi_j\cr\cos\phi_j\end{pmatrix}\psi(\tau_j)^T,\quad
/// a \mathrel{-}= L\Delta\tau_j\thinspace\dot\phi_j^2\begin{pmatrix}\cos\phi_j\cr\sin\phi_j\end{pmatrix},$$
///
/// and at the outer node $t_k$ that ends the panel
/// $M \mathrel{+}= L\Delta_k\mu(t_k)J_r^TJ_r$, $h \mathrel{+}= L\Delta_k\mu(t_k)J_r^Ta$.
/// Generic over [`Scalar`], so dual numbers differentiate it. Does not allocate.
///
/// # Panics
/// If `alpha` (or `alpha_dot`) does not have [`MassModel::order`] entries, or
/// `data` was made for another order. Validate user input first with
/// [`Flexure::check_coordinates`].
///
/// # Example
/// ```
/// use flexure::inertia::RigidInertia;
/// use flexure::mass::{update, MassData, MassModel};
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// // A massless flexure with a point mass of 2 kg at the tip.
/// let body = RigidInertia::new(2.0, 0.0, [0.0, 0.0]).unwrap();
/// let model = MassModel::new(&f, Some(&body)).unwrap();
/// let mut data = MassData::new(&model);
/// update(&model, &[0.0; 3], Some(&[1.0, 0.0, 0.0]), &mut data);
/// // Straight: the tip moves sideways by ∂y/∂α₁ = L/2 per radian.
/// assert!((data.mass_matrix[(0, 0)] - 2.0 * 0.25).abs() < 1e-14);
/// // Bending at 1 rad/s: the velocity-product acceleration −L∫t²dt·(1, 0) lies along
/// // the straight beam, normal to the tip's sideways motion, so h₁ = 0.
/// assert!(data.velocity_product[0].abs() < 1e-14);
/// ```
pub fn update<T: Scalar>(model: &MassModel, alpha: &[T], alpha_dot: Option<&[T]>, data: &mut MassData<T>) {
    let n = model.order;
    assert!(alpha.len() == n, "alpha must have {n} entries (one per coordinate), got {}", alpha.len());
    if let Some(v) = alpha_dot {
        assert!(v.len() == n, "alpha_dot must have {n} entries (one per coordinate), got {}", v.len());
    }
    assert!(data.jacobian.len() == n, "MassData was made for a model of another order");
    let m = data.mass_matrix.as_mut_slice();
    for (o, &c) in m.iter_mut().zip(&model.constant) {
        *o = T::c(c);
    }
    let h = data.velocity_product.as_mut_slice();
    h.fill(T::zero());
    let jac = &mut data.jacobian;
    jac.fill([T::zero(); 2]);
    let mut acc = [T::zero(); 2];
    for (psis, weights, mass) in model.panels() {
        for (psi, &w) in psis.chunks_exact(n).zip(weights) {
            let (s, c) = angle(psi, alpha).sin_cos();
            let w = T::c(w);
            for (j, &p) in jac.iter_mut().zip(psi) {
                let wp = w * T::c(p);
                j[0] -= wp * s;
                j[1] += wp * c;
            }
            if let Some(v) = alpha_dot {
                let mut rate = T::zero();
                for (&p, &a) in psi.iter().zip(v) {
                    rate += T::c(p) * a;
                }
                let ww = w * rate * rate;
                acc[0] -= ww * c;
                acc[1] -= ww * s;
            }
        }
        if mass != 0.0 {
            let mass = T::c(mass);
            for i in 0..n {
                let ji = jac[i];
                for j in i..n {
                    m[j * n + i] += mass * (ji[0] * jac[j][0] + ji[1] * jac[j][1]);
                }
                if alpha_dot.is_some() {
                    h[i] += mass * (ji[0] * acc[0] + ji[1] * acc[1]);
                }
            }
        }
    }
    if let Some(b) = &model.body {
        let mut phi_tip = T::zero();
        let mut rate_tip = T::zero();
        for (i, &d) in model.tip_row.iter().enumerate() {
            phi_tip += T::c(d) * alpha[i];
            if let Some(v) = alpha_dot {
                rate_tip += T::c(d) * v[i];
            }
        }
        let (s, c) = phi_tip.sin_cos();
        // R(φ)c and its quarter turn E R(φ)c.
        let rc = [c * T::c(b.com[0]) - s * T::c(b.com[1]), s * T::c(b.com[0]) + c * T::c(b.com[1])];
        let erc = [-rc[1], rc[0]];
        for (j, &d) in jac.iter_mut().zip(&model.tip_row) {
            j[0] += erc[0] * T::c(d);
            j[1] += erc[1] * T::c(d);
        }
        let acc_c = [acc[0] - rate_tip * rate_tip * rc[0], acc[1] - rate_tip * rate_tip * rc[1]];
        let mass = T::c(b.mass);
        for i in 0..n {
            let ji = jac[i];
            for j in i..n {
                m[j * n + i] += mass * (ji[0] * jac[j][0] + ji[1] * jac[j][1]);
            }
            if alpha_dot.is_some() {
                h[i] += mass * (ji[0] * acc_c[0] + ji[1] * acc_c[1]);
            }
        }
    }
    // Only the upper triangle was accumulated (column-major: m[j n + i], i ≤ j).
    for j in 0..n {
        for i in j + 1..n {
            m[j * n + i] = m[i * n + j];
        }
    }
}

/// The first moment of a flexure's distributed mass about its root, in the
/// root frame, and its derivatives in $\alpha$: what its weight contributes
/// to a potential, $V_g = -g\cdot(m\thinspace o + R\thinspace c(\alpha))$ for a root at
/// $o$ turned by $R$ ([`crate::mechanism::lagrangian`]).
///
/// $$c = \int_0^L\mu\thinspace r\thinspace ds,\quad
/// \frac{\partial c}{\partial\alpha_i} = \int_0^L\mu\thinspace J_{r,i}\thinspace ds,\quad
/// \frac{\partial^2c}{\partial\alpha_i\partial\alpha_j} = -\int_0^L\mu\int_0^s\psi_i\psi_j
/// \begin{pmatrix}\cos\phi\cr\sin\phi\end{pmatrix}ds^{\prime}\thinspace ds,$$
///
/// on the nested quadrature of [`update`] (the tip body is not included).
#[derive(Debug, Clone, PartialEq)]
pub struct Weight<T: Scalar = f64> {
    /// $m = \int_0^L\mu\thinspace ds$ (kg).
    pub mass: f64,
    /// $c$ (kg·m).
    pub first_moment: [T; 2],
    /// $\partial c/\partial\alpha_i$, one per coordinate.
    pub jacobian: Vec<[T; 2]>,
    /// $\partial^2c/\partial\alpha_i\partial\alpha_j$, `[i * n + j]`.
    pub hessian: Vec<[T; 2]>,
    /// $J_r$ and $\partial J_r/\partial\alpha$ at the current node.
    node_jacobian: Vec<[T; 2]>,
    node_hessian: Vec<[T; 2]>,
}

impl<T: Scalar> Weight<T> {
    /// Buffers for `model`.
    pub fn new(model: &MassModel) -> Self {
        let n = model.order;
        let zero = [T::zero(); 2];
        Self {
            mass: 0.0,
            first_moment: zero,
            jacobian: vec![zero; n],
            hessian: vec![zero; n * n],
            node_jacobian: vec![zero; n],
            node_hessian: vec![zero; n * n],
        }
    }
}

/// Fills `out` with the [`Weight`] of `model`'s distributed mass at `alpha`,
/// in one pass over the nodes of [`update`]. Generic over [`Scalar`], so
/// dual numbers differentiate it. Does not allocate.
///
/// # Panics
/// If `alpha` does not have [`MassModel::order`] entries or `out` was made
/// for another order.
///
/// # Example
/// ```
/// use flexure::mass::{weight, MassModel, Weight};
/// use flexure::section::{Profile, Section};
/// let s = Section::given(Profile::Constant(1.0)).unwrap().with_mass_per_length(Profile::Constant(2.0)).unwrap();
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap().with_section(s).unwrap();
/// let model = MassModel::new(&f, None).unwrap();
/// let mut w = Weight::new(&model);
/// weight(&model, &[0.0; 3], &mut w);
/// // Straight: m = μL, c = (μL²/2, 0), and ∂c_y/∂α₁ = μ∫ s²/2L ds = μL²/6.
/// assert!((w.mass - 2.0).abs() < 1e-14 && (w.first_moment[0] - 1.0).abs() < 1e-14);
/// assert!((w.jacobian[0][1] - 2.0 / 6.0).abs() < 1e-14);
/// ```
pub fn weight<T: Scalar>(model: &MassModel, alpha: &[T], out: &mut Weight<T>) {
    let n = model.order;
    assert!(alpha.len() == n, "alpha must have {n} entries (one per coordinate), got {}", alpha.len());
    assert!(out.jacobian.len() == n, "Weight was made for a model of another order");
    let zero = [T::zero(); 2];
    out.mass = 0.0;
    out.first_moment = zero;
    out.jacobian.fill(zero);
    out.hessian.fill(zero);
    out.node_jacobian.fill(zero);
    out.node_hessian.fill(zero);
    let mut r = zero;
    for (psis, weights, mass) in model.panels() {
        for (psi, &w) in psis.chunks_exact(n).zip(weights) {
            let (s, c) = angle(psi, alpha).sin_cos();
            r[0] += T::c(w) * c;
            r[1] += T::c(w) * s;
            for (i, &pi) in psi.iter().enumerate() {
                let wp = w * pi;
                out.node_jacobian[i][0] -= T::c(wp) * s;
                out.node_jacobian[i][1] += T::c(wp) * c;
                // The upper triangle (j ≥ i), mirrored at the end: exactly symmetric.
                for (j, &pj) in psi.iter().enumerate().skip(i) {
                    let h = &mut out.node_hessian[i * n + j];
                    h[0] -= T::c(wp * pj) * c;
                    h[1] -= T::c(wp * pj) * s;
                }
            }
        }
        if mass != 0.0 {
            out.mass += mass;
            let m = T::c(mass);
            out.first_moment[0] += m * r[0];
            out.first_moment[1] += m * r[1];
            for (o, j) in out.jacobian.iter_mut().zip(&out.node_jacobian) {
                o[0] += m * j[0];
                o[1] += m * j[1];
            }
            for (o, h) in out.hessian.iter_mut().zip(&out.node_hessian) {
                o[0] += m * h[0];
                o[1] += m * h[1];
            }
        }
    }
    for i in 0..n {
        for j in 0..i {
            out.hessian[i * n + j] = out.hessian[j * n + i];
        }
    }
}
