//! No heap allocation after creation: a counting global allocator around updates and
//! getters of every kind (the C ABI's error path included), and each kind's footprint.

mod common;

use common::sim::{c_sample, simulate, Moment};
use orient::{Config, Filter, Kind, Quat, Sample, Vec3};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Counts allocations made on threads that armed it (the test's own thread): the
/// harness allocates on its threads at any time.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static ARMED: Cell<bool> = const { Cell::new(false) };
}

fn count() {
    if ARMED.try_with(|a| a.get()).unwrap_or(false) {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
    }
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations_during(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    ARMED.with(|a| a.set(true));
    f();
    ARMED.with(|a| a.set(false));
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

#[test]
fn updates_and_outputs_do_not_allocate_for_any_kind() {
    // One test function: the allocator count is global and tests run on threads.
    let run = simulate(Quat::IDENTITY, 20.0, 100.0, (0.002, 0.02, 0.2), |t| Moment {
        omega: if t < 3.0 { Vec3::ZERO } else { Vec3::new(0.4 * t.sin(), 0.3, -0.2 * t.cos()) },
        ..Default::default()
    });
    let bad = Sample { dt: -1.0, ..run.samples[0] };
    for kind in Kind::ALL {
        let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
        // Samples, rejected samples and every output, from the start-up period on.
        let n = allocations_during(|| {
            for s in &run.samples {
                f.update(s).unwrap();
                assert!(f.update(&bad).is_err());
                std::hint::black_box((
                    f.quaternion(),
                    f.euler(),
                    f.gravity(),
                    f.linear_accel(),
                    f.diagnostics(),
                ));
            }
            f.reset();
            f.update(&run.samples[0]).unwrap();
        });
        assert_eq!(n, 0, "{kind:?}: {n} allocations during updates");
        // Through the C ABI, including the error path that records a message.
        unsafe {
            use orient::ffi::*;
            let mut c = std::mem::MaybeUninit::<OrientConfig>::uninit();
            let k = Kind::ALL.iter().position(|x| *x == kind).unwrap() as i32 + 1;
            assert_eq!(orient_config_default(k, c.as_mut_ptr()), OrientStatus::Ok);
            let mut h = std::ptr::null_mut();
            assert_eq!(orient_filter_new(c.as_ptr(), &mut h), OrientStatus::Ok);
            let samples: Vec<OrientSample> = run.samples.iter().map(c_sample).collect();
            let mut out = vec![OrientQuaternion::default(); samples.len()];
            let bad_c = OrientSample { dt: f64::NAN, ..samples[0] };
            // Warm the thread-local error buffer once (its first use may set it up).
            let _ = orient_filter_update(h, &bad_c);
            let n = allocations_during(|| {
                let mut processed = 0;
                let half = samples.len() / 2;
                assert_eq!(
                    orient_filter_update_batch(h, samples.as_ptr(), half, out.as_mut_ptr(), &mut processed),
                    OrientStatus::Ok
                );
                for s in &samples[half..] {
                    assert_eq!(orient_filter_update(h, s), OrientStatus::Ok);
                    assert_eq!(orient_filter_update(h, &bad_c), OrientStatus::InvalidDt);
                    let mut q = OrientQuaternion::default();
                    assert_eq!(orient_filter_quaternion(h, &mut q), OrientStatus::Ok);
                }
            });
            assert_eq!(n, 0, "{kind:?}: {n} allocations through the C ABI");
            orient_filter_free(h);
        }
    }
}

#[test]
fn footprint_of_one_filter_per_kind() {
    // Printed for the notes; bounded so that a state that grows by accident is seen.
    use orient::filters::{
        complementary::Complementary, ekf::Ekf, gmvdk::Gmvdk, madgwick::Madgwick, mahony::Mahony,
    };
    use std::mem::size_of;
    let handle = size_of::<Filter>();
    println!(
        "Filter (any kind, inline): {handle} bytes; GMVDK adds a {} byte window on the heap",
        2 * 8 * 1024
    );
    println!(
        "filter states: madgwick {}, mahony {}, complementary {}, ekf {}, gmvdk {} (+16384 heap) bytes",
        size_of::<Madgwick>(),
        size_of::<Mahony>(),
        size_of::<Complementary>(),
        size_of::<Ekf>(),
        size_of::<Gmvdk>()
    );
    assert!(handle <= 2304, "{handle}");
}
