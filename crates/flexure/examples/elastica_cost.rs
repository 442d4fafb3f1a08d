//! Cost of the exact elastica (L = EI = 1) as the load grows: at the
//! issue's transverse forces, and along fixed load directions scaled until
//! the tip turns by given angles. `cargo run --release --example elastica_cost`.
//! Wall-clock times vary from run to run; compare them within one run.

use flexure::reference::elastica;
use flexure::{Flexure, TipLoad};
use std::time::Instant;

/// Mean milliseconds per solve, over repetitions filling about 0.2 s.
fn time(f: &Flexure, load: &TipLoad) -> f64 {
    let mut reps = 0;
    let t = Instant::now();
    while t.elapsed().as_secs_f64() < 0.2 || reps < 3 {
        let _ = std::hint::black_box(elastica::deflect(f, std::hint::black_box(load), &Default::default()));
        reps += 1;
    }
    t.elapsed().as_secs_f64() * 1e3 / reps as f64
}

fn report(f: &Flexure, name: &str, load: &TipLoad) {
    match elastica::deflect(f, load, &Default::default()) {
        Ok(s) => println!(
            "{name:>26}: tip {:+8.2}°  {:8.3} ms  {:3} load steps  stable {}",
            s.pose.phi.to_degrees(),
            time(f, load),
            s.load_steps,
            s.stable
        ),
        Err(e) => println!("{name:>26}: {e}"),
    }
}

fn main() {
    let f = Flexure::new(1.0, 1.0, 3).unwrap();
    println!("transverse tip force Fy:");
    for fy in [3.0, 5.0, 10.0, 50.0] {
        report(&f, &format!("Fy = {fy}"), &TipLoad { moment: 0.0, fx: 0.0, fy });
    }
    // Loads s·(M, Fx, Fy), s found by bisection so that the tip turns by
    // each angle (each direction's tip angle grows with s).
    let directions: [(&str, [f64; 3], &[f64]); 3] = [
        ("s·(0, 0, 1): transverse force", [0.0, 0.0, 1.0], &[45.0, 80.0, 89.0]),
        ("s·(0, -1, 0.01): column", [0.0, -1.0, 0.01], &[45.0, 90.0, 135.0, 170.0]),
        ("s·(1, -1, 0): moment and compression", [1.0, -1.0, 0.0], &[45.0, 90.0, 180.0, 270.0]),
    ];
    for (name, d, targets) in directions {
        println!("{name}:");
        let load = |s: f64| TipLoad { moment: s * d[0], fx: s * d[1], fy: s * d[2] };
        let below = |s: f64, target: f64| {
            elastica::deflect(&f, &load(s), &Default::default()).is_ok_and(|r| r.pose.phi.to_degrees().abs() < target)
        };
        for &target in targets {
            let (mut lo, mut hi) = (0.0, 1.0);
            while below(hi, target) {
                (lo, hi) = (hi, 2.0 * hi);
            }
            for _ in 0..50 {
                let mid = 0.5 * (lo + hi);
                if below(mid, target) { lo = mid } else { hi = mid }
            }
            report(&f, &format!("{target}° at s = {:.4}", hi), &load(hi));
        }
    }
}
