//! The equations of motion of a mechanism of either dimension as a
//! [`System`]: [`MechanismSystem`], its mass matrix, velocity-product
//! terms, loads and damping (the parent module's docs give the equations),
//! with the dimension's mass elements from [`Dynamics`].

use super::dimension::{Dynamics, MassElements};
use crate::dynamics::system::System;
use crate::error::{Error, Result};
use crate::mechanism::{Loads, Mechanism};
use crate::space::Planar;
use nalgebra::{DMatrix, DVector};

/// The equations of motion of a [`Mechanism`] as a [`System`] (module docs):
/// its coordinates are the mechanism's $q$, its closures the welds and pins.
///
/// The loads are the mechanism's own ([`Mechanism::loads`]), constant in
/// time, until [`MechanismSystem::set_loads`] replaces them.
///
/// # Example
/// ```
/// use flexure::dynamics::{mechanism::MechanismSystem, System};
/// use flexure::mechanism::file::from_toml;
/// // A pendulum: a point mass of 2 kg, 0.5 m from a free pin, under gravity.
/// let m = from_toml(
///     "gravity = [0.0, -9.81]\n[[joint]]\nname = \"pin\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"bob\"\n\
///      [[body]]\nname = \"bob\"\nmass = 2.0\ncom = [0.5, 0.0]\n",
/// )
/// .unwrap();
/// let mut sys = MechanismSystem::new(&m).unwrap();
/// let (mut mass, mut force) = ([0.0], [0.0]);
/// sys.dynamics(&[0.0], &[0.0], 0.0, &mut mass, &mut force).unwrap();
/// // M = m l², and gravity's moment −m g l about the pin.
/// assert!((mass[0] - 0.5).abs() < 1e-15 && (force[0] + 9.81).abs() < 1e-13);
/// ```
#[derive(Debug, Clone)]
pub struct MechanismSystem<D: Dynamics = Planar> {
    mechanism: Mechanism<D>,
    loads: Loads<D>,
    /// $D$ (column-major, $n\times n$).
    damping: DMatrix<f64>,
    masses: D::Masses,
}

impl<D: Dynamics> MechanismSystem<D> {
    /// The system of `m`, with the joints' damping and its loads. Fails if a
    /// flexure's mass integrals cannot be made accurate ([`MassModel::new`](crate::mass::MassModel::new)).
    pub fn new(m: &Mechanism<D>) -> Result<Self> {
        let n = m.dof();
        let mut damping = DMatrix::zeros(n, n);
        for j in m.joints.iter().filter(|j| j.damping != 0.0) {
            let joint = j.kind.joint();
            let k = joint.dof();
            joint.add_damping(j.damping, &mut damping.view_mut((j.offset, j.offset), (k, k)));
        }
        let loads = m.loads();
        let mut masses = D::Masses::new(m)?;
        masses.set_loads(&loads);
        Ok(MechanismSystem { mechanism: m.clone(), loads, damping, masses })
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism<D> {
        &self.mechanism
    }

    /// The loads applied.
    pub fn loads(&self) -> &Loads<D> {
        &self.loads
    }

    /// Replaces the loads (validated against the mechanism: [`Loads::validate`]).
    pub fn set_loads(&mut self, loads: Loads<D>) -> Result<()> {
        D::check_loads(&self.mechanism, &loads)?;
        self.masses.set_loads(&loads);
        self.loads = loads;
        Ok(())
    }

    /// Whether anything carries inertia: a body's mass or inertia, or a flexure's distributed mass.
    pub fn has_inertia(&self) -> bool {
        self.masses.has_inertia(&self.mechanism)
    }

    /// The damping matrix $D$ ($n\times n$, constant).
    pub fn damping(&self) -> &DMatrix<f64> {
        &self.damping
    }

    fn check(&self, q: &[f64], v: &[f64]) -> Result<()> {
        let n = self.mechanism.dof();
        if q.len() != n || v.len() != n {
            return Err(Error::invalid(
                "q",
                format!("{} coordinates and {} rates", q.len(), v.len()),
                "must have one coordinate and one rate per coordinate of the mechanism",
            ));
        }
        if let Some(x) = q.iter().chain(v).find(|x| !x.is_finite()) {
            return Err(Error::invalid("q", x, "coordinates and rates must be finite"));
        }
        Ok(())
    }

    /// $M(q)$ ($n\times n$, symmetric, positive semi-definite).
    ///
    /// # Errors
    /// If `q` does not have one finite value per coordinate.
    pub fn mass_matrix(&mut self, q: &[f64]) -> Result<DMatrix<f64>> {
        self.check(q, &vec![0.0; self.mechanism.dof()])?;
        Ok(self.masses.mass_matrix(&self.mechanism, &self.loads, q))
    }

    /// $h(q, \dot q) = \dot M\dot q - \frac12\nabla(\dot q^TM\dot q)$ (module docs).
    ///
    /// # Errors
    /// If `q` or `v` does not have one finite value per coordinate.
    pub fn velocity_product(&mut self, q: &[f64], v: &[f64]) -> Result<DVector<f64>> {
        self.check(q, v)?;
        Ok(self.masses.velocity_product(&self.mechanism, &self.loads, q, v))
    }
}

impl<D: Dynamics> System for MechanismSystem<D> {
    fn dim(&self) -> usize {
        self.mechanism.dof()
    }

    fn closures(&self) -> usize {
        self.masses.closures(&self.mechanism)
    }

    fn dynamics(&mut self, q: &[f64], v: &[f64], _t: f64, mass: &mut [f64], force: &mut [f64]) -> Result<()> {
        self.check(q, v)?;
        let n = self.dim();
        self.masses.forces(&self.mechanism, &self.loads, q, v, mass, force)?;
        for (r, f) in force.iter_mut().enumerate() {
            let damping: f64 = (0..n).map(|c| self.damping[(r, c)] * v[c]).sum();
            *f -= damping;
        }
        if !(mass.iter().all(|x| x.is_finite()) && force.iter().all(|x| x.is_finite())) {
            return Err(Error::Singular { what: "the mass matrix or the generalized force is not finite".into() });
        }
        Ok(())
    }

    /// The stiffness is the dimension's ([`MassElements::stiffness`]: the
    /// Hessian of the potential, in space with the change of $h$ with $q$)
    /// and the damping is $D + \partial h/\partial\dot q$ (exact: $h$ is
    /// quadratic in $\dot q$).
    fn tangent(&mut self, q: &[f64], v: &[f64], _t: f64, stiffness: &mut [f64], damping: &mut [f64]) -> Result<()> {
        self.check(q, v)?;
        let n = self.dim();
        self.masses.stiffness(&self.mechanism, &self.loads, q, v, stiffness)?;
        let mut d = self.damping.clone();
        // h is quadratic in v: ∂h/∂v e = (h(v + e) − h(v − e))/2 exactly.
        let mut shifted = v.to_vec();
        for c in 0..n {
            let step = D::Masses::rate_step(v, c);
            shifted[c] = v[c] + step;
            let plus = self.masses.velocity_product(&self.mechanism, &self.loads, q, &shifted);
            shifted[c] = v[c] - step;
            let minus = self.masses.velocity_product(&self.mechanism, &self.loads, q, &shifted);
            shifted[c] = v[c];
            for r in 0..n {
                d[(r, c)] += (plus[r] - minus[r]) / (2.0 * step);
            }
        }
        damping.copy_from_slice(d.as_slice());
        Ok(())
    }

    fn closure(&mut self, q: &[f64], c: &mut [f64], g: &mut [f64]) -> Result<()> {
        self.masses.closure(&self.mechanism, q, c, g);
        Ok(())
    }

    fn energy(&mut self, q: &[f64], v: &[f64], _t: f64) -> Result<f64> {
        self.check(q, v)?;
        self.masses.energy(&self.mechanism, &self.loads, q, v)
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        self.masses.distance(&self.mechanism, a, b)
    }

    fn error_weights(&self) -> crate::dynamics::system::ErrorWeights {
        let group =
            self.mechanism.joints.iter().enumerate().flat_map(|(i, j)| std::iter::repeat_n(i, j.kind.joint().dof()));
        crate::dynamics::system::ErrorWeights { group: group.collect(), weight: self.mechanism.error_weights() }
    }
}
