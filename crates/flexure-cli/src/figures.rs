//! SVG line charts for the report (plotters), with labelled axes and units.

use plotters::prelude::*;
use std::path::Path;

/// One curve of a chart.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub color: RGBColor,
    /// Draw markers instead of a line.
    pub markers: bool,
}

impl Series {
    pub fn line(name: &str, points: Vec<(f64, f64)>, color: RGBColor) -> Self {
        Self { name: name.into(), points, color, markers: false }
    }
    pub fn dots(name: &str, points: Vec<(f64, f64)>, color: RGBColor) -> Self {
        Self { name: name.into(), points, color, markers: true }
    }
}

/// A chart's text and scales.
pub struct Chart<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub log_y: bool,
    /// Same scale on both axes (for shapes).
    pub equal_aspect: bool,
}

pub const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    BLACK,
];

fn bounds(series: &[Series], log_y: bool) -> ((f64, f64), (f64, f64)) {
    let pts = series.iter().flat_map(|s| s.points.iter()).filter(|p| !log_y || p.1 > 0.0);
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in pts {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if x0 > x1 {
        return ((0.0, 1.0), (if log_y { 1e-3 } else { 0.0 }, 1.0));
    }
    let pad = |a: f64, b: f64| if b - a > 0.0 { 0.05 * (b - a) } else { 0.5 * a.abs().max(1.0) };
    let (px, py) = (pad(x0, x1), pad(y0, y1));
    if log_y { ((x0 - px, x1 + px), (y0 / 2.0, y1 * 2.0)) } else { ((x0 - px, x1 + px), (y0 - py, y1 + py)) }
}

/// Writes an SVG chart of `series` to `path`; an error names the path. A
/// series with a non-finite point is refused before anything is written.
pub fn draw(path: &Path, chart: &Chart, series: &[Series]) -> Result<(), String> {
    for s in series {
        if let Some((i, p)) = s.points.iter().enumerate().find(|(_, p)| !(p.0.is_finite() && p.1.is_finite())) {
            let name = if s.name.is_empty() { "a line" } else { s.name.as_str() };
            return Err(format!(
                "drawing {}: point {i} of {name} is ({}, {}), not finite; nothing was written",
                path.display(),
                p.0,
                p.1
            ));
        }
    }
    let mut svg = String::new();
    plot(&mut svg, chart, series).map_err(|e| format!("drawing {}: {e}", path.display()))?;
    std::fs::write(path, svg).map_err(|e| format!("writing {}: {e}", path.display()))
}

/// Renders the chart as SVG text.
fn plot(svg: &mut String, chart: &Chart, series: &[Series]) -> Result<(), String> {
    let root = SVGBackend::with_string(svg, (1080, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let ((mut x0, mut x1), (mut y0, mut y1)) = bounds(series, chart.log_y);
    if chart.equal_aspect {
        // 720×480 pixels less margins: widen the shorter span to keep circles round.
        let (w, h) = (x1 - x0, y1 - y0);
        let ratio = 980.0 / 640.0;
        if w / h < ratio {
            let extra = (h * ratio - w) / 2.0;
            (x0, x1) = (x0 - extra, x1 + extra);
        } else {
            let extra = (w / ratio - h) / 2.0;
            (y0, y1) = (y0 - extra, y1 + extra);
        }
    }
    let mut builder = ChartBuilder::on(&root);
    builder.caption(chart.title, ("sans-serif", 26)).margin(20).x_label_area_size(60).y_label_area_size(90);
    macro_rules! finish {
        ($ctx:expr) => {{
            let mut ctx = $ctx;
            ctx.configure_mesh()
                .x_desc(chart.x_label)
                .y_desc(chart.y_label)
                .label_style(("sans-serif", 16))
                .axis_desc_style(("sans-serif", 18))
                .draw()
                .map_err(|e| e.to_string())?;
            for s in series {
                let style = s.color.stroke_width(2);
                let color = s.color;
                // A series with an empty name stays out of the legend.
                if s.markers {
                    let drawn = ctx
                        .draw_series(s.points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                        .map_err(|e| e.to_string())?;
                    if !s.name.is_empty() {
                        drawn.label(s.name.as_str()).legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
                    }
                } else {
                    let drawn =
                        ctx.draw_series(LineSeries::new(s.points.iter().copied(), style)).map_err(|e| e.to_string())?;
                    if !s.name.is_empty() {
                        drawn
                            .label(s.name.as_str())
                            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
                    }
                }
            }
            ctx.configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| e.to_string())?;
        }};
    }
    if chart.log_y {
        finish!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale()).map_err(|e| e.to_string())?);
    } else {
        finish!(builder.build_cartesian_2d(x0..x1, y0..y1).map_err(|e| e.to_string())?);
    }
    root.present().map_err(|e| e.to_string())
}
