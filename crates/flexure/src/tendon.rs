//! A tendon-driven flexure joint (paper Sec. III-D, Eqs. 23–26).

use crate::energy::{energy, energy_gradient, stiffness};
use crate::error::{Error, Result, finite};
use crate::joint::Flexure;
use crate::kinematics::{self, Kinematics, Level};
use crate::newton::{self, Objective};
use crate::scalar::Scalar;
use crate::statics::Equilibrium;

/// A tendon of constant tension spanning the flexure, attached at
/// $T_1$ = translation $(0, d_1)$ in the root frame and $T_2$ = translation
/// $(0, d_2)$ in the tip frame (Eq. 26): offsets from the neutral axis (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tendon {
    /// $d_1$: offset at the root.
    pub root_offset: f64,
    /// $d_2$: offset at the tip.
    pub tip_offset: f64,
}

impl Tendon {
    /// Checks that both offsets are finite.
    pub fn validate(&self) -> Result<()> {
        finite("root-offset", self.root_offset)?;
        finite("tip-offset", self.tip_offset)?;
        Ok(())
    }

    /// $\Delta x$ of Eq. 23: the tip attachment seen from the root one,
    /// $\Delta x = (x - d_2\sin\phi,\; y + d_2\cos\phi - d_1)$.
    pub fn span<T: Scalar>(&self, phi: T, x: T, y: T) -> [T; 2] {
        let (s, c) = phi.sin_cos();
        let d2 = T::c(self.tip_offset);
        [x - d2 * s, y + d2 * c - T::c(self.root_offset)]
    }
}

/// The tendon's length $\lvert\Delta x(\alpha)\rvert$ (m).
///
/// # Example
/// ```
/// use flexure::{tendon::{tendon_length, Tendon}, Flexure};
/// let f = Flexure::new(0.015, 1.4558e-3, 3).unwrap();
/// let t = Tendon { root_offset: 0.005, tip_offset: 0.005 };
/// // Straight: the tendon runs parallel to the flexure.
/// assert!((tendon_length(&f, &t, &[0.0, 0.0, 0.0]) - 0.015).abs() < 1e-15);
/// ```
pub fn tendon_length<T: Scalar>(flexure: &Flexure, tendon: &Tendon, alpha: &[T]) -> T {
    let p = kinematics::pose_root_tip(flexure, alpha);
    let [dx, dy] = tendon.span(p.phi, p.x, p.y);
    (dx * dx + dy * dy).sqrt()
}

/// $E(\alpha) = U(\alpha) + f\lvert\Delta x(\alpha)\rvert$ (Eq. 24 with the
/// errata's sign: tension shortens the tendon), with exact gradient and Hessian.
pub struct TendonPotential<'a, T: Scalar> {
    /// The joint.
    pub flexure: &'a Flexure,
    /// The tendon's attachments.
    pub tendon: Tendon,
    /// Tension $f$ (N).
    pub tension: T,
    /// Kinematics buffers.
    pub kinematics: &'a mut Kinematics<T>,
}

impl<T: Scalar> Objective<T> for TendonPotential<'_, T> {
    fn evaluate(&mut self, alpha: &[T], gradient: &mut [T], hessian: &mut [T]) -> T {
        let (f, k, n) = (self.flexure, &mut *self.kinematics, self.flexure.order());
        kinematics::update(f, alpha, k, Level::Hessian);
        let p = k.pose_root_tip;
        let [dx, dy] = self.tendon.span(p.phi, p.x, p.y);
        let length = (dx * dx + dy * dy).sqrt();
        let (s, c) = p.phi.sin_cos();
        let d2 = T::c(self.tendon.tip_offset);
        let j = &k.jacobian_root_tip;
        // ∂Δx/∂α_i, from the pose Jacobian and the tip attachment's rotation.
        let ddx = |i: usize| j[(1, i)] - d2 * c * j[(0, i)];
        let ddy = |i: usize| j[(2, i)] - d2 * s * j[(0, i)];
        let (ux, uy) = (dx / length, dy / length);
        energy_gradient(f, alpha, gradient);
        for (i, g) in gradient.iter_mut().enumerate() {
            *g += self.tension * (ux * ddx(i) + uy * ddy(i));
        }
        let (hx, hy) = (&k.hessian_root_tip_x, &k.hessian_root_tip_y);
        for col in 0..n {
            for row in 0..n {
                let (ar, ac) = ([ddx(row), ddy(row)], [ddx(col), ddy(col)]);
                let jj = j[(0, row)] * j[(0, col)];
                // ∂²Δx: the tip Hessians plus the attachment's rotation terms.
                let d2x = hx[(row, col)] + d2 * s * jj;
                let d2y = hy[(row, col)] - d2 * c * jj;
                // ∂²|Δx| = (∂Δx)ᵀ(I − u uᵀ)(∂Δx)/|Δx| + u·∂²Δx.
                let proj =
                    (ar[0] * ac[0] + ar[1] * ac[1] - (ux * ar[0] + uy * ar[1]) * (ux * ac[0] + uy * ac[1])) / length;
                hessian[col * n + row] = self.tension * (proj + ux * d2x + uy * d2y);
            }
            hessian[col * n + col] += T::c(stiffness(f, col));
        }
        energy(f, alpha) + self.tension * length
    }
}

/// Work buffers and results of [`pull`].
#[derive(Debug, Clone)]
pub struct TendonData {
    /// Kinematics at the solution.
    pub kinematics: Kinematics<f64>,
    newton: newton::Workspace<f64>,
    alpha: Vec<f64>,
    tension: f64,
}

impl TendonData {
    /// Buffers for `flexure`, starting at its rest shape with no tension.
    pub fn new(flexure: &Flexure) -> Self {
        Self {
            kinematics: Kinematics::new(flexure),
            newton: newton::Workspace::new(flexure.order()),
            alpha: flexure.rest().to_vec(),
            tension: 0.0,
        }
    }

    /// Coordinates at the last equilibrium.
    pub fn alpha(&self) -> &[f64] {
        &self.alpha
    }

    /// Generalized stiffness $\nabla\nabla E$ at the last equilibrium (column-major).
    pub fn stiffness(&self) -> &[f64] {
        &self.newton.hessian
    }
}

/// Equilibrium of the joint under tendon tension `tension`: the minimum of
/// $E(\alpha)$, reached by continuation in the tension from the last
/// equilibrium held in `data` (from rest on a fresh `data`), so sweeps follow
/// the loading path. Steps are bounded to 0.5 rad of tip rotation.
///
/// # Example
/// ```
/// use flexure::{tendon::{pull, Tendon, TendonData}, Flexure};
/// let ei = flexure::bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).unwrap();
/// let f = Flexure::new(0.015, ei, 3).unwrap();
/// let t = Tendon { root_offset: 0.005, tip_offset: 0.005 };
/// let mut data = TendonData::new(&f);
/// pull(&f, &t, 10.0, &mut data).unwrap();
/// // Tension bends the joint toward the tendon (errata, Eq. 24).
/// assert!(data.alpha()[0] > 0.1);
/// ```
pub fn pull(flexure: &Flexure, tendon: &Tendon, tension: f64, data: &mut TendonData) -> Result<Equilibrium> {
    tendon.validate()?;
    if !(tension.is_finite() && tension >= 0.0) {
        return Err(Error::invalid("force", tension, "a tendon's tension must be finite and not negative"));
    }
    let start = data.tension;
    let scale = flexure.ei() / flexure.length() + tension * (tendon.root_offset.abs() + tendon.tip_offset.abs());
    let settings = newton::Settings { tolerance: 1e-12 * scale, max_iterations: 50 };
    let (mut done, mut step) = (0.0_f64, 1.0_f64);
    let (mut iterations, mut load_steps) = (0, 0);
    loop {
        let target = (done + step).min(1.0);
        data.newton.x.copy_from_slice(&data.alpha);
        let mut potential = TendonPotential {
            flexure,
            tendon: *tendon,
            tension: start + target * (tension - start),
            kinematics: &mut data.kinematics,
        };
        let found = newton::minimize(&mut potential, &mut data.newton, &settings);
        let turn = (data.newton.x[0] - data.alpha[0]).abs();
        match found {
            Ok(report) if turn <= 0.5 || step < 1e-3 => {
                iterations += report.iterations;
                load_steps += 1;
                data.alpha.copy_from_slice(&data.newton.x);
                done = target;
                if done >= 1.0 {
                    data.tension = tension;
                    return Ok(Equilibrium {
                        stable: report.positive_definite,
                        residual: report.residual,
                        iterations,
                        load_steps,
                    });
                }
                step = (2.0 * step).min(1.0 - done);
            }
            other => {
                let residual = match other {
                    Err(Error::NoConvergence { residual, .. }) => residual,
                    _ => 0.0,
                };
                step *= 0.5;
                if step < 1e-4 {
                    return Err(Error::NoConvergence { unit: "N·m",
                        solver: "tendon equilibrium (continuation)",
                        iterations,
                        residual,
                    });
                }
            }
        }
    }
}
