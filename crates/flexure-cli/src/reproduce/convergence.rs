//! Beyond the paper: how the buckling error and the energy error η fall with
//! the order N.

use super::{DASHES, FIG4_POSE, MARKERS, Run, lib, svg, unit};
use crate::analyses::exact_connection;
use flexure::connect::connect;
use flexure::reference::euler;
use flexure::{TipConstraint, buckling_load};
use flexure_chart::{COLORS, Chart, Series};
use serde_json::{Value, json};
use std::path::Path;

/// Beyond the paper: how the buckling error and η fall with the order N.
pub(super) fn convergence(out: &Path, md: &mut String) -> Run<Value> {
    let orders: Vec<usize> = (3..=12).collect();
    let mut series = Vec::new();
    let mut table = Vec::new();
    for (i, tip) in TipConstraint::ALL.into_iter().enumerate() {
        let e = euler::buckling_load(tip, 1.0, 1.0);
        let mut pts = Vec::new();
        for &n in &orders {
            let p = buckling_load(&unit(n)?, tip).map_err(lib)?.critical_load;
            pts.push((n as f64, p / e - 1.0));
        }
        table.push(json!({ "tip": tip.name(), "relative_error": pts.iter().map(|p| p.1).collect::<Vec<_>>() }));
        // Magnitudes: past N ≈ 8 the differences are rounding of either sign.
        let magnitudes = pts.iter().map(|p| (p.0, p.1.abs())).collect();
        series.push(Series::line(tip.name(), magnitudes, COLORS[i]).dashed(DASHES[i]).marked(MARKERS[i], 1, 0));
    }
    let exact = exact_connection(&unit(3)?, &FIG4_POSE).map_err(lib)?;
    let mut eta = Vec::new();
    for n in 3..=9 {
        eta.push((n as f64, connect(&unit(n)?, &FIG4_POSE).map_err(lib)?.energy / exact.energy - 1.0));
    }
    let mut text = String::from(
        "## Beyond the paper: convergence with the order N\n\n\
        With the default quadrature (N + 2 points) the straight flexure's load stiffness is integrated exactly, \
        so buckling is a Rayleigh–Ritz problem: loads fall monotonically onto Euler's from above. \
        The chart shows magnitudes: near 10⁻¹⁶ they are double-precision rounding, of either sign, \
        and a difference of exactly 0 has no place on a log axis.\n\n",
    );
    text += &svg(
        out,
        "convergence_buckling.svg",
        &Chart {
            title: "Buckling load error against order",
            x_label: "order N",
            y_label: "|P_model / P_Euler − 1|",
            log_y: true,
            equal_aspect: false,
        },
        &series,
    )?;
    text += &svg(
        out,
        "convergence_eta.svg",
        &Chart {
            title: "Energy error η at the Fig. 4 pose against order",
            x_label: "order N",
            y_label: "η = U/U* − 1",
            log_y: true,
            equal_aspect: false,
        },
        &[Series::dots("Smooth Curvature", eta.clone(), COLORS[0])],
    )?;
    md.push_str(&text);
    Ok(
        json!({ "orders": orders, "buckling": table, "eta": eta.iter().map(|e| json!({ "order": e.0, "eta": e.1 })).collect::<Vec<_>>() }),
    )
}
