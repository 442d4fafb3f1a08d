//! A spatial flexure's own mass: its stations (a quadrature along the rod)
//! and their frames and Jacobians from the tip's own Magnus pass.
//!
//! A section of mass per length $\mu(s)$ and rotary inertia per length
//! $\rho I(s) = \rho\thinspace\mathrm{diag}(I_y + I_z, I_y, I_z)$ (section
//! frame, [`crate::section::SpatialSection::rotary_inertia_per_length`])
//! moving with the centre velocity $\dot p(s)$ and angular velocity
//! $\omega(s)$ has the kinetic energy
//! $$T = \tfrac12\int_0^L \big(\mu\lvert\dot p\rvert^2 + \omega\cdot R\rho IR^T\omega\big)\thinspace ds
//!   \approx \tfrac12\sum_k w_k\big(\mu_k\lvert J_{v,k}\dot\alpha\rvert^2 + (J_{\omega,k}\dot\alpha)\cdot R_k\rho I_kR_k^T(J_{\omega,k}\dot\alpha)\big),$$
//! and under gravity $g$ the potential $-\int_0^L\mu\thinspace g\cdot p\thinspace ds$.
//! The stations $s_k$ are the three Gauss points of each of the flexure's
//! $M$ Magnus subintervals (weights $\frac5{18}, \frac8{18}, \frac5{18}$ of
//! its length $h$): exact for integrands of degree 5 on each, so the
//! quadrature's error falls as $h^6$, as the Magnus pose's does.
//!
//! A station's frame is the one [`super::shape_at`] gives, one more
//! Magnus step from the start $s_j$ of its subinterval over $d = s_k - s_j$:
//! $g(s_k) = g(s_j)\exp\Omega(s_j, d)$, with the curvature at that step's own
//! three Gauss nodes. Its Jacobian rides along the tip's recursion
//! ([`super::kinematics`]): the Jacobian at $s_j$ is carried through the
//! partial step as through a whole one, so it is the exact derivative of the
//! station's pose (`tests/spatial_flexure_mass.rs` checks it against central
//! differences at both levels). At [`Level::Jacobian`], what dynamics asks for
//! at every evaluation, the columns are carried in the root frame,
//! $\omega_a \leftarrow \omega_a + RJ_l\delta\omega_a$ and
//! $\partial_ap \leftarrow \partial_ap + \omega_a\times Rp_k + R\delta p_a$, whose
//! increments combine nine unit images a step (three curvatures at three
//! nodes) rather than a tangent and an adjoint a coordinate; at
//! [`Level::Hessian`] the body-frame recursion with its $H_{ab}$. At [`Level::Hessian`] the pass also gives the first moment
//! $S = \sum_k w_k\mu_kp_k$ with its exact Hessian, what the weight's
//! stiffness needs.

use super::SpatialFlexure;
use super::kinematics::{
    Images, Motion, SpatialKinematics, advance, carry, carry_motion, images, images_alphas, increments, row_curvature,
};
use super::magnus::{Exponent, NODES};
use super::step::Step;
use crate::basis;
use crate::kinematics::Level;
use nalgebra::{Matrix3, Vector3, Vector6};

/// The Gauss weights on $[0, 1]$ of the stations in a subinterval.
const WEIGHTS: [f64; 3] = [5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0];

/// One station of a flexure's mass quadrature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassStation {
    /// Arc length $s_k$ from the root (m).
    pub s: f64,
    /// Its share of the mass, $w_k\mu(s_k)$ (kg).
    pub mass: f64,
    /// Its share of the rotary inertia, $w_k\rho\thinspace(I_y + I_z, I_y, I_z)$
    /// at $s_k$ (kg·m²), the diagonal in the section frame.
    pub rotary: [f64; 3],
}

/// A flexure's mass stations, and the shape values of the partial Magnus
/// steps that reach them (the Model's tables; made once per flexure).
#[derive(Debug, Clone, PartialEq)]
pub struct MassQuadrature {
    stations: Vec<MassStation>,
    width: usize,
    /// $\tilde P_i(t)/L$ at the Gauss node $g$ of the partial step to
    /// station $k$, `[(k * 3 + g) * width + i]`.
    partial: Vec<f64>,
    /// The same shape values as they enter the step's exponent's $w_1, w_2, w_3$
    /// ([`by_alphas`]): of the partial step to station $k$ at `[(k * 3 + b) * width + i]`,
    /// and of subinterval $j$'s whole step at `[(j * 3 + b) * width + i]`.
    partial_alphas: Vec<f64>,
    whole_alphas: Vec<f64>,
}

impl MassQuadrature {
    /// The stations of `flexure`: three per Magnus subinterval (module
    /// docs); `None` for a massless flexure.
    ///
    /// # Example
    /// ```
    /// use flexure::section::{Profile, SpatialSection};
    /// use flexure::spatial::{MassQuadrature, SpatialFlexure};
    /// let f = SpatialFlexure::new(2.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
    /// assert!(MassQuadrature::new(&f).is_none());
    /// let q = MassQuadrature::new(&f.with_mass_per_length(Profile::Linear { root: 1.0, tip: 3.0 }).unwrap()).unwrap();
    /// assert_eq!(q.stations().len(), 3 * 8);
    /// // μ = 1 + s: the rule is exact for it, ∫₀² (1 + s) ds = 4 kg.
    /// assert!((q.mass() - 4.0).abs() < 1e-14);
    /// ```
    pub fn new(flexure: &SpatialFlexure) -> Option<Self> {
        let section = flexure.section();
        if !section.has_mass() {
            return None;
        }
        let (m, width, l) = (flexure.subintervals(), flexure.width(), flexure.length());
        let h = l / m as f64;
        let mut stations = Vec::with_capacity(3 * m);
        let mut partial = Vec::with_capacity(9 * m * width);
        let mut row = vec![0.0; width];
        for k in 0..m {
            for (tau, w) in NODES.iter().zip(WEIGHTS) {
                let t = (k as f64 + tau) / m as f64;
                let weight = w * h;
                let mu = section.mass_per_length(t).unwrap_or(0.0);
                let rotary = section.rotary_inertia_per_length(t).unwrap_or([0.0; 3]).map(|i| weight * i);
                stations.push(MassStation { s: t * l, mass: weight * mu, rotary });
                for g in NODES {
                    basis::shifted_legendre((k as f64 + tau * g) / m as f64, &mut row);
                    partial.extend(row.iter().map(|v| v / l));
                }
            }
        }
        let partial_alphas =
            (0..3 * m).flat_map(|k| by_alphas(&partial[k * 3 * width..], width, NODES[k % 3] * h)).collect();
        let whole_alphas = (0..m).flat_map(|k| by_alphas(flexure.shapes(k), width, h)).collect();
        Some(MassQuadrature { stations, width, partial, partial_alphas, whole_alphas })
    }

    /// The stations, root to tip.
    pub fn stations(&self) -> &[MassStation] {
        &self.stations
    }

    /// The flexure's mass $\sum_kw_k\mu_k$ (kg).
    pub fn mass(&self) -> f64 {
        self.stations.iter().map(|s| s.mass).sum()
    }

    /// Whether any station has rotary inertia (a section of mass per length alone has none).
    pub fn rotary(&self) -> bool {
        self.stations.iter().any(|s| s.rotary != [0.0; 3])
    }

    /// Whether it was made for `flexure` (its subintervals and orders).
    pub fn fits(&self, flexure: &SpatialFlexure) -> bool {
        self.stations.len() == 3 * flexure.subintervals() && self.width == flexure.width()
    }
}

/// Three nodes' shape values `rows` (rows of `width`) of a step of length `h` as
/// they enter its exponent's $w_1 = hu_2$, $w_2 = \frac{\sqrt{15}h}3(u_3 - u_1)$ and
/// $w_3 = \frac{10h}3(u_3 - 2u_2 + u_1)$ ([`Exponent::alphas`]): three rows of `width`.
fn by_alphas(rows: &[f64], width: usize, h: f64) -> Vec<f64> {
    let (s, q) = (15f64.sqrt() * h / 3.0, 10.0 * h / 3.0);
    let node = |g: usize, i: usize| rows[g * width + i];
    let mut out = Vec::with_capacity(3 * width);
    out.extend((0..width).map(|i| h * node(1, i)));
    out.extend((0..width).map(|i| s * (node(2, i) - node(0, i))));
    out.extend((0..width).map(|i| q * (node(2, i) - 2.0 * node(1, i) + node(0, i))));
    out
}

/// The stations' frames and derivatives at one configuration, in the
/// flexure's root frame (the Data of [`stations_update`]).
#[derive(Debug, Clone)]
pub struct StationKinematics {
    /// $R_k$: the section axes at each station.
    pub rotation: Vec<Matrix3<f64>>,
    /// $p_k$ (m).
    pub position: Vec<Vector3<f64>>,
    /// $\partial_a(R_k)R_k^T$'s axial vector, the section's rotation per
    /// unit $\alpha_a$, at `[k * n + a]` (at [`Level::Jacobian`] and up).
    pub omega: Vec<Vector3<f64>>,
    /// $\partial_ap_k$ at `[k * n + a]` (m; at [`Level::Jacobian`] and up).
    pub velocity: Vec<Vector3<f64>>,
    /// The first moment $S = \sum_kw_k\mu_kp_k$ (kg·m).
    pub moment: Vector3<f64>,
    /// $\partial_a\partial_bS$ at `[a * n + b]` (kg·m; at [`Level::Hessian`]).
    pub moment_hessian: Vec<Vector3<f64>>,
    /// Each station's motion under a rate $\dot\alpha$ at $\ddot\alpha = 0$
    /// ([`Motion`]: $\omega_k$, $\dot p_k$, $\dot\omega_k$, $\ddot p_k$), filled by [`stations_dynamics_update`].
    pub(crate) rates: Vec<Motion>,
    /// The tip's, in the same form.
    pub(crate) tip: Motion,
    main: SpatialKinematics,
    scratch: SpatialKinematics,
}

impl StationKinematics {
    /// Buffers for `flexure` and its `quadrature`.
    pub fn new(flexure: &SpatialFlexure, quadrature: &MassQuadrature) -> Self {
        let (k, n) = (quadrature.stations.len(), flexure.coordinates());
        StationKinematics {
            rotation: vec![Matrix3::identity(); k],
            position: vec![Vector3::zeros(); k],
            omega: vec![Vector3::zeros(); k * n],
            velocity: vec![Vector3::zeros(); k * n],
            moment: Vector3::zeros(),
            moment_hessian: vec![Vector3::zeros(); n * n],
            rates: vec![[Vector3::zeros(); 4]; k],
            tip: [Vector3::zeros(); 4],
            main: SpatialKinematics::new(flexure),
            scratch: SpatialKinematics::new(flexure),
        }
    }

    /// The tip's motion subspace in the root frame after a pass at
    /// [`Level::Jacobian`]: $\omega_a$ and $\partial_ap$ of each coordinate, the columns
    /// a joint's [`crate::mechanism::JointState::jacobian`] holds, carried by the same pass as the stations'.
    pub(crate) fn tip_columns(&self) -> (&[Vector3<f64>], &[Vector3<f64>]) {
        (&self.main.turning, &self.main.moving)
    }

    /// Whether these buffers fit `flexure` and `quadrature`.
    pub fn fits(&self, flexure: &SpatialFlexure, quadrature: &MassQuadrature) -> bool {
        self.position.len() == quadrature.stations.len() && self.main.fits(flexure)
    }
}

/// Fills `out` with the stations' frames at `alpha`, and to `level` their
/// Jacobians and the first moment's Hessian (module docs), in one pass
/// over the subintervals. Does not allocate.
///
/// # Panics
/// If `alpha` does not have one entry per coordinate, or `quadrature` or
/// `out` were made for another flexure.
///
/// # Example
/// ```
/// use flexure::kinematics::Level;
/// use flexure::section::{Profile, SpatialSection};
/// use flexure::spatial::{MassQuadrature, SpatialFlexure, StationKinematics, stations_update};
/// let f = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [1, 1, 1]).unwrap()
///     .with_mass_per_length(Profile::Constant(1.0)).unwrap();
/// let q = MassQuadrature::new(&f).unwrap();
/// let mut k = StationKinematics::new(&f, &q);
/// // A circle's arc of κ_z = 1: each station on it, x = sin s, y = 1 − cos s.
/// stations_update(&f, &q, &[0.0, 0.0, 1.0], Level::Jacobian, &mut k);
/// for (st, p) in q.stations().iter().zip(&k.position) {
///     assert!((p.x - st.s.sin()).abs() < 1e-15 && (p.y - (1.0 - st.s.cos())).abs() < 1e-15);
/// }
/// // ∂p/∂α_z at the station s: the arc's growth, ((s cos s − sin s)/1, …) for α_z = 1.
/// let (s, v) = (q.stations()[5].s, k.velocity[5 * 3 + 2]);
/// assert!((v.x - (s * s.cos() - s.sin())).abs() < 1e-14);
/// ```
pub fn stations_update(
    flexure: &SpatialFlexure,
    quadrature: &MassQuadrature,
    alpha: &[f64],
    level: Level,
    out: &mut StationKinematics,
) {
    check(flexure, quadrature, alpha, out);
    match level {
        Level::Hessian => hessian_pass(flexure, quadrature, alpha, out),
        Level::Jacobian => root_pass::<false>(flexure, quadrature, alpha, 1, None, out),
        Level::Pose => root_pass::<false>(flexure, quadrature, alpha, 0, None, out),
    }
}

/// [`stations_update`] at [`Level::Jacobian`] for the dynamics, each
/// step's exponent and images along its $w_1, w_2, w_3$ (`root_pass`'s `ALPHAS`: equal to
/// rounding, cheaper), and with a rate `rate` the stations' and the tip's
/// motion under it at $\ddot\alpha = 0$ into `out.rates` and `out.tip`: their
/// exact second derivatives contracted with the rate twice, carried
/// through the same pass in the root frame (`kinematics::carry_motion`).
pub(crate) fn stations_dynamics_update(
    flexure: &SpatialFlexure,
    quadrature: &MassQuadrature,
    alpha: &[f64],
    rate: Option<&[f64]>,
    out: &mut StationKinematics,
) {
    assert!(rate.is_none_or(|u| u.len() == alpha.len()), "rate must have one entry per coordinate");
    check(flexure, quadrature, alpha, out);
    root_pass::<true>(flexure, quadrature, alpha, 1, rate, out);
}

fn check(flexure: &SpatialFlexure, quadrature: &MassQuadrature, alpha: &[f64], out: &StationKinematics) {
    assert_eq!(alpha.len(), flexure.coordinates(), "alpha must have one entry per coordinate");
    assert!(quadrature.fits(flexure) && out.fits(flexure, quadrature), "mass buffers made for another flexure");
}

/// The pass to `order` 0 or 1 in the root frame: each station one partial
/// step from the tip's root-frame columns at its subinterval's start
/// (`kinematics::jacobian_pass`'s recursion, the station's step's images
/// added to a copy of them), with the rate's motion at order 1 when asked.
/// With `ALPHAS` (the dynamics) each step's exponent is made from the sums
/// of the coordinates on the tables of [`by_alphas`] and its images are
/// along its $w_1, w_2, w_3$ ([`images_alphas`]); without (the statics, whose
/// answers stay bit for bit), from the nodal curvatures ([`images`]).
fn root_pass<const ALPHAS: bool>(
    flexure: &SpatialFlexure,
    quadrature: &MassQuadrature,
    alpha: &[f64],
    order: usize,
    rate: Option<&[f64]>,
    out: &mut StationKinematics,
) {
    // Fixed sizes for equal orders 2 to 4: the nodal sums unroll (the same sums, in the same order).
    match (flexure.orders(), quadrature.width) {
        ([2, 2, 2], 2) => root_pass_with::<ALPHAS>(flexure, quadrature, alpha, order, rate, out, |rows, x| {
            fixed_curvatures::<2>(rows, x)
        }),
        ([3, 3, 3], 3) => root_pass_with::<ALPHAS>(flexure, quadrature, alpha, order, rate, out, |rows, x| {
            fixed_curvatures::<3>(rows, x)
        }),
        ([4, 4, 4], 4) => root_pass_with::<ALPHAS>(flexure, quadrature, alpha, order, rate, out, |rows, x| {
            fixed_curvatures::<4>(rows, x)
        }),
        (orders, w) => root_pass_with::<ALPHAS>(flexure, quadrature, alpha, order, rate, out, |rows, alpha| {
            let g = |g: usize| row_curvature(&rows[g * w..(g + 1) * w], orders, alpha);
            [g(0), g(1), g(2)]
        }),
    }
}

/// The nodal curvatures at the three nodes whose shape values are `rows`, for orders `[N, N, N]`.
#[inline(always)]
fn fixed_curvatures<const N: usize>(rows: &[f64], alpha: &[f64]) -> [Vector3<f64>; 3] {
    let (rows, alpha) = (&rows[..3 * N], &alpha[..3 * N]);
    let mut out = [Vector3::zeros(); 3];
    for (g, node) in out.iter_mut().enumerate() {
        for c in 0..3 {
            let mut sum = 0.0;
            for i in 0..N {
                sum += rows[g * N + i] * alpha[c * N + i];
            }
            node[c] = sum;
        }
    }
    out
}

/// [`root_pass`] with the sums `curvatures(rows, x)` of the coordinates or a rate `x` on a step's shape rows `rows`
/// (for a rate, its change of them: $\sum_a\dot\alpha_a\partial_a$ of the sums, which are linear).
#[inline(always)]
fn root_pass_with<const ALPHAS: bool>(
    flexure: &SpatialFlexure,
    quadrature: &MassQuadrature,
    alpha: &[f64],
    order: usize,
    rate: Option<&[f64]>,
    out: &mut StationKinematics,
    curvatures: impl Fn(&[f64], &[f64]) -> [Vector3<f64>; 3],
) {
    let (m, w) = (flexure.subintervals(), quadrature.width);
    let h = flexure.length() / m as f64;
    let order = if rate.is_some() { 2 } else { order };
    let partial = if ALPHAS { &quadrature.partial_alphas } else { &quadrature.partial };
    let exponent =
        |sums: &[Vector3<f64>; 3], h: f64| if ALPHAS { Exponent::with_alphas(sums, h) } else { Exponent::new(sums, h) };
    let images_into = |e: &Exponent<f64>, step: &Step<f64>, r: &Matrix3<f64>, out: &mut Images<f64>| {
        if ALPHAS {
            images_alphas(e, step, r, out);
        } else {
            *out = images(e, step, r);
        }
    };
    let (mut r, mut p) = (Matrix3::identity(), Vector3::zeros());
    out.moment = Vector3::zeros();
    out.main.turning.fill(Vector3::zeros());
    out.main.moving.fill(Vector3::zeros());
    let (mut motion, mut images): (Motion, _) = ([Vector3::zeros(); 4], Images::default());
    // The rate's motion carried over a step from the frame of rotation r.
    let carried = |from: &Motion,
                   rows: &[f64],
                   e: &Exponent<f64>,
                   step: &Step<f64>,
                   images: &Images<f64>,
                   arm: &Vector3<f64>,
                   r: &Matrix3<f64>| {
        let along = curvatures(rows, rate.expect("a rate"));
        let (first, second) = if ALPHAS { e.along_alphas(&along) } else { e.along(&along) };
        carry_motion(from, first, second, step, r, images, arm)
    };
    for k in 0..m {
        for (j, tau) in NODES.iter().enumerate() {
            let station = 3 * k + j;
            let rows = &partial[station * 3 * w..(station + 1) * 3 * w];
            let e = exponent(&curvatures(rows, alpha), tau * h);
            let (wv, v) = e.value();
            let step = Step::new(wv, v, order);
            let (rs, arm) = (r * step.r, r * step.p);
            let ps = p + arm;
            out.rotation[station] = rs;
            out.position[station] = ps;
            out.moment += ps * quadrature.stations[station].mass;
            if order >= 1 {
                images_into(&e, &step, &r, &mut images);
                station_columns(flexure, &out.main, rows, &images, &arm, station, (&mut out.omega, &mut out.velocity));
                if rate.is_some() {
                    out.rates[station] = carried(&motion, rows, &e, &step, &images, &arm, &r);
                }
            }
        }
        let rows = if ALPHAS { &quadrature.whole_alphas[k * 3 * w..(k + 1) * 3 * w] } else { flexure.shapes(k) };
        let e = exponent(&curvatures(rows, alpha), h);
        let (wv, v) = e.value();
        let step = Step::new(wv, v, order);
        let (rs, arm) = (r * step.r, r * step.p);
        if order >= 1 {
            images_into(&e, &step, &r, &mut images);
            carry(&mut out.main, flexure, rows, &images, &arm);
            if rate.is_some() {
                motion = carried(&motion, rows, &e, &step, &images, &arm, &r);
            }
        }
        p += arm;
        r = rs;
    }
    if rate.is_some() {
        out.tip = motion;
    }
}

/// The pass at [`Level::Hessian`], in the body frame: every station's
/// partial step carries the tip's columns and their derivatives
/// (`kinematics::advance`), for the first moment's Hessian.
fn hessian_pass(flexure: &SpatialFlexure, quadrature: &MassQuadrature, alpha: &[f64], out: &mut StationKinematics) {
    let (n, m, w) = (flexure.coordinates(), flexure.subintervals(), quadrature.width);
    let h = flexure.length() / m as f64;
    let orders = flexure.orders();
    let (mut r, mut p) = (Matrix3::identity(), Vector3::zeros());
    out.main.columns.fill(Vector6::zeros());
    out.main.hessian.fill(Vector6::zeros());
    out.moment_hessian.fill(Vector3::zeros());
    out.moment = Vector3::zeros();
    let twist = |row: &[f64]| {
        let u = row_curvature(row, orders, alpha);
        Vector6::new(u[0], u[1], u[2], 1.0, 0.0, 0.0)
    };
    for k in 0..m {
        for (j, tau) in NODES.iter().enumerate() {
            let station = 3 * k + j;
            let rows = &quadrature.partial[station * 3 * w..(station + 1) * 3 * w];
            let xi: [Vector6<f64>; 3] = std::array::from_fn(|g| twist(&rows[g * w..(g + 1) * w]));
            let scratch = &mut out.scratch;
            scratch.columns.copy_from_slice(&out.main.columns);
            scratch.hessian.copy_from_slice(&out.main.hessian);
            let step = advance(scratch, &xi, |a| nodal(flexure, rows, a), tau * h, 2);
            let (rs, ps) = (r * step.r, p + r * step.p);
            out.rotation[station] = rs;
            out.position[station] = ps;
            let mass = quadrature.stations[station].mass;
            out.moment += ps * mass;
            let part = |x: &Vector6<f64>| (Vector3::new(x[0], x[1], x[2]), Vector3::new(x[3], x[4], x[5]));
            for a in 0..n {
                let (wa, va) = part(&scratch.columns[a]);
                out.omega[station * n + a] = rs * wa;
                out.velocity[station * n + a] = rs * va;
            }
            if mass != 0.0 {
                for a in 0..n {
                    let va = part(&scratch.columns[a]).1;
                    for b in 0..n {
                        let wb = part(&scratch.columns[b]).0;
                        let hab = part(&scratch.hessian[a * n + b]).1;
                        out.moment_hessian[a * n + b] += rs * (wb.cross(&va) + hab) * mass;
                    }
                }
            }
        }
        let rows = flexure.shapes(k);
        let xi: [Vector6<f64>; 3] = std::array::from_fn(|g| twist(&rows[g * w..(g + 1) * w]));
        let step = advance(&mut out.main, &xi, |a| nodal(flexure, rows, a), h, 2);
        p += r * step.p;
        r *= step.r;
    }
}

/// Coordinate `a`'s nodal twist derivatives $(\partial_au(s_g), 0)$ at the nodes whose shape values are `rows`.
fn nodal(flexure: &SpatialFlexure, rows: &[f64], a: usize) -> [Vector6<f64>; 3] {
    let (w, (c, i)) = (flexure.width(), flexure.component(a));
    std::array::from_fn(|g| {
        let mut d = Vector6::zeros();
        d[c] = rows[g * w + i];
        d
    })
}

/// A station's root-frame columns into `into` (its $\omega_{k,a}$ and
/// $\partial_ap_k$ at `[station * n + a]`): the tip's at its subinterval's
/// start, `main`'s, carried over its partial step as `kinematics::jacobian_pass`
/// carries them over a whole one, $\omega_{k,a} = \omega_a + \delta\omega_a$ and
/// $\partial_ap_k = \partial_ap + \omega_a\times Rp_k + \delta p_a$, with the
/// step's `images` and `arm` $= Rp_k$.
fn station_columns(
    flexure: &SpatialFlexure,
    main: &SpatialKinematics,
    rows: &[f64],
    images: &Images<f64>,
    arm: &Vector3<f64>,
    station: usize,
    into: (&mut [Vector3<f64>], &mut [Vector3<f64>]),
) {
    let n = flexure.coordinates();
    let (omega, velocity) = into;
    increments(flexure, images, rows, |a, dw, dp| {
        omega[station * n + a] = main.turning[a] + dw;
        velocity[station * n + a] = main.moving[a] + main.turning[a].cross(arm) + dp;
    });
}

#[cfg(test)]
mod tests {
    use super::super::kinematics::{Rate, carry_rate, rate_direction, update_rate};
    use super::*;
    use crate::section::{Profile, SpatialSection};

    /// The largest difference of two lists of vectors, against the largest entry of the first.
    fn apart(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
        let size = a.iter().fold(0.0_f64, |m, x| m.max(x.amax()));
        a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).amax())) / size
    }

    /// The dynamics' pass (its exponents from the tables of $w_1, w_2, w_3$,
    /// its images along them, the rate's motion carried in the root frame)
    /// meets the statics' pass (nodal curvatures) in the stations' frames and
    /// columns, and the body-frame recursion it replaced (`carry_rate` on
    /// each step, turned into the root frame at each station) in the
    /// stations' and the tip's motion, to 1e-13 of each quantity's largest
    /// entry: equal orders (the unrolled sums) and unequal ones.
    #[test]
    fn the_dynamics_pass_meets_the_statics_pass_and_the_body_frame_rate() {
        for orders in [[4, 4, 4], [3, 2, 4]] {
            let f = SpatialFlexure::new(10.0, SpatialSection::uniform(1e3, 1e3, 1e3).unwrap(), orders)
                .unwrap()
                .with_mass_per_length(Profile::Constant(1.0))
                .unwrap();
            let (quadrature, n, w) = (MassQuadrature::new(&f).unwrap(), f.coordinates(), f.width());
            let alpha: Vec<f64> = (0..n).map(|i| 0.3 * (i as f64 * 1.3 + 0.2).sin()).collect();
            let rate: Vec<f64> = (0..n).map(|i| 0.5 * (1.9 * i as f64 + 0.5).cos()).collect();
            let (mut old, mut new) = (StationKinematics::new(&f, &quadrature), StationKinematics::new(&f, &quadrature));
            stations_update(&f, &quadrature, &alpha, Level::Jacobian, &mut old);
            stations_dynamics_update(&f, &quadrature, &alpha, Some(&rate), &mut new);
            let rotation = |k: &StationKinematics| -> Vec<Vector3<f64>> {
                k.rotation.iter().flat_map(|r| [0, 1, 2].map(|c| r.column(c).into_owned())).collect()
            };
            for (what, d) in [
                ("rotation", apart(&rotation(&old), &rotation(&new))),
                ("position", apart(&old.position, &new.position)),
                ("omega", apart(&old.omega, &new.omega)),
                ("velocity", apart(&old.velocity, &new.velocity)),
            ] {
                assert!(d < 1e-13, "orders {orders:?}: {what} apart by {d:e}");
            }
            // The body-frame recursion, step by step as the pass takes them.
            let h = f.length() / f.subintervals() as f64;
            let (mut state, mut r, mut rates) = (Rate::default(), Matrix3::identity(), Vec::new());
            let curvatures = |rows: &[f64]| std::array::from_fn(|g| row_curvature(&rows[g * w..], orders, &alpha));
            for k in 0..f.subintervals() {
                for (j, tau) in NODES.iter().enumerate() {
                    let rows = &quadrature.partial[(3 * k + j) * 3 * w..];
                    let e = Exponent::new(&curvatures(rows), tau * h);
                    let (wv, v) = e.value();
                    let (step, mut s) = (Step::new(wv, v, 2), state);
                    carry_rate(&mut s, &e, &step, &rate_direction(&f, rows, &rate));
                    rates.extend(s.in_root(&(r * step.r)));
                }
                let e = Exponent::new(&curvatures(f.shapes(k)), h);
                let (wv, v) = e.value();
                let step = Step::new(wv, v, 2);
                carry_rate(&mut state, &e, &step, &rate_direction(&f, f.shapes(k), &rate));
                r *= step.r;
            }
            let flat: Vec<Vector3<f64>> = new.rates.iter().flatten().copied().collect();
            for part in 0..4 {
                let pick = |v: &[Vector3<f64>]| v.iter().skip(part).step_by(4).copied().collect::<Vec<_>>();
                let d = apart(&pick(&rates), &pick(&flat));
                assert!(d < 1e-13, "orders {orders:?}: the stations' motion, part {part}, apart by {d:e}");
            }
            let tip = update_rate(&f, &alpha, &rate, &mut SpatialKinematics::new(&f));
            let tip = tip.in_root(&r);
            let d = apart(&tip, &new.tip);
            assert!(d < 1e-13, "orders {orders:?}: the tip's motion apart by {d:e}");
        }
    }
}
