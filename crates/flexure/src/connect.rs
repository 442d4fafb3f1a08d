//! The minimum-energy shape between two poses (paper Sec. II-E, Eq. 16).

use crate::energy::{energy, energy_gradient, energy_gradient_entry};
use crate::error::{Error, Result, finite};
use crate::flexure::{Basis, Flexure};
use crate::kinematics::{self, Kinematics, Level, Pose};
use crate::solver;
use crate::statics::{self, Settings, TipLoad, rotation};
use nalgebra::DVector;

/// A minimum-energy shape. Serialized as the CLI prints it and Python
/// returns it: `{alpha, energy, load: {moment, fx, fy}}` (the iteration
/// count is the solver's, not part of the answer).
///
/// # Example
/// ```
/// use flexure::{connect::connect, Flexure, Pose};
/// let f = Flexure::new(1.0, 1.0, 3)?;
/// // A constant-curvature arc of angle 0.5: x = sin(0.5)/0.5, y = (1 − cos 0.5)/0.5.
/// let arc = Pose { phi: 0.5, x: 0.5f64.sin() / 0.5, y: (1.0 - 0.5f64.cos()) / 0.5 };
/// let c = connect(&f, &arc)?;
/// let v = serde_json::to_value(&c).unwrap();
/// let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
/// assert_eq!(keys, ["alpha", "energy", "load"]);
/// // The arc is held by a pure moment EI·φ/L = 0.5 N·m.
/// assert!((v["load"]["moment"].as_f64().unwrap() - 0.5).abs() < 1e-9);
/// # Ok::<(), flexure::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Connection {
    /// Joint coordinates.
    pub alpha: Vec<f64>,
    /// Bending energy $U(\alpha)$ (J).
    pub energy: f64,
    /// The tip load that holds this shape: the Lagrange multipliers of the
    /// three tip constraints, $\nabla U = \mathcal J^T (M, F_x, F_y)$.
    pub load: TipLoad,
    /// Newton iterations.
    #[serde(skip)]
    pub iterations: usize,
}

impl Connection {
    /// The energy error of Eq. 16 against the exact minimum energy $U^{\ast}$
    /// through the same pose: $\eta = U(\alpha^{\ast})/U^{\ast} - 1$, not negative
    /// when $U^{\ast}$ is the true minimum (the model's shapes are a subset of
    /// the elastica's).
    ///
    /// # Example
    /// ```
    /// use flexure::{connect::connect, Flexure, Pose};
    /// let f = Flexure::new(1.0, 1.0, 3)?;
    /// // An arc of angle 0.5 is in the model's basis: its energy is the exact
    /// // EI·φ²/(2L) = 0.125 J, so η vanishes to rounding.
    /// let arc = Pose { phi: 0.5, x: 0.5f64.sin() / 0.5, y: (1.0 - 0.5f64.cos()) / 0.5 };
    /// assert!(connect(&f, &arc)?.eta(0.125).abs() < 1e-12);
    /// # Ok::<(), flexure::Error>(())
    /// ```
    pub fn eta(&self, exact_energy: f64) -> f64 {
        self.energy / exact_energy - 1.0
    }
}

/// Checks that a tip pose is finite and within reach of an inextensible flexure.
pub fn check_pose(flexure: &Flexure, target: &Pose) -> Result<()> {
    finite("pose", target.phi)?;
    finite("pose", target.x)?;
    finite("pose", target.y)?;
    let r = target.x.hypot(target.y);
    if r >= flexure.length() {
        return Err(Error::invalid(
            "pose",
            format!("({}, {}, {}) at distance {r} from the root", target.phi, target.x, target.y),
            "the tip must lie closer to the root than the length L",
        ));
    }
    Ok(())
}

/// Buffers for [`connect_with`] on one flexure: kinematics and the
/// solver's workspace, reused from call to call (the Data of [`connect`]).
#[derive(Debug, Clone)]
pub struct ConnectData {
    kinematics: Kinematics<f64>,
    solver: solver::SolverWorkspace<f64>,
}

impl ConnectData {
    /// Buffers sized for `flexure`.
    pub fn new(flexure: &Flexure) -> Self {
        Self { kinematics: Kinematics::new(flexure), solver: solver::SolverWorkspace::new(flexure.order() + 3) }
    }
}

/// The coordinates of least energy $U(\alpha)$ whose tip reaches `target`.
///
/// Newton on the KKT conditions of $\min U$ s.t. tip pose = target,
/// $$\begin{bmatrix} K & -\mathcal J^T\cr \mathcal J & 0\end{bmatrix}
/// \begin{bmatrix}\delta\alpha\cr \delta\lambda\end{bmatrix} = -
/// \begin{bmatrix}\nabla U - \mathcal J^T\lambda\cr p(\alpha) - p^*\end{bmatrix},$$
/// with $K = \nabla\nabla U - F_x\nabla\nabla x - F_y\nabla\nabla y$ (Eq. 32), followed by the
/// shared continuation ([`crate::solver`]) from the circular arc with the
/// target's tip angle, whose tip is moved to the target. For the paper's
/// $N = 3$ this solves Eqs. 11, 14 and 15 ($\alpha_1 = \phi$, two equations
/// in $\alpha_2, \alpha_3$), with the multipliers alongside.
///
/// Allocates its buffers on every call: [`connect_with`] reuses them.
///
/// # Example
/// ```
/// use flexure::{connect::connect, Flexure, Pose};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// // The tip of a circular arc of angle 1 is reached by that arc.
/// let target = Pose { phi: 1.0, x: 1f64.sin(), y: 1.0 - 1f64.cos() };
/// let c = connect(&f, &target).unwrap();
/// assert!((c.alpha[0] - 1.0).abs() < 1e-12 && c.alpha[1].abs() < 1e-8);
/// ```
pub fn connect(flexure: &Flexure, target: &Pose) -> Result<Connection> {
    connect_with(flexure, target, &mut ConnectData::new(flexure))
}

/// [`connect`] on buffers made once by [`ConnectData::new`] (for this
/// flexure, or any of the same order and quadrature rule): the same answer,
/// and the only allocation is the answer's coordinates ([`Connection::alpha`]).
/// Buffers of another order or rule are an error naming `data`.
///
/// # Example
/// ```
/// use flexure::{connect::{connect, connect_with, ConnectData}, Flexure, Pose};
/// let f = Flexure::new(1.0, 1.0, 3).unwrap();
/// let mut data = ConnectData::new(&f);
/// let target = Pose { phi: 1.5, x: 0.55, y: 0.65 };
/// assert_eq!(connect_with(&f, &target, &mut data).unwrap(), connect(&f, &target).unwrap());
/// ```
pub fn connect_with(flexure: &Flexure, target: &Pose, data: &mut ConnectData) -> Result<Connection> {
    check_pose(flexure, target)?;
    let n = flexure.order();
    if n < 3 {
        return Err(Error::invalid("order", n, "must be at least 3 to reach a tip pose (three constraints)"));
    }
    data.kinematics.check_fits(flexure)?;
    let ConnectData { kinematics: k, solver: ws, .. } = data;
    arc(flexure, target.phi, &mut ws.x[..n]);
    kinematics::update(flexure, &ws.x[..n], k, Level::Jacobian);
    let from = k.pose_root_tip;
    let settings = Settings { tolerance: TOLERANCE, ..Default::default() };
    let (alpha, multipliers) = ws.x.split_at_mut(n);
    // Multipliers that solve λ = 0 outright where some do (a uniform arc
    // is held by the pure moment EI·φ/L), so the start needs no Newton
    // step; elsewhere (a rest curvature, a varying section) zero, as before.
    let load = holding_load(flexure, alpha, k);
    multipliers.copy_from_slice(&load.unwrap_or([0.0; 3]));
    let mut problem = ConnectProblem { flexure, kinematics: k, from, target: *target };
    let path = solver::continuation(&mut problem, ws, &settings)?;
    let alpha = ws.x[..n].to_vec();
    let load = TipLoad { moment: ws.x[n], fx: ws.x[n + 1], fy: ws.x[n + 2] };
    Ok(Connection { energy: energy(flexure, &alpha), alpha, load, iterations: path.iterations })
}

/// The multipliers $\mu$ with $\nabla U = \mathcal J^T\mu$ at `alpha`
/// (with `k` at `alpha`, Jacobian level) to [`connect`]'s tolerance in its
/// scaled residual, if there are such: the least-squares solution by the
/// normal equations $\mathcal J\mathcal J^T\mu = \mathcal J\nabla U$, checked
/// entry by entry as the solver will check it.
fn holding_load(flexure: &Flexure, alpha: &[f64], k: &Kinematics<f64>) -> Option<[f64; 3]> {
    let j = k.jacobian_root_tip.as_slice();
    let scale = flexure.ei() / flexure.length();
    let (mut normal, mut rhs) = ([0.0; 9], [0.0; 3]);
    for (i, jc) in j.chunks_exact(3).enumerate() {
        let g = energy_gradient_entry(flexure, alpha, i);
        for a in 0..3 {
            rhs[a] += jc[a] * g;
            for b in 0..3 {
                normal[3 * a + b] += jc[a] * jc[b];
            }
        }
    }
    if !crate::linalg::cholesky(&mut normal, 3) {
        return None;
    }
    crate::linalg::cholesky_solve(&normal, 3, &mut rhs);
    // The residual's first block as ConnectProblem::evaluate writes it.
    j.chunks_exact(3)
        .enumerate()
        .all(|(i, jc)| stationarity(energy_gradient_entry(flexure, alpha, i), jc, rhs, scale).abs() <= TOLERANCE)
        .then_some(rhs)
}

/// One entry of the scaled KKT residual's first block,
/// $(\partial_iU - \mathcal J_{\cdot i}\cdot\mu)/(EI/L)$, from $\partial_iU$ and
/// the tip Jacobian's column $i$ ($\phi$, $x$, $y$).
fn stationarity(gradient: f64, column: &[f64], [mo, fx, fy]: [f64; 3], scale: f64) -> f64 {
    (gradient - (column[0] * mo + column[1] * fx + column[2] * fy)) / scale
}

/// [`connect`]'s tolerance on the scaled KKT residual.
const TOLERANCE: f64 = 1e-13;

/// Writes the coordinates of the circular arc with tip angle `phi` into `alpha`.
fn arc(flexure: &Flexure, phi: f64, alpha: &mut [f64]) {
    let n = flexure.order();
    match flexure.basis() {
        Basis::Legendre => {
            alpha.fill(0.0);
            alpha[0] = phi;
        }
        Basis::Segments => alpha.fill(phi / n as f64),
    }
}

/// The KKT system in $z = (\alpha, M, F_x, F_y)$, with the target moved
/// from `from` (at $\lambda = 0$) to `target` (at $\lambda = 1$); the first
/// block is scaled by $L/EI$ and the second by $1/L$, so both are dimensionless.
struct ConnectProblem<'a> {
    flexure: &'a Flexure,
    kinematics: &'a mut Kinematics<f64>,
    from: Pose,
    target: Pose,
}

impl solver::Problem<f64> for ConnectProblem<'_> {
    fn dim(&self) -> usize {
        self.flexure.order() + 3
    }

    fn evaluate(
        &mut self,
        z: &[f64],
        lambda: f64,
        r: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> Result<()> {
        let (f, k) = (self.flexure, &mut *self.kinematics);
        let (n, m) = (f.order(), f.order() + 3);
        let (l, scale) = (f.length(), f.ei() / f.length());
        let alpha = &z[..n];
        kinematics::update(f, alpha, k, if jacobian.is_some() { Level::Hessian } else { Level::Jacobian });
        energy_gradient(f, alpha, &mut r[..n]);
        let (mo, fx, fy) = (z[n], z[n + 1], z[n + 2]);
        // The tip Jacobian column-major, three rows (φ, x, y) per coordinate.
        let j = k.jacobian_root_tip.as_slice();
        for (r, j) in r[..n].iter_mut().zip(j.chunks_exact(3)) {
            *r = stationarity(*r, j, [mo, fx, fy], scale);
        }
        let p = k.pose_root_tip;
        let goal = |a: f64, b: f64| a + lambda * (b - a);
        r[n] = p.phi - goal(self.from.phi, self.target.phi);
        r[n + 1] = (p.x - goal(self.from.x, self.target.x)) / l;
        r[n + 2] = (p.y - goal(self.from.y, self.target.y)) / l;
        if let Some(d) = dlambda {
            d[..n].fill(0.0);
            d[n] = -(self.target.phi - self.from.phi);
            d[n + 1] = -(self.target.x - self.from.x) / l;
            d[n + 2] = -(self.target.y - self.from.y) / l;
        }
        if let Some(jac) = jacobian {
            // Column c: (K − Fx∇∇x − Fy∇∇y)/scale over 𝒥 with its x, y rows over L;
            // the multipliers' columns: −𝒥ᵀ/scale over zeros.
            let (coordinates, multipliers) = jac[..m * m].split_at_mut(n * m);
            statics::loaded_stiffness_into(f, k, [fx, fy], 1.0, coordinates, m);
            for (column, jc) in coordinates.chunks_exact_mut(m).zip(j.chunks_exact(3)) {
                let (top, bottom) = column.split_at_mut(n);
                top.iter_mut().for_each(|t| *t /= scale);
                bottom.copy_from_slice(&[jc[0], jc[1] / l, jc[2] / l]);
            }
            for (a, column) in multipliers.chunks_exact_mut(m).enumerate() {
                for (t, jc) in column[..n].iter_mut().zip(j.chunks_exact(3)) {
                    *t = -jc[a] / scale;
                }
                column[n..].fill(0.0);
            }
        }
        Ok(())
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        rotation(self.flexure, a, Some(b))
    }

    fn weight(&self, i: usize) -> f64 {
        // Arc length in the coordinates only: the multipliers follow them.
        if i < self.flexure.order() { 1.0 } else { 0.0 }
    }

    fn scale(&self) -> f64 {
        1.0
    }

    fn unit(&self) -> &'static str {
        "relative"
    }

    fn name(&self) -> &'static str {
        "connect"
    }
}

/// The tip load that holds `alpha` in equilibrium: the least-squares
/// solution of $\nabla U = \mathcal J^T\lambda$ (exact at a KKT point, and
/// for any equilibrium under a tip load), with `k` evaluated at `alpha`.
pub fn tip_load(flexure: &Flexure, alpha: &[f64], k: &Kinematics<f64>) -> Result<TipLoad> {
    let mut g = vec![0.0; alpha.len()];
    energy_gradient(flexure, alpha, &mut g);
    let l = crate::linalg::least_squares(&k.jacobian_root_tip.transpose(), &DVector::from_vec(g));
    Ok(TipLoad { moment: l[0], fx: l[1], fy: l[2] })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The start's multipliers against the closed form: a uniform arc of
    /// tip angle φ is held by the pure moment $EI\phi/L$ (Legendre and
    /// segments, several EI/L); with a rest curvature the arc is not held
    /// by any tip load (its curvature differs from the rest one along the
    /// length), so there are none and the start stays at zero.
    #[test]
    fn start_multipliers_are_the_arcs_moment() {
        for f in [
            Flexure::new(1.0, 1.0, 3).unwrap(),
            Flexure::new(0.02, 3.0, 6).unwrap(),
            Flexure::segments(1.5, 0.4, 22).unwrap(),
        ] {
            let n = f.order();
            let mut k = Kinematics::new(&f);
            for phi in [-2.0, 0.3, std::f64::consts::FRAC_PI_2] {
                let mut alpha = vec![0.0; n];
                arc(&f, phi, &mut alpha);
                kinematics::update(&f, &alpha, &mut k, Level::Jacobian);
                let [mo, fx, fy] = holding_load(&f, &alpha, &k).expect("an arc is held by a moment");
                let moment = f.ei() * phi / f.length();
                // Rounding of the 3×3 normal equations, which square the
                // conditioning of 𝒥 (forces count by their moment F·L).
                let tol = 1e-12 * moment.abs();
                assert!(
                    (mo - moment).abs() < tol && fx.abs() * f.length() < tol && fy.abs() * f.length() < tol,
                    "order {n}, φ = {phi}: {:?} against {moment}",
                    [mo, fx, fy]
                );
            }
        }
        let f = Flexure::new(1.0, 1.0, 4).unwrap().with_rest(&[0.4, -0.2, 0.1, 0.0]).unwrap();
        let mut k = Kinematics::new(&f);
        let alpha = [1.0, 0.0, 0.0, 0.0];
        kinematics::update(&f, &alpha, &mut k, Level::Jacobian);
        assert_eq!(holding_load(&f, &alpha, &k), None);
    }
}
