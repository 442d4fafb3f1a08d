//! Tip pose, transform, Jacobian and Hessians in one pass over the
//! quadrature points (paper Eqs. 7, 11, 14–15, 19–21, 29–31).

use crate::flexure::{Flexure, assert_coordinates};
use crate::scalar::Scalar;
use nalgebra::DMatrix;

pub use crate::space::Pose;

/// How far [`update`] goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    /// Tip pose only.
    Pose,
    /// Pose and Jacobian.
    Jacobian,
    /// Pose, Jacobian and the Hessians of $x$ and $y$.
    Hessian,
}

/// Kinematics results for one flexure, reused across evaluations (the Data).
#[derive(Debug, Clone)]
pub struct Kinematics<T: Scalar = f64> {
    /// Tip pose in the root frame.
    pub pose_root_tip: Pose<T>,
    /// $3 \times N$ Jacobian of the tip pose, rows $(\phi, x, y)$ (Eqs. 19–21).
    pub jacobian_root_tip: DMatrix<T>,
    /// $N \times N$ Hessian of the tip's $x$ (Eq. 30).
    pub hessian_root_tip_x: DMatrix<T>,
    /// $N \times N$ Hessian of the tip's $y$ (Eq. 31).
    pub hessian_root_tip_y: DMatrix<T>,
    /// $(\cos\phi_k, \sin\phi_k)$ at every node, for orders and rules
    /// without a fixed-size kernel.
    node_cos_sin: Vec<[T; 2]>,
}

impl<T: Scalar> Kinematics<T> {
    /// Whether these buffers were made for a flexure of `flexure`'s order
    /// and quadrature rule (any such flexure may use them).
    ///
    /// # Example
    /// ```
    /// use flexure::{kinematics::Kinematics, Flexure};
    /// let k: Kinematics = Kinematics::new(&Flexure::new(1.0, 1.0, 3).unwrap());
    /// assert!(k.fits(&Flexure::new(2.0, 5.0, 3).unwrap()));
    /// assert!(!k.fits(&Flexure::segments(1.0, 1.0, 3).unwrap()));
    /// ```
    pub fn fits(&self, flexure: &Flexure) -> bool {
        self.jacobian_root_tip.ncols() == flexure.order() && self.node_cos_sin.len() == flexure.scaled_weights().len()
    }

    /// [`Kinematics::fits`] as a result: an error naming `data`, the
    /// workspace these buffers belong to, when they do not fit `flexure`.
    ///
    /// # Example
    /// ```
    /// use flexure::{kinematics::Kinematics, Error, Flexure};
    /// let k: Kinematics = Kinematics::new(&Flexure::new(1.0, 1.0, 3).unwrap());
    /// let e = k.check_fits(&Flexure::segments(1.0, 1.0, 3).unwrap()).unwrap_err();
    /// assert!(matches!(e, Error::InvalidParameter { name: "data", .. }));
    /// ```
    pub fn check_fits(&self, flexure: &Flexure) -> crate::Result<()> {
        if self.fits(flexure) {
            return Ok(());
        }
        Err(crate::Error::invalid(
            "data",
            format!("buffers of order {}", self.jacobian_root_tip.ncols()),
            "was made for a flexure of another order or quadrature rule",
        ))
    }

    /// Buffers sized for `flexure`.
    pub fn new(flexure: &Flexure) -> Self {
        let n = flexure.order();
        Self {
            pose_root_tip: Pose { phi: T::zero(), x: T::zero(), y: T::zero() },
            jacobian_root_tip: DMatrix::zeros(3, n),
            hessian_root_tip_x: DMatrix::zeros(n, n),
            hessian_root_tip_y: DMatrix::zeros(n, n),
            node_cos_sin: vec![[T::zero(); 2]; flexure.scaled_weights().len()],
        }
    }
}

/// The tip's kinematics at one $\alpha$, as the CLI's `kinematics` prints
/// them: the pose $(\phi, x, y)$, the homogeneous transform $G$ of Eq. 7 by
/// rows, the Jacobian's rows $\partial(\phi, x, y)/\partial\alpha$ (Eqs. 19–21)
/// and the Hessians of $x$ and $y$ (Eqs. 30–31) by rows.
///
/// # Example
/// ```
/// use flexure::{kinematics::TipKinematics, Flexure};
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// let k = TipKinematics::at(&f, &[0.0, 0.0, 0.0])?;
/// // Straight: the tip at (L, 0); φ = α₁, so the Jacobian's first row is (1, 0, 0);
/// // ∂y/∂α₁ = L∫t = 1/2 and ∂²x/∂α₁² = −L∫t² = −1/3 (Eqs. 20, 30).
/// assert_eq!((k.pose.x, k.transform[0][3], k.jacobian.phi.as_slice()), (1.0, 1.0, &[1.0, 0.0, 0.0][..]));
/// assert!((k.jacobian.y[0] - 0.5).abs() < 1e-14 && (k.hessian.x[0][0] + 1.0 / 3.0).abs() < 1e-14);
/// // Printed as the CLI's `kinematics` prints them.
/// let v = serde_json::to_value(&k).unwrap();
/// assert_eq!(v["jacobian"]["phi"], serde_json::json!([1.0, 0.0, 0.0]));
/// assert_eq!(v["pose"], serde_json::json!({ "phi": 0.0, "x": 1.0, "y": 0.0 }));
/// # Ok::<(), flexure::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TipKinematics {
    /// Tip pose in the root frame.
    pub pose: Pose,
    /// The transform $G$ (Eq. 7), row by row.
    pub transform: [[f64; 4]; 4],
    /// The Jacobian's rows (Eqs. 19–21).
    pub jacobian: JacobianRows,
    /// The Hessians of the tip's $x$ and $y$ (Eqs. 30–31), row by row.
    pub hessian: TipHessians,
}

/// A $3 \times N$ Jacobian by its rows $(\phi, x, y)$, each of $N$ entries.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct JacobianRows {
    /// $\partial\phi/\partial\alpha$.
    pub phi: Vec<f64>,
    /// $\partial x/\partial\alpha$.
    pub x: Vec<f64>,
    /// $\partial y/\partial\alpha$.
    pub y: Vec<f64>,
}

/// The $N \times N$ Hessians of the tip's $x$ and $y$, row by row.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TipHessians {
    /// $\partial^2 x/\partial\alpha_i\partial\alpha_j$ (Eq. 30).
    pub x: Vec<Vec<f64>>,
    /// $\partial^2 y/\partial\alpha_i\partial\alpha_j$ (Eq. 31).
    pub y: Vec<Vec<f64>>,
}

impl TipKinematics {
    /// The kinematics of `flexure` at `alpha`, by [`update`] to
    /// [`Level::Hessian`]; an error naming `alpha` unless it has one finite
    /// value per coordinate ([`Flexure::check_coordinates`]).
    pub fn at(flexure: &Flexure, alpha: &[f64]) -> crate::Result<Self> {
        flexure.check_coordinates("alpha", alpha)?;
        let mut k = Kinematics::new(flexure);
        update(flexure, alpha, &mut k, Level::Hessian);
        let rows = |m: &DMatrix<f64>| m.row_iter().map(|r| r.iter().copied().collect()).collect::<Vec<Vec<f64>>>();
        let g = k.pose_root_tip.transform();
        let mut jacobian = rows(&k.jacobian_root_tip).into_iter();
        let mut row = || jacobian.next().unwrap_or_default();
        Ok(Self {
            pose: k.pose_root_tip,
            transform: std::array::from_fn(|i| std::array::from_fn(|j| g[(i, j)])),
            jacobian: JacobianRows { phi: row(), x: row(), y: row() },
            hessian: TipHessians { x: rows(&k.hessian_root_tip_x), y: rows(&k.hessian_root_tip_y) },
        })
    }
}

/// The tip pose alone: $\phi = \alpha_1$, $x = L\sum_k \Delta_k\cos\phi(t_k)$,
/// $y = L\sum_k \Delta_k\sin\phi(t_k)$ (Eqs. 11, 14, 15).
///
/// Needs no workspace and does not allocate.
///
/// # Panics
/// If `alpha` does not have [`Flexure::order`] entries (never truncates);
/// validate user input first with [`Flexure::check_coordinates`].
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// // A constant-curvature arc of angle a: x = sin(a)/a, y = (1 − cos a)/a.
/// let p = flexure::pose_root_tip(&f, &[1.0, 0.0, 0.0]);
/// assert!((p.x - 1f64.sin()).abs() < 1e-9 && (p.y - (1.0 - 1f64.cos())).abs() < 1e-9);
/// ```
pub fn pose_root_tip<T: Scalar>(flexure: &Flexure, alpha: &[T]) -> Pose<T> {
    assert_coordinates(flexure, "alpha", alpha.len());
    match (flexure.order(), flexure.scaled_weights().len()) {
        (2, 4) => fixed_pose::<T, 2, 4>(flexure, alpha),
        (3, 5) => fixed_pose::<T, 3, 5>(flexure, alpha),
        (4, 6) => fixed_pose::<T, 4, 6>(flexure, alpha),
        (5, 7) => fixed_pose::<T, 5, 7>(flexure, alpha),
        (6, 8) => fixed_pose::<T, 6, 8>(flexure, alpha),
        _ => any_pose(flexure, alpha),
    }
}

/// $\phi(t_k) = \sum_i \psi_i(t_k)\alpha_i$ at one node, for order `N`.
#[inline(always)]
fn fixed_angle<T: Scalar, const N: usize>(psi: &[f64], a: &[T; N]) -> T {
    let mut phi = T::zero();
    for i in 0..N {
        phi += T::c(psi[i]) * a[i];
    }
    phi
}

/// $(\cos\phi(t_k), \sin\phi(t_k))$ at all `Q` nodes for order `N`, one
/// pair per node: every x and y quantity downstream shares its weight, so
/// each multiply-add works on both lanes at once.
#[inline(always)]
fn fixed_cos_sin<T: Scalar, const N: usize, const Q: usize>(flexure: &Flexure, alpha: &[T]) -> [[T; 2]; Q] {
    let a: [T; N] = std::array::from_fn(|i| alpha[i]);
    let psi = &flexure.psi_table()[..Q * N];
    let phi: [T; Q] = std::array::from_fn(|k| fixed_angle(&psi[k * N..(k + 1) * N], &a));
    T::cos_sin(&phi)
}

#[inline(always)]
fn fixed_pose<T: Scalar, const N: usize, const Q: usize>(flexure: &Flexure, alpha: &[T]) -> Pose<T> {
    let [x, y] = weighted_sum(&flexure.scaled_weights()[..Q], &fixed_cos_sin::<T, N, Q>(flexure, alpha));
    Pose { phi: tip_angle(flexure, alpha), x, y }
}

/// $\sum_k w_k (\cos\phi_k, \sin\phi_k)$ over as many nodes as `weights`
/// holds, in four partial sums: one running sum would make every add wait
/// for the previous one, four let the processor overlap them.
#[inline(always)]
fn weighted_sum<T: Scalar>(weights: &[f64], cs: &[[T; 2]]) -> [T; 2] {
    let cs = &cs[..weights.len()];
    let mut acc = [[T::zero(); 2]; 4];
    let (w4, c4) = (weights.chunks_exact(4), cs.chunks_exact(4));
    let rest = w4.remainder().iter().zip(c4.remainder());
    for (w, c) in w4.zip(c4) {
        for l in 0..4 {
            acc[l][0] += T::c(w[l]) * c[l][0];
            acc[l][1] += T::c(w[l]) * c[l][1];
        }
    }
    for (a, (&w, c)) in acc.iter_mut().zip(rest) {
        a[0] += T::c(w) * c[0];
        a[1] += T::c(w) * c[1];
    }
    std::array::from_fn(|i| (acc[0][i] + acc[1][i]) + (acc[2][i] + acc[3][i]))
}

/// Nodes per block on the any-order paths: a block's angles are turned into
/// sin/cos together.
const BLOCK: usize = 4;

/// The angles $\phi(t_k)$ of one block of nodes (`psi` holds its rows),
/// padded with zeros.
#[inline(always)]
fn block_angles<T: Scalar>(psi: &[f64], alpha: &[T]) -> [T; BLOCK] {
    let mut phi = [T::zero(); BLOCK];
    for (p, row) in phi.iter_mut().zip(psi.chunks_exact(alpha.len())) {
        *p = node_angle(row, alpha);
    }
    phi
}

fn any_pose<T: Scalar>(flexure: &Flexure, alpha: &[T]) -> Pose<T> {
    let (mut x, mut y) = (T::zero(), T::zero());
    let blocks = flexure.scaled_weights().chunks(BLOCK).zip(flexure.psi_table().chunks(BLOCK * alpha.len()));
    for (weights, psi) in blocks {
        let [dx, dy] = weighted_sum(weights, &T::cos_sin(&block_angles(psi, alpha)));
        x += dx;
        y += dy;
    }
    Pose { phi: tip_angle(flexure, alpha), x, y }
}

/// $(\cos\phi(t_k), \sin\phi(t_k))$ at every node into `out`, a block at a time.
fn any_cos_sin<T: Scalar>(flexure: &Flexure, alpha: &[T], out: &mut [[T; 2]]) {
    for (block, psi) in out.chunks_mut(BLOCK).zip(flexure.psi_table().chunks(BLOCK * alpha.len())) {
        block.copy_from_slice(&T::cos_sin(&block_angles(psi, alpha))[..block.len()]);
    }
}

#[inline(always)]
fn tip_angle<T: Scalar>(flexure: &Flexure, alpha: &[T]) -> T {
    match flexure.basis() {
        // Eq. 11: exactly α₁, with no rounding from the other coordinates.
        crate::flexure::Basis::Legendre => alpha[0],
        crate::flexure::Basis::Segments => node_angle(flexure.tip_angle_row(), alpha),
    }
}

#[inline(always)]
fn node_angle<T: Scalar>(psi: &[f64], alpha: &[T]) -> T {
    let mut phi = T::zero();
    for (&p, &a) in psi.iter().zip(alpha) {
        phi += T::c(p) * a;
    }
    phi
}

/// Fills `data` up to `level` at `alpha`, sharing one $\sin/\cos$ pair per
/// quadrature point between pose, Jacobian and Hessians:
///
/// $$\frac{\partial x}{\partial\alpha_i} = -L\sum_k \Delta_k\psi_i(t_k)\sin\phi_k,\quad
/// \frac{\partial^2 x}{\partial\alpha_i\partial\alpha_j} = -L\sum_k \Delta_k\psi_i\psi_j\cos\phi_k$$
///
/// and likewise for $y$ (Eqs. 20–21, 30–31). Does not allocate.
///
/// # Panics
/// If `alpha` does not have [`Flexure::order`] entries (never truncates;
/// validate user input with [`Flexure::check_coordinates`]), or if `data` was
/// made for a flexure of another order or quadrature rule.
///
/// # Example
/// ```
/// use flexure::{Flexure, Kinematics, Level, update_kinematics};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut k = Kinematics::new(&f);
/// update_kinematics(&f, &[0.0, 0.0, 0.0], &mut k, Level::Hessian);
/// // Straight flexure: ∂²x/∂α₁² = −L∫t² = −1/3 (Eq. 39).
/// assert!((k.hessian_root_tip_x[(0, 0)] + 1.0 / 3.0).abs() < 1e-14);
/// ```
pub fn update<T: Scalar>(flexure: &Flexure, alpha: &[T], data: &mut Kinematics<T>, level: Level) {
    assert_coordinates(flexure, "alpha", alpha.len());
    assert!(data.fits(flexure), "Kinematics buffers were made for a flexure of another order or quadrature rule");
    // Fixed sizes for the common orders with the default rule (N + 2
    // points): every loop unrolls and loses its bounds checks.
    match (flexure.order(), flexure.scaled_weights().len()) {
        (2, 4) => accumulate(flexure, alpha, &fixed_cos_sin::<T, 2, 4>(flexure, alpha), 2, data, level),
        (3, 5) => accumulate(flexure, alpha, &fixed_cos_sin::<T, 3, 5>(flexure, alpha), 3, data, level),
        (4, 6) => accumulate(flexure, alpha, &fixed_cos_sin::<T, 4, 6>(flexure, alpha), 4, data, level),
        (5, 7) => accumulate(flexure, alpha, &fixed_cos_sin::<T, 5, 7>(flexure, alpha), 5, data, level),
        (6, 8) => accumulate(flexure, alpha, &fixed_cos_sin::<T, 6, 8>(flexure, alpha), 6, data, level),
        (n, _) => {
            // Taken out and put back, so the buffer is read while the
            // outputs are written; neither step allocates.
            let mut cs = std::mem::take(&mut data.node_cos_sin);
            any_cos_sin(flexure, alpha, &mut cs);
            accumulate(flexure, alpha, &cs, n, data, level);
            data.node_cos_sin = cs;
        }
    }
}

/// The second phase of the one pass: with every node's sin/cos in `cs`, the
/// pose, Jacobian and Hessians are dot products over the nodes. Inlined into
/// the fixed-size paths, where `n` and the length of `cs` are constants.
#[inline(always)]
fn accumulate<T: Scalar>(
    flexure: &Flexure,
    alpha: &[T],
    cs: &[[T; 2]],
    n: usize,
    data: &mut Kinematics<T>,
    level: Level,
) {
    let q = cs.len();
    let [x, y] = weighted_sum(&flexure.scaled_weights()[..q], cs);
    if level >= Level::Jacobian {
        let jac = data.jacobian_root_tip.as_mut_slice();
        for (i, (row, &d)) in flexure.jacobian_weights().chunks_exact(q).zip(flexure.tip_angle_row()).enumerate() {
            // ∂x = −Σ w ψ sin, ∂y = Σ w ψ cos (Eqs. 20–21).
            let [c, s] = weighted_sum(row, cs);
            jac[3 * i] = T::c(d);
            jac[3 * i + 1] = -s;
            jac[3 * i + 2] = c;
        }
    }
    if level >= Level::Hessian {
        let (ox, oy) = (data.hessian_root_tip_x.as_mut_slice(), data.hessian_root_tip_y.as_mut_slice());
        let mut rows = flexure.hessian_weights().chunks_exact(q);
        for i in 0..n {
            for j in i..n {
                // ∂²x = −Σ w ψψ cos, ∂²y = −Σ w ψψ sin (Eqs. 30–31).
                let [c, s] = weighted_sum(rows.next().unwrap_or(&[]), cs);
                (ox[j * n + i], ox[i * n + j]) = (-c, -c);
                (oy[j * n + i], oy[i * n + j]) = (-s, -s);
            }
        }
    }
    data.pose_root_tip = Pose { phi: tip_angle(flexure, alpha), x, y };
}

/// The pose of the cross-section at `samples` equally spaced arc lengths
/// $s_i = iL/(\text{samples} - 1)$, from the root (identity) to the tip: for
/// drawing. Each interval is integrated with a 5-point Gauss rule.
///
/// # Panics
/// If `alpha` does not have [`Flexure::order`] entries (never truncates;
/// validate user input with [`Flexure::check_coordinates`]).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// let b = flexure::kinematics::backbone(&f, &[1.0, 0.0, 0.0], 11);
/// // Halfway along an arc of angle 1: φ = 1/2, x = sin(1/2).
/// assert!((b[5].phi - 0.5).abs() < 1e-14 && (b[5].x - 0.5f64.sin()).abs() < 1e-12);
/// ```
pub fn backbone(flexure: &Flexure, alpha: &[f64], samples: usize) -> Vec<Pose<f64>> {
    assert_coordinates(flexure, "alpha", alpha.len());
    let mut centreline = Centreline::new(flexure, alpha);
    let count = samples.max(2);
    let h = 1.0 / (count - 1) as f64;
    let mut out = Vec::with_capacity(count);
    let mut xy = (0.0, 0.0);
    out.push(Pose { phi: centreline.angle(0.0), x: xy.0, y: xy.1 });
    for i in 1..count {
        centreline.run((i - 1) as f64 * h, h, &mut xy);
        out.push(Pose { phi: centreline.angle(i as f64 * h), x: xy.0, y: xy.1 });
    }
    out
}

/// The pose of the cross-section at arc length `s` (m, from 0 to $L$):
/// $x + iy = \int_0^s e^{i\theta(u)}\thinspace du$, $\theta(u) = \sum_i \psi_i(u/L)\alpha_i$,
/// by the 5-point Gauss rule on `pieces` equal pieces of $[0, s]$, as
/// [`backbone`] integrates between its samples.
///
/// # Panics
/// If `alpha` does not have [`Flexure::order`] entries (validate user
/// input with [`Flexure::check_coordinates`]).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// // On an arc of angle 1, a quarter along: φ = 1/4, (x, y) = (sin 1/4, 1 − cos 1/4).
/// let p = flexure::kinematics::pose_at(&f, &[1.0, 0.0, 0.0], 0.25, 8);
/// assert!((p.phi - 0.25).abs() < 1e-14 && (p.x - 0.25f64.sin()).abs() < 1e-14 && (p.y - (1.0 - 0.25f64.cos())).abs() < 1e-14);
/// ```
pub fn pose_at(flexure: &Flexure, alpha: &[f64], s: f64, pieces: usize) -> Pose<f64> {
    pose_from(flexure, alpha, (0.0, 0.0, 0.0), s, pieces)
}

/// [`pose_at`] from a section already known: the pose at `s` (m) run from
/// the section at arc length $s_0$ whose position is $(x_0, y_0)$
/// (`from`), by the 5-point Gauss rule on `pieces` equal pieces of
/// $[s_0, s]$: a point near a known one costs a piece, not a whole run.
///
/// # Panics
/// As [`pose_at`].
///
/// # Example
/// ```
/// use flexure::kinematics::{pose_at, pose_from};
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// let alpha = [0.3, -0.2, 0.1];
/// let half = pose_at(&f, &alpha, 0.5, 32);
/// let on = pose_from(&f, &alpha, (0.5, half.x, half.y), 0.75, 16);
/// let whole = pose_at(&f, &alpha, 0.75, 48);
/// assert!((on.x - whole.x).abs() < 1e-15 && (on.y - whole.y).abs() < 1e-15 && on.phi == whole.phi);
/// ```
pub fn pose_from(flexure: &Flexure, alpha: &[f64], from: (f64, f64, f64), s: f64, pieces: usize) -> Pose<f64> {
    assert_coordinates(flexure, "alpha", alpha.len());
    let mut centreline = Centreline::new(flexure, alpha);
    let (count, length) = (pieces.max(1), flexure.length());
    let (t0, t) = (from.0 / length, s / length);
    let h = (t - t0) / count as f64;
    let mut xy = (from.1, from.2);
    for k in 0..count {
        centreline.run(t0 + k as f64 * h, h, &mut xy);
    }
    Pose { phi: centreline.angle(t), x: xy.0, y: xy.1 }
}

/// A flexure's centreline at coordinates $\alpha$: its angle
/// $\theta(t) = \sum_i \psi_i(t)\alpha_i$ along $t = s/L$, and its run
/// between two $t$ by the 5-point Gauss rule ([`backbone`], [`pose_at`]).
struct Centreline<'a> {
    flexure: &'a Flexure,
    alpha: &'a [f64],
    rule: crate::quadrature::GaussLegendre,
    psi: Vec<f64>,
}

impl<'a> Centreline<'a> {
    fn new(flexure: &'a Flexure, alpha: &'a [f64]) -> Self {
        let rule = crate::quadrature::GaussLegendre::new(5).expect("five points");
        Centreline { flexure, alpha, rule, psi: vec![0.0; flexure.order()] }
    }

    /// $\theta(t)$.
    fn angle(&mut self, t: f64) -> f64 {
        self.flexure.angle_shapes(t, &mut self.psi);
        self.psi.iter().zip(self.alpha).map(|(p, a)| p * a).sum::<f64>()
    }

    /// Adds to `xy` the run $L\int(\cos\theta, \sin\theta)\thinspace dt$ over $[t_0, t_0 + h]$.
    fn run(&mut self, t0: f64, h: f64, xy: &mut (f64, f64)) {
        let length = self.flexure.length();
        for k in 0..self.rule.nodes().len() {
            let (t, w) = (self.rule.nodes()[k], self.rule.weights()[k]);
            let (s, c) = self.angle(t0 + t * h).sin_cos();
            xy.0 += w * h * length * c;
            xy.1 += w * h * length * s;
        }
    }
}

/// Tip poses of many configurations: `alphas` holds one row of
/// [`Flexure::order`] coordinates per pose, row after row, and `poses`
/// receives one pose per row, as a [`Pose`] or as a row $[\phi, x, y]$
/// (`[f64; 3]`; a flat buffer of three values per pose is one through
/// `as_chunks_mut::<3>()`). Does not allocate.
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap();
/// let alphas = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
/// let mut poses = [flexure::Pose::default(); 2];
/// flexure::kinematics::poses_root_tip(&f, &alphas, &mut poses).unwrap();
/// assert_eq!(poses[1], flexure::pose_root_tip(&f, &alphas[3..]));
/// // The same poses written as rows of a flat (2, 3) buffer.
/// let mut flat = [0.0; 6];
/// flexure::kinematics::poses_root_tip(&f, &alphas, flat.as_chunks_mut::<3>().0).unwrap();
/// assert_eq!(flat[3..], <[f64; 3]>::from(poses[1]));
/// ```
pub fn poses_root_tip<P: From<Pose<f64>>>(flexure: &Flexure, alphas: &[f64], poses: &mut [P]) -> crate::Result<()> {
    check_batch(flexure, alphas, poses.len())?;
    poses_chunk(flexure, alphas, poses);
    Ok(())
}

/// [`poses_root_tip`] spread over all cores with rayon, in chunks of 4096 poses.
///
/// The speed-up is that of the cores left idle. On two cores, criterion's
/// `batch/pose_1m` against `batch/pose_1m_serial` (10⁶ poses, order 3) gave
/// about 2× when both were idle (1.86× in BENCHMARKS.md's run), but 0.8–1.3×
/// while other builds kept the machine busy (load average 4–5): a busy
/// second core gives about 1.0×, no speed-up.
#[cfg(feature = "parallel")]
pub fn par_poses_root_tip<P: From<Pose<f64>> + Send>(
    flexure: &Flexure,
    alphas: &[f64],
    poses: &mut [P],
) -> crate::Result<()> {
    use rayon::prelude::*;
    check_batch(flexure, alphas, poses.len())?;
    const CHUNK: usize = 4096;
    let n = flexure.order();
    alphas.par_chunks(CHUNK * n).zip(poses.par_chunks_mut(CHUNK)).for_each(|(a, p)| poses_chunk(flexure, a, p));
    Ok(())
}

/// One chunk of a batch, dispatched on the order once rather than per pose.
fn poses_chunk<P: From<Pose<f64>>>(flexure: &Flexure, alphas: &[f64], poses: &mut [P]) {
    fn run<P: From<Pose<f64>>, const N: usize, const Q: usize>(flexure: &Flexure, alphas: &[f64], poses: &mut [P]) {
        for (alpha, pose) in alphas.chunks_exact(N).zip(poses.iter_mut()) {
            *pose = fixed_pose::<f64, N, Q>(flexure, alpha).into();
        }
    }
    match (flexure.order(), flexure.scaled_weights().len()) {
        (2, 4) => run::<P, 2, 4>(flexure, alphas, poses),
        (3, 5) => run::<P, 3, 5>(flexure, alphas, poses),
        (4, 6) => run::<P, 4, 6>(flexure, alphas, poses),
        (5, 7) => run::<P, 5, 7>(flexure, alphas, poses),
        (6, 8) => run::<P, 6, 8>(flexure, alphas, poses),
        (n, _) => {
            for (alpha, pose) in alphas.chunks_exact(n).zip(poses.iter_mut()) {
                *pose = any_pose(flexure, alpha).into();
            }
        }
    }
}

fn check_batch(flexure: &Flexure, alphas: &[f64], poses: usize) -> crate::Result<()> {
    if alphas.len() != poses * flexure.order() {
        return Err(crate::Error::invalid(
            "alpha",
            format!("{} values for {poses} poses", alphas.len()),
            "must hold one row of `order` coordinates per pose",
        ));
    }
    Ok(())
}
