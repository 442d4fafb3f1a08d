//! Schedules of loads over time, and the initial state of a simulation.

use super::dimension::FileDimension;
use super::document::{Sign, Source, number};
use super::{BTreeMap, Deserialize, Error, Mechanism, Result, Schedule, Spanned, Waveform};
use crate::mechanism::sweep::Parameter;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ScheduleToml {
    pub(super) load: Spanned<String>,
    pub(super) points: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
    pub(super) harmonic: Option<Spanned<HarmonicToml>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct HarmonicToml {
    pub(super) amplitude: Spanned<f64>,
    pub(super) frequency: Spanned<f64>,
    pub(super) phase: Option<Spanned<f64>>,
    pub(super) offset: Option<Spanned<f64>>,
}

/// The `[[schedule]]` tables: each names a load of the mechanism (as
/// sweeps do) at most once, with either points `[t, value]` of finite
/// numbers whose times do not decrease, at most two at one time (a step),
/// or a `harmonic` (amplitude, frequency in Hz, phase in rad, offset).
pub(super) fn schedules<D: FileDimension>(
    src: &Source,
    m: &Mechanism<D>,
    tables: &[ScheduleToml],
) -> Result<Vec<Schedule>> {
    let mut out: Vec<Schedule> = Vec::new();
    for s in tables {
        let load = s.load.get_ref();
        let owner = format!("schedule {load:?}: ");
        let parameter = Parameter::parse(m, load).map_err(|e| match e {
            Error::InvalidParameter { reason, .. } => {
                src.error(&s.load.span(), format!("{owner}load {load:?} {reason}"))
            }
            other => src.placed(&owner, &s.load.span(), other),
        })?;
        if out.iter().any(|o| o.parameter == parameter) {
            return src.fail(&s.load.span(), format!("{owner}load {load:?} is scheduled twice"));
        }
        let waveform = match (&s.points, &s.harmonic) {
            (Some(points), None) => Waveform::Points(schedule_points(src, &owner, points, parameter.is_tension())?),
            (None, Some(h)) => schedule_harmonic(src, &owner, h, parameter.is_tension())?,
            (Some(_), Some(h)) => {
                return src.fail(&h.span(), format!("{owner}give points or harmonic, not both"));
            }
            (None, None) => {
                return src.fail(
                    &s.load.span(),
                    format!(
                        "{owner}give points = [[t, value], …] or harmonic = {{ amplitude, frequency, phase, offset }}"
                    ),
                );
            }
        };
        out.push(Schedule { load: load.clone(), parameter, waveform });
    }
    Ok(out)
}

/// A schedule's `points`: at least one, times not decreasing, at most two
/// at one time; a tension's values not negative.
pub(super) fn schedule_points(
    src: &Source,
    owner: &str,
    points: &Spanned<Vec<Spanned<[f64; 2]>>>,
    tension: bool,
) -> Result<Vec<[f64; 2]>> {
    let list = points.get_ref();
    if list.is_empty() {
        return src.fail(&points.span(), format!("{owner}points is empty: give at least one [t, value]"));
    }
    let sign = if tension { Sign::NotNegative } else { Sign::Any };
    for (k, p) in list.iter().enumerate() {
        let [t, v] = *p.get_ref();
        src.whole(owner, &format!("points[{k}]"), &p.span(), 2)?;
        src.numbers(owner, &format!("points[{k}] time"), &p.span(), &[t], Sign::Any)?;
        src.numbers(owner, &format!("points[{k}] value"), &p.span(), &[v], sign)?;
        let before = |j: usize| list[j].get_ref()[0];
        if k > 0 && t < before(k - 1) {
            return src.fail(
                &p.span(),
                format!(
                    "{owner}points[{k}] has time {} after points[{}] at {}: the times of points must not decrease (two points at one time make a step)",
                    number(t),
                    k - 1,
                    number(before(k - 1))
                ),
            );
        }
        if k > 1 && t == before(k - 1) && t == before(k - 2) {
            return src.fail(
                &p.span(),
                format!(
                    "{owner}points[{k}] is the third point at time {}: a step is two points at one time, the value before and the value after",
                    number(t)
                ),
            );
        }
    }
    Ok(list.iter().map(|p| *p.get_ref()).collect())
}

/// A schedule's `harmonic`: a finite amplitude and offset, a frequency
/// (Hz) greater than zero, a phase (rad); a tension's offset at least its
/// amplitude, so that it is never negative.
pub(super) fn schedule_harmonic(
    src: &Source,
    owner: &str,
    h: &Spanned<HarmonicToml>,
    tension: bool,
) -> Result<Waveform> {
    let t = h.get_ref();
    let amplitude = src.number(owner, "harmonic.amplitude", &t.amplitude, Sign::Any)?;
    let frequency = src.number(owner, "harmonic.frequency", &t.frequency, Sign::Positive)?;
    let phase = t.phase.as_ref().map_or(Ok(0.0), |p| src.number(owner, "harmonic.phase", p, Sign::Any))?;
    let offset = t.offset.as_ref().map_or(Ok(0.0), |o| src.number(owner, "harmonic.offset", o, Sign::Any))?;
    if tension && offset < amplitude.abs() {
        return src.fail(
            &h.span(),
            format!(
                "{owner}harmonic has offset {} below its amplitude {}: a tendon's tension cannot be negative",
                number(offset),
                number(amplitude.abs())
            ),
        );
    }
    Ok(Waveform::Harmonic { amplitude, frequency, phase, offset })
}

/// A joint and the coordinates (or rates) given it.
type Given = (usize, Vec<f64>);

/// `[initial]` or `[initial_velocity]` (`key`): joint name → its
/// coordinates, a number for a joint of one coordinate or an array of as
/// many numbers as the joint has coordinates, in the file's order; with
/// each entry's place ("line L, column C").
pub(super) fn initial_state<D: FileDimension>(
    src: &Source,
    m: &Mechanism<D>,
    key: &str,
    table: Option<&BTreeMap<String, Spanned<toml::Value>>>,
) -> Result<(Vec<Given>, Vec<String>)> {
    let (mut out, mut places) = (Vec::new(), Vec::new());
    // In the file's order (the table is read sorted by name).
    let mut entries: Vec<_> = table.into_iter().flatten().collect();
    entries.sort_by_key(|(_, value)| value.span().start);
    for (name, value) in entries {
        let span = value.span();
        let Some(j) = m.joints.iter().position(|j| &j.name == name) else {
            return src.fail(&span, format!("{key}: unknown joint {name:?}"));
        };
        let owner = format!("{key}: joint {name:?}: ");
        let number = |v: &toml::Value| match v {
            toml::Value::Float(x) => Some(*x),
            toml::Value::Integer(i) => Some(*i as f64),
            _ => None,
        };
        let values = match value.get_ref() {
            toml::Value::Array(items) => items.iter().map(number).collect::<Option<Vec<f64>>>(),
            v => number(v).map(|x| vec![x]),
        };
        let dof = m.joints[j].kind.joint().dof();
        let Some(values) = values else {
            return src.fail(&span, format!("{owner}must be a number or an array of {dof} numbers"));
        };
        if values.len() != dof {
            let (n, plural) = (values.len(), if dof == 1 { "" } else { "s" });
            let were = if n == 1 { "was" } else { "were" };
            return src.fail(&span, format!("{owner}the joint has {dof} coordinate{plural} and {n} {were} given"));
        }
        src.numbers(&owner, "coordinates", &span, &values, Sign::Any)?;
        // Bounded as every coordinate is (rad, m, and per second for rates).
        let bound = crate::flexure::MAX_COORDINATE;
        if let Some((i, x)) = values.iter().enumerate().find(|(_, x)| x.abs() > bound) {
            return src.fail(
                &span,
                format!("{owner}coordinates[{i}] = {}: must be at most {bound:e} in magnitude", self::number(*x)),
            );
        }
        out.push((j, values));
        places.push(super::place(src.text, span.start));
    }
    Ok((out, places))
}
