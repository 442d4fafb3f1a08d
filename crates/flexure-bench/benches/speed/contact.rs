//! Equilibria with contact (`mechanism/statics/contact.rs`), each beside
//! the exact elastica with contact unknowns solving the same problem
//! (`reference::elastica::contact`): a unit strip (L = EI = 1, order 6)
//! whose tip a moment of −0.1 N·m presses onto a floor 0.01 below it (the
//! propped cantilever), and one whose span a tip force of −3 N presses onto
//! a circular post (the contact moves along the span), each solved from no
//! load in a workspace kept between solves, the path found each time.

use criterion::Criterion;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings, Workspace, solve_with};
use flexure::reference::elastica::{self, contact::Obstacle};
use flexure::{Flexure, TipLoad};
use std::hint::black_box;

fn strip(geom: &str, load: &str) -> String {
    format!(
        "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 1.0\nei = 1.0\norder = 6\n\
         [[force]]\nbody = \"tip\"\nat = [0.0, 0.0]\n{load}\n[[geom]]\nname = \"floor\"\nbody = \"ground\"\n{geom}"
    )
}

pub fn run(c: &mut Criterion) {
    let floor = "shape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n";
    let post = "shape = \"circle\"\norigin = [0.55, -0.3]\nradius = 0.25\n";
    let cases = [
        (
            "propped_tip",
            strip(floor, "moment = -0.1"),
            Obstacle::half_plane([0.0, -0.01], [0.0, 1.0]),
            TipLoad { moment: -0.1, fx: 0.0, fy: 0.0 },
        ),
        (
            "post_span",
            strip(post, "force = [0.0, -3.0]"),
            Obstacle::circle([0.55, -0.3], 0.25),
            TipLoad { moment: 0.0, fx: 0.0, fy: -3.0 },
        ),
    ];
    let unit = Flexure::new(1.0, 1.0, 3).unwrap();
    let mut g = c.benchmark_group("contact");
    g.sample_size(20);
    for (name, text, obstacle, load) in &cases {
        let m = from_toml(text).unwrap();
        let mut work = Workspace::new(&m);
        g.bench_function(*name, |b| b.iter(|| solve_with(black_box(&m), &Settings::default(), &mut work).unwrap()));
        let (obstacles, path) = ([*obstacle], [*load]);
        g.bench_function(format!("{name}_exact"), |b| {
            b.iter(|| elastica::contact(black_box(&unit), &obstacles, 0.0, &path, &Default::default()).unwrap())
        });
    }
    g.finish();
}
