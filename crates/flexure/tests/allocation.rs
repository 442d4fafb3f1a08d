//! The evaluation path allocates nothing: kinematics, Jacobian, Hessians,
//! energy and deflect, at orders 3 and 6 (the fixed-size kernels) and 9
//! (the any-order path), counted by a global allocator.

use flexure::{Flexure, Kinematics, Level, Statics, TipLoad, deflect, energy, energy_gradient, update_kinematics};
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
        let mut data = Statics::new(&f);
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
