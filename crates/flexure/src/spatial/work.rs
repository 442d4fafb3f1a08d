//! The generalized force of a dead tip wrench, and its derivative, by
//! quadrature of the virtual work along the flexure.
//!
//! A tip moment $M$ and force $F$ fixed in the root frame load the section
//! at $s$ with the moment $m(s) = M + (p(L) - p(s))\times F$ about its
//! centre. A change $\delta\alpha_a$ turns the section by
//! $P_a(s)\thinspace\delta\alpha_a$ about its director $d_c = Re_c$ (the
//! component $c$ of coordinate $a$, $P_a$ its shape $\tilde P_i(s/L)/L$),
//! so the virtual work is (the spatial form of $J^Tw$, Eq. 22)
//! $$Q_a = \int_0^L P_a(s)\thinspace d_c(s)\cdot m(s)\thinspace ds.$$
//! With $\omega_b(s) = \int_0^s P_b\thinspace d_{c(b)}$ the rotation of
//! the section at $s$ per unit $\alpha_b$ (root frame) and
//! $\partial_bp(s) = \int_0^s\omega_b\times d_x$ its displacement, the
//! derivative is
//! $$\partial_bQ_a = \int_0^L P_a\big(\omega_b\cdot(d_c\times m) +
//!   (\partial_bp(L) - \partial_bp)\cdot(F\times d_c)\big)\thinspace ds.$$
//! Both integrals are taken by the three-point Gauss rule on each Magnus
//! subinterval (exact to degree 5, as SoRoSim takes its generalized
//! forces), with the frames at the Gauss nodes from the same 6th-order
//! Magnus step taken from the subinterval's start; the running integrals
//! $\omega_b$ and $\partial_bp$ at the nodes come from the degree-4
//! interpolant through the subinterval's ends and nodes. So every node
//! costs $O(n)$ and the derivative $O(n^2)$ per node, with no second
//! derivative of the Magnus exponential: the quadrature and the Magnus
//! product's exact $J^Tw$ agree to the discretization's $h^6$
//! (`tests/spatial_statics.rs` measures it).

use super::SpatialFlexure;
use super::kinematics::row_curvature as curvature;
use super::magnus::{NODES, exponential as step};
use crate::basis;
use crate::error::Result;
use crate::scalar::Scalar;
use nalgebra::{DMatrix, DMatrixViewMut, Matrix3, SMatrix, Vector3};

/// The three-point Gauss weights on $[0, 1]$, for [`NODES`].
const WEIGHTS: [f64; 3] = [5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0];

/// Points of a subinterval where frames are kept: its start, its three Gauss nodes, its end.
const POINTS: usize = 5;

/// The quadrature's tables for one flexure: shape values and the running integral's weights.
#[derive(Debug, Clone)]
pub(crate) struct Quadrature {
    width: usize,
    /// $\tilde P_i(t)/L$ at the [`POINTS`] of subinterval $k$, `[(k * POINTS + m) * width + i]`.
    points: Vec<f64>,
    /// $\tilde P_i(t)/L$ at the Gauss nodes of the partial step from the
    /// start of subinterval $k$ to its node $j$, `[((k * 3 + j) * 3 + g) * width + i]`.
    partial: Vec<f64>,
    /// $\int_0^{\tau_j}\ell_m$, the Lagrange basis on the [`POINTS`] (as fractions of the subinterval).
    running: [[f64; POINTS]; 3],
    /// $\tilde P_i(t)/L$ at the Gauss nodes, `[(i, k * 3 + j)]`: the left
    /// factor of [`load_derivative`]'s product at many coordinates.
    nodes: DMatrix<f64>,
    /// Each coordinate's (component, Legendre index).
    components: Vec<(usize, usize)>,
    /// Each component's coordinates, (first, count): the coordinates are in component order.
    blocks: [(usize, usize); 3],
}

impl Quadrature {
    pub fn new(flexure: &SpatialFlexure) -> Self {
        let (m, width, l) = (flexure.subintervals(), flexure.width(), flexure.length());
        let mut row = vec![0.0; width];
        let mut shape = |t: f64, out: &mut Vec<f64>| {
            basis::shifted_legendre(t, &mut row);
            out.extend(row.iter().map(|v| v / l));
        };
        let (mut points, mut partial) = (Vec::new(), Vec::new());
        let at = [0.0, NODES[0], NODES[1], NODES[2], 1.0];
        for k in 0..m {
            for t in at {
                shape((k as f64 + t) / m as f64, &mut points);
            }
            for tau in NODES {
                for g in NODES {
                    shape((k as f64 + tau * g) / m as f64, &mut partial);
                }
            }
        }
        let components = (0..flexure.coordinates()).map(|a| flexure.component(a)).collect();
        let orders = flexure.orders();
        let blocks = [(0, orders[0]), (orders[0], orders[1]), (orders[0] + orders[1], orders[2])];
        let nodes = DMatrix::from_fn(width, 3 * m, |i, g| points[((g / 3) * POINTS + 1 + g % 3) * width + i]);
        Quadrature { width, points, partial, running: running(at), nodes, components, blocks }
    }

    fn fits(&self, flexure: &SpatialFlexure) -> bool {
        self.components.len() == flexure.coordinates()
            && self.points.len() == flexure.subintervals() * POINTS * self.width
    }
}

/// $\int_0^{\tau_j}\ell_m(\tau)\thinspace d\tau$ for the Lagrange basis $\ell_m$ on `at`.
fn running(at: [f64; POINTS]) -> [[f64; POINTS]; 3] {
    let v = SMatrix::<f64, POINTS, POINTS>::from_fn(|i, p| at[i].powi(p as i32));
    // ℓ_m(τ) = Σ_p C[p, m] τ^p with C = V⁻¹; the points are distinct, so V is invertible.
    let c = v.try_inverse().unwrap_or_else(SMatrix::zeros);
    std::array::from_fn(|j| {
        let tau = NODES[j];
        std::array::from_fn(|m| (0..POINTS).map(|p| c[(p, m)] * tau.powi(p as i32 + 1) / (p as f64 + 1.0)).sum())
    })
}

/// The frames and running integrals of one evaluation (the Data).
#[derive(Debug, Clone)]
pub(crate) struct Work<T: Scalar> {
    rotations: Vec<Matrix3<T>>,
    positions: Vec<Vector3<T>>,
    /// The section moment $m$ (root frame) at each point; kept at the Gauss nodes.
    loads: Vec<Vector3<T>>,
    /// $\omega_b$ and $\partial_bp$ at each point, `[point * n + b]`.
    omega: Vec<Vector3<T>>,
    displacement: Vec<Vector3<T>>,
    /// $Q$, and $\partial_bQ_a$ at `[b * n + a]`.
    pub force: Vec<T>,
    pub derivative: Vec<T>,
    /// At many coordinates, [`load_derivative`]'s factors: the Gauss-node
    /// shapes (made on first use) and, per component, the integrand's
    /// other factor at each node, `[(k * 3 + j, b)]`.
    nodes: DMatrix<T>,
    integrands: [DMatrix<T>; 3],
}

impl<T: Scalar> Work<T> {
    pub fn new(flexure: &SpatialFlexure) -> Self {
        let (p, n) = (flexure.subintervals() * POINTS, flexure.coordinates());
        Work {
            rotations: vec![Matrix3::identity(); p],
            positions: vec![Vector3::zeros(); p],
            loads: vec![Vector3::zeros(); p],
            omega: vec![Vector3::zeros(); p * n],
            displacement: vec![Vector3::zeros(); p * n],
            force: vec![T::zero(); n],
            derivative: vec![T::zero(); n * n],
            nodes: DMatrix::zeros(0, 0),
            integrands: std::array::from_fn(|_| DMatrix::zeros(0, 0)),
        }
    }
}

/// Fills `work.force` with $Q$ (module docs) of the tip wrench
/// `(moment, force)` at `alpha`, and with `derivative` also
/// `work.derivative` with $\partial_bQ_a$. Does not allocate.
pub(crate) fn evaluate<T: Scalar>(
    flexure: &SpatialFlexure,
    quadrature: &Quadrature,
    alpha: &[T],
    (moment, force): (Vector3<T>, Vector3<T>),
    derivative: bool,
    work: &mut Work<T>,
) {
    let (m, w) = (flexure.subintervals(), quadrature.width);
    let orders = flexure.orders();
    let h = flexure.length() / m as f64;
    let (mut r, mut p) = (Matrix3::identity(), Vector3::zeros());
    for k in 0..m {
        let base = k * POINTS;
        work.rotations[base] = r;
        work.positions[base] = p;
        for (j, tau) in NODES.iter().enumerate() {
            let rows = &quadrature.partial[(k * 3 + j) * 3 * w..(k * 3 + j + 1) * 3 * w];
            let u = std::array::from_fn(|g| curvature(&rows[g * w..(g + 1) * w], orders, alpha));
            let (rj, pj) = step(&u, tau * h);
            work.rotations[base + 1 + j] = r * rj;
            work.positions[base + 1 + j] = p + r * pj;
        }
        let rows = &quadrature.points[(base + 1) * w..(base + 4) * w];
        let u = std::array::from_fn(|g| curvature(&rows[g * w..(g + 1) * w], orders, alpha));
        let (rk, pk) = step(&u, h);
        p += r * pk;
        r *= rk;
        work.rotations[base + 4] = r;
        work.positions[base + 4] = p;
    }
    let tip = p;
    work.force.fill(T::zero());
    for k in 0..m {
        for j in 0..3 {
            let point = k * POINTS + 1 + j;
            let weight = T::c(WEIGHTS[j] * h);
            let load = moment + (tip - work.positions[point]).cross(&force);
            work.loads[point] = load;
            let turned = work.rotations[point].tr_mul(&load);
            let row = &quadrature.points[point * w..(point + 1) * w];
            for (c, &(start, len)) in quadrature.blocks.iter().enumerate() {
                let per = weight * turned[c];
                for (q, &p) in work.force[start..start + len].iter_mut().zip(&row[..len]) {
                    *q += T::c(p) * per;
                }
            }
        }
    }
    if derivative {
        running_integrals(flexure, quadrature, work);
        load_derivative(flexure, quadrature, force, work);
    }
}

/// $\omega_b$ and $\partial_bp$ at every point, from the frames in `work`.
fn running_integrals<T: Scalar>(flexure: &SpatialFlexure, quadrature: &Quadrature, work: &mut Work<T>) {
    let (m, n, w) = (flexure.subintervals(), flexure.coordinates(), quadrature.width);
    let h = flexure.length() / m as f64;
    for (b, &(c, i)) in quadrature.components.iter().enumerate() {
        let (mut omega, mut moved) = (Vector3::zeros(), Vector3::zeros());
        for k in 0..m {
            let base = k * POINTS;
            // The integrands at the five points: P_b d_c, then ω_b × d_x.
            let turn: [Vector3<T>; POINTS] = std::array::from_fn(|q| {
                let shape = T::c(quadrature.points[(base + q) * w + i] * h);
                work.rotations[base + q].column(c) * shape
            });
            let mut omegas = [omega; POINTS];
            for j in 0..3 {
                omegas[1 + j] = omega + weighted(&quadrature.running[j], &turn);
            }
            omegas[4] = omega + gauss(&turn);
            let along: [Vector3<T>; POINTS] =
                std::array::from_fn(|q| omegas[q].cross(&work.rotations[base + q].column(0).into_owned()) * T::c(h));
            let mut moves = [moved; POINTS];
            for j in 0..3 {
                moves[1 + j] = moved + weighted(&quadrature.running[j], &along);
            }
            moves[4] = moved + gauss(&along);
            for q in 0..POINTS {
                work.omega[(base + q) * n + b] = omegas[q];
                work.displacement[(base + q) * n + b] = moves[q];
            }
            (omega, moved) = (omegas[4], moves[4]);
        }
    }
}

/// The three-point Gauss rule on a subinterval of the five `values` (its nodes are the middle three).
#[inline(always)]
fn gauss<T: Scalar>(values: &[Vector3<T>; POINTS]) -> Vector3<T> {
    values[1] * T::c(WEIGHTS[0]) + values[2] * T::c(WEIGHTS[1]) + values[3] * T::c(WEIGHTS[2])
}

#[inline(always)]
fn weighted<T: Scalar>(weights: &[f64; POINTS], values: &[Vector3<T>; POINTS]) -> Vector3<T> {
    let mut sum = Vector3::zeros();
    for (&c, v) in weights.iter().zip(values) {
        sum += v * T::c(c);
    }
    sum
}

/// $\partial_bQ_a$ (module docs) into `work.derivative`, from the section
/// moments and running integrals in `work` and the tip `force`.
fn load_derivative<T: Scalar>(
    flexure: &SpatialFlexure,
    quadrature: &Quadrature,
    force: Vector3<T>,
    work: &mut Work<T>,
) {
    let (m, n, w) = (flexure.subintervals(), flexure.coordinates(), quadrature.width);
    let h = flexure.length() / m as f64;
    let last = m * POINTS - 1;
    if n > PRODUCT {
        return load_derivative_product(flexure, quadrature, force, work);
    }
    work.derivative.fill(T::zero());
    for k in 0..m {
        for j in 0..3 {
            let point = k * POINTS + 1 + j;
            let weight = T::c(WEIGHTS[j] * h);
            let (turning, pulling) = factors(work, point, &force);
            let row = &quadrature.points[point * w..(point + 1) * w];
            for b in 0..n {
                let omega = work.omega[point * n + b];
                let moved = work.displacement[last * n + b] - work.displacement[point * n + b];
                let per: [T; 3] = std::array::from_fn(|c| weight * (omega.dot(&turning[c]) + moved.dot(&pulling[c])));
                let column = &mut work.derivative[b * n..(b + 1) * n];
                for (c, &(start, len)) in quadrature.blocks.iter().enumerate() {
                    for (dq, &p) in column[start..start + len].iter_mut().zip(&row[..len]) {
                        *dq += T::c(p) * per[c];
                    }
                }
            }
        }
    }
}

/// At the point `point`, for each director $d_c$: $d_c\times m$ and $F\times d_c$.
#[inline(always)]
fn factors<T: Scalar>(work: &Work<T>, point: usize, force: &Vector3<T>) -> ([Vector3<T>; 3], [Vector3<T>; 3]) {
    let load = work.loads[point];
    let rot = &work.rotations[point];
    let d: [Vector3<T>; 3] = std::array::from_fn(|c| rot.column(c).into_owned());
    (std::array::from_fn(|c| d[c].cross(&load)), std::array::from_fn(|c| force.cross(&d[c])))
}

/// Above this many coordinates [`load_derivative`] is taken as a matrix
/// product; at and below it, point by point as before (the same sums in
/// the same order, so the orders most files use keep their answers bit for bit).
const PRODUCT: usize = 18;

/// [`load_derivative`] as three matrix products, one per component $c$:
/// $\partial_bQ_a = \sum_g \tilde P_{i(a)}(t_g)\thinspace G_{gb}^{(c)}$ over the
/// Gauss nodes $g$, with
/// $G_{gb}^{(c)} = w_g\big(\omega_b\cdot(d_c\times m) + (\partial_bp(L) - \partial_bp)\cdot(F\times d_c)\big)$,
/// the same sum as the point-by-point loop ($O(Mn^2)$ either way), in a
/// blocked product: at orders [64, 64, 64] ($n = 192$, 3024 nodes) the loop
/// was two fifths of a solve's time.
fn load_derivative_product<T: Scalar>(
    flexure: &SpatialFlexure,
    quadrature: &Quadrature,
    force: Vector3<T>,
    work: &mut Work<T>,
) {
    let (m, n) = (flexure.subintervals(), flexure.coordinates());
    let h = flexure.length() / m as f64;
    let last = m * POINTS - 1;
    if work.nodes.shape() != quadrature.nodes.shape() {
        work.nodes = quadrature.nodes.map(T::c);
    }
    for g in &mut work.integrands {
        if g.shape() != (3 * m, n) {
            *g = DMatrix::zeros(3 * m, n);
        }
    }
    for k in 0..m {
        for j in 0..3 {
            let point = k * POINTS + 1 + j;
            let weight = T::c(WEIGHTS[j] * h);
            let (turning, pulling) = factors(work, point, &force);
            let row = k * 3 + j;
            for b in 0..n {
                let omega = work.omega[point * n + b];
                let moved = work.displacement[last * n + b] - work.displacement[point * n + b];
                for c in 0..3 {
                    work.integrands[c][(row, b)] = weight * (omega.dot(&turning[c]) + moved.dot(&pulling[c]));
                }
            }
        }
    }
    let mut derivative = DMatrixViewMut::from_slice(&mut work.derivative, n, n);
    for (c, &(start, len)) in quadrature.blocks.iter().enumerate() {
        derivative.rows_mut(start, len).gemm(T::one(), &work.nodes.rows(0, len), &work.integrands[c], T::zero());
    }
}

/// The generalized force $Q$ of the dead tip wrench `load` (root frame) at
/// coordinates `alpha` (module docs): the load's part of the equilibrium
/// $\nabla U = Q$ that [`super::deflect`] solves.
///
/// # Example
/// ```
/// use flexure::section::SpatialSection;
/// use flexure::spatial::{SpatialFlexure, SpatialLoad, generalized_force};
/// let f = SpatialFlexure::new(2.0, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [2, 2, 2]).unwrap();
/// // Straight, a tip force F_z bends about −y with the moment (L − s)F_z:
/// // Q for κ_y's first coefficient is −∫(L − s)F_z ds/L = −F_z L/2.
/// let q = generalized_force(&f, &SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 3.0] }, &[0.0; 6]).unwrap();
/// assert!((q[2] + 3.0).abs() < 1e-14 && q[0].abs() < 1e-15);
/// ```
pub fn generalized_force(flexure: &SpatialFlexure, load: &super::SpatialLoad, alpha: &[f64]) -> Result<Vec<f64>> {
    load.validate()?;
    flexure.check_coordinates("alpha", alpha)?;
    let quadrature = Quadrature::new(flexure);
    let mut work = Work::new(flexure);
    evaluate(flexure, &quadrature, alpha, (Vector3::from(load.moment), Vector3::from(load.force)), false, &mut work);
    Ok(work.force)
}

/// Whether `quadrature` and `work` were made for `flexure` (its coordinates and subintervals).
pub(crate) fn fits<T: Scalar>(flexure: &SpatialFlexure, quadrature: &Quadrature, work: &Work<T>) -> bool {
    quadrature.fits(flexure)
        && work.force.len() == flexure.coordinates()
        && work.rotations.len() == flexure.subintervals() * POINTS
}
