//! Mechanism equilibria: a finger, serial chains of 10 and 100 flexures, an
//! eight-leg stage and the parallelogram example, each solved from no load
//! in a workspace kept between solves (`solve_with`).

use criterion::Criterion;
use flexure::mechanism::Mechanism;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings as MechanismSettings, Workspace, solve_with};
use std::fmt::Write;
use std::hint::black_box;

fn example(name: &str) -> String {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).unwrap()
}

/// A cantilever of total length 1 m and $EI$ = 1 N·m² cut into `n` flexures
/// of order 3 in series, each welded tip to root through its own body,
/// under a transverse tip force of 2 N: $FL^2/EI = 2$ turns the tip by
/// about 0.8 rad (the linear estimate $FL^2/2EI$ is 1 rad), so the
/// continuation takes several steps.
fn chain(n: usize) -> Mechanism {
    let mut text = String::new();
    let length = 1.0 / n as f64;
    for i in 0..n {
        let parent = if i == 0 { "ground".to_string() } else { format!("b{}", i - 1) };
        writeln!(text, "[[joint]]\nname = \"j{i}\"\nkind = \"flexure\"\nparent = \"{parent}\"\nchild = \"b{i}\"")
            .unwrap();
        writeln!(text, "length = {length}\nei = 1.0\n").unwrap();
    }
    writeln!(text, "[[force]]\nname = \"tip\"\nbody = \"b{}\"\nat = [0.0, 0.0]\nforce = [0.0, 2.0]", n - 1).unwrap();
    from_toml(&text).unwrap()
}

/// Eight parallel legs (order 3, 0.05 m, $EI$ = 2e-3 N·m², 0.04 m apart,
/// as in `examples/four_leg_stage.toml`) welded to one stage, under a
/// lateral 4 N and an axial push of 20 N at the stage's middle: a lateral
/// stiffness of $8\cdot 12EI/L^3$ = 1536 N/m, and a push at 5/16 of the
/// 64 N buckling load.
fn stage(legs: usize) -> Mechanism {
    let mut text = String::new();
    for i in 0..legs {
        let child = if i == 0 { "stage".to_string() } else { format!("tip{i}") };
        writeln!(text, "[[joint]]\nname = \"leg{i}\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"{child}\"")
            .unwrap();
        writeln!(text, "origin = [{}, 0.0, 1.5707963267948966]\nlength = 0.05\nei = 2.0e-3\n", 0.04 * i as f64)
            .unwrap();
    }
    for i in 1..legs {
        writeln!(text, "[[weld]]\na = \"stage\"\na_origin = [0.0, {}, 0.0]\nb = \"tip{i}\"\n", -0.04 * i as f64)
            .unwrap();
    }
    let middle = -0.02 * (legs - 1) as f64;
    writeln!(text, "[[force]]\nname = \"push\"\nbody = \"stage\"\nat = [0.0, {middle}]\nforce = [4.0, -20.0]").unwrap();
    from_toml(&text).unwrap()
}

pub fn run(c: &mut Criterion) {
    let finger = from_toml(&example("finger.toml")).unwrap();
    // examples/parallelogram.toml's axial 1 N push, plus a lateral 0.5 N.
    let parallelogram =
        from_toml(&example("parallelogram.toml").replace("force = [0.0, -1.0]", "force = [0.5, -1.0]")).unwrap();
    assert_eq!(
        parallelogram.loads().force,
        vec![flexure::space::Wrench { moment: 0.0, fx: 0.5, fy: -1.0 }],
        "the example's push line changed"
    );
    let cases = [
        ("finger_equilibrium", finger),
        ("chain_10", chain(10)),
        ("chain_100", chain(100)),
        ("stage_8", stage(8)),
        ("parallelogram", parallelogram),
    ];
    let mut g = c.benchmark_group("mechanism");
    for (name, m) in &cases {
        // The long chain takes milliseconds: fewer, longer samples.
        g.sample_size(if *name == "chain_100" { 10 } else { 100 });
        // The Model/Data split as a user repeating solves would use it: the
        // workspace (frames, assembly, solver buffers) is made once.
        let mut work = Workspace::new(m);
        g.bench_function(*name, |b| {
            b.iter(|| solve_with(black_box(m), &MechanismSettings::default(), &mut work).unwrap())
        });
    }
    g.finish();
}
