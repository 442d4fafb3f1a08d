//! Beyond the paper: the pseudo-rigid-body chains that `flexure
//! export` fits, against the model and the exact elastica.

use super::{DASHES, MARKERS, Run, lib, svg, unit};
use flexure::reference::elastica;
use flexure::{StaticsData, TipLoad, deflect};
use flexure_chart::{COLORS, Chart, Series};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// The pseudo-rigid-body chains that `flexure export` fits, their
/// tip errors against the model along a growing end force, beside the
/// model's own error against the exact elastica.
pub(super) fn prb_fits(out: &Path, md: &mut String) -> Run<Value> {
    use flexure::prb::{self, PrbKind};
    let f = unit(3)?;
    // A vertical end force PL²/EI = 0.5 … 6 across the unit strip (tip angles to about 70°).
    let loads: Vec<TipLoad> = (1..=12).map(|k| TipLoad { moment: 0.0, fx: 0.0, fy: 0.5 * k as f64 }).collect();
    let mut data = StaticsData::new(&f);
    let (mut model, mut exact_phi) = (Vec::new(), Vec::new());
    let (mut scm_pos, mut scm_ang) = (Vec::new(), Vec::new());
    for load in &loads {
        deflect(&f, load, &mut data, &Default::default()).map_err(lib)?;
        let m = data.pose_root_tip();
        let e = elastica::deflect(&f, load, &Default::default()).map_err(lib)?.pose;
        let phi = e.phi.to_degrees();
        exact_phi.push(phi);
        scm_pos.push((phi, 100.0 * (m.x - e.x).hypot(m.y - e.y)));
        scm_ang.push((phi, (m.phi - e.phi).abs().to_degrees()));
        model.push(m);
    }
    let mut pos_series = vec![
        Series::line("Smooth Curvature (N = 3) against the exact elastica", scm_pos.clone(), COLORS[0])
            .marked(MARKERS[0], 1, 0),
    ];
    let mut ang_series = vec![
        Series::line("Smooth Curvature (N = 3) against the exact elastica", scm_ang.clone(), COLORS[0])
            .marked(MARKERS[0], 1, 0),
    ];
    let mut table =
        String::from("| chain | γ | K_Θ | largest position error / L | largest angle error |\n|---|---|---|---|---|\n");
    let mut fits = serde_json::Map::new();
    for (i, kind) in [PrbKind::OneR, PrbKind::ThreeR].into_iter().enumerate() {
        let fit = prb::fit(&f, &loads, kind).map_err(lib)?;
        let (mut pos, mut ang) = (Vec::new(), Vec::new());
        for ((load, m), phi) in loads.iter().zip(&model).zip(&exact_phi) {
            let theta = prb::equilibrium(&fit, &f, load).map_err(lib)?;
            let g = prb::tip_pose(&fit, &f, &theta);
            // Against the model, as the fit's error is reported (floored for the log axis).
            pos.push((*phi, (100.0 * (g.x - m.x).hypot(g.y - m.y)).max(1e-12)));
            ang.push((*phi, (g.phi - m.phi).abs().to_degrees().max(1e-12)));
        }
        let label = format!("{kind} chain against the Smooth Curvature Model");
        pos_series.push(Series::line(&label, pos, COLORS[i + 1]).dashed(DASHES[i + 1]).marked(MARKERS[i + 1], 1, 0));
        ang_series.push(Series::line(&label, ang, COLORS[i + 1]).dashed(DASHES[i + 1]).marked(MARKERS[i + 1], 1, 0));
        let list = |v: &[f64]| v.iter().map(|x| format!("{x:.4}")).collect::<Vec<_>>().join(", ");
        let _ = writeln!(
            table,
            "| {kind} | {} | {} | {:.2e} | {:.3}° |",
            list(&fit.gamma),
            list(&fit.k_theta),
            fit.error.position,
            fit.error.angle.to_degrees()
        );
        fits.insert(
            kind.to_string(),
            json!({ "gamma": fit.gamma, "k_theta": fit.k_theta, "error": fit.error, "flagged": fit.flagged }),
        );
    }
    let scm_max = scm_pos.iter().map(|p| p.1 / 100.0).fold(0.0, f64::max);
    let mut text = String::from("## Pseudo-rigid-body chains\n\n");
    text += "The chains `flexure export` puts in place of a flexure, fitted here to the unit strip under a vertical \
             end force PL²/EI = 0.5 to 6, and their tip errors at their own equilibria against the Smooth Curvature \
             Model, beside that model's own error against the exact elastica (Howell's tabulated 1R chain for \
             an end force: γ ≈ 0.85, K_Θ ≈ 2.65). A 1R chain's tip turns by its one hinge's angle, while the strip's turns by about 1.24 \
             times it, hence its angle error.\n\n";
    text += &table;
    let _ = write!(text, "\nThe model's own largest position error: {scm_max:.2e} L.\n\n");
    let chart = |title, y_label| Chart {
        title,
        x_label: "exact tip angle (degrees)",
        y_label,
        log_y: true,
        equal_aspect: false,
    };
    text += &svg(
        out,
        "prb_position.svg",
        &chart("PRB chains: tip position error", "position error (% of L)"),
        &pos_series,
    )?;
    text += &svg(out, "prb_angle.svg", &chart("PRB chains: tip angle error", "angle error (degrees)"), &ang_series)?;
    md.push_str(&text);
    Ok(json!({ "fits": fits, "scm_max_position_error": scm_max }))
}
