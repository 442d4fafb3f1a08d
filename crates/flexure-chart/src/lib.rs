//! Figures as SVG: line charts with linear or logarithmic axes (the
//! paper's figures that `flexure reproduce` regenerates) and same-scale
//! drawings of mechanisms (`flexure draw`). It knows nothing of flexures:
//! the command builds a [`Figure`] of [`Mark`]s and legend [`Entry`]s, and
//! [`render`] lays it out and writes the SVG text.
//!
//! # Why a crate of its own, not `plotters`
//!
//! Issue 22 asked for `plotters`' SVG backend or a crate of its own with a
//! stated reason. The figures need what `plotters` leaves to its caller or
//! does otherwise:
//!
//! - **Layout measured from the text it holds.** Margins are sized from the
//!   tick and axis labels, the legend goes right of the plot or under it
//!   (whichever draws the plot larger) or into the plot's emptiest corner,
//!   and a shape's height is fitted to its aspect. `plotters` takes fixed
//!   label areas in whole pixels from its caller, and measuring its text
//!   needs its `ttf` feature, which loads system fonts: the same command
//!   would lay out differently on two machines.
//! - **Deterministic text.** The SVG here depends on its input alone (the
//!   characterization and figure tests read it), with coordinates to 0.1 px;
//!   `plotters`' backend API is in integer pixels (`BackendCoord = (i32, i32)`).
//! - **Round ticks and readable labels** (`10⁻⁶`, never `9.999999999999999e-6`;
//!   a true minus; a shared factor `×10⁻⁴`), text of at least [`MIN_TEXT`] px.
//! - **Marks that are not chart series**: filled hulls of links, turning
//!   arrows for moments, force arrows, labels offset in pixels, a colour bar
//!   with marks (yield strengths) inside the legend, stacked figures in one
//!   SVG (a drawing above its time charts), and curves told apart by dash and
//!   marker as well as colour. With `plotters` each would be a custom element
//!   drawn by hand, as here, plus its coordinate system and layout.
//!
//! So the chart stays hand-written, but in a crate with no dependencies,
//! tested on its own (`tests/chart.rs`), which the command line only uses.
//!
//! # Example
//!
//! ```
//! use flexure_chart::{COLORS, Chart, Series, chart_figure, render};
//!
//! let chart = Chart { title: "A line", x_label: "x", y_label: "y", log_y: false, equal_aspect: false };
//! let fig = chart_figure(&chart, &[Series::line("y = x²", vec![(0.0, 0.0), (1.0, 1.0), (2.0, 4.0)], COLORS[0])])?;
//! let svg = render(&fig)?;
//! assert!(svg.starts_with("<svg") && svg.contains("A line") && svg.contains("y = x²"));
//! # Ok::<(), String>(())
//! ```

use std::fmt::Write as _;
use std::path::Path;

/// The smallest text in any figure (px, at the default size).
pub const MIN_TEXT: f64 = 14.0;
const TITLE_SIZE: f64 = 22.0;
const LABEL_SIZE: f64 = 18.0;
const TICK_SIZE: f64 = 16.0;
const LEGEND_SIZE: f64 = 16.0;
const NOTE_SIZE: f64 = MIN_TEXT;

/// An opaque colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Color(pub u8, pub u8, pub u8);

impl Color {
    fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    /// This colour mixed toward white by `t` (0: unchanged, 1: white).
    pub fn tint(self, t: f64) -> Color {
        let mix = |c: u8| (f64::from(c) + t.clamp(0.0, 1.0) * (255.0 - f64::from(c))).round() as u8;
        Color(mix(self.0), mix(self.1), mix(self.2))
    }
}

pub const BLACK: Color = Color(0, 0, 0);
pub const GRAY: Color = Color(140, 140, 140);

/// Categorical colours (Tableau 10), then black.
pub const COLORS: [Color; 6] =
    [Color(31, 119, 180), Color(214, 39, 40), Color(44, 160, 44), Color(148, 103, 189), Color(255, 127, 14), BLACK];

/// A sequential colour map for a quantity from 0 to 1: the dark four
/// fifths of matplotlib's *plasma* (blue, purple, red, orange), each end
/// visible on white and its lightness rising with the value.
const RAMP: [Color; 5] =
    [Color(13, 8, 135), Color(106, 0, 168), Color(177, 42, 144), Color(225, 100, 98), Color(252, 166, 54)];

/// The colour of `t` in [0, 1] (clamped) on the sequential map.
pub fn ramp(t: f64) -> Color {
    let x = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 } * (RAMP.len() - 1) as f64;
    let k = (x.floor() as usize).min(RAMP.len() - 2);
    let f = x - k as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (RAMP[k], RAMP[k + 1]);
    Color(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// A colour bar under the legend: the [`ramp`] from `lo` to `hi`, with round ticks.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorBar {
    /// What the colours stand for, with its unit: `bending stress (MPa)`.
    pub label: String,
    pub lo: f64,
    pub hi: f64,
    /// Values marked by a black line across the bar (yield strengths), which
    /// `label` names.
    pub marks: Vec<f64>,
}

/// A line's dash pattern.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dash {
    Solid,
    Dashed,
    Dotted,
    /// Dash and dot (a chain line).
    Chain,
}

impl Dash {
    /// The SVG `stroke-dasharray`, scaled with the line width.
    fn array(self, width: f64) -> Option<String> {
        let w = (width / 2.0).max(1.0);
        let pattern: &[f64] = match self {
            Dash::Solid => return None,
            Dash::Dashed => &[10.0, 6.0],
            Dash::Dotted => &[1.5, 5.0],
            Dash::Chain => &[12.0, 5.0, 2.0, 5.0],
        };
        Some(pattern.iter().map(|p| format!("{}", p * w)).collect::<Vec<_>>().join(" "))
    }
}

/// A marker's shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
}

/// How a line is stroked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    pub color: Color,
    /// Width (px).
    pub width: f64,
    pub dash: Dash,
}

impl Stroke {
    pub fn solid(color: Color, width: f64) -> Self {
        Self { color, width, dash: Dash::Solid }
    }
}

/// How an area is filled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fill {
    pub color: Color,
    pub opacity: f64,
}

/// Something drawn in the plot area; positions are in data units, sizes in px.
#[derive(Debug, Clone, PartialEq)]
pub enum Mark {
    /// A polyline, or a polygon when `closed`.
    Path { points: Vec<(f64, f64)>, stroke: Option<Stroke>, fill: Option<Fill>, closed: bool },
    /// A marker of radius `radius` px; hollow (white inside) unless `filled`.
    Dot { at: (f64, f64), shape: Marker, radius: f64, color: Color, filled: bool },
    /// A straight arrow with its head at `to`.
    Arrow { from: (f64, f64), to: (f64, f64), color: Color, width: f64 },
    /// Three quarters of a circle of `radius` px around `at` with a head
    /// showing the sense: counter-clockwise (positive) if `ccw`.
    Turn { at: (f64, f64), radius: f64, ccw: bool, color: Color, width: f64 },
    /// Text at `at`, moved by `offset` px (x right, y down).
    Label { at: (f64, f64), offset: (f64, f64), text: String, color: Color, anchor: Anchor },
}

/// Which end of a label sits at its position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

impl Anchor {
    fn svg(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// The small picture beside a legend entry.
#[derive(Debug, Clone, PartialEq)]
pub enum Swatch {
    /// A line, with a marker on it.
    Line(Option<Stroke>, Option<(Marker, Color, bool)>),
    /// A filled area with an outline.
    Area(Fill, Stroke),
    Arrow(Color),
    Turn(Color),
    /// No picture: a note, such as a scale.
    Note,
}

/// One legend row.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    pub swatch: Swatch,
    pub label: String,
}

/// Where a legend goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Place {
    /// In the corner of the plot where it hides no data, else right of the plot.
    Inside,
    /// Right of the plot.
    Right,
    /// Under the plot, in columns.
    Below,
    /// Right of the plot or under it, whichever draws the plot larger.
    Outside,
}

/// A figure: axes, marks and a legend.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_y: bool,
    /// Same scale on both axes (shapes).
    pub equal_aspect: bool,
    /// Size (px).
    pub width: f64,
    pub height: f64,
    /// Where the legend goes.
    pub place: Place,
    /// With equal aspect: lower the height (at most `height`) to what the shape needs.
    pub fit_height: bool,
    pub marks: Vec<Mark>,
    pub legend: Vec<Entry>,
    /// A colour bar, drawn in the legend's box under its entries.
    pub color_bar: Option<ColorBar>,
}

impl Figure {
    /// An empty 960 × 640 figure.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            log_y: false,
            equal_aspect: false,
            width: 960.0,
            height: 640.0,
            place: Place::Inside,
            fit_height: false,
            marks: Vec::new(),
            legend: Vec::new(),
            color_bar: None,
        }
    }
}

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

/// The positions a mark occupies (data units).
fn mark_points(mark: &Mark) -> Vec<(f64, f64)> {
    match mark {
        Mark::Path { points, .. } => points.clone(),
        Mark::Dot { at, .. } | Mark::Turn { at, .. } | Mark::Label { at, .. } => vec![*at],
        Mark::Arrow { from, to, .. } => vec![*from, *to],
    }
}

/// Roughly how wide `text` is in DejaVu Sans at `size` px (slightly generous).
fn text_width(text: &str, size: f64) -> f64 {
    let em: f64 = text
        .chars()
        .map(|c| match c {
            '0'..='9' => 0.64,
            'i' | 'j' | 'l' | '.' | ',' | ':' | ';' | '\'' | '|' | '!' => 0.32,
            ' ' | '(' | ')' | '[' | ']' | 'f' | 't' | 'r' | '-' => 0.4,
            'm' | 'w' | 'M' | 'W' => 0.92,
            'A'..='Z' => 0.72,
            'a'..='z' => 0.6,
            '⁰'..='⁹' | '¹' | '²' | '³' | '⁻' | '₀'..='₉' => 0.42,
            _ => 0.72,
        })
        .sum();
    em * size
}

/// XML text.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// `10` with superscript exponent `k`: `10⁻⁶`.
fn power_of_ten(k: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for d in k.unsigned_abs().to_string().bytes() {
        s.push(DIGITS[usize::from(d - b'0')]);
    }
    s
}

/// The smallest of 1, 2, 5 × 10ᵏ at least `raw`.
fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let k = raw.log10().floor();
    let base = 10f64.powf(k);
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * base).find(|s| *s >= raw * (1.0 - 1e-9)).unwrap_or(10.0 * base)
}

/// A tick at a position in axis units (log₁₀ of the value on a log axis).
struct Tick {
    at: f64,
    label: String,
}

/// One axis: its range in axis units, ticks, minor ticks, and a note for
/// its label (a common factor such as `×10⁻⁴`).
struct Axis {
    lo: f64,
    hi: f64,
    ticks: Vec<Tick>,
    minor: Vec<f64>,
    factor: Option<String>,
}

/// Ticks at round multiples on `[lo, hi]`, about `target` of them; whole
/// numbers only when `integer`. Labels carry as many decimals as the step
/// needs; very small or large values share a factor `×10ᵏ` instead.
fn linear_axis(lo: f64, hi: f64, target: f64, integer: bool) -> Axis {
    let mut step = nice_step((hi - lo) / target.max(1.0));
    if integer {
        step = step.max(1.0);
    }
    let (i0, i1) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
    let values: Vec<f64> = (i0..=i1.min(i0 + 200)).map(|i| i as f64 * step).collect();
    let big = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let k = if big > 0.0 && (step < 1e-3 || big >= 1e5) { big.log10().floor() as i32 } else { 0 };
    let unit = 10f64.powi(k);
    let decimals = (-(step / unit).log10().floor()).max(0.0) as usize;
    let ticks = values
        .iter()
        .map(|&v| {
            let text = format!("{:.*}", decimals, v / unit);
            // No "-0.0": a label that reads as zero is zero.
            let zero = text.trim_start_matches('-').chars().all(|c| c == '0' || c == '.');
            let label = if zero { format!("{:.*}", decimals, 0.0) } else { text.replace('-', "−") };
            Tick { at: v, label }
        })
        .collect();
    Axis { lo, hi, ticks, minor: Vec::new(), factor: (k != 0).then(|| format!("×{}", power_of_ten(k))) }
}

/// A log axis on whole decades `[10^k0, 10^k1]` (axis units are log₁₀):
/// a labelled tick per decade (every other one past 8 decades), minor ticks
/// at 2…9, and labels at 2 and 5 too when only one decade shows.
fn log_axis(k0: i32, k1: i32) -> Axis {
    let n = (k1 - k0).max(1);
    let every = (n + 7) / 8;
    let mut ticks = Vec::new();
    let mut minor = Vec::new();
    for k in k0..=k1 {
        if (k - k0) % every == 0 {
            ticks.push(Tick { at: f64::from(k), label: power_of_ten(k) });
        }
        if k < k1 {
            for m in 2..=9 {
                let at = f64::from(k) + f64::from(m).log10();
                if n == 1 && (m == 2 || m == 5) {
                    ticks.push(Tick { at, label: format!("{m}×{}", power_of_ten(k)) });
                } else {
                    minor.push(at);
                }
            }
        }
    }
    Axis { lo: f64::from(k0), hi: f64::from(k1), ticks, minor, factor: None }
}

/// Where everything goes, in px.
struct Layout {
    left: f64,
    top: f64,
    w: f64,
    h: f64,
    x: Axis,
    y: Axis,
    /// Top-left corner of the legend box, its width and height.
    legend: Option<(f64, f64, f64, f64)>,
    /// Rows per legend column.
    rows: usize,
    /// The span (axis units) of what is drawn, labels included, before
    /// equal aspect widened one axis.
    content: (f64, f64),
}

impl Layout {
    fn px(&self, p: (f64, f64), log_y: bool) -> (f64, f64) {
        let y = if log_y { p.1.log10() } else { p.1 };
        (
            self.left + (p.0 - self.x.lo) / (self.x.hi - self.x.lo) * self.w,
            self.top + self.h - (y - self.y.lo) / (self.y.hi - self.y.lo) * self.h,
        )
    }
}

const LEGEND_ROW: f64 = LEGEND_SIZE * 1.5;
const SWATCH: f64 = 40.0;

/// The widest legend row (px).
fn legend_column(entries: &[Entry]) -> f64 {
    entries
        .iter()
        .map(|e| {
            let size = if e.swatch == Swatch::Note { NOTE_SIZE } else { LEGEND_SIZE };
            let swatch = if e.swatch == Swatch::Note { 0.0 } else { SWATCH + 8.0 };
            swatch + text_width(&e.label, size)
        })
        .fold(0.0, f64::max)
}

/// The height of a colour bar's block in the legend (px): its label, the
/// bar, and its tick labels.
const BAR_BLOCK: f64 = LEGEND_ROW + BAR_HEIGHT + 6.0 + TICK_SIZE + 12.0;
const BAR_HEIGHT: f64 = 16.0;
/// The least width of a legend holding a colour bar (px), for its ticks to read.
const BAR_WIDTH: f64 = 300.0;

/// A legend's size (px) and rows per column, in as many columns (at most
/// three) as fit in `room` px; a colour bar adds a block under the entries.
fn legend_size(entries: &[Entry], bar: bool, room: f64) -> (f64, f64, usize) {
    let column = legend_column(entries) + 24.0;
    let columns = ((room / column).floor() as usize).clamp(1, 3).min(entries.len().max(1));
    let rows = entries.len().div_ceil(columns);
    let (w, h) = (columns as f64 * column, rows as f64 * LEGEND_ROW + 14.0);
    if bar { (w.max(BAR_WIDTH), h + BAR_BLOCK, rows) } else { (w, h, rows) }
}

/// Data range in axis units, padded: linear axes by 4 % a side, log axes
/// out to whole decades. `None` if nothing is drawable.
fn data_range(fig: &Figure) -> ((f64, f64), (f64, f64)) {
    let pts = fig.marks.iter().flat_map(mark_points).filter(|p| !fig.log_y || p.1 > 0.0);
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in pts {
        let y = if fig.log_y { y.log10() } else { y };
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if x0 > x1 {
        return ((0.0, 1.0), if fig.log_y { (-3.0, 0.0) } else { (0.0, 1.0) });
    }
    let pad = |a: f64, b: f64| if b - a > 0.0 { 0.04 * (b - a) } else { 0.5 * a.abs().max(1.0) };
    let (px, py) = (pad(x0, x1), pad(y0, y1));
    let y = if fig.log_y {
        let (k0, k1) = ((y0 - 0.5 * py).floor(), (y1 + 0.5 * py).ceil());
        (k0, if k1 > k0 { k1 } else { k0 + 1.0 })
    } else {
        (y0 - py, y1 + py)
    };
    ((x0 - px, x1 + px), y)
}

/// Whether every x drawn is a whole number (an axis of counts).
fn integer_x(fig: &Figure) -> bool {
    let mut xs = fig.marks.iter().flat_map(mark_points).map(|p| p.0).peekable();
    xs.peek().is_some() && xs.all(|x| x == x.round() && x.abs() < 1e15)
}

/// Margins measured from the labels, the range grown until every label,
/// marker and turn fits inside the plot, and (for equal aspect) the shorter
/// span widened; repeated, because the ticks depend on the ranges.
fn layout(fig: &Figure, place: Place) -> Layout {
    let ((mut x0, mut x1), (mut y0, mut y1)) = data_range(fig);
    let integer = integer_x(fig);
    let top = if fig.title.is_empty() { 20.0 } else { 56.0 };
    let axis_room = 6.0 + 8.0 + TICK_SIZE + 16.0 + LABEL_SIZE + 12.0;
    let (mut left, mut right) = (120.0, 30.0);
    let mut l = None;
    let mut legend = None;
    for _ in 0..8 {
        let bar = fig.color_bar.is_some();
        legend = (!fig.legend.is_empty() || bar).then(|| match place {
            Place::Below => legend_size(&fig.legend, bar, fig.width - left - right),
            _ => legend_size(&fig.legend, bar, 0.0),
        });
        let beside = if place == Place::Right { legend.map_or(0.0, |l| l.0 + 20.0) } else { 0.0 };
        let under = if place == Place::Below { legend.map_or(0.0, |l| l.1 + 12.0) } else { 0.0 };
        let w = fig.width - left - right - beside;
        let h = fig.height - top - axis_room - under;
        let (mut xr, mut yr) = ((x0, x1), (y0, y1));
        if fig.equal_aspect && !fig.log_y {
            let (sx, sy) = ((x1 - x0) / w, (y1 - y0) / h);
            if sx > sy {
                let extra = (sx * h - (y1 - y0)) / 2.0;
                yr = (y0 - extra, y1 + extra);
            } else {
                let extra = (sy * w - (x1 - x0)) / 2.0;
                xr = (x0 - extra, x1 + extra);
            }
        }
        let x = linear_axis(xr.0, xr.1, if integer && xr.1 - xr.0 <= 16.0 { 16.0 } else { w / 110.0 }, integer);
        let y = if fig.log_y { log_axis(yr.0 as i32, yr.1 as i32) } else { linear_axis(yr.0, yr.1, h / 55.0, false) };
        let widest = y.ticks.iter().map(|t| text_width(&t.label, TICK_SIZE)).fold(0.0, f64::max);
        let (new_left, new_right) = (
            16.0 + LABEL_SIZE + 14.0 + widest + 12.0,
            x.ticks.last().map_or(0.0, |t| text_width(&t.label, TICK_SIZE) / 2.0).max(24.0) + 6.0,
        );
        let here = Layout { left, top, w, h, x, y, legend: None, rows: 0, content: (x1 - x0, y1 - y0) };
        // What sticks out of the plot (px), turned into data units.
        let (mut over, mut settled) = ([0.0_f64; 4], true);
        for mark in &fig.marks {
            if let Some(b) = extent(mark, &here, fig.log_y) {
                over[0] = over[0].max(here.left + 2.0 - b.0);
                over[1] = over[1].max(b.1 - (here.left + w - 2.0));
                over[2] = over[2].max(b.3 - (here.top + h - 2.0));
                over[3] = over[3].max(here.top + 2.0 - b.2);
            }
        }
        let (ux, uy) = ((here.x.hi - here.x.lo) / w, (here.y.hi - here.y.lo) / h);
        if over.iter().any(|&o| o > 0.5) && !fig.log_y {
            (x0, x1, y0, y1) =
                (x0 - 1.1 * over[0] * ux, x1 + 1.1 * over[1] * ux, y0 - 1.1 * over[2] * uy, y1 + 1.1 * over[3] * uy);
            settled = false;
        }
        settled &= (new_left - left).abs() < 0.5 && (new_right - right).abs() < 0.5;
        (left, right) = (new_left, new_right);
        l = Some(here);
        if settled {
            break;
        }
    }
    let mut l = l.unwrap_or_else(|| Layout {
        left,
        top,
        w: 1.0,
        h: 1.0,
        x: linear_axis(x0, x1, 8.0, integer),
        y: linear_axis(y0, y1, 8.0, false),
        legend: None,
        rows: 0,
        content: (x1 - x0, y1 - y0),
    });
    if let Some((lw, lh, rows)) = legend {
        l.rows = rows;
        l.legend = Some(match place {
            Place::Right | Place::Outside => (l.left + l.w + 20.0, top, lw, lh),
            Place::Below => (l.left, top + l.h + axis_room + 4.0, lw, lh),
            Place::Inside => best_corner(fig, &l, lw, lh),
        });
    }
    l
}

/// The box a mark covers (px: left, right, top, bottom), counting its
/// text, markers, heads and line width.
fn extent(mark: &Mark, l: &Layout, log_y: bool) -> Option<(f64, f64, f64, f64)> {
    let grow = |p: (f64, f64), r: f64| (p.0 - r, p.0 + r, p.1 - r, p.1 + r);
    let join =
        |a: (f64, f64, f64, f64), b: (f64, f64, f64, f64)| (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3));
    let px = |p: (f64, f64)| l.px(p, log_y);
    match mark {
        Mark::Path { points, stroke, .. } => {
            let r = stroke.map_or(0.0, |s| s.width / 2.0);
            points.iter().filter(|p| !log_y || p.1 > 0.0).map(|&p| grow(px(p), r)).reduce(join)
        }
        Mark::Dot { at, radius, .. } => (!log_y || at.1 > 0.0).then(|| grow(px(*at), radius + 1.5)),
        Mark::Arrow { from, to, width, .. } => Some(join(grow(px(*from), *width), grow(px(*to), 0.5 * head(*width)))),
        Mark::Turn { at, radius, width, .. } => Some(grow(px(*at), radius + width)),
        Mark::Label { at, offset, text: body, anchor, .. } => {
            let p = px(*at);
            let (x, y, tw) = (p.0 + offset.0, p.1 + offset.1, text_width(body, LEGEND_SIZE));
            let (a, b) = match anchor {
                Anchor::Start => (x, x + tw),
                Anchor::Middle => (x - tw / 2.0, x + tw / 2.0),
                Anchor::End => (x - tw, x),
            };
            Some((a, b, y - 0.8 * LEGEND_SIZE, y + 0.3 * LEGEND_SIZE))
        }
    }
}

/// An arrowhead's length for a line `width` px wide.
fn head(width: f64) -> f64 {
    3.0 * width + 8.0
}

/// The corner of the plot where a `lw` × `lh` legend covers the fewest drawn points.
fn best_corner(fig: &Figure, l: &Layout, lw: f64, lh: f64) -> (f64, f64, f64, f64) {
    let inset = 10.0;
    let corners = [
        (l.left + l.w - lw - inset, l.top + inset),
        (l.left + inset, l.top + inset),
        (l.left + l.w - lw - inset, l.top + l.h - lh - inset),
        (l.left + inset, l.top + l.h - lh - inset),
    ];
    let pts = drawn_pixels(fig, l);
    let covered = |&(cx, cy): &(f64, f64)| {
        pts.iter()
            .filter(|p| p.0 >= cx - 6.0 && p.0 <= cx + lw + 6.0 && p.1 >= cy - 6.0 && p.1 <= cy + lh + 6.0)
            .count()
    };
    let best = corners.iter().min_by_key(|c| covered(c)).copied().unwrap_or(corners[0]);
    (best.0, best.1, lw, lh)
}

/// Pixels along every drawn line (every 4 px) and at every marker.
fn drawn_pixels(fig: &Figure, l: &Layout) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for mark in &fig.marks {
        let pts = mark_points(mark);
        // On a log axis a non-positive value breaks the line.
        for run in pts.split(|p| fig.log_y && p.1 <= 0.0) {
            let run: Vec<(f64, f64)> = run.iter().map(|&p| l.px(p, fig.log_y)).collect();
            out.extend(run.first());
            for s in run.windows(2) {
                let n = ((s[1].0 - s[0].0).hypot(s[1].1 - s[0].1) / 4.0).ceil().min(2000.0) as usize;
                out.extend((1..=n).map(|i| {
                    let t = i as f64 / n as f64;
                    (s[0].0 + t * (s[1].0 - s[0].0), s[0].1 + t * (s[1].1 - s[0].1))
                }));
            }
        }
    }
    out
}

fn num(x: f64) -> String {
    format!("{x:.2}")
}

fn points_attr(pts: &[(f64, f64)]) -> String {
    pts.iter().map(|p| format!("{},{}", num(p.0), num(p.1))).collect::<Vec<_>>().join(" ")
}

fn stroke_attrs(s: &Stroke) -> String {
    let dash = s.dash.array(s.width).map_or(String::new(), |d| format!(r#" stroke-dasharray="{d}""#));
    format!(
        r#"stroke="{}" stroke-width="{}" stroke-linejoin="round" stroke-linecap="round"{dash}"#,
        s.color.hex(),
        num(s.width)
    )
}

fn text(svg: &mut String, (x, y): (f64, f64), size: f64, anchor: Anchor, extra: &str, body: &str) {
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{}" font-size="{size}" text-anchor="{}"{extra}>{}</text>"#,
        num(x),
        num(y),
        anchor.svg(),
        escape(body)
    );
}

fn marker(svg: &mut String, (x, y): (f64, f64), shape: Marker, r: f64, color: Color, filled: bool) {
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
fn arrow(svg: &mut String, from: (f64, f64), to: (f64, f64), color: Color, width: f64) {
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
fn turn(svg: &mut String, c: (f64, f64), r: f64, ccw: bool, color: Color, width: f64) {
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

/// Every position finite, or the first that is not.
fn check_finite(fig: &Figure) -> Result<(), String> {
    for (i, mark) in fig.marks.iter().enumerate() {
        if let Some(p) = mark_points(mark).into_iter().find(|p| !(p.0.is_finite() && p.1.is_finite())) {
            return Err(format!("mark {i} has the point ({}, {}), not finite", p.0, p.1));
        }
    }
    if !(fig.width >= 200.0 && fig.height >= 200.0 && fig.width <= 10_000.0 && fig.height <= 10_000.0) {
        return Err(format!("the figure size {} × {} px is outside 200…10000", fig.width, fig.height));
    }
    Ok(())
}

/// `fig` no taller than its drawing at equal scale needs (nor shorter than
/// its legend or 400 px), with the legend beside or under the plot,
/// whichever draws it larger; `height` bounds the figure, less any legend under the plot.
fn fit_height(fig: &Figure) -> Figure {
    let fitted = |place: Place| {
        let mut f = Figure { place, ..fig.clone() };
        // Labels grow the content as the scale changes: settle in a few rounds.
        for _ in 0..3 {
            let l = layout(&f, place);
            let chrome = f.height - l.h;
            // A legend beside the plot sets its least height; one under it adds to the most.
            let (least, most) = match (place, l.legend) {
                (Place::Right, Some(b)) => (b.3 + l.top + 20.0, fig.height),
                (Place::Below, Some(b)) => (0.0, fig.height + b.3),
                _ => (0.0, fig.height),
            };
            let least = least.max(400.0).min(most);
            let height = (chrome + l.w * l.content.1 / l.content.0).clamp(least, most);
            f.height = height.round();
        }
        let l = layout(&f, place);
        (l.w / (l.x.hi - l.x.lo), f)
    };
    let candidates = match fig.place {
        Place::Outside => vec![fitted(Place::Right), fitted(Place::Below)],
        place => vec![fitted(place)],
    };
    candidates.into_iter().max_by(|a, b| a.0.total_cmp(&b.0)).map_or_else(|| fig.clone(), |c| c.1)
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
    // A legend that would hide data moves out beside the plot.
    if fig.place == Place::Inside
        && let Some((x, y, w, h)) = l.legend
    {
        let pts = drawn_pixels(fig, &l);
        if pts.iter().any(|p| p.0 >= x - 6.0 && p.0 <= x + w + 6.0 && p.1 >= y - 6.0 && p.1 <= y + h + 6.0) {
            l = layout(fig, Place::Right);
        }
    }
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

fn draw_mark(svg: &mut String, mark: &Mark, l: &Layout, log_y: bool) {
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

fn draw_legend(svg: &mut String, entries: &[Entry], (x, y, w, h): (f64, f64, f64, f64), rows: usize) {
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
fn draw_color_bar(svg: &mut String, bar: &ColorBar, (x, y, w): (f64, f64, f64)) {
    let (x0, x1) = (x + 12.0, x + w - 24.0);
    text(
        svg,
        (x0, y + 0.5 * LEGEND_ROW + 0.36 * LEGEND_SIZE),
        LEGEND_SIZE,
        Anchor::Start,
        r#" class="bar-label""#,
        &bar.label,
    );
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
fn line(svg: &mut String, [x1, y1, x2, y2]: [f64; 4], stroke: &str, width: &str) {
    let _ = writeln!(
        svg,
        r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{stroke}" stroke-width="{width}"/>"#,
        num(x1),
        num(y1),
        num(x2),
        num(y2)
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_read_as_round_numbers() {
        // Decades print as powers of ten, never as 9.999999999999999e-6.
        let a = log_axis(-8, -2);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["10⁻⁸", "10⁻⁷", "10⁻⁶", "10⁻⁵", "10⁻⁴", "10⁻³", "10⁻²"]);
        // A linear axis through zero reads "0.0", never "-0.0"; negatives get a true minus.
        let a = linear_axis(-0.26, 0.83, 8.0, false);
        let labels: Vec<&str> = a.ticks.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(labels, ["−0.2", "0.0", "0.2", "0.4", "0.6", "0.8"]);
        let a = linear_axis(2.7, 9.3, 8.0, true);
        assert_eq!(a.ticks.iter().map(|t| t.label.as_str()).collect::<Vec<_>>(), ["3", "4", "5", "6", "7", "8", "9"]);
        // Small values share a factor.
        let a = linear_axis(0.0, 7.7e-4, 8.0, false);
        assert_eq!(a.factor.as_deref(), Some("×10⁻⁴"));
        assert_eq!(a.ticks[1].label, "1");
    }
}
