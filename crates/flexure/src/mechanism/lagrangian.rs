//! The potential of a mechanism, its exact derivatives, and its closures.
//!
//! $V(q) = \sum_j U_j(q_j) - \sum_k (F_k\cdot w_k + M_k\theta_k) -
//! \sum_b m_b\thinspace g\cdot w_b + \sum_t T_t\thinspace\ell_t(q)$
//! (elastic joints, point forces and moments, weights, tendons of constant
//! tension), and the closures $c(q) = 0$ with $G = \partial c/\partial q$.
//! Point derivatives come from [`super::kinematics::point`], chained
//! through the tree; a tendon of length $\ell = \sum_i\lvert d_i\rvert$,
//! $d_i = w_{i+1} - w_i$, has $\nabla\ell = \sum_i \partial d_i^T u_i$ and
//! $\nabla^2\ell = \sum_i \partial d_i^T(I - u_iu_i^T)\partial d_i/\lvert d_i\rvert + u_i\cdot\partial^2 d_i$.

use super::kinematics::{Frames, frames, point};
use super::{Closure, Loads, Mechanism};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix2};

/// The potential, its derivatives and the closures at one configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct Lagrangian {
    /// $V(q)$ (J).
    pub potential: f64,
    /// $\sum_j U_j$: the elastic part of $V$ (J).
    pub elastic: f64,
    /// $\nabla V$.
    pub gradient: DVector<f64>,
    /// $\nabla^2 V + \sum_i \mu_i\nabla^2 c_i$.
    pub hessian: DMatrix<f64>,
    /// $c(q)$: per weld $(\Delta x, \Delta y, \Delta\theta)$ (m, m, rad, the
    /// angle wrapped to $(-\pi, \pi]$), per pin $(\Delta x, \Delta y)$.
    pub closure: DVector<f64>,
    /// $G = \partial c/\partial q$.
    pub closure_jacobian: DMatrix<f64>,
}

pub(super) fn wrap(a: f64) -> f64 {
    a - std::f64::consts::TAU * (a / std::f64::consts::TAU).round()
}

pub(super) fn check_sizes(m: &Mechanism, q: &[f64], mu: &[f64], loads: &Loads) -> Result<()> {
    if q.len() != m.dof() {
        return Err(Error::invalid("q", format!("{} values", q.len()), "must have one value per coordinate"));
    }
    if mu.len() != m.constraints() {
        return Err(Error::invalid(
            "multipliers",
            format!("{} values", mu.len()),
            "must have one per closure equation",
        ));
    }
    if q.iter().chain(mu).any(|v| !v.is_finite()) {
        return Err(Error::invalid("q", format!("{q:?}"), "coordinates and multipliers must be finite"));
    }
    loads.validate(m)
}

/// $V$, $\nabla V$, $\nabla^2 V + \sum_i\mu_i\nabla^2 c_i$, $c$ and $G$ at `q`
/// under `loads` (exact derivatives; see [`Lagrangian`]).
///
/// # Example
/// ```
/// let m = flexure::mechanism::file::from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n",
/// )
/// .unwrap();
/// let l = flexure::mechanism::lagrangian::lagrangian(&m, &[0.5], &[], &m.loads()).unwrap();
/// // A torsional spring: V = k q²/2, ∇V = k q.
/// assert!((l.potential - 0.25).abs() < 1e-15 && (l.gradient[0] - 1.0).abs() < 1e-15);
/// ```
pub fn lagrangian(m: &Mechanism, q: &[f64], mu: &[f64], loads: &Loads) -> Result<Lagrangian> {
    check_sizes(m, q, mu, loads)?;
    assemble(m, &frames(m, q), mu, loads, true)
}

pub(super) fn assemble(m: &Mechanism, f: &Frames, mu: &[f64], loads: &Loads, with_hessian: bool) -> Result<Lagrangian> {
    let n = m.dof();
    let (mut gradient, mut hessian) = (DVector::zeros(n), DMatrix::zeros(n, n));
    let mut elastic = 0.0;
    for (j, s) in m.joints.iter().zip(&f.joints) {
        let k = s.gradient.len();
        elastic += s.energy;
        let mut g = gradient.rows_mut(j.offset, k);
        g += &s.gradient;
        if with_hessian {
            let mut h = hessian.view_mut((j.offset, j.offset), (k, k));
            h += &s.stiffness;
        }
    }
    let load = add_loads(m, f, loads, &mut gradient, with_hessian.then_some(&mut hessian))?;
    let rows = m.constraints();
    let (mut closure, mut g) = (DVector::zeros(rows), DMatrix::zeros(rows, n));
    add_closures(m, f, mu, &mut closure, &mut g, with_hessian.then_some(&mut hessian));
    Ok(Lagrangian { potential: elastic + load, elastic, gradient, hessian, closure, closure_jacobian: g })
}

/// Writes $c$ and $G$, and adds $\sum_i\mu_i\nabla^2 c_i$ to `hessian` if given.
pub(super) fn add_closures(
    m: &Mechanism,
    f: &Frames,
    mu: &[f64],
    closure: &mut DVector<f64>,
    g: &mut DMatrix<f64>,
    mut hessian: Option<&mut DMatrix<f64>>,
) {
    let mut row = 0;
    for c in &m.closures {
        let (a, ar, aphi, b, br, bphi, angle) = match *c {
            Closure::Weld { a, a_origin, b, b_origin } => {
                (a, [a_origin.x, a_origin.y], a_origin.phi, b, [b_origin.x, b_origin.y], b_origin.phi, true)
            }
            Closure::Pin { a, a_at, b, b_at } => (a, a_at, 0.0, b, b_at, 0.0, false),
        };
        let with_hessian = hessian.is_some();
        let (pa, pb) = (point(m, f, a, ar, with_hessian), point(m, f, b, br, with_hessian));
        for k in 0..2 {
            closure[row + k] = pa.position[k] - pb.position[k];
            g.row_mut(row + k).copy_from(&(pa.jacobian.row(1 + k) - pb.jacobian.row(1 + k)));
        }
        // The angle is linear in q for every joint kind: no Hessian term.
        if let (Some(h), Some([ax, ay]), Some([bx, by])) = (hessian.as_deref_mut(), &pa.hessian, &pb.hessian) {
            *h += (ax - bx) * mu[row] + (ay - by) * mu[row + 1];
        }
        if angle {
            closure[row + 2] = wrap(pa.angle + aphi - pb.angle - bphi);
            g.row_mut(row + 2).copy_from(&(pa.jacobian.row(0) - pb.jacobian.row(0)));
        }
        row += c.equations();
    }
}

/// $\sum_i\mu_i\nabla^2 c_i$ alone.
pub(super) fn closure_hessian(m: &Mechanism, f: &Frames, mu: &[f64]) -> DMatrix<f64> {
    let (n, rows) = (m.dof(), m.constraints());
    let mut h = DMatrix::zeros(n, n);
    add_closures(m, f, mu, &mut DVector::zeros(rows), &mut DMatrix::zeros(rows, n), Some(&mut h));
    h
}

/// Adds the loads' gradient (and Hessian) to `gradient` (`hessian`);
/// returns their potential.
pub(super) fn add_loads(
    m: &Mechanism,
    f: &Frames,
    loads: &Loads,
    gradient: &mut DVector<f64>,
    mut hessian: Option<&mut DMatrix<f64>>,
) -> Result<f64> {
    let n = m.dof();
    let mut potential = 0.0;
    // A force and moment at a point: V = −F·w − Mθ.
    let mut push = |body: usize, at: [f64; 2], force: [f64; 2], moment: f64, h: Option<&mut DMatrix<f64>>| {
        if force == [0.0; 2] && moment == 0.0 {
            return 0.0;
        }
        let p = point(m, f, body, at, h.is_some());
        for c in 0..n {
            gradient[c] -= force[0] * p.jacobian[(1, c)] + force[1] * p.jacobian[(2, c)] + moment * p.jacobian[(0, c)];
        }
        if let (Some(h), Some([hx, hy])) = (h, &p.hessian) {
            *h -= hx * force[0] + hy * force[1];
        }
        -(force[0] * p.position[0] + force[1] * p.position[1] + moment * p.angle)
    };
    for (p, l) in m.forces.iter().zip(&loads.force) {
        potential += push(p.body, p.at, [l[0], l[1]], l[2], hessian.as_deref_mut());
    }
    for (b, body) in m.bodies.iter().enumerate() {
        if body.mass > 0.0 {
            let weight = [body.mass * loads.gravity[0], body.mass * loads.gravity[1]];
            potential += push(b, body.com, weight, 0.0, hessian.as_deref_mut());
        }
    }
    // A tendon: V = T Σ|w_{i+1} − w_i|.
    for (t, &tension) in m.tendons.iter().zip(&loads.tension) {
        if tension == 0.0 {
            continue;
        }
        let pts: Vec<_> = t.path.iter().map(|&(b, r)| point(m, f, b, r, hessian.is_some())).collect();
        for (i, pair) in pts.windows(2).enumerate() {
            let (a, b) = (&pair[0], &pair[1]);
            let d = [b.position[0] - a.position[0], b.position[1] - a.position[1]];
            let len = d[0].hypot(d[1]);
            // Coincident to rounding: the direction u is undefined.
            let size = a.position.iter().chain(&b.position).map(|v| v.abs()).sum::<f64>();
            if len.is_nan() || len <= 1e-14 * size {
                return Err(Error::Singular {
                    what: format!("tendon {:?}: via points {} and {} coincide", t.name, i + 1, i + 2),
                });
            }
            potential += tension * len;
            let u = [d[0] / len, d[1] / len];
            let jd = b.jacobian.rows(1, 2) - a.jacobian.rows(1, 2);
            *gradient += jd.transpose() * DVector::from_column_slice(&u) * tension;
            if let Some(h) = hessian.as_deref_mut() {
                // ∂²|d| = ∂dᵀ(I − u uᵀ)∂d/|d| + u·∂²d.
                let proj = Matrix2::new(1.0 - u[0] * u[0], -u[0] * u[1], -u[0] * u[1], 1.0 - u[1] * u[1]) / len;
                *h += jd.transpose() * proj * &jd * tension;
                if let (Some([ax, ay]), Some([bx, by])) = (&a.hessian, &b.hessian) {
                    *h += ((bx - ax) * u[0] + (by - ay) * u[1]) * tension;
                }
            }
        }
    }
    Ok(potential)
}
