//! The spatial model against the exact Kirchhoff rod
//! (`reference::rod`), and both against published values: the
//! Bathe–Bolourchi bend, and the model's convergence with order on 3-D loads.

use flexure::reference::rod::{self, Rod};
use flexure::section::{Profile, Shear, SpatialSection};
use flexure::spatial::{SpatialFlexure, SpatialLoad, SpatialStatics, deflect, pose_root_tip};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// The model's tip under `load` at `orders` (with the rest bend `bend`,
/// rad, in κ_z's first coefficient), and the rod's.
fn both(
    section: &SpatialSection,
    l: f64,
    bend: f64,
    orders: [usize; 3],
    load: &SpatialLoad,
) -> (Vector3<f64>, Vector3<f64>) {
    let n: usize = orders.iter().sum();
    let mut rest = vec![0.0; n];
    rest[orders[0] + orders[1]] = bend;
    let f = SpatialFlexure::new(l, section.clone(), orders).unwrap().with_rest(&rest).unwrap();
    let mut data = SpatialStatics::new(&f);
    let eq = deflect(&f, load, &mut data, &Default::default()).unwrap();
    assert!(eq.stable);
    let (_, model) = pose_root_tip(&f, data.alpha());
    let r = Rod::new(l, section.clone()).unwrap().with_rest(move |_| [0.0, 0.0, bend / l]).unwrap();
    let w = *load;
    let exact = rod::deflect(&r, &w, &Default::default()).unwrap();
    (model, exact.position)
}

/// Reference: the exact rod (`reference::rod`, Saint-Venant's torsion
/// constant, whose tip meets the 32-element published (46.90, 15.56,
/// 53.60) to 0.02: tests/rod.rs). The Bathe–Bolourchi 45° bend (R = 100,
/// unit square, E = 1e7, ν = 0, P = 600 along z): the model's tip error
/// against the rod falls with order, and from orders 3 is within 1e-3 of L
/// (L = 78.54; at the default subintervals, 8, 8, 12 and 20: measured
/// 6.2e-3 L at orders 2, 2.4e-4 at 3, 2.6e-5 at 4 and 9.0e-8 at 6, where
/// the model's tip is (46.8928, 15.5581, 53.6011)).
#[test]
fn bathe_bolourchi_bend_converges_to_the_rod() {
    let (r, e) = (100.0, 1e7);
    let l = PI * r / 4.0;
    let section =
        SpatialSection::rectangle(e, Shear::Poisson(0.0), Profile::Constant(1.0), Profile::Constant(1.0)).unwrap();
    let load = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, 600.0] };
    let mut last = f64::INFINITY;
    for n in [2, 3, 4, 6] {
        let (model, exact) = both(&section, l, PI / 4.0, [n, n, n], &load);
        let error = (model - exact).norm() / l;
        assert!(error < last, "orders {n}: {error} after {last}");
        if n >= 3 {
            assert!(error < 1e-3, "orders {n}: {error}");
        }
        last = error;
    }
}

/// Reference: the exact rod under 3-D tip wrenches (a seeded set turning
/// the tip by up to about a radian, on an anisotropic strip with a rest
/// bend): the model's largest tip error over the set falls with order and
/// is below 1e-9 of L at orders 6 (at the default subintervals, 8, 8, 12
/// and 20: measured 7.8e-4 L at orders 2, 3.8e-5 at 3, 9.8e-7 at 4,
/// 6.1e-11 at 6; at 8 subintervals orders 6 were 5.6e-10, nearly all of
/// it discretization).
#[test]
fn random_3d_loads_converge_to_the_rod_with_order() {
    let section = SpatialSection::uniform(0.6, 2.0, 1.0).unwrap();
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let loads: Vec<SpatialLoad> = (0..4)
        .map(|_| SpatialLoad {
            moment: [0.3 * next(), 0.5 * next(), 0.5 * next()],
            force: [0.5 * next(), 0.8 * next(), 0.8 * next()],
        })
        .collect();
    let mut last = f64::INFINITY;
    for n in [2, 3, 4, 6] {
        let worst = loads
            .iter()
            .map(|w| {
                let (model, exact) = both(&section, 1.0, 0.3, [n, n, n], w);
                (model - exact).norm()
            })
            .fold(0.0, f64::max);
        assert!(worst < last, "orders {n}: {worst} after {last}");
        last = worst;
    }
    assert!(last < 1e-9, "{last}");
}

/// Reference: the exact rod's conjugate point (`reference::rod`) for a
/// strip whose bending about y is not rigid (EI_y = 10·EI_z, GJ = 1.3·EI_z),
/// loaded along z past lateral-torsional buckling: Michell's load is raised
/// by the pre-buckling bending to 1.1878 times, and the model at orders 6
/// loses stability at the rod's load to 1e-5 relative (measured 6.1e-6 at
/// its default 20 subintervals, the same at 8).
#[test]
fn lateral_torsional_buckling_meets_the_rods_conjugate_point() {
    let (gj, ei_y, ei_z) = (1.3, 10.0, 1.0);
    let p = 1.2 * 4.0126 * f64::sqrt(ei_z * gj);
    let section = SpatialSection::uniform(gj, ei_y, ei_z).unwrap();
    let f = SpatialFlexure::new(1.0, section.clone(), [6, 6, 6]).unwrap();
    let mut data = SpatialStatics::new(&f);
    let load = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, p] };
    let model = deflect(&f, &load, &mut data, &Default::default()).unwrap().limit.expect("the model buckles");
    let w = SpatialLoad { moment: [0.0; 3], force: [0.0, 0.0, p] };
    let rod = rod::deflect(&Rod::new(1.0, section).unwrap(), &w, &Default::default()).unwrap();
    let exact = rod.limit.expect("the rod buckles");
    assert!((model / exact - 1.0).abs() < 1e-5, "model {model}, rod {exact}");
    assert!((1.2 * exact - 1.1878).abs() < 1e-3, "{}", 1.2 * exact);
}
