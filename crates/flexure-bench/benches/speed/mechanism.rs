//! Mechanism equilibria.

use criterion::Criterion;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings as MechanismSettings, solve};
use std::hint::black_box;

pub fn run(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/finger.toml");
    let m = from_toml(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut g = c.benchmark_group("mechanism");
    g.bench_function("finger_equilibrium", |b| b.iter(|| solve(black_box(&m), &MechanismSettings::default()).unwrap()));
    g.finish();
}
