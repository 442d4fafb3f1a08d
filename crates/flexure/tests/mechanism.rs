//! Mechanisms against independent computations: closed forms, the single-joint
//! library functions, and the exact elastica composed by hand.

use flexure::mechanism::buckling::buckle;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::statics::{Settings, assemble_unloaded, body_frames, compliance, solve};
use flexure::mechanism::sweep::{Parameter, sweep};
use flexure::mechanism::{Holds, JointKind, Mechanism};
use flexure::reference::elastica;
use flexure::tendon::{TendonData, TendonOffsets, pull};
use flexure::{Error, Flexure, TipLoad, bending_stiffness};

fn example(name: &str) -> Mechanism {
    let path = format!("{}/../../examples/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    from_toml(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Fig. 9 as a mechanism agrees with the tendon module (a separate code path: Eq. 24 directly).
#[test]
fn paper_tendon_matches_the_tendon_module() {
    let m = example("paper_tendon");
    let s = solve(&m, &Settings::default()).unwrap();
    let f = Flexure::new(0.015, bending_stiffness(200e9, 0.01, 0.0002, Some(0.29)).unwrap(), 3).unwrap();
    let mut d = TendonData::new(&f);
    pull(&f, &TendonOffsets { root_offset: 0.005, tip_offset: 0.005 }, 28.0, &mut d).unwrap();
    for (a, b) in s.q.iter().zip(d.alpha()) {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
    assert!(s.stable);
}

/// Parallelogram stage, closed forms: unloaded lateral stiffness 2 × 12 EI/L³
/// (a guided beam's curvature is linear, so N = 3 is exact); buckling under
/// axial compression at 2 × the model's guided load (Table I: 10 EI/L²);
/// and under the file's 1 N push the sway stiffness falls by 1 − P/P_cr.
#[test]
fn parallelogram_stage() {
    let m = example("parallelogram");
    let (l, ei): (f64, f64) = (0.05, 2.0e-3);
    let stage = m.body("stage").unwrap();
    let unloaded = assemble_unloaded(&m, &Settings::default()).unwrap();
    let c = compliance(&m, &unloaded, stage, [0.0, -0.02].into()).unwrap();
    assert!((1.0 / c[(1, 1)] - 24.0 * ei / l.powi(3)).abs() < 1e-8 * 24.0 * ei / l.powi(3));
    let b = buckle(&m, &Settings::default()).unwrap();
    let critical = b.load_factor * 1.0;
    assert!((critical - 2.0 * 10.0 * ei / (l * l)).abs() < 1e-8 * critical, "{critical}");
    // Euler: 2π²EI/L², 1.3 % below the model (Table I's guided error).
    assert!((critical / (2.0 * std::f64::consts::PI.powi(2) * ei / (l * l)) - 1.0 - 0.01321).abs() < 1e-4);
    let loaded = solve(&m, &Settings::default()).unwrap();
    let cl = compliance(&m, &loaded, stage, [0.0, -0.02].into()).unwrap();
    assert!((c[(1, 1)] / cl[(1, 1)] - (1.0 - 1.0 / critical)).abs() < 1e-8);
    // The sway mode moves both flexures alike.
    assert!((b.mode[1] - b.mode[4]).abs() < 1e-6);
}

/// The parallelogram solved by `solve_with` in one workspace kept across
/// loads (the benchmark's path: closure stability on the workspace's
/// buffers), against closed forms. A lateral 1 mN sways the stage by
/// F L³/(24 EI) (2 × 12EI/L³, exact for N = 3); the sway of 2.6e-6 m =
/// 5e-5 L changes the stiffness by about (5e-5)², so 1e-8 bounds it with
/// the solver's 1e-12 tolerance to spare. With the file's 1 N push the
/// sway stiffness falls by 1 − P/P_cr exactly at small sway (P_cr = 16 N =
/// 2 × 10 EI/L², Table I). An axial 17 N loses stability at 16/17 of
/// the push (to the bisection's 1e-6 and the √tolerance margin), 15 N
/// does not; 16 N is 1.3 % above Euler's 2π²EI/L². Every answer equals a
/// fresh `solve`'s, bit for bit: the kept buffers carry nothing over.
#[test]
fn parallelogram_in_a_kept_workspace() {
    use flexure::mechanism::statics::{Workspace, solve_with};
    let text =
        std::fs::read_to_string(format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let with = |fx: f64, fy: f64| {
        from_toml(&text.replace("force = [0.0, -1.0]", &format!("force = [{fx:?}, {fy:?}]"))).unwrap()
    };
    let (l, ei): (f64, f64) = (0.05, 2.0e-3);
    let (k, critical) = (24.0 * ei / l.powi(3), 2.0 * 10.0 * ei / (l * l));
    let mut work = Workspace::new(&with(0.0, 0.0));
    let settings = Settings::default();
    let mut solve_kept = |m: &Mechanism| {
        let s = solve_with(m, &settings, &mut work);
        assert_eq!(format!("{s:?}"), format!("{:?}", solve(m, &settings)), "kept and fresh workspaces differ");
        s
    };
    let sway =
        |m: &Mechanism, s: &flexure::mechanism::statics::Solution| body_frames(m, s).bodies[m.body("stage").unwrap()].x;
    for push in [0.0, 1.0] {
        let m = with(1e-3, -push);
        let s = solve_kept(&m).unwrap();
        let expected = 1e-3 / (k * (1.0 - push / critical));
        assert!(s.stable && s.limit.is_none());
        assert!((sway(&m, &s) / expected - 1.0).abs() < 1e-8, "push {push}: {} vs {expected}", sway(&m, &s));
    }
    let bench = solve_kept(&with(0.5, -1.0)).unwrap();
    assert!(bench.stable && bench.limit.is_none() && bench.load_steps == 1);
    let below = solve_kept(&with(0.0, -15.0)).unwrap();
    assert!(below.stable && below.limit.is_none(), "15 N is below the 16 N buckling load");
    let limit = match solve_kept(&with(0.0, -17.0)) {
        Ok(s) => s.limit.unwrap(),
        Err(Error::Unstable { load_fraction, .. }) => load_fraction,
        Err(e) => panic!("{e}"),
    };
    assert!((limit * 17.0 / critical - 1.0).abs() < 3e-6, "lost at {} N", limit * 17.0);
    assert!((critical / (2.0 * std::f64::consts::PI.powi(2) * ei / (l * l)) - 1.0 - 0.01321).abs() < 1e-4);
}

/// A workspace kept across mechanisms and settings of one shape reuses its
/// assembled start only where that start is theirs: each kept solve must
/// equal a fresh one to the bit, and the sway the closed form of the
/// parallelogram's lateral stiffness $12(EI_l + EI_r)/L^3$ (two guided
/// flexures; a 1 mN load keeps the sway 5e-6 of the length, so 1e-8 is
/// far above the model's nonlinearity and rounding). Changed: one joint's
/// stiffness, then back; the tolerance; and a weld 0.1 mm off, whose start
/// needs Newton iterations and whose Newton tolerance moves with the load.
#[test]
fn kept_start_is_the_mechanisms_own() {
    use flexure::mechanism::statics::{Workspace, solve_with};
    let text =
        std::fs::read_to_string(format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let with = |right_ei: &str, weld: &str, fx: f64| {
        let text = text.replace("force = [0.0, -1.0]", &format!("force = [{fx:?}, 0.0]"));
        let (left, right) = text.split_at(text.find("name = \"right\"").unwrap());
        let right = right.replacen("ei = 2.0e-3", &format!("ei = {right_ei}"), 1);
        from_toml(
            &format!("{left}{right}")
                .replace("a_origin = [0.0, -0.04, 0.0]", &format!("a_origin = [0.0, {weld}, 0.0]")),
        )
        .unwrap()
    };
    let (l, ei): (f64, f64) = (0.05, 2.0e-3);
    let default = Settings::default();
    let loose = Settings { tolerance: 1e-11, ..default };
    let mut work = Workspace::new(&with("2.0e-3", "-0.04", 0.0));
    let mut kept = |m: &Mechanism, settings: &Settings| {
        let fresh = solve(m, settings);
        let s = solve_with(m, settings, &mut work).unwrap_or_else(|e| panic!("{e:?}; fresh {fresh:?}"));
        assert_eq!(format!("{s:?}"), format!("{:?}", solve(m, settings).unwrap()), "kept and fresh workspaces differ");
        s
    };
    let sway =
        |m: &Mechanism, s: &flexure::mechanism::statics::Solution| body_frames(m, s).bodies[m.body("stage").unwrap()].x;
    for (right_ei, settings) in
        [(2.0e-3, &default), (2.0e-3, &default), (6.0e-3, &default), (2.0e-3, &default), (2.0e-3, &loose)]
    {
        let m = with(&format!("{right_ei:?}"), "-0.04", 1e-3);
        eprintln!("case {right_ei} {settings:?}");
        let s = kept(&m, settings);
        let expected = 1e-3 / (12.0 * (ei + right_ei) / l.powi(3));
        assert!((sway(&m, &s) / expected - 1.0).abs() < 1e-8, "EI {right_ei}: {} vs {expected}", sway(&m, &s));
    }
    for fx in [1e-3, 2e-3, 2e-3, 0.0] {
        let s = kept(&with("2.0e-3", "-0.0401", fx), &default);
        assert!(s.iterations > 1 && s.stable, "an assembly that iterates: {s:?}");
    }
}

/// Mixed chain under an end moment M, closed forms: the spring turns M/k,
/// each flexure bends into an arc of ML/EI, the slider's spring carries nothing.
#[test]
fn mixed_chain_closed_form() {
    let m = example("mixed_chain");
    let s = solve(&m, &Settings::default()).unwrap();
    let moment = 0.01;
    assert!((s.q[0] - moment / 2.0).abs() < 1e-10, "revolute: M/k");
    assert!((s.q[1] - moment * 0.02 / 1e-3).abs() < 1e-10, "elbow arc: ML/EI");
    assert!(s.q[2].abs() < 1e-10 && s.q[3].abs() < 1e-10);
    assert!(s.q[4].abs() < 1e-12, "slider carries no force");
    assert!((s.q[5] - moment * 0.015 / 5e-4).abs() < 1e-10, "wrist arc");
    // The hand's angle is the sum of the joint rotations.
    let f = body_frames(&m, &s);
    let hand = m.body("hand").unwrap();
    assert!((f.bodies[hand].phi - (s.q[0] + s.q[1] + s.q[5])).abs() < 1e-12);
}

/// Composed by hand: cut each flexure, sum the loads on everything beyond
/// it (point forces; weights; the tendon's pull at its via points and where
/// it leaves the cut; closure forces, −μ on body a and +μ on body b of each
/// pin or weld, from the solution's multipliers), express them at the
/// flexure tip in its root frame, and solve the exact elastica. The model's
/// joint poses agree within 1 % of L and 1° (Sec. III-C).
fn against_the_exact_elastica(m: &Mechanism, gravity: bool) {
    let s = solve(m, &Settings::default()).unwrap();
    assert!(s.stable);
    let f = body_frames(m, &s);
    for (ji, j) in m.joints.iter().enumerate() {
        // Bodies beyond this joint: its child and everything below.
        let beyond: Vec<usize> = (0..m.bodies.len()).filter(|&b| m.path(b).contains(&ji)).collect();
        let tip = f.bodies[j.child];
        let (mut fx, mut fy, mut mz) = (0.0, 0.0, 0.0);
        let mut add = |p: [f64; 2], force: [f64; 2], moment: f64| {
            fx += force[0];
            fy += force[1];
            mz += (p[0] - tip.x) * force[1] - (p[1] - tip.y) * force[0] + moment;
        };
        for load in &m.forces {
            if beyond.contains(&load.body) {
                add(world(&f.bodies[load.body], load.at), [load.wrench.fx, load.wrench.fy], load.wrench.moment);
            }
        }
        for &b in &beyond {
            if gravity {
                let body = &m.bodies[b];
                add(world(&f.bodies[b], body.com), [body.mass * m.gravity[0], body.mass * m.gravity[1]], 0.0);
            }
        }
        // The tendon pulls each via point toward its neighbours; count the
        // pulls on via points that ride on bodies beyond the cut.
        for tendon in &m.tendons {
            let via: Vec<[f64; 2]> = tendon.path.iter().map(|&(b, r)| world(&f.bodies[b], r)).collect();
            for (i, &(b, _)) in tendon.path.iter().enumerate() {
                if !beyond.contains(&b) {
                    continue;
                }
                for k in [i.wrapping_sub(1), i + 1] {
                    if let Some(q) = via.get(k) {
                        let d = [q[0] - via[i][0], q[1] - via[i][1]];
                        let n = d[0].hypot(d[1]);
                        add(via[i], [tendon.tension * d[0] / n, tendon.tension * d[1] / n], 0.0);
                    }
                }
            }
        }
        let mut row = 0;
        for c in &m.closures {
            let (a, a_at, b, b_at) = (c.a, c.a_origin.origin(), c.b, c.b_origin.origin());
            let moment = (c.holds == Holds::Weld).then(|| s.multipliers[row + 2]);
            let mu = [s.multipliers[row], s.multipliers[row + 1]];
            if beyond.contains(&a) {
                add(world(&f.bodies[a], a_at), [-mu[0], -mu[1]], -moment.unwrap_or(0.0));
            }
            if beyond.contains(&b) {
                add(world(&f.bodies[b], b_at), mu, moment.unwrap_or(0.0));
            }
            row += c.equations();
        }
        // Into the flexure's root frame.
        let root = f.roots[ji];
        let (sn, cs) = root.phi.sin_cos();
        let load = TipLoad { moment: mz, fx: cs * fx + sn * fy, fy: -sn * fx + cs * fy };
        let JointKind::Flexure(flex) = &j.kind else { panic!("flexures only") };
        let exact = elastica::deflect(flex, &load, &Default::default()).unwrap().pose;
        let model = &f.joints[ji].pose;
        let l = flex.length();
        assert!((model.x - exact.x).hypot(model.y - exact.y) < 0.01 * l, "{}: position", j.name);
        assert!((model.phi - exact.phi).abs().to_degrees() < 1.0, "{}: angle {} vs {}", j.name, model.phi, exact.phi);
        assert!(exact.phi.abs() > 0.02, "{}: a test that bends the joint", j.name);
    }
}

/// The finger: an open chain loaded by a tendon and a fingertip force.
#[test]
fn finger_against_the_exact_elastica() {
    against_the_exact_elastica(&example("finger"), false);
}

/// The four-bar: a loop closed by a pin (its force from the multipliers),
/// with gravity, a tendon and a force.
#[test]
fn four_bar_against_the_exact_elastica() {
    let m = example("four_bar");
    assert_eq!(m.constraints(), 2);
    against_the_exact_elastica(&m, true);
}

/// The four-leg example's stated numbers: lateral stiffness 4 × 12 EI/L³
/// (N = 3 exact for guided legs) and buckling at 4 × 10 EI/L² (Table I).
#[test]
fn four_leg_stage_example() {
    let m = example("four_leg_stage");
    let (l, ei): (f64, f64) = (0.05, 2.0e-3);
    let unloaded = assemble_unloaded(&m, &Settings::default()).unwrap();
    let c = compliance(&m, &unloaded, m.body("stage").unwrap(), [0.0, -0.06].into()).unwrap();
    assert!((1.0 / c[(1, 1)] - 48.0 * ei / l.powi(3)).abs() < 1e-9 * 48.0 * ei / l.powi(3));
    let b = buckle(&m, &Settings::default()).unwrap();
    // The file pushes with 10 N.
    assert!((b.load_factor * 10.0 - 40.0 * ei / (l * l)).abs() < 1e-9 * 40.0 * ei / (l * l));
    // Under its 2 N lateral, 10 N axial load the welds' forces are fixed by
    // compatibility, not by the least-force rule: a rigid stage on identical
    // inextensible legs shortens them linearly across it, so the legs'
    // forces along world y are P_k = a + b·d_k (equal steps, the overturning
    // moment of the lateral load making b ≠ 0), and they carry the 10 N
    // (leg0 takes what the welds, pushing the stage with −μ, do not).
    let s = solve(&m, &Settings::default()).unwrap();
    let welds: Vec<f64> = (0..3).map(|k| -s.multipliers[3 * k + 1]).collect();
    let legs = [10.0 - welds.iter().sum::<f64>(), welds[0], welds[1], welds[2]];
    let steps: Vec<f64> = legs.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps[0].abs() > 0.1, "the lateral load tilts the shares: {legs:?}");
    assert!(steps.windows(2).all(|w| (w[1] - w[0]).abs() < 1e-6 * 10.0), "{legs:?}");
}

/// A sweep continues from value to value and ends where a direct solve does.
#[test]
fn sweep_follows_the_load() {
    let m = example("paper_tendon");
    let p = Parameter::parse(&m, "tendon.flexor.tension").unwrap();
    let out = sweep(&m, &p, &[0.0, 10.0, 20.0, 28.0], &Settings::default()).unwrap();
    assert!(out.stability_limit.is_none());
    let rows: Vec<_> = out.rows.iter().map(|(_, s)| s).collect();
    assert_eq!(rows.len(), 4);
    assert!(rows.windows(2).all(|w| w[1].q[0] > w[0].q[0]));
    let direct = solve(&m, &Settings::default()).unwrap();
    assert!((rows[3].q[0] - direct.q[0]).abs() < 1e-9);
    assert!(Parameter::parse(&m, "tendon.nope.tension").is_err());
    assert!(sweep(&m, &p, &[-1.0], &Settings::default()).is_err());
}

/// Beyond its buckling load (16 N) the stage's straight path loses
/// stability at 16/40 of a 40 N push, and says so: rounding makes the
/// bifurcation slightly imperfect, the path follows the stage as it buckles
/// sideways, and the stable buckled state it reaches is the answer, with
/// the limit fraction where stability was lost. Below the load, a stable
/// straight stage and no limit.
#[test]
fn instability_is_reported() {
    let text =
        std::fs::read_to_string(format!("{}/../../examples/parallelogram.toml", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let heavy = from_toml(&text.replace("force = [0.0, -1.0]", "force = [0.0, -40.0]")).unwrap();
    let limit = match solve(&heavy, &Settings::default()) {
        Ok(s) => {
            assert!(s.stable);
            let sway = body_frames(&heavy, &s).bodies[heavy.body("stage").unwrap()].x;
            assert!(sway.abs() > 0.01, "buckled sideways: {sway}");
            s.limit.unwrap()
        }
        // The policy's other outcome, had no stable state been reached.
        Err(Error::Unstable { load_fraction, .. }) => load_fraction,
        Err(e) => panic!("{e}"),
    };
    // The model's critical push is 16 N (2 × 10 EI/L², Table I): 40 % of 40 N.
    assert!((limit - 0.4).abs() < 1e-5, "{limit}");
    let light = from_toml(&text.replace("force = [0.0, -1.0]", "force = [0.0, -15.0]")).unwrap();
    let s = solve(&light, &Settings::default()).unwrap();
    assert!(s.stable && s.limit.is_none(), "below it, a stable equilibrium");
}

/// Gravity on a sprung pendulum, closed form: k θ = −m g l cos θ (moment of
/// the weight about the pivot), solved here by bisection.
#[test]
fn gravity_on_a_sprung_pendulum() {
    let (k, m, l, g) = (3.0, 0.5, 0.4, 9.81);
    let text = format!(
        "gravity = [0.0, -{g}]\n[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = {k}\n[[body]]\nname = \"arm\"\nmass = {m}\ncom = [{l}, 0.0]\n"
    );
    let mech = from_toml(&text).unwrap();
    let s = solve(&mech, &Settings::default()).unwrap();
    let (mut lo, mut hi) = (-std::f64::consts::FRAC_PI_2, 0.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if k * mid + m * g * l * f64::cos(mid) > 0.0 { hi = mid } else { lo = mid }
    }
    assert!((s.q[0] - 0.5 * (lo + hi)).abs() < 1e-10, "{} vs {}", s.q[0], lo);
}

/// Pin closure, closed form: two sprung slider stacks (x, then y) pinned at
/// their ends act as springs in parallel: Δx = Fx/(k1 + k2), Δy = Fy/(k3 + k4).
#[test]
fn pinned_springs_add() {
    let slider = |name: &str, parent: &str, child: &str, angle: f64, k: f64| {
        format!(
            "[[joint]]\nname = \"{name}\"\nkind = \"prismatic\"\nparent = \"{parent}\"\nchild = \"{child}\"\norigin = [0.0, 0.0, {angle}]\nstiffness = {k}\n"
        )
    };
    let half = std::f64::consts::FRAC_PI_2;
    let text = slider("ax", "ground", "a1", 0.0, 100.0)
        + &slider("ay", "a1", "a", half, 300.0)
        + &slider("bx", "ground", "b1", 0.0, 50.0)
        + &slider("by", "b1", "b", half, 100.0)
        + "[[pin]]\na = \"a\"\nb = \"b\"\n[[force]]\nbody = \"a\"\nat = [0.0, 0.0]\nforce = [3.0, -8.0]\n";
    let mech = from_toml(&text).unwrap();
    let s = solve(&mech, &Settings::default()).unwrap();
    assert!((s.q[0] - 3.0 / 150.0).abs() < 1e-12 && (s.q[2] - 3.0 / 150.0).abs() < 1e-12, "{:?}", s.q);
    assert!((s.q[1] + 8.0 / 400.0).abs() < 1e-12 && (s.q[3] + 8.0 / 400.0).abs() < 1e-12, "{:?}", s.q);
    assert!(s.stable);
}

/// File errors name the place, with line and column.
#[test]
fn file_errors_name_the_place() {
    let joint = |name: &str, parent: &str, child: &str, extra: &str| {
        format!(
            "[[joint]]\nname = \"{name}\"\nkind = \"flexure\"\nparent = \"{parent}\"\nchild = \"{child}\"\nlength = 0.01\nei = 1e-3\n{extra}\n"
        )
    };
    let cases = [
        (joint("a", "palm", "b", ""), "unknown body \"palm\"", "line 4"),
        (joint("a", "ground", "b", "") + &joint("a", "b", "c", ""), "duplicate joint name", "line 10"),
        (joint("a", "ground", "b", "") + &joint("c", "ground", "b", ""), "reached by two joints", "line 13"),
        (joint("a", "c", "b", "") + &joint("d", "b", "c", ""), "cycle", "line 4"),
        (joint("a", "ground", "b", "").replace("length = 0.01", "length = -0.01"), "length", "line 6"),
        (
            joint("a", "ground", "b", "") + "[[weld]]\na = \"b\"\nb = \"nowhere\"\n",
            "unknown body \"nowhere\"",
            "line 11",
        ),
        (joint("a", "ground", "b", "").replace("kind = \"flexure\"", "kind = \"hinge\""), "unknown kind", "line 3"),
        ("[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = ground\n".to_string(), "", "line 4"),
        (joint("a", "ground", "b", "") + "[[force]]\nbody = \"b\"\nat = [nan, 0.0]\n", "finite", "line 11"),
    ];
    for (text, what, place) in cases {
        let e = from_toml(&text).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains(what) && msg.contains(place), "expected {what:?} at {place}: {msg}");
    }
}

/// The solver core's interrupt hook stops mechanism solves too, saying where.
#[test]
fn interruptible() {
    let m = example("finger");
    let r = flexure::solver::with_interrupt(|| true, || solve(&m, &Settings::default()));
    assert!(matches!(r, Err(Error::Interrupted { .. })), "{r:?}");
}

/// Newton's root of `f` from `x` with derivative `df` (100 steps).
fn root(f: impl Fn(f64) -> f64, df: impl Fn(f64) -> f64, mut x: f64) -> f64 {
    for _ in 0..100 {
        x -= f(x) / df(x);
    }
    x
}

/// A sprung arm (k, length l) pushed along itself by P = 1.5 k/l, closed
/// forms. Perfectly aligned, the straight arm is an equilibrium at every
/// load and loses stability at P = k/l, 2/3 of the push: the path follows
/// it and ends unstable, an error at 2/3. With a transverse force F of
/// 1e-3 N the bifurcation is imperfect and the path leads smoothly to the
/// buckled arm, kθ = P l sin θ + F l cos θ.
#[test]
fn pitchfork_of_a_sprung_arm() {
    let (k, l, p) = (1.0, 0.1, 15.0);
    let arm = |transverse: f64| {
        from_toml(&format!(
            "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = {k}\n\
             [[force]]\nname = \"push\"\nbody = \"arm\"\nat = [{l}, 0.0]\nforce = [-{p}, {transverse}]\n"
        ))
        .unwrap()
    };
    match solve(&arm(0.0), &Settings::default()) {
        // The stability margin and the bisection: 1e-5.
        Err(Error::Unstable { load_fraction, .. }) => assert!((load_fraction - k / (p * l)).abs() < 1e-5),
        other => panic!("{other:?}"),
    }
    let f = 1e-3;
    let s = solve(&arm(f), &Settings::default()).unwrap();
    let theta = root(|t| k * t - p * l * t.sin() - f * l * t.cos(), |t| k - p * l * t.cos() + f * l * t.sin(), 1.4);
    assert!(s.stable && s.limit.is_none());
    assert!((s.q[0] - theta).abs() < 1e-10, "{} vs {theta}", s.q[0]);
}

/// A von Mises half-truss snaps through, closed form: a bar of length
/// l = √(X² + h²) on a free hinge, its foot on a slider with spring k,
/// its head pinned to an apex that slides vertically on a spring k_v,
/// pressed down by P. With apex height y the foot moves d = X − √(l² − y²),
/// and equilibrium is P = k_v(h − y) − k d y/√(l² − y²): a local maximum
/// (the limit load) at y > 0, then the path runs back to a stable state at
/// y < −h. Loaded past the maximum the mechanism snaps through: the answer
/// is that stable state, with the limit fraction P_max/P (to the 1e-6 the
/// bisection seeks, plus the stability margin's shift).
#[test]
fn von_mises_truss_snaps_through() {
    let (x, h, k, kv, p) = (0.1_f64, 0.03_f64, 1000.0, 12.0, 1.0);
    let l = x.hypot(h);
    let text = format!(
        "[[joint]]\nname = \"roll\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"foot\"\nstiffness = {k}\n\
         [[joint]]\nname = \"hinge\"\nkind = \"revolute\"\nparent = \"foot\"\nchild = \"bar\"\nrest = {}\n\
         [[joint]]\nname = \"guide\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"apex\"\n\
         origin = [{x}, 0.0, {}]\nrest = {h}\nstiffness = {kv}\n\
         [[pin]]\na = \"bar\"\na_at = [{l}, 0.0]\nb = \"apex\"\n\
         [[force]]\nname = \"press\"\nbody = \"apex\"\nat = [0.0, 0.0]\nforce = [0.0, -{p}]\n",
        h.atan2(x),
        std::f64::consts::FRAC_PI_2
    );
    let load = |y: f64| {
        let s = (l * l - y * y).sqrt();
        kv * (h - y) - k * (x - s) * y / s
    };
    // The limit load: the maximum of the load on 0 < y < h, by ternary search.
    let (mut a, mut b) = (0.0, h);
    for _ in 0..200 {
        let (m1, m2) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
        if load(m1) < load(m2) { a = m1 } else { b = m2 }
    }
    let limit = load(a);
    assert!(limit < p && load(-a) > 0.0, "a snap-through that stays under load");
    // The far stable state: load(y) = P for y < −h, by bisection.
    let (mut lo, mut hi) = (-0.9999 * l, -h);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if load(mid) > p { lo = mid } else { hi = mid }
    }
    let s = solve(&from_toml(&text).unwrap(), &Settings::default()).unwrap();
    assert!(s.stable);
    assert!((s.q[2] - lo).abs() < 1e-10, "apex {} vs {lo}", s.q[2]);
    let fraction = s.limit.unwrap();
    assert!((fraction / (limit / p) - 1.0).abs() < 2e-6, "{fraction} vs {}", limit / p);
}

/// A cantilever of length 1 m and EI = 1 N·m² cut into `count` flexures of
/// order 1 (one constant-curvature arc each) in series, each welded tip to
/// root through its own body, under a tip force `force` and moment.
fn arc_chain(count: usize, force: [f64; 2], moment: f64) -> Mechanism {
    let mut text = String::new();
    for i in 0..count {
        let parent = if i == 0 { "ground".to_string() } else { format!("b{}", i - 1) };
        text += &format!("[[joint]]\nname = \"j{i}\"\nkind = \"flexure\"\nparent = \"{parent}\"\nchild = \"b{i}\"\n");
        text += &format!("length = {}\nei = 1.0\norder = 1\n", 1.0 / count as f64);
    }
    text += &format!(
        "[[force]]\nbody = \"b{}\"\nat = [0.0, 0.0]\nforce = [{}, {}]\nmoment = {moment}\n",
        count - 1,
        force[0],
        force[1]
    );
    from_toml(&text).unwrap()
}

/// A chain of K one-arc flexures is the paper's K-segment flexure
/// (`Flexure::segments`, Sec. II-E) of the same length: its coordinates are
/// the segments' rotations. The mechanism (tree factorization, no
/// closures) and the single flexure's `deflect` (dense, its own kinematics)
/// agree to 1e-9 rad under tip loads that turn the tip from 0.64 to 1.65 rad,
/// for K = 6 and 24 (both converge to 1e-12 of the load; the arcs'
/// quadratures differ in rounding only).
#[test]
fn arc_chain_is_the_segmented_flexure() {
    use flexure::{StaticsData, deflect};
    for count in [6, 24] {
        for (force, moment) in [([0.0, 1.5], 0.0), ([-1.0, 3.0], 0.5), ([0.5, -2.0], -1.5)] {
            let m = arc_chain(count, force, moment);
            let s = solve(&m, &Settings::default()).unwrap();
            let f = Flexure::segments(1.0, 1.0, count).unwrap();
            let mut data = StaticsData::new(&f);
            let e =
                deflect(&f, &TipLoad { moment, fx: force[0], fy: force[1] }, &mut data, &Default::default()).unwrap();
            assert!(s.stable && e.stable);
            let tip: f64 = s.q.iter().sum();
            assert!(tip.abs() > 0.5, "a large deflection: {tip}");
            for (a, b) in s.q.iter().zip(data.alpha()) {
                assert!((a - b).abs() < 1e-9, "K = {count}, {force:?}: {a} vs {b}");
            }
        }
    }
}

/// A chain of K one-arc flexures pushed along its axis loses stability at
/// the K-segment flexure's buckling load (`buckling_load`, a generalized
/// eigenproblem of its own): past it, `solve` reports the load fraction
/// P_cr/P to the solver's limit precision (1e-6; the stability margin adds
/// about 1e-6 more). The stability tests along the way are the tree's pivots.
#[test]
fn arc_chain_buckles_as_the_segmented_flexure() {
    use flexure::{TipConstraint, buckling_load};
    for count in [4, 16] {
        let critical =
            buckling_load(&Flexure::segments(1.0, 1.0, count).unwrap(), TipConstraint::Free).unwrap().critical_load;
        let push = 1.5 * critical;
        let m = arc_chain(count, [-push, 0.0], 0.0);
        match solve(&m, &Settings::default()) {
            Err(Error::Unstable { load_fraction, .. }) => {
                assert!((load_fraction * push / critical - 1.0).abs() < 1e-5, "K = {count}: {load_fraction}")
            }
            other => panic!("K = {count}: expected a loss of stability, got {other:?}"),
        }
    }
}

/// The mechanism's problem with the solver's dense LU in place of the
/// tree's factorization: every other answer (residual, stability, step
/// bounds) is the mechanism's own.
struct DenseLu<'a>(flexure::mechanism::statics::Kkt<'a>);

impl flexure::solver::Problem<f64> for DenseLu<'_> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        residual: &mut [f64],
        jacobian: Option<&mut [f64]>,
        dlambda: Option<&mut [f64]>,
    ) -> flexure::Result<()> {
        self.0.evaluate(x, lambda, residual, jacobian, dlambda)
    }
    fn stable(&mut self, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        self.0.stable(x, lambda, jacobian)
    }
    fn far_from_instability(&mut self, x: &[f64], lambda: f64, jacobian: &[f64]) -> bool {
        self.0.far_from_instability(x, lambda, jacobian)
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        self.0.distance(a, b)
    }
    fn scale(&self) -> f64 {
        self.0.scale()
    }
    fn unit(&self) -> &'static str {
        self.0.unit()
    }
    fn name(&self) -> &'static str {
        self.0.name()
    }
    fn weight(&self, i: usize) -> f64 {
        self.0.weight(i)
    }
}

/// The continuation with the tree's factorization (Newton steps, bordered
/// corrector and tangent by block elimination) follows the same path as
/// with dense LU: chains of 3 and 30 order-3 flexures (L = 1 m, EI = 1)
/// under tip loads that take one to eight steps, and an axial push of 4 N
/// past buckling (at 0.617 of it, where both lose stability). Same steps,
/// same stability and limit, end states equal to 1e-10 rad
/// (both converge to 1e-12 of the load; the factorizations differ in
/// rounding only).
#[test]
fn tree_factorization_follows_the_dense_path() {
    use flexure::mechanism::statics::Kkt;
    use flexure::solver::{self, Problem};
    for count in [3, 30] {
        for (force, moment) in [([0.0, 2.0], 0.0), ([-3.0, 6.0], 1.0), ([-4.0, 0.1], 0.0), ([-4.0, 0.0], 0.0)] {
            let mut text = String::new();
            for i in 0..count {
                let parent = if i == 0 { "ground".to_string() } else { format!("b{}", i - 1) };
                text += &format!(
                    "[[joint]]\nname = \"j{i}\"\nkind = \"flexure\"\nparent = \"{parent}\"\nchild = \"b{i}\"\n"
                );
                text += &format!("length = {}\nei = 1.0\n", 1.0 / count as f64);
            }
            text += &format!(
                "[[force]]\nbody = \"b{}\"\nat = [0.0, 0.0]\nforce = [{}, {}]\nmoment = {moment}\n",
                count - 1,
                force[0],
                force[1]
            );
            let m = from_toml(&text).unwrap();
            let settings = Settings::default();
            let zero = m.loads().zero_like();
            let run = |dense: bool| {
                let kkt = Kkt::new(&m, &zero, &m.loads(), &settings).unwrap();
                let mut ws = solver::SolverWorkspace::new(kkt.dim());
                ws.x.copy_from_slice(&kkt.state(&m.rest(), &[]));
                let path = if dense {
                    solver::continuation(&mut DenseLu(kkt), &mut ws, &settings)
                } else {
                    solver::continuation(&mut { kkt }, &mut ws, &settings)
                };
                (path.unwrap(), ws.x)
            };
            let ((tree, x), (dense, y)) = (run(false), run(true));
            let what = format!("{count} flexures, {force:?}, {moment}");
            assert_eq!((tree.steps, tree.stable), (dense.steps, dense.stable), "{what}");
            match (tree.limit, dense.limit) {
                (None, None) => {}
                (Some(a), Some(b)) => assert!((a - b).abs() < 1e-12, "{what}: limits {a} and {b}"),
                other => panic!("{what}: limits {other:?}"),
            }
            for (a, b) in x.iter().zip(&y) {
                assert!((a - b).abs() < 1e-10, "{what}: {a} vs {b}");
            }
        }
    }
}

/// A point given in a frame, in the world, as components.
fn world(frame: &flexure::Pose, r: impl Into<nalgebra::Point2<f64>>) -> [f64; 2] {
    let w = frame.act(&r.into());
    [w.x, w.y]
}
