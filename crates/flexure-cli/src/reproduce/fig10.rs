//! Fig. 10 of the paper: the tendon's tension against the rotation of the steel
//! flexure, and its Euler load (Eq. 38).

use super::{Run, lib, svg};
use flexure::reference::euler;
use flexure::tendon::{TendonData, TendonOffsets, pull};
use flexure::{Flexure, TipConstraint, bending_stiffness};
use flexure_chart::{COLORS, Chart, Series};
use serde_json::{Value, json};
use std::f64::consts::FRAC_PI_2;
use std::fmt::Write as _;
use std::path::Path;

/// Fig. 10: tendon tension against rotation for the paper's steel flexure.
pub(super) fn fig10(out: &Path, md: &mut String) -> Run<Value> {
    let ei = bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).map_err(lib)?;
    let f = Flexure::new(0.015, ei, 3).map_err(lib)?;
    let t = TendonOffsets { root_offset: 0.005, tip_offset: 0.005 };
    let mut data = TendonData::new(&f);
    let mut rows = Vec::new();
    for i in 0..=40 {
        let tension = i as f64;
        pull(&f, &t, tension, &mut data).map_err(lib)?;
        rows.push((tension, data.alpha()[0].to_degrees()));
    }
    let (mut lo, mut hi) = (0.0, 40.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let mut d = TendonData::new(&f);
        pull(&f, &t, mid, &mut d).map_err(lib)?;
        if d.alpha()[0] < FRAC_PI_2 { lo = mid } else { hi = mid }
    }
    let tension90 = 0.5 * (lo + hi);
    let mut text = String::from("## Fig. 10: tendon-driven joint\n\n");
    let _ = write!(
        text,
        "Steel flexure 15 × 10 × 0.2 mm, E = 200 GPa, ν = 0.29, EI = {ei:.4e} N·m² (Eq. 25; the paper rounds to 1.46e-3), \
         tendon 5 mm from the neutral axis at both ends. Potential U + f·|Δx| (errata: the paper prints −). \
         90° needs **{tension90:.2} N**; the paper reads about 28 N off Fig. 10. \
         For scale, this flexure's Euler load is π²EI/4L² = {:.2} N (errata: 15.97, printed 15.76).\n\n",
        euler::buckling_load(TipConstraint::Free, 0.015, ei)
    );
    text += &svg(
        out,
        "fig10_tendon.svg",
        &Chart {
            title: "Fig. 10: joint rotation against tendon tension",
            x_label: "tendon tension f (N)",
            y_label: "rotation φ (degrees)",
            log_y: false,
            equal_aspect: false,
        },
        &[Series::line("Smooth Curvature, N = 3", rows.clone(), COLORS[0])],
    )?;
    md.push_str(&text);
    Ok(
        json!({ "ei": ei, "rows": rows.iter().map(|(f, a)| json!({ "tension": f, "rotation_degrees": a })).collect::<Vec<_>>(), "tension_at_90": tension90, "paper": { "tension_at_90": 28.0 } }),
    )
}
