//! Beyond the paper: a tapered strip and a notch hinge, the model against the
//! exact references with EI(s).

use super::{DASHES, MARKERS, Run, lib, svg};
use flexure::reference::{self, elastica};
use flexure::section::{Notch, Profile};
use flexure::{Flexure, StaticsData, TipLoad, compliance_tip_rest, deflect};
use flexure_chart::{COLORS, Chart, Dash, Series};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// A steel strip 50 × 10 mm whose thickness tapers from 0.6 to 0.25 mm.
fn tapered_strip(order: usize) -> Run<Flexure> {
    let section = flexure::section::Section::rectangle(
        200e9,
        None,
        Profile::Constant(0.01),
        Profile::Linear { root: 6e-4, tip: 2.5e-4 },
    )
    .map_err(lib)?;
    Flexure::new(0.05, 1.0, order).and_then(|f| f.with_section(section)).map_err(lib)
}

/// The Paros–Weisbord hinge: aluminium (E = 70 GPa), 10 mm wide, two cut-outs
/// of radius R = 5 mm leaving h = 0.5 mm, through a blank 2R + h thick, L = 2R.
const HINGE: (f64, f64, f64, f64) = (70e9, 0.01, 0.005, 5e-4);

fn notch_hinge(order: usize) -> Run<Flexure> {
    let (e, b, r, h) = HINGE;
    let section = flexure::section::Section::rectangle(e, None, Profile::Constant(b), Profile::Constant(2.0 * r + h))
        .and_then(|s| s.with_notch(Notch { radius: r, min_thickness: h }))
        .map_err(lib)?;
    Flexure::new(2.0 * r, 1.0, order).and_then(|f| f.with_section(section)).map_err(lib)
}

/// Paros & Weisbord (1965): the circular hinge's rotation per moment,
/// Δφ/M = 3/(2EbR²)·1/(2β+β²)·[(3+4β+2β²)/((1+β)(2β+β²)) + 6(1+β)/(2β+β²)^{3/2}·atan√((2+β)/β)], β = h/(2R).
fn paros_weisbord() -> f64 {
    let (e, b, r, h) = HINGE;
    let beta = h / (2.0 * r);
    let q = 2.0 * beta + beta * beta;
    3.0 / (2.0 * e * b * r * r) / q
        * ((3.0 + 4.0 * beta + 2.0 * beta * beta) / ((1.0 + beta) * q)
            + 6.0 * (1.0 + beta) / q.powf(1.5) * ((2.0 + beta) / beta).sqrt().atan())
}

/// Beyond the paper: a tapered strip and a notch hinge, the model against the exact references with EI(s).
pub(super) fn sections(out: &Path, md: &mut String) -> Run<Value> {
    let orders: Vec<usize> = (2..=16).collect();
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for (i, (name, build)) in
        [("tapered strip", tapered_strip as fn(usize) -> Run<Flexure>), ("notch hinge", notch_hinge)]
            .into_iter()
            .enumerate()
    {
        let f = build(3)?;
        // A tip force across the flexure turning the tip by about 0.8 rad in linear theory.
        let c = reference::compliance::compliance_tip(&f, &Default::default()).map_err(lib)?;
        let load = TipLoad { moment: 0.0, fx: 0.0, fy: 0.8 / c[(0, 2)] };
        let exact = elastica::deflect(&f, &load, &Default::default()).map_err(lib)?.pose;
        let mut errors = Vec::new();
        for &n in &orders {
            let g = build(n)?;
            let mut data = StaticsData::new(&g);
            deflect(&g, &load, &mut data, &Default::default()).map_err(lib)?;
            let m = data.pose_root_tip();
            errors.push(((m.x - exact.x).hypot(m.y - exact.y) / g.length(), (m.phi - exact.phi).abs()));
        }
        series.push(
            Series::line(name, orders.iter().zip(&errors).map(|(&n, e)| (n as f64, e.0)).collect(), COLORS[i])
                .dashed(DASHES[i])
                .marked(MARKERS[i], 1, 0),
        );
        rows.push(json!({
            "flexure": name, "length": f.length(), "force": load.fy,
            "exact": { "phi": exact.phi, "x": exact.x, "y": exact.y },
            "orders": orders, "position_error_over_length": errors.iter().map(|e| e.0).collect::<Vec<_>>(),
            "angle_error": errors.iter().map(|e| e.1).collect::<Vec<_>>(),
        }));
    }
    let closed = paros_weisbord();
    let ode = reference::compliance::compliance_tip(&notch_hinge(3)?, &Default::default()).map_err(lib)?[(0, 0)];
    let hinge_orders = [4, 8, 16, 24, 32, 48, 64];
    let mut hinge = Vec::new();
    for n in hinge_orders {
        hinge.push((n, compliance_tip_rest(&notch_hinge(n)?)[(0, 0)]));
    }
    let (e, b, r, h) = HINGE;
    let mut text = String::from("## Beyond the paper: non-uniform sections\n\n");
    let _ = write!(
        text,
        "The paper leaves non-constant cross-sections to future work. Two flexures: a steel strip 50 × 10 mm \
         whose thickness tapers from 0.6 to 0.25 mm (EI falls 14-fold), and a circular notch hinge \
         (E = {:.0} GPa, b = {:.0} mm, R = {:.0} mm, h = {:.1} mm, L = 2R, EI falling {:.0}-fold to the middle). \
         The exact references integrate EI(s) along the flexure: the elastica by multiple shooting, the compliance by Eq. 34.\n\n\
         **The model's error against order** under a tip force across the flexure that would turn the tip by 0.8 rad \
         in linear theory, against the exact elastica. The taper's EI is smooth and the error falls by orders of magnitude \
         with every few coefficients; the notch concentrates the bending near its middle, which a polynomial \
         curvature resolves only slowly.\n\n| N | taper: position error / L | notch: position error / L |\n|---|---|---|\n",
        e / 1e9,
        b * 1e3,
        r * 1e3,
        h * 1e3,
        (1.0 + 2.0 * r / h).powi(3)
    );
    let column = |k: usize, i: usize| rows[k]["position_error_over_length"][i].as_f64().unwrap_or(f64::NAN);
    for (i, n) in orders.iter().enumerate() {
        let _ = writeln!(text, "| {n} | {:.2e} | {:.2e} |", column(0, i), column(1, i));
    }
    text.push('\n');
    text += &svg(
        out,
        "sections_order.svg",
        &Chart {
            title: "Tip position error against order, non-uniform sections",
            x_label: "order N",
            y_label: "|p_model − p_exact| / L",
            log_y: true,
            equal_aspect: false,
        },
        &series,
    )?;
    let _ = write!(
        text,
        "**The notch hinge's rotational compliance** Δφ/M beside the Paros–Weisbord closed form \
         (Paros & Weisbord 1965, \"How to design flexure hinges\", Machine Design 37), which is the exact ∫ds/EI: \
         **{closed:.6e}** rad/(N·m). The compliance ODE gives {ode:.6e} (relative difference {:.1e}). \
         The model's C_φφ is a Ritz value, from below:\n\n| N | model C_φφ | relative error |\n|---|---|---|\n",
        ode / closed - 1.0
    );
    for (n, c) in &hinge {
        let _ = writeln!(text, "| {n} | {c:.6e} | {:.2e} |", c / closed - 1.0);
    }
    text.push('\n');
    text += &svg(
        out,
        "sections_notch.svg",
        &Chart {
            title: "Notch hinge compliance against Paros–Weisbord",
            x_label: "order N",
            y_label: "|C_φφ / C_Paros–Weisbord − 1|",
            log_y: true,
            equal_aspect: false,
        },
        &[
            Series::line(
                "Smooth Curvature",
                hinge.iter().map(|(n, c)| (*n as f64, (c / closed - 1.0).abs())).collect(),
                COLORS[0],
            )
            .marked(MARKERS[0], 1, 0),
            Series::line(
                "compliance ODE (Eq. 34)",
                vec![(4.0, (ode / closed - 1.0).abs().max(1e-16)), (64.0, (ode / closed - 1.0).abs().max(1e-16))],
                COLORS[1],
            )
            .dashed(Dash::Dashed),
        ],
    )?;
    md.push_str(&text);
    Ok(json!({
        "order_error": rows,
        "notch": {
            "modulus": e, "width": b, "radius": r, "min_thickness": h, "length": 2.0 * r,
            "paros_weisbord": closed, "ode": ode, "ode_relative_error": ode / closed - 1.0,
            "model": hinge.iter().map(|(n, c)| json!({ "order": n, "compliance": c, "relative_error": c / closed - 1.0 })).collect::<Vec<_>>(),
        },
    }))
}
