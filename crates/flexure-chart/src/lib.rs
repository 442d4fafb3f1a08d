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
//!   a legend beside the plot takes columns (and the figure grows) rather
//!   than run past the figure's foot, and a shape's height is fitted to its
//!   aspect. `plotters` takes fixed
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

mod axis;
mod chart;
mod color;
mod figure;
mod layout;
mod svg;

pub use chart::{Chart, Series, chart_figure, draw};
pub use color::{BLACK, COLORS, Color, GRAY, ramp};
pub use figure::{Anchor, ColorBar, Dash, Entry, Figure, Fill, Mark, Marker, Place, Stroke, Swatch};
pub use svg::{render, stack, write, write_stack};

/// The smallest text in any figure (px, at the default size).
pub const MIN_TEXT: f64 = 14.0;
pub(crate) const TITLE_SIZE: f64 = 22.0;
pub(crate) const LABEL_SIZE: f64 = 18.0;
pub(crate) const TICK_SIZE: f64 = 16.0;
pub(crate) const LEGEND_SIZE: f64 = 16.0;
pub(crate) const NOTE_SIZE: f64 = MIN_TEXT;
