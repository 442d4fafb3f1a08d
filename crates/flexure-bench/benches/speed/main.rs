//! Speed against the floor: five sin/cos pairs, the cost of one evaluation's
//! trigonometry; and against exact beam theory solving the same task.
//!
//! `cargo bench -p flexure-bench --bench speed`; ratios are in BENCHMARKS.md.
//! One module per area, each a criterion group function `run`.

use criterion::{criterion_group, criterion_main};

mod batch;
mod contact;
mod dynamics;
mod joint;
mod linalg;
mod mechanism;
mod reference;
mod rod;
mod spatial;
mod spatial_mechanism;
mod statics;

/// Seeded inputs, cycled so each call sees different arguments.
pub fn inputs(count: usize, width: usize) -> Vec<f64> {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    (0..count * width)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

criterion_group!(
    benches,
    joint::run,
    statics::run,
    batch::run,
    mechanism::run,
    contact::run,
    reference::run,
    rod::run,
    dynamics::run,
    spatial::run,
    spatial_mechanism::run,
    linalg::run
);
criterion_main!(benches);
