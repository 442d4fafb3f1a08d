//! Bending stress along a flexure, and where it peaks.
//!
//! At arc length $s$ the outer fibre of a section of thickness $h(s)$ is
//! strained by $\frac{h}{2}(\hat\omega - \hat\omega_0)$, so the bending stress is
//! $\sigma(s) = E^{\prime}\thinspace\frac{h(s)}{2}\thinspace\lvert\hat\omega(s) - \hat\omega_0(s)\rvert$
//! with $E^{\prime}$ the section's effective modulus ([`crate::section::Section::modulus`]).
//! A section given by $EI$ alone has no thickness, so no stress: its
//! answers report the largest change of curvature instead.

use crate::flexure::Flexure;
use crate::flexure::assert_coordinates;

/// Samples of the coarse scan that brackets a peak, per coordinate (at least 64 in all).
const SAMPLES_PER_ORDER: usize = 16;

/// Golden-section steps refining a bracketed peak: $0.618^{80} \approx 10^{-17}$ of the bracket.
const REFINEMENTS: usize = 80;

/// The largest value of a quantity along the flexure and where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peak {
    /// The value (Pa for stress, 1/m for curvature).
    pub value: f64,
    /// Arc length from the root where it is reached (m).
    pub at: f64,
}

/// The change of curvature from rest, $\hat\omega(\alpha, s) - \hat\omega_0(s)$ (1/m), at `s` (m).
///
/// # Panics
/// If `alpha` does not have [`Flexure::order`] entries.
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(2.0, 1.0, 2).unwrap().with_rest(&[0.5, 0.0]).unwrap();
/// // A tip angle of 1.5 rad over 2 m against a rest of 0.5 rad: 0.5 1/m more.
/// assert!((flexure::stress::curvature_change(&f, &[1.5, 0.0], 0.3) - 0.5).abs() < 1e-15);
/// ```
pub fn curvature_change(flexure: &Flexure, alpha: &[f64], s: f64) -> f64 {
    let d = change(flexure, alpha);
    flexure.curvature(&d[..alpha.len()], s)
}

/// The coordinates of the change from rest, $\alpha - \kappa$, in the first
/// [`Flexure::order`] entries: computed once for a whole scan.
fn change(flexure: &Flexure, alpha: &[f64]) -> [f64; crate::flexure::MAX_ORDER] {
    assert_coordinates(flexure, "alpha", alpha.len());
    let mut d = [0.0; crate::flexure::MAX_ORDER];
    for ((d, a), k) in d.iter_mut().zip(alpha).zip(flexure.rest()) {
        *d = a - k;
    }
    d
}

/// Bending stress $\sigma(s)$ (Pa) at `s` (m); `None` for a section without thickness.
///
/// # Example
/// ```
/// use flexure::section::{Profile, Section};
/// let section = Section::rectangle(200e9, None, Profile::Constant(0.01), Profile::Constant(2e-4)).unwrap();
/// let f = flexure::Flexure::new(0.02, 1.0, 3).unwrap().with_section(section).unwrap();
/// // A uniform bend of 0.5 rad over 20 mm: 25 1/m, so σ = E h/2 · 25 = 500 MPa.
/// let sigma = flexure::stress::stress(&f, &[0.5, 0.0, 0.0], 0.01).unwrap();
/// assert!((sigma - 500e6).abs() < 1e-3);
/// ```
pub fn stress(flexure: &Flexure, alpha: &[f64], s: f64) -> Option<f64> {
    let section = flexure.section();
    let (e, h) = (section.modulus()?, section.thickness(s / flexure.length(), flexure.length())?);
    Some(e * 0.5 * h * curvature_change(flexure, alpha, s).abs())
}

/// The peak bending stress along the flexure; `None` for a section without thickness.
pub fn peak_stress(flexure: &Flexure, alpha: &[f64]) -> Option<Peak> {
    let e = flexure.section().modulus()?;
    let (section, l) = (flexure.section(), flexure.length());
    let d = change(flexure, alpha);
    let d = &d[..alpha.len()];
    // `stress` at each point, the change from rest taken once.
    Some(peak(flexure, |s| section.thickness(s / l, l).map_or(0.0, |h| e * 0.5 * h * flexure.curvature(d, s).abs())))
}

/// The largest change of curvature from rest, $\max_s\lvert\hat\omega - \hat\omega_0\rvert$ (1/m).
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 2).unwrap();
/// // ω = 1 + (2s − 1): largest at the tip, 2 1/m.
/// let p = flexure::stress::peak_curvature(&f, &[1.0, 1.0]);
/// assert!((p.value - 2.0).abs() < 1e-12 && (p.at - 1.0).abs() < 1e-12);
/// ```
pub fn peak_curvature(flexure: &Flexure, alpha: &[f64]) -> Peak {
    let d = change(flexure, alpha);
    let d = &d[..alpha.len()];
    peak(flexure, |s| flexure.curvature(d, s).abs())
}

/// The maximum of `g` on $[0, L]$: a scan of evenly spaced points, the
/// section's breakpoints and the segment boundaries, then golden-section
/// refinement between the best point's neighbours (bounded steps).
fn peak(flexure: &Flexure, g: impl Fn(f64) -> f64) -> Peak {
    let l = flexure.length();
    let count = (SAMPLES_PER_ORDER * flexure.order()).max(64);
    let mut points: Vec<f64> = (0..=count).map(|k| k as f64 / count as f64).collect();
    points.extend(flexure.section().breakpoints(l));
    if flexure.basis() == crate::flexure::Basis::Segments {
        // Curvature jumps at each boundary: take both sides.
        let n = flexure.order() as f64;
        for j in 1..flexure.order() {
            points.extend([(j as f64 - 1e-9) / n, (j as f64 + 1e-9) / n]);
        }
    }
    points.sort_by(f64::total_cmp);
    let values: Vec<f64> = points.iter().map(|t| g(t * l)).collect();
    let best = (0..points.len()).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap_or(0);
    let bracket = (points[best.saturating_sub(1)] * l, points[(best + 1).min(points.len() - 1)] * l);
    let top = Peak { value: values[best], at: points[best] * l };
    match refine(bracket, top, l, REFINEMENTS, |s| Ok::<f64, std::convert::Infallible>(g(s))) {
        Ok(peak) => peak,
        Err(never) => match never {},
    }
}

/// Golden-section refinement of the best scanned point `top` of `g` between
/// its neighbours `(a, b)`, `steps` times (bounded); a peak at an end of
/// $[0, L]$ (the root, most often) is reported there, not a rounding error
/// inside it. Shared by the model's and the exact references' peaks.
pub fn refine<E>(
    (mut a, mut b): (f64, f64),
    mut top: Peak,
    length: f64,
    steps: usize,
    mut g: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Peak, E> {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..steps {
        let (c, d) = (b - ratio * (b - a), a + ratio * (b - a));
        let (gc, gd) = (g(c)?, g(d)?);
        for (s, v) in [(c, gc), (d, gd)] {
            if v > top.value {
                top = Peak { value: v, at: s };
            }
        }
        if gc >= gd { b = d } else { a = c }
    }
    for end in [0.0, length] {
        if (top.at - end).abs() <= 1e-9 * length {
            let v = g(end)?;
            if v >= top.value * (1.0 - 1e-12) {
                top = Peak { value: v, at: end };
            }
        }
    }
    Ok(top)
}

/// The value of [`peak_curvature`] for the Legendre basis, found faster for
/// the error estimates: the same scan of evenly spaced points (a polynomial
/// has no breakpoints to add), evaluated eight at a time, then the root of
/// the derivative between the best point's neighbours by safeguarded Newton
/// instead of golden section. The change of curvature is the polynomial
/// $p(x) = \frac1L\sum_n (\alpha_n - \kappa_n) P_n(x)$, $x = 2s/L - 1$, so
/// its largest magnitude is at an end or where $p^{\prime} = 0$; the value
/// agrees with [`peak_curvature`]'s to rounding.
///
/// # Panics
/// If `alpha` does not have [`Flexure::order`] entries.
///
/// # Example
/// ```
/// let f = flexure::Flexure::new(1.0, 1.0, 5).unwrap();
/// let alpha = [0.3, -1.2, 0.7, 0.4, -0.9];
/// let slow = flexure::stress::peak_curvature(&f, &alpha).value;
/// assert!((flexure::stress::peak_curvature_legendre(&f, &alpha) - slow).abs() <= 1e-14 * slow);
/// ```
pub fn peak_curvature_legendre(flexure: &Flexure, alpha: &[f64]) -> f64 {
    let d = change(flexure, alpha);
    let d = &d[..alpha.len()];
    let n = d.len();
    let l = flexure.length();
    // Bonnet's recurrence P_{k+1} = a_k x P_k − b_k P_{k−1}, its factors once.
    let mut a = [0.0; crate::flexure::MAX_ORDER];
    let mut b = [0.0; crate::flexure::MAX_ORDER];
    for k in 1..n {
        a[k] = (2 * k + 1) as f64 / (k + 1) as f64;
        b[k] = k as f64 / (k + 1) as f64;
    }
    let count = (SAMPLES_PER_ORDER * n).max(64);
    const LANES: usize = 8;
    let (mut top, mut best) = (f64::NEG_INFINITY, 0);
    for start in (0..=count).step_by(LANES) {
        let x: [f64; LANES] = std::array::from_fn(|j| 2.0 * ((start + j).min(count) as f64 / count as f64) - 1.0);
        let (mut prev, mut cur) = ([0.0; LANES], [1.0; LANES]);
        let mut sum = [d[0]; LANES];
        for k in 1..n {
            for j in 0..LANES {
                let next = if k == 1 { x[j] } else { a[k - 1] * x[j] * cur[j] - b[k - 1] * prev[j] };
                prev[j] = cur[j];
                cur[j] = next;
                sum[j] += d[k] * next;
            }
        }
        for (j, s) in sum.iter().enumerate() {
            if start + j <= count && s.abs() > top {
                (top, best) = (s.abs(), start + j);
            }
        }
    }
    // p, p′ and p″ in x at once.
    let eval = |x: f64| {
        let (mut p0, mut p1) = (1.0, x);
        let (mut d0, mut d1) = (0.0, 1.0);
        let (mut e0, mut e1) = (0.0, 0.0);
        let (mut p, mut dp, mut ddp) = (d[0], 0.0, 0.0);
        for (k, &c) in d.iter().enumerate().skip(1) {
            p += c * p1;
            dp += c * d1;
            ddp += c * e1;
            let m = k as f64;
            let p2 = ((2.0 * m + 1.0) * x * p1 - m * p0) / (m + 1.0);
            let d2 = d0 + (2.0 * m + 1.0) * p1;
            let e2 = e0 + (2.0 * m + 1.0) * d1;
            (p0, p1, d0, d1, e0, e1) = (p1, p2, d1, d2, e1, e2);
        }
        (p, dp, ddp)
    };
    let at = |i: usize| 2.0 * (i as f64 / count as f64) - 1.0;
    let mut peak = top / l;
    // Each half of the bracket round the best point where p′ changes sign
    // holds a stationary point: Newton, bisecting whenever a step leaves it.
    for (i, j) in [(best.saturating_sub(1), best), (best, (best + 1).min(count))] {
        let (mut lo, mut hi) = (at(i), at(j));
        let (flo, fhi) = (eval(lo).1, eval(hi).1);
        if i == j || flo == 0.0 || fhi == 0.0 || flo.signum() == fhi.signum() {
            continue;
        }
        if flo > 0.0 {
            std::mem::swap(&mut lo, &mut hi);
        }
        let mut x = 0.5 * (lo + hi);
        for _ in 0..100 {
            let (p, dp, ddp) = eval(x);
            peak = peak.max(p.abs() / l);
            if dp == 0.0 {
                break;
            }
            if dp < 0.0 {
                lo = x
            } else {
                hi = x
            }
            let newton = x - dp / ddp;
            let next = if ddp != 0.0 && (newton - lo) * (newton - hi) < 0.0 { newton } else { 0.5 * (lo + hi) };
            // Quadratic convergence: a step of 1e-10 leaves the value at a
            // stationary point changed by rounding only, and the next is far smaller.
            if (next - x).abs() <= 1e-10 {
                peak = peak.max(eval(next).0.abs() / l);
                break;
            }
            x = next;
        }
    }
    peak
}
