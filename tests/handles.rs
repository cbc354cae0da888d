//! The registry of live handles, process-wide: its capacity (the header's 24576), and
//! creation and release on some threads while others update their own handles.
//! One test function: the registry is shared by every thread of this process.

use orient::ffi::*;

struct Handle(*mut OrientFilter);
// The C contract: a handle may move between threads, never be used by two at once.
unsafe impl Send for Handle {}

fn new_filter(kind: OrientKind) -> Result<*mut OrientFilter, OrientStatus> {
    unsafe {
        let mut c = std::mem::MaybeUninit::<OrientConfig>::uninit();
        assert_eq!(orient_config_default(kind as i32, c.as_mut_ptr()), OrientStatus::Ok);
        let mut h = std::ptr::null_mut();
        match orient_filter_new(c.as_ptr(), &mut h) {
            OrientStatus::Ok => Ok(h),
            s => {
                assert!(h.is_null());
                Err(s)
            }
        }
    }
}

fn sample(i: usize) -> OrientSample {
    OrientSample {
        dt: 0.01,
        gyro: OrientVec3 { x: 0.01 * (i % 7) as f64, y: -0.02, z: 0.03 },
        accel: OrientVec3 { x: 0.1, y: 0.2, z: 9.7 },
        mag: OrientVec3 { x: 10.0, y: 20.0, z: -40.0 },
        flags: ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG,
        reserved: 0,
    }
}

fn capacity_is_the_documented_one() {
    let mut live = Vec::new();
    let refused = loop {
        match new_filter(OrientKind::Madgwick) {
            Ok(h) => live.push(h),
            Err(s) => break s,
        }
        assert!(live.len() <= 24576, "more live handles than the header says");
    };
    assert_eq!((refused, live.len()), (OrientStatus::CountTooLarge, 24576));
    unsafe {
        let detail = std::ffi::CStr::from_ptr(orient_last_error()).to_str().unwrap();
        assert!(detail.contains("24576"), "{detail}");
        // Every one of them is still a live handle; one free makes room for one more.
        let mut k = 0;
        assert!(live.iter().all(|h| orient_filter_kind(*h, &mut k) == OrientStatus::Ok));
        assert_eq!(orient_filter_free(live.pop().unwrap()), OrientStatus::Ok);
        live.push(new_filter(OrientKind::Mahony).unwrap());
        assert_eq!(new_filter(OrientKind::Madgwick), Err(OrientStatus::CountTooLarge));
        for h in live {
            assert_eq!(orient_filter_free(h), OrientStatus::Ok);
        }
    }
}

/// Four threads create, use and free handles in a loop while four others update
/// handles of their own: every call on a live handle succeeds. (A freed handle is not
/// passed again here: another thread may have been handed its address.)
fn creation_and_release_beside_updates_on_other_threads() {
    std::thread::scope(|scope| {
        for t in 0..4 {
            scope.spawn(move || {
                let own: Vec<Handle> =
                    (0..8).map(|_| Handle(new_filter(OrientKind::Madgwick).unwrap())).collect();
                for i in 0..5000 {
                    for h in &own {
                        assert_eq!(unsafe { orient_filter_update(h.0, &sample(i + t)) }, OrientStatus::Ok);
                    }
                }
                for h in own {
                    assert_eq!(unsafe { orient_filter_free(h.0) }, OrientStatus::Ok);
                }
            });
            scope.spawn(move || {
                for i in 0..5000 {
                    let h =
                        new_filter(if i % 2 == 0 { OrientKind::Mahony } else { OrientKind::Robust }).unwrap();
                    unsafe {
                        assert_eq!(orient_filter_update(h, &sample(i)), OrientStatus::Ok);
                        assert_eq!(orient_filter_free(h), OrientStatus::Ok);
                    }
                }
            });
        }
    });
}

#[test]
fn the_registry_of_live_handles() {
    capacity_is_the_documented_one();
    creation_and_release_beside_updates_on_other_threads();
}
