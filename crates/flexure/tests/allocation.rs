//! The evaluation path allocates nothing: kinematics, Jacobian, Hessians,
//! energy and deflect, at orders 3 and 6 (the fixed-size kernels) and 9
//! (the any-order path), counted by a global allocator.

use flexure::{Flexure, Kinematics, Level, StaticsData, TipLoad, deflect, energy, energy_gradient, update_kinematics};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// Counts allocations made by the current thread (tests run on several threads).
struct Counting;

thread_local! {
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        COUNT.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        COUNT.with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn allocations(f: impl FnOnce()) -> usize {
    let before = COUNT.with(Cell::get);
    f();
    COUNT.with(Cell::get) - before
}

#[test]
fn evaluation_path_does_not_allocate() {
    for order in [3, 6, 9] {
        let f = Flexure::new(1.0, 1.0, order).unwrap();
        let alpha: Vec<f64> = (0..order).map(|i| 0.3 / (i + 1) as f64).collect();
        let mut k = Kinematics::new(&f);
        let mut g = vec![0.0; order];
        let mut data = StaticsData::new(&f);
        let load = TipLoad::polar(0.2, 3.8477, 45f64.to_radians());
        // The counter must see allocations at all, or the test proves nothing.
        assert!(allocations(|| drop(std::hint::black_box(vec![0u8; 16]))) > 0);
        let n = allocations(|| {
            for level in [Level::Pose, Level::Jacobian, Level::Hessian] {
                update_kinematics(&f, &alpha, &mut k, level);
            }
            std::hint::black_box(flexure::pose_root_tip(&f, &alpha));
            std::hint::black_box(energy(&f, &alpha));
            energy_gradient(&f, &alpha, &mut g);
            let eq = deflect(&f, &load, &mut data, &Default::default()).unwrap();
            assert!(eq.load_steps > 1, "a path that exercises continuation");
        });
        assert_eq!(n, 0, "order {order}: {n} allocations");
    }
}

/// A mechanism's Newton iterations allocate nothing once its problem and
/// the solver's buffers exist: a whole `solver::newton` at the full load of
/// a 4-flexure chain under a tip force (several iterations, each evaluating
/// residual, Jacobian and load derivative, each step by the tree's
/// factorization) and its stability test (no closures: the tree's pivots),
/// repeated from the rest state on warm buffers, then a whole
/// `solver::continuation` from rest; and, for the parallelogram (closures),
/// one evaluation with its Jacobian. Counted per call: any allocation fails
/// the test.
#[test]
fn mechanism_newton_does_not_allocate() {
    use flexure::mechanism::file::from_toml;
    use flexure::mechanism::statics::{Kkt, Settings};
    use flexure::solver::{self, Problem};
    let mut text = String::new();
    for i in 0..4 {
        let parent = if i == 0 { "ground".to_string() } else { format!("b{}", i - 1) };
        text += &format!("[[joint]]\nname = \"j{i}\"\nkind = \"flexure\"\nparent = \"{parent}\"\nchild = \"b{i}\"\n");
        text += "length = 0.25\nei = 1.0\n";
    }
    text += "[[force]]\nbody = \"b3\"\nat = [0.0, 0.0]\nforce = [0.0, 0.5]\n";
    let chain = from_toml(&text).unwrap();
    let settings = Settings::default();
    let zero = chain.loads().zero_like();
    let mut kkt = Kkt::new(&chain, &zero, &chain.loads(), &settings).unwrap();
    let mut ws = solver::SolverWorkspace::new(kkt.dim());
    let start = kkt.state(&chain.rest(), &[]);
    ws.x.copy_from_slice(&start);
    solver::newton(&mut kkt, &mut ws, 1.0, &settings).unwrap();
    ws.x.copy_from_slice(&start);
    let mut report = None;
    let mut stable = false;
    let n = allocations(|| {
        report = Some(solver::newton(&mut kkt, &mut ws, 1.0, &settings).unwrap());
        stable = kkt.stable(&ws.x, 1.0, &ws.jacobian);
        std::hint::black_box(kkt.distance(&ws.x, &start));
    });
    let report = report.unwrap();
    assert!(report.iterations > 2 && stable, "a solve that iterates to a stable state: {report:?}");
    assert_eq!(n, 0, "chain: {n} allocations in {} Newton iterations", report.iterations);
    // A whole continuation from rest on the same buffers: Newton steps and
    // tangents by the tree's factorization, stability and far-from-instability
    // tests on its pivots, step bounds.
    let mut path = None;
    let n = allocations(|| {
        ws.x.copy_from_slice(&start);
        path = Some(solver::continuation(&mut kkt, &mut ws, &settings).unwrap());
    });
    let path = path.unwrap();
    assert!(path.stable && path.iterations >= 2, "a continuation that iterates: {path:?}");
    assert_eq!(n, 0, "chain: {n} allocations in a continuation of {} steps", path.steps);

    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/parallelogram.toml");
    let text = std::fs::read_to_string(path).unwrap().replace("force = [0.0, -1.0]", "force = [0.5, -1.0]");
    let stage = from_toml(&text).unwrap();
    let zero = stage.loads().zero_like();
    let mut kkt = Kkt::new(&stage, &zero, &stage.loads(), &settings).unwrap();
    let size = kkt.dim();
    let x = kkt.state(&stage.rest(), &vec![0.0; stage.constraints()]);
    let (mut r, mut jac, mut dl) = (vec![0.0; size], vec![0.0; size * size], vec![0.0; size]);
    kkt.evaluate(&x, 0.5, &mut r, Some(&mut jac), Some(&mut dl)).unwrap();
    let n = allocations(|| kkt.evaluate(&x, 0.5, &mut r, Some(&mut jac), Some(&mut dl)).unwrap());
    assert!(r.iter().any(|v| *v != 0.0), "a loaded state has a residual");
    assert_eq!(n, 0, "parallelogram: {n} allocations in one evaluation");
}

/// A warm `solve_with` of the parallelogram (two closures: assembly,
/// tangent, corrector, stability tests on the workspace's buffers, and the
/// solution) allocates exactly the three vectors of the `Solution` it
/// returns: `q`, `multipliers` and `loads.force` (no tendons: `tension` is
/// empty and allocates nothing).
#[test]
fn parallelogram_solve_with_allocates_only_its_answer() {
    use flexure::mechanism::file::from_toml;
    use flexure::mechanism::statics::{Settings, Workspace, solve_with};
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/parallelogram.toml");
    let text = std::fs::read_to_string(path).unwrap().replace("force = [0.0, -1.0]", "force = [0.5, -1.0]");
    let stage = from_toml(&text).unwrap();
    let settings = Settings::default();
    let mut work = Workspace::new(&stage);
    let first = solve_with(&stage, &settings, &mut work).unwrap();
    let mut found = None;
    let n = allocations(|| found = Some(solve_with(&stage, &settings, &mut work).unwrap()));
    let s = found.unwrap();
    assert_eq!(s, first);
    assert!(s.stable && s.iterations >= 2, "a solve that iterates: {s:?}");
    assert!(s.loads.tension.is_empty() && !s.q.is_empty() && !s.multipliers.is_empty() && !s.loads.force.is_empty());
    assert_eq!(n, 3, "parallelogram: {n} allocations in a warm solve_with");
}

/// A warm `connect_with` (issue 4's Fig. 4 pose, orders 3 and 9, and a
/// chain of 22 segments) allocates exactly the answer's coordinates
/// (`Connection::alpha`): kinematics, KKT evaluations, Newton steps and
/// tangents run on `ConnectData`'s buffers.
#[test]
fn connect_with_allocates_only_its_answer() {
    use flexure::Pose;
    use flexure::connect::{ConnectData, connect_with};
    let target = Pose { phi: std::f64::consts::FRAC_PI_2, x: 0.55, y: 0.65 };
    for f in [
        Flexure::new(1.0, 1.0, 3).unwrap(),
        Flexure::new(1.0, 1.0, 9).unwrap(),
        Flexure::segments(1.0, 1.0, 22).unwrap(),
    ] {
        let mut data = ConnectData::new(&f);
        let first = connect_with(&f, &target, &mut data).unwrap();
        let mut found = None;
        let n = allocations(|| found = Some(connect_with(&f, &target, &mut data).unwrap()));
        let c = found.unwrap();
        assert_eq!(c, first);
        assert!(c.iterations >= 2, "a solve that iterates: {c:?}");
        assert_eq!(n, 1, "order {}: {n} allocations in a warm connect_with", f.order());
    }
}

/// Non-uniform sections keep evaluation allocation-free (issue "Sections"):
/// the stiffness matrix is integrated once when the flexure is built, so
/// energy, gradient, kinematics and a whole `deflect` on a tapered and on a
/// notched flexure allocate nothing on warm buffers; nor does the dynamics'
/// mass matrix with its velocity-product terms (`dynamics::update_mass`).
#[test]
fn sections_and_mass_do_not_allocate() {
    use flexure::inertia::RigidInertia;
    use flexure::mass::{MassData, MassModel, update as update_mass};
    use flexure::section::{Notch, Profile, Section};
    let taper = Section::rectangle(200e9, None, Profile::Constant(0.01), Profile::Linear { root: 4e-4, tip: 2e-4 })
        .unwrap()
        .with_density(7850.0)
        .unwrap();
    let notch = Section::rectangle(70e9, None, Profile::Constant(0.01), Profile::Constant(0.004))
        .unwrap()
        .with_notch(Notch { radius: 0.005, min_thickness: 0.0006 })
        .unwrap()
        .with_density(2700.0)
        .unwrap();
    for (section, order) in [(taper, 6), (notch, 12)] {
        let f = Flexure::new(0.01, 1.0, order).unwrap().with_section(section).unwrap();
        let alpha: Vec<f64> = (0..order).map(|i| 0.3 / (i + 1) as f64).collect();
        let mut g = vec![0.0; order];
        let mut data = StaticsData::new(&f);
        let load = TipLoad { moment: 0.0, fx: 0.0, fy: 0.5 * f.ei() / (0.01 * 0.01) };
        let body = RigidInertia::new(0.005, 1e-7, [0.002, 0.0]).unwrap();
        let model = MassModel::new(&f, Some(&body)).unwrap();
        let mut mass = MassData::new(&model);
        deflect(&f, &load, &mut data, &Default::default()).unwrap();
        let n = allocations(|| {
            std::hint::black_box(energy(&f, &alpha));
            energy_gradient(&f, &alpha, &mut g);
            deflect(&f, &load, &mut data, &Default::default()).unwrap();
            update_mass(&model, &alpha, Some(&alpha), &mut mass);
            std::hint::black_box(mass.kinetic_energy(&alpha));
        });
        assert_eq!(n, 0, "order {order}: {n} allocations");
    }
}
