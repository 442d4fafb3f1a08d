//! The load range a fit is made over: fractions of the file's loads.

use crate::error::{Error, Result};

/// Most samples of a load range: each is one equilibrium of the mechanism
/// and one more load case of every flexure's fit.
pub const MAX_SAMPLES: usize = 64;

/// The fractions $\lambda_i$ of the file's loads (every tension, force,
/// moment and gravity times $\lambda$) at which the mechanism is solved and
/// its flexures' tip wrenches taken: `count` values evenly spaced from
/// `from` to `to`, both included,
/// $$\lambda_i = \lambda_0 + \frac{i}{n - 1}(\lambda_1 - \lambda_0),\qquad i = 0, \dots, n - 1.$$
/// Written `F0:F1:N` on the command line, as a sweep's values are.
///
/// # Example
/// ```
/// use flexure::export::LoadRange;
/// let r: LoadRange = "0:1:5".parse().unwrap();
/// assert_eq!(r.fractions(), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
/// assert!("0:1:1".parse::<LoadRange>().unwrap_err().to_string().contains("range"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadRange {
    /// The first fraction $\lambda_0$.
    pub from: f64,
    /// The last fraction $\lambda_1$.
    pub to: f64,
    /// How many fractions, from 2 to [`MAX_SAMPLES`].
    pub count: usize,
}

impl Default for LoadRange {
    /// The file's loads from none to all of them, at 12 fractions.
    fn default() -> Self {
        LoadRange { from: 0.0, to: 1.0, count: 12 }
    }
}

impl LoadRange {
    /// Checks the fractions: finite, at most 1e3 in magnitude (a fit far past
    /// the file's loads is no fit of the mechanism), distinct, and a count
    /// from 2 to [`MAX_SAMPLES`].
    pub fn validate(&self) -> Result<()> {
        for v in [self.from, self.to] {
            if !(v.is_finite() && v.abs() <= 1e3) {
                return Err(Error::invalid("range", v, "each fraction must be finite and at most 1e3 in magnitude"));
            }
        }
        if self.from == self.to {
            return Err(Error::invalid("range", format!("{}:{}", self.from, self.to), "the two fractions must differ"));
        }
        if !(2..=MAX_SAMPLES).contains(&self.count) {
            return Err(Error::invalid("range", self.count, "the count must be from 2 to 64"));
        }
        Ok(())
    }

    /// The fractions, from `from` to `to`.
    pub fn fractions(&self) -> Vec<f64> {
        let n = self.count.max(2);
        (0..n).map(|i| self.from + (self.to - self.from) * i as f64 / (n - 1) as f64).collect()
    }
}

impl std::str::FromStr for LoadRange {
    type Err = Error;

    /// `F0:F1:N`, e.g. `0:1:12`.
    fn from_str(s: &str) -> Result<Self> {
        let bad =
            || Error::invalid("range", format!("{s:?}"), "must be F0:F1:N, fractions of the file's loads, e.g. 0:1:12");
        let parts: Vec<&str> = s.split(':').collect();
        let [a, b, n] = parts.as_slice() else { return Err(bad()) };
        let from: f64 = a.trim().parse().map_err(|_| bad())?;
        let to: f64 = b.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        let r = LoadRange { from, to, count };
        r.validate()?;
        Ok(r)
    }
}
