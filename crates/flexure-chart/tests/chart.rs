//! The chart on its own, through its public API: what it refuses, how
//! figures stack, and what a reader sees (round tick labels, legends, the
//! smallest text). The command line's `tests/figures.rs` checks the figures
//! `reproduce` and `draw` make with it.

use flexure_chart::{
    COLORS, Chart, Color, Entry, Figure, MIN_TEXT, Mark, Marker, Place, Series, Stroke, Swatch, chart_figure, ramp,
    render, stack,
};

fn chart(log_y: bool) -> Chart<'static> {
    Chart { title: "Error against order", x_label: "order", y_label: "error (m)", log_y, equal_aspect: false }
}

/// Every `font-size="…"` in the SVG.
fn font_sizes(svg: &str) -> Vec<f64> {
    svg.split("font-size=\"").skip(1).filter_map(|r| r.split('"').next()?.parse().ok()).collect()
}

#[test]
fn a_chart_names_its_curves_and_reads_round_ticks() {
    let points: Vec<(f64, f64)> = (1..=8).map(|n| (f64::from(n), 10f64.powi(-n))).collect();
    let series = [
        Series::line("model", points.clone(), COLORS[0]).marked(Marker::Square, 1, 0),
        Series::dots("reference", points, COLORS[1]).hollow(),
    ];
    let svg = render(&chart_figure(&chart(true), &series).unwrap()).unwrap();
    for text in ["Error against order", "order", "error (m)", "model", "reference", "10⁻"] {
        assert!(svg.contains(text), "{text} missing");
    }
    assert!(!svg.contains("9.99999"), "a tick is not round");
    let sizes = font_sizes(&svg);
    assert!(!sizes.is_empty() && sizes.iter().all(|&s| s >= MIN_TEXT), "{sizes:?}");
}

#[test]
fn a_point_that_is_not_finite_is_refused_by_name() {
    let series = [Series::line("model", vec![(0.0, 1.0), (1.0, f64::NAN)], COLORS[0])];
    let e = chart_figure(&chart(false), &series).unwrap_err();
    assert!(e.contains("point 1 of model"), "{e}");
    let mut fig = Figure::new("t", "x", "y");
    fig.marks.push(Mark::Arrow { from: (0.0, 0.0), to: (f64::INFINITY, 1.0), color: COLORS[0], width: 2.0 });
    assert!(render(&fig).unwrap_err().contains("mark 0"));
    let mut fig = Figure::new("t", "x", "y");
    fig.width = 50.0;
    assert!(render(&fig).unwrap_err().contains("outside"));
}

#[test]
fn stacked_figures_keep_their_own_clip_paths() {
    let series = [Series::line("a", vec![(0.0, 0.0), (1.0, 1.0)], COLORS[0])];
    let one = chart_figure(&chart(false), &series).unwrap();
    let mut two = one.clone();
    two.height = 300.0;
    two.place = Place::Outside;
    let svg = stack(&[one, two]).unwrap();
    assert!(svg.contains(r#"id="plot-0""#) && svg.contains(r#"id="plot-1""#) && !svg.contains(r#"id="plot""#));
    assert!(
        svg.starts_with(r#"<svg xmlns="http://www.w3.org/2000/svg" width="960.00" height="940.00""#),
        "{}",
        &svg[..120]
    );
}

#[test]
fn a_drawing_is_one_scale_on_both_axes() {
    let mut fig = Figure::new("a square", "x (m)", "y (m)");
    fig.equal_aspect = true;
    let square = vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    fig.marks.push(Mark::Path {
        points: square,
        stroke: Some(Stroke::solid(COLORS[2], 1.5)),
        fill: None,
        closed: true,
    });
    fig.legend.push(Entry { swatch: Swatch::Note, label: "a note".into() });
    let svg = render(&fig).unwrap();
    // The polygon's corners in px: its width and height are equal.
    let points = svg.split("<polygon points=\"").nth(1).unwrap().split('"').next().unwrap();
    let p: Vec<(f64, f64)> = points
        .split(' ')
        .map(|xy| {
            let (x, y) = xy.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect();
    let (w, h) = ((p[1].0 - p[0].0).abs(), (p[2].1 - p[1].1).abs());
    assert!(w > 100.0 && (w - h).abs() < 0.2, "{w} × {h}");
    assert!(svg.contains("a note"));
}

#[test]
fn the_ramp_runs_dark_to_light_and_clamps() {
    assert_eq!(ramp(-1.0), ramp(0.0));
    assert_eq!(ramp(2.0), ramp(1.0));
    assert_eq!(ramp(f64::NAN), ramp(0.0));
    let light = |c: Color| u32::from(c.0) + u32::from(c.1) + u32::from(c.2);
    assert!((0..10).all(|k| light(ramp(f64::from(k) / 10.0)) <= light(ramp(f64::from(k + 1) / 10.0))));
    assert_eq!(Color(0, 0, 0).tint(1.0), Color(255, 255, 255));
}

/// Each `<text … class="legend">`'s label, x and baseline y (px), and the
/// SVG's width and height.
fn legend_texts(svg: &str) -> (Vec<(String, f64, f64)>, f64, f64) {
    let attr = |tag: &str, name: &str| -> f64 {
        tag.split(&format!(" {name}=\"")).nth(1).and_then(|r| r.split('"').next()?.parse().ok()).unwrap_or(f64::NAN)
    };
    let head = svg.lines().next().unwrap_or_default();
    let texts = svg
        .split("<text ")
        .skip(1)
        .filter(|t| t.contains(r#"class="legend""#))
        .map(|t| {
            let (tag, rest) = t.split_once('>').unwrap_or_default();
            let label = rest.split("</text>").next().unwrap_or_default().to_string();
            let tag = format!(" {tag}");
            (label, attr(&tag, "x"), attr(&tag, "y"))
        })
        .collect();
    (texts, attr(head, "width"), attr(head, "height"))
}

/// A legend beside the plot with more entries than one column holds (60
/// series in a 1200 × 420 chart, as a motion chart of 20 bodies' three
/// components): every entry is drawn, and every one inside the figure (its
/// baseline at least the text's descent, 0.3 of the 16 px size, above the
/// foot; its start inside the width; measured here by a generous 0.72 em a
/// character, the widest letter's width). The legend takes columns, and the
/// figure grows when three are not enough. A short legend stays in one
/// column, so a figure whose legend fitted is unchanged.
#[test]
fn a_long_legend_beside_the_plot_stays_inside_the_figure() {
    let series: Vec<Series> = (0..60)
        .map(|i| {
            let points = (0..20).map(|k| (f64::from(k), f64::from(k * (i + 1)).sin())).collect();
            Series::line(
                &format!("body_{} θ{}", i / 3, ["x", "y", "z"][i as usize % 3]),
                points,
                COLORS[i as usize % 6],
            )
        })
        .collect();
    for count in [4, 20, 40, 60] {
        let mut fig = chart_figure(&chart(false), &series[..count]).unwrap();
        (fig.width, fig.height, fig.place) = (1200.0, 420.0, Place::Outside);
        let svg = render(&fig).unwrap();
        let (texts, width, height) = legend_texts(&svg);
        assert_eq!(texts.len(), count, "every entry is drawn");
        for (label, x, y) in &texts {
            let right = x + 0.72 * 16.0 * label.chars().count() as f64;
            assert!(*y + 0.3 * 16.0 <= height && *y >= 16.0, "{count} entries: {label} at y = {y} in {height}");
            assert!(*x >= 0.0 && right <= width, "{count} entries: {label} from x = {x} to {right} in {width}");
        }
        let columns = {
            let mut xs: Vec<f64> = texts.iter().map(|t| t.1).collect();
            xs.dedup();
            xs.len()
        };
        match count {
            4 => assert!(columns == 1 && height == 420.0, "{columns} columns, {height} px"),
            20 | 40 => assert!(columns > 1 && height == 420.0, "{count}: {columns} columns, {height} px"),
            _ => assert!(columns == 3 && height > 420.0, "{columns} columns, {height} px"),
        }
    }
}

/// A colour bar's title longer than its bar (a drawing's yield strengths of
/// many flexures) stays inside the legend block and the figure, below and
/// beside the plot: set smaller, at the chart's own measure of its text
/// (0.6 em a lowercase letter); a title that fits keeps the legend's size.
#[test]
fn a_long_colour_bar_title_stays_inside_the_figure() {
    let bar_label = |svg: &str| -> (f64, f64) {
        let tag = svg.split("<text ").find(|t| t.contains(r#"class="bar-label""#)).expect("a bar label");
        let attr = |name: &str| -> f64 {
            tag.split(&format!("{name}=\"")).nth(1).and_then(|r| r.split('"').next()?.parse().ok()).unwrap()
        };
        (attr("x"), attr("font-size"))
    };
    for (label, long) in [("abcdeghkno".repeat(20), true), ("stress".to_string(), false)] {
        for place in [Place::Below, Place::Outside] {
            let mut fig = Figure::new("stress", "x (m)", "y (m)");
            fig.marks.push(Mark::Dot {
                at: (0.0, 0.0),
                shape: Marker::Circle,
                radius: 3.0,
                color: COLORS[0],
                filled: true,
            });
            fig.marks.push(Mark::Dot {
                at: (1.0, 1.0),
                shape: Marker::Circle,
                radius: 3.0,
                color: COLORS[0],
                filled: true,
            });
            fig.legend.push(Entry { swatch: Swatch::Note, label: "a note".into() });
            fig.color_bar = Some(flexure_chart::ColorBar { label: label.clone(), lo: 0.0, hi: 1.0, marks: vec![] });
            (fig.width, fig.height, fig.place) = (800.0, 420.0, place);
            let svg = render(&fig).unwrap();
            let width: f64 = svg.split(" width=\"").nth(1).and_then(|r| r.split('"').next()?.parse().ok()).unwrap();
            let (x, size) = bar_label(&svg);
            let right = x + 0.6 * size * label.chars().count() as f64;
            assert!(right <= width, "{place:?}: the title runs to {right} px in a {width} px figure");
            assert_eq!(size < 16.0, long, "{place:?}: set at {size} px");
        }
    }
}
