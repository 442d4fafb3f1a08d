//! The error-estimate validation sweep: random tip loads on the order-3
//! model, each answer's estimated error beside its true error against the
//! exact elastica. Prints the generated part of `VALIDATION.md`, all before
//! its `## PRB` section; the sections from there on are written by hand
//! (the PRB fits and the spatial flexure), so regenerate with
//!
//! ```sh
//! { cargo run --release -p flexure --example validation; sed -n '/^## PRB/,$p' VALIDATION.md; } > VALIDATION.new
//! mv VALIDATION.new VALIDATION.md
//! ```

use flexure::estimate::{Accuracy, deflect_auto, deflect_error};
use flexure::reference::elastica;
use flexure::section::{Profile, Section};
use flexure::{Flexure, StaticsData, TipLoad, deflect};

/// SplitMix64: a seeded, reproducible stream in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.next()).exp()
    }
}

/// One random case: a family name, the load and the rest curvature.
fn case(rng: &mut Rng) -> (&'static str, TipLoad, [f64; 3]) {
    let kappa = if rng.next() < 0.25 {
        [rng.uniform(-2.0, 2.0), rng.uniform(-1.0, 1.0), rng.uniform(-0.5, 0.5)]
    } else {
        [0.0; 3]
    };
    let family = (rng.next() * 4.0) as usize;
    let (name, load) = match family {
        0 => ("moment", TipLoad { moment: rng.uniform(-25.0, 25.0), fx: 0.0, fy: 0.0 }),
        1 => {
            let p = rng.log_uniform(0.1, 30.0);
            ("force", TipLoad::polar(0.0, p, rng.uniform(0.0, std::f64::consts::TAU)))
        }
        2 => {
            let side = if rng.next() < 0.5 { -1.0 } else { 1.0 };
            ("compression", TipLoad { moment: 0.0, fx: -rng.uniform(1.0, 40.0), fy: side * rng.log_uniform(1e-3, 0.5) })
        }
        _ => {
            let p = rng.log_uniform(0.1, 20.0);
            ("mixed", TipLoad::polar(rng.uniform(-8.0, 8.0), p, rng.uniform(0.0, std::f64::consts::TAU)))
        }
    };
    (name, load, kappa)
}

struct Row {
    angle: f64,
    true_position: f64,
    true_angle: f64,
    estimate_position: f64,
    flagged: bool,
}

/// The sweep's outcome: one row per compared case, and the cases left out.
pub struct Sweep {
    rows: Vec<Row>,
    cases: usize,
    model_failed: usize,
    exact_failed: usize,
    exact_unstable: usize,
}

impl Sweep {
    /// (cases whose true position error exceeds 1e-3 L, of them those estimated within 3×).
    pub fn honesty(&self) -> (usize, usize) {
        let large: Vec<&Row> = self.rows.iter().filter(|r| r.true_position > 1e-3).collect();
        let honest =
            large.iter().filter(|r| (1.0 / 3.0..=3.0).contains(&(r.estimate_position / r.true_position))).count();
        (large.len(), honest)
    }

    /// Cases truly outside the target but not flagged.
    pub fn missed(&self, t: &Accuracy) -> usize {
        self.rows.iter().filter(|r| !r.flagged && (r.true_position > t.position || r.true_angle > t.angle)).count()
    }

    /// Cases compared, and cases left out.
    pub fn counts(&self) -> (usize, usize) {
        (self.rows.len(), self.model_failed + self.exact_failed + self.exact_unstable)
    }
}

/// Runs `cases` seeded random cases.
pub fn sweep(cases: usize) -> Sweep {
    let mut rng = Rng(20261130);
    let target = Accuracy::default();
    let mut out = Sweep { rows: Vec::new(), cases, model_failed: 0, exact_failed: 0, exact_unstable: 0 };
    for _ in 0..cases {
        let (_name, load, kappa) = case(&mut rng);
        let f = Flexure::new(1.0, 1.0, 3).and_then(|f| f.with_rest(&kappa)).expect("a valid flexure");
        let mut data = StaticsData::new(&f);
        if deflect(&f, &load, &mut data, &Default::default()).is_err() {
            out.model_failed += 1;
            continue;
        }
        let alpha = data.alpha().to_vec();
        let model = data.pose_root_tip();
        let Ok(e) = deflect_error(&f, &load, &alpha, &target) else {
            out.model_failed += 1;
            continue;
        };
        let exact = match elastica::deflect(&f, &load, &Default::default()) {
            Ok(s) if s.stable => s.pose,
            Ok(_) => {
                out.exact_unstable += 1;
                continue;
            }
            Err(_) => {
                out.exact_failed += 1;
                continue;
            }
        };
        out.rows.push(Row {
            angle: exact.phi.abs(),
            true_position: (model.x - exact.x).hypot(model.y - exact.y),
            true_angle: (model.phi - exact.phi).abs(),
            estimate_position: e.position,
            // The tip's part of the flag (the peak-curvature part is not compared here).
            flagged: e.position > target.position * f.length() || e.angle > target.angle,
        });
    }
    out
}

fn main() {
    let cases: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(2000);
    let s = sweep(cases);
    print_report(&s.rows, s.cases, s.model_failed, s.exact_failed, s.exact_unstable, &Accuracy::default());
    taper_sweep(&Accuracy::default());
}

/// The taper sweep of `tests/estimate.rs` (`taper_sweep_is_met_or_flagged`):
/// a pure tip moment on a linear taper of EI, against $\phi = M\int ds/EI$.
fn taper_sweep(t: &Accuracy) {
    println!("\n## Steep tapers: the order cap\n");
    println!(
        "A pure tip moment M on a flexure of L = 1 whose EI falls linearly from 1 at the root to r at the tip, \
         for 23 ratios r = 10^(−6k/22) (k = 0…22, 1 down to 1e-6) and M = 0.1, 0.3, 1 N·m: 69 cases. \
         The exact tip angle is the closed form φ = M∫ds/EI = M ln r/(r − 1) (the same moment in every \
         section). \"Order 64\" is the model at the highest order, its estimate against the exact elastica \
         (no model refines order 64); \"--order auto\" is `deflect_auto` from order 3: the order that met \
         the target (1 % of L, 1°, 1 % of the peak curvature), or \"refused\" when even order 64 misses it. \
         `cargo test -p flexure --test all taper_sweep` checks that every answer is within the target or \
         flagged (refused), and that the estimate at order 64 is the true angle error to 1e-6 of φ.\n"
    );
    println!(
        "| r = EI tip/root | M (N·m) | exact φ (rad) | order 64 φ | its error (°) | estimated (°) | flagged | --order auto |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let (mut refused, mut off, mut flagged) = (0, 0, 0);
    for k in 0..23 {
        let r = 10f64.powf(-6.0 * k as f64 / 22.0);
        let section = Section::given(Profile::Linear { root: 1.0, tip: r }).unwrap();
        let f = Flexure::new(1.0, 1.0, 3).unwrap().with_section(section.clone()).unwrap();
        let cap = Flexure::new(1.0, 1.0, 64).unwrap().with_section(section).unwrap();
        for m in [0.1, 0.3, 1.0] {
            let exact = if k == 0 { m } else { m * r.ln() / (r - 1.0) };
            let load = TipLoad { moment: m, fx: 0.0, fy: 0.0 };
            let mut data = StaticsData::new(&cap);
            let row = deflect(&cap, &load, &mut data, &Default::default())
                .and_then(|_| deflect_error(&cap, &load, data.alpha(), t));
            let auto = match deflect_auto(&f, &load, t) {
                Ok((used, _, _)) => format!("order {}", used.order()),
                Err(_) => {
                    refused += 1;
                    "refused".into()
                }
            };
            match row {
                Ok(e) => {
                    let phi = data.pose_root_tip().phi;
                    off += usize::from((phi - exact).abs() > t.angle);
                    flagged += usize::from(e.flagged);
                    println!(
                        "| {r:.3e} | {m} | {exact:.5} | {phi:.5} | {:.3} | {:.3} | {} | {auto} |",
                        (phi - exact).abs().to_degrees(),
                        e.angle.to_degrees(),
                        if e.flagged { "yes" } else { "no" }
                    );
                }
                Err(e) => println!("| {r:.3e} | {m} | {exact:.5} | failed: {e} | | | | {auto} |"),
            }
        }
    }
    println!(
        "\nOrder 64 is more than 1° off in {off} of the 69 cases and flagged in {flagged} (the others for their \
         peak curvature); `--order auto` is refused in {refused} and meets the target in the rest. Before the \
         cap's estimate was against the exact elastica, it was the order-64 model against itself with more \
         points, about 0 for these answers, so those {off} were not flagged for their angle (not measured \
         here: this report runs the code as it is)."
    );
}

fn print_report(rows: &[Row], cases: usize, model_failed: usize, exact_failed: usize, unstable: usize, t: &Accuracy) {
    println!("# Validation of the error estimates\n");
    println!(
        "The sections before `## PRB` are generated by `cargo run --release -p flexure --example validation` \
         (see its docs for keeping the hand-written sections after them) \
         ({cases} seeded random cases; L = EI = 1, order 3, 5 points, the default accuracy target of \
         1 % of L and 1°). Each case is a tip load — a pure moment up to 25 EI/L, a force of any direction \
         up to 30 EI/L², compression up to 16× Euler's load with a small lateral imperfection, or a moment \
         with a force — on a straight flexure or, in a quarter of the cases, one with random rest curvature. \
         The model's answer and its error estimate are compared with the exact elastica (shooting, \
         followed from rest). \"Flagged\" here is the tip's part of the flag (position or angle); an \
         answer is also flagged when its peak stress or curvature misses the target.\n"
    );
    println!(
        "Compared: {} cases. Left out: {model_failed} where the model solver failed (it reports why), \
         {exact_failed} where the exact solver failed, {unstable} where the exact equilibrium reached \
         from rest is unstable (no reference to compare with).\n",
        rows.len()
    );
    println!("## Error against tip angle\n");
    println!(
        "| exact tip angle | cases | median position error (L) | max position error (L) | max angle error (°) | flagged |"
    );
    println!("|---|---|---|---|---|---|");
    let bins = [(0.0, 45.0), (45.0, 90.0), (90.0, 180.0), (180.0, 360.0), (360.0, 720.0), (720.0, f64::INFINITY)];
    for (lo, hi) in bins {
        let mut sel: Vec<&Row> =
            rows.iter().filter(|r| r.angle.to_degrees() >= lo && r.angle.to_degrees() < hi).collect();
        if sel.is_empty() {
            continue;
        }
        sel.sort_by(|a, b| a.true_position.total_cmp(&b.true_position));
        let median = sel[sel.len() / 2].true_position;
        let max_p = sel.last().map_or(0.0, |r| r.true_position);
        let max_a = sel.iter().map(|r| r.true_angle.to_degrees()).fold(0.0, f64::max);
        let flagged = sel.iter().filter(|r| r.flagged).count();
        let range = if hi.is_finite() { format!("{lo:.0}°–{hi:.0}°") } else { format!("≥ {lo:.0}°") };
        println!("| {range} | {} | {median:.1e} | {max_p:.1e} | {max_a:.2} | {flagged} |", sel.len());
    }
    let misses = |r: &Row| r.true_position > t.position || r.true_angle > t.angle;
    let count =
        |flagged: bool, missed: bool| rows.iter().filter(|r| r.flagged == flagged && misses(r) == missed).count();
    println!("\n## Flagged against true error\n");
    println!("| | truly within 1 % L and 1° | truly outside |");
    println!("|---|---|---|");
    println!("| flagged | {} | {} |", count(true, false), count(true, true));
    println!("| not flagged | {} | {} |", count(false, false), count(false, true));
    let large: Vec<&Row> = rows.iter().filter(|r| r.true_position > 1e-3).collect();
    let honest = large.iter().filter(|r| (1.0 / 3.0..=3.0).contains(&(r.estimate_position / r.true_position))).count();
    let worst_low = large.iter().map(|r| r.estimate_position / r.true_position).fold(f64::INFINITY, f64::min);
    let worst_high = large.iter().map(|r| r.estimate_position / r.true_position).fold(0.0, f64::max);
    println!("\n## Honesty\n");
    println!(
        "Of the {} cases whose true position error exceeds 1e-3 L, the estimate is within 3× of the true \
         error in {honest} ({:.1} %). The ratio estimate/true ranges from {worst_low:.3} to {worst_high:.3}.",
        large.len(),
        100.0 * honest as f64 / large.len().max(1) as f64
    );
}
