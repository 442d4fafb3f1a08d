//! Spatial sections: the torsion series against Timoshenko and Goodier's
//! table, the rectangle's and the circle's closed forms, tapers, stress at
//! the candidate points, and bad input.

use flexure::Error;
use flexure::section::torsion::{alpha, beta, long_side_shear, short_side_shear};
use flexure::section::{Profile, Shear, SpatialSection, StressPoint};
use std::f64::consts::PI;

/// β(r) and α(r) against S. P. Timoshenko and J. N. Goodier, *Theory of
/// Elasticity* (3rd ed., 1970), §109, the table after Eq. 167 (their k₁ is
/// our β, k₂ our α, k the long-side shear): printed to three digits, so a
/// tolerance of 5e-4 (half the last digit); r = 1's β to the four digits
/// 0.1406 that the same table quotes. r → ∞: 1/3, to rounding. (α(5) is
/// 0.291500, printed 0.291: the bound is 5.01e-4 for that halfway case.)
#[test]
fn torsion_coefficients_match_timoshenko_goodier_table() {
    let table = [
        (1.0, 0.675, 0.141, 0.208),
        (1.5, 0.848, 0.196, 0.231),
        (2.0, 0.930, 0.229, 0.246),
        (2.5, 0.968, 0.249, 0.258),
        (3.0, 0.985, 0.263, 0.267),
        (4.0, 0.997, 0.281, 0.282),
        (5.0, 0.999, 0.291, 0.291),
        (10.0, 1.000, 0.312, 0.312),
    ];
    for (r, k, b, a) in table {
        assert!((long_side_shear(r) - k).abs() < 5e-4, "k({r}) = {}", long_side_shear(r));
        assert!((beta(r) - b).abs() < 5e-4, "β({r}) = {}", beta(r));
        assert!((alpha(r) - a).abs() < 5.01e-4, "α({r}) = {}", alpha(r));
    }
    assert!((beta(1.0) - 0.1406).abs() < 5e-5);
    assert!((beta(1e12) - 1.0 / 3.0).abs() < 1e-12 && beta(1e12) < 1.0 / 3.0);
    // The thin-strip asymptote β = (1 − 0.63025/r)/3, exact to e^{−πr}.
    assert!((beta(20.0) - (1.0 - 0.630_249 / 20.0) / 3.0).abs() < 1e-8);
}

/// A square's four sides are alike: the short-side series (a different
/// sum, alternating in tanh) equals the long-side one to rounding (1e-14);
/// a thin strip's short side carries 8·Catalan/π² of Gθc (to 1e-12).
#[test]
fn short_side_shear_of_a_square_equals_the_long_side() {
    assert!((short_side_shear(1.0) - long_side_shear(1.0)).abs() < 1e-14);
    assert!((short_side_shear(1e9) - 8.0 * 0.915_965_594_177_219 / (PI * PI)).abs() < 1e-12);
    // Between, the short side carries less than the long one.
    for r in [1.5, 2.0, 5.0, 10.0] {
        assert!(short_side_shear(r) < long_side_shear(r), "r = {r}");
    }
}

/// The rectangle's closed forms EI_z = E w h³/12, EI_y = E h w³/12,
/// GJ = G β(r) b c³ with G = E/(2(1 + ν)) or given, to 1e-14 relative; a
/// strip stood on edge (w < h) swaps EI_y and EI_z and keeps GJ.
#[test]
fn rectangle_closed_forms() {
    let (e, nu, w, h) = (70e9, 0.33, 0.012, 0.003);
    let s = SpatialSection::rectangle(e, Shear::Poisson(nu), Profile::Constant(w), Profile::Constant(h)).unwrap();
    let g = e / (2.0 * (1.0 + nu));
    let [gj, ei_y, ei_z] = s.stiffness(0.7);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-14 * b.abs();
    assert!(close(ei_z, e * w * h.powi(3) / 12.0));
    assert!(close(ei_y, e * h * w.powi(3) / 12.0));
    assert!(close(gj, g * beta(4.0) * w * h.powi(3)));
    let edge = SpatialSection::rectangle(e, Shear::Modulus(g), Profile::Constant(h), Profile::Constant(w)).unwrap();
    let [gj2, ei_y2, ei_z2] = edge.stiffness(0.7);
    assert!(close(gj2, gj) && close(ei_y2, ei_z) && close(ei_z2, ei_y));
    assert!(s.is_uniform() && s.breakpoints().is_empty());
}

/// The circle: EI = Eπd⁴/64 about both axes, GJ = Gπd⁴/32 (1e-14 relative).
#[test]
fn circle_closed_forms() {
    let (e, nu, d) = (200e9, 0.3, 2e-3);
    let s = SpatialSection::circle(e, nu, Profile::Constant(d)).unwrap();
    let [gj, ei_y, ei_z] = s.stiffness(0.2);
    let i = PI * d.powi(4) / 64.0;
    assert!((ei_y - e * i).abs() <= 1e-14 * e * i && ei_y == ei_z);
    assert!((gj - e / (2.0 * (1.0 + nu)) * 2.0 * i).abs() <= 1e-14 * gj);
}

/// Tapers: a width tapering linearly and a thickness given by a table give
/// the closed forms of the local w(t), h(t) at every t (1e-14 relative),
/// and the table's inner point is a breakpoint; a tapered circle likewise.
#[test]
fn tapered_profiles() {
    let width = Profile::Linear { root: 0.02, tip: 0.01 };
    let thickness = Profile::Table(vec![[0.0, 1e-3], [0.4, 5e-4], [1.0, 8e-4]]);
    let (e, g) = (200e9, 77e9);
    let s = SpatialSection::rectangle(e, Shear::Modulus(g), width.clone(), thickness.clone()).unwrap();
    assert!(!s.is_uniform());
    assert_eq!(s.breakpoints(), vec![0.4]);
    for t in [0.0, 0.2, 0.4, 0.65, 1.0] {
        let (w, h) = (width.at(t), thickness.at(t));
        let [gj, ei_y, ei_z] = s.stiffness(t);
        assert!((ei_z - e * w * h.powi(3) / 12.0).abs() <= 1e-14 * ei_z);
        assert!((ei_y - e * h * w.powi(3) / 12.0).abs() <= 1e-14 * ei_y);
        assert!((gj - g * beta(w / h) * w * h.powi(3)).abs() <= 1e-14 * gj);
    }
    let c = SpatialSection::circle(e, 0.3, Profile::Linear { root: 2e-3, tip: 1e-3 }).unwrap();
    let [_, ei, _] = c.stiffness(0.5);
    assert!((ei - e * PI * 1.5e-3f64.powi(4) / 64.0).abs() <= 1e-14 * ei);
}

/// Stress at the candidates, against beam theory and the torsion series
/// (1e-12 relative): twist alone peaks at the middle of the long sides
/// (√3·τ_max); bending about y (the wide way) with twist at the middle of
/// the short sides when its shear is large enough, else at a corner.
#[test]
fn stress_at_corners_and_mid_sides() {
    let (e, g, w, h) = (200e9, 80e9, 0.004, 0.001);
    let s = SpatialSection::rectangle(e, Shear::Modulus(g), Profile::Constant(w), Profile::Constant(h)).unwrap();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    let twist = s.stress(0.3, [0.5, 0.0, 0.0]).unwrap();
    let tau = g * 0.5 * h * long_side_shear(4.0);
    assert!(close(twist.shear, tau) && close(twist.von_mises, 3f64.sqrt() * tau));
    assert_eq!(twist.at, StressPoint::WidthSide);
    // σ_y = E κ_y w/2 = 4e5 κ_y... with a strong twist the short sides govern.
    let mixed = s.stress(0.3, [0.5, -1e-3, 0.0]).unwrap();
    let (sy, tau_h) = (e * 1e-3 * w / 2.0, g * 0.5 * h * short_side_shear(4.0));
    assert!(close(mixed.bending_y, sy) && mixed.bending_z == 0.0);
    let side = (sy * sy + 3.0 * tau_h * tau_h).sqrt();
    let mid = (3.0f64).sqrt() * tau;
    assert!(close(mixed.von_mises, side.max(mid).max(sy)));
    assert_eq!(mixed.at, if side > mid { StressPoint::ThicknessSide } else { StressPoint::WidthSide });
    // Bending both ways, no twist: the corner, σ_y + σ_z.
    let corner = s.stress(1.0, [0.0, 0.02, -0.3]).unwrap();
    assert!(close(corner.von_mises, e * 0.02 * w / 2.0 + e * 0.3 * h / 2.0));
    assert_eq!(corner.at, StressPoint::Corner);
    // A circle: resultant bending and rim shear.
    let c = SpatialSection::circle(e, 0.25, Profile::Constant(1e-3)).unwrap();
    let r = c.stress(0.0, [0.2, 0.3, 0.4]).unwrap();
    let (sigma, tau) = (e * 0.5 * 5e-4, 80e9 * 0.2 * 5e-4);
    assert!(close(r.von_mises, (sigma * sigma + 3.0 * tau * tau).sqrt()) && r.at == StressPoint::Rim);
    assert!(close(r.safety_factor(1e9).unwrap(), 1e9 / r.von_mises));
}

fn name_of(e: Error) -> &'static str {
    match e {
        Error::InvalidParameter { name, .. } => name,
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

/// Bad input is an error naming the parameter.
#[test]
fn bad_input_names_the_parameter() {
    let one = || Profile::Constant(1e-3);
    let rect = |e: f64, shear: Shear, w: Profile| SpatialSection::rectangle(e, shear, w, one()).unwrap_err();
    assert_eq!(name_of(rect(0.0, Shear::Poisson(0.3), one())), "modulus");
    assert_eq!(name_of(rect(f64::NAN, Shear::Poisson(0.3), one())), "modulus");
    assert_eq!(name_of(rect(1e9, Shear::Poisson(0.5000001), one())), "poisson");
    assert_eq!(name_of(rect(1e9, Shear::Poisson(-1.0), one())), "poisson");
    assert_eq!(name_of(rect(1e9, Shear::Modulus(f64::INFINITY), one())), "shear_modulus");
    assert_eq!(name_of(rect(1e9, Shear::Modulus(1e9), Profile::Linear { root: 1.0, tip: -1.0 })), "width");
    let thin = SpatialSection::rectangle(1e9, Shear::Poisson(0.3), one(), Profile::Constant(0.0));
    assert_eq!(name_of(thin.unwrap_err()), "thickness");
    assert_eq!(name_of(SpatialSection::circle(1e9, 0.3, Profile::Constant(-1.0)).unwrap_err()), "diameter");
    assert_eq!(name_of(SpatialSection::circle(1e9, f64::NAN, one()).unwrap_err()), "poisson");
    let given = SpatialSection::uniform(1.0, 1.0, 1.0).unwrap();
    assert_eq!(name_of(given.stress(0.5, [0.0; 3]).unwrap_err()), "section");
    let c = SpatialSection::circle(1e9, 0.3, one()).unwrap();
    assert_eq!(name_of(c.stress(0.5, [0.0, f64::NAN, 0.0]).unwrap_err()), "kappa_y");
    assert_eq!(name_of(c.stress(1.5, [0.0; 3]).unwrap_err()), "t");
    let zero = c.stress(0.5, [0.0; 3]).unwrap();
    assert_eq!(zero.safety_factor(1e8).unwrap(), f64::INFINITY);
    assert_eq!(name_of(zero.safety_factor(-1.0).unwrap_err()), "yield_strength");
}
