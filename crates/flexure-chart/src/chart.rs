//! Line charts: curves (`Series`) on linear or logarithmic axes, made into a [`Figure`].

use crate::color::Color;
use crate::figure::{Dash, Entry, Figure, Mark, Marker, Stroke, Swatch};
use crate::svg::write;
use std::path::Path;

/// One curve of a chart.
pub struct Series {
    /// Its legend entry; empty keeps it out of the legend.
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub color: Color,
    /// The line's width (px) and pattern; `None` draws markers only.
    pub width: f64,
    pub dash: Option<Dash>,
    /// A marker on every `every`-th point, starting at `first`.
    pub marker: Option<Marker>,
    pub every: usize,
    pub first: usize,
    /// Filled markers, or hollow ones that let a line beneath show.
    pub filled: bool,
}

impl Series {
    /// A solid line.
    pub fn line(name: &str, points: Vec<(f64, f64)>, color: Color) -> Self {
        Self {
            name: name.into(),
            points,
            color,
            width: 2.0,
            dash: Some(Dash::Solid),
            marker: None,
            every: 1,
            first: 0,
            filled: true,
        }
    }
    /// Filled circles and no line.
    pub fn dots(name: &str, points: Vec<(f64, f64)>, color: Color) -> Self {
        Self { dash: None, marker: Some(Marker::Circle), ..Self::line(name, points, color) }
    }
    pub fn dashed(self, dash: Dash) -> Self {
        Self { dash: Some(dash), ..self }
    }
    pub fn width(self, width: f64) -> Self {
        Self { width, ..self }
    }
    /// Markers on every `every`-th point from `first`.
    pub fn marked(self, marker: Marker, every: usize, first: usize) -> Self {
        Self { marker: Some(marker), every: every.max(1), first, ..self }
    }
    /// Hollow markers.
    pub fn hollow(self) -> Self {
        Self { filled: false, ..self }
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

/// Writes an SVG chart of `series` to `path`; an error names the path. A
/// series with a non-finite point is refused before anything is written.
pub fn draw(path: &Path, chart: &Chart, series: &[Series]) -> Result<(), String> {
    let fig =
        chart_figure(chart, series).map_err(|e| format!("drawing {}: {e}; nothing was written", path.display()))?;
    write(path, &fig)
}

/// The figure of a chart of `series`; a series with a non-finite point is
/// refused, by its name and the point's index.
pub fn chart_figure(chart: &Chart, series: &[Series]) -> Result<Figure, String> {
    let mut fig = Figure::new(chart.title, chart.x_label, chart.y_label);
    fig.log_y = chart.log_y;
    fig.equal_aspect = chart.equal_aspect;
    for s in series {
        if let Some((i, p)) = s.points.iter().enumerate().find(|(_, p)| !(p.0.is_finite() && p.1.is_finite())) {
            let name = if s.name.is_empty() { "a line" } else { s.name.as_str() };
            return Err(format!("point {i} of {name} is ({}, {}), not finite", p.0, p.1));
        }
        if let Some(dash) = s.dash {
            let stroke = Stroke { color: s.color, width: s.width, dash };
            fig.marks.push(Mark::Path { points: s.points.clone(), stroke: Some(stroke), fill: None, closed: false });
        }
        if let Some(shape) = s.marker {
            for &at in s.points.iter().skip(s.first).step_by(s.every.max(1)) {
                fig.marks.push(Mark::Dot { at, shape, radius: 5.0, color: s.color, filled: s.filled });
            }
        }
        if !s.name.is_empty() {
            let stroke = s.dash.map(|dash| Stroke { color: s.color, width: s.width, dash });
            fig.legend.push(Entry {
                swatch: Swatch::Line(stroke, s.marker.map(|m| (m, s.color, s.filled))),
                label: s.name.clone(),
            });
        }
    }
    Ok(fig)
}
