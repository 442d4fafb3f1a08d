//! The spatial flexure's tip pose in SE(3), its body Jacobian and its
//! Hessians, in one pass over the Magnus subintervals.
//!
//! There is no closed form once the curvature vector changes direction, so
//! $g^{\prime} = g\thinspace\hat\xi(s)$, $\xi = (u(s), e_1)$, is integrated over
//! $M$ equal subintervals, each by the 6th-order Magnus step of three Gauss
//! points (the module `magnus` gives $\Omega$, the module `step` the tangents of its
//! exponential), as SoRoSim integrates its Cosserat rods (Mathew, Hmida,
//! Armanini, Boyer and Renda, *SoRoSim*, IEEE RA-M 2022, which uses Zanna
//! collocation over Gauss subintervals). The tip is the product
//! $g = \exp\Omega_1\cdots\exp\Omega_M$, and the derivatives ride along
//! the same product: with $g_k = \exp\Omega_k$, $A_k = \mathrm{Ad}(g_k^{-1})$ and
//! the step's body tangent $J_a^{(k)} = g_k^{-1}\partial_a g_k$,
//! $$J_a \leftarrow A_k J_a + J_a^{(k)},\qquad
//!   H_{ab} \leftarrow A_k H_{ab} - \big[J_b^{(k)},\ A_k J_a\big] + \partial_b J_a^{(k)},$$
//! where $J_a = g^{-1}\partial_a g$ is the body twist of the tip per unit
//! $\alpha_a$ and $H_{ab} = \partial_bJ_a$ (as $\partial_b A_k X = -[J_b^{(k)}, A_k X]$).
//! Every pair is propagated, so that the Maurer–Cartan identity
//! $\partial_aJ_b = \partial_bJ_a - [J_a, J_b]$ and the symmetry of the
//! position's Hessian check the pass instead of being built into it. The tip position's
//! Hessian in the root frame, which a force's load stiffness needs, is
//! $\partial_a\partial_bp = R\thinspace(J_b^{\omega}\times J_a^{v} + H_{ab}^{v})$, symmetric.
//!
//! Without Hessians, the columns can ride in the root frame instead
//! ([`jacobian_pass`], which the stations' mass and a rate's bias use):
//! $\omega_a \leftarrow \omega_a + RJ_l(\omega)\thinspace\partial_a\omega$ and
//! $\partial_ap \leftarrow \partial_ap + \omega_a\times Rp_k + R\thinspace\partial_ap_k$,
//! both linear in the coordinate's nodal derivatives, so each step takes its
//! derivative along nine unit changes once and every column combines three.

use super::SpatialFlexure;
use super::magnus::{Exponent, Jet2, Nine, exponent, exponential};
use super::step::{Step, Tangent};
use crate::kinematics::Level;
use crate::scalar::Scalar;
use crate::space::bracket;
use nalgebra::{DMatrix, Isometry3, Matrix3, Vector3, Vector6};

/// The kinematics of one spatial flexure, reused across evaluations (the Data).
#[derive(Debug, Clone)]
pub struct SpatialKinematics<T: Scalar = f64> {
    /// The tip's rotation $R$ in the root frame.
    pub rotation: Matrix3<T>,
    /// The tip's position $p$ in the root frame (m).
    pub position: Vector3<T>,
    /// The $6\times n$ body Jacobian: column $a$ is the tip's body twist
    /// $g^{-1}\partial g/\partial\alpha_a$, rows $(r_x, r_y, r_z, x, y, z)$ in the tip frame.
    pub jacobian: DMatrix<T>,
    /// $\partial_bJ_a$ at `[a * n + b]`, 6-vectors (angular, linear) in the tip frame.
    pub(super) hessian: Vec<Vector6<T>>,
    /// $\partial_a\partial_b p$ in the root frame at `[a * n + b]` (m), symmetric.
    hessian_position: Vec<Vector3<T>>,
    /// The body Jacobian's columns during the pass.
    pub(super) columns: Vec<Vector6<T>>,
    /// The Jacobian-level pass's columns in the root frame ([`carry`]):
    /// the angular velocity $\omega_a$ of the frame reached per unit $\alpha_a$, and $\partial_ap$.
    pub(super) turning: Vec<Vector3<T>>,
    pub(super) moving: Vec<Vector3<T>>,
    /// $\mathrm{Ad}_{g_k^{-1}}J_a$ of the step being taken.
    moved: Vec<Vector6<T>>,
    /// The step's tangents, one per coordinate.
    tangents: Vec<Tangent<T>>,
    /// $\partial_a\partial_b\Omega$ of the step at `[a * n + b]`.
    exponent_second: Vec<Vector6<T>>,
    /// Each coordinate's nodal twist derivatives, for the step's second derivatives.
    derivatives: Vec<[Vector6<T>; 3]>,
    /// The step's tangents along the unit nodal directions, and which are used.
    along: [Tangent<T>; SLOTS],
    used: [bool; SLOTS],
    /// The step's second derivative (`Step::second`) along pairs of used unit nodal directions.
    bilinear: Vec<Vector6<T>>,
    /// Each coordinate's nonzero nodal coefficients, (used direction, coefficient), `[a * SLOTS + k]`,
    /// and how many it has.
    coefficients: Vec<(usize, T)>,
    counts: Vec<usize>,
}

impl<T: Scalar> SpatialKinematics<T> {
    /// Buffers sized for `flexure`.
    ///
    /// # Example
    /// ```
    /// use flexure::{section::SpatialSection, spatial::{SpatialFlexure, SpatialKinematics}};
    /// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
    /// let k: SpatialKinematics = SpatialKinematics::new(&f);
    /// assert_eq!(k.jacobian.shape(), (6, 9));
    /// ```
    pub fn new(flexure: &SpatialFlexure) -> Self {
        let n = flexure.coordinates();
        Self {
            rotation: Matrix3::identity(),
            position: Vector3::zeros(),
            jacobian: DMatrix::zeros(6, n),
            hessian: vec![Vector6::zeros(); n * n],
            hessian_position: vec![Vector3::zeros(); n * n],
            columns: vec![Vector6::zeros(); n],
            turning: vec![Vector3::zeros(); n],
            moving: vec![Vector3::zeros(); n],
            moved: vec![Vector6::zeros(); n],
            tangents: vec![Tangent::default(); n],
            exponent_second: vec![Vector6::zeros(); n * n],
            derivatives: vec![[Vector6::zeros(); 3]; n],
            along: [Tangent::default(); SLOTS],
            used: [false; SLOTS],
            bilinear: vec![Vector6::zeros(); SLOTS * SLOTS],
            coefficients: vec![(0, T::zero()); n * SLOTS],
            counts: vec![0; n],
        }
    }

    /// Whether these buffers fit `flexure` (its number of coordinates).
    pub fn fits(&self, flexure: &SpatialFlexure) -> bool {
        self.columns.len() == flexure.coordinates()
    }

    /// $H_{ab} = \partial J_a/\partial\alpha_b$: the derivative of column
    /// `a` of the body Jacobian along coordinate `b` (filled at
    /// [`Level::Hessian`]). Not symmetric: $H_{ab} - H_{ba} = [J_a, J_b]$.
    pub fn hessian(&self, a: usize, b: usize) -> Vector6<T> {
        self.hessian[a * self.columns.len() + b]
    }

    /// $\partial^2 p/\partial\alpha_a\partial\alpha_b$, the tip position's
    /// Hessian in the root frame (m, filled at [`Level::Hessian`]).
    pub fn hessian_position(&self, a: usize, b: usize) -> Vector3<T> {
        self.hessian_position[a * self.columns.len() + b]
    }
}

impl SpatialKinematics<f64> {
    /// The tip pose as an isometry (the [`crate::space::Spatial`] pose).
    pub fn pose(&self) -> Isometry3<f64> {
        crate::space::isometry(&self.rotation, &self.position)
    }
}

/// The twists $\xi_j = (u(s_j), e_1)$ at the three Gauss nodes of subinterval `k`.
#[inline(always)]
fn node_twists<T: Scalar>(flexure: &SpatialFlexure, alpha: &[T], k: usize) -> [Vector6<T>; 3] {
    let w = flexure.width();
    let shapes = flexure.shapes(k);
    let orders = flexure.orders();
    let mut xi = [Vector6::zeros(); 3];
    for (j, x) in xi.iter_mut().enumerate() {
        let u = row_curvature(&shapes[j * w..(j + 1) * w], orders, alpha);
        x.fixed_rows_mut::<3>(0).copy_from(&u);
        x[3] = T::one();
    }
    xi
}

/// The curvature $u$ of `alpha` at a point whose shape values $\tilde P_i/L$ are `row`.
#[inline(always)]
pub(super) fn row_curvature<T: Scalar>(row: &[f64], orders: [usize; 3], alpha: &[T]) -> Vector3<T> {
    let mut start = 0;
    Vector3::from_fn(|c, _| {
        let mut sum = T::zero();
        for (&p, &a) in row[..orders[c]].iter().zip(&alpha[start..start + orders[c]]) {
            sum += T::c(p) * a;
        }
        start += orders[c];
        sum
    })
}

/// The nodal twists' derivatives along coordinate `a`: $(\partial_a u(s_j), 0)$.
#[inline(always)]
fn node_derivatives<T: Scalar>(flexure: &SpatialFlexure, k: usize, a: usize) -> [Vector6<T>; 3] {
    let w = flexure.width();
    let shapes = flexure.shapes(k);
    let (c, i) = flexure.component(a);
    std::array::from_fn(|j| {
        let mut d = Vector6::zeros();
        d[c] = T::c(shapes[j * w + i]);
        d
    })
}

fn parts<T: Scalar>(x: &Vector6<T>) -> (Vector3<T>, Vector3<T>) {
    (Vector3::new(x[0], x[1], x[2]), Vector3::new(x[3], x[4], x[5]))
}

/// The nodal twists' entries, 3 nodes of 6: the unit directions a
/// coordinate's derivative is a combination of.
const SLOTS: usize = 18;

/// The step's contribution to every $H_{ab}$ (the module docs' recursion),
/// for many coordinates. The step's second derivative
/// $\partial_b(g_k^{-1}\partial_ag_k)$ (`Step::second`, with the exponent's
/// $D^2\Omega[\partial_a\xi, \partial_b\xi]$) is bilinear in the two
/// coordinates' nodal derivatives, which span at most [`SLOTS`] unit
/// directions (9 for a flexure: 3 nodes, 3 curvatures): it is taken on the
/// pairs of directions the coordinates use (with the tangents along them,
/// [`tangents_by_directions`]) and combined,
/// $\sum_{pq}c_{a,p}c_{b,q}S[e_p, e_q]$, rather than taken for each of the
/// $n^2$ pairs: at orders [64, 64, 64] ($n = 192$) 45 jets and 81 second
/// derivatives a step rather than 18 528 jets and 36 864 second derivatives.
/// Taken above `2 * SLOTS` coordinates; below, the combining costs more than it saves.
fn hessians_by_directions<T: Scalar>(data: &mut SpatialKinematics<T>, xi: &[Vector6<T>; 3], h: f64, step: &Step<T>) {
    let n = data.columns.len();
    let zero = T::zero();
    let mut slots = [0usize; SLOTS];
    let mut s = 0;
    for p in 0..SLOTS {
        if data.used[p] {
            slots[s] = p;
            s += 1;
        }
    }
    let unit = |p: usize, j: usize| {
        let mut u = Vector6::zeros();
        if p / 6 == j {
            u[p % 6] = T::one();
        }
        u
    };
    for i in 0..s {
        for k in i..s {
            let (p, q) = (slots[i], slots[k]);
            let jets: [Jet2<T>; 3] =
                std::array::from_fn(|j| Jet2 { v: xi[j], a: unit(p, j), b: unit(q, j), ab: Vector6::zeros() });
            let (dw, dv) = parts(&exponent(&jets, h).ab);
            // D²Ω is symmetric, the step's second derivative is not.
            let (w, v) = step.second(&data.along[p], &data.along[q], dw, dv);
            data.bilinear[i * SLOTS + k] = six(&w, &v);
            let (w, v) = step.second(&data.along[q], &data.along[p], dw, dv);
            data.bilinear[k * SLOTS + i] = six(&w, &v);
        }
    }
    for a in 0..n {
        let mut count = 0;
        for (i, &p) in slots[..s].iter().enumerate() {
            let c = data.derivatives[a][p / 6][p % 6];
            if c != zero {
                data.coefficients[a * SLOTS + count] = (i, c);
                count += 1;
            }
        }
        data.counts[a] = count;
    }
    for a in 0..n {
        let ca = &data.coefficients[a * SLOTS..a * SLOTS + data.counts[a]];
        for b in 0..n {
            let cb = &data.coefficients[b * SLOTS..b * SLOTS + data.counts[b]];
            let mut second = Vector6::zeros();
            for &(i, x) in ca {
                for &(k, y) in cb {
                    second += data.bilinear[i * SLOTS + k] * (x * y);
                }
            }
            let tb = &data.tangents[b];
            let jb = six(&tb.angular, &tb.linear);
            let hab = &mut data.hessian[a * n + b];
            *hab = adjoint_inverse(&step.r, &step.p, hab) - bracket(&jb, &data.moved[a]) + second;
        }
    }
}

/// The step's tangents along every coordinate into `data.tangents`, as
/// [`hessians_by_directions`] takes the second derivatives: the exponent's
/// derivative $D\Omega[\partial_a\xi]$ and the tangent built on it are
/// linear in the nodal derivatives, which span at most [`SLOTS`] unit
/// directions (9 for a flexure), so they are taken along those and
/// combined, $\sum_p c_{a,p}\thinspace T(e_p)$, rather than taken for each of the $n$
/// coordinates: at orders [64, 64, 64] 9 jets a step rather than 192.
/// Taken above [`SLOTS`] coordinates; below, each coordinate's own jet
/// costs no more.
fn tangents_by_directions<T: Scalar>(
    data: &mut SpatialKinematics<T>,
    derivative: &impl Fn(usize) -> [Vector6<T>; 3],
    exponent: &Exponent<T>,
    step: &Step<T>,
) {
    let n = data.columns.len();
    for a in 0..n {
        data.derivatives[a] = derivative(a);
    }
    let zero = T::zero();
    let (mut along, mut used) = ([Tangent::default(); SLOTS], [false; SLOTS]);
    for p in 0..SLOTS {
        used[p] = data.derivatives.iter().any(|d| d[p / 6][p % 6] != zero);
        if used[p] {
            let mut d = [Vector6::zeros(); 3];
            d[p / 6][p % 6] = T::one();
            let (dw, dv) = exponent.derivative(&d.map(|x| parts(&x).0));
            along[p] = step.tangent(dw, dv);
        }
    }
    for a in 0..n {
        let mut t = Tangent::default();
        for p in (0..SLOTS).filter(|&p| used[p]) {
            let c = data.derivatives[a][p / 6][p % 6];
            if c != zero {
                t.add_scaled(&along[p], c);
            }
        }
        data.tangents[a] = t;
    }
    (data.along, data.used) = (along, used);
}

/// $\mathrm{Ad}_{g^{-1}}\xi = (R^T\omega,\ R^T(v - p\times\omega))$ for $g = (R, p)$.
#[inline(always)]
fn adjoint_inverse<T: Scalar>(r: &Matrix3<T>, p: &Vector3<T>, x: &Vector6<T>) -> Vector6<T> {
    let w = Vector3::new(x[0], x[1], x[2]);
    let v = Vector3::new(x[3], x[4], x[5]) - p.cross(&w);
    let (a, b) = (r.tr_mul(&w), r.tr_mul(&v));
    Vector6::new(a[0], a[1], a[2], b[0], b[1], b[2])
}

#[inline(always)]
fn six<T: Scalar>(a: &Vector3<T>, b: &Vector3<T>) -> Vector6<T> {
    Vector6::new(a[0], a[1], a[2], b[0], b[1], b[2])
}

/// The tip pose $(R, p)$ alone, without a workspace (does not allocate).
///
/// # Panics
/// If `alpha` does not have [`SpatialFlexure::coordinates`] entries.
///
/// # Example
/// ```
/// use flexure::{section::SpatialSection, spatial::{SpatialFlexure, pose_root_tip}};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 1]).unwrap();
/// // A circle's arc of 1 rad about z: x = sin 1, y = 1 − cos 1, exact to rounding.
/// let (r, p) = pose_root_tip(&f, &[0.0, 0.0, 1.0]);
/// assert!((p.x - 1f64.sin()).abs() < 1e-15 && (p.y - (1.0 - 1f64.cos())).abs() < 1e-15 && p.z == 0.0);
/// assert!((r[(1, 0)] - 1f64.sin()).abs() < 1e-15);
/// ```
pub fn pose_root_tip<T: Scalar>(flexure: &SpatialFlexure, alpha: &[T]) -> (Matrix3<T>, Vector3<T>) {
    assert_eq!(alpha.len(), flexure.coordinates(), "alpha must have one entry per coordinate");
    // Fixed sizes for equal orders 2 to 4: the nodal sums unroll.
    match (flexure.orders(), flexure.width()) {
        ([2, 2, 2], 2) => pose_with(flexure, alpha, fixed_curvatures::<T, 2>),
        ([3, 3, 3], 3) => pose_with(flexure, alpha, fixed_curvatures::<T, 3>),
        ([4, 4, 4], 4) => pose_with(flexure, alpha, fixed_curvatures::<T, 4>),
        _ => pose_with(flexure, alpha, |f, a, k| node_twists(f, a, k).map(|x| parts(&x).0)),
    }
}

/// The nodal curvatures of subinterval `k` for orders `[N, N, N]`.
#[inline(always)]
fn fixed_curvatures<T: Scalar, const N: usize>(flexure: &SpatialFlexure, alpha: &[T], k: usize) -> [Vector3<T>; 3] {
    let shapes = &flexure.shapes(k)[..3 * N];
    std::array::from_fn(|j| {
        let row = &shapes[j * N..(j + 1) * N];
        Vector3::from_fn(|c, _| {
            let mut sum = T::zero();
            for i in 0..N {
                sum += T::c(row[i]) * alpha[c * N + i];
            }
            sum
        })
    })
}

#[inline(always)]
fn pose_with<T: Scalar>(
    flexure: &SpatialFlexure,
    alpha: &[T],
    curvatures: impl Fn(&SpatialFlexure, &[T], usize) -> [Vector3<T>; 3],
) -> (Matrix3<T>, Vector3<T>) {
    let h = flexure.length() / flexure.subintervals() as f64;
    let mut r = Matrix3::identity();
    let mut p = Vector3::zeros();
    for k in 0..flexure.subintervals() {
        let (rk, pk) = exponential(&curvatures(flexure, alpha, k), h);
        p += r * pk;
        r *= rk;
    }
    (r, p)
}

/// Fills `data` up to `level` at `alpha` in one pass over the
/// subintervals (the module docs give the recursion): the tip's rotation
/// and position, at [`Level::Jacobian`] the body Jacobian, at
/// [`Level::Hessian`] $H_{ab} = \partial_bJ_a$ and the position's Hessian.
/// Does not allocate.
///
/// # Panics
/// If `alpha` does not have [`SpatialFlexure::coordinates`] entries (check
/// user input with [`SpatialFlexure::check_coordinates`]), or `data` was
/// made for a flexure with another number of coordinates.
///
/// # Example
/// ```
/// use flexure::{Level, section::SpatialSection, spatial::{SpatialFlexure, SpatialKinematics, update}};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
/// let mut k = SpatialKinematics::new(&f);
/// update(&f, &[0.0; 9], Level::Hessian, &mut k);
/// // Straight: the first κ_z coefficient turns the tip about z and moves it
/// // by L/2 along the tip's y (the planar ∂y/∂α₁ = L∫t dt).
/// assert!((k.jacobian[(2, 6)] - 1.0).abs() < 1e-15 && (k.jacobian[(4, 6)] - 0.5).abs() < 1e-15);
/// // ∂²x/∂α₁² = −L∫t² dt = −1/3 (Eq. 39), as the planar flexure's.
/// assert!((k.hessian_position(6, 6).x + 1.0 / 3.0).abs() < 1e-14);
/// ```
pub fn update<T: Scalar>(flexure: &SpatialFlexure, alpha: &[T], level: Level, data: &mut SpatialKinematics<T>) {
    assert_eq!(alpha.len(), flexure.coordinates(), "alpha must have one entry per coordinate");
    assert!(data.fits(flexure), "SpatialKinematics buffers were made for a flexure with another number of coordinates");
    let n = flexure.coordinates();
    let m = flexure.subintervals();
    let h = flexure.length() / m as f64;
    let order = match level {
        Level::Pose => 0,
        Level::Jacobian => 1,
        Level::Hessian => 2,
    };
    let mut r = Matrix3::identity();
    let mut p = Vector3::zeros();
    data.columns.fill(Vector6::zeros());
    if level >= Level::Hessian {
        data.hessian.fill(Vector6::zeros());
    }
    for k in 0..m {
        let xi = node_twists(flexure, alpha, k);
        let step = advance(data, &xi, |a| node_derivatives(flexure, k, a), h, order);
        p += r * step.p;
        r *= step.r;
    }
    data.rotation = r;
    data.position = p;
    if level >= Level::Jacobian {
        for (a, col) in data.columns.iter().enumerate() {
            data.jacobian.column_mut(a).copy_from(col);
        }
    }
    if level >= Level::Hessian {
        for a in 0..n {
            for b in 0..n {
                let (ja, jb) = (&data.columns[a], &data.columns[b]);
                let hab = &data.hessian[a * n + b];
                let lin = Vector3::new(jb[0], jb[1], jb[2]).cross(&Vector3::new(ja[3], ja[4], ja[5]))
                    + Vector3::new(hab[3], hab[4], hab[5]);
                data.hessian_position[a * n + b] = r * lin;
            }
        }
    }
}

/// One Magnus step of length `h` from the nodal twists `xi`, whose
/// derivatives along coordinate `a` are `derivative(a)`: carries the body
/// Jacobian's columns (at `order` 1 and up) and their derivatives (at 2)
/// in `data` from the step's start to its end (the module docs'
/// recursion), and returns the step. [`update`] takes every subinterval
/// by it; [`super::mass`] takes the partial steps to the stations by it.
#[inline(always)]
pub(super) fn advance<T: Scalar>(
    data: &mut SpatialKinematics<T>,
    xi: &[Vector6<T>; 3],
    derivative: impl Fn(usize) -> [Vector6<T>; 3],
    h: f64,
    order: usize,
) -> Step<T> {
    let e = Exponent::new(&xi.map(|x| parts(&x).0), h);
    let (w, v) = e.value();
    advance_step(data, xi, derivative, &e, h, order, Step::new(w, v, order))
}

/// A rate $\dot\alpha$'s body twist $V = \sum_a\dot\alpha_aJ_a$ and its
/// bias $B = \sum_{ab}\dot\alpha_a\dot\alpha_bH_{ab}$, the body
/// acceleration at $\ddot\alpha = 0$ (6-vectors, angular then linear, in
/// the frame reached).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Rate {
    pub twist: Vector6<f64>,
    pub bias: Vector6<f64>,
}

impl Rate {
    /// In the frame $(R, p)$ of the root: the angular velocity $RV^{\omega}$,
    /// the velocity $\dot p = RV^{v}$, the angular acceleration $\dot\omega = RB^{\omega}$
    /// and the acceleration $\ddot p = R(V^{\omega}\times V^{v} + B^{v})$, at $\ddot\alpha = 0$.
    pub fn in_root(&self, r: &Matrix3<f64>) -> [Vector3<f64>; 4] {
        let ((w, v), (bw, bv)) = (parts(&self.twist), parts(&self.bias));
        [r * w, r * v, r * bw, r * (w.cross(&v) + bv)]
    }
}

/// The rate $\dot\alpha$'s twist and bias carried over one step (the
/// module docs' recursion contracted with the rate twice),
/// $$B \leftarrow A_kB - \big[J_{\dot\alpha}^{(k)},\ A_kV\big] + \partial_{\dot\alpha}J_{\dot\alpha}^{(k)},\qquad V \leftarrow A_kV + J_{\dot\alpha}^{(k)},$$
/// where $J_{\dot\alpha}^{(k)}$ and its derivative are the step's along the one
/// change `along` $= \sum_a\dot\alpha_a\partial_au$ of the nodal curvatures ([`Exponent::along`], not $n^2$ pairs): the
/// exact second derivative along the rate for the cost of a first. The
/// step's coefficients must be made to order 2.
pub(super) fn carry_rate(state: &mut Rate, e: &Exponent<f64>, step: &Step<f64>, along: &[Vector3<f64>; 3]) {
    let ((dw, dv), (dww, dvv)) = e.along(along);
    let t = step.tangent(dw, dv);
    let (sw, sv) = step.second(&t, &t, dww, dvv);
    let moved = adjoint_inverse(&step.r, &step.p, &state.twist);
    let own = six(&t.angular, &t.linear);
    state.bias = adjoint_inverse(&step.r, &step.p, &state.bias) - bracket(&own, &moved) + six(&sw, &sv);
    state.twist = moved + own;
}

/// $\sum_a\dot\alpha_a\partial_au$ at the three nodes whose shape values are `rows`: the change of the nodal curvatures along the rate `rate`.
pub(super) fn rate_direction(flexure: &SpatialFlexure, rows: &[f64], rate: &[f64]) -> [Vector3<f64>; 3] {
    let w = flexure.width();
    let mut along = [Vector3::zeros(); 3];
    for (a, &u) in rate.iter().enumerate() {
        if u != 0.0 {
            let (c, i) = flexure.component(a);
            for (g, x) in along.iter_mut().enumerate() {
                x[c] += rows[g * w + i] * u;
            }
        }
    }
    along
}

/// The tip's [`Rate`] for the rate `rate` at `alpha`, with the body
/// Jacobian (as [`update`] at [`Level::Jacobian`]) into `data`, in one pass
/// ([`carry_rate`] on each step of [`jacobian_pass`]).
pub(crate) fn update_rate(flexure: &SpatialFlexure, alpha: &[f64], rate: &[f64], data: &mut SpatialKinematics) -> Rate {
    assert!(alpha.len() == flexure.coordinates() && rate.len() == alpha.len() && data.fits(flexure));
    let mut state = Rate::default();
    jacobian_pass(flexure, alpha, 2, data, |k, e, step| {
        carry_rate(&mut state, e, step, &rate_direction(flexure, flexure.shapes(k), rate));
    });
    state
}

/// What a step adds to the root-frame columns ([`carry`]) per unit change
/// of one of nine directions (three curvatures at three nodes, or in three
/// of the exponent's $w_b$): angular then linear, column `3 * g + c` for curvature `c`
/// at node (or $w$) `g`; and the maps they are made with ([`Step::maps`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Images<T: Scalar> {
    pub turning: Nine<T>,
    pub moving: Nine<T>,
    /// $RJ_l(\omega)$ and $RQ$.
    pub left: Matrix3<T>,
    pub shift: Matrix3<T>,
}

impl<T: Scalar> Default for Images<T> {
    fn default() -> Self {
        Images { turning: Nine::zeros(), moving: Nine::zeros(), left: Matrix3::zeros(), shift: Matrix3::zeros() }
    }
}

/// The [`Images`] of the step `step` (exponent `e`) taken from the frame
/// of rotation `frame` $= R$: for the unit change
/// $\delta u$, $\big(RJ_l(\omega)\thinspace\delta\omega,\ R\thinspace\delta p_k\big)$ with
/// $(\delta\omega, \delta v) = D\Omega[\delta u]$ ([`Exponent::jacobian`],
/// [`Step::maps`]). A coordinate's nodal derivatives are a combination
/// of these nine unit changes, and the images are linear in them: nine
/// tangents a step serve every coordinate.
#[inline(always)]
pub(super) fn images<T: Scalar>(e: &Exponent<T>, step: &Step<T>, frame: &Matrix3<T>) -> Images<T> {
    let (dw, dv) = e.jacobian();
    let (left, shift) = step.maps(frame);
    Images { turning: left * dw, moving: left * dv + shift * dw, left, shift }
}

/// [`images`] along unit changes of the exponent's $w_1, w_2, w_3$ rather
/// than of the nodal curvatures ([`Exponent::jacobian_alphas`]): a coordinate's
/// change of them combines three as its nodal one does, with the
/// coefficients of [`Exponent::alphas`] folded into its table
/// (`MassQuadrature`'s), so that the blocks need not be combined by nodes. For the dynamics; into `out`.
#[inline(always)]
pub(super) fn images_alphas(e: &Exponent<f64>, step: &Step<f64>, frame: &Matrix3<f64>, out: &mut Images<f64>) {
    let (left, shift) = step.maps(frame);
    e.jacobian_alphas(|b, omega, v| {
        out.turning.fixed_view_mut::<3, 3>(0, 3 * b).copy_from(&(left * omega));
        out.moving.fixed_view_mut::<3, 3>(0, 3 * b).copy_from(&(left * v + shift * omega));
    });
    (out.left, out.shift) = (left, shift);
}

/// A frame's motion under a rate $\dot\alpha$ at $\ddot\alpha = 0$ in the flexure's
/// root frame ([`Rate::in_root`]'s form): its angular velocity $\omega$, its
/// origin's velocity $\dot p$, its angular acceleration $\dot\omega$ and its origin's acceleration $\ddot p$.
pub(crate) type Motion = [Vector3<f64>; 4];

/// The [`Motion`] `from` of the frame $(R, p)$ a step is taken from, carried
/// to the frame reached, $(RR_k, p + Rp_k)$ with `arm` $= Rp_k$: the step
/// turns it at $\omega_k = RJ_l\delta\omega$ and moves it at $\dot p_k = R\delta p$
/// relative to $(R, p)$ (the step's `images`' maps on the exponent's first
/// derivative along the rate's change `along` of its directions), with
/// $\dot\omega_k$ and $\ddot p_k$ from its second ([`Step::quadratic`]), so
/// $$\omega^{\prime} = \omega + \omega_k,\quad \dot p^{\prime} = \dot p + \omega\times Rp_k + \dot p_k,\quad
///   \dot\omega^{\prime} = \dot\omega + \omega\times\omega_k + \dot\omega_k,$$
/// $$\ddot p^{\prime} = \ddot p + \dot\omega\times Rp_k + \omega\times(\omega\times Rp_k) + 2\omega\times\dot p_k + \ddot p_k:$$
/// [`carry_rate`]'s body-frame recursion in the root frame, where the
/// stations' motion is wanted, without the adjoints.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn carry_motion(
    from: &Motion,
    first: (Vector3<f64>, Vector3<f64>),
    second: (Vector3<f64>, Vector3<f64>),
    step: &Step<f64>,
    r: &Matrix3<f64>,
    images: &Images<f64>,
    arm: &Vector3<f64>,
) -> Motion {
    let ((dw, dv), (dww, dvv)) = (first, second);
    let (left, shift) = (&images.left, &images.shift);
    let (turn, slide) = (left * dw, left * dv + shift * dw);
    let (a, b) = step.quadratic(&dw, &dv);
    let (turning, moving) = (left * dww + r * a, left * dvv + shift * dww + r * b);
    let [w, pd, wd, pdd] = *from;
    let wa = w.cross(arm);
    [
        w + turn,
        pd + wa + slide,
        wd + w.cross(&turn) + turning,
        pdd + wd.cross(arm) + w.cross(&wa) + w.cross(&slide) * 2.0 + moving,
    ]
}

/// Each column's [`Images`] combination for a step whose nodal shape values
/// are `rows`, `each(a, δω_a, δp_a)` in the order of the coordinates:
/// $\sum_g\tilde P_i(s_g)\thinspace I_{c,g}$ for coordinate $a$'s curvature $c$ and shape $i$.
#[inline(always)]
pub(super) fn increments<T: Scalar>(
    flexure: &SpatialFlexure,
    images: &Images<T>,
    rows: &[f64],
    mut each: impl FnMut(usize, Vector3<T>, Vector3<T>),
) {
    let (w, orders) = (flexure.width(), flexure.orders());
    let mut a = 0;
    for (c, &order) in orders.iter().enumerate() {
        for i in 0..order {
            let (mut dw, mut dp) = (Vector3::zeros(), Vector3::zeros());
            for g in 0..3 {
                let k = T::c(rows[g * w + i]);
                dw += images.turning.column(3 * g + c) * k;
                dp += images.moving.column(3 * g + c) * k;
            }
            each(a, dw, dp);
            a += 1;
        }
    }
}

/// The root-frame columns carried over one step $(R_k, p_k)$ from the frame
/// $(R, p)$, whose images are `images` and whose nodal shape values are `rows`:
/// as $R^{\prime} = RR_k$ and $p^{\prime} = p + Rp_k$,
/// $$\omega_a \leftarrow \omega_a + RJ_l(\omega)\thinspace\partial_a\omega,\qquad
///   \partial_ap \leftarrow \partial_ap + \omega_a\times Rp_k + R\thinspace\partial_ap_k,$$
/// with `arm` $= Rp_k$. Against the body recursion's $\mathrm{Ad}$ on every
/// column and a tangent for each coordinate, this is a combination of
/// three images and a cross product a column.
#[inline(always)]
pub(super) fn carry<T: Scalar>(
    data: &mut SpatialKinematics<T>,
    flexure: &SpatialFlexure,
    rows: &[f64],
    images: &Images<T>,
    arm: &Vector3<T>,
) {
    increments(flexure, images, rows, |a, dw, dp| {
        data.moving[a] += data.turning[a].cross(arm) + dp;
        data.turning[a] += dw;
    });
}

/// One step of [`jacobian_pass`] from the frame rotation `r`: the step
/// `step` (exponent `e`, nodal shape values `rows`) carries `data`'s
/// root-frame columns when its coefficients have their derivatives
/// (order 1 and up), and gives the frame reached, $(RR_k, Rp_k)$ (the rotation, and the position's change).
#[inline(always)]
pub(super) fn root_step<T: Scalar>(
    flexure: &SpatialFlexure,
    rows: &[f64],
    e: &Exponent<T>,
    step: &Step<T>,
    r: &Matrix3<T>,
    data: &mut SpatialKinematics<T>,
    images: impl Fn(&Exponent<T>, &Step<T>, &Matrix3<T>) -> Images<T>,
) -> (Matrix3<T>, Vector3<T>) {
    let (turn, arm) = (r * step.r, r * step.p);
    if step.order >= 1 {
        carry(data, flexure, rows, &images(e, step, r), &arm);
    }
    (turn, arm)
}

/// The tip's pose and body Jacobian, as [`update`] at [`Level::Jacobian`]
/// gives them, carried in the root frame ([`carry`]) and turned at the end,
/// $(R^T\omega_a, R^T\partial_ap)$ (equal to rounding; `update` keeps the
/// body-frame pass, so that statics answers stay bit for bit).
/// Each step's coefficients are made to `order` (at least 1), and
/// `each(k, exponent, step)` is called on subinterval `k`'s step.
pub(super) fn jacobian_pass<T: Scalar>(
    flexure: &SpatialFlexure,
    alpha: &[T],
    order: usize,
    data: &mut SpatialKinematics<T>,
    mut each: impl FnMut(usize, &Exponent<T>, &Step<T>),
) {
    let m = flexure.subintervals();
    let h = flexure.length() / m as f64;
    let (mut r, mut p) = (Matrix3::identity(), Vector3::zeros());
    data.turning.fill(Vector3::zeros());
    data.moving.fill(Vector3::zeros());
    for k in 0..m {
        let e = Exponent::new(&node_twists(flexure, alpha, k).map(|x| parts(&x).0), h);
        let (w, v) = e.value();
        let step = Step::new(w, v, order);
        let (turn, arm) = root_step(flexure, flexure.shapes(k), &e, &step, &r, data, images);
        each(k, &e, &step);
        p += arm;
        r = turn;
    }
    data.rotation = r;
    data.position = p;
    for a in 0..data.columns.len() {
        let column = six(&r.tr_mul(&data.turning[a]), &r.tr_mul(&data.moving[a]));
        data.columns[a] = column;
        data.jacobian.column_mut(a).copy_from(&column);
    }
}

/// [`advance`] with its step made (coefficients to at least `order`).
#[inline(always)]
fn advance_step<T: Scalar>(
    data: &mut SpatialKinematics<T>,
    xi: &[Vector6<T>; 3],
    derivative: impl Fn(usize) -> [Vector6<T>; 3],
    e: &Exponent<T>,
    h: f64,
    order: usize,
    step: Step<T>,
) -> Step<T> {
    let n = data.columns.len();
    if order >= 1 {
        if n > SLOTS {
            tangents_by_directions(data, &derivative, e, &step);
        } else {
            for a in 0..n {
                let (dw, dv) = e.derivative(&derivative(a).map(|x| parts(&x).0));
                data.tangents[a] = step.tangent(dw, dv);
            }
        }
        for a in 0..n {
            data.moved[a] = adjoint_inverse(&step.r, &step.p, &data.columns[a]);
        }
        if order >= 2 && n > 2 * SLOTS {
            hessians_by_directions(data, xi, h, &step);
        } else if order >= 2 {
            // Few coordinates: a jet for each pair costs no more than one
            // for each pair of directions, without the combining.
            for a in 0..n {
                let da = derivative(a);
                for b in a..n {
                    let db = derivative(b);
                    let jets: [Jet2<T>; 3] =
                        std::array::from_fn(|j| Jet2 { v: xi[j], a: da[j], b: db[j], ab: Vector6::zeros() });
                    let ab = exponent(&jets, h).ab;
                    data.exponent_second[a * n + b] = ab;
                    data.exponent_second[b * n + a] = ab;
                }
            }
        }
        if order >= 2 && n <= 2 * SLOTS {
            for a in 0..n {
                for b in 0..n {
                    let (ta, tb) = (&data.tangents[a], &data.tangents[b]);
                    let (dwab, dvab) = parts(&data.exponent_second[a * n + b]);
                    let (wa, va) = step.second(ta, tb, dwab, dvab);
                    let jb = six(&tb.angular, &tb.linear);
                    let hab = &mut data.hessian[a * n + b];
                    *hab = adjoint_inverse(&step.r, &step.p, hab) - bracket(&jb, &data.moved[a]) + six(&wa, &va);
                }
            }
        }
        for a in 0..n {
            let t = &data.tangents[a];
            data.columns[a] = data.moved[a] + six(&t.angular, &t.linear);
        }
    }
    step
}
