//! Sweeps of one load, with the stability limit found between two values.

use super::equilibria::{ParameterOf, first_loss, refine_limit};
use super::statics::{LIMIT_PRECISION, Settings, Solution, Statics, assemble_unloaded, follow};
use super::{Loads, Mechanism};
use crate::error::{Error, Result};
use crate::space::Spatial;

/// A load that a sweep varies.
#[derive(Debug, Clone, PartialEq)]
pub enum Parameter {
    /// `tendon.NAME.tension`
    Tension(usize),
    /// `force.NAME.moment`, `.fx` or `.fy`: the component of its [`crate::space::Wrench`]
    /// (0, 1, 2, in the wrench's order $(M, F_x, F_y)$).
    Force(usize, usize),
    /// `gravity.x` or `gravity.y`.
    Gravity(usize),
}

impl Parameter {
    /// Parses `tendon.NAME.tension`, `force.NAME.fx|fy|moment` or `gravity.x|y`
    /// (NAME may itself hold dots).
    pub fn parse(m: &Mechanism, spec: &str) -> Result<Parameter> {
        let bad = |why: &'static str| Error::invalid("sweep", format!("{spec:?}"), why);
        if let Some(name) = spec.strip_prefix("tendon.").and_then(|s| s.strip_suffix(".tension")) {
            return m
                .tendons
                .iter()
                .position(|t| t.name == name)
                .map(Parameter::Tension)
                .ok_or_else(|| bad("names no tendon of the mechanism"));
        }
        if let Some((name, comp)) = spec.strip_prefix("force.").and_then(|s| s.rsplit_once('.')) {
            let k =
                m.forces.iter().position(|f| f.name == name).ok_or_else(|| bad("names no force of the mechanism"))?;
            let c = match comp {
                "moment" => 0,
                "fx" => 1,
                "fy" => 2,
                _ => return Err(bad("a force's component is fx, fy or moment")),
            };
            return Ok(Parameter::Force(k, c));
        }
        match spec {
            "gravity.x" => Ok(Parameter::Gravity(0)),
            "gravity.y" => Ok(Parameter::Gravity(1)),
            _ => Err(bad("must be tendon.NAME.tension, force.NAME.fx|fy|moment or gravity.x|y")),
        }
    }

    /// `loads` with this parameter set to `value`.
    pub fn apply(&self, loads: &Loads, value: f64) -> Loads {
        let mut l = loads.clone();
        self.set(&mut l, value);
        l
    }

    /// Sets this parameter of `loads` to `value`, in place.
    pub fn set(&self, loads: &mut Loads, value: f64) {
        match *self {
            Parameter::Tension(t) => loads.tension[t] = value,
            Parameter::Force(k, c) => loads.force[k][c] = value,
            Parameter::Gravity(c) => loads.gravity[c] = value,
        }
    }
}

/// The one load a spatial mechanism's sweep varies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpatialParameter {
    /// Component 0..6 (`mx, my, mz, fx, fy, fz`) of point load `i`.
    Force(usize, usize),
    /// Tendon `i`'s tension.
    Tension(usize),
    /// Gravity's component 0..3 (`x, y, z`).
    Gravity(usize),
}

/// The components of a point load, by name.
pub const WRENCH_COMPONENTS: [&str; 6] = ["mx", "my", "mz", "fx", "fy", "fz"];

impl SpatialParameter {
    /// `force.NAME.mx|my|mz|fx|fy|fz`, `tendon.NAME.tension` or `gravity.x|y|z`.
    ///
    /// # Example
    /// ```
    /// use flexure::mechanism::sweep::SpatialParameter;
    /// # use flexure::mechanism::spatial::{SpatialBody, SpatialMechanism};
    /// # let m = SpatialMechanism::new(vec![SpatialBody::massless("ground")], vec![], vec![], vec![], vec![], Default::default()).unwrap();
    /// assert_eq!(SpatialParameter::parse(&m, "gravity.z").unwrap(), SpatialParameter::Gravity(2));
    /// assert!(SpatialParameter::parse(&m, "force.none.fx").unwrap_err().to_string().contains("none"));
    /// ```
    pub fn parse(m: &Mechanism<Spatial>, text: &str) -> Result<Self> {
        let bad = |why: &'static str| Error::invalid("sweep", text, why);
        let parts: Vec<&str> = text.split('.').collect();
        match parts.as_slice() {
            ["gravity", axis] => ["x", "y", "z"]
                .iter()
                .position(|a| a == axis)
                .map(SpatialParameter::Gravity)
                .ok_or_else(|| bad("gravity's component must be x, y or z")),
            ["force", name, component] => {
                let i = m
                    .forces
                    .iter()
                    .position(|f| f.name == *name)
                    .ok_or_else(|| bad("names no force of the mechanism"))?;
                let c = WRENCH_COMPONENTS
                    .iter()
                    .position(|c| c == component)
                    .ok_or_else(|| bad("a force's component must be mx, my, mz, fx, fy or fz"))?;
                Ok(SpatialParameter::Force(i, c))
            }
            ["tendon", name, "tension"] => {
                let i = m
                    .tendons
                    .iter()
                    .position(|t| t.name == *name)
                    .ok_or_else(|| bad("names no tendon of the mechanism"))?;
                Ok(SpatialParameter::Tension(i))
            }
            _ => Err(bad("must be force.NAME.mx|my|mz|fx|fy|fz, tendon.NAME.tension or gravity.x|y|z")),
        }
    }

    /// `loads` with this parameter set to `value`.
    pub fn apply(&self, loads: &Loads<Spatial>, value: f64) -> Loads<Spatial> {
        let mut out = loads.clone();
        self.set(&mut out, value);
        out
    }

    /// Sets this parameter of `loads` to `value`, in place.
    pub fn set(&self, loads: &mut Loads<Spatial>, value: f64) {
        match *self {
            SpatialParameter::Force(i, c) => loads.force[i][c] = value,
            SpatialParameter::Tension(i) => loads.tension[i] = value,
            SpatialParameter::Gravity(c) => loads.gravity[c] = value,
        }
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
    parameter: &ParameterOf<D>,
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
    if D::is_tension(parameter)
        && let Some(v) = values.iter().find(|v| **v < 0.0)
    {
        return Err(Error::invalid("sweep", v, "a tendon's tension must be finite and not negative"));
    }
    let base = m.loads();
    let (first, last) = (values[0], values[values.len() - 1]);
    let fraction = |v: f64| if last != first { (v - first) / (last - first) } else { 0.0 };
    let mut out = Sweep { rows: Vec::with_capacity(values.len()), stability_limit: None, stopped: None };
    let mut start = assemble_unloaded(m, settings)?;
    for (i, &v) in values.iter().enumerate() {
        let target = D::apply(parameter, &base, v);
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
                out.stability_limit = Some(SweepLimit { value: value(s), fraction: fraction(value(s)) });
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
