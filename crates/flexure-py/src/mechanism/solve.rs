//! `Mechanism.solve`'s report: the equilibrium shaped like `flexure solve
//! --json`, each flexure joint's estimated error, stress, safety factor and
//! shape, and the findings and warnings about it.

use crate::error_estimate::{estimate_dict, interrupted_or};
use crate::errors::StabilityWarning;
use crate::findings;
use crate::interrupt::interruptible;
use crate::stress::{self, peak_item};
use crate::strict;
use crate::warnings::{warn, warn_inaccurate, warn_unestimated};
use flexure::estimate::{self, Accuracy};
use flexure::mechanism::file::Report;
use flexure::mechanism::statics::{Settings as MechanismSettings, body_frames, solve as equilibrium};
use flexure::mechanism::{JointKind, Mechanism};
use numpy::IntoPyArray;
use numpy::ndarray::Array1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The equilibrium of `m` as `Mechanism.solve` documents it; `reports` holds
/// each flexure joint's `yield_strength` and `shape`, by name.
pub fn solve<'py>(
    py: Python<'py>,
    m: &Mechanism,
    reports: &[(String, Report)],
    target: &Accuracy,
) -> PyResult<Bound<'py, PyDict>> {
    let (s, estimated, open) = interruptible(py, || {
        let open = flexure::mechanism::findings::open_closures(m, &MechanismSettings::default())?;
        let s = equilibrium(m, &MechanismSettings::default())?;
        // Each flexure joint carries only the load at its tip: its error is that of a deflect.
        let mut estimated = Vec::new();
        for j in &m.joints {
            if let JointKind::Flexure(f) = &j.kind {
                let alpha = &s.q[j.offset..j.offset + f.order()];
                estimated.push((j, f.as_ref(), interrupted_or(estimate::joint_error(f, alpha, target))?));
            }
        }
        Ok((s, estimated, open))
    })?;
    let frames = body_frames(m, &s);
    let bodies = PyDict::new(py);
    for (b, f) in m.bodies.iter().zip(&frames.bodies) {
        let d = PyDict::new(py);
        d.set_item("x", f.x)?;
        d.set_item("y", f.y)?;
        d.set_item("phi", f.phi)?;
        bodies.set_item(&b.name, d)?;
    }
    let coordinates = PyDict::new(py);
    for j in &m.joints {
        let q = Array1::from_vec(s.q[j.offset..j.offset + j.kind.joint().dof()].to_vec());
        coordinates.set_item(&j.name, q.into_pyarray(py))?;
    }
    // `error_estimate` {flexure joint: estimate, or None where it could not be made}, and
    // `flagged`, which an unknown accuracy sets too.
    let estimates = PyDict::new(py);
    let mut flagged = false;
    // Stack level 2: the line calling `flexure.Mechanism.solve`, past its Python wrapper.
    for (j, f, e) in &estimated {
        let what = format!("Mechanism.solve, flexure joint '{}'", j.name);
        match e {
            Ok(e) => {
                if e.flagged {
                    let hint = "raise the joint's order (and quadrature) in the mechanism file";
                    warn_inaccurate(py, &what, f, e, target, hint, 2)?;
                }
                estimates.set_item(&j.name, estimate_dict(py, e)?)?;
                flagged |= e.flagged;
            }
            Err(why) => {
                flagged = true;
                warn_unestimated(py, &what, why, 2)?;
                estimates.set_item(&j.name, py.None())?;
            }
        }
    }
    let keys = ["stress", "curvature_max", "safety_factor", "shape"];
    let maps = keys.map(|_| PyDict::new(py));
    for j in &m.joints {
        let JointKind::Flexure(f) = &j.kind else { continue };
        let q = &s.q[j.offset..j.offset + f.order()];
        let report = reports.iter().find(|r| r.0 == j.name).map_or_else(Report::default, |r| r.1);
        let (key, peak) = peak_item(py, f, q)?;
        maps[if key == "stress" { 0 } else { 1 }].set_item(&j.name, peak)?;
        if let Some(strength) = report.yield_strength {
            let what = format!("Mechanism.solve, flexure joint '{}'", j.name);
            if let Some((_, factor)) = stress::safety_factor(py, f, q, strength, &what, 2)? {
                maps[2].set_item(&j.name, factor)?;
            }
        }
        if let Some(k) = report.shape {
            maps[3].set_item(&j.name, stress::shape(py, f, q, k)?)?;
        }
    }
    let out = PyDict::new(py);
    out.set_item("bodies", bodies)?;
    out.set_item("coordinates", coordinates)?;
    out.set_item("energy", s.energy)?;
    out.set_item("stable", s.stable)?;
    out.set_item("error_estimate", estimates)?;
    out.set_item("flagged", flagged)?;
    for (key, map) in keys.into_iter().zip(maps) {
        if !map.is_empty() {
            out.set_item(key, map)?;
        }
    }
    let crossings = flexure::mechanism::findings::crossings(m, &s.q).into_iter().map(|c| (None, c)).collect::<Vec<_>>();
    let listed = findings::report(py, "Mechanism.solve", &open, &crossings, 2)?;
    if !listed.is_empty() {
        out.set_item("findings", listed)?;
    }
    if let Some(limit) = s.limit {
        // A snap-through: the stable answer beyond a limit load, which the caller must know of.
        out.set_item("limit_fraction", limit)?;
        let text = format!(
            "Mechanism.solve: the loading path lost stability at {:.4} % of the load and snapped through to this stable equilibrium",
            100.0 * limit
        );
        warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
    }
    if !s.stable {
        let text = "Mechanism.solve: the equilibrium is unstable (`stable` is False): its constrained stiffness is not positive definite, so a small disturbance moves it away".to_string();
        warn(py, &py.get_type::<StabilityWarning>(), text, 2)?;
    }
    strict::finite_answer("Mechanism.solve", out.as_any())?;
    Ok(out)
}
