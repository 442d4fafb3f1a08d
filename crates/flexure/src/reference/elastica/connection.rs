//! The exact minimum-energy shape between two poses (Eq. 16).

use super::ShootingSettings;
use super::chain::MAX_FORCE_GROWTH;
use super::trace::Trace;
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::Pose;
use crate::ode::{Tolerance, integrate_through};
use crate::scalar::Scalar;
use crate::solver::{self, Problem};
use nalgebra::Const;
use num_dual::DualSVec64;

/// An exact minimum-energy shape between two poses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticaConnection {
    /// Bending energy $U^* = \int_0^L \frac{EI}{2}(\omega - \omega_0)^2 ds$ (J).
    pub energy: f64,
    /// Bending moment at the root, $M_0$ (N·m).
    pub root_moment: f64,
    /// The force carried along the beam, equal to the force on the tip (N).
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
}

/// Integrates Eq. 3 as [`shoot`](super::shoot) does, adding the energy $\int m^2/2EI\thinspace ds$ as a fourth state.
fn shoot_with_energy<T: Scalar>(
    flexure: &Flexure,
    stops: &[f64],
    m0: T,
    fx: T,
    fy: T,
    tol: &Tolerance,
) -> Result<[T; 4]> {
    let kappa = flexure.rest();
    let rhs = |s: f64, y: &[T; 4]| {
        let (sn, cs) = y[0].sin_cos();
        let m = m0 - fy * y[1] + fx * y[2];
        let ei = T::c(flexure.ei_at(s));
        [T::c(flexure.curvature(kappa, s)) + m / ei, cs, sn, m * m / (ei + ei)]
    };
    integrate_through(rhs, 0.0, flexure.length(), stops, [T::zero(); 4], tol, &mut 0.0, |_, _| {})
}

/// The connection as a [`Problem`] for [`solver::newton`]: unknowns
/// $(M_0, F_x, F_y)$, residual the tip-pose mismatch $((\phi_L - \phi_t)L, x_L - x_t, y_L - y_t)$.
struct Through<'a> {
    flexure: &'a Flexure,
    target: Pose,
    ode: Tolerance,
    /// The section's breakpoints (m).
    stops: Vec<f64>,
    /// $\int_0^L ds/EI$ and $\int_0^L EI^{-1/2} ds$ (`L/EI` and `L/√EI` when uniform).
    flexibility: f64,
    stretch: f64,
}

impl Problem<f64> for Through<'_> {
    fn dim(&self) -> usize {
        3
    }

    fn evaluate(
        &mut self,
        z: &[f64],
        _lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let (l, t) = (self.flexure.length(), self.target);
        // Iterates no connection needs are refused before integrating: a
        // shot under such loads coils and costs steps in proportion to them.
        let growth = z[1].hypot(z[2]).sqrt() * self.stretch;
        if growth > MAX_FORCE_GROWTH || z[0].abs() * self.flexibility > MAX_FORCE_GROWTH.powi(2) {
            return Err(Error::Singular {
                what: "exact connection: a Newton iterate beyond any connection's load".into(),
            });
        }
        if let Some(jac) = jacobian {
            let v = |i: usize| DualSVec64::<3>::from_re(z[i]).derivative(i);
            let tip = shoot_with_energy(self.flexure, &self.stops, v(0), v(1), v(2), &self.ode)?;
            let r = [(tip[0] - t.phi) * l, tip[1] - t.x, tip[2] - t.y];
            for (row, ri) in r.iter().enumerate() {
                residual[row] = ri.re;
                let d = ri.eps.unwrap_generic(Const::<3>, Const::<1>);
                for col in 0..3 {
                    jac[col * 3 + row] = d[col];
                }
            }
        } else {
            let tip = shoot_with_energy(self.flexure, &self.stops, z[0], z[1], z[2], &self.ode)?;
            residual.copy_from_slice(&[(tip[0] - t.phi) * l, tip[1] - t.x, tip[2] - t.y]);
        }
        if let Some(d) = dlambda {
            d.fill(0.0);
        }
        if residual.iter().all(|r| r.is_finite()) {
            Ok(())
        } else {
            Err(Error::Singular { what: "exact connection: non-finite tip pose".into() })
        }
    }

    /// An upper bound, in linear theory, of the cross-sections' rotation
    /// between the loads $(M_0, F_x, F_y)$ `a` and `b`: $(|\Delta M_0| + L|\Delta F|_1)\int_0^L ds/EI$.
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let l = self.flexure.length();
        ((a[0] - b[0]).abs() + l * ((a[1] - b[1]).abs() + (a[2] - b[2]).abs())) * self.flexibility
    }

    fn scale(&self) -> f64 {
        self.flexure.length()
    }

    fn unit(&self) -> &'static str {
        "m"
    }

    fn name(&self) -> &'static str {
        "exact connection"
    }
}

/// The exact elastica through `target`, by shooting on the root moment and
/// both force components (three unknowns) until the tip pose matches.
///
/// `guess` is $(M_0, F_x, F_y)$; the model's [`crate::connect::connect`]
/// multipliers, moved to the root, make a good one. Damped Newton
/// ([`solver::newton`]) with the Jacobian from dual numbers through the
/// integrator, to a tip-pose mismatch of `settings.solver.tolerance` × $L$.
/// The minimum energy $U^*$ of Eq. 16.
///
/// # Example
/// ```
/// use flexure::{reference::elastica, Flexure, Pose};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // An arc of angle 1 needs a pure moment 1: U* = 1/2.
/// let target = Pose { phi: 1.0, x: 1f64.sin(), y: 1.0 - 1f64.cos() };
/// let c = elastica::connect(&f, &target, [0.9, 0.0, 0.0], &Default::default()).unwrap();
/// assert!((c.energy - 0.5).abs() < 1e-10 && (c.root_moment - 1.0).abs() < 1e-9);
/// ```
pub fn connect(
    flexure: &Flexure,
    target: &Pose,
    guess: [f64; 3],
    settings: &ShootingSettings,
) -> Result<ElasticaConnection> {
    crate::connect::check_pose(flexure, target)?;
    settings.validate()?;
    for (name, g) in ["guess[0]", "guess[1]", "guess[2]"].into_iter().zip(guess) {
        crate::error::finite(name, g)?;
    }
    let s = crate::reference::Stretch::of(flexure)?;
    let (flexibility, stretch) = (s.flexibility, s.total());
    let stops = crate::reference::stops(flexure);
    let mut problem = Through { flexure, target: *target, ode: settings.ode, stops, flexibility, stretch };
    let mut ws = solver::SolverWorkspace::new(3);
    ws.x.copy_from_slice(&guess);
    solver::newton(&mut problem, &mut ws, 1.0, &settings.solver)?;
    let tip = shoot_with_energy(flexure, &problem.stops, ws.x[0], ws.x[1], ws.x[2], &settings.ode)?;
    Ok(ElasticaConnection { energy: tip[3], root_moment: ws.x[0], fx: ws.x[1], fy: ws.x[2] })
}

impl ElasticaConnection {
    /// The exact shape of this connection on `flexure` (the one it was
    /// found for): the shot from the root with its moment and force.
    pub fn trace<'a>(&self, flexure: &'a Flexure, tol: &Tolerance) -> Result<Trace<'a>> {
        Trace::shot(flexure, self.root_moment, self.fx, self.fy, tol)
    }
}
