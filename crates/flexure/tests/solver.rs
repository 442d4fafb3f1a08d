//! The shared solver core on problems with closed-form answers.

use flexure::Error;
use flexure::solver::{Problem, Settings, SolverWorkspace, Stop, continuation, newton, trace, with_interrupt};

/// $r(x, \lambda) = x^3 - 3x + 3 - 8\lambda$: the gradient of a one-degree
/// potential with a fold at $x = -1$, $\lambda = 5/8$ (the limit load) and
/// another at $x = 1$, $\lambda = 1/8$. Loaded from the rest root at
/// $\lambda = 0$, the path snaps through to the stable root of
/// $x^3 - 3x - 5 = 0$ at $\lambda = 1$.
struct Snap;

impl Problem<f64> for Snap {
    fn dim(&self) -> usize {
        1
    }
    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        r: &mut [f64],
        j: Option<&mut [f64]>,
        d: Option<&mut [f64]>,
    ) -> flexure::Result<()> {
        r[0] = x[0].powi(3) - 3.0 * x[0] + 3.0 - 8.0 * lambda;
        if let Some(j) = j {
            j[0] = 3.0 * x[0] * x[0] - 3.0;
        }
        if let Some(d) = d {
            d[0] = -8.0;
        }
        Ok(())
    }
    fn stable(&mut self, _x: &[f64], _lambda: f64, j: &[f64]) -> bool {
        j[0] > 0.0
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (a[0] - b[0]).abs()
    }
    fn scale(&self) -> f64 {
        1.0
    }
    fn unit(&self) -> &'static str {
        "1"
    }
    fn name(&self) -> &'static str {
        "snap"
    }
}

/// Cardano: the real root of $x^3 + px + q = 0$ with one real root.
fn cardano(p: f64, q: f64) -> f64 {
    let d = (q * q / 4.0 + p * p * p / 27.0).sqrt();
    (-q / 2.0 + d).cbrt() + (-q / 2.0 - d).cbrt()
}

#[test]
fn snap_through_reaches_the_stable_root_and_names_the_limit_load() {
    let mut ws = SolverWorkspace::new(1);
    ws.x[0] = cardano(-3.0, 3.0);
    let path = continuation(&mut Snap, &mut ws, &Settings::default()).unwrap();
    // Closed form: the root of x³ − 3x − 5 = 0 (tolerance: Newton's, 1e-12 on r).
    assert!((ws.x[0] - cardano(-3.0, -5.0)).abs() < 1e-11, "{}", ws.x[0]);
    assert!(path.stable);
    // The fold is at λ = 5/8; the limit is the peak of the cubic Hermite
    // through the two path points around it (error of order h⁴ in the step:
    // 1.8e-5 at the steps taken here, so 1e-4).
    let limit = path.limit.expect("stability is lost at the fold");
    assert!((limit - 0.625).abs() < 1e-4, "{limit}");
}

#[test]
fn newton_converges_quadratically_on_a_cubic() {
    let mut ws = SolverWorkspace::new(1);
    ws.x[0] = 3.0;
    let r = newton(&mut Snap, &mut ws, 1.0, &Settings::default()).unwrap();
    assert!((ws.x[0] - cardano(-3.0, -5.0)).abs() < 1e-12 && r.iterations <= 8, "{r:?}");
}

#[test]
fn limits_are_reported_with_what_was_reached() {
    let mut ws = SolverWorkspace::new(1);
    ws.x[0] = 3.0;
    let one = Settings { max_iterations: 1, ..Default::default() };
    match newton(&mut Snap, &mut ws, 1.0, &one) {
        Err(Error::NoConvergence { iterations: 1, residual, unit: "1", .. }) => assert!(residual > 0.0),
        other => panic!("expected NoConvergence after one iteration, got {other:?}"),
    }
    ws.x[0] = cardano(-3.0, 3.0);
    let few = Settings { max_steps: 2, ..Default::default() };
    match continuation(&mut Snap, &mut ws, &few) {
        Err(Error::ContinuationStalled { steps: 2, load_fraction, .. }) => assert!(load_fraction > 0.0),
        other => panic!("expected ContinuationStalled after two steps, got {other:?}"),
    }
}

#[test]
fn an_interrupt_stops_the_solver() {
    let mut ws = SolverWorkspace::new(1);
    ws.x[0] = cardano(-3.0, 3.0);
    let r = with_interrupt(|| true, || continuation(&mut Snap, &mut ws, &Settings::default()));
    assert!(matches!(r, Err(Error::Interrupted { load_fraction }) if load_fraction == 0.0), "{r:?}");
    // The hook is removed afterwards.
    ws.x[0] = cardano(-3.0, 3.0);
    assert!(continuation(&mut Snap, &mut ws, &Settings::default()).is_ok());
}

#[test]
fn a_workspace_of_another_size_is_refused() {
    let mut ws = SolverWorkspace::new(2);
    assert!(matches!(newton(&mut Snap, &mut ws, 0.0, &Settings::default()), Err(Error::InvalidParameter { .. })));
}

/// [`Settings::max_evaluations`] bounds a continuation's work whatever its
/// steps: the snap-through cubic, whose full path takes more evaluations
/// than the bound allows, stops with the path reached (a load fraction
/// between 0 and 1, the state there in `ws`) and an error that names the
/// bound; the same run with the default bound reaches the load.
#[test]
fn a_work_bound_stops_the_continuation_and_names_itself() {
    let mut ws = SolverWorkspace::new(1);
    ws.x[0] = cardano(-3.0, 3.0);
    let few = Settings { max_evaluations: 6, ..Default::default() };
    let path = trace(&mut Snap, &mut ws, &few).unwrap();
    assert!(matches!(path.stop, Stop::WorkCap { evaluations: 6, .. }), "{path:?}");
    assert!(path.load_fraction > 0.0 && path.load_fraction < 1.0 && ws.lambda == path.load_fraction, "{path:?}");
    let e = path.error(&Snap).expect("a path stopped by its bound is an error").to_string();
    assert!(e.contains("its limit of 6 Newton evaluations (max_evaluations)") && e.contains("orders"), "{e}");
    ws.x[0] = cardano(-3.0, 3.0);
    assert!(trace(&mut Snap, &mut ws, &Settings::default()).unwrap().reached());
    // Zero is refused, by name.
    let zero = Settings { max_evaluations: 0, ..Default::default() };
    assert!(matches!(zero.validate(), Err(Error::InvalidParameter { name: "max_evaluations", .. })));
}

/// [`trace`] returns partial runs as paths that say why they stopped, and
/// [`continuation`]'s error is the one the path stands for.
#[test]
fn a_traced_path_says_why_it_stopped() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let mut ws = SolverWorkspace::new(1);
    ws.x[0] = cardano(-3.0, 3.0);
    let path = trace(&mut Snap, &mut ws, &Settings::default()).unwrap();
    assert!(path.reached() && path.load_fraction == 1.0 && path.stable, "{path:?}");
    assert!(path.limit.is_some_and(|l| (l - 0.625).abs() < 1e-4), "{path:?}");
    // A step cap: the path so far, with the load fraction it reached.
    ws.x[0] = cardano(-3.0, 3.0);
    let few = Settings { max_steps: 2, ..Default::default() };
    let path = trace(&mut Snap, &mut ws, &few).unwrap();
    assert!(matches!(path.stop, Stop::StepCap { .. }) && path.steps == 2, "{path:?}");
    assert!(path.load_fraction > 0.0 && path.load_fraction < 1.0 && ws.lambda == path.load_fraction);
    match path.error(&Snap) {
        Some(Error::ContinuationStalled { steps: 2, load_fraction, .. }) => {
            assert_eq!(load_fraction, path.load_fraction)
        }
        other => panic!("expected ContinuationStalled after two steps, got {other:?}"),
    }
    // An interrupt after the start: a path, stopped where it was.
    static POLLS: AtomicUsize = AtomicUsize::new(0);
    POLLS.store(0, Ordering::SeqCst);
    ws.x[0] = cardano(-3.0, 3.0);
    let path = with_interrupt(
        || POLLS.fetch_add(1, Ordering::SeqCst) > 20,
        || trace(&mut Snap, &mut ws, &Settings::default()),
    )
    .unwrap();
    assert_eq!(path.stop, Stop::Interrupted, "{path:?}");
    assert!(
        matches!(path.error(&Snap), Some(Error::Interrupted { load_fraction }) if load_fraction == path.load_fraction)
    );
}
