//! The stability limit of a mechanism's loads
//! (`mechanism::stability_limit`): against closed forms, with and without
//! contact.

use flexure::StabilityLimit;
use flexure::mechanism::file::from_toml;
use flexure::mechanism::stability_limit::stability_limit;
use flexure::mechanism::statics::Settings;

/// A strip (L = 0.1 m, EI = 0.01 N·m², order `order`) clamped on a carriage
/// that slides along it on a spring of 100 N/m, pushed by 1 N towards a
/// wall 0.1 mm past its tip, of friction `mu`.
fn column(order: usize, mu: f64) -> String {
    format!(
        "[[joint]]\nname = \"feed\"\nkind = \"prismatic\"\nparent = \"ground\"\nchild = \"carriage\"\nstiffness = 100.0\n\
         [[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"carriage\"\nchild = \"tip\"\nlength = 0.1\nei = 0.01\norder = {order}\n\
         [[force]]\nname = \"push\"\nbody = \"carriage\"\nforce = [1.0, 0.0]\n\
         [[geom]]\nname = \"wall\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.1001, 0.0]\nnormal = [-1.0, 0.0]\nfriction = {mu}\n"
    )
}

/// A column pushed into a wall: once its tip touches (at 100 N/m × 0.1 mm
/// = 0.01 N of push), the wall carries the rest. On a rough wall the tip
/// sticks, pinned, so the strip buckles as a clamped–pinned column,
/// $P = (4.4934)^2 EI/L^2$ = 20.19 N, where on a frictionless wall it slides
/// and buckles as a cantilever, $P = \pi^2 EI/4L^2$ = 2.467 N: the limit
/// follows the contact's state along the path. Each factor (on the 1 N
/// push) to $10^{-5}$ of the closed form plus the 0.01 N: the stability
/// margin moves a limit by about $10^{-6}$ of itself, and orders 10 and
/// 12 agree to $10^{-9}$ (order 4 misses the pinned one by 0.5 %).
#[test]
fn a_column_pushed_into_a_wall_buckles_pinned_where_its_tip_sticks_and_free_where_it_slides() {
    let ei_l2 = 0.01 / 0.01;
    let pinned = 4.493409457909064f64.powi(2) * ei_l2 + 0.01;
    let free = std::f64::consts::PI.powi(2) / 4.0 * ei_l2 + 0.01;
    for (mu, exact) in [(0.5, pinned), (0.0, free)] {
        let m = from_toml(&column(10, mu)).unwrap();
        let l = stability_limit(&m, &Settings::default(), 1000.0).unwrap();
        let StabilityLimit::Lost { factor } = l else { panic!("μ = {mu}: {l:?}") };
        assert!((factor / exact - 1.0).abs() < 1e-5, "μ = {mu}: {factor}, not {exact}");
    }
}

/// A strip (L = 0.1 m, EI = 0.01 N·m², 0.1 kg/m) sagging under its weight
/// onto a floor 1 mm below it: its tip rests on the floor, and the more it
/// weighs the flatter it lies there, until its tip's slope is zero and it
/// would lie along the floor, which is refused: the path holds up to that
/// factor, and says why it goes no further. A propped cantilever's slope
/// at the prop, $wL^3/6EI - RL^2/2EI$ with $\delta = wL^4/8EI - RL^3/3EI$,
/// is zero at $w = 72EI\delta/L^4$ = 7.2 N/m, 7.339 times the weight: to
/// $10^{-3}$ (Euler–Bernoulli's, to within slopes of 1 %).
#[test]
fn a_strip_sagging_onto_a_floor_holds_until_it_would_lie_along_it() {
    let m = from_toml(
        "gravity = [0.0, -9.81]\n[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\n\
         length = 0.1\nei = 0.01\norder = 8\nmass_per_length = 0.1\n\
         [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.001]\nnormal = [0.0, 1.0]\n",
    )
    .unwrap();
    let flat = 72.0 * 0.01 * 0.001 / 0.1f64.powi(4) / (0.1 * 9.81);
    let l = stability_limit(&m, &Settings::default(), 1000.0).unwrap();
    let StabilityLimit::StableUpTo { factor, stalled: Some(why) } = &l else { panic!("{l:?}") };
    assert!((factor / flat - 1.0).abs() < 1e-3, "{factor}, not {flat}");
    assert!(why.starts_with("on the way from 4 to 8 times the load") && why.contains("lies along the geom"), "{why}");
}

/// A mechanism that nothing destabilizes is stable up to the largest
/// factor, with nothing stalled, with and without contact: a sprung arm
/// pushed across itself, and a strip whose tip is pressed onto a floor.
/// A largest factor below 1 is one stage; one that is not a finite number
/// above zero is refused by name.
#[test]
fn what_stays_stable_is_stable_up_to_the_largest_factor() {
    let arm = from_toml(
        "[[joint]]\nname = \"pivot\"\nkind = \"revolute\"\nparent = \"ground\"\nchild = \"arm\"\nstiffness = 1.0\n\
         [[force]]\nname = \"push\"\nbody = \"arm\"\nat = [0.1, 0.0]\nforce = [0.0, 1.0]\n",
    )
    .unwrap();
    let pressed = from_toml(
        "[[joint]]\nname = \"strip\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"tip\"\nlength = 0.1\nei = 0.01\norder = 8\n\
         [[force]]\nbody = \"tip\"\nforce = [0.0, -0.5]\n\
         [[geom]]\nname = \"floor\"\nbody = \"ground\"\nshape = \"plane\"\norigin = [0.0, -0.01]\nnormal = [0.0, 1.0]\n",
    )
    .unwrap();
    for m in [&arm, &pressed] {
        let l = stability_limit(m, &Settings::default(), 100.0).unwrap();
        assert_eq!(l, StabilityLimit::StableUpTo { factor: 100.0, stalled: None });
    }
    // A largest factor below the first stage's.
    let l = stability_limit(&pressed, &Settings::default(), 0.5).unwrap();
    assert_eq!(l, StabilityLimit::StableUpTo { factor: 0.5, stalled: None });
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = stability_limit(&arm, &Settings::default(), bad).unwrap_err().to_string();
        assert!(e.contains("max_factor") && e.contains("must be a finite number greater than zero"), "{e}");
    }
}

/// An interrupt that comes along the path stops the search, with contact
/// as without: an error that says so, not a path that stalled (it read as
/// stable up to where the interrupt came).
#[test]
fn an_interrupted_search_says_so() {
    static POLLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    // Past the assembly at no load, on the way.
    fn later() -> bool {
        POLLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed) >= 40
    }
    for mu in [0.5, 0.0] {
        let m = from_toml(&column(10, mu)).unwrap();
        POLLS.store(0, std::sync::atomic::Ordering::Relaxed);
        let e = flexure::solver::with_interrupt(later, || stability_limit(&m, &Settings::default(), 1000.0));
        assert!(
            matches!(e, Err(flexure::Error::Interrupted { load_fraction }) if load_fraction > 0.0),
            "μ = {mu}: {e:?}"
        );
    }
}
