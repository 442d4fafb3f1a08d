//! The potential of a mechanism, its exact derivatives, and its closures:
//! one assembly for both dimensions, what differs in [`Potential`].
//!
//! $$V(q) = \sum_j U_j(q_j) + \sum_t T_t\thinspace\ell_t(q) - \sum_b m_b\thinspace g\cdot c_b(q) - V_f(q) - \sum_i f_i\cdot x_i(q) - \sum_i M_i\theta_i,$$
//! the elastic joints, tendons of constant tension with lengths $\ell_t$
//! through their via points, the bodies' weights at their centres of mass
//! $c_b$, the weight $V_f$ of flexures with mass, and point loads at $x_i$,
//! and the closures $c(q) = 0$ with $G = \partial c/\partial q$. A point
//! load's moment $M_i$ has the potential $-M_i\theta_i$ in the plane, where
//! rotations add; in space, fixed there, it adds the generalized force
//! $Q_a = M_i\cdot\omega_a$, which has none (its derivative is not
//! symmetric), so the "gradient" is $\nabla V - Q_M$ and its "Hessian" the
//! derivative of that: equilibrium is gradient $+\thinspace G^T\mu = 0$ in
//! both. Point derivatives come from [`super::kinematics`], chained through
//! the tree.

mod dimension;
mod planar;
mod spatial;

pub use dimension::Potential;
pub use planar::Weights;
pub(crate) use planar::{closure_hessian, closures, wrap};
pub(crate) use spatial::flexure_weight_potential;
pub use spatial::{add_closure_hessian, closures_into};

use super::kinematics::{Attached, Frames, frames};
use super::{Loads, Mechanism};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};

pub(crate) fn check_sizes<D: Potential>(m: &Mechanism<D>, q: &[f64], mu: &[f64], loads: &Loads<D>) -> Result<()> {
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
    D::check_loads(m, loads)
}

/// $V$, $\nabla V$, $\nabla^2 V + \sum_i\mu_i\nabla^2 c_i$, $c$ and $G$ at `q`
/// under `loads` (exact derivatives), in fresh buffers.
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
pub fn lagrangian<D: Potential>(m: &Mechanism<D>, q: &[f64], mu: &[f64], loads: &Loads<D>) -> Result<Assembly<D>> {
    check_sizes(m, q, mu, loads)?;
    let mut a = Assembly::new(m);
    assemble_into(m, &frames(m, q), mu, loads, true, &mut a)?;
    Ok(a)
}

/// The potential, its derivatives and the closures at one configuration:
/// the buffers of one assembly (the Data of [`assemble_into`]).
#[derive(Debug, Clone)]
pub struct Assembly<D: Potential = crate::space::Planar> {
    /// $V$ (J).
    pub potential: f64,
    /// $\sum_j U_j$: its elastic part (J).
    pub elastic: f64,
    /// $\nabla V$ ($-\thinspace Q_M$ in space).
    pub gradient: DVector<f64>,
    /// Its derivative plus $\sum_i \mu_i\nabla^2 c_i$ (when asked for).
    pub hessian: DMatrix<f64>,
    /// $c(q)$: in the plane per weld $(\Delta x, \Delta y, \Delta\theta)$ (m,
    /// m, rad, the angle wrapped to $(-\pi, \pi]$), per pin $(\Delta x, \Delta y)$.
    pub closure: DVector<f64>,
    /// $G = \partial c/\partial q$.
    pub closure_jacobian: DMatrix<f64>,
    /// Two points' derivatives.
    pub points: [Attached<D>; 2],
    /// What only this dimension's loads and closures keep.
    pub kept: D::Kept,
}

impl<D: Potential> Assembly<D> {
    /// Buffers for `m`.
    pub fn new(m: &Mechanism<D>) -> Self {
        let (n, rows) = (m.dof(), m.constraints());
        Assembly {
            potential: 0.0,
            elastic: 0.0,
            gradient: DVector::zeros(n),
            hessian: DMatrix::zeros(n, n),
            closure: DVector::zeros(rows),
            closure_jacobian: DMatrix::zeros(rows, n),
            points: [Attached::new(m), Attached::new(m)],
            kept: D::kept(m),
        }
    }

    /// $c$ and $G$ alone at the frames `f`, into `closure` and
    /// `closure_jacobian` (no potential, no Hessian).
    pub(crate) fn closures_at(&mut self, m: &Mechanism<D>, f: &Frames<D>) {
        let Assembly { closure, closure_jacobian, points, kept, .. } = self;
        D::closure_terms(m, f, &[], closure, closure_jacobian, None, points, kept);
    }
}

/// Everything at the frames `f` (of [`super::kinematics::frames_into`]),
/// with multipliers `mu` (one per closure equation) and `loads`, into `a`
/// (made for `m`); the Hessian only `with_hessian`.
pub fn assemble_into<D: Potential>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    mu: &[f64],
    loads: &Loads<D>,
    with_hessian: bool,
    a: &mut Assembly<D>,
) -> Result<()> {
    let Assembly { gradient, hessian, closure, closure_jacobian, points, kept, .. } = a;
    // Each joint's block is written, not added: the blocks do not overlap.
    let n = gradient.len();
    gradient.as_mut_slice().fill(0.0);
    if with_hessian {
        hessian.as_mut_slice().fill(0.0);
    }
    let mut elastic = 0.0;
    for (j, s) in m.joints.iter().zip(&f.joints) {
        let (o, k) = (j.offset, s.gradient.len());
        elastic += s.energy;
        gradient.as_mut_slice()[o..o + k].copy_from_slice(s.gradient.as_slice());
        if with_hessian && k > 0 {
            let h = hessian.as_mut_slice();
            for (c, column) in s.stiffness.as_slice().chunks_exact(k).enumerate() {
                h[(o + c) * n + o..(o + c) * n + o + k].copy_from_slice(column);
            }
        }
    }
    let load = D::load_terms(m, f, loads, gradient, with_hessian.then_some(&mut *hessian), points, kept)?;
    D::closure_terms(m, f, mu, closure, closure_jacobian, with_hessian.then_some(hessian), points, kept);
    (a.potential, a.elastic) = (elastic + load, elastic);
    Ok(())
}

/// The buffers of [`gradient_into`], made once for a mechanism.
#[derive(Debug, Clone)]
pub struct GradientWork<D: Potential = crate::space::Planar> {
    gradient: DVector<f64>,
    points: [Attached<D>; 2],
    kept: D::Kept,
}

impl<D: Potential> GradientWork<D> {
    /// Buffers for `m`.
    pub fn new(m: &Mechanism<D>) -> Self {
        GradientWork {
            gradient: DVector::zeros(m.dof()),
            points: [Attached::new(m), Attached::new(m)],
            kept: D::kept(m),
        }
    }
}

/// $V$, its elastic part and $\nabla V$ under `loads` at the frames `f`
/// (of [`super::kinematics::frames_into`] at $q$), without the Hessian or
/// the closures: the part of [`lagrangian`] the equations of motion need at
/// every evaluation. Allocates nothing; the gradient is `work`'s.
///
/// # Example
/// ```
/// use flexure::mechanism::kinematics::frames;
/// use flexure::mechanism::lagrangian::{GradientWork, gradient_into, lagrangian};
/// let m = flexure::mechanism::file::from_toml(
///     "[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 2.0\n",
/// )
/// .unwrap();
/// let mut work = GradientWork::new(&m);
/// let (v, elastic, g) = gradient_into(&m, &frames(&m, &[0.5]), &m.loads(), &mut work).unwrap();
/// let full = lagrangian(&m, &[0.5], &[], &m.loads()).unwrap();
/// assert!(v == full.potential && elastic == full.elastic && g == &full.gradient);
/// ```
pub fn gradient_into<'a, D: Potential>(
    m: &Mechanism<D>,
    f: &Frames<D>,
    loads: &Loads<D>,
    work: &'a mut GradientWork<D>,
) -> Result<(f64, f64, &'a DVector<f64>)> {
    let GradientWork { gradient, points, kept } = work;
    gradient.fill(0.0);
    let mut elastic = 0.0;
    for (j, s) in m.joints.iter().zip(&f.joints) {
        elastic += s.energy;
        let mut g = gradient.rows_mut(j.offset, s.gradient.len());
        g += &s.gradient;
    }
    let load = D::load_terms(m, f, loads, gradient, None, points, kept)?;
    Ok((elastic + load, elastic, gradient))
}
