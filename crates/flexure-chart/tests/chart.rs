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
