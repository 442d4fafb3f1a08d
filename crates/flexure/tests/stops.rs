//! Why a solver stopped: [`NewtonStop`] on a Newton solve and the time
//! integrator's [`TrajectoryStop`] on a trajectory, each way each can end, on
//! problems with closed-form answers.

use flexure::dynamics::System;
use flexure::dynamics::integrate::{MotionSettings, TrajectoryStop, integrate, integrate_kept};
use flexure::solver::{NewtonStop, Problem, SolverWorkspace, newton, with_interrupt};
use flexure::{Error, Result};
use std::sync::atomic::{AtomicUsize, Ordering};

/// $r(x, \lambda) = x^2 - 2 - \lambda$: root $\sqrt{2 + \lambda}$.
struct Root;

impl Problem<f64> for Root {
    fn dim(&self) -> usize {
        1
    }
    fn evaluate(
        &mut self,
        x: &[f64],
        l: f64,
        r: &mut [f64],
        j: Option<&mut [f64]>,
        d: Option<&mut [f64]>,
    ) -> Result<()> {
        r[0] = x[0] * x[0] - 2.0 - l;
        if let Some(j) = j {
            j[0] = 2.0 * x[0];
        }
        if let Some(d) = d {
            d[0] = -1.0;
        }
        Ok(())
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
        "root"
    }
}

/// A Newton solve that returns has converged: its residual meets the
/// tolerance (1e-12 × scale 1), from afar and from the root itself (zero
/// iterations); the root is √3 to 4 ulp. Its other ends are errors.
#[test]
fn a_newton_solve_that_returns_converged() {
    let settings = flexure::solver::Settings::default();
    let mut ws = SolverWorkspace::new(1);
    ws.x[0] = 5.0;
    let r = newton(&mut Root, &mut ws, 1.0, &settings).unwrap();
    assert_eq!(r.stop, NewtonStop::Converged);
    assert!(r.iterations >= 3 && r.residual <= settings.tolerance, "{r:?}");
    assert!((ws.x[0] - 3f64.sqrt()).abs() <= 4.0 * f64::EPSILON * 3f64.sqrt(), "{}", ws.x[0]);
    let again = newton(&mut Root, &mut ws, 1.0, &settings).unwrap();
    assert_eq!((again.stop, again.iterations), (NewtonStop::Converged, 0));
    // The cap: NoConvergence after the one iteration allowed.
    ws.x[0] = 5.0;
    let one = flexure::solver::Settings { max_iterations: 1, ..settings };
    assert!(matches!(newton(&mut Root, &mut ws, 1.0, &one), Err(Error::NoConvergence { iterations: 1, .. })));
    // The interrupt: Interrupted at the load asked.
    ws.x[0] = 5.0;
    let r = with_interrupt(|| true, || newton(&mut Root, &mut ws, 1.0, &settings));
    assert!(matches!(r, Err(Error::Interrupted { load_fraction }) if load_fraction == 1.0), "{r:?}");
}

/// A unit mass on a unit spring, $q = \cos t$ from $q = 1$ at rest, whose
/// dynamics cannot be evaluated past `dynamics_until` and whose energy
/// cannot past `energy_until` (s).
struct Spring {
    dynamics_until: f64,
    energy_until: f64,
}

impl System for Spring {
    fn dim(&self) -> usize {
        1
    }
    fn closures(&self) -> usize {
        0
    }
    fn dynamics(&mut self, q: &[f64], _: &[f64], t: f64, m: &mut [f64], f: &mut [f64]) -> Result<()> {
        if t > self.dynamics_until {
            return Err(Error::Singular { what: "the spring past its time".into() });
        }
        m[0] = 1.0;
        f[0] = -q[0];
        Ok(())
    }
    fn tangent(&mut self, _: &[f64], _: &[f64], _: f64, k: &mut [f64], d: &mut [f64]) -> Result<()> {
        k[0] = 1.0;
        d[0] = 0.0;
        Ok(())
    }
    fn energy(&mut self, q: &[f64], v: &[f64], t: f64) -> Result<f64> {
        if t > self.energy_until {
            return Err(Error::Singular { what: "the spring's energy past its time".into() });
        }
        Ok(0.5 * (q[0] * q[0] + v[0] * v[0]))
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        (a[0] - b[0]).abs()
    }
}

fn settings() -> MotionSettings {
    MotionSettings { duration: 3.0, every: 0.5, tolerance: 1e-10, absolute: 1e-10, ..Default::default() }
}

/// A run that records every sample reached its duration; one that ends
/// early says which way, with the samples before: stalled (the dynamics
/// fail past 1.2 s, so every step across it is refused), failed (a sample's
/// energy fails past 1.2 s, at the 1.5 s sample) and interrupted (the hook
/// asks after 40 polls).
#[test]
fn a_trajectory_says_why_it_ended() {
    let mut fine = Spring { dynamics_until: f64::INFINITY, energy_until: f64::INFINITY };
    let run = integrate(&mut fine, &[1.0], &[0.0], &settings()).unwrap();
    assert_eq!(run.stop, TrajectoryStop::Reached);
    // Closed form q = cos t, to the tolerance's order (1e-8).
    for (k, t) in run.time.iter().enumerate() {
        assert!((run.q(k)[0] - t.cos()).abs() < 1e-8, "t = {t}: {}", run.q(k)[0]);
    }
    let stall = &mut Spring { dynamics_until: 1.2, energy_until: f64::INFINITY };
    let (run, e) = integrate_kept(stall, &[1.0], &[0.0], &settings()).unwrap();
    assert_eq!((run.stop, run.time.as_slice()), (TrajectoryStop::Stalled, &[0.0, 0.5, 1.0][..]));
    assert!(matches!(e, Some(Error::IntegrationStalled { .. })), "{e:?}");
    let fail = &mut Spring { dynamics_until: f64::INFINITY, energy_until: 1.2 };
    let (run, e) = integrate_kept(fail, &[1.0], &[0.0], &settings()).unwrap();
    assert_eq!((run.stop, run.time.as_slice()), (TrajectoryStop::Failed, &[0.0, 0.5, 1.0][..]));
    assert!(matches!(e, Some(Error::Singular { .. })), "{e:?}");
    // `integrate` returns the error itself.
    assert!(matches!(integrate(fail, &[1.0], &[0.0], &settings()), Err(Error::Singular { .. })));
    static POLLS: AtomicUsize = AtomicUsize::new(0);
    let (run, e) = with_interrupt(
        || POLLS.fetch_add(1, Ordering::Relaxed) >= 40,
        || integrate_kept(&mut fine, &[1.0], &[0.0], &settings()),
    )
    .unwrap();
    assert_eq!(run.stop, TrajectoryStop::Interrupted);
    assert!(!run.time.is_empty() && run.time.len() < 7, "{:?}", run.time);
    assert!(matches!(e, Some(Error::InterruptedAt { .. })), "{e:?}");
}

/// Issue 35 item 3 and issue 39 item 8, with the load given there: a
/// 30 mm blade at the order cap, orders [64, 64, 64], under a tip force of
/// 1e12 N. Its curvature concentrates in a boundary layer of
/// $\sqrt{EI/F} \approx 7\times10^{-8}$ m that no order resolves, and
/// the solve (its path, then the refinement of the limit it reports) ran
/// for minutes. Bounded by [`flexure::solver::Settings::max_evaluations`]
/// (here 12, so the test is cheap; the default bounds it the same way,
/// later), it stops at the fraction of the load it reached, with an error
/// that names the bound and says how to avoid it: lower orders.
#[test]
fn a_spatial_file_at_the_order_cap_under_1e12_n_stops_at_its_work_bound() {
    use flexure::mechanism::statics::solve;
    let text = "dimension = 3\n\
        [[joint]]\nname = \"blade\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
        length = 0.03\nmodulus = 200e9\nwidth = 0.01\nthickness = 0.0003\npoisson = 0.3\norders = [64, 64, 64]\n\
        [[force]]\nname = \"push\"\nbody = \"tip\"\nforce = [0.0, 1e12, 0.0]\n";
    let m = flexure::mechanism::file::spatial_from_toml(text).unwrap();
    let settings = flexure::solver::Settings { max_evaluations: 12, ..Default::default() };
    match solve(&m, &settings) {
        Err(e @ Error::ContinuationStalled { load_fraction, .. }) => {
            assert!(load_fraction > 0.0 && load_fraction < 1.0, "{e}");
            let message = e.to_string();
            assert!(message.contains("its limit of 12 Newton evaluations (max_evaluations)"), "{message}");
            assert!(message.contains("lower the flexures' orders"), "{message}");
        }
        other => panic!("expected the work bound, got {other:?}"),
    }
}
