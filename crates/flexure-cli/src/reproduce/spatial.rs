//! Beyond the paper: the spatial flexure's Bathe–Bolourchi bend,
//! lateral-torsional buckling beside Michell, and a picture of the bend.

use super::{Run, lib, svg};
use flexure::section::Profile;
use flexure_chart::{COLORS, Chart, Dash, Series};
use serde_json::{Value, json};
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

/// bend beside the published tips and the exact rod, lateral-torsional
/// buckling beside Michell, and a picture of the bend.
pub(super) fn spatial(out: &Path, md: &mut String) -> Run<Value> {
    use flexure::reference::rod::{self, Rod};
    use flexure::section::{Shear, SpatialSection};
    use flexure::spatial::{self as sp, SpatialFlexure, SpatialLoad, SpatialStatics};
    use nalgebra::Vector3;
    // Bathe–Bolourchi: R = 100, unit square (Saint-Venant's J), E = 1e7, ν = 0, 600 along z.
    let (r, l) = (100.0, PI * 100.0 / 4.0);
    let square = SpatialSection::rectangle(1e7, Shear::Poisson(0.0), Profile::Constant(1.0), Profile::Constant(1.0))
        .map_err(lib)?;
    let bend = Rod::new(l, square.clone()).map_err(lib)?.with_rest(move |_| [0.0, 0.0, 1.0 / r]).map_err(lib)?;
    let load = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 600.0] };
    let exact = rod::deflect(&bend, &load, &Default::default()).map_err(lib)?;
    let mut table = String::from("| orders | model tip (x, y, z) | off the rod (of L) |\n|---|---|---|\n");
    let mut rows = Vec::new();
    for n in [2, 3, 4, 6] {
        let mut rest = vec![0.0; 3 * n];
        rest[2 * n] = PI / 4.0;
        let f = SpatialFlexure::new(l, square.clone(), [n; 3]).map_err(lib)?.with_rest(&rest).map_err(lib)?;
        let mut data = SpatialStatics::new(&f);
        sp::deflect(&f, &load, &mut data, &Default::default()).map_err(lib)?;
        let (_, p) = sp::pose_root_tip(&f, data.alpha());
        let off = (p - exact.position).norm() / l;
        let _ = writeln!(table, "| {n} | ({:.3}, {:.3}, {:.3}) | {off:.1e} |", p.x, p.y, p.z);
        rows.push(json!({ "orders": n, "tip": [p.x, p.y, p.z], "error_over_length": off }));
    }
    let e = exact.position;
    let _ = writeln!(table, "| exact rod | ({:.3}, {:.3}, {:.3}) | |", e.x, e.y, e.z);
    table += "| Simo and Vu-Quoc, 32 elements | (46.90, 15.56, 53.60) | |\n| 8 elements | (47.23, 15.79, 53.37) | |\n";
    // Michell: a strip GJ = 1.3 EI_z, EI_y = 1e4 EI_z, an end force along z, past the load.
    let (gj, ei_z) = (1.3, 1.0);
    let michell = 4.0126 * f64::sqrt(gj * ei_z);
    let mut michell_rows = String::from("| orders | buckling load / Michell's |\n|---|---|\n");
    let mut ltb = Vec::new();
    for n in [3, 4, 6] {
        let strip = SpatialFlexure::new(1.0, SpatialSection::uniform(gj, 1e4 * ei_z, ei_z).map_err(lib)?, [n; 3])
            .map_err(lib)?;
        let mut data = SpatialStatics::new(&strip);
        let past = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 1.5 * michell] };
        let eq = sp::deflect(&strip, &past, &mut data, &Default::default()).map_err(lib)?;
        let factor = 1.5 * eq.limit.ok_or("the strip did not buckle past Michell's load")?;
        let _ = writeln!(michell_rows, "| {n} | {factor:.5} |");
        ltb.push(json!({ "orders": n, "factor": factor }));
    }
    // The picture: a cabinet projection (z up, y receding at 45° and half
    // scale), so the rest arc lies on the floor and the bend rises from it.
    let view = |p: &Vector3<f64>| {
        let d = 0.5 * std::f64::consts::FRAC_1_SQRT_2;
        (p.x + d * p.y, p.z + d * p.y)
    };
    let rest_arc: Vec<(f64, f64)> = (0..=40)
        .map(|k| {
            let a = PI / 4.0 * k as f64 / 40.0;
            view(&Vector3::new(r * a.sin(), r * (1.0 - a.cos()), 0.0))
        })
        .collect();
    let bent: Vec<(f64, f64)> = exact.shape.iter().map(|frame| view(&frame.position)).collect();
    let chart = Chart {
        title: "The Bathe–Bolourchi bend (cabinet view: y recedes at 45°, half scale)",
        x_label: "x + y/(2√2)",
        y_label: "z + y/(2√2)",
        log_y: false,
        equal_aspect: true,
    };
    let floor: Vec<(f64, f64)> = [(0.0, 0.0), (80.0, 0.0), (80.0, 40.0), (0.0, 40.0), (0.0, 0.0)]
        .iter()
        .map(|&(x, y)| view(&Vector3::new(x, y, 0.0)))
        .collect();
    let series = [
        Series::line("the x–y plane (z = 0)", floor, flexure_chart::GRAY).dashed(Dash::Dotted),
        Series::line("at rest: a 45° arc of radius 100 in the x–y plane", rest_arc, COLORS[1]).dashed(Dash::Dashed),
        Series::line("under 600 along z (the exact rod)", bent, COLORS[0]),
    ];
    let mut text = String::from("## Beyond the paper: spatial flexures\n\n");
    text += "The spatial flexure (`deflect --spatial`): three curvature components, twist and bending about y and z, \
             each a series of its own order, integrated in SE(3) by 6th-order Magnus steps, beside the exact \
             Kirchhoff rod (multiple shooting). The Bathe–Bolourchi 45° bend (R = 100, a unit square, E = 1e7, ν = 0, \
             Saint-Venant's torsion constant, 600 out of the plane):\n\n";
    text += &table;
    text += "\nLateral-torsional buckling of a narrow cantilever strip under an end force along its stiff direction \
             (GJ = 1.3 EI_z, EI_y = 1e4 EI_z), against Michell's P = 4.0126·√(EI_z·GJ)/L² (the last 1.2e-4 is \
             the finite EI_y's pre-buckling bending):\n\n";
    text += &michell_rows;
    text += "\n";
    text += &svg(out, "spatial_bend.svg", &chart, &series)?;
    md.push_str(&text);
    Ok(json!({ "bathe_bolourchi": { "model": rows, "rod": [e.x, e.y, e.z] }, "michell": ltb }))
}
