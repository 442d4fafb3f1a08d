//! Sweeps of one load, with the stability limit found between two values.

use super::equilibria::{first_loss, refine_limit};
use super::statics::{
    LIMIT_PRECISION, Settings, Solution, Statics, Touched, Workspace, assemble_unloaded, follow, follow_touching,
};
use super::{Dimension, Loads, Mechanism};
use crate::error::{Error, Result};

/// A load that a sweep or a schedule varies, in either dimension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Parameter {
    /// `tendon.NAME.tension`: tendon `i`'s tension.
    Tension(usize),
    /// `force.NAME.C`: component `c` of point load `i`'s wrench, in the
    /// wrench's order, moment first ([`LoadNames::components`]): 0, 1, 2 for
    /// $(M, F_x, F_y)$ in the plane, 0..6 for `mx, my, mz, fx, fy, fz` in space.
    Force(usize, usize),
    /// `gravity.x`, `.y` (or `.z` in space): gravity's component.
    Gravity(usize),
}

/// How a dimension names its loads in a sweep or a schedule
/// ([`crate::mechanism::Dimension::LOADS`]), and what [`Parameter::parse`]
/// says of a name it refuses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadNames {
    /// A point load's components, in its wrench's order.
    pub components: &'static [&'static str],
    /// Gravity's components.
    pub axes: &'static [&'static str],
    /// What a load must be.
    pub must_be: &'static str,
    /// What a point load's component must be.
    pub component: &'static str,
    /// What gravity's component must be, where a wrong one is told apart
    /// from a wrong load (in space; in the plane it is a wrong load).
    pub axis: Option<&'static str>,
    /// Whether a NAME may hold dots (in the plane), or holds none (in space).
    pub dotted: bool,
    /// Whether a refused name is shown quoted (in the plane).
    pub quoted: bool,
}

impl Parameter {
    /// Parses `tendon.NAME.tension`, `force.NAME.C` with `C` one of the
    /// dimension's [`LoadNames::components`] (`fx`, `fy`, `moment` in the
    /// plane; `mx`, `my`, `mz`, `fx`, `fy`, `fz` in space), or `gravity.A`
    /// with `A` one of its [`LoadNames::axes`].
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::sweep::Parameter;
    /// # use flexure::mechanism::spatial::{SpatialBody, SpatialMechanism};
    /// # let m = SpatialMechanism::new(vec![SpatialBody::massless("ground")], vec![], vec![], vec![], vec![], Default::default()).unwrap();
    /// assert_eq!(Parameter::parse(&m, "gravity.z").unwrap(), Parameter::Gravity(2));
    /// assert!(Parameter::parse(&m, "force.none.fx").unwrap_err().to_string().contains("none"));
    /// ```
    pub fn parse<D: Dimension>(m: &Mechanism<D>, text: &str) -> Result<Parameter> {
        let words = D::LOADS;
        let shown = if words.quoted { format!("{text:?}") } else { text.to_string() };
        let bad = |why: &'static str| Error::invalid("sweep", &shown, why);
        let name = |n: &str| words.dotted || !n.contains('.');
        if let Some(n) = text.strip_prefix("tendon.").and_then(|s| s.strip_suffix(".tension")).filter(|n| name(n)) {
            return m
                .tendons
                .iter()
                .position(|t| t.name == n)
                .map(Parameter::Tension)
                .ok_or_else(|| bad("names no tendon of the mechanism"));
        }
        if let Some((n, c)) = text.strip_prefix("force.").and_then(|s| s.rsplit_once('.')).filter(|(n, _)| name(n)) {
            let i = m.forces.iter().position(|f| f.name == n).ok_or_else(|| bad("names no force of the mechanism"))?;
            let c = words.components.iter().position(|w| *w == c).ok_or_else(|| bad(words.component))?;
            return Ok(Parameter::Force(i, c));
        }
        if let Some(a) = text.strip_prefix("gravity.").filter(|a| !a.contains('.')) {
            match (words.axes.iter().position(|w| *w == a), words.axis) {
                (Some(c), _) => return Ok(Parameter::Gravity(c)),
                (None, Some(why)) => return Err(bad(why)),
                (None, None) => {}
            }
        }
        Err(bad(words.must_be))
    }

    /// `loads` with this parameter set to `value`.
    pub fn apply<D: Dimension>(&self, loads: &Loads<D>, value: f64) -> Loads<D> {
        let mut out = loads.clone();
        self.set(&mut out, value);
        out
    }

    /// Sets this parameter of `loads` to `value`, in place.
    pub fn set<D: Dimension>(&self, loads: &mut Loads<D>, value: f64) {
        match *self {
            Parameter::Tension(i) => loads.tension[i] = value,
            Parameter::Force(i, c) => loads.force[i][c] = value,
            Parameter::Gravity(c) => loads.gravity[c] = value,
        }
    }

    /// Whether it is a tendon's tension (which cannot be negative).
    pub fn is_tension(&self) -> bool {
        matches!(self, Parameter::Tension(_))
    }
}

/// Where a sweep lost stability, in the swept quantity (serialized as a
/// sweep's `stability_limit`; [`crate::StabilityLimit`] is the factor on a load).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SweepLimit {
    /// The swept quantity's value there, in its units.
    pub value: f64,
    /// Its position along the sweep's range, `(value − first)/(last − first)`.
    pub fraction: f64,
}

impl SweepLimit {
    /// The limit at `value` of a sweep over `values` (its fraction 0 for a
    /// sweep of one value, or of equal first and last).
    fn at(value: f64, values: &[f64]) -> Self {
        let (first, last) = (values[0], values[values.len() - 1]);
        let fraction = if last != first { (value - first) / (last - first) } else { 0.0 };
        SweepLimit { value, fraction }
    }
}

/// What [`sweep`] reached; serialized with each row as
/// `{"value", "solution"}` and `stopped` as `{"value", "error"}` (the
/// error's message).
/// Written once for either dimension: `Sweep<Solution<Spatial>>` is a
/// spatial mechanism's.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(bound = "S: serde::Serialize")]
pub struct Sweep<S = Solution> {
    /// The values solved, each with its stable equilibrium: every value up
    /// to where stability was lost beyond recovery.
    #[serde(serialize_with = "rows")]
    pub rows: Vec<(f64, S)>,
    /// The first loss of stability along the sweep, if any.
    pub stability_limit: Option<SweepLimit>,
    /// Why the sweep ended before its last value, if a solve failed (a
    /// stalled continuation, an interrupt): the value, and the error. The
    /// rows before it are kept; the values after it are not tried, since
    /// each is continued from the last.
    #[serde(serialize_with = "stopped")]
    pub stopped: Option<(f64, Error)>,
}

/// [`Sweep::rows`] as `[{"value", "solution"}, ...]`.
fn rows<T: serde::Serialize, S: serde::Serializer>(rows: &[(f64, T)], s: S) -> std::result::Result<S::Ok, S::Error> {
    #[derive(serde::Serialize)]
    struct Row<'a, T> {
        value: f64,
        solution: &'a T,
    }
    s.collect_seq(rows.iter().map(|(value, solution)| Row { value: *value, solution }))
}

/// [`Sweep::stopped`] as `{"value", "error"}`, the error by its message.
fn stopped<S: serde::Serializer>(stopped: &Option<(f64, Error)>, s: S) -> std::result::Result<S::Ok, S::Error> {
    #[derive(serde::Serialize)]
    struct Stopped {
        value: f64,
        error: String,
    }
    let stopped = stopped.as_ref().map(|(value, e)| Stopped { value: *value, error: e.to_string() });
    serde::Serialize::serialize(&stopped, s)
}

/// Equilibria along `values` of one load, each continued from the last.
///
/// Every row is stable. When the path loses stability between two values,
/// the loss is found by bisection between them, to a relative
/// [`LIMIT_PRECISION`] of the swept value (at most 64 halvings, each a
/// continuation of at most [`super::statics::PROBE_STEPS`] steps from the
/// last stable state). The sweep goes on past a snap-through that lands on
/// a stable state, and stops where none is reached. The first value is
/// reached from the unloaded state with every load ramped together: if
/// stability is lost on the way, that is the first row's own
/// [`Solution::limit`] (or [`Error::Unstable`] if no stable state is reached).
/// A solve that fails ends the sweep there, with the rows reached and the
/// failure in [`Sweep::stopped`]; only bad input is an error.
///
/// # Example
/// ```
/// use flexure::mechanism::{file::from_toml, statics::Settings, sweep::{sweep, Parameter}};
/// // A sprung arm (k = 1 N·m/rad, l = 0.1 m) pushed along itself loses
/// // stability at P = k/l = 10 N: found between the rows at 8 and 12 N.
/// let m = from_toml(
///     "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
///      [[force]]\nname = \"push\"\nbody = \"arm\"\nat = [0.1, 0.0]\n",
/// )
/// .unwrap();
/// let p = Parameter::parse(&m, "force.push.fx").unwrap();
/// let out = sweep(&m, &p, &[0.0, -4.0, -8.0, -12.0, -16.0], &Settings::default()).unwrap();
/// assert_eq!(out.rows.len(), 3);
/// let limit = out.stability_limit.unwrap();
/// assert!((limit.value + 10.0).abs() < 1e-4 && (limit.fraction - 0.625).abs() < 1e-5);
/// ```
pub fn sweep<D: Statics>(
    m: &Mechanism<D>,
    parameter: &Parameter,
    values: &[f64],
    settings: &Settings,
) -> Result<Sweep<Solution<D>>> {
    settings.validate()?;
    if values.is_empty() {
        return Err(Error::invalid("sweep", "no values", "a sweep needs at least one value"));
    }
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(Error::invalid("sweep", v, "values must be finite"));
    }
    if parameter.is_tension()
        && let Some(v) = values.iter().find(|v| **v < 0.0)
    {
        return Err(Error::invalid("sweep", v, "a tendon's tension must be finite and not negative"));
    }
    if !super::contact::pairs(m).is_empty() {
        return Ok(sweep_touching(m, parameter, values, settings));
    }
    let base = m.loads();
    let mut out = Sweep { rows: Vec::with_capacity(values.len()), stability_limit: None, stopped: None };
    let mut start = assemble_unloaded(m, settings)?;
    for (i, &v) in values.iter().enumerate() {
        let target = parameter.apply(&base, v);
        // The first value is reached from the unloaded state with every load
        // ramped together: a loss there is refined as a solve's.
        let found = follow(m, &start, &target, settings);
        let found = if i == 0 { refine_limit(m, &start, &target, settings, found) } else { found };
        let lost = i > 0
            && match &found {
                Ok(s) => s.limit.is_some(),
                Err(Error::Unstable { .. }) => true,
                Err(_) => false,
            };
        let mut limit = None;
        if lost {
            let previous = values[i - 1];
            let value = |s: f64| previous + s * (v - previous);
            let precise = |lo: f64, hi: f64| {
                (value(hi) - value(lo)).abs() <= LIMIT_PRECISION * value(lo).abs().max(value(hi).abs())
            };
            let s = match first_loss(m, &start, &target, settings, precise) {
                Ok(s) => s,
                Err(e) => {
                    out.stopped = Some((v, e));
                    break;
                }
            };
            limit = Some(s);
            if out.stability_limit.is_none() {
                out.stability_limit = Some(SweepLimit::at(value(s), values));
            }
        }
        match found {
            Ok(s) => {
                let own = s.limit;
                let s = Solution { limit: limit.or(own), ..s };
                start = s.clone();
                out.rows.push((v, s));
            }
            Err(Error::Unstable { .. }) if lost => break,
            Err(e @ Error::InvalidParameter { .. }) => return Err(e),
            Err(e) => {
                out.stopped = Some((v, e));
                break;
            }
        }
    }
    Ok(out)
}

/// Where a stopped sweep followed its failing value from, as its error's
/// fraction of the load counts: the last value it reached, or no load.
///
/// # Example
/// ```
/// use flexure::mechanism::sweep::way_to;
/// assert!(way_to(Some(3.75)).contains("from 3.75"));
/// assert!(way_to(None).contains("from no load"));
/// ```
pub fn way_to(last: Option<f64>) -> String {
    match last {
        Some(v) => format!("on its way there from {v} (a fraction of the load below is of that way)"),
        None => "on its way there from no load (a fraction of the load below is of all of it)".to_string(),
    }
}

/// [`sweep`] of a mechanism with contact: each value followed from the
/// last with its contacts ([`follow_touching`]), the first from no load.
/// Where the path from one value to the next loses stability, that is the
/// sweep's `stability_limit` (at the fraction of the way the path found,
/// to its event resolution), and the values past it are left out, as
/// without contact (snap-through is not followed with contact). A value it
/// cannot reach otherwise (one that stalls, distributed contact, a first
/// value unstable from no load) stops the sweep there, with the rows before it.
fn sweep_touching<D: Statics>(
    m: &Mechanism<D>,
    parameter: &Parameter,
    values: &[f64],
    settings: &Settings,
) -> Sweep<Solution<D>> {
    let base = m.loads();
    let mut out = Sweep { rows: Vec::with_capacity(values.len()), stability_limit: None, stopped: None };
    let mut work = Workspace::new(m);
    let mut from: Option<Touched<D>> = None;
    let mut path = Vec::new();
    for (i, &v) in values.iter().enumerate() {
        let loads = parameter.apply(&base, v);
        match follow_touching(m, from.as_ref(), &loads, settings, &mut work) {
            Ok((s, next)) => {
                out.rows.push((v, Solution { path: path.clone(), ..s }));
                path.push(loads);
                from = Some(next);
            }
            Err(Error::Unstable { load_fraction, .. }) if i > 0 => {
                let value = values[i - 1] + load_fraction * (v - values[i - 1]);
                out.stability_limit = Some(SweepLimit::at(value, values));
                break;
            }
            Err(e) => {
                out.stopped = Some((v, e));
                break;
            }
        }
    }
    out
}
