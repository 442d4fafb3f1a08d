//! What an answer reports of a flexure's bending: the peak stress (or, for a
//! section given by EI alone, the peak change of curvature), the safety
//! factor against a yield strength, and the deformed shape.

use crate::options::{StressOptions, warn};
use flexure::Flexure;
use flexure::model::Bending;
use flexure::stress::{Peak, peak_curvature, peak_stress};
use serde_json::{Value, json};

/// Refuses a yield strength on a flexure that has no thickness, whose
/// stress is therefore unknown (`name` is the option or key that gave it).
pub fn check(f: &Flexure, options: &StressOptions) -> flexure::Result<()> {
    flexure::model::check_yield(f, options.yield_strength)
}

/// The peak: `stress: {max (Pa), at (m)}` with a thickness, else
/// `curvature_max: {max (1/m), at (m)}`, the largest change of curvature
/// from rest; with `yield_strength`, `safety_factor` = S/σmax (left out when
/// the flexure is unstressed: it would be infinite), and a warning naming
/// `what` below 1.
pub fn peak(answer: &mut Value, f: &Flexure, alpha: &[f64], yield_strength: Option<f64>, what: &str) {
    let never = insert_peak(
        answer,
        peak_stress(f, alpha),
        || Ok::<_, std::convert::Infallible>(peak_curvature(f, alpha)),
        yield_strength,
        what,
    );
    if let Err(e) = never {
        match e {}
    }
}

/// Writes `stress` (and `safety_factor`) from `stress`, or without one
/// `curvature_max` from `curvature`: shared by the model's and the exact answers.
pub fn insert_peak<E>(
    answer: &mut Value,
    stress: Option<Peak>,
    curvature: impl FnOnce() -> Result<Peak, E>,
    yield_strength: Option<f64>,
    what: &str,
) -> Result<(), E> {
    match stress {
        Some(p) => {
            answer["stress"] = json!({ "max": p.value, "at": p.at });
            if let Some(s) = yield_strength
                && p.value > 0.0
            {
                let factor = s / p.value;
                answer["safety_factor"] = json!(factor);
                warn_past_yield("bending", (p.value, p.at), (s, factor), what);
            }
        }
        None => {
            let p = curvature()?;
            answer["curvature_max"] = json!({ "max": p.value, "at": p.at });
        }
    }
    Ok(())
}

/// Warns when the safety `factor` against the yield strength `s` (Pa) is
/// below 1: the peak stress of `kind` is `max` (Pa) at `at` (m); `what` names the answer.
fn warn_past_yield(kind: &str, (max, at): (f64, f64), (s, factor): (f64, f64), what: &str) {
    if factor < 1.0 {
        warn(format!(
            "{what}: the peak {kind} stress {max:.4e} Pa (at s = {at:.4e} m) exceeds the yield strength {s:e} Pa: safety factor {factor:.3}"
        ));
    }
}

/// [`warn_past_yield`] for an answer's [`Bending`]: a
/// stress with its point over the section is the peak von Mises stress of
/// a spatial section's parts; without one, the bending stress.
pub fn warn_yield(bending: &Bending, yield_strength: Option<f64>, what: &str) {
    if let (Some(p), Some(factor), Some(s)) = (&bending.stress, bending.safety_factor, yield_strength) {
        let kind = if p.point.is_some() { "von Mises" } else { "bending" };
        warn_past_yield(kind, (p.max, p.at), (s, factor), what);
    }
}

/// The deformed flexure at `count` points evenly spaced in arc length, ends
/// included, in its root frame: `{s, x, y, phi, curvature, stress}` with the
/// total curvature (1/m) and, with a thickness, the bending stress (Pa).
pub fn shape(f: &Flexure, alpha: &[f64], count: usize) -> Value {
    json!(flexure::report::shape(f, alpha, count))
}

/// [`peak`], and [`shape`] when asked for: everything `options` asks of `f` at `alpha`.
pub fn insert_stress(answer: &mut Value, f: &Flexure, alpha: &[f64], options: &StressOptions, what: &str) {
    peak(answer, f, alpha, options.yield_strength, what);
    if let Some(k) = options.shape {
        answer["shape"] = shape(f, alpha, k);
    }
}
