//! Axes with ticks at round values: 1, 2 or 5 × 10ᵏ on linear axes (with a
//! shared factor for small values), decades as powers of ten on logarithmic ones.

/// `10` with superscript exponent `k`: `10⁻⁶`.
pub(crate) fn power_of_ten(k: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for d in k.unsigned_abs().to_string().bytes() {
        s.push(DIGITS[usize::from(d - b'0')]);
    }
    s
}

/// The smallest of 1, 2, 5 × 10ᵏ at least `raw`.
pub(crate) fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let k = raw.log10().floor();
    let base = 10f64.powf(k);
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * base).find(|s| *s >= raw * (1.0 - 1e-9)).unwrap_or(10.0 * base)
}

/// A tick at a position in axis units (log₁₀ of the value on a log axis).
pub(crate) struct Tick {
    pub(crate) at: f64,
    pub(crate) label: String,
}

/// One axis: its range in axis units, ticks, minor ticks, and a note for
/// its label (a common factor such as `×10⁻⁴`).
pub(crate) struct Axis {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) ticks: Vec<Tick>,
    pub(crate) minor: Vec<f64>,
    pub(crate) factor: Option<String>,
}

/// Ticks at round multiples on `[lo, hi]`, about `target` of them; whole
/// numbers only when `integer`. Labels carry as many decimals as the step
/// needs; very small or large values share a factor `×10ᵏ` instead.
pub(crate) fn linear_axis(lo: f64, hi: f64, target: f64, integer: bool) -> Axis {
    let mut step = nice_step((hi - lo) / target.max(1.0));
    if integer {
        step = step.max(1.0);
    }
    let (i0, i1) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
    let values: Vec<f64> = (i0..=i1.min(i0 + 200)).map(|i| i as f64 * step).collect();
    let big = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let k = if big > 0.0 && (step < 1e-3 || big >= 1e5) { big.log10().floor() as i32 } else { 0 };
    let unit = 10f64.powi(k);
    let decimals = (-(step / unit).log10().floor()).max(0.0) as usize;
    let ticks = values
        .iter()
        .map(|&v| {
            let text = format!("{:.*}", decimals, v / unit);
            // No "-0.0": a label that reads as zero is zero.
            let zero = text.trim_start_matches('-').chars().all(|c| c == '0' || c == '.');
            let label = if zero { format!("{:.*}", decimals, 0.0) } else { text.replace('-', "−") };
            Tick { at: v, label }
        })
        .collect();
    Axis { lo, hi, ticks, minor: Vec::new(), factor: (k != 0).then(|| format!("×{}", power_of_ten(k))) }
}

/// A log axis on whole decades `[10^k0, 10^k1]` (axis units are log₁₀):
/// a labelled tick per decade (every other one past 8 decades), minor ticks
/// at 2…9, and labels at 2 and 5 too when only one decade shows.
pub(crate) fn log_axis(k0: i32, k1: i32) -> Axis {
    let n = (k1 - k0).max(1);
    let every = (n + 7) / 8;
    let mut ticks = Vec::new();
    let mut minor = Vec::new();
    for k in k0..=k1 {
        if (k - k0) % every == 0 {
            ticks.push(Tick { at: f64::from(k), label: power_of_ten(k) });
        }
        if k < k1 {
            for m in 2..=9 {
                let at = f64::from(k) + f64::from(m).log10();
                if n == 1 && (m == 2 || m == 5) {
                    ticks.push(Tick { at, label: format!("{m}×{}", power_of_ten(k)) });
                } else {
                    minor.push(at);
                }
            }
        }
    }
    Axis { lo: f64::from(k0), hi: f64::from(k1), ticks, minor, factor: None }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    pub(crate) fn ticks_read_as_round_numbers() {
        // Decades print as powers of ten, never as 9.999999999999999e-6.
        let a = log_axis(-8, -2);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["10⁻⁸", "10⁻⁷", "10⁻⁶", "10⁻⁵", "10⁻⁴", "10⁻³", "10⁻²"]);
        // A linear axis through zero reads "0.0", never "-0.0"; negatives get a true minus.
        let a = linear_axis(-0.26, 0.83, 8.0, false);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["−0.2", "0.0", "0.2", "0.4", "0.6", "0.8"]);
        let a = linear_axis(2.7, 9.3, 8.0, true);
        assert_eq!(a.ticks.iter().map(|t| t.label.as_str()).collect::<Vec<_>>(), ["3", "4", "5", "6", "7", "8", "9"]);
        // Small values share a factor.
        let a = linear_axis(0.0, 7.7e-4, 8.0, false);
        assert_eq!(a.factor.as_deref(), Some("×10⁻⁴"));
        assert_eq!(a.ticks[1].label, "1");
    }
}
