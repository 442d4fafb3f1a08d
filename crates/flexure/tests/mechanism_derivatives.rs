//! The mechanism's exact derivatives against central finite differences, at
//! random states (seeded), for every example file: point Jacobians and
//! Hessians chained through the tree, the potential's gradient and Hessian
//! (joints, forces, moments, weights, tendons), the closures' residual,
//! Jacobian and multiplier Hessian, and the KKT problem the solver sees.
//!
//! Step and tolerance: a central difference with step h errs by
//! h²|f'''|/6 (truncation) plus about ε|f|/h (rounding). With h = 1e-5 (in
//! radians, or in units of the mechanism's length for slider travel) both
//! are near 1e-11 of the quantities' scale here, so agreement to 1e-6 of
//! the largest entry leaves a margin of 10⁴ for the unknown third
//! derivatives, while a missing or wrong term is of the size of the entry
//! itself, 10⁶ times larger. (This is far stricter than the √h ≈ 3e-3
//! that a forward difference would need.)

use flexure::mechanism::file::from_toml;
use flexure::mechanism::kinematics::{frames, point};
use flexure::mechanism::lagrangian::lagrangian;
use flexure::mechanism::statics::{Kkt, Settings};
use flexure::mechanism::{JointKind, Loads, Mechanism};
use flexure::solver::Problem;
use flexure::space::Wrench;
use nalgebra::{DMatrix, DVector};

const H: f64 = 1e-5;
const TOLERANCE: f64 = 1e-6;

/// SplitMix64: a seeded, reproducible source of uniform numbers.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in (−a, a).
    fn within(&mut self, a: f64) -> f64 {
        a * (2.0 * self.next() - 1.0)
    }
}

/// Every example file, each body given a random mass and centre of mass so
/// that gravity terms are exercised too.
fn examples(rng: &mut Rng) -> Vec<(String, Mechanism)> {
    let dir = format!("{}/../../examples", env!("CARGO_MANIFEST_DIR"));
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        // Planar examples: the spatial ones' derivatives are tests/spatial_mechanism_derivatives.rs's.
        .filter(|p| !std::fs::read_to_string(p).unwrap().contains("dimension = 3"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 6, "the example files");
    paths
        .into_iter()
        .map(|p| {
            let mut m = from_toml(&std::fs::read_to_string(&p).unwrap()).unwrap();
            // Without its geoms (the grasp's): these are the derivatives of the
            // problem without contact, which refuses a pair that may touch; the
            // contact terms' are checked in statics::contact's own test.
            m.geoms.clear();
            for b in m.bodies.iter_mut().skip(1) {
                b.mass = 0.01 + 0.1 * rng.next();
                b.com = nalgebra::Point2::new(rng.within(0.05), rng.within(0.05));
            }
            (p.file_name().unwrap().to_string_lossy().into_owned(), m)
        })
        .collect()
}

/// A random state near rest: 0.3 rad per angle-like coordinate, 5 mm of slider travel.
fn state(m: &Mechanism, rng: &mut Rng) -> Vec<f64> {
    let mut q = m.rest();
    for j in &m.joints {
        let amplitude = if let JointKind::Prismatic(_) = j.kind { 0.005 } else { 0.3 };
        for v in &mut q[j.offset..j.offset + j.kind.joint().dof()] {
            *v += rng.within(amplitude);
        }
    }
    q
}

/// Random loads of the file's shape, with gravity.
fn loads(m: &Mechanism, rng: &mut Rng) -> Loads {
    Loads {
        tension: m.tendons.iter().map(|_| 5.0 * rng.next()).collect(),
        force: m
            .forces
            .iter()
            .map(|_| Wrench { fx: rng.within(3.0), fy: rng.within(3.0), moment: rng.within(0.05) })
            .collect(),
        gravity: nalgebra::Vector2::new(rng.within(10.0), rng.within(10.0)),
    }
}

/// Central difference of `f` along coordinate `i` of `q`.
fn central<F: Fn(&[f64]) -> DVector<f64>>(f: F, q: &[f64], i: usize) -> DVector<f64> {
    let (mut a, mut b) = (q.to_vec(), q.to_vec());
    a[i] += H;
    b[i] -= H;
    (f(&a) - f(&b)) / (2.0 * H)
}

fn agree(what: &str, exact: &DMatrix<f64>, approx: &DMatrix<f64>) {
    let scale = exact.amax().max(approx.amax()).max(1e-12);
    let error = (exact - approx).amax() / scale;
    assert!(error < TOLERANCE, "{what}: relative error {error:.2e} (scale {scale:.2e})");
}

/// Columns of the finite-difference Jacobian of `f` at `q`.
fn jacobian<F: Fn(&[f64]) -> DVector<f64>>(f: F, q: &[f64]) -> DMatrix<f64> {
    let columns: Vec<DVector<f64>> = (0..q.len()).map(|i| central(&f, q, i)).collect();
    DMatrix::from_columns(&columns)
}

/// Point positions and angles, their Jacobians and Hessians, for random
/// points on every body, against differences of the frames.
#[test]
fn point_jacobians_and_hessians() {
    let mut rng = Rng(1);
    for (name, m) in examples(&mut rng) {
        for _ in 0..3 {
            let q = state(&m, &mut rng);
            for body in 0..m.bodies.len() {
                let r = nalgebra::Point2::new(rng.within(0.05), rng.within(0.05));
                let p = point(&m, &frames(&m, &q), body, r, true);
                let pose = |q: &[f64]| {
                    let f = frames(&m, q);
                    let w = world(&f.bodies[body], r);
                    DVector::from_vec(vec![f.bodies[body].phi, w[0], w[1]])
                };
                agree(
                    &format!("{name}: body {body} Jacobian"),
                    &p.jacobian,
                    &jacobian(pose, &q).transpose().transpose(),
                );
                let [hx, hy] = p.hessian.unwrap();
                for (row, h) in [(1, hx), (2, hy)] {
                    let grad = |q: &[f64]| {
                        let p = point(&m, &frames(&m, q), body, r, false);
                        p.jacobian.row(row).transpose()
                    };
                    agree(&format!("{name}: body {body} Hessian row {row}"), &h, &jacobian(grad, &q));
                }
            }
        }
    }
}

/// ∇V against differences of V, and ∇²V + Σμ∇²c against differences of
/// ∇V + Gᵀμ, under random loads of every kind.
#[test]
fn potential_gradient_and_lagrangian_hessian() {
    let mut rng = Rng(2);
    for (name, m) in examples(&mut rng) {
        for _ in 0..3 {
            let (q, l) = (state(&m, &mut rng), loads(&m, &mut rng));
            let mu: Vec<f64> = (0..m.constraints()).map(|_| rng.within(5.0)).collect();
            let a = lagrangian(&m, &q, &mu, &l).unwrap();
            let v = |q: &[f64]| DVector::from_element(1, lagrangian(&m, q, &mu, &l).unwrap().potential);
            agree(
                &format!("{name}: ∇V"),
                &DMatrix::from_column_slice(q.len(), 1, a.gradient.as_slice()),
                &jacobian(v, &q).transpose(),
            );
            let dl = |q: &[f64]| {
                let b = lagrangian(&m, q, &mu, &l).unwrap();
                &b.gradient + b.closure_jacobian.transpose() * DVector::from_column_slice(&mu)
            };
            agree(&format!("{name}: ∇²L"), &a.hessian, &jacobian(dl, &q));
        }
    }
}

/// The tendons alone: T·ℓ and its derivatives, as the change from no load
/// to tendon tension only.
#[test]
fn tendon_terms() {
    let mut rng = Rng(3);
    let mut tendons = 0;
    for (name, m) in examples(&mut rng) {
        if m.tendons.is_empty() {
            continue;
        }
        tendons += m.tendons.len();
        for _ in 0..3 {
            let q = state(&m, &mut rng);
            let mu = vec![0.0; m.constraints()];
            let zero = m.loads().zero_like();
            let pull = Loads { tension: m.tendons.iter().map(|_| 1.0 + 5.0 * rng.next()).collect(), ..zero.clone() };
            let part = |q: &[f64]| {
                let (a, b) = (lagrangian(&m, q, &mu, &pull).unwrap(), lagrangian(&m, q, &mu, &zero).unwrap());
                (a.potential - b.potential, &a.gradient - &b.gradient, &a.hessian - &b.hessian)
            };
            let (_, gradient, hessian) = part(&q);
            let value = |q: &[f64]| DVector::from_element(1, part(q).0);
            assert!(gradient.amax() > 0.0, "{name}: a test that pulls");
            agree(
                &format!("{name}: tendon gradient"),
                &DMatrix::from_column_slice(q.len(), 1, gradient.as_slice()),
                &jacobian(value, &q).transpose(),
            );
            agree(&format!("{name}: tendon Hessian"), &hessian, &jacobian(|q: &[f64]| part(q).1, &q));
        }
    }
    assert!(tendons >= 3, "tendons in the examples");
}

/// c(q) and G: position rows and (wrapped) angle rows of welds and pins.
#[test]
fn closure_residual_and_jacobian() {
    let mut rng = Rng(4);
    let mut closures = 0;
    for (name, m) in examples(&mut rng) {
        if m.closures.is_empty() {
            continue;
        }
        closures += m.closures.len();
        for _ in 0..3 {
            let q = state(&m, &mut rng);
            let mu = vec![0.0; m.constraints()];
            let zero = m.loads().zero_like();
            let a = lagrangian(&m, &q, &mu, &zero).unwrap();
            let c = |q: &[f64]| lagrangian(&m, q, &mu, &zero).unwrap().closure;
            agree(&format!("{name}: G"), &a.closure_jacobian, &jacobian(c, &q));
        }
    }
    assert!(closures >= 5, "closures in the examples");
}

/// The KKT problem as the solver sees it (scaled unknowns and rows): its
/// Jacobian, less the documented 1e-10 shift of the multiplier block,
/// against differences of its residual, and ∂r/∂λ against differences in λ.
#[test]
fn kkt_problem_jacobian_and_load_derivative() {
    let mut rng = Rng(5);
    for (name, m) in examples(&mut rng) {
        let (from, to) = (loads(&m, &mut rng), loads(&m, &mut rng));
        let mut kkt = Kkt::new(&m, &from, &to, &Settings::default()).unwrap();
        let (n, rows) = (m.dof(), m.constraints());
        let size = n + rows;
        for _ in 0..3 {
            let q = state(&m, &mut rng);
            let mu: Vec<f64> = (0..rows).map(|_| rng.within(5.0)).collect();
            let x = kkt.state(&q, &mu);
            let lambda = rng.next();
            let (mut r, mut jac, mut d) = (vec![0.0; size], vec![0.0; size * size], vec![0.0; size]);
            kkt.evaluate(&x, lambda, &mut r, Some(&mut jac), Some(&mut d)).unwrap();
            let mut exact = DMatrix::from_column_slice(size, size, &jac);
            for i in n..size {
                exact[(i, i)] += 1e-10;
            }
            let residual = |x: &[f64], lambda: f64| {
                let mut r = vec![0.0; size];
                Kkt::new(&m, &from, &to, &Settings::default())
                    .unwrap()
                    .evaluate(x, lambda, &mut r, None, None)
                    .unwrap();
                DVector::from_vec(r)
            };
            agree(&format!("{name}: KKT Jacobian"), &exact, &jacobian(|x: &[f64]| residual(x, lambda), &x));
            let dl = (residual(&x, lambda + H) - residual(&x, lambda - H)) / (2.0 * H);
            agree(
                &format!("{name}: ∂r/∂λ"),
                &DMatrix::from_column_slice(size, 1, &d),
                &DMatrix::from_column_slice(size, 1, dl.as_slice()),
            );
        }
    }
}

/// A branched tree of every joint kind (flexures of orders 1 to 5, a pin, a
/// free pin, a slider, a weld), loaded at three bodies, with masses: the
/// shape the tree factorization must handle.
fn branched_tree(rng: &mut Rng) -> Mechanism {
    let text = "\
[[joint]]\nname = \"a\"\nkind = \"flexure\"\nparent = \"ground\"\nchild = \"b1\"\nlength = 0.03\nei = 1e-3\n\
[[joint]]\nname = \"b\"\nkind = \"revolute\"\nparent = \"b1\"\nchild = \"b2\"\norigin = [0.01, 0.005, 0.3]\nstiffness = 0.5\n\
[[joint]]\nname = \"c\"\nkind = \"flexure\"\nparent = \"b1\"\nchild = \"b3\"\norigin = [0.0, -0.01, -0.5]\nlength = 0.02\nei = 5e-4\norder = 2\n\
[[joint]]\nname = \"d\"\nkind = \"prismatic\"\nparent = \"b3\"\nchild = \"b4\"\norigin = [0.01, 0.0, 0.2]\nstiffness = 300.0\n\
[[joint]]\nname = \"e\"\nkind = \"flexure\"\nparent = \"b4\"\nchild = \"b5\"\nlength = 0.025\nei = 2e-3\norder = 5\n\
[[joint]]\nname = \"f\"\nkind = \"fixed\"\nparent = \"b2\"\nchild = \"b6\"\norigin = [0.01, 0.0, 0.1]\n\
[[joint]]\nname = \"g\"\nkind = \"flexure\"\nparent = \"b6\"\nchild = \"b7\"\nlength = 0.01\nei = 1e-3\norder = 1\n\
[[joint]]\nname = \"h\"\nkind = \"revolute\"\nparent = \"b4\"\nchild = \"b8\"\norigin = [0.0, 0.01, 0.0]\n\
[[joint]]\nname = \"i\"\nkind = \"flexure\"\nparent = \"b8\"\nchild = \"b9\"\nlength = 0.02\nei = 1e-3\norder = 4\n\
[[force]]\nbody = \"b5\"\nat = [0.01, 0.0]\nforce = [1.0, 1.0]\n\
[[force]]\nbody = \"b7\"\nat = [0.0, 0.005]\nforce = [1.0, 1.0]\nmoment = 0.01\n\
[[force]]\nbody = \"b9\"\nat = [0.005, 0.0]\nforce = [1.0, 1.0]\n";
    let mut m = from_toml(text).unwrap();
    for b in m.bodies.iter_mut().skip(1) {
        b.mass = 0.01 + 0.1 * rng.next();
        b.com = nalgebra::Point2::new(rng.within(0.05), rng.within(0.05));
    }
    m
}

/// The tree's O(n) factorization (`Problem::factor`, `solve_factored`) of
/// the KKT Jacobian of mechanisms without closures or tendons solves what
/// dense LU solves: at random states and loads of a branched tree of every
/// joint kind and of the closure-free examples, the two answers agree to
/// 1e-9 of their size (both are backward stable; these Jacobians have
/// condition numbers below about 1e5, so they agree to about 1e-11). And
/// the stability verdict (`Problem::stable`, the tree's pivots) is the sign
/// of the smallest eigenvalue of the Hessian from `lagrangian` (an
/// independent assembly, by nalgebra's eigensolver), in units of each
/// joint's stiffness, wherever it is clear of zero by 1e-3, far beyond the
/// verdict's margin (1e-6); both verdicts occur. Mechanisms with closures or tendons
/// decline (`factor` is false) and keep dense LU.
#[test]
fn tree_factorization_against_dense_lu() {
    let mut rng = Rng(7);
    let mut cases: Vec<(String, Mechanism)> = vec![("branched tree".into(), branched_tree(&mut rng))];
    cases.extend(examples(&mut rng));
    let (mut stable, mut unstable) = (0, 0);
    for (name, m) in cases {
        let tree = m.closures.is_empty() && m.tendons.is_empty();
        for _ in 0..12 {
            let scale = 10f64.powf(-3.0 + 3.5 * rng.next());
            let loads = |rng: &mut Rng| {
                let mut l = loads(&m, rng);
                l.force.iter_mut().for_each(|w| (0..3).for_each(|i| w[i] *= scale));
                l
            };
            let (from, to) = (loads(&mut rng), loads(&mut rng));
            let mut kkt = Kkt::new(&m, &from, &to, &Settings::default()).unwrap();
            let n = m.dof();
            let size = n + m.constraints();
            let q = state(&m, &mut rng);
            let x = kkt.state(&q, &vec![0.0; m.constraints()]);
            let lambda = rng.next();
            let (mut r, mut jac) = (vec![0.0; size], vec![0.0; size * size]);
            kkt.evaluate(&x, lambda, &mut r, Some(&mut jac), None).unwrap();
            assert_eq!(
                kkt.factor(&jac),
                tree,
                "{name}: the tree factorization applies exactly without closures and tendons"
            );
            if !tree {
                continue;
            }
            let b: Vec<f64> = (0..n).map(|_| rng.within(1.0)).collect();
            let mut y = b.clone();
            kkt.solve_factored(&mut y);
            let dense = DMatrix::from_column_slice(n, n, &jac).lu().solve(&DVector::from_vec(b)).unwrap();
            let error = (DVector::from_vec(y) - &dense).amax() / dense.amax();
            assert!(error < 1e-9, "{name}: tree solve against LU: relative error {error:.2e}");

            // In each joint's own units (S H S, S = diag(1/√k), k the
            // elastic diagonal, the stiffest's for a free pin): the verdict
            // is the sign of the lowest eigenvalue unless it is within the
            // margin of zero.
            let h = lagrangian(&m, &q, &[], &from.lerp(&to, lambda)).unwrap().hessian;
            let k = lagrangian(&m, &m.rest(), &[], &from.zero_like()).unwrap().hessian.diagonal();
            let s = k.map(|k| 1.0 / if k > 0.0 { k } else { 1.0 }.sqrt());
            let scaled = DMatrix::from_fn(n, n, |r, c| h[(r, c)] * s[r] * s[c]);
            let lowest = scaled.symmetric_eigen().eigenvalues.min();
            if lowest.abs() > 1e-3 {
                let verdict = kkt.stable(&x, lambda, &jac);
                assert_eq!(verdict, lowest > 0.0, "{name}: stability against the eigenvalues ({lowest:.3e})");
                if verdict { stable += 1 } else { unstable += 1 }
            }
        }
    }
    assert!(stable >= 3 && unstable >= 3, "both verdicts tested: {stable} stable, {unstable} unstable");
}

/// A point given in a frame, in the world, as components.
fn world(frame: &flexure::Pose, r: impl Into<nalgebra::Point2<f64>>) -> [f64; 2] {
    let w = frame.act(&r.into());
    [w.x, w.y]
}
