//! Sine and cosine of a handful of angles at once: the quadrature nodes'
//! $\sin\phi(t_k), \cos\phi(t_k)$, which are half the cost of an evaluation.
//!
//! libm's `sincos` works on one argument at a time and cannot be inlined or
//! vectorized. Here every node runs the same branch-free steps, so the
//! compiler packs two (SSE2) or four (AVX) nodes per instruction:
//!
//! 1. Cody–Waite reduction $r = x - n\frac\pi2$, $n = \mathrm{round}(2x/\pi)$,
//!    with $\frac\pi2$ split into 33-bit pieces so each $n\cdot$piece is
//!    exact for $|n| < 2^{20}$;
//! 2. the minimax polynomials of fdlibm's `__kernel_sin`/`__kernel_cos`
//!    on $|r| \le \pi/4$, with the reduced argument's rounding error $y$;
//! 3. a swap and sign flips chosen by the quadrant $n \bmod 4$.
//!
//! Results agree with libm to within 1 ulp (see `tests/sincos.rs`).
//! Arguments beyond [`REDUCTION_LIMIT`], infinities and NaN go to libm.

/// Largest $|x|$ reduced here: $2^{19}\pi/2$, half the range where the
/// 33-bit pieces of $\pi/2$ times $n$ stay exact.
pub const REDUCTION_LIMIT: f64 = 823_549.664_582_643_1;

const INV_PIO2: f64 = std::f64::consts::FRAC_2_PI;
// π/2 = PIO2_1 + PIO2_2 + PIO2_3 + PIO2_3T; the first three have 33 bits.
const PIO2_1: f64 = 1.570_796_326_734_125_6;
const PIO2_2: f64 = 6.077_100_506_303_966e-11;
const PIO2_3: f64 = 2.022_266_248_711_166_5e-21;
const PIO2_3T: f64 = 8.478_427_660_368_9e-32;
// 1.5·2⁵²: adding it rounds to an integer, kept in the low mantissa bits.
const ROUND: f64 = 6_755_399_441_055_744.0;

const S1: f64 = -1.666_666_666_666_663_2e-1;
const S2: f64 = 8.333_333_333_322_49e-3;
const S3: f64 = -1.984_126_982_985_795e-4;
const S4: f64 = 2.755_731_370_707_006_8e-6;
const S5: f64 = -2.505_076_025_340_686_3e-8;
const S6: f64 = 1.589_690_995_211_55e-10;

const C1: f64 = 4.166_666_666_666_66e-2;
const C2: f64 = -1.388_888_888_887_411e-3;
const C3: f64 = 2.480_158_728_947_673e-5;
const C4: f64 = -2.755_731_435_139_066_3e-7;
const C5: f64 = 2.087_572_321_298_175e-9;
const C6: f64 = -1.135_964_755_778_819_5e-11;

/// $(\cos x_l, \sin x_l)$ of `M` angles, all within [`REDUCTION_LIMIT`].
///
/// Written lane by lane: each step is one loop over the `M` angles, which
/// the compiler turns into packed instructions, and the polynomials use
/// Estrin's scheme, so the dependency chain is short and the lanes overlap.
#[inline(always)]
fn reduced<const M: usize>(x: &[f64; M]) -> [[f64; 2]; M] {
    let t = lanes::<M>(|l| x[l] * INV_PIO2 + ROUND);
    let n = lanes::<M>(|l| t[l] - ROUND);
    // r + y = x − nπ/2 to about 100 bits, even where it cancels: each
    // n·PIO2_i is exact, x − n·PIO2_1 is exact, and (a − b) − w recovers
    // what rounding b = a − w lost.
    let a = lanes::<M>(|l| x[l] - n[l] * PIO2_1);
    let b = lanes::<M>(|l| a[l] - n[l] * PIO2_2);
    let c = lanes::<M>(|l| b[l] - n[l] * PIO2_3);
    let e = lanes::<M>(|l| ((a[l] - b[l]) - n[l] * PIO2_2) + ((b[l] - c[l]) - n[l] * PIO2_3) - n[l] * PIO2_3T);
    let r = lanes::<M>(|l| c[l] + e[l]);
    let y = lanes::<M>(|l| (c[l] - r[l]) + e[l]);
    // fdlibm's __kernel_sin(r, y) and __kernel_cos(r, y) on |r| ≤ π/4.
    let z = lanes::<M>(|l| r[l] * r[l]);
    let zz = lanes::<M>(|l| z[l] * z[l]);
    let v = lanes::<M>(|l| z[l] * r[l]);
    let p = lanes::<M>(|l| (S2 + z[l] * S3) + zz[l] * ((S4 + z[l] * S5) + zz[l] * S6));
    let sin_r = lanes::<M>(|l| r[l] - ((z[l] * (0.5 * y[l] - v[l] * p[l]) - y[l]) - v[l] * S1));
    let q = lanes::<M>(|l| (C1 + z[l] * C2) + zz[l] * ((C3 + z[l] * C4) + zz[l] * (C5 + z[l] * C6)));
    let h = lanes::<M>(|l| 0.5 * z[l]);
    let w = lanes::<M>(|l| 1.0 - h[l]);
    // 1 − z/2 rounded, then its rounding error added back.
    let cos_r = lanes::<M>(|l| w[l] + (((1.0 - w[l]) - h[l]) + (zz[l] * q[l] - r[l] * y[l])));
    // Quadrant n mod 4: sin x = (sin r, cos r, −sin r, −cos r)[n], and
    // cos x = (cos r, −sin r, −cos r, sin r)[n].
    let mut out = [[0.0; 2]; M];
    for l in 0..M {
        let quadrant = t[l].to_bits();
        let swap = (quadrant & 1).wrapping_neg();
        let (sb, cb) = (sin_r[l].to_bits(), cos_r[l].to_bits());
        let sin_bits = ((cb & swap) | (sb & !swap)) ^ ((quadrant & 2) << 62);
        let cos_bits = ((sb & swap) | (cb & !swap)) ^ ((quadrant.wrapping_add(1) & 2) << 62);
        out[l] = [f64::from_bits(cos_bits), f64::from_bits(sin_bits)];
    }
    out
}

/// One step applied to every lane.
#[inline(always)]
fn lanes<const M: usize>(step: impl Fn(usize) -> f64) -> [f64; M] {
    // A plain loop over a constant count: fully unrolled and inlined, where
    // `array::from_fn` left an out-of-line closure call per lane at M = 8.
    let mut out = [0.0; M];
    for l in 0..M {
        out[l] = step(l);
    }
    out
}

/// $(\cos x_l, \sin x_l)$ of `M` angles at once.
///
/// # Example
/// ```
/// let out = flexure::sincos::cos_sin(&[0.0, 1.0, -2.5]);
/// assert_eq!(out[0], [1.0, 0.0]);
/// assert!((out[1][1] - 1f64.sin()).abs() <= f64::EPSILON);
/// assert!((out[2][0] - (-2.5f64).cos()).abs() <= f64::EPSILON);
/// ```
#[inline(always)]
pub fn cos_sin<const M: usize>(angles: &[f64; M]) -> [[f64; 2]; M] {
    if angles.iter().all(|x| x.abs() <= REDUCTION_LIMIT) {
        reduced(angles)
    } else {
        angles.map(|x| {
            let (s, c) = x.sin_cos();
            [c, s]
        })
    }
}
