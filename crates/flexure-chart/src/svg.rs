//! The SVG text of a laid-out figure, and of figures stacked in one file.

use crate::axis::{Axis, linear_axis};
use crate::color::{Color, ramp};
use crate::figure::{Anchor, ColorBar, Entry, Figure, Mark, Marker, Place, Stroke, Swatch};
use crate::layout::{
    BAR_BLOCK, BAR_HEIGHT, LEGEND_FOOT, LEGEND_ROW, Layout, SWATCH, drawn_pixels, fit_height, head, layout,
    legend_column, mark_points, text_width,
};
use crate::{LABEL_SIZE, LEGEND_SIZE, NOTE_SIZE, TICK_SIZE, TITLE_SIZE};
use std::fmt::Write as _;
use std::path::Path;

/// Writes `figs` one above the other as one SVG to `path`, each at its own
/// size (the widest sets the width); an error names the path, and nothing
/// is written if any figure cannot be drawn.
pub fn write_stack(path: &Path, figs: &[Figure]) -> Result<(), String> {
    let svg = stack(figs).map_err(|e| format!("drawing {}: {e}; nothing was written", path.display()))?;
    std::fs::write(path, svg).map_err(|e| format!("writing {}: {e}", path.display()))
}

/// `figs` one above the other in one SVG: each rendered figure nested as
/// an `<svg>` at its offset, its clip path renamed so that each keeps its own.
pub fn stack(figs: &[Figure]) -> Result<String, String> {
    let (mut width, mut height) = (0.0_f64, 0.0_f64);
    let mut body = String::new();
    for (k, fig) in figs.iter().enumerate() {
        let svg = render(fig)?;
        // The size render settled on (fit_height may lower the height).
        let attribute = |name: &str| -> f64 {
            let head = svg.lines().next().unwrap_or_default();
            head.split(&format!(" {name}=\""))
                .nth(1)
                .and_then(|r| r.split('"').next())
                .and_then(|v| v.parse().ok())
                .unwrap_or(0.0)
        };
        let (w, h) = (attribute("width"), attribute("height"));
        let nested = svg
            .replacen("<svg ", &format!(r#"<svg x="0" y="{}" "#, num(height)), 1)
            .replace(r#"id="plot""#, &format!(r#"id="plot-{k}""#))
            .replace("url(#plot)", &format!("url(#plot-{k})"));
        body.push_str(&nested);
        width = width.max(w);
        height += h;
    }
    let (w, h) = (num(width), num(height));
    Ok(format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n<rect width=\"{w}\" height=\"{h}\" fill=\"#ffffff\"/>\n{body}</svg>\n"
    ))
}

/// Writes `fig` as SVG to `path`; an error names the path, and a mark with
/// a non-finite position is refused before anything is written.
pub fn write(path: &Path, fig: &Figure) -> Result<(), String> {
    let svg = render(fig).map_err(|e| format!("drawing {}: {e}; nothing was written", path.display()))?;
    std::fs::write(path, svg).map_err(|e| format!("writing {}: {e}", path.display()))
}

/// XML text.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

pub(crate) fn num(x: f64) -> String {
    format!("{x:.2}")
}

pub(crate) fn points_attr(pts: &[(f64, f64)]) -> String {
    pts.iter().map(|p| format!("{},{}", num(p.0), num(p.1))).collect::<Vec<_>>().join(" ")
}

pub(crate) fn stroke_attrs(s: &Stroke) -> String {
    let dash = s.dash.array(s.width).map_or(String::new(), |d| format!(r#" stroke-dasharray="{d}""#));
    format!(
        r#"stroke="{}" stroke-width="{}" stroke-linejoin="round" stroke-linecap="round"{dash}"#,
        s.color.hex(),
        num(s.width)
    )
}

pub(crate) fn text(svg: &mut String, (x, y): (f64, f64), size: f64, anchor: Anchor, extra: &str, body: &str) {
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{}" font-size="{size}" text-anchor="{}"{extra}>{}</text>"#,
        num(x),
        num(y),
        anchor.svg(),
        escape(body)
    );
}

pub(crate) fn marker(svg: &mut String, (x, y): (f64, f64), shape: Marker, r: f64, color: Color, filled: bool) {
    let fill = if filled { color.hex() } else { "#ffffff".into() };
    let paint = format!(r#"fill="{fill}" stroke="{}" stroke-width="1.5""#, color.hex());
    let _ = match shape {
        Marker::Circle => writeln!(svg, r#"<circle cx="{}" cy="{}" r="{}" {paint}/>"#, num(x), num(y), num(r)),
        Marker::Square => {
            let a = 0.9 * r;
            writeln!(
                svg,
                r#"<rect x="{}" y="{}" width="{}" height="{}" {paint}/>"#,
                num(x - a),
                num(y - a),
                num(2.0 * a),
                num(2.0 * a)
            )
        }
        Marker::Triangle => {
            let pts = [(x, y - 1.2 * r), (x + 1.1 * r, y + 0.8 * r), (x - 1.1 * r, y + 0.8 * r)];
            writeln!(svg, r#"<polygon points="{}" {paint}/>"#, points_attr(&pts))
        }
        Marker::Diamond => {
            let a = 1.25 * r;
            let pts = [(x, y - a), (x + a, y), (x, y + a), (x - a, y)];
            writeln!(svg, r#"<polygon points="{}" {paint}/>"#, points_attr(&pts))
        }
    };
}

/// An arrow in px with its head at `to`.
pub(crate) fn arrow(svg: &mut String, from: (f64, f64), to: (f64, f64), color: Color, width: f64) {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = dx.hypot(dy);
    if len < 1e-9 {
        return;
    }
    let (ux, uy) = (dx / len, dy / len);
    let head = head(width).min(len);
    let base = (to.0 - head * ux, to.1 - head * uy);
    let half = 0.45 * head;
    let _ = writeln!(
        svg,
        r#"<line x1="{}" y1="{}" x2="{}" y2="{}" {}/>"#,
        num(from.0),
        num(from.1),
        num(base.0),
        num(base.1),
        stroke_attrs(&Stroke::solid(color, width))
    );
    let pts = [to, (base.0 - half * uy, base.1 + half * ux), (base.0 + half * uy, base.1 - half * ux)];
    let _ = writeln!(svg, r#"<polygon points="{}" fill="{}"/>"#, points_attr(&pts), color.hex());
}

/// Three quarters of a circle around `c` (px), opening to the lower right,
/// with the head at the end of the turn.
pub(crate) fn turn(svg: &mut String, c: (f64, f64), r: f64, ccw: bool, color: Color, width: f64) {
    // Angles measured counter-clockwise on the page (y up).
    let (a0, a1) = if ccw {
        (-0.25 * std::f64::consts::PI, 1.25 * std::f64::consts::PI)
    } else {
        (1.25 * std::f64::consts::PI, -0.25 * std::f64::consts::PI)
    };
    let at = |a: f64| (c.0 + r * a.cos(), c.1 - r * a.sin());
    let head = head(width).min(0.9 * r);
    // Stop the arc where the head begins.
    let stop = a1 - (a1 - a0).signum() * head / r;
    let pts: Vec<(f64, f64)> = (0..=40).map(|i| at(a0 + (stop - a0) * f64::from(i) / 40.0)).collect();
    let _ = writeln!(
        svg,
        r#"<polyline points="{}" fill="none" {}/>"#,
        points_attr(&pts),
        stroke_attrs(&Stroke::solid(color, width))
    );
    let from = at(stop);
    let to = at(a1);
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = dx.hypot(dy).max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let half = 0.45 * head;
    let pts = [to, (from.0 - half * uy, from.1 + half * ux), (from.0 + half * uy, from.1 - half * ux)];
    let _ = writeln!(svg, r#"<polygon points="{}" fill="{}"/>"#, points_attr(&pts), color.hex());
}

/// The largest figure side (px).
const MAX_SIZE: f64 = 10_000.0;

/// Every position finite, or the first that is not.
pub(crate) fn check_finite(fig: &Figure) -> Result<(), String> {
    for (i, mark) in fig.marks.iter().enumerate() {
        if let Some(p) = mark_points(mark).into_iter().find(|p| !(p.0.is_finite() && p.1.is_finite())) {
            return Err(format!("mark {i} has the point ({}, {}), not finite", p.0, p.1));
        }
    }
    if !(fig.width >= 200.0 && fig.height >= 200.0 && fig.width <= MAX_SIZE && fig.height <= MAX_SIZE) {
        return Err(format!("the figure size {} × {} px is outside 200…10000", fig.width, fig.height));
    }
    Ok(())
}

/// The figure as SVG text.
pub fn render(fig: &Figure) -> Result<String, String> {
    check_finite(fig)?;
    let fitted;
    let fig = if fig.equal_aspect && fig.fit_height && !fig.log_y {
        fitted = fit_height(fig);
        &fitted
    } else {
        fig
    };
    let mut l = layout(fig, if fig.place == Place::Outside { Place::Right } else { fig.place });
    // A legend that would hide data, or is larger than the plot, moves out beside it.
    if fig.place == Place::Inside
        && let Some((x, y, w, h)) = l.legend
    {
        let pts = drawn_pixels(fig, &l);
        let hides = pts.iter().any(|p| p.0 >= x - 6.0 && p.0 <= x + w + 6.0 && p.1 >= y - 6.0 && p.1 <= y + h + 6.0);
        if hides || w + 20.0 > l.w || h + 20.0 > l.h {
            l = layout(fig, Place::Right);
        }
    }
    // A legend beside the plot that its columns cannot fit into the height
    // grows the figure (and the plot with it) to hold every entry.
    let grown;
    let fig = match l.legend {
        Some((x, y, _, h)) if x >= l.left + l.w && y + h + LEGEND_FOOT > fig.height => {
            grown = Figure { height: (y + h + LEGEND_FOOT).ceil().min(MAX_SIZE), ..fig.clone() };
            l = layout(&grown, Place::Right);
            &grown
        }
        _ => fig,
    };
    let (w, h) = (fig.width, fig.height);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Helvetica, Arial, sans-serif">"#
    );
    let _ = writeln!(svg, r##"<rect width="{w}" height="{h}" fill="#ffffff"/>"##);
    if !fig.title.is_empty() {
        text(&mut svg, (w / 2.0, 34.0), TITLE_SIZE, Anchor::Middle, r#" class="title""#, &fig.title);
    }
    let (left, top, pw, ph) = (l.left, l.top, l.w, l.h);
    let (bottom, right) = (top + ph, left + pw);
    let xpx = |v: f64| left + (v - l.x.lo) / (l.x.hi - l.x.lo) * pw;
    let ypx = |v: f64| bottom - (v - l.y.lo) / (l.y.hi - l.y.lo) * ph;
    // Grid, then the frame.
    for &m in &l.y.minor {
        let y = ypx(m);
        line(&mut svg, [left, y, right, y], "#f0f0f0", "1");
    }
    for t in &l.x.ticks {
        let x = xpx(t.at);
        line(&mut svg, [x, top, x, bottom], "#dddddd", "1");
    }
    for t in &l.y.ticks {
        let y = ypx(t.at);
        line(&mut svg, [left, y, right, y], "#dddddd", "1");
    }
    let _ = writeln!(
        svg,
        r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#333333" stroke-width="1.2"/>"##,
        num(left),
        num(top),
        num(pw),
        num(ph)
    );
    for t in &l.x.ticks {
        let x = xpx(t.at);
        line(&mut svg, [x, bottom, x, bottom + 6.0], "#333333", "1.2");
        text(&mut svg, (x, bottom + 8.0 + TICK_SIZE), TICK_SIZE, Anchor::Middle, r#" class="tick-x""#, &t.label);
    }
    for &m in &l.y.minor {
        let y = ypx(m);
        line(&mut svg, [left - 3.0, y, left, y], "#333333", "1");
    }
    for t in &l.y.ticks {
        let y = ypx(t.at);
        line(&mut svg, [left - 6.0, y, left, y], "#333333", "1.2");
        text(&mut svg, (left - 10.0, y + 0.36 * TICK_SIZE), TICK_SIZE, Anchor::End, r#" class="tick-y""#, &t.label);
    }
    let with_factor = |label: &str, axis: &Axis| match &axis.factor {
        Some(f) => format!("{label}  ({f})"),
        None => label.to_string(),
    };
    text(
        &mut svg,
        (left + pw / 2.0, bottom + 8.0 + TICK_SIZE + 16.0 + LABEL_SIZE),
        LABEL_SIZE,
        Anchor::Middle,
        r#" class="axis-x""#,
        &with_factor(&fig.x_label, &l.x),
    );
    let ylx = 16.0 + LABEL_SIZE * 0.8;
    let yly = top + ph / 2.0;
    text(
        &mut svg,
        (ylx, yly),
        LABEL_SIZE,
        Anchor::Middle,
        &format!(r#" class="axis-y" transform="rotate(-90 {} {})""#, num(ylx), num(yly)),
        &with_factor(&fig.y_label, &l.y),
    );
    // Data, clipped to the plot.
    let _ = writeln!(
        svg,
        r#"<clipPath id="plot"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>"#,
        num(left),
        num(top),
        num(pw),
        num(ph)
    );
    let _ = writeln!(svg, r#"<g clip-path="url(#plot)">"#);
    for mark in &fig.marks {
        draw_mark(&mut svg, mark, &l, fig.log_y);
    }
    let _ = writeln!(svg, "</g>");
    if let Some(b) = l.legend {
        draw_legend(&mut svg, &fig.legend, b, l.rows);
        if let Some(bar) = &fig.color_bar {
            draw_color_bar(&mut svg, bar, (b.0, b.1 + b.3 - BAR_BLOCK, b.2));
        }
    }
    let _ = writeln!(svg, "</svg>");
    Ok(svg)
}

pub(crate) fn draw_mark(svg: &mut String, mark: &Mark, l: &Layout, log_y: bool) {
    let px = |p: (f64, f64)| l.px(p, log_y);
    match mark {
        Mark::Path { points, stroke, fill, closed } => {
            // On a log axis a non-positive value breaks the line.
            let runs: Vec<Vec<(f64, f64)>> = if log_y {
                points
                    .split(|p| p.1 <= 0.0)
                    .filter(|r| !r.is_empty())
                    .map(|r| r.iter().map(|&p| px(p)).collect())
                    .collect()
            } else {
                vec![points.iter().map(|&p| px(p)).collect()]
            };
            let paint_fill =
                fill.map_or("none".to_string(), |f| format!(r#"{}" fill-opacity="{}"#, f.color.hex(), f.opacity));
            let paint_stroke = stroke.as_ref().map_or(r#"stroke="none""#.to_string(), stroke_attrs);
            for run in runs {
                let tag = if *closed { "polygon" } else { "polyline" };
                let _ = writeln!(svg, r#"<{tag} points="{}" fill="{paint_fill}" {paint_stroke}/>"#, points_attr(&run));
            }
        }
        Mark::Dot { at, shape, radius, color, filled } => {
            if !log_y || at.1 > 0.0 {
                marker(svg, px(*at), *shape, *radius, *color, *filled);
            }
        }
        Mark::Arrow { from, to, color, width } => arrow(svg, px(*from), px(*to), *color, *width),
        Mark::Turn { at, radius, ccw, color, width } => turn(svg, px(*at), *radius, *ccw, *color, *width),
        Mark::Label { at, offset, text: body, color, anchor } => {
            let p = px(*at);
            let halo = format!(
                r##" class="label" fill="{}" stroke="#ffffff" stroke-width="4" stroke-linejoin="round" paint-order="stroke""##,
                color.hex()
            );
            text(svg, (p.0 + offset.0, p.1 + offset.1), LEGEND_SIZE, *anchor, &halo, body);
        }
    }
}

pub(crate) fn draw_legend(svg: &mut String, entries: &[Entry], (x, y, w, h): (f64, f64, f64, f64), rows: usize) {
    let _ = writeln!(
        svg,
        r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff" fill-opacity="0.92" stroke="#888888" stroke-width="1"/>"##,
        num(x),
        num(y),
        num(w),
        num(h)
    );
    let column = legend_column(entries) + 24.0;
    for (i, e) in entries.iter().enumerate() {
        let (col, row) = (i / rows.max(1), i % rows.max(1));
        let cy = y + 7.0 + LEGEND_ROW * (row as f64 + 0.5);
        let x = x + col as f64 * column;
        let (sx0, sx1) = (x + 12.0, x + 12.0 + SWATCH);
        match &e.swatch {
            Swatch::Line(stroke, dot) => {
                if let Some(s) = stroke {
                    let _ = writeln!(
                        svg,
                        r#"<line x1="{}" y1="{}" x2="{}" y2="{}" {}/>"#,
                        num(sx0),
                        num(cy),
                        num(sx1),
                        num(cy),
                        stroke_attrs(s)
                    );
                }
                if let Some((m, c, filled)) = dot {
                    marker(svg, ((sx0 + sx1) / 2.0, cy), *m, 5.0, *c, *filled);
                }
            }
            Swatch::Area(fill, stroke) => {
                let _ = writeln!(
                    svg,
                    r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{}" fill-opacity="{}" {}/>"#,
                    num(sx0),
                    num(cy - 7.0),
                    num(SWATCH),
                    num(14.0),
                    fill.color.hex(),
                    fill.opacity,
                    stroke_attrs(stroke)
                );
            }
            Swatch::Arrow(c) => arrow(svg, (sx0, cy), (sx1, cy), *c, 2.0),
            Swatch::Turn(c) => turn(svg, ((sx0 + sx1) / 2.0, cy), 8.0, true, *c, 1.5),
            Swatch::Note => {}
        }
        let (tx, size) = if e.swatch == Swatch::Note { (x + 12.0, NOTE_SIZE) } else { (sx1 + 8.0, LEGEND_SIZE) };
        text(svg, (tx, cy + 0.36 * size), size, Anchor::Start, r#" class="legend""#, &e.label);
    }
}

/// A colour bar in the block at `(x, y)` (px, top left) `w` wide: its
/// label, the ramp as a gradient, and ticks at round values under it.
pub(crate) fn draw_color_bar(svg: &mut String, bar: &ColorBar, (x, y, w): (f64, f64, f64)) {
    let (x0, x1) = (x + 12.0, x + w - 24.0);
    // A label longer than the bar is set smaller, so that it stays inside
    // the legend's block (and the figure) rather than run past it.
    let size = LEGEND_SIZE * ((x1 - x0) / text_width(&bar.label, LEGEND_SIZE)).min(1.0);
    text(svg, (x0, y + 0.5 * LEGEND_ROW + 0.36 * size), size, Anchor::Start, r#" class="bar-label""#, &bar.label);
    let stops: String = (0..=8)
        .map(|i| {
            let t = f64::from(i) / 8.0;
            format!(r#"<stop offset="{t}" stop-color="{}"/>"#, ramp(t).hex())
        })
        .collect();
    let _ = writeln!(svg, r#"<defs><linearGradient id="color-bar">{stops}</linearGradient></defs>"#);
    let top = y + LEGEND_ROW;
    let _ = writeln!(
        svg,
        r##"<rect x="{}" y="{}" width="{}" height="{}" fill="url(#color-bar)" stroke="#333333" stroke-width="1"/>"##,
        num(x0),
        num(top),
        num(x1 - x0),
        num(BAR_HEIGHT)
    );
    let axis = linear_axis(bar.lo, bar.hi, ((x1 - x0) / 70.0).max(2.0), false);
    let span = (bar.hi - bar.lo).max(f64::MIN_POSITIVE);
    let mut last_right = f64::MIN;
    for t in &axis.ticks {
        let tx = x0 + (t.at - bar.lo) / span * (x1 - x0);
        line(svg, [tx, top + BAR_HEIGHT, tx, top + BAR_HEIGHT + 5.0], "#333333", "1.2");
        let label = match &axis.factor {
            Some(f) => format!("{}{f}", t.label),
            None => t.label.clone(),
        };
        // Labels that would touch the one before are left out.
        let half = text_width(&label, NOTE_SIZE) / 2.0;
        if tx - half > last_right + 4.0 {
            let at = (tx, top + BAR_HEIGHT + 6.0 + NOTE_SIZE);
            text(svg, at, NOTE_SIZE, Anchor::Middle, r#" class="bar-tick""#, &label);
            last_right = tx + half;
        }
    }
    // Marks are lines across the bar; the bar's label says what they are.
    for value in &bar.marks {
        let tx = x0 + ((value - bar.lo) / span).clamp(0.0, 1.0) * (x1 - x0);
        line(svg, [tx, top - 3.0, tx, top + BAR_HEIGHT + 3.0], "#000000", "2.5");
    }
}

/// One SVG line from `(x1, y1)` to `(x2, y2)` (`[x1, y1, x2, y2]`, px), in `stroke` of `width` px.
pub(crate) fn line(svg: &mut String, [x1, y1, x2, y2]: [f64; 4], stroke: &str, width: &str) {
    let _ = writeln!(
        svg,
        r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{stroke}" stroke-width="{width}"/>"#,
        num(x1),
        num(y1),
        num(x2),
        num(y2)
    );
}
