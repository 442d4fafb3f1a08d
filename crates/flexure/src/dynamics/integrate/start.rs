//! The consistent start: the directions with neither inertia nor damping
//! obey algebraic equations at $t = 0$, and a start off them is first
//! moved onto them (IDA's `IDACalcIC`).

use super::{MotionSettings, fatal, largest};
use crate::dynamics::System;
use crate::error::Result;
use crate::linalg;

/// Iterations of [`consistent_start`]'s Newton method.
const START_ITERATIONS: usize = 30;

/// Moves `q` onto the quasi-static equilibrium of the directions with
/// neither inertia nor damping ([`massless_directions`], a basis $N$),
/// keeping the others: it solves for $y$ and $\lambda$
/// $$r = N^T\bigl(G(q)^T\lambda - f(q, \dot q_0, 0)\bigr) = 0,\qquad c(q) = 0,
/// \qquad q = q_0 + Ny,$$
/// by Newton's method ([`start_step`]; closure forces acting only on
/// massive coordinates are left to the motion). These are the algebraic
/// equations of the system at $t = 0$: a start that violates them (a
/// massless flexure at its unloaded shape under a load) has no consistent
/// first step, the error of whichever jump the first step makes does not
/// shrink with the step, and at tight tolerances the run stalls there. DAE
/// codes compute consistent initial values the same way (IDA's
/// `IDACalcIC` for the algebraic components).
///
/// The answer is taken when the last correction is below $10^{-3}$ of the
/// tolerance (or rounding's level in the coordinates) and, evaluated there,
/// $r$ has fallen below $10^{-8}$ of its start's (or rounding's level) and
/// the closure violation is no larger than the start's (or `absolute`).
/// Otherwise, or after [`START_ITERATIONS`], `q` is left as it was and the
/// first step projects it. Returns whether there are such directions.
pub(super) fn consistent_start<S: System + ?Sized>(
    system: &mut S,
    q: &mut [f64],
    v: &[f64],
    settings: &MotionSettings,
) -> Result<bool> {
    use nalgebra::{DMatrix, DVector};
    let (n, m) = (system.dim(), system.closures());
    let (mut mass, mut force) = (vec![0.0; n * n], vec![0.0; n]);
    let (mut k, mut d) = (vec![0.0; n * n], vec![0.0; n * n]);
    let (mut c, mut g) = (vec![0.0; m], vec![0.0; m * n]);
    system.dynamics(q, v, 0.0, &mut mass, &mut force)?;
    system.tangent(q, v, 0.0, &mut k, &mut d)?;
    let basis = massless_directions(n, &mass, &d);
    if basis.ncols() == 0 {
        return Ok(false);
    }
    let start = q.to_vec();
    let (mut start_violation, mut start_residual) = (0.0, 0.0);
    let mut lambda = DVector::<f64>::zeros(m);
    let mut converged = false;
    for iteration in 0..=START_ITERATIONS {
        // A state Newton moved to that cannot be evaluated ends the attempt.
        let evaluated = if iteration > 0 {
            system.dynamics(q, v, 0.0, &mut mass, &mut force).and_then(|()| system.tangent(q, v, 0.0, &mut k, &mut d))
        } else {
            Ok(())
        }
        .and_then(|()| if m > 0 { system.closure(q, &mut c, &mut g) } else { Ok(()) });
        match evaluated {
            Ok(()) => {}
            Err(e) if fatal(&e) => return Err(e),
            Err(_) => break,
        }
        // G is m × n, column-major.
        let g_matrix = DMatrix::from_column_slice(m, n, &g);
        let closure_force = g_matrix.transpose() * &lambda;
        let residual = basis.transpose() * DVector::from_fn(n, |r, _| closure_force[r] - force[r]);
        let stiffness = basis.transpose() * DMatrix::from_column_slice(n, n, &k) * &basis;
        if iteration == 0 {
            (start_violation, start_residual) = (largest(&c), residual.amax());
        }
        if converged {
            // Rounding's level of r: its terms' size, and the stiffness times the coordinates.
            let terms = (basis.transpose() * DVector::from_column_slice(&force)).amax().max(closure_force.amax());
            let noise = 1e3 * f64::EPSILON * terms.max(stiffness.amax() * largest(q));
            if largest(&c) <= start_violation.max(settings.absolute)
                && residual.amax() <= (1e-8 * start_residual).max(noise)
            {
                return Ok(true);
            }
            break;
        }
        if iteration == START_ITERATIONS {
            break;
        }
        let Some((dy, dlambda)) =
            start_step(&stiffness, &(&g_matrix * &basis), &residual, &DVector::from_column_slice(&c))
        else {
            break;
        };
        let dq = &basis * dy;
        lambda += dlambda;
        let mut size: f64 = 0.0;
        for r in 0..n {
            q[r] += dq[r];
            let scale = settings.absolute + settings.tolerance * q[r].abs();
            size = size.max(dq[r].abs() / scale);
        }
        let floor = dq.iter().zip(q.iter()).all(|(x, y)| x.abs() <= 1e3 * f64::EPSILON * (1.0 + y.abs()));
        converged = (size <= 1e-3 || floor) && q.iter().all(|x| x.is_finite());
    }
    q.copy_from_slice(&start);
    Ok(true)
}

/// A basis (columns) of the directions with neither inertia nor damping:
/// the null space of $M$ and $D_t$ stacked, each row over its largest
/// entry (a row is one coordinate's equation: this makes the test
/// independent of the coordinates' units), singular values below
/// $10^{-13}$ of the largest counting as zero: far above rounding (a
/// massless direction gives about $10^{-19}$) and below real mass ratios.
/// A massless direction with damping follows a first-order equation from
/// its start, and is not one of them.
fn massless_directions(n: usize, mass: &[f64], damping: &[f64]) -> nalgebra::DMatrix<f64> {
    let mut stacked = nalgebra::DMatrix::zeros(2 * n, n);
    for (block, values) in [(0, mass), (n, damping)] {
        for r in 0..n {
            let top = (0..n).fold(0.0, |a: f64, col| a.max(values[col * n + r].abs()));
            if top > 0.0 {
                for col in 0..n {
                    stacked[(block + r, col)] = values[col * n + r] / top;
                }
            }
        }
    }
    linalg::null_space_below(&stacked, 1e-13)
}

/// One Newton step of [`consistent_start`] by the null-space method, for
/// the stiffness $A = N^TK_tN$, $B = GN$, the residual $r$ and closures
/// $c$: $\delta y_p = -B^+c$ (least norm), then with $Z$ spanning the null
/// space of $B$, $Z^TAZ\thinspace b = -Z^T(r + A\delta y_p)$,
/// $\delta y = \delta y_p + Zb$, and $\delta\lambda$ from
/// $B^T\delta\lambda = -(r + A\delta y)$ in least squares. Only redundant closures are cut off; $Z^TAZ$ is solved
/// down to $10^{-14}$ of its largest singular value, so a soft massless
/// flexure beside a stiff massless spring keeps its step. `None` when a
/// step is not finite.
fn start_step(
    a: &nalgebra::DMatrix<f64>,
    b: &nalgebra::DMatrix<f64>,
    r: &nalgebra::DVector<f64>,
    c: &nalgebra::DVector<f64>,
) -> Option<(nalgebra::DVector<f64>, nalgebra::DVector<f64>)> {
    let free = a.ncols();
    let (particular, z) = if b.nrows() == 0 {
        (nalgebra::DVector::zeros(free), nalgebra::DMatrix::identity(free, free))
    } else {
        (linalg::least_squares(b, &(-c)), linalg::null_space(b))
    };
    // Closures that leave no motion: the particular step is the whole step
    // (nalgebra's SVD refuses an empty matrix).
    let coefficients = if z.ncols() == 0 {
        nalgebra::DVector::zeros(0)
    } else {
        let reduced = z.transpose() * a * &z;
        let rhs = -(z.transpose() * (r + a * &particular));
        let svd = nalgebra::SVD::new(reduced, true, true);
        let cutoff = 1e-14 * svd.singular_values.amax();
        svd.solve(&rhs, cutoff).ok()?
    };
    let dy = particular + z * coefficients;
    let dlambda = if b.nrows() == 0 {
        nalgebra::DVector::zeros(0)
    } else {
        linalg::least_squares(&b.transpose(), &(-(r + a * &dy)))
    };
    let finite = dy.iter().chain(dlambda.iter()).all(|x| x.is_finite());
    finite.then_some((dy, dlambda))
}
