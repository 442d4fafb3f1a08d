//! Figs. 12–13 of the paper: compliance ellipses, and the model's compliance
//! error against rest curvature (Eq. 37).

use super::{Run, lib, svg, unit};
use flexure::compliance_tip_rest;
use flexure::kinematics::backbone;
use flexure::reference::{self};
use flexure_chart::{COLORS, Chart, Dash, Series};
use serde_json::{Value, json};
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

/// Figs. 12–13: compliance ellipses and the model's compliance error against rest curvature.
pub(super) fn fig12_13(out: &Path, md: &mut String) -> Run<Value> {
    let arc = |c: f64| unit(3).and_then(|f| f.with_rest(&[c, 0.0, 0.0]).map_err(lib));
    let mut errors = Vec::new();
    for i in 0..=60 {
        let c = PI * i as f64 / 60.0;
        let f = arc(c)?;
        let e = (compliance_tip_rest(&f)
            - reference::compliance::compliance_tip(&f, &Default::default()).map_err(lib)?)
        .amax();
        errors.push((c, e));
    }
    let (at, max) = errors.iter().fold((0.0, 0.0), |m, &(c, e)| if e > m.1 { (c, e) } else { m });
    let eq37 = reference::compliance::compliance_tip(&arc(PI)?, &Default::default()).map_err(lib)?;
    let eq37_model = compliance_tip_rest(&arc(PI)?);
    // The paper's printed digits of Eq. 37 (0.3183 is not a stand-in for 1/π).
    #[allow(clippy::approx_constant)]
    let printed = [[1.0000, -0.3183, -0.2026], [-0.3183, 0.1520, 0.0645], [-0.2026, 0.0645, 0.0507]];
    let mut shapes = Vec::new();
    for (i, c) in [0.0, PI / 4.0, PI / 2.0, 3.0 * PI / 4.0, PI].into_iter().enumerate() {
        let f = arc(c)?;
        let b = backbone(&f, f.rest(), 61);
        let tip = b[b.len() - 1];
        let cm = compliance_tip_rest(&f);
        // Displacements under unit forces in every direction, scaled to read.
        let ellipse = (0..=72)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / 72.0;
                let (fx, fy) = (a.cos(), a.sin());
                let scale = 0.6;
                (
                    tip.x + scale * (cm[(1, 1)] * fx + cm[(1, 2)] * fy),
                    tip.y + scale * (cm[(2, 1)] * fx + cm[(2, 2)] * fy),
                )
            })
            .collect();
        let name = format!("ω₀ = {}", ["0", "π/4", "π/2", "3π/4", "π"][i]);
        shapes.push(Series::line(&name, b.iter().map(|p| (p.x, p.y)).collect(), COLORS[i]).width(2.5));
        shapes.push(Series::line("", ellipse, COLORS[i]).dashed(Dash::Dashed).width(1.5));
    }
    let mut text = String::from("## Figs. 12–13: small-load compliance against the compliance ODE\n\n");
    let _ = write!(
        text,
        "Constant rest curvature ω₀ from 0 to π; the exact compliance integrates Eq. 34 (Dormand–Prince, tolerance 1e-12). \
         Largest elementwise error **{max:.3e}** at ω₀ = {at:.4} (paper: 7.33e-4, at the largest curvature).\n\n\
         Eq. 37, the exact compliance at ω₀ = π, against the printed matrix:\n\n| | printed | ODE | model |\n|---|---|---|---|\n"
    );
    for i in 0..3 {
        for j in i..3 {
            let _ = writeln!(
                text,
                "| C[{i}{j}] | {:.4} | {:.6} | {:.6} |",
                printed[i][j],
                eq37[(i, j)],
                eq37_model[(i, j)]
            );
        }
    }
    text.push('\n');
    text += &svg(
        out,
        "fig12_ellipses.svg",
        &Chart {
            title: "Fig. 12: shapes and tip compliance ellipses (dashed; unit force, ×0.6)",
            x_label: "x (m)",
            y_label: "y (m)",
            log_y: false,
            equal_aspect: true,
        },
        &shapes,
    )?;
    text += &svg(
        out,
        "fig13_compliance_error.svg",
        &Chart {
            title: "Fig. 13: largest compliance error against rest curvature",
            x_label: "rest curvature ω₀ (1/m)",
            y_label: "max |C_model − C_exact|",
            log_y: false,
            equal_aspect: false,
        },
        &[Series::line("Smooth Curvature, N = 3", errors.clone(), COLORS[0])],
    )?;
    md.push_str(&text);
    let m3 =
        |m: &nalgebra::Matrix3<f64>| (0..3).map(|i| (0..3).map(|j| m[(i, j)]).collect::<Vec<_>>()).collect::<Vec<_>>();
    Ok(json!({
        "curvature": errors.iter().map(|e| e.0).collect::<Vec<_>>(),
        "error": errors.iter().map(|e| e.1).collect::<Vec<_>>(),
        "max_error": max, "max_error_at": at,
        "eq37_exact": m3(&eq37), "eq37_model": m3(&eq37_model),
        "paper": { "max_error": 7.33e-4, "eq37": printed },
    }))
}
