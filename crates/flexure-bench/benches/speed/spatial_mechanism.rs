//! Spatial mechanism equilibria: the planar `mechanism/chain_10` built in
//! space (ten spatial flexures of orders 3 in series, 90 coordinates,
//! $EI$ = $GJ$ = 1 N·m², total length 1 m) under the same 2 N transverse tip
//! force, and under that force with an out-of-plane 1 N beside it; against
//! `mechanism/chain_10` of the same run. And one blade at the order cap.

use criterion::Criterion;
use flexure::mechanism::spatial::{
    SpatialBody, SpatialJointKind, SpatialJointSpec, SpatialMechanism, SpatialPointLoad,
};
use flexure::mechanism::statics::solve;
use flexure::section::SpatialSection;
use flexure::spatial::SpatialFlexure;
use nalgebra::{Isometry3, Point3, Vector3, Vector6};
use std::hint::black_box;

fn chain(n: usize, force: [f64; 3]) -> SpatialMechanism {
    let length = 1.0 / n as f64;
    let mut bodies = vec![SpatialBody::massless("ground")];
    let mut joints = Vec::new();
    for i in 0..n {
        bodies.push(SpatialBody::massless(&format!("b{i}")));
        let f = SpatialFlexure::new(length, SpatialSection::uniform(1.0, 1.0, 1.0).unwrap(), [3, 3, 3]).unwrap();
        joints.push(SpatialJointSpec {
            name: format!("j{i}"),
            kind: SpatialJointKind::Flexure(Box::new(f)),
            parent: i,
            child: i + 1,
            origin: Isometry3::identity(),
            offset: 0,
            damping: 0.0,
            auto_order: false,
            report: Default::default(),
        });
    }
    let tip = SpatialPointLoad {
        name: "tip".into(),
        body: n,
        at: Point3::origin(),
        wrench: Vector6::new(0.0, 0.0, 0.0, force[0], force[1], force[2]),
    };
    SpatialMechanism::new(bodies, joints, vec![], vec![tip], vec![], Vector3::zeros()).unwrap()
}

/// A spatial file with one blade at the order cap.
const BLADE_ORDER_64: &str = "dimension = 3
[[joint]]
name = \"blade\"
kind = \"flexure\"
parent = \"ground\"
child = \"tip\"
length = 0.03
modulus = 200e9
width = 0.01
thickness = 0.0003
poisson = 0.3
orders = [64, 64, 64]
[[force]]
name = \"push\"
body = \"tip\"
force = [0.0, 1.0, 0.0]
";

pub fn run(c: &mut Criterion) {
    let mut g = c.benchmark_group("spatial_mechanism");
    for (name, m) in [("chain_10", chain(10, [0.0, 2.0, 0.0])), ("chain_10_out_of_plane", chain(10, [0.0, 2.0, 1.0]))] {
        g.sample_size(10);
        g.bench_function(name, |b| b.iter(|| solve(black_box(&m), &Default::default()).unwrap()));
    }
    // The order cap (issue 39): one spring-steel blade, 30 mm long, at
    // orders [64, 64, 64] (192 coordinates, 1008 subintervals) under a 1 N
    // tip force across it (its tip turns by about 0.1 rad).
    let blade = flexure::mechanism::file::spatial_from_toml(BLADE_ORDER_64).unwrap();
    g.bench_function("blade_order_64", |b| b.iter(|| solve(black_box(&blade), &Default::default()).unwrap()));
    g.finish();
}
