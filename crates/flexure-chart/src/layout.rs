//! Where everything goes, in px: margins measured from the labels they
//! hold, the legend beside, under or inside the plot where it hides no
//! data, and a shape's height fitted to its aspect.

use crate::axis::{Axis, linear_axis, log_axis};
use crate::figure::{Anchor, Entry, Figure, Mark, Place, Swatch};
use crate::{LABEL_SIZE, LEGEND_SIZE, NOTE_SIZE, TICK_SIZE};

/// Where everything goes, in px.
pub(crate) struct Layout {
    pub(crate) left: f64,
    pub(crate) top: f64,
    pub(crate) w: f64,
    pub(crate) h: f64,
    pub(crate) x: Axis,
    pub(crate) y: Axis,
    /// Top-left corner of the legend box, its width and height.
    pub(crate) legend: Option<(f64, f64, f64, f64)>,
    /// Rows per legend column.
    pub(crate) rows: usize,
    /// The span (axis units) of what is drawn, labels included, before
    /// equal aspect widened one axis.
    pub(crate) content: (f64, f64),
}

impl Layout {
    pub(crate) fn px(&self, p: (f64, f64), log_y: bool) -> (f64, f64) {
        let y = if log_y { p.1.log10() } else { p.1 };
        (
            self.left + (p.0 - self.x.lo) / (self.x.hi - self.x.lo) * self.w,
            self.top + self.h - (y - self.y.lo) / (self.y.hi - self.y.lo) * self.h,
        )
    }
}

pub(crate) const LEGEND_ROW: f64 = LEGEND_SIZE * 1.5;
pub(crate) const SWATCH: f64 = 40.0;

/// The widest legend row (px).
pub(crate) fn legend_column(entries: &[Entry]) -> f64 {
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
pub(crate) const BAR_BLOCK: f64 = LEGEND_ROW + BAR_HEIGHT + 6.0 + TICK_SIZE + 12.0;
pub(crate) const BAR_HEIGHT: f64 = 16.0;
/// The least width of a legend holding a colour bar (px), for its ticks to read.
pub(crate) const BAR_WIDTH: f64 = 300.0;

/// The most columns a legend takes.
pub(crate) const MOST_COLUMNS: usize = 3;

/// Room (px) kept under a legend beside the plot, to the figure's foot.
pub(crate) const LEGEND_FOOT: f64 = 10.0;

/// The columns a legend of `entries` may take in `room` px of width: as
/// many as fit, one to [`MOST_COLUMNS`], no more than its entries.
fn columns_in(entries: &[Entry], room: f64) -> usize {
    let column = legend_column(entries) + 24.0;
    ((room / column).floor() as usize).clamp(1, MOST_COLUMNS).min(entries.len().max(1))
}

/// A legend's size (px) and rows per column in `columns` columns; a colour
/// bar (`bar`: its title's width, px) adds a block under the entries, as
/// wide as its title where `room` allows (the title is set smaller past it).
fn legend_box(entries: &[Entry], bar: Option<f64>, columns: usize, room: f64) -> (f64, f64, usize) {
    let column = legend_column(entries) + 24.0;
    let rows = entries.len().div_ceil(columns.max(1));
    let (w, h) = (columns as f64 * column, rows as f64 * LEGEND_ROW + 14.0);
    match bar {
        Some(title) => (w.max(BAR_WIDTH).max((title + 36.0).min(room)), h + BAR_BLOCK, rows),
        None => (w, h, rows),
    }
}

/// A legend's size (px) and rows per column, in as many columns (at most
/// three) as fit in `room` px; a colour bar adds a block under the entries.
pub(crate) fn legend_size(entries: &[Entry], bar: Option<f64>, room: f64) -> (f64, f64, usize) {
    legend_box(entries, bar, columns_in(entries, room), room)
}

/// A legend beside the plot: one column if it is no taller than `height`
/// px, else the fewest columns (at most three, and no wider together than
/// `width` px) that are; as many as `width` allows if none is, and the
/// figure then grows to hold it ([`crate::render`]).
pub(crate) fn legend_beside(entries: &[Entry], bar: Option<f64>, height: f64, width: f64) -> (f64, f64, usize) {
    let most = columns_in(entries, width);
    let at = |c| legend_box(entries, bar, c, width);
    (1..=most).map(at).find(|b| b.1 <= height).unwrap_or(at(most))
}

/// Data range in axis units, padded: linear axes by 4 % a side, log axes
/// out to whole decades. `None` if nothing is drawable.
pub(crate) fn data_range(fig: &Figure) -> ((f64, f64), (f64, f64)) {
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
pub(crate) fn integer_x(fig: &Figure) -> bool {
    let mut xs = fig.marks.iter().flat_map(mark_points).map(|p| p.0).peekable();
    xs.peek().is_some() && xs.all(|x| x == x.round() && x.abs() < 1e15)
}

/// Margins measured from the labels, the range grown until every label,
/// marker and turn fits inside the plot, and (for equal aspect) the shorter
/// span widened; repeated, because the ticks depend on the ranges.
pub(crate) fn layout(fig: &Figure, place: Place) -> Layout {
    let ((mut x0, mut x1), (mut y0, mut y1)) = data_range(fig);
    let integer = integer_x(fig);
    let top = if fig.title.is_empty() { 20.0 } else { 56.0 };
    let axis_room = 6.0 + 8.0 + TICK_SIZE + 16.0 + LABEL_SIZE + 12.0;
    let (mut left, mut right) = (120.0, 30.0);
    let mut l = None;
    let mut legend = None;
    for _ in 0..8 {
        let bar = fig.color_bar.as_ref().map(|b| text_width(&b.label, LEGEND_SIZE));
        legend = (!fig.legend.is_empty() || bar.is_some()).then(|| match place {
            Place::Below => legend_size(&fig.legend, bar, fig.width - left - right),
            // Beside the plot, in columns rather than past the figure's foot,
            // leaving the plot at least half the width.
            Place::Right | Place::Outside => {
                legend_beside(&fig.legend, bar, fig.height - top - LEGEND_FOOT, 0.5 * fig.width)
            }
            Place::Inside => legend_size(&fig.legend, bar, 0.0),
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
        let bar_title = fig.color_bar.as_ref();
        l.rows = rows;
        // A colour bar's block widened for its title ends inside the figure
        // (the margins were measured after the legend was sized).
        let fit = |x: f64| if bar_title.is_some() { lw.min(fig.width - x - 10.0) } else { lw };
        l.legend = Some(match place {
            Place::Right | Place::Outside => (l.left + l.w + 20.0, top, fit(l.left + l.w + 20.0), lh),
            Place::Below => (l.left, top + l.h + axis_room + 4.0, fit(l.left), lh),
            Place::Inside => best_corner(fig, &l, lw, lh),
        });
    }
    l
}

/// The box a mark covers (px: left, right, top, bottom), counting its
/// text, markers, heads and line width.
pub(crate) fn extent(mark: &Mark, l: &Layout, log_y: bool) -> Option<(f64, f64, f64, f64)> {
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
pub(crate) fn head(width: f64) -> f64 {
    3.0 * width + 8.0
}

/// The corner of the plot where a `lw` × `lh` legend covers the fewest drawn points.
pub(crate) fn best_corner(fig: &Figure, l: &Layout, lw: f64, lh: f64) -> (f64, f64, f64, f64) {
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
pub(crate) fn drawn_pixels(fig: &Figure, l: &Layout) -> Vec<(f64, f64)> {
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

/// The positions a mark occupies (data units).
pub(crate) fn mark_points(mark: &Mark) -> Vec<(f64, f64)> {
    match mark {
        Mark::Path { points, .. } => points.clone(),
        Mark::Dot { at, .. } | Mark::Turn { at, .. } | Mark::Label { at, .. } => vec![*at],
        Mark::Arrow { from, to, .. } => vec![*from, *to],
    }
}

/// Roughly how wide `text` is in DejaVu Sans at `size` px (slightly generous).
pub(crate) fn text_width(text: &str, size: f64) -> f64 {
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

/// `fig` no taller than its drawing at equal scale needs (nor shorter than
/// its legend or 400 px), with the legend beside or under the plot,
/// whichever draws it larger; `height` bounds the figure, less any legend under the plot.
pub(crate) fn fit_height(fig: &Figure) -> Figure {
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
