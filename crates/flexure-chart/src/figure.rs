//! What a figure is made of: marks in data units, strokes and fills, the
//! legend's entries, a colour bar, and the figure that holds them.

use crate::color::Color;

/// A colour bar under the legend: the [`ramp`](crate::ramp) from `lo` to `hi`, with round ticks.
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
    pub(crate) fn array(self, width: f64) -> Option<String> {
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
    pub(crate) fn svg(self) -> &'static str {
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
    /// Right of the plot, in columns (up to three) where one would run past
    /// the figure's foot; the figure grows where three would.
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
