//! The spatial flexure's energy (`flexure::spatial`): its Gram matrix
//! against exact integrals of the shifted Legendre polynomials' monomial
//! expansions, its κ_z block against the planar flexure's stiffness
//! matrix, its diagonal for a uniform section, and the energy's gradient
//! against central differences and dual numbers.

use flexure::Flexure;
use flexure::section::{Profile, Section, SpatialSection};
use flexure::spatial::{SpatialFlexure, energy, energy_gradient};
use num_dual::Dual64;

/// The monomial coefficients of $\tilde P_n(t) = \sum_k (-1)^{n+k}\binom nk\binom{n+k}k t^k$.
fn monomials(n: usize) -> Vec<f64> {
    let binomial = |a: usize, b: usize| (0..b).fold(1.0, |acc, i| acc * (a - i) as f64 / (i + 1) as f64);
    (0..=n).map(|k| if (n + k).is_multiple_of(2) { 1.0 } else { -1.0 } * binomial(n, k) * binomial(n + k, k)).collect()
}

/// $\int_0^1 k(t)\tilde P_i\tilde P_j\thinspace dt$ for a profile linear between
/// `points`, by exact integration of each piece's polynomial.
fn exact_gram_entry(points: &[[f64; 2]], i: usize, j: usize) -> f64 {
    let (a, b) = (monomials(i), monomials(j));
    let mut product = vec![0.0; i + j + 1];
    for (p, x) in a.iter().enumerate() {
        for (q, y) in b.iter().enumerate() {
            product[p + q] += x * y;
        }
    }
    let mut total = 0.0;
    for w in points.windows(2) {
        let ([t0, v0], [t1, v1]) = (w[0], w[1]);
        // k(t) = c0 + c1 t on the piece.
        let c1 = (v1 - v0) / (t1 - t0);
        let c0 = v0 - c1 * t0;
        for (m, c) in product.iter().enumerate() {
            let power = |e: i32| (t1.powi(e) - t0.powi(e)) / e as f64;
            total += c * (c0 * power(m as i32 + 1) + c1 * power(m as i32 + 2));
        }
    }
    total
}

/// A twist stiffness tapering linearly, a bending one given as a table with
/// two interior points, and a constant one.
fn profiles() -> [Vec<[f64; 2]>; 3] {
    [vec![[0.0, 0.8], [1.0, 0.3]], vec![[0.0, 2.0], [0.3, 1.2], [0.7, 1.5], [1.0, 0.9]], vec![[0.0, 1.1], [1.0, 1.1]]]
}

fn profile(points: &[[f64; 2]]) -> Profile {
    Profile::Table(points.to_vec())
}

/// Every block of K against the exact integrals, $K^{(c)}_{ij} = \frac1L\int k_c\tilde P_i\tilde P_j$,
/// to 1e-12 of the largest entry: the reference's own rounding, its
/// monomials' coefficients reaching 630 at degree 4 and cancelling, is up to
/// 3e-13 (measured on the constant block's zeros); the blocks between
/// components are exactly 0.
#[test]
fn gram_matrix_is_the_exact_integral() {
    let [gj, ei_y, ei_z] = profiles();
    let s = SpatialSection::given(profile(&gj), profile(&ei_y), profile(&ei_z)).unwrap();
    let orders = [4, 3, 5];
    let l = 0.7;
    let f = SpatialFlexure::new(l, s, orders).unwrap();
    let k = f.stiffness_matrix();
    let n = 12;
    let largest = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for a in 0..n {
        for b in 0..n {
            let ((ca, i), (cb, j)) = (f.component(a), f.component(b));
            let expected = if ca == cb { exact_gram_entry(&profiles()[ca], i, j) / l } else { 0.0 };
            if ca != cb {
                assert_eq!(k[a * n + b], 0.0, "coupling ({a}, {b})");
            }
            assert!(
                (k[a * n + b] - expected).abs() < 1e-12 * largest,
                "K[{a}][{b}] = {} against {expected}",
                k[a * n + b]
            );
        }
    }
}

/// The κ_z block is the planar flexure's stiffness matrix for the same
/// EI(s) (a table), to 1e-12 of its largest entry: κ_z's coefficients are
/// the planar coordinates.
#[test]
fn in_plane_block_is_the_planar_stiffness_matrix() {
    let [gj, ei_y, _] = profiles();
    let table = vec![[0.0, 1.4], [0.45, 0.7], [1.0, 1.0]];
    let s = SpatialSection::given(profile(&gj), profile(&ei_y), profile(&table)).unwrap();
    let f = SpatialFlexure::new(0.9, s, [2, 2, 4]).unwrap();
    let planar = Flexure::new(0.9, 1.0, 4).unwrap().with_section(Section::given(profile(&table)).unwrap()).unwrap();
    let (k, kp) = (f.stiffness_matrix(), planar.stiffness_matrix());
    let largest = kp.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for i in 0..4 {
        for j in 0..4 {
            let (a, b) = (4 + i, 4 + j);
            assert!((k[a * 8 + b] - kp[i * 4 + j]).abs() < 1e-12 * largest, "({i}, {j})");
        }
    }
}

/// A uniform section's K is exactly diagonal, $\frac{k_c}{L}\frac{1}{2i+1}$ (Eq. 28 per component).
#[test]
fn uniform_section_is_diagonal() {
    let f = SpatialFlexure::new(2.0, SpatialSection::uniform(0.5, 3.0, 1.5).unwrap(), [3, 2, 4]).unwrap();
    let k = f.stiffness_matrix();
    let n = 9;
    for a in 0..n {
        for b in 0..n {
            let (c, i) = f.component(a);
            let expected = if a == b { [0.5, 3.0, 1.5][c] / 2.0 / (2 * i + 1) as f64 } else { 0.0 };
            assert!((k[a * n + b] - expected).abs() <= 1e-16, "K[{a}][{b}]");
        }
    }
}

/// The energy is $\frac12(\alpha-\kappa)^TK(\alpha-\kappa)$ (1e-14 against the
/// quadratic form written out); its gradient equals central differences of
/// the energy (a quadratic: exact but for rounding, tolerance 1e-9) and the
/// dual numbers' derivative (1e-14).
#[test]
fn gradient_is_the_energy_derivative() {
    let [gj, ei_y, ei_z] = profiles();
    let s = SpatialSection::given(profile(&gj), profile(&ei_y), profile(&ei_z)).unwrap();
    let rest = [0.1, -0.2, 0.0, 0.3, 0.05, 0.0, 0.4, -0.1];
    let f = SpatialFlexure::new(0.6, s, [3, 2, 3]).unwrap().with_rest(&rest).unwrap();
    let alpha = [0.7, -0.3, 0.2, -0.9, 0.4, 1.1, -0.5, 0.3];
    let k = f.stiffness_matrix();
    let d: Vec<f64> = alpha.iter().zip(&rest).map(|(a, r)| a - r).collect();
    let quadratic: f64 = (0..8).map(|a| (0..8).map(|b| 0.5 * d[a] * k[a * 8 + b] * d[b]).sum::<f64>()).sum();
    assert!((energy(&f, &alpha) - quadratic).abs() < 1e-14);
    let mut g = [0.0; 8];
    energy_gradient(&f, &alpha, &mut g);
    let h = 1e-5;
    for a in 0..8 {
        let (mut p, mut m) = (alpha, alpha);
        p[a] += h;
        m[a] -= h;
        let fd = (energy(&f, &p) - energy(&f, &m)) / (2.0 * h);
        assert!((g[a] - fd).abs() < 1e-9, "gradient {a}: {} against {fd}", g[a]);
        let x: Vec<Dual64> = (0..8).map(|i| Dual64::new(alpha[i], (i == a) as u8 as f64)).collect();
        assert!((g[a] - energy(&f, &x).eps).abs() < 1e-14);
    }
}

/// Stiffnesses outside the model's range are refused, naming which.
#[test]
fn stiffness_out_of_range_names_it() {
    let e = SpatialFlexure::new(1.0, SpatialSection::uniform(1.0, 1e16, 1.0).unwrap(), [3, 3, 3]).unwrap_err();
    assert!(matches!(e, flexure::Error::InvalidParameter { name: "ei_y", .. }), "{e}");
}
