//! The vectorized node sine/cosine against libm (glibc's `sincos`, an
//! independent, correctly rounded-in-practice implementation).

use flexure::sincos::{REDUCTION_LIMIT, cos_sin};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// Distance in units in the last place of `exact`.
fn ulps(value: f64, exact: f64) -> f64 {
    let spacing = f64::from_bits(exact.abs().max(f64::MIN_POSITIVE).to_bits() + 1) - exact.abs().max(f64::MIN_POSITIVE);
    (value - exact).abs() / spacing
}

/// Seeded xorshift in [lo, hi).
fn uniform(count: usize, lo: f64, hi: f64, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..count)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            lo + (hi - lo) * ((state >> 11) as f64 / (1u64 << 53) as f64)
        })
        .collect()
}

/// Largest error, in ulp, of `cos_sin` over `angles`, fed in groups of `M`.
fn worst_of<const M: usize>(angles: &[f64]) -> (f64, f64) {
    let (mut cos_err, mut sin_err) = (0.0f64, 0.0f64);
    for group in angles.chunks_exact(M) {
        let group: &[f64; M] = group.try_into().expect("M angles");
        for (&x, [c, s]) in group.iter().zip(cos_sin(group)) {
            let (s_ref, c_ref) = x.sin_cos();
            cos_err = cos_err.max(ulps(c, c_ref));
            sin_err = sin_err.max(ulps(s, s_ref));
        }
    }
    (cos_err, sin_err)
}

/// The worst of groups of 1, 5 (the kernel's node count at order 3) and 8.
fn worst(angles: &[f64]) -> (f64, f64) {
    let all = [worst_of::<1>(angles), worst_of::<5>(angles), worst_of::<8>(angles)];
    all.into_iter().fold((0.0, 0.0), |(c, s), (ci, si)| (c.max(ci), s.max(si)))
}

/// Within 1 ulp of libm over every range the reduction takes: both are
/// faithful (fdlibm's kernels with the reduced argument's tail are under
/// 1 ulp, as is glibc), so they can differ by one rounding, not two.
#[test]
fn within_one_ulp_of_libm() {
    for (i, (lo, hi)) in
        [(-0.8, 0.8), (-7.0, 7.0), (-100.0, 100.0), (-REDUCTION_LIMIT, REDUCTION_LIMIT)].into_iter().enumerate()
    {
        let (c, s) = worst(&uniform(200_000, lo, hi, 0x9e37_79b9_7f4a_7c15 + i as u64));
        assert!(c <= 1.0 && s <= 1.0, "[{lo}, {hi}]: cos {c} ulp, sin {s} ulp");
    }
}

/// Within 1 ulp at every magnitude, from subnormal to the limit: log-uniform
/// magnitudes with random signs.
#[test]
fn within_one_ulp_at_every_magnitude() {
    let top = REDUCTION_LIMIT.log10();
    let exponents = uniform(200_000, -310.0, top, 0x2545_f491_4f6c_dd1d);
    let signs = uniform(200_000, -1.0, 1.0, 0x1234_5678_9abc_def1);
    let angles: Vec<f64> =
        exponents.iter().zip(&signs).map(|(e, s)| 10f64.powf(*e).min(REDUCTION_LIMIT).copysign(*s)).collect();
    let (c, s) = worst(&angles);
    assert!(c <= 1.0 && s <= 1.0, "cos {c} ulp, sin {s} ulp");
}

/// Next to multiples of π/2, where the reduced argument cancels and the
/// small result must keep its relative accuracy; and at quadrant edges π/4.
#[test]
fn near_multiples_of_half_pi() {
    let mut angles = Vec::new();
    for k in [-1_000_000i64, -12345, -4, -3, -2, -1, 1, 2, 3, 4, 7, 100, 12345, 400_000, 524_287] {
        let centre = k as f64 * FRAC_PI_2;
        let mut x = centre;
        for _ in 0..40 {
            angles.extend([x, x + FRAC_PI_4]);
            x = x.next_up();
        }
    }
    angles.retain(|x| x.abs() <= REDUCTION_LIMIT);
    let (c, s) = worst(&angles);
    assert!(c <= 1.0 && s <= 1.0, "cos {c} ulp, sin {s} ulp");
}

/// Signed zero, tiny arguments, and the hand-off to libm past the limit,
/// at infinity and at NaN (all of a group goes to libm then).
#[test]
fn edges_and_hand_off() {
    let angles = [0.0, -0.0, 1e-300, -1e-12, REDUCTION_LIMIT, 2.0 * REDUCTION_LIMIT];
    let out = cos_sin(&angles);
    assert_eq!(out[0], [1.0, 0.0]);
    assert!(out[1][1] == 0.0 && out[1][1].is_sign_negative());
    assert_eq!(out[2], [1.0, 1e-300]);
    assert_eq!(out[3], [1.0, -1e-12]);
    for (&x, [c, s]) in angles.iter().zip(out).skip(4) {
        assert!(ulps(c, x.cos()) <= 1.0 && ulps(s, x.sin()) <= 1.0, "{x}");
    }
    let out = cos_sin(&[1.0, f64::INFINITY]);
    assert_eq!(out[0], [1f64.cos(), 1f64.sin()]);
    assert!(out[1][0].is_nan() && out[1][1].is_nan());
    let out = cos_sin(&[f64::NAN, 0.5]);
    assert!(out[0][0].is_nan() && out[1] == [0.5f64.cos(), 0.5f64.sin()]);
}
