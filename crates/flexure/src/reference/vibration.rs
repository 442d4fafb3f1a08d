//! Exact linear vibration of a straight Euler–Bernoulli beam (with rotary
//! inertia: a Rayleigh beam), root clamped, tip free or carrying a rigid
//! [`Body`], under an optional axial compression or tension: natural
//! frequencies counted by the Wittrick–Williams argument and refined on the
//! dynamic stiffness determinant.
//!
//! The lateral deflection $w(s)\cos\omega t$ obeys
//!
//! $$(EI\thinspace w^{\prime\prime})^{\prime\prime} + P w^{\prime\prime} = \mu\omega^2 w - (\rho I\thinspace\omega^2 w^{\prime})^{\prime},$$
//!
//! written as four first-order equations in $w$, $\theta = w^{\prime}$, the bending
//! moment $\mathcal M = EI\thinspace w^{\prime\prime}$ and the shear
//! $S = \mathcal M^{\prime} + (P + \rho I\omega^2)\theta$:
//! $w^{\prime} = \theta$, $\theta^{\prime} = \mathcal M/EI$, $\mathcal M^{\prime} = S - (P + \rho I\omega^2)\theta$,
//! $S^{\prime} = \mu\omega^2 w$. It is the stationarity condition of
//!
//! $$\Pi = \tfrac12\int_0^L \big(EI\thinspace w^{\prime\prime 2} - (P + \rho I\omega^2)w^{\prime 2} - \mu\omega^2 w^2\big)ds -
//! \tfrac12\omega^2 u_L^T M_b u_L,$$
//!
//! with $u_L = (w, \theta)(L)$ and the body's mass matrix about the tip
//! $M_b = [m, mc_x; mc_x, I_{tip}]$ ($I_{tip} = I_c + m\lvert c\rvert^2$, the
//! axial inertia of an offset $c_y$ entering through $I_{tip}$). A free tip is
//! the body of zero mass.
//!
//! **Counting.** The beam is cut into elements short enough that none has a
//! natural frequency of its own with both ends clamped below the trial
//! $\omega$ (a Rayleigh-quotient bound, below); each element's exact
//! dynamic stiffness $K_e(\omega)$, the $4\times4$ matrix of end forces
//! $(S_0, -\mathcal M_0, -S_1, \mathcal M_1)$ against end motions
//! $(w_0, \theta_0, w_1, \theta_1)$, comes from its transfer matrix, integrated
//! over the element alone (so no shot grows by more than a few times).
//! The assembled, root-clamped $K(\omega)$ with $-\omega^2M_b$ at the tip is
//! block tridiagonal; by Wittrick and Williams (1971), the number of natural
//! frequencies below $\omega$ is the number of its negative eigenvalues (the
//! elements' own clamped–clamped count $J_0$ being zero), which block
//! elimination from the root counts through the inertia of its $2\times2$
//! pivots (Sylvester, Haynsworth). So no root is skipped, however close two
//! are, and a count at $\omega = 0$ above zero is a compression past the
//! buckling load.
//!
//! **Refining.** On a fixed mesh, $\det K(\omega)$ is analytic below every
//! element's clamped–clamped frequency and changes sign at each simple natural
//! frequency; once the count brackets exactly one frequency, Brent's method
//! refines it on that determinant (kept as sign and logarithm, by banded LU
//! with partial pivoting, on the coarsest mesh valid at the bracket's top) to a
//! relative $10^{-12}$ in $\bar\beta$.
//!
//! **Element length.** For $w$ clamped at both ends of an element of length
//! $h$, $\int w^{\prime\prime 2} \ge (4.7300/h)^4\int w^2$ and $\int w^{\prime\prime 2} \ge (2\pi/h)^2\int w^{\prime 2}$
//! (the clamped–clamped beam's first frequency and first buckling load), so the
//! element's lowest clamped–clamped $\omega^2$ is at least
//! $(EI_{min} - P^+h^2/4\pi^2)/(\mu_{max}h^4/500.56 + \rho I_{max}h^2/4\pi^2)$
//! with the extremes sampled over the element; elements are halved until this
//! is at least twice the largest $\omega^2$ asked about.

use crate::buckling::TipConstraint;
use crate::error::{Error, Result};
use crate::flexure::Flexure;
use crate::inertia::RigidInertia as Body;
use crate::ode::{Tolerance, integrate_through};
use crate::solver::interrupted;

/// The most elements in a mesh: past it the section is too soft somewhere,
/// or the frequency or compression too high, to resolve.
const MAX_ELEMENTS: usize = 20_000;

/// The most evaluations of the count and determinant in one call (each
/// integrates every element once).
const MAX_EVALUATIONS: usize = 20_000;

/// The most evaluations spent on one frequency (bracketing and refining).
const ROOT_EVALUATIONS: usize = 300;

/// The highest scaled frequency $\bar\beta$ searched.
const MAX_BETA: f64 = 2.0e4;

/// The margin of the element's clamped–clamped frequency bound over the
/// trial $\lambda = \bar\beta^4$.
const SAFETY: f64 = 2.0;

/// Sample points per element for the extremes of $EI$, $\mu$ and $\rho I$.
const SAMPLES: usize = 9;

/// The relative width in $\bar\beta$ at which a root is refined (measured on the
/// uniform cantilever to mode 30: within $3\times10^{-13}$ of the frequency equation).
const ROOT_TOLERANCE: f64 = 1e-12;

/// Natural frequencies of the exact beam, lowest first.
#[derive(Debug, Clone, PartialEq)]
pub struct Vibration {
    /// Angular frequencies $\omega$ (rad/s), ascending.
    pub omega: Vec<f64>,
    /// Frequencies $\omega/2\pi$ (Hz).
    pub frequency: Vec<f64>,
    /// Scaled frequencies $\bar\beta = (\bar\mu\omega^2L^4/\overline{EI})^{1/4}$ with the
    /// mean $\overline{EI}$ and the reference mass per length $\bar\mu$ ([`Vibration::mass_per_length`]):
    /// $\beta L$ for a uniform beam.
    pub scaled: Vec<f64>,
    /// $\bar\mu$ (kg/m): the flexure's mean mass per length, or, for a
    /// massless flexure, $(m + I_{tip}/L^2)/L$ of its body.
    pub mass_per_length: f64,
}

/// The lowest `count` natural frequencies of `flexure` (straight: its rest
/// curvature is ignored), with $EI(s)$, $\mu(s)$ and $\rho I(s)$ from its
/// section, carrying `body` at the tip, under an axial compression
/// `compression` $P$ (N, along the root's $-x$; negative for tension), each
/// element's ODE integrated to `tol` (module docs: counted by Wittrick–Williams,
/// refined by Brent's method to a relative $10^{-12}$ in $\bar\beta$).
///
/// A massless flexure has at most as many modes as its body has inertial
/// degrees of freedom (lateral and rotary), and fewer are returned if fewer
/// exist. A compression at or past the first buckling load (the straight
/// column is unstable, its lowest $\omega^2 < 0$) is refused as
/// [`Error::InvalidParameter`] naming `compression`, its value and the
/// buckling load. The work is bounded: at most 300 evaluations per frequency,
/// 20 000 in all, 20 000 elements and $\bar\beta$ up to $2\times10^4$, past
/// which [`Error::NoConvergence`] says the modes found and the scaled
/// frequency reached. The interrupt hook of [`crate::solver::with_interrupt`]
/// is polled at every element: [`Error::Interrupted`]'s fraction is that of
/// the modes asked for that were found.
///
/// # Example
/// ```
/// use flexure::reference::vibration::frequencies;
/// use flexure::section::{Profile, Section};
/// let s = Section::given(Profile::Constant(1.0)).unwrap().with_mass_per_length(Profile::Constant(1.0)).unwrap();
/// let f = flexure::Flexure::new(1.0, 1.0, 3).unwrap().with_section(s).unwrap();
/// let v = frequencies(&f, None, 0.0, 2, &Default::default()).unwrap();
/// // The uniform cantilever: βL = 1.87510, 4.69409.
/// assert!((v.scaled[0] - 1.8751040687).abs() < 1e-9 && (v.scaled[1] - 4.6940911330).abs() < 1e-9);
/// ```
pub fn frequencies(
    flexure: &Flexure,
    body: Option<&Body>,
    compression: f64,
    count: usize,
    tol: &Tolerance,
) -> Result<Vibration> {
    tol.validate()?;
    crate::error::finite("compression", compression)?;
    if count == 0 {
        return Err(Error::invalid("count", count, "must be at least 1"));
    }
    let body = body.copied().unwrap_or_default();
    body.validate()?;
    let (l, section) = (flexure.length(), flexure.section());
    let ei0 = flexure.ei();
    let mut breaks = vec![0.0];
    breaks.extend(section.breakpoints(l));
    breaks.push(1.0);
    breaks.dedup();
    let distributed = section.mass_per_length(0.5, l).is_some();
    let i_tip = body.inertia_about_tip();
    let inner: Vec<f64> = breaks[1..breaks.len() - 1].to_vec();
    let mu_ref = if distributed {
        crate::quadrature::integrate(&inner, 16, section.polynomial(), 1e-14, 1, |t, out| {
            out[0] = section.mass_per_length(t, l).unwrap_or(0.0)
        })?[0]
    } else {
        (body.mass + i_tip / (l * l)) / l
    };
    if !(mu_ref > 0.0 && mu_ref.is_finite()) {
        return Err(Error::invalid(
            "mass",
            "none",
            "the flexure has no density or mass per length and there is no tip body with mass or inertia",
        ));
    }
    let available = if distributed {
        usize::MAX
    } else {
        let lateral = usize::from(body.mass > 0.0);
        let rotary = usize::from(body.mass * body.com[1] * body.com[1] + body.inertia > 0.0);
        lateral + rotary
    };
    let want = count.min(available);
    // Dimensionless: t = s/L, λ = μ̄ω²L⁴/EI₀, p = PL²/EI₀, body by μ̄L.
    let mass = body.mass / (mu_ref * l);
    let offset = body.com[0] / l;
    let inertia = i_tip / (mu_ref * l.powi(3));
    let beam = Beam {
        flexure,
        breaks: &breaks,
        ei0,
        mu_ref,
        p: compression * l * l / ei0,
        body: [mass, mass * offset, inertia],
        tol,
        evaluations: std::cell::Cell::new(0),
        want,
        found: std::cell::Cell::new(0),
    };
    let scaled = beam.roots(compression)?;
    let unit = (ei0 / (mu_ref * l.powi(4))).sqrt();
    let omega: Vec<f64> = scaled.iter().map(|b| b * b * unit).collect();
    let frequency = omega.iter().map(|w| w / std::f64::consts::TAU).collect();
    Ok(Vibration { omega, frequency, scaled, mass_per_length: mu_ref })
}

/// Half-bandwidth of the assembled $K$: a node's two motions meet only its
/// neighbours'.
const KL: usize = 3;

/// A square matrix of half-bandwidth [`KL`], stored by columns in LAPACK's
/// band layout with room for the fill-in of partial pivoting (`gbtrf`):
/// entry $(r, c)$ at row $2K_L + r - c$ of column $c$.
struct Band {
    n: usize,
    data: Vec<f64>,
}

impl Band {
    const ROWS: usize = 3 * KL + 1;

    fn new(n: usize) -> Self {
        Self { n, data: vec![0.0; Self::ROWS * n] }
    }

    /// Entry $(r, c)$, for $-2K_L \le r - c \le K_L$.
    fn at(&mut self, r: usize, c: usize) -> &mut f64 {
        &mut self.data[(2 * KL + r - c) + c * Self::ROWS]
    }

    /// The sign and $\ln\lvert\det\rvert$, by LU with partial pivoting in
    /// place; `None` if a pivot is zero or not finite.
    fn log_determinant(&mut self) -> Option<(f64, f64)> {
        let n = self.n;
        let (mut sign, mut log) = (1.0, 0.0);
        // The last column the factors reach so far.
        let mut reach = 0;
        for j in 0..n {
            let below = KL.min(n - 1 - j);
            let p = (0..=below)
                .fold(0, |best, i| if self.at(j + i, j).abs() > self.at(j + best, j).abs() { i } else { best });
            let pivot = *self.at(j + p, j);
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            reach = reach.max((j + KL + p).min(n - 1));
            if p != 0 {
                sign = -sign;
                for c in j..=reach {
                    let (x, y) = (*self.at(j, c), *self.at(j + p, c));
                    (*self.at(j, c), *self.at(j + p, c)) = (y, x);
                }
            }
            sign *= pivot.signum();
            log += pivot.abs().ln();
            for i in 1..=below {
                *self.at(j + i, j) /= pivot;
            }
            for c in j + 1..=reach {
                let u = *self.at(j, c);
                if u != 0.0 {
                    for i in 1..=below {
                        let l = *self.at(j + i, j);
                        *self.at(j + i, c) -= l * u;
                    }
                }
            }
        }
        Some((sign, log))
    }
}

/// The refusal of a compression at or past the buckling load `load`, naming both.
fn refusal(compression: f64, load: f64) -> Error {
    Error::InvalidParameter {
        name: "compression",
        value: format!(
            "{compression} N, at or past the buckling load {load} N of the column clamped at its root and free at its tip"
        ),
        reason: "the straight beam is unstable there (its lowest ω² would be negative): give a compression below the buckling load",
    }
}

/// The dimensionless beam and tip body.
struct Beam<'a> {
    flexure: &'a Flexure,
    /// $0$, the section's breakpoints, $1$.
    breaks: &'a [f64],
    ei0: f64,
    mu_ref: f64,
    /// $PL^2/\overline{EI}$.
    p: f64,
    /// The body's mass matrix about the tip, $[m, mc_x, I_{tip}]$, scaled by $\bar\mu L$.
    body: [f64; 3],
    tol: &'a Tolerance,
    /// Evaluations of the count so far, against [`MAX_EVALUATIONS`].
    evaluations: std::cell::Cell<usize>,
    /// Modes asked for, and found so far (for an interruption's fraction).
    want: usize,
    found: std::cell::Cell<usize>,
}

type M2 = [[f64; 2]; 2];

fn det2(a: &M2) -> f64 {
    a[0][0] * a[1][1] - a[0][1] * a[1][0]
}

fn mul2(a: &M2, b: &M2) -> M2 {
    let mut c = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j];
        }
    }
    c
}

fn inv2(a: &M2) -> Option<M2> {
    let d = det2(a);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    Some([[a[1][1] / d, -a[0][1] / d], [-a[1][0] / d, a[0][0] / d]])
}

impl Beam<'_> {
    /// $EI/\overline{EI}$, $\mu/\bar\mu$ and $\rho I/(\bar\mu L^2)$ at `t`.
    fn properties(&self, t: f64) -> [f64; 3] {
        let (l, section) = (self.flexure.length(), self.flexure.section());
        [
            section.ei(t, l) / self.ei0,
            section.mass_per_length(t, l).unwrap_or(0.0) / self.mu_ref,
            section.rotary_inertia_per_length(t, l).unwrap_or(0.0) / (self.mu_ref * l * l),
        ]
    }

    /// Whether an element `[a, b]` has no clamped–clamped natural frequency
    /// below [`SAFETY`] × `lambda` (module docs).
    fn short_enough(&self, a: f64, b: f64, lambda: f64) -> bool {
        let h = b - a;
        let (mut e, mut m, mut r) = (f64::INFINITY, 0.0_f64, 0.0_f64);
        for k in 0..SAMPLES {
            let [ek, mk, rk] = self.properties(a + h * k as f64 / (SAMPLES - 1) as f64);
            (e, m, r) = (e.min(ek), m.max(mk), r.max(rk));
        }
        let four_pi2 = 4.0 * std::f64::consts::PI.powi(2);
        let stiffness = e - self.p.max(0.0) * h * h / four_pi2;
        let inertia = m * h.powi(4) / 500.5639 + r * h * h / four_pi2;
        stiffness > 0.0 && stiffness >= SAFETY * lambda * inertia
    }

    /// The nodes of a mesh on which every element is short enough at `lambda`:
    /// each smooth piece between breakpoints cut evenly, halved until it is.
    fn mesh(&self, lambda: f64) -> Result<Vec<f64>> {
        let mut nodes = vec![0.0];
        for piece in self.breaks.windows(2) {
            let (a, b) = (piece[0], piece[1]);
            let mut n = 1usize;
            loop {
                let h = (b - a) / n as f64;
                if (0..n).all(|k| self.short_enough(a + h * k as f64, a + h * (k + 1) as f64, lambda)) {
                    break;
                }
                n *= 2;
                if nodes.len() + n > MAX_ELEMENTS {
                    return Err(Error::NoConvergence {
                        solver: "exact vibration mesh (more elements needed than the cap)",
                        iterations: MAX_ELEMENTS,
                        residual: lambda.powf(0.25),
                        unit: "scaled frequency βL to resolve",
                    });
                }
            }
            let h = (b - a) / n as f64;
            nodes.extend((1..n).map(|k| a + h * k as f64));
            nodes.push(b);
        }
        Ok(nodes)
    }

    /// The exact dynamic stiffness of the element `[a, b]` at `lambda`, in
    /// the end motions $(w_0, \theta_0, w_1, \theta_1)$ (module docs).
    fn element(&self, a: f64, b: f64, lambda: f64) -> Result<[[f64; 4]; 4]> {
        let h = b - a;
        // Scaled state z = (w, hθ, h²M, h³S) in ξ = (t − a)/h: entries of order 1.
        let rhs = |xi: f64, y: &[f64; 16]| {
            let [e, mu, r] = self.properties(a + h * xi);
            let axial = (self.p + lambda * r) * h * h;
            let inertial = lambda * mu * h.powi(4);
            let mut d = [0.0; 16];
            for k in (0..16).step_by(4) {
                let [w, th, m, s] = [y[k], y[k + 1], y[k + 2], y[k + 3]];
                d[k] = th;
                d[k + 1] = m / e;
                d[k + 2] = s - axial * th;
                d[k + 3] = inertial * w;
            }
            d
        };
        let mut start = [0.0; 16];
        for k in 0..4 {
            start[5 * k] = 1.0;
        }
        let y = integrate_through(rhs, 0.0, 1.0, &[], start, self.tol, &mut 0.0, |_, _| {})?;
        // Transfer z(1) = T z(0): column j is the solution from the unit state j.
        let t = |i: usize, j: usize| y[4 * j + i];
        let block = |r: usize, c: usize| [[t(r, c), t(r, c + 1)], [t(r + 1, c), t(r + 1, c + 1)]];
        let (ta, tb, tc, td) = (block(0, 0), block(0, 2), block(2, 0), block(2, 2));
        let Some(b_inv) = inv2(&tb) else {
            return Err(Error::Singular {
                what: format!(
                    "exact vibration: an element's transfer matrix is singular at βL = {}",
                    lambda.powf(0.25)
                ),
            });
        };
        // End forces f0 = B⁻¹(u1 − A u0), f1 = C u0 + D f0, in scaled motions (u0, u1).
        let g0a = mul2(&b_inv, &ta).map(|row| row.map(|x| -x));
        let g0b = b_inv;
        let db = mul2(&td, &b_inv);
        let dba = mul2(&db, &ta);
        let g1a = [[tc[0][0] - dba[0][0], tc[0][1] - dba[0][1]], [tc[1][0] - dba[1][0], tc[1][1] - dba[1][1]]];
        let g1b = db;
        let row = |ga: &M2, gb: &M2, i: usize, sign: f64| {
            [sign * ga[i][0], sign * ga[i][1], sign * gb[i][0], sign * gb[i][1]]
        };
        // Nodal forces (S0, −M0, −S1, M1) = (f0[1], −f0[0], −f1[1], f1[0]).
        let scaled =
            [row(&g0a, &g0b, 1, 1.0), row(&g0a, &g0b, 0, -1.0), row(&g1a, &g1b, 1, -1.0), row(&g1a, &g1b, 0, 1.0)];
        // Back to motions (w, θ) and forces (S, M): F = diag(h⁻³, h⁻², h⁻³, h⁻²) F̃, ũ = diag(1, h, 1, h) u.
        let force = [h.powi(-3), h.powi(-2), h.powi(-3), h.powi(-2)];
        let motion = [1.0, h, 1.0, h];
        let mut k = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                k[i][j] = force[i] * scaled[i][j] * motion[j];
            }
        }
        // Symmetric in exact arithmetic (the Hessian of Π); rounding aside.
        for i in 0..4 {
            for j in 0..i {
                let s = 0.5 * (k[i][j] + k[j][i]);
                (k[i][j], k[j][i]) = (s, s);
            }
        }
        Ok(k)
    }

    /// Every element's dynamic stiffness at `beta` on the mesh `nodes` (valid
    /// there), counting the evaluation and polling the interrupt at each element.
    fn elements(&self, beta: f64, nodes: &[f64]) -> Result<Vec<[[f64; 4]; 4]>> {
        let used = self.evaluations.get() + 1;
        self.evaluations.set(used);
        if used > MAX_EVALUATIONS {
            return Err(Error::NoConvergence {
                solver: "exact vibration frequencies (evaluations cap; modes found so far in iterations)",
                iterations: self.found.get(),
                residual: beta,
                unit: "scaled frequency βL reached",
            });
        }
        let lambda = beta.powi(4);
        nodes
            .windows(2)
            .map(|e| {
                if interrupted() {
                    return Err(Error::Interrupted { load_fraction: self.found.get() as f64 / self.want as f64 });
                }
                self.element(e[0], e[1], lambda)
            })
            .collect()
    }

    /// The inertia of the root-clamped $K$ at `beta` on the mesh `nodes`
    /// (valid at `beta`), by block elimination from the root (a congruence:
    /// its $2\times2$ pivots' negative eigenvalues are $K$'s).
    fn inertia(&self, beta: f64, nodes: &[f64]) -> Result<usize> {
        let elements = self.elements(beta, nodes)?;
        let lambda = beta.powi(4);
        let mut negative = 0;
        let pivot = |d: &mut M2, negative: &mut usize| -> Result<M2> {
            let mut det = det2(d);
            if det == 0.0 {
                // Exactly singular (measure zero): nudge it, keeping a count.
                let shift = 1e-15 * (d[0][0].abs() + d[1][1].abs()).max(f64::MIN_POSITIVE);
                d[0][0] += shift;
                d[1][1] += shift;
                det = det2(d);
            }
            let trace = d[0][0] + d[1][1];
            *negative += if det < 0.0 {
                1
            } else if trace < 0.0 {
                2
            } else {
                0
            };
            inv2(d).ok_or_else(|| Error::Singular {
                what: format!("exact vibration: a pivot of the dynamic stiffness is singular at βL = {beta}"),
            })
        };
        let mut current: M2 = [[0.0; 2]; 2];
        for (j, k) in elements.iter().enumerate() {
            let sub = |r: usize, c: usize| [[k[r][c], k[r][c + 1]], [k[r + 1][c], k[r + 1][c + 1]]];
            let (k00, k01, k10, k11) = (sub(0, 0), sub(0, 2), sub(2, 0), sub(2, 2));
            if j == 0 {
                current = k11; // node 0 is clamped
                continue;
            }
            for (r, row) in current.iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    *x += k00[r][c];
                }
            }
            let d_inv = pivot(&mut current, &mut negative)?;
            let schur = mul2(&mul2(&k10, &d_inv), &k01);
            current = [
                [k11[0][0] - schur[0][0], k11[0][1] - schur[0][1]],
                [k11[1][0] - schur[1][0], k11[1][1] - schur[1][1]],
            ];
        }
        let [m, mc, i] = self.body;
        current[0][0] -= lambda * m;
        current[0][1] -= lambda * mc;
        current[1][0] -= lambda * mc;
        current[1][1] -= lambda * i;
        pivot(&mut current, &mut negative)?;
        Ok(negative)
    }

    /// The sign and $\ln\lvert\det K\rvert$ of the root-clamped $K$ at `beta` on
    /// the mesh `nodes` (valid at `beta`), by banded LU with partial pivoting:
    /// the block elimination of [`Beam::inertia`] divides by whatever pivot
    /// comes, and one near a substructure's own frequency would cost digits.
    /// An exactly singular $K$ has sign 0.
    fn determinant(&self, beta: f64, nodes: &[f64]) -> Result<(f64, f64)> {
        let elements = self.elements(beta, nodes)?;
        let lambda = beta.powi(4);
        let n = 2 * elements.len();
        let mut band = Band::new(n);
        for (j, k) in elements.iter().enumerate() {
            // Element j joins node j (dofs 2j − 2, 2j − 1; none for the clamped root) and node j + 1.
            let dof = |local: usize| -> Option<usize> { (2 * j + local).checked_sub(2) };
            for (r, row) in k.iter().enumerate() {
                for (c, x) in row.iter().enumerate() {
                    if let (Some(i), Some(l)) = (dof(r), dof(c)) {
                        *band.at(i, l) += x;
                    }
                }
            }
        }
        let [m, mc, i] = self.body;
        let tip = n - 2;
        *band.at(tip, tip) -= lambda * m;
        *band.at(tip, tip + 1) -= lambda * mc;
        *band.at(tip + 1, tip) -= lambda * mc;
        *band.at(tip + 1, tip + 1) -= lambda * i;
        let Some((sign, log)) = band.log_determinant() else {
            return Ok((0.0, 0.0));
        };
        if !log.is_finite() {
            return Err(Error::Singular {
                what: format!("exact vibration: the dynamic stiffness is not finite at βL = {beta}"),
            });
        }
        Ok((sign, log))
    }

    /// The buckling load (N) of the column clamped at its root, free at its tip.
    fn buckling_load(&self) -> Result<f64> {
        let f = self.flexure;
        if f.section().is_uniform() {
            Ok(crate::reference::euler::buckling_load(TipConstraint::Free, f.length(), f.ei()))
        } else {
            crate::reference::column::buckling_load(f, TipConstraint::Free, self.tol)
        }
    }

    /// The lowest [`Beam::want`] scaled frequencies.
    fn roots(&self, compression: f64) -> Result<Vec<f64>> {
        // Stable at rest? The count at ω = 0 is the number of ω² < 0.
        let stable = match self.mesh(0.0) {
            Ok(nodes) => self.inertia(0.0, &nodes)? == 0,
            Err(e @ Error::NoConvergence { .. }) if self.p > 0.0 => {
                // So much compression that no mesh resolves it: compare with the buckling load.
                let load = self.buckling_load()?;
                return Err(if compression >= load { refusal(compression, load) } else { e });
            }
            Err(e) => return Err(e),
        };
        if !stable {
            return Err(refusal(compression, self.buckling_load()?));
        }
        // A top frequency with at least `want` below it: above the uniform
        // cantilever's (want − ½)π, and not on its next root.
        let mut top = (self.want as f64 + 0.2) * std::f64::consts::PI;
        let top_count = loop {
            let n = self.count(top)?;
            if n >= self.want {
                break n;
            }
            if top >= MAX_BETA {
                return Err(Error::NoConvergence {
                    solver: "exact vibration frequencies (fewer modes below the highest frequency searched; modes found in iterations)",
                    iterations: n,
                    residual: top,
                    unit: "scaled frequency βL reached",
                });
            }
            top = (2.0 * top).min(MAX_BETA);
        };
        // Samples (β, count), ascending in β.
        let mut samples: Vec<(f64, usize)> = vec![(0.0, 0), (top, top_count)];
        let mut scaled: Vec<f64> = Vec::with_capacity(self.want);
        while scaled.len() < self.want {
            let k = scaled.len();
            self.found.set(k);
            let mut spent = 0;
            let root = loop {
                spent += 1;
                if spent > ROOT_EVALUATIONS {
                    return Err(Error::NoConvergence {
                        solver: "exact vibration frequency bracketing (modes found in iterations)",
                        iterations: k,
                        residual: samples.iter().rev().find(|s| s.1 > k).map_or(top, |s| s.0),
                        unit: "scaled frequency βL of the bracket's top",
                    });
                }
                // The tightest bracket of the (k+1)-th frequency.
                // β = 0 counts none and the top every mode asked, so both exist.
                let lo = samples.iter().rev().find(|s| s.1 <= k).copied().unwrap_or((0.0, 0));
                let hi = samples.iter().find(|s| s.1 > k).copied().unwrap_or((top, top_count));
                if hi.0 - lo.0 <= ROOT_TOLERANCE * hi.0 {
                    // Frequencies closer than the tolerance: each is this one.
                    break (0.5 * (lo.0 + hi.0), (hi.1 - k).min(self.want - k));
                }
                // Exactly one in the bracket: refine it; unless an end is too close to
                // a root for the determinant's sign, then narrow by the count.
                if lo.1 == k
                    && hi.1 == k + 1
                    && let Some(root) = self.refine(lo.0, hi.0)?
                {
                    break (root, 1);
                }
                let mid = 0.5 * (lo.0 + hi.0);
                let n = self.count(mid)?;
                let at = samples.partition_point(|s| s.0 < mid);
                samples.insert(at, (mid, n));
            };
            let (value, multiplicity) = root;
            scaled.extend(std::iter::repeat_n(value, multiplicity));
        }
        self.found.set(scaled.len());
        Ok(scaled)
    }

    /// The natural frequencies below `beta`, on the coarsest mesh valid there.
    fn count(&self, beta: f64) -> Result<usize> {
        self.inertia(beta, &self.mesh(beta.powi(4))?)
    }

    /// The one root of $\det K$ in `(lo, hi]`, where the count goes up by one, by
    /// Brent's method on $\operatorname{sign}(\det K)\exp(\ln\lvert\det K\rvert - c)$,
    /// on one mesh, the coarsest valid at `hi`: a finer one would only spread
    /// the stiffness's scales and lose digits to rounding.
    ///
    /// `None` when the determinant's signs at the two ends agree: an end lies
    /// within rounding of a root (of this one, or of the next, where the count
    /// and the determinant may round differently).
    fn refine(&self, lo: f64, hi: f64) -> Result<Option<f64>> {
        let mesh = self.mesh(hi.powi(4))?;
        let nodes = &mesh[..];
        let first = self.determinant(lo, nodes)?;
        let shift = first.1;
        let value = |(sign, log): (f64, f64)| sign * (log - shift).clamp(-700.0, 700.0).exp();
        let (mut a, mut b) = (lo, hi);
        let (mut fa, mut fb) = (value(first), value(self.determinant(hi, nodes)?));
        if fa == 0.0 || fb == 0.0 || fa.signum() == fb.signum() {
            return Ok(None);
        }
        let (mut c, mut fc) = (a, fa);
        let (mut d, mut e) = (b - a, b - a);
        for _ in 0..ROOT_EVALUATIONS {
            if fb.signum() == fc.signum() {
                (c, fc) = (a, fa);
                (d, e) = (b - a, b - a);
            }
            if fc.abs() < fb.abs() {
                (a, b, c) = (b, c, b);
                (fa, fb, fc) = (fb, fc, fb);
            }
            let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * ROOT_TOLERANCE * b.abs();
            let m = 0.5 * (c - b);
            if m.abs() <= tol || fb == 0.0 {
                return Ok(Some(b));
            }
            if e.abs() >= tol && fa.abs() > fb.abs() {
                let s = fb / fa;
                let (mut p, mut q) = if a == c {
                    (2.0 * m * s, 1.0 - s)
                } else {
                    let (q, r) = (fa / fc, fb / fc);
                    (s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0)), (q - 1.0) * (r - 1.0) * (s - 1.0))
                };
                if p > 0.0 {
                    q = -q;
                } else {
                    p = -p;
                }
                if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                    (e, d) = (d, p / q);
                } else {
                    (d, e) = (m, m);
                }
            } else {
                (d, e) = (m, m);
            }
            (a, fa) = (b, fb);
            b += if d.abs() > tol { d } else { tol.copysign(m) };
            fb = value(self.determinant(b, nodes)?);
        }
        Err(Error::NoConvergence {
            solver: "exact vibration frequency refinement (Brent)",
            iterations: ROOT_EVALUATIONS,
            residual: (c - b).abs(),
            unit: "width of the bracket in βL",
        })
    }
}
