//! No heap allocation after creation: a counting global allocator around updates and
//! getters of every kind (the C ABI's error path included), and each kind's footprint.

mod common;

use common::sim::{c_sample, simulate, Moment};
use orient::{Config, Filter, Kind, Quat, Sample, Vec3};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// Counts allocations (and their bytes) made on threads that armed it, per thread: the
/// harness allocates on its threads at any time, and the tests run side by side.
struct Counting;

thread_local! {
    static ARMED: Cell<bool> = const { Cell::new(false) };
    static ALLOCATIONS: Cell<(usize, usize)> = const { Cell::new((0, 0)) };
}

fn count(bytes: usize) {
    if ARMED.try_with(|a| a.get()).unwrap_or(false) {
        let _ = ALLOCATIONS.try_with(|c| c.set((c.get().0 + 1, c.get().1 + bytes)));
    }
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// What `f` returns, and the allocations and bytes it made on this thread.
fn allocations_in<R>(f: impl FnOnce() -> R) -> (R, usize, usize) {
    let before = ALLOCATIONS.with(|c| c.get());
    ARMED.with(|a| a.set(true));
    let r = f();
    ARMED.with(|a| a.set(false));
    let after = ALLOCATIONS.with(|c| c.get());
    (r, after.0 - before.0, after.1 - before.1)
}

fn allocations_during(f: impl FnOnce()) -> usize {
    allocations_in(f).1
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
            let k = OrientKind::from(kind) as i32;
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

/// A handle's memory is its kind's state and a few words: the `Filter` value (a kind tag
/// and a pointer) and one block holding the kind's runner. Issue 18's bound: at most 256
/// bytes for Madgwick, Mahony and McGinnis' complementary filter, whose start-up sums
/// share their bytes with the state they lead to; the bounds are the current figures
/// (docs/PERFORMANCE.md gives the layout), so that a change that grows a handle says so.
#[test]
fn footprint_of_one_filter_per_kind() {
    let inline = std::mem::size_of::<Filter>();
    println!("Filter value: {inline} bytes");
    assert!(inline <= 16, "{inline}");
    for kind in Kind::ALL {
        let config = Config::new(kind).unwrap();
        let (filter, _, heap) = allocations_in(|| Filter::new(&config).unwrap());
        println!("{kind:?}: {inline} bytes inline + {heap} on the heap = {}", inline + heap);
        // Every byte the filter allocated, its boxes' included, is in memory().
        assert_eq!(filter.memory(), inline + heap, "{kind:?}");
        let bound = match kind {
            // Issue 40: the rest watch (8 bytes in every kind).
            Kind::Madgwick | Kind::Mahony => 192,
            // Issue 40: the configured gravity, the rest reference g0 of a start that was
            // given or never kept still (8).
            Kind::Complementary => 272,
            // Issue 40: the mean gravity innovation behind the reported inclination σ
            // (24 bytes, 32 with the lanes' alignment).
            // Issue 42: the rest detector's mean of the still period for its tilt test
            // (24, 32 with the allocation's rounding).
            Kind::Ekf => 1104,
            // 624 and the running-minimum window of μ (Appendix B.2), two 1024-entry f64
            // buffers and two indices.
            // Issue 40: the configured gravity, the rest reference of a start that never
            // kept still (8).
            Kind::Gmvdk => 640 + 16_400,
            // Issue 20's heading uncertainty added five settings and a 2x2 covariance (64);
            // issue 18 keeps the heading correction as a half-angle pair (8).
            // Issue 40: two settings of the heading uncertainty, the field's deviation
            // gain and the gyroscope's scale sigma (16), and its evidence of error, the
            // low-passed heading innovation and what it holds (16).
            // Issue 42: the motion bias filter, four low-passes of the rotation and the
            // rotated bias (448), the bias covariance (72) and the window's sums (64);
            // the rest detector's mean of the still period for its tilt test (24).
            Kind::Robust => 760 + 608,
        };
        assert!(inline + heap <= bound, "{kind:?}: {} bytes", inline + heap);
        drop(filter);
    }
}

/// The rest-bias option keeps its detector in a box made when the option is set: the
/// first sample (the initialising one), later samples and a reset allocate nothing.
#[test]
fn the_rest_bias_option_allocates_only_when_set() {
    for (kind, slot) in [
        (Kind::Madgwick, orient::filters::params::id::MADGWICK_REST_BIAS_TAU),
        (Kind::Mahony, orient::filters::params::id::MAHONY_REST_BIAS_TAU),
    ] {
        let mut c = Config::new(kind).unwrap();
        c.set_param(slot, 5.0).unwrap();
        let mut f = Filter::new(&c).unwrap();
        let s = orient::Sample {
            dt: 0.01,
            gyro: Some(orient::Vec3::new(0.0, 0.0, 0.01)),
            accel: Some(orient::Vec3::new(0.0, 0.0, 9.81)),
            mag: None,
        };
        let n = allocations_during(|| {
            for _ in 0..300 {
                f.update(&s).unwrap();
            }
            f.reset();
            f.update(&s).unwrap();
        });
        assert_eq!(n, 0, "{kind:?}");
    }
}

#[test]
fn joint_updates_and_outputs_do_not_allocate() {
    use orient::joints::{JointKind, JointParams, JointSpec, Joints};
    // A finger: hand (0), proximal (1) through a 2-DoF joint, middle (2) through a hinge;
    // each sensor's filter a robust 6D one.
    let x = Vec3::new(1.0, 0.0, 0.0);
    let z = Vec3::new(0.0, 0.0, 1.0);
    let specs = [
        JointSpec { kind: JointKind::TwoDof, parent: 0, child: 1, axis_parent: z, axis_child: x },
        JointSpec { kind: JointKind::Hinge, parent: 1, child: 2, axis_parent: x, axis_child: x },
    ];
    let mut joints = Joints::new(3, &specs, &[], JointParams::default()).unwrap();
    let mut filters: Vec<Filter> =
        (0..3).map(|_| Filter::new(&Config::new(Kind::Robust).unwrap()).unwrap()).collect();
    let sample = |t: f64| Sample {
        dt: 0.01,
        gyro: Some(Vec3::new(libm::sin(t), 0.3, libm::cos(2.0 * t))),
        accel: Some(Vec3::new(0.5 * libm::sin(t), 0.2, 9.8)),
        mag: None,
    };
    // Started outside the count: the filters' first samples and the joints' first rows.
    let mut row = [sample(0.0); 3];
    for i in 0..100 {
        row = [sample(i as f64 * 0.01); 3];
        for f in &mut filters {
            f.update(&row[0]).unwrap();
        }
        let refs: Vec<&Filter> = filters.iter().collect();
        joints.update_from(&refs, &row).unwrap();
    }
    let refs: Vec<&Filter> = filters.iter().collect();
    let sensors: Vec<Quat> = filters.iter().map(Filter::sensor_quaternion).collect();
    let allocations = allocations_during(|| {
        for i in 0..200 {
            joints.update(&sensors, &row).unwrap();
            joints.update_from(&refs, &[sample(i as f64 * 0.01); 3]).unwrap();
            let _ = (joints.segment_quaternion(2), joints.angles(1), joints.rating(0), joints.axes(1));
            let _ = joints.update(&sensors[..2], &row);
        }
    });
    assert_eq!(allocations, 0);
}
