//! Howell's procedure for the 1R constants of a cantilever under an end
//! force of fixed direction (Howell and Midha 1995; Howell, *Compliant
//! Mechanisms*, 2001, Sec. 5.3 and Table 5.1).

use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::kinematics::Pose;
use crate::statics::{Settings, StaticsData, TipLoad, correct, deflect};

/// What Howell's relative error is measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum ErrorMeasure {
    /// The tip's distance from the PRB tip over the tip's deflection
    /// $\delta = \lvert r - r_0\rvert$ (Howell and Midha's "relative deflection error").
    Deflection,
    /// The same distance over the length $L$.
    Length,
}

/// One point of a loading path: the end load and the beam's tip under it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// The end load, root frame.
    pub load: TipLoad,
    /// The beam's tip pose under it, root frame.
    pub tip: Pose,
}

/// Howell's 1R constants for one force direction.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HowellFit {
    /// The characteristic radius factor $\gamma$ that maximizes $\Theta_{max}$.
    pub gamma: f64,
    /// The largest PRB angle $\Theta$ up to which the error stays within the tolerance (rad).
    pub theta_max: f64,
    /// The stiffness coefficient $K_\Theta$: the least-squares slope through
    /// the origin of $\alpha_t^2 = F_tL^2/EI$ against $\Theta$ on $[0, \Theta_{max}]$,
    /// $K_\Theta = \int\Theta\alpha_t^2\thinspace d\Theta / \int\Theta^2\thinspace d\Theta$.
    /// At $n = 0$ this is Howell's 2.67617 within 0.8 %; for $n \ne 0$ it is
    /// not Howell and Midha's fit $K_\Theta(n)$, which falls with $n$ while this
    /// grows (+11.9 % at $n = 10$): no rule measured reproduces theirs within
    /// 1 % (VALIDATION.md, section PRB).
    pub k_theta: f64,
    /// The parametric angle coefficient $c_\theta$: the least-squares slope
    /// through the origin of the tip angle $\theta_0$ against $\Theta$ on $[0, \Theta_{max}]$,
    /// $c_\theta = \int\Theta\theta_0\thinspace d\Theta / \int\Theta^2\thinspace d\Theta$.
    pub c_theta: f64,
}

/// Grid points of the search over $\gamma$.
const GRID: usize = 801;
/// The range of $\gamma$ searched.
const RANGE: (f64, f64) = (0.6, 1.0);
/// Bisection steps locating the edge of the best $\gamma$.
const BISECTIONS: usize = 60;

/// The loading path of Howell's cantilever: end forces
/// $F = P(-n, 1)$ (a transverse force $P$ and an axial one $nP$, $n > 0$
/// compressive), with $PL^2/EI$ from 0 to `top` in `count` steps (quadratic
/// in the step index, so small deflections are sampled finely), solved by
/// the Smooth Curvature Model along the loading path: the first load by
/// continuation from rest ([`deflect`]), each next one by Newton from the
/// previous equilibrium ([`correct`]). Solving each load from rest instead
/// can land on another stable branch once the axial part $nP$ passes the
/// buckling load $\pi^2EI/4L^2$ (measured: at $n = 4$ and 5 the tip swung
/// to $\Theta \approx -78°$, which moved Howell's $\gamma$ from 0.821 to 0.809).
///
/// Errors: non-finite `n`, non-finite or non-positive `top`, fewer than 2
/// points; the model's solver errors; a load past a buckling or limit load.
///
/// # Example
/// ```
/// use flexure::prb::howell;
/// let f = flexure::Flexure::new(1.0, 1.0, 6)?;
/// let path = howell::path(&f, 0.0, 2.0, 20)?;
/// assert_eq!(path.len(), 20);
/// assert!((path[19].load.fy - 2.0).abs() < 1e-15 && path[19].tip.phi > 0.5);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn path(f: &Flexure, n: f64, top: f64, count: usize) -> Result<Vec<PathPoint>> {
    crate::error::finite("n", n)?;
    crate::error::positive("top", top)?;
    if count < 2 {
        return Err(Error::invalid("count", count, "must be at least 2"));
    }
    let scale = f.ei() / (f.length() * f.length());
    let mut data = StaticsData::new(f);
    let settings = Settings::default();
    let mut alpha = Vec::new();
    (1..=count)
        .map(|k| {
            let p = top * scale * (k as f64 / count as f64).powi(2);
            let load = TipLoad { moment: 0.0, fx: -n * p, fy: p };
            let eq = if k == 1 {
                deflect(f, &load, &mut data, &settings)?
            } else {
                correct(f, &load, &alpha, &mut data, &settings)?
            };
            if !eq.stable || eq.limit.is_some() {
                return Err(Error::invalid("top", top, "takes the path past a buckling or limit load"));
            }
            alpha.clear();
            alpha.extend_from_slice(data.alpha());
            Ok(PathPoint { load, tip: data.pose_root_tip() })
        })
        .collect()
}

/// The PRB angle and the relative error of the 1R model with factor
/// `gamma` at each path point, in path order.
fn errors(f: &Flexure, path: &[PathPoint], gamma: f64, measure: ErrorMeasure) -> impl Iterator<Item = (f64, f64)> {
    let l = f.length();
    let pivot = (1.0 - gamma) * l;
    path.iter().map(move |p| {
        let (dx, dy) = (p.tip.x - pivot, p.tip.y);
        let theta = dy.atan2(dx);
        let radial = (dx.hypot(dy) - gamma * l).abs();
        let scale = match measure {
            ErrorMeasure::Deflection => (p.tip.x - l).hypot(p.tip.y),
            ErrorMeasure::Length => l,
        };
        (theta, if scale > 0.0 { radial / scale } else { 0.0 })
    })
}

/// $\Theta_{max}(\gamma)$: the PRB angle where the error first exceeds
/// `tolerance`, interpolated linearly between path points (the last
/// point's angle if it never does).
fn theta_max(f: &Flexure, path: &[PathPoint], gamma: f64, tolerance: f64, measure: ErrorMeasure) -> f64 {
    let (mut last_t, mut last_e) = (0.0, 0.0);
    for (t, e) in errors(f, path, gamma, measure) {
        if e > tolerance {
            return last_t + (t - last_t) * (tolerance - last_e) / (e - last_e);
        }
        (last_t, last_e) = (t, e);
    }
    last_t
}

/// Howell's procedure on a straight cantilever's loading `path` (end
/// forces of one direction, growing; as [`path`] makes, or from the exact
/// elastica): for each $\gamma$, the 1R tip at the PRB angle
/// $\Theta = \operatorname{atan2}(y, x - (1-\gamma)L)$ of the beam's tip
/// $(x, y)$ is compared with it, and $\Theta_{max}(\gamma)$ is the PRB angle
/// where the relative error ([`ErrorMeasure`]) first exceeds `tolerance`
/// (Howell: 0.5 %); $\gamma$ maximizes $\Theta_{max}$ (an 801-point grid on
/// $[0.6, 1]$, then 60 bisections on the edge where $\Theta_{max}$ drops).
/// Then, on $[0, \Theta_{max}]$, $K_\Theta$ is the least-squares slope of
/// $\alpha_t^2 = F_tL^2/EI$ against $\Theta$, with
/// $F_t = -F_x\sin\Theta + F_y\cos\Theta$ the force across the PRB link
/// (so the spring is $K = \gamma K_\Theta EI/L$), and $c_\theta$ that of
/// the tip angle against $\Theta$.
///
/// Errors: fewer than 2 points, a tolerance not in $(0, 1)$, a rest-curved flexure.
///
/// # Example
/// ```
/// use flexure::prb::howell::{self, ErrorMeasure};
/// let f = flexure::Flexure::new(1.0, 1.0, 8)?;
/// let path = howell::path(&f, 0.0, 12.0, 150)?;
/// let h = howell::fit(&f, &path, 0.005, ErrorMeasure::Deflection)?;
/// assert!((h.gamma - 0.8517).abs() < 0.01 && (h.k_theta - 2.676).abs() < 0.05);
/// # Ok::<(), flexure::Error>(())
/// ```
pub fn fit(f: &Flexure, path: &[PathPoint], tolerance: f64, measure: ErrorMeasure) -> Result<HowellFit> {
    if path.len() < 2 {
        return Err(Error::invalid("path", path.len(), "must have at least 2 points"));
    }
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(Error::invalid("tolerance", tolerance, "must be in (0, 1)"));
    }
    if f.rest().iter().any(|&k| k != 0.0) {
        return Err(Error::invalid("flexure", "rest-curved", "Howell's procedure is for a straight cantilever"));
    }
    let reach = |g: f64| theta_max(f, path, g, tolerance, measure);
    let h = (RANGE.1 - RANGE.0) / (GRID - 1) as f64;
    let best = (0..GRID)
        .map(|i| (i, reach(RANGE.0 + i as f64 * h)))
        .fold((0, f64::NEG_INFINITY), |b, (i, v)| if v > b.1 { (i, v) } else { b });
    // Θmax grows with γ up to where the error's first hump touches the
    // tolerance, then drops: bisect for that edge between the best grid
    // point and the next.
    let (mut lo, mut hi) = (RANGE.0 + best.0 as f64 * h, (RANGE.0 + (best.0 + 1) as f64 * h).min(RANGE.1));
    let mut theta = best.1;
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        let t = reach(mid);
        if t >= theta {
            (lo, theta) = (mid, t);
        } else {
            hi = mid;
        }
    }
    let gamma = lo;
    // Least squares in the continuous sense, the trapezoidal rule over the
    // path's PRB angles: the answer does not depend on how the path is sampled.
    let scale = f.length() * f.length() / f.ei();
    let points: Vec<[f64; 3]> = path
        .iter()
        .zip(errors(f, path, gamma, measure))
        .take_while(|(_, (t, _))| *t <= theta)
        .map(|(p, (t, _))| {
            let (s, c) = t.sin_cos();
            [t, (-p.load.fx * s + p.load.fy * c) * scale, p.tip.phi]
        })
        .collect();
    let (mut tt, mut tk, mut tc) = (0.0, 0.0, 0.0);
    for w in points.windows(2) {
        let d = 0.5 * (w[1][0] - w[0][0]);
        tt += d * (w[0][0] * w[0][0] + w[1][0] * w[1][0]);
        tk += d * (w[0][0] * w[0][1] + w[1][0] * w[1][1]);
        tc += d * (w[0][0] * w[0][2] + w[1][0] * w[1][2]);
    }
    Ok(HowellFit { gamma, theta_max: theta, k_theta: tk / tt, c_theta: tc / tt })
}
