//! Equilibrium under tip loads (paper Eqs. 22 and 32).

use crate::linalg;
use crate::energy::{energy, energy_gradient, stiffness};
use crate::error::{Error, Result, finite};
use crate::joint::Flexure;
use crate::kinematics::{self, Kinematics, Level, Pose};
use crate::newton::{self, Objective};
use crate::scalar::Scalar;
use nalgebra::DMatrix;

/// A load at the tip, in the root frame: moment $M$ (N·m) and force $(F_x, F_y)$ (N).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TipLoad<T = f64> {
    /// Moment about the tip, counter-clockwise positive.
    pub moment: T,
    /// Force along the root's x axis.
    pub fx: T,
    /// Force along the root's y axis.
    pub fy: T,
}

impl TipLoad<f64> {
    /// The paper's load (Sec. III-C): force of magnitude $P$ at angle $\theta$,
    /// $F_x = -P\sin\theta$, $F_y = P\cos\theta$, with moment $M$.
    ///
    /// # Example
    /// ```
    /// let l = flexure::TipLoad::polar(0.0, 2.0, std::f64::consts::FRAC_PI_2);
    /// assert!((l.fx + 2.0).abs() < 1e-15 && l.fy.abs() < 1e-15);
    /// ```
    pub fn polar(moment: f64, force: f64, angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        // + 0.0 turns the −0 of a zero angle into 0.
        Self { moment, fx: -force * s + 0.0, fy: force * c }
    }

    /// Checks that every component is finite.
    pub fn validate(&self) -> Result<()> {
        finite("moment", self.moment)?;
        finite("fx", self.fx)?;
        finite("fy", self.fy)?;
        Ok(())
    }
}

/// Solver settings for [`deflect`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Relative tolerance on the generalized force residual, scaled by
    /// $EI/L + |M| + L(|F_x| + |F_y|)$.
    pub tolerance: f64,
    /// Newton iterations per load step.
    pub max_iterations: usize,
    /// Smallest load-continuation step before giving up.
    pub min_load_step: f64,
    /// Largest rotation (rad) of any cross-section, $\phi(t_k)$ at the
    /// quadrature nodes, that one load step may cause. Bounding it keeps the
    /// solution on the branch that grows from the rest shape, as quasi-static
    /// loading would.
    pub max_rotation_per_step: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { tolerance: 1e-12, max_iterations: 50, min_load_step: 1e-4, max_rotation_per_step: 0.5 }
    }
}

/// Work buffers and results of [`deflect`] for one flexure (the Data).
#[derive(Debug, Clone)]
pub struct Statics<T: Scalar = f64> {
    /// Kinematics at the solution.
    pub kinematics: Kinematics<T>,
    /// Generalized stiffness $K$ at the solution (Eq. 32).
    pub stiffness: DMatrix<T>,
    newton: newton::Workspace<T>,
    alpha: Vec<T>,
    /// $d\alpha/d\lambda$ along the load path.
    tangent: Vec<T>,
    factor: Vec<T>,
}

impl<T: Scalar> Statics<T> {
    /// Buffers sized for `flexure`.
    pub fn new(flexure: &Flexure) -> Self {
        let n = flexure.order();
        Self {
            kinematics: Kinematics::new(flexure),
            stiffness: DMatrix::zeros(n, n),
            newton: newton::Workspace::new(n),
            alpha: vec![T::zero(); n],
            tangent: vec![T::zero(); n],
            factor: vec![T::zero(); n * n],
        }
    }

    /// Joint coordinates $\alpha$ at the last equilibrium.
    pub fn alpha(&self) -> &[T] {
        &self.alpha
    }

    /// Tip pose at the last equilibrium.
    pub fn pose_root_tip(&self) -> Pose<T> {
        self.kinematics.pose_root_tip
    }
}

/// What [`deflect`] found, beside the data left in [`Statics`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Equilibrium {
    /// Whether $K$ is positive definite: a stable equilibrium.
    pub stable: bool,
    /// Final generalized-force residual (N·m).
    pub residual: f64,
    /// Newton iterations over all load steps.
    pub iterations: usize,
    /// Load-continuation steps taken.
    pub load_steps: usize,
}

/// The potential $\Pi(\alpha) = U(\alpha) - \lambda(M\phi + F_x x + F_y y)$.
struct TipLoadPotential<'a, T: Scalar> {
    flexure: &'a Flexure,
    kinematics: &'a mut Kinematics<T>,
    load: TipLoad<T>,
    scale: T,
}

impl<T: Scalar> Objective<T> for TipLoadPotential<'_, T> {
    fn evaluate(&mut self, alpha: &[T], gradient: &mut [T], hessian: &mut [T]) -> T {
        let (f, k) = (self.flexure, &mut *self.kinematics);
        kinematics::update(f, alpha, k, Level::Hessian);
        let (m, fx, fy) = (self.load.moment * self.scale, self.load.fx * self.scale, self.load.fy * self.scale);
        energy_gradient(f, alpha, gradient);
        let n = f.order();
        for (i, g) in gradient.iter_mut().enumerate() {
            let j = k.jacobian_root_tip.column(i);
            *g -= m * j[0] + fx * j[1] + fy * j[2];
        }
        let (hx, hy) = (k.hessian_root_tip_x.as_slice(), k.hessian_root_tip_y.as_slice());
        for (idx, h) in hessian.iter_mut().enumerate() {
            *h = -(fx * hx[idx] + fy * hy[idx]);
        }
        for i in 0..n {
            hessian[i * n + i] += T::c(stiffness(f, i));
        }
        let p = k.pose_root_tip;
        energy(f, alpha) - (m * p.phi + fx * p.x + fy * p.y)
    }
}

/// Equilibrium of the flexure under `load`: the $\alpha$ where
/// $\tau = \nabla U - M\nabla\phi - F_x\nabla x - F_y\nabla y = 0$ (Eq. 22),
/// with stiffness $K = \nabla\nabla U - F_x\nabla\nabla x - F_y\nabla\nabla y$ (Eq. 32).
///
/// Newton with exact $K$ and a line search, inside load continuation from
/// the rest shape. Each load step is sized by the tangent
/// $d\alpha/d\lambda = K^{-1}\mathcal J^T(M, F_x, F_y)$ so that no
/// cross-section is predicted to turn more than 70 % of
/// [`Settings::max_rotation_per_step`], and the tangent also gives Newton its
/// start. A step that fails, or turns a cross-section by more than the bound,
/// is halved; so the solution follows the branch that grows from the rest
/// shape. Results stay in `data`; nothing is allocated.
///
/// # Example
/// ```
/// use flexure::{deflect, Flexure, Statics, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = Statics::new(&f);
/// // A pure moment bends the flexure into an arc of angle ML/EI.
/// let eq = deflect(&f, &TipLoad { moment: 1.2, fx: 0.0, fy: 0.0 }, &mut data, &Default::default()).unwrap();
/// assert!(eq.stable && (data.alpha()[0] - 1.2).abs() < 1e-12);
/// ```
pub fn deflect<T: Scalar>(
    flexure: &Flexure,
    load: &TipLoad<T>,
    data: &mut Statics<T>,
    settings: &Settings,
) -> Result<Equilibrium> {
    TipLoad { moment: load.moment.re(), fx: load.fx.re(), fy: load.fy.re() }.validate()?;
    let l = flexure.length();
    let scale = flexure.ei() / l + load.moment.re().abs() + l * (load.fx.re().abs() + load.fy.re().abs());
    let newton_settings =
        newton::Settings { tolerance: settings.tolerance * scale, max_iterations: settings.max_iterations };
    for (a, &k) in data.alpha.iter_mut().zip(flexure.rest()) {
        *a = T::c(k);
    }
    // The rest shape is the equilibrium at λ = 0; evaluate there for K and 𝒥.
    data.newton.x.copy_from_slice(&data.alpha);
    let mut rest = TipLoadPotential { flexure, kinematics: &mut data.kinematics, load: *load, scale: T::zero() };
    rest.evaluate(&data.newton.x, &mut data.newton.gradient, &mut data.newton.hessian);
    let mut has_tangent = tangent(flexure, load, data);
    let (mut lambda, mut allowed) = (0.0_f64, 1.0_f64);
    let (mut iterations, mut load_steps, mut residual) = (0, 0, f64::INFINITY);
    loop {
        let mut step = allowed.min(1.0 - lambda);
        if has_tangent {
            let rate = rotation(flexure, &data.tangent, None);
            if rate > 0.0 {
                step = step.min(0.7 * settings.max_rotation_per_step / rate);
            }
        }
        let target = if 1.0 - lambda - step < 1e-12 { 1.0 } else { lambda + step };
        let h = T::c(if has_tangent { target - lambda } else { 0.0 });
        for ((x, &a), &t) in data.newton.x.iter_mut().zip(&data.alpha).zip(&data.tangent) {
            *x = a + h * t;
        }
        let mut potential =
            TipLoadPotential { flexure, kinematics: &mut data.kinematics, load: *load, scale: T::c(target) };
        let found = newton::minimize(&mut potential, &mut data.newton, &newton_settings);
        let change = rotation(flexure, &data.newton.x, Some(&data.alpha));
        match found {
            Ok(report) if change <= settings.max_rotation_per_step => {
                iterations += report.iterations;
                load_steps += 1;
                residual = report.residual;
                data.alpha.copy_from_slice(&data.newton.x);
                lambda = target;
                if lambda >= 1.0 {
                    // The minimizer's last evaluation was at its solution, so
                    // the kinematics in `data` already belong to it.
                    data.stiffness.as_mut_slice().copy_from_slice(&data.newton.hessian);
                    return Ok(Equilibrium { stable: report.positive_definite, residual, iterations, load_steps });
                }
                has_tangent = tangent(flexure, load, data);
                allowed = 2.0 * step;
            }
            found => {
                if let Ok(report) = &found {
                    (iterations, residual) = (iterations + report.iterations, report.residual);
                } else if let Err(Error::NoConvergence { iterations: it, residual: r, .. }) = found {
                    (iterations, residual) = (iterations + it, r);
                }
                allowed = 0.5 * step;
                if allowed < settings.min_load_step {
                    return Err(Error::NoConvergence { unit: "N·m",
                        solver: "deflect (load continuation: the load step fell below min_load_step)",
                        iterations,
                        residual,
                    });
                }
                // The tangent at the last equilibrium is still valid: the data there is unchanged.
            }
        }
    }
}

/// Writes $d\alpha/d\lambda = K^{-1}\mathcal J^T(M, F_x, F_y)$ into `data.tangent`,
/// from the Hessian and kinematics of the last evaluation. False where $K$
/// is not positive definite (no tangent: the next step starts from $\alpha$).
fn tangent<T: Scalar>(flexure: &Flexure, load: &TipLoad<T>, data: &mut Statics<T>) -> bool {
    let n = flexure.order();
    data.factor.copy_from_slice(&data.newton.hessian);
    if !linalg::cholesky(&mut data.factor, n) {
        data.tangent.fill(T::zero());
        return false;
    }
    for (i, t) in data.tangent.iter_mut().enumerate() {
        let j = data.kinematics.jacobian_root_tip.column(i);
        *t = load.moment * j[0] + load.fx * j[1] + load.fy * j[2];
    }
    linalg::cholesky_solve(&data.factor, n, &mut data.tangent);
    true
}

/// Largest cross-section rotation $\max_k\lvert\sum_i\psi_i(t_k)(a_i - b_i)\rvert$ (b = 0 if absent).
fn rotation<T: Scalar>(flexure: &Flexure, a: &[T], b: Option<&[T]>) -> f64 {
    flexure.psi_rows().fold(0.0_f64, |m, psi| {
        let d: f64 = psi.iter().enumerate().map(|(i, p)| p * (a[i].re() - b.map_or(0.0, |b| b[i].re()))).sum();
        m.max(d.abs())
    })
}

/// The smallest factor $\lambda$ for which the equilibrium under
/// $\lambda\cdot$`load`, followed from the rest shape, stops being stable:
/// $K$ (Eq. 32) is no longer positive definite, or continuation loses the
/// branch (a snap-through). `None` if it stays stable up to `max_factor`.
///
/// Brackets by doubling $\lambda$, then bisects to a relative $10^{-10}$.
///
/// # Example
/// ```
/// use flexure::{statics::stability_limit, Flexure, TipLoad};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // Axial compression: the model's free buckling load, Table I.
/// let l = stability_limit(&f, &TipLoad { moment: 0.0, fx: -1.0, fy: 0.0 }, 100.0).unwrap().unwrap();
/// assert!((l - 2.4677).abs() < 1e-4);
/// ```
pub fn stability_limit(flexure: &Flexure, load: &TipLoad, max_factor: f64) -> Result<Option<f64>> {
    load.validate()?;
    if !(max_factor.is_finite() && max_factor > 0.0) {
        return Err(Error::invalid("max_factor", max_factor, "must be a finite number greater than zero"));
    }
    let mut data = Statics::new(flexure);
    let mut stable_at = |factor: f64| {
        let scaled = TipLoad { moment: factor * load.moment, fx: factor * load.fx, fy: factor * load.fy };
        deflect(flexure, &scaled, &mut data, &Settings::default()).map(|e| e.stable).unwrap_or(false)
    };
    let (mut lo, mut hi) = (0.0, max_factor / 1024.0);
    while stable_at(hi) {
        if hi >= max_factor {
            return Ok(None);
        }
        lo = hi;
        hi = (2.0 * hi).min(max_factor);
    }
    while hi - lo > 1e-10 * hi {
        let mid = 0.5 * (lo + hi);
        if stable_at(mid) { lo = mid } else { hi = mid }
    }
    Ok(Some(0.5 * (lo + hi)))
}
