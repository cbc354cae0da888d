//! The C ABI. It only translates: pointer and handle checks, conversions between C and
//! core types, status codes, and a panic boundary inside every exported body.
//!
//! Handle checks look the address up in the registry of live handles
//! (`registry`) before anything is read through it: a freed handle, a copy of a
//! handle's bytes and a pointer that never was a handle are refused without their
//! memory being read.
//!
//! # Safety
//! One contract covers every `unsafe extern "C"` function here: each pointer argument
//! other than a handle is NULL (reported as ORIENT_STATUS_NULL_POINTER unless the
//! function says NULL is allowed) or valid for the reads and writes its documentation
//! names; a handle may hold any value (it is looked up before it is read), and a live
//! handle is not used from two threads at once (freeing it included).
#![allow(clippy::missing_safety_doc)]

mod arrays;
mod calib; // issue 20
mod config;
mod convert;
mod error;
mod handles;
mod info;
mod joint_settings; // generated: orient_config_for_joints
mod joints; // issue 42
mod offline;
mod outputs;
mod param_ids;
mod registry;
#[cfg(test)]
mod render;
mod rig; // issue 20
mod snapshot;
mod strings;
mod types;
// Declared after `types` so that the header lists the flag and diagnostics bits after
// the C API's own constants.
mod bits;
mod update;

pub use arrays::*;
pub use bits::*;
pub use calib::*; // issue 20
pub use config::*;
pub(crate) use convert::*;
pub use handles::*;
pub use info::*;
pub use joint_settings::*;
pub use joints::*; // issue 42
pub use offline::*;
pub use outputs::*;
pub use param_ids::*;
pub use rig::*; // issue 20
pub use snapshot::*;
pub use types::*;
pub use update::*;

use crate::filters::pipeline::sample::SampleView;
use crate::filters::{Config, Filter, Init, Kind};
use crate::math::{Frame, Quat, Vec3};
use core::ffi::{c_char, CStr};
use error::{detail_ptr, fail, from_core, from_state, guard, guard_value, status_message};

#[cfg(test)]
mod tests {
    use super::*;

    /// A new Madgwick filter with the default configuration.
    unsafe fn new_madgwick() -> *mut OrientFilter {
        let mut c = core::mem::MaybeUninit::<OrientConfig>::uninit();
        assert_eq!(orient_config_default(OrientKind::Madgwick as i32, c.as_mut_ptr()), OrientStatus::Ok);
        let mut h = core::ptr::null_mut();
        assert_eq!(orient_filter_new(c.as_ptr(), &mut h), OrientStatus::Ok);
        h
    }

    #[test]
    fn the_structs_have_the_sizes_their_docs_give() {
        assert_eq!(core::mem::size_of::<OrientSample>(), 88);
        assert_eq!(core::mem::size_of::<OrientConfig>(), 1072);
    }

    #[test]
    fn a_batch_stops_at_a_bad_sample_past_the_first_chunk() {
        unsafe {
            let (f, twin) = (new_madgwick(), new_madgwick());
            let mut batch: Vec<OrientSample> = (0..40)
                .map(|i| OrientSample {
                    dt: 0.01,
                    gyro: OrientVec3 { x: 0.01 * i as f64, y: -0.2, z: 0.3 },
                    accel: OrientVec3 { x: 0.5, y: 0.2, z: 9.7 },
                    mag: OrientVec3 { x: 10.0, y: 20.0, z: -40.0 },
                    flags: ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG,
                    reserved: 0,
                })
                .collect();
            batch[21].gyro.y = f64::NAN;
            let mut out = vec![OrientQuaternion::default(); 40];
            let mut n = 0;
            let status = orient_filter_update_batch(f, batch.as_ptr(), 40, out.as_mut_ptr(), &mut n);
            assert_eq!((status, n), (OrientStatus::NonFinite, 21));
            assert!(out[21..].iter().all(|q| *q == OrientQuaternion::default()), "entries past 21 written");
            let detail = CStr::from_ptr(orient_last_error()).to_str().unwrap();
            assert!(detail.starts_with("sample 21: "), "{detail}");
            let mut q = OrientQuaternion::default();
            for (i, s) in batch[..21].iter().enumerate() {
                assert_eq!(orient_filter_update(twin, s), OrientStatus::Ok);
                assert_eq!(orient_filter_quaternion(twin, &mut q), OrientStatus::Ok);
                assert_eq!(out[i].w.to_bits(), q.w.to_bits(), "sample {i}");
            }
            let mut a = OrientQuaternion::default();
            assert_eq!(orient_filter_quaternion(f, &mut a), OrientStatus::Ok);
            assert_eq!((a.x.to_bits(), a.z.to_bits()), (q.x.to_bits(), q.z.to_bits()));
            assert_eq!(orient_filter_free(f), OrientStatus::Ok);
            assert_eq!(orient_filter_free(twin), OrientStatus::Ok);
        }
    }

    /// The sample every FFI unit test feeds (MARG, moving).
    fn moving_sample() -> OrientSample {
        OrientSample {
            dt: 0.01,
            gyro: OrientVec3 { x: 0.1, y: -0.2, z: 0.3 },
            accel: OrientVec3 { x: 0.5, y: 0.2, z: 9.7 },
            mag: OrientVec3 { x: 10.0, y: 20.0, z: -40.0 },
            flags: SAMPLE_ALL,
            reserved: 0,
        }
    }

    fn quat_bits(q: OrientQuaternion) -> [u64; 4] {
        [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()]
    }

    #[test]
    fn a_rig_call_writes_the_output_of_every_filter_it_updated() {
        // Four distinct Madgwick filters (two lane pairs) whose third or fourth sample (the
        // first or the second of a pair) is refused, once by the flag check and once by
        // the reading checks. Past initialisation and with a different sample each, so
        // that the first pair takes the lanes and each output is its own filter's.
        let unwritten = OrientQuaternion { w: f64::NAN, x: 7.0, y: 7.0, z: 7.0 };
        let spoil: [fn(&mut OrientSample); 2] = [|s| s.reserved = 1, |s| s.gyro.y = f64::NAN];
        let sample = |k: usize| {
            let mut s = moving_sample();
            s.gyro.x += 0.05 * k as f64;
            s
        };
        for (spoil, bad) in spoil.into_iter().flat_map(|f| [(f, 2), (f, 3)]) {
            unsafe {
                let hs: Vec<*mut OrientFilter> = (0..4).map(|_| new_madgwick()).collect();
                let twins: Vec<*mut OrientFilter> = (0..4).map(|_| new_madgwick()).collect();
                let mut frame: [OrientSample; 4] = core::array::from_fn(sample);
                for _ in 0..3 {
                    let status = orient_filters_update(
                        hs.as_ptr(),
                        frame.as_ptr(),
                        4,
                        core::ptr::null_mut(),
                        core::ptr::null_mut(),
                    );
                    assert_eq!(status, OrientStatus::Ok);
                    for (t, s) in twins.iter().zip(&frame) {
                        assert_eq!(orient_filter_update(*t, s), OrientStatus::Ok);
                    }
                }
                spoil(&mut frame[bad]);
                let mut out = [unwritten; 4];
                let mut n = 99;
                let status = orient_filters_update(hs.as_ptr(), frame.as_ptr(), 4, out.as_mut_ptr(), &mut n);
                assert_ne!(status, OrientStatus::Ok);
                assert_eq!(n, bad);
                for k in 0..bad {
                    assert_eq!(orient_filter_update(twins[k], &frame[k]), OrientStatus::Ok);
                    let mut q = OrientQuaternion::default();
                    assert_eq!(orient_filter_quaternion(twins[k], &mut q), OrientStatus::Ok);
                    assert_eq!(quat_bits(out[k]), quat_bits(q), "filter {k}: output not written");
                    assert_eq!(orient_filter_quaternion(hs[k], &mut q), OrientStatus::Ok);
                    assert_eq!(quat_bits(out[k]), quat_bits(q), "filter {k}");
                }
                for o in &out[bad..] {
                    assert_eq!(quat_bits(*o), quat_bits(unwritten), "an unprocessed entry was written");
                }
                for h in hs.into_iter().chain(twins) {
                    assert_eq!(orient_filter_free(h), OrientStatus::Ok);
                }
            }
        }
    }

    #[test]
    fn a_rig_call_updates_distinct_and_repeated_handles() {
        unsafe {
            let hs: Vec<*mut OrientFilter> = (0..5).map(|_| new_madgwick()).collect();
            let twin = new_madgwick();
            let s = OrientSample {
                dt: 0.01,
                gyro: OrientVec3 { x: 0.1, y: -0.2, z: 0.3 },
                accel: OrientVec3 { x: 0.5, y: 0.2, z: 9.7 },
                mag: OrientVec3 { x: 10.0, y: 20.0, z: -40.0 },
                flags: ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG,
                reserved: 0,
            };
            let frame = [s; 5];
            let mut out = [OrientQuaternion::default(); 5];
            let mut n = 0;
            for _ in 0..3 {
                // Four distinct handles (two lane pairs), then one more (the odd tail).
                assert_eq!(
                    orient_filters_update(hs.as_ptr(), frame.as_ptr(), 5, out.as_mut_ptr(), &mut n),
                    OrientStatus::Ok
                );
                assert_eq!(n, 5);
                assert_eq!(orient_filter_update(twin, &s), OrientStatus::Ok);
            }
            let mut q = OrientQuaternion::default();
            assert_eq!(orient_filter_quaternion(twin, &mut q), OrientStatus::Ok);
            for o in out {
                assert_eq!(
                    (o.w.to_bits(), o.x.to_bits(), o.y.to_bits(), o.z.to_bits()),
                    (q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits())
                );
            }
            // The same handle four times is updated four times, in order.
            let same = [hs[0]; 4];
            assert_eq!(
                orient_filters_update(same.as_ptr(), frame.as_ptr(), 4, core::ptr::null_mut(), &mut n),
                OrientStatus::Ok
            );
            for _ in 0..4 {
                assert_eq!(orient_filter_update(twin, &s), OrientStatus::Ok);
            }
            let mut a = OrientQuaternion::default();
            assert_eq!(orient_filter_quaternion(hs[0], &mut a), OrientStatus::Ok);
            assert_eq!(orient_filter_quaternion(twin, &mut q), OrientStatus::Ok);
            assert_eq!(a.w.to_bits(), q.w.to_bits());
            for h in hs.into_iter().chain([twin]) {
                assert_eq!(orient_filter_free(h), OrientStatus::Ok);
            }
        }
    }

    #[test]
    fn double_free_and_null_are_reported_not_crashes() {
        unsafe {
            let h = new_madgwick();
            assert_eq!(orient_filter_free(core::ptr::null_mut()), OrientStatus::Ok);
            let mut q = OrientQuaternion::default();
            assert_eq!(orient_filter_quaternion(h, core::ptr::null_mut()), OrientStatus::NullPointer);
            assert_eq!(orient_filter_quaternion(h, &mut q), OrientStatus::Ok);
            assert_eq!(q, OrientQuaternion { w: 1.0, x: 0.0, y: 0.0, z: 0.0 });
            // A foreign but readable, aligned object is not a handle.
            let mut fake = [0u64; 16];
            let fake_h = fake.as_mut_ptr() as *mut OrientFilter;
            assert_eq!(orient_filter_reset(fake_h), OrientStatus::InvalidHandle);
            assert_eq!(orient_filter_free(h), OrientStatus::Ok);
        }
    }

    #[test]
    fn freed_copied_and_forged_handles_are_refused_without_being_read() {
        unsafe {
            let h = new_madgwick();
            assert_eq!(orient_filter_update(h, &moving_sample()), OrientStatus::Ok);
            // A byte copy of a live handle, and a block that starts with the old tag.
            let size = core::mem::size_of::<OrientFilter>();
            let mut copy = vec![0u64; size / 8 + 1];
            core::ptr::copy_nonoverlapping(h as *const u8, copy.as_mut_ptr() as *mut u8, size);
            let copy_h = copy.as_mut_ptr() as *mut OrientFilter;
            let mut forged = vec![0u64; size / 8 + 1];
            forged[0] = 0x4f52_4945_4e54_2e31; // "ORIENT.1"
            let forged_h = forged.as_mut_ptr() as *mut OrientFilter;
            let mut k = 0;
            for bad in [copy_h, forged_h] {
                assert_eq!(orient_filter_kind(bad, &mut k), OrientStatus::InvalidHandle);
                assert_eq!(orient_filter_update(bad, &moving_sample()), OrientStatus::InvalidHandle);
                assert_eq!(orient_filter_free(bad), OrientStatus::InvalidHandle);
            }
            let detail = CStr::from_ptr(orient_last_error()).to_str().unwrap();
            assert!(detail.starts_with("not a live OrientFilter handle"), "{detail}");
            // The original is untouched by the refused free of its copy.
            assert_eq!(orient_filter_kind(h, &mut k), OrientStatus::Ok);
            assert_eq!(k, OrientKind::Madgwick as i32);
            // A freed handle: refused by every call, its memory never read (Miri and
            // valgrind would report the read).
            assert_eq!(orient_filter_free(h), OrientStatus::Ok);
            let mut q = OrientQuaternion::default();
            assert_eq!(orient_filter_quaternion(h, &mut q), OrientStatus::InvalidHandle);
            assert_eq!(orient_filter_update(h, &moving_sample()), OrientStatus::InvalidHandle);
            assert_eq!(orient_filter_free(h), OrientStatus::InvalidHandle);
            let frame = [moving_sample()];
            let mut n = 9;
            assert_eq!(
                orient_filters_update([h].as_ptr(), frame.as_ptr(), 1, core::ptr::null_mut(), &mut n),
                OrientStatus::InvalidHandle
            );
            assert_eq!(n, 0);
        }
    }

    #[test]
    fn param_tables_are_reachable_by_index_and_name() {
        unsafe {
            let k = OrientKind::Madgwick as i32;
            let mut n = 0;
            assert_eq!(orient_param_count(k, &mut n), OrientStatus::Ok);
            assert_eq!(n, 9);
            let mut info = core::mem::MaybeUninit::<OrientParamInfo>::uninit();
            for i in 0..n {
                assert_eq!(orient_param_info(k, i, info.as_mut_ptr()), OrientStatus::Ok);
                let info = info.assume_init();
                let mut id = 99;
                assert_eq!(orient_param_find(k, info.name, &mut id), OrientStatus::Ok);
                assert_eq!(id, info.id);
            }
            assert_eq!(orient_param_info(k, n, info.as_mut_ptr()), OrientStatus::InvalidArgument);
            assert_eq!(orient_param_count(77, &mut n), OrientStatus::InvalidArgument);
        }
    }
}
