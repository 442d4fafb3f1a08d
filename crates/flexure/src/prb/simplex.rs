//! A bounded Nelder–Mead search, for the 3R chain's lengths.

/// The minimizer of `g` near `start` by Nelder–Mead's simplex (reflection
/// 1, expansion 2, contraction and shrink ½), from a simplex of `step`
/// along each axis, stopping after `iterations` steps or when the values
/// at the simplex's vertices agree to `tolerance`. Returns the best vertex
/// and its value. Non-finite values count as worse than any finite one.
pub(crate) fn minimize(
    g: &mut impl FnMut(&[f64]) -> f64,
    start: &[f64],
    step: f64,
    iterations: usize,
    tolerance: f64,
) -> (Vec<f64>, f64) {
    let n = start.len();
    let value = |g: &mut dyn FnMut(&[f64]) -> f64, x: &[f64]| {
        let v = g(x);
        if v.is_finite() { v } else { f64::INFINITY }
    };
    let mut simplex: Vec<(Vec<f64>, f64)> = Vec::with_capacity(n + 1);
    simplex.push((start.to_vec(), value(g, start)));
    for i in 0..n {
        let mut x = start.to_vec();
        x[i] += step;
        let v = value(g, &x);
        simplex.push((x, v));
    }
    for _ in 0..iterations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let (best, worst) = (simplex[0].1, simplex[n].1);
        if worst.is_finite() && (worst - best).abs() <= tolerance {
            break;
        }
        let centroid: Vec<f64> =
            (0..n).map(|j| simplex[..n].iter().map(|(x, _)| x[j]).sum::<f64>() / n as f64).collect();
        let along =
            |t: f64, worst: &[f64]| -> Vec<f64> { centroid.iter().zip(worst).map(|(c, w)| c + t * (c - w)).collect() };
        let reflected = along(1.0, &simplex[n].0);
        let r = value(g, &reflected);
        if r < simplex[0].1 {
            let expanded = along(2.0, &simplex[n].0);
            let e = value(g, &expanded);
            simplex[n] = if e < r { (expanded, e) } else { (reflected, r) };
        } else if r < simplex[n - 1].1 {
            simplex[n] = (reflected, r);
        } else {
            let contracted = along(if r < simplex[n].1 { 0.5 } else { -0.5 }, &simplex[n].0);
            let c = value(g, &contracted);
            if c < simplex[n].1.min(r) {
                simplex[n] = (contracted, c);
            } else {
                let best = simplex[0].0.clone();
                for (x, v) in simplex.iter_mut().skip(1) {
                    for (xi, bi) in x.iter_mut().zip(&best) {
                        *xi = bi + 0.5 * (*xi - bi);
                    }
                    *v = value(g, x);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    simplex.swap_remove(0)
}
