//! Separate handles on separate threads never interfere: 64 handles (every kind, several
//! configurations) updated by 8 threads give the same bits as one thread updating them
//! one after the other.

mod common;

use common::sim::{c_sample, simulate, Moment};
use orient::ffi::*;
use orient::{Kind, Quat, Vec3};

struct Handle(*mut OrientFilter);
// The C contract: a handle may move between threads, never be used by two at once.
unsafe impl Send for Handle {}

fn inputs(seed: usize) -> Vec<OrientSample> {
    let phase = seed as f64 * 0.37;
    simulate(Quat::IDENTITY, 6.0, 100.0, (0.002, 0.05, 0.3), |t| Moment {
        omega: if t < 2.5 {
            Vec3::ZERO
        } else {
            Vec3::new(0.5 * (t + phase).sin(), 0.3 * (0.7 * t).cos(), -0.2)
        },
        ..Default::default()
    })
    .samples
    .iter()
    .map(c_sample)
    .collect()
}

fn new_handle(i: usize) -> Handle {
    unsafe {
        let mut c = std::mem::MaybeUninit::<OrientConfig>::uninit();
        let kind = OrientKind::from(Kind::ALL[i % Kind::ALL.len()]);
        assert_eq!(orient_config_default(kind as i32, c.as_mut_ptr()), OrientStatus::Ok);
        let mut c = c.assume_init();
        c.frame = (i % 3) as i32;
        let mut h = std::ptr::null_mut();
        assert_eq!(orient_filter_new(&c, &mut h), OrientStatus::Ok);
        Handle(h)
    }
}

/// Runs every sample through the handle, one call at a time (with rejected samples
/// in between, which write the thread's error detail), and returns all outputs' bits.
fn drive(h: &Handle, samples: &[OrientSample]) -> Vec<[u64; 4]> {
    let bad = OrientSample { dt: -1.0, ..samples[0] };
    samples
        .iter()
        .map(|s| unsafe {
            assert_eq!(orient_filter_update(h.0, s), OrientStatus::Ok);
            assert_eq!(orient_filter_update(h.0, &bad), OrientStatus::InvalidDt);
            let mut q = OrientQuaternion::default();
            assert_eq!(orient_filter_quaternion(h.0, &mut q), OrientStatus::Ok);
            [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()]
        })
        .collect()
}

#[test]
fn eight_threads_and_64_handles_match_one_thread_bit_for_bit() {
    const HANDLES: usize = 64;
    const THREADS: usize = 8;
    let inputs: Vec<Vec<OrientSample>> = (0..HANDLES).map(inputs).collect();
    let serial: Vec<Vec<[u64; 4]>> = (0..HANDLES)
        .map(|i| {
            let h = new_handle(i);
            let out = drive(&h, &inputs[i]);
            unsafe { orient_filter_free(h.0) };
            out
        })
        .collect();

    let handles: Vec<Handle> = (0..HANDLES).map(new_handle).collect();
    let mut groups: Vec<Vec<(usize, Handle)>> = (0..THREADS).map(|_| Vec::new()).collect();
    for (i, h) in handles.into_iter().enumerate() {
        groups[i % THREADS].push((i, h));
    }
    let inputs = &inputs;
    let parallel: Vec<(usize, Vec<[u64; 4]>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = groups
            .into_iter()
            .map(|group| {
                scope.spawn(move || {
                    // Interleave the group's handles sample by sample, so that every thread
                    // keeps all its handles busy at once.
                    let mut outs: Vec<Vec<[u64; 4]>> = group.iter().map(|_| Vec::new()).collect();
                    let n = inputs[0].len();
                    for k in 0..n {
                        for (g, (i, h)) in group.iter().enumerate() {
                            outs[g].extend(drive(h, &inputs[*i][k..k + 1]));
                        }
                    }
                    for (_, h) in &group {
                        unsafe { orient_filter_free(h.0) };
                    }
                    group.iter().map(|(i, _)| *i).zip(outs).collect::<Vec<_>>()
                })
            })
            .collect();
        workers.into_iter().flat_map(|w| w.join().unwrap()).collect()
    });
    assert_eq!(parallel.len(), HANDLES);
    for (i, out) in parallel {
        assert_eq!(out, serial[i], "handle {i} differs between threaded and serial runs");
    }
}

/// The functions without a handle are thread-safe, and orient_last_error() is per
/// thread: "" on a thread that has not failed yet, and each thread's own detail after
/// its failures, whatever the others do meanwhile.
#[test]
fn handle_free_functions_and_error_details_are_per_thread() {
    std::thread::scope(|scope| {
        for t in 0..8usize {
            scope.spawn(move || unsafe {
                let last = || std::ffi::CStr::from_ptr(orient_last_error()).to_str().unwrap().to_owned();
                assert_eq!(last(), "", "thread {t} starts with a detail");
                let kinds: Vec<i32> = Kind::ALL.iter().map(|k| OrientKind::from(*k) as i32).collect();
                for round in 0..200 {
                    let kind = kinds[(t + round) % kinds.len()];
                    let mut c = std::mem::MaybeUninit::<OrientConfig>::uninit();
                    assert_eq!(orient_config_default(kind, c.as_mut_ptr()), OrientStatus::Ok);
                    let mut n = 0;
                    assert_eq!(orient_param_count(kind, &mut n), OrientStatus::Ok);
                    let mut info = std::mem::MaybeUninit::<OrientParamInfo>::uninit();
                    assert_eq!(
                        orient_param_info(kind, round as u32 % n, info.as_mut_ptr()),
                        OrientStatus::Ok
                    );
                    let mut id = 0;
                    assert_eq!(orient_param_find(kind, info.assume_init().name, &mut id), OrientStatus::Ok);
                    // A failure of this thread's own, with its own number in the detail.
                    let bad = 1000 + t as u32;
                    assert_eq!(
                        orient_param_info(kind, bad, info.as_mut_ptr()),
                        OrientStatus::InvalidArgument
                    );
                    assert_eq!(last(), format!("parameter index {bad} out of range"), "thread {t}");
                    assert!(!orient_status_message(round as i32 % 24).is_null());
                }
            });
        }
    });
}
