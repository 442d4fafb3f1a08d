//! A tendon-driven flexure joint (paper Sec. III-D, Eqs. 23–26).

use crate::energy::{energy, energy_gradient_entry};
use crate::error::{Error, Result, finite};
use crate::flexure::Flexure;
use crate::kinematics::{self, Kinematics, Level, Pose};
use crate::limit::{self, StabilityLimit};
use crate::linalg;
use crate::scalar::Scalar;
use crate::solver;
use crate::statics::{Equilibrium, Settings, rotation};

/// A tendon of constant tension spanning the flexure, attached at
/// $T_1$ = translation $(0, d_1)$ in the root frame and $T_2$ = translation
/// $(0, d_2)$ in the tip frame (Eq. 26): offsets from the neutral axis (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TendonOffsets {
    /// $d_1$: offset at the root.
    pub root_offset: f64,
    /// $d_2$: offset at the tip.
    pub tip_offset: f64,
}

impl TendonOffsets {
    /// Checks that both offsets are finite.
    pub fn validate(&self) -> Result<()> {
        finite("root-offset", self.root_offset)?;
        finite("tip-offset", self.tip_offset)?;
        Ok(())
    }

    /// $\Delta x$ of Eq. 23: the tip attachment seen from the root one,
    /// $\Delta x = (x - d_2\sin\phi,\thickspace y + d_2\cos\phi - d_1)$.
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
/// use flexure::{tendon::{tendon_length, TendonOffsets}, Flexure};
/// let f = Flexure::new(0.015, 1.4558e-3, 3).unwrap();
/// let t = TendonOffsets { root_offset: 0.005, tip_offset: 0.005 };
/// // Straight: the tendon runs parallel to the flexure.
/// assert!((tendon_length(&f, &t, &[0.0, 0.0, 0.0]) - 0.015).abs() < 1e-15);
/// ```
pub fn tendon_length<T: Scalar>(flexure: &Flexure, tendon: &TendonOffsets, alpha: &[T]) -> T {
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
    pub tendon: TendonOffsets,
    /// Tension $f$ (N).
    pub tension: T,
    /// Kinematics buffers.
    pub kinematics: &'a mut Kinematics<T>,
}

impl<T: Scalar> TendonPotential<'_, T> {
    /// Returns $E(\alpha)$ and writes $\nabla E$ and the column-major $\nabla\nabla E$.
    pub fn evaluate(&mut self, alpha: &[T], gradient: &mut [T], hessian: &mut [T]) -> T {
        let n = self.flexure.order();
        let length = self.length_derivatives(alpha, gradient, Some(hessian));
        for g in gradient.iter_mut() {
            *g *= self.tension;
        }
        for h in hessian.iter_mut() {
            *h *= self.tension;
        }
        for i in 0..n {
            gradient[i] += energy_gradient_entry(self.flexure, alpha, i);
        }
        for (h, &k) in hessian.iter_mut().zip(self.flexure.stiffness_matrix()) {
            *h += T::c(k);
        }
        energy(self.flexure, alpha) + self.tension * length
    }

    /// Updates the kinematics at `alpha` and returns the tendon length
    /// $\ell = \lvert\Delta x\rvert$, writing $\nabla\ell$ and, if asked, $\nabla\nabla\ell$.
    fn length_derivatives(&mut self, alpha: &[T], gradient: &mut [T], hessian: Option<&mut [T]>) -> T {
        let (f, k, n) = (self.flexure, &mut *self.kinematics, self.flexure.order());
        kinematics::update(f, alpha, k, if hessian.is_some() { Level::Hessian } else { Level::Jacobian });
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
        for (i, g) in gradient.iter_mut().enumerate() {
            *g = ux * ddx(i) + uy * ddy(i);
        }
        if let Some(hessian) = hessian {
            let (hx, hy) = (&k.hessian_root_tip_x, &k.hessian_root_tip_y);
            for col in 0..n {
                for row in 0..n {
                    let (ar, ac) = ([ddx(row), ddy(row)], [ddx(col), ddy(col)]);
                    let jj = j[(0, row)] * j[(0, col)];
                    // ∂²Δx: the tip Hessians plus the attachment's rotation terms.
                    let d2x = hx[(row, col)] + d2 * s * jj;
                    let d2y = hy[(row, col)] - d2 * c * jj;
                    // ∂²|Δx| = (∂Δx)ᵀ(I − u uᵀ)(∂Δx)/|Δx| + u·∂²Δx.
                    let proj = (ar[0] * ac[0] + ar[1] * ac[1] - (ux * ar[0] + uy * ar[1]) * (ux * ac[0] + uy * ac[1]))
                        / length;
                    hessian[col * n + row] = proj + ux * d2x + uy * d2y;
                }
            }
        }
        length
    }
}

/// Work buffers and results of [`pull`].
#[derive(Debug, Clone)]
pub struct TendonData {
    /// Kinematics at the solution.
    pub kinematics: Kinematics<f64>,
    solver: solver::SolverWorkspace<f64>,
    alpha: Vec<f64>,
    tension: f64,
    scratch: Vec<f64>,
}

impl TendonData {
    /// Buffers for `flexure`, starting at its rest shape with no tension.
    pub fn new(flexure: &Flexure) -> Self {
        let n = flexure.order();
        Self {
            kinematics: Kinematics::new(flexure),
            solver: solver::SolverWorkspace::new(n),
            alpha: flexure.rest().to_vec(),
            tension: 0.0,
            scratch: vec![0.0; n * n],
        }
    }

    /// Coordinates at the last equilibrium.
    pub fn alpha(&self) -> &[f64] {
        &self.alpha
    }

    /// Generalized stiffness $\nabla\nabla E$ at the last equilibrium (column-major).
    pub fn stiffness(&self) -> &[f64] {
        &self.solver.jacobian
    }
}

/// The tendon problem in the load factor: tension $f_0 + \lambda(f_1 - f_0)$,
/// $r = \nabla E$, Jacobian $\nabla\nabla E$, $\partial_\lambda r = (f_1 - f_0)\nabla\ell$.
struct TendonProblem<'a> {
    potential: TendonPotential<'a, f64>,
    start: f64,
    end: f64,
    scale: f64,
    scratch: &'a mut [f64],
}

impl solver::Problem<f64> for TendonProblem<'_> {
    fn dim(&self) -> usize {
        self.potential.flexure.order()
    }

    fn evaluate(
        &mut self,
        alpha: &[f64],
        lambda: f64,
        residual: &mut [f64],
        mut jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let (f, n) = (self.potential.flexure, self.dim());
        let tension = self.start + lambda * (self.end - self.start);
        let length = self.potential.length_derivatives(alpha, residual, jacobian.as_deref_mut());
        if length.is_nan() || length <= 1e-15 * f.length() {
            return Err(Error::Singular { what: "the tendon's attachments coincide".into() });
        }
        if let Some(d) = dlambda {
            for (d, g) in d.iter_mut().zip(residual.iter()) {
                *d = (self.end - self.start) * g;
            }
        }
        for i in 0..n {
            residual[i] = energy_gradient_entry(f, alpha, i) + tension * residual[i];
        }
        if let Some(h) = jacobian {
            for v in h.iter_mut() {
                *v *= tension;
            }
            for (h, &k) in h.iter_mut().zip(f.stiffness_matrix()) {
                *h += k;
            }
        }
        Ok(())
    }

    fn stable(&mut self, _alpha: &[f64], _lambda: f64, jacobian: &[f64]) -> bool {
        linalg::positive_definite(jacobian, self.dim(), self.scratch)
    }

    fn far_from_instability(&mut self, _alpha: &[f64], _lambda: f64, jacobian: &[f64]) -> bool {
        crate::statics::far_from_instability(self.potential.flexure, jacobian, self.scratch)
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        rotation(self.potential.flexure, a, Some(b))
    }

    fn scale(&self) -> f64 {
        self.scale
    }

    fn unit(&self) -> &'static str {
        "N·m"
    }

    fn name(&self) -> &'static str {
        "tendon equilibrium"
    }
}

/// Equilibrium of the joint under tendon tension `tension`: a minimum of
/// $E(\alpha)$, reached by the shared continuation ([`crate::solver`]) in
/// the tension from the last equilibrium held in `data` (from rest on a
/// fresh `data`), so sweeps follow the loading path.
///
/// # Example
/// ```
/// use flexure::{tendon::{pull, TendonOffsets, TendonData}, Flexure};
/// let ei = flexure::bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).unwrap();
/// let f = Flexure::new(0.015, ei, 3).unwrap();
/// let t = TendonOffsets { root_offset: 0.005, tip_offset: 0.005 };
/// let mut data = TendonData::new(&f);
/// pull(&f, &t, 10.0, &mut data).unwrap();
/// // Tension bends the joint toward the tendon (errata, Eq. 24).
/// assert!(data.alpha()[0] > 0.1);
/// ```
pub fn pull(flexure: &Flexure, tendon: &TendonOffsets, tension: f64, data: &mut TendonData) -> Result<Equilibrium> {
    follow(flexure, tendon, tension, data, false)
}

/// The tendon-driven joint at an equilibrium: the answer of [`equilibrium`],
/// serialized as the CLI prints it (a sweep's row; a single answer leaves
/// `tension` out) and Python returns it: `{tension, alpha, pose: {phi, x, y},
/// tendon_length, stable}`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TendonEquilibrium {
    /// The tendon's tension $f$ (N).
    pub tension: f64,
    /// Joint coordinates $\alpha$ at the equilibrium.
    pub alpha: Vec<f64>,
    /// Tip pose $(\phi, x, y)$ in the root frame at $\alpha$ (Eq. 7).
    pub pose: Pose,
    /// The tendon's length $\lvert\Delta x(\alpha)\rvert$ (m), as [`tendon_length`].
    pub tendon_length: f64,
    /// Whether $\nabla\nabla E$ is positive definite there (see [`Equilibrium::stable`]).
    pub stable: bool,
}

/// [`pull`] to `tension`, and the answer at the equilibrium reached: its
/// coordinates, tip pose, tendon length and stability, taken once from the
/// solution in `data` (which keeps it, for the next value of a sweep).
///
/// # Example
/// ```
/// use flexure::{tendon::{equilibrium, pull, tendon_length, TendonOffsets, TendonData}, Flexure};
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// let t = TendonOffsets { root_offset: 0.1, tip_offset: 0.05 };
/// let answer = equilibrium(&f, &t, 5.0, &mut TendonData::new(&f))?;
/// // The same equilibrium as `pull`'s, described at its own α.
/// let mut data = TendonData::new(&f);
/// let eq = pull(&f, &t, 5.0, &mut data)?;
/// assert_eq!(answer.alpha, data.alpha());
/// assert_eq!(answer.pose, flexure::pose_root_tip(&f, data.alpha()));
/// assert_eq!(answer.tendon_length, tendon_length(&f, &t, data.alpha()));
/// assert!(answer.stable && eq.stable && answer.tension == 5.0);
/// // Printed with the CLI's keys, in its order.
/// let v = serde_json::to_value(&answer).unwrap();
/// let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
/// assert_eq!(keys, ["tension", "alpha", "pose", "tendon_length", "stable"]);
/// assert_eq!(v["pose"]["phi"].as_f64(), Some(answer.pose.phi));
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn equilibrium(
    flexure: &Flexure,
    tendon: &TendonOffsets,
    tension: f64,
    data: &mut TendonData,
) -> Result<TendonEquilibrium> {
    let eq = pull(flexure, tendon, tension, data)?;
    let alpha = data.alpha().to_vec();
    Ok(TendonEquilibrium {
        tension,
        pose: kinematics::pose_root_tip(flexure, &alpha),
        tendon_length: tendon_length(flexure, tendon, &alpha),
        alpha,
        stable: eq.stable,
    })
}

/// The smallest factor on `tension` at which the joint's equilibrium,
/// followed from rest, stops being stable ($\nabla\nabla E$ stops being
/// positive definite: a snap), or the factor up to which it stays stable
/// (`max_factor`, or as far as the path can be followed): the search of
/// [`crate::limit`], shared with the tip load's
/// [`crate::statics::stability_limit`].
///
/// # Example
/// ```
/// use flexure::{tendon::{stability_limit, TendonOffsets}, Flexure, StabilityLimit};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // A tendon that crosses the flexure pulls its tip attachment onto its root
/// // attachment near 22.9 N, where the path ends (|Δx| has a kink there)…
/// let crossing = TendonOffsets { root_offset: 0.1, tip_offset: -0.05 };
/// let l = stability_limit(&f, &crossing, 1.0, 1000.0).unwrap();
/// assert!(matches!(l, StabilityLimit::StableUpTo { stalled: Some(_), .. }));
/// assert!((l.factor() - 22.893).abs() < 1e-3);
/// // …and so does its mirror image, at the same tension.
/// let mirror = TendonOffsets { root_offset: -0.1, tip_offset: 0.05 };
/// let m = stability_limit(&f, &mirror, 1.0, 1000.0).unwrap();
/// assert!((m.factor() / l.factor() - 1.0).abs() < 1e-9);
/// ```
pub fn stability_limit(
    flexure: &Flexure,
    tendon: &TendonOffsets,
    tension: f64,
    max_factor: f64,
) -> Result<StabilityLimit> {
    let mut data = TendonData::new(flexure);
    limit::search(max_factor, |factor| {
        data = TendonData::new(flexure);
        follow(flexure, tendon, factor * tension, &mut data, true)
    })
}

/// Checks a tendon, its tension and the data against the flexure, and
/// gives the residual's scale: $EI/L$ plus the tension's largest moment.
fn checked(flexure: &Flexure, tendon: &TendonOffsets, tension: f64, data: &mut TendonData) -> Result<f64> {
    tendon.validate()?;
    if !(tension.is_finite() && tension >= 0.0) {
        return Err(Error::invalid("force", tension, "a tendon's tension must be finite and not negative"));
    }
    if data.alpha.len() != flexure.order() {
        return Err(Error::invalid("data", data.alpha.len(), "was made for a flexure of another order"));
    }
    data.kinematics.check_fits(flexure)?;
    Ok(flexure.ei() / flexure.length() + tension * (tendon.root_offset.abs() + tendon.tip_offset.abs()))
}

/// [`pull`], or with `while_stable` stopping where the path loses stability.
fn follow(
    flexure: &Flexure,
    tendon: &TendonOffsets,
    tension: f64,
    data: &mut TendonData,
    while_stable: bool,
) -> Result<Equilibrium> {
    let scale = checked(flexure, tendon, tension, data)?;
    data.solver.x.copy_from_slice(&data.alpha);
    let mut problem = TendonProblem {
        potential: TendonPotential { flexure, tendon: *tendon, tension: 0.0, kinematics: &mut data.kinematics },
        start: data.tension,
        end: tension,
        scale,
        scratch: &mut data.scratch,
    };
    let path = if while_stable {
        solver::continuation_while_stable(&mut problem, &mut data.solver, &Settings::default())?
    } else {
        solver::continuation(&mut problem, &mut data.solver, &Settings::default())?
    };
    data.alpha.copy_from_slice(&data.solver.x);
    data.tension = tension;
    Ok(Equilibrium::from_path(&path))
}

/// The equilibrium under the full `tension` nearest to `alpha`: Newton
/// alone, with no continuation. Leaves the solution in `data`.
pub fn correct(
    flexure: &Flexure,
    tendon: &TendonOffsets,
    tension: f64,
    alpha: &[f64],
    data: &mut TendonData,
) -> Result<Equilibrium> {
    tendon.validate()?; // before alpha's check, as the errors have always come
    flexure.check_coordinates("alpha", alpha)?;
    let scale = checked(flexure, tendon, tension, data)?;
    data.solver.x.copy_from_slice(alpha);
    let mut problem = TendonProblem {
        potential: TendonPotential { flexure, tendon: *tendon, tension: 0.0, kinematics: &mut data.kinematics },
        start: tension,
        end: tension,
        scale,
        scratch: &mut data.scratch,
    };
    let report = solver::newton(&mut problem, &mut data.solver, 1.0, &Settings::default())?;
    let stable = solver::Problem::stable(&mut problem, &data.solver.x, 1.0, &data.solver.jacobian);
    data.alpha.copy_from_slice(&data.solver.x);
    data.tension = tension;
    Ok(Equilibrium { stable, limit: None, residual: report.residual, iterations: report.iterations, load_steps: 0 })
}
