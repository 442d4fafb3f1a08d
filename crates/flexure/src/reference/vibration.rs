//! Exact linear vibration of a straight Euler–Bernoulli beam (with rotary
//! inertia: a Rayleigh beam), root clamped, tip free or carrying a rigid
//! [`Body`], under an optional axial compression: natural frequencies by
//! shooting on the frequency.
//!
//! The lateral deflection $w(s)\cos\omega t$ obeys
//!
//! $$(EI\thinspace w'')'' + P w'' = \mu\omega^2 w - (\rho I\thinspace\omega^2 w')',$$
//!
//! written as four first-order equations in $w$, $\theta = w'$, the bending
//! moment $\mathcal M = EI\thinspace w''$ and the shear
//! $S = \mathcal M' + (P + \rho I\omega^2)\theta$:
//! $w' = \theta$, $\theta' = \mathcal M/EI$, $\mathcal M' = S - (P + \rho I\omega^2)\theta$,
//! $S' = \mu\omega^2 w$. At the root $w = \theta = 0$; shooting from the two
//! unit root states $(\mathcal M, S) = (1, 0)$ and $(0, 1)$, the tip
//! conditions
//!
//! $$\mathcal M(L) = \omega^2(mc_x w + I_{tip}\theta),\qquad S(L) = -\omega^2 m(w + c_x\theta)$$
//!
//! (the body's inertial force and moment; $I_{tip} = I_c + m\lvert c\rvert^2$, the
//! axial inertia of an offset $c_y$ entering through $I_{tip}$) are linear in
//! the two root unknowns, and $\omega$ is a natural frequency where their
//! $2\times2$ determinant vanishes. A free tip is the body of zero mass.

use crate::dynamics::Body;
use crate::error::{Error, Result};
use crate::joint::Flexure;
use crate::ode::{Tolerance, integrate_through};

/// Step of the frequency scan in the scaled frequency $\bar\beta = \lambda^{1/4}$
/// (the uniform cantilever's $\beta L$): roots of a distributed beam lie
/// about $\pi$ apart in it, so a root closer than $\pi/32$ to the next would be needed to hide one.
const SCAN_STEP: f64 = std::f64::consts::PI / 32.0;

/// The most scan steps: $\bar\beta$ up to about 2000, $\lambda$ up to $1.6\times10^{13}$.
const MAX_SCAN: usize = 20_000;

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
/// `compression` $P$ (N, along the root's $-x$; negative for tension), the
/// ODE integrated to `tol` piecewise between the section's breakpoints.
///
/// The scan steps $\bar\beta$ by $\pi/32$ from $10^{-3}$, brackets each sign change of the
/// frequency determinant and bisects it to a relative $10^{-14}$. A massless
/// flexure has at most as many modes as its body has inertial degrees of
/// freedom (lateral and rotary), and fewer are returned if fewer exist.
/// Under a compression beyond the first buckling load the lowest modes have
/// $\omega^2 < 0$ and are not found. After 20 000 steps the scan stops with
/// [`Error::NoConvergence`], whose residual is the scaled frequency reached.
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
    let breaks = section.breakpoints(l);
    let distributed = section.mass_per_length(0.5, l).is_some();
    let i_tip = body.inertia_about_tip();
    let mu_ref = if distributed {
        crate::quadrature::integrate(&breaks, 16, section.polynomial(), 1e-14, 1, |t, out| {
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
    let beam = Beam {
        flexure,
        breaks: &breaks,
        ei0,
        mu_ref,
        p: compression * l * l / ei0,
        mass: body.mass / (mu_ref * l),
        offset: body.com[0] / l,
        inertia: i_tip / (mu_ref * l.powi(3)),
        tol,
    };
    let mut scaled = Vec::with_capacity(want);
    let mut lo = 1e-3;
    let mut f_lo = beam.determinant(lo)?;
    let mut steps = 0;
    while scaled.len() < want {
        if steps >= MAX_SCAN {
            return Err(Error::NoConvergence {
                solver: "exact vibration frequency scan (fewer modes found than asked)",
                iterations: steps,
                residual: lo,
                unit: "scaled frequency βL reached",
            });
        }
        steps += 1;
        let hi = lo + SCAN_STEP;
        let f_hi = beam.determinant(hi)?;
        if f_lo == 0.0 || f_lo.signum() != f_hi.signum() {
            scaled.push(beam.bisect(lo, hi, f_lo)?);
        }
        (lo, f_lo) = (hi, f_hi);
    }
    let unit = (ei0 / (mu_ref * l.powi(4))).sqrt();
    let omega: Vec<f64> = scaled.iter().map(|b| b * b * unit).collect();
    let frequency = omega.iter().map(|w| w / std::f64::consts::TAU).collect();
    Ok(Vibration { omega, frequency, scaled, mass_per_length: mu_ref })
}

/// The dimensionless beam and tip body.
struct Beam<'a> {
    flexure: &'a Flexure,
    breaks: &'a [f64],
    ei0: f64,
    mu_ref: f64,
    /// $PL^2/\overline{EI}$.
    p: f64,
    /// $m/(\bar\mu L)$, $c_x/L$, $I_{tip}/(\bar\mu L^3)$.
    mass: f64,
    offset: f64,
    inertia: f64,
    tol: &'a Tolerance,
}

impl Beam<'_> {
    /// The tip conditions' determinant at the scaled frequency `beta`.
    fn determinant(&self, beta: f64) -> Result<f64> {
        let lambda = beta.powi(4);
        let (l, section) = (self.flexure.length(), self.flexure.section());
        let rhs = |t: f64, y: &[f64; 8]| {
            let e = section.ei(t, l) / self.ei0;
            let mu = section.mass_per_length(t, l).unwrap_or(0.0) / self.mu_ref;
            let r = section.rotary_inertia_per_length(t, l).unwrap_or(0.0) / (self.mu_ref * l * l);
            let axial = self.p + lambda * r;
            let mut d = [0.0; 8];
            for k in [0, 4] {
                let [w, th, m, s] = [y[k], y[k + 1], y[k + 2], y[k + 3]];
                d[k] = th;
                d[k + 1] = m / e;
                d[k + 2] = s - axial * th;
                d[k + 3] = lambda * mu * w;
            }
            d
        };
        let start = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        let y = integrate_through(rhs, 0.0, 1.0, self.breaks, start, self.tol, &mut 0.0, |_, _| {})?;
        let tip = |k: usize| {
            let [w, th, m, s] = [y[k], y[k + 1], y[k + 2], y[k + 3]];
            (
                m - lambda * (self.mass * self.offset * w + self.inertia * th),
                s + lambda * self.mass * (w + self.offset * th),
            )
        };
        let ((a1, a2), (b1, b2)) = (tip(0), tip(4));
        let det = a1 * b2 - a2 * b1;
        if det.is_finite() {
            Ok(det)
        } else {
            Err(Error::Singular {
                what: format!("exact vibration: the shooting determinant is not finite at βL = {beta}"),
            })
        }
    }

    /// The root of the determinant in `[lo, hi]` (a sign change), by bisection.
    fn bisect(&self, mut lo: f64, mut hi: f64, mut f_lo: f64) -> Result<f64> {
        for _ in 0..200 {
            if f_lo == 0.0 {
                return Ok(lo);
            }
            if hi - lo <= 1e-14 * hi {
                break;
            }
            let mid = 0.5 * (lo + hi);
            let f_mid = self.determinant(mid)?;
            if f_mid.signum() == f_lo.signum() {
                (lo, f_lo) = (mid, f_mid);
            } else {
                hi = mid;
            }
        }
        Ok(0.5 * (lo + hi))
    }
}
