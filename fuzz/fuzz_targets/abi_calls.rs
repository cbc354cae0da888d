//! Random sequences of C-ABI calls with random bytes as samples, configurations and
//! state blobs. Invariants checked on every call: no panic reaches the boundary
//! (ORIENT_STATUS_PANIC never comes back), a rejected update leaves the orientation
//! bit-identical, an accepted one leaves a finite unit quaternion, and a failed load
//! changes nothing. Handles are only ever used while live (a freed handle is a
//! documented limit of the tag check, not something a fuzzer should exercise).
#![no_main]

use libfuzzer_sys::fuzz_target;
use orient::ffi::*;
use std::mem::MaybeUninit;

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        let (b, rest) = self.0.split_first().map(|(b, r)| (*b, r)).unwrap_or((0, &[]));
        self.0 = rest;
        b
    }
    fn u64(&mut self) -> u64 {
        (0..8).fold(0u64, |acc, i| acc | (self.u8() as u64) << (8 * i))
    }
    /// Mostly plausible values, sometimes any bit pattern (NaN, Inf, subnormal, huge).
    fn f64(&mut self) -> f64 {
        match self.u8() % 4 {
            0 => f64::from_bits(self.u64()),
            _ => (self.u8() as i8 as f64) * 0.25,
        }
    }
    fn vec(&mut self) -> OrientVec3 {
        OrientVec3 { x: self.f64(), y: self.f64(), z: self.f64() }
    }
    fn empty(&self) -> bool {
        self.0.is_empty()
    }
}

fn quaternion(h: *mut OrientFilter) -> OrientQuaternion {
    let mut q = OrientQuaternion::default();
    let s = unsafe { orient_filter_quaternion(h, &mut q) };
    assert_eq!(s, OrientStatus::Ok);
    q
}

fn same(a: OrientQuaternion, b: OrientQuaternion) -> bool {
    a.w.to_bits() == b.w.to_bits()
        && a.x.to_bits() == b.x.to_bits()
        && a.y.to_bits() == b.y.to_bits()
        && a.z.to_bits() == b.z.to_bits()
}

fn unit(q: OrientQuaternion) -> bool {
    let n = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    q.w.is_finite() && q.x.is_finite() && q.y.is_finite() && q.z.is_finite() && (n - 1.0).abs() < 1e-9
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let mut handles: Vec<*mut OrientFilter> = Vec::new();
    let mut blob: Vec<u8> = Vec::new();
    let mut steps = 0;
    while !b.empty() && steps < 2000 {
        steps += 1;
        let op = b.u8() % 10;
        let pick = |b: &mut Bytes, n: usize| (b.u8() as usize) % n.max(1);
        unsafe {
            match op {
                0 if handles.len() < 8 => {
                    let mut c = MaybeUninit::<OrientConfig>::uninit();
                    let kind = (b.u8() % 7) as i32; // includes invalid kinds 0 and 6
                    if orient_config_default(kind, c.as_mut_ptr()) != OrientStatus::Ok {
                        continue;
                    }
                    let mut c = c.assume_init();
                    c.frame = (b.u8() % 4) as i32;
                    c.init = (b.u8() % 4) as i32;
                    c.initial = OrientQuaternion { w: b.f64(), x: b.f64(), y: b.f64(), z: b.f64() };
                    for _ in 0..b.u8() % 4 {
                        let id = (b.u8() % 80) as u32;
                        let v = b.f64();
                        let s = orient_config_set_param(&mut c, id, v);
                        assert_ne!(s, OrientStatus::Panic);
                    }
                    let mut h = std::ptr::null_mut();
                    let s = orient_filter_new(&c, &mut h);
                    assert_ne!(s, OrientStatus::Panic);
                    if s == OrientStatus::Ok {
                        handles.push(h);
                    } else {
                        assert!(h.is_null());
                    }
                }
                1 | 2 | 3 if !handles.is_empty() => {
                    let h = handles[pick(&mut b, handles.len())];
                    let sample = OrientSample {
                        dt: if b.u8() % 8 == 0 { b.f64() } else { 0.001 + (b.u8() as f64) * 1e-4 },
                        gyro: b.vec(),
                        accel: b.vec(),
                        mag: b.vec(),
                        flags: if b.u8() % 16 == 0 { b.u8() as u32 } else { (b.u8() % 8) as u32 },
                        reserved: if b.u8() % 32 == 0 { 1 } else { 0 },
                    };
                    let before = quaternion(h);
                    let s = orient_filter_update(h, &sample);
                    assert_ne!(s, OrientStatus::Panic);
                    let after = quaternion(h);
                    if s == OrientStatus::Ok {
                        assert!(unit(after), "{after:?}");
                    } else {
                        assert!(same(before, after), "rejected sample changed the state");
                    }
                }
                4 if !handles.is_empty() => {
                    let h = handles[pick(&mut b, handles.len())];
                    let n = b.u8() as usize % 16;
                    let samples: Vec<OrientSample> = (0..n)
                        .map(|_| OrientSample {
                            dt: 0.002 + (b.u8() as f64) * 1e-4,
                            gyro: b.vec(),
                            accel: b.vec(),
                            mag: b.vec(),
                            flags: (b.u8() % 8) as u32,
                            reserved: 0,
                        })
                        .collect();
                    let mut out = vec![OrientQuaternion::default(); n];
                    let mut done = usize::MAX;
                    let s = orient_filter_update_batch(h, samples.as_ptr(), n, out.as_mut_ptr(), &mut done);
                    assert_ne!(s, OrientStatus::Panic);
                    assert!(done <= n);
                    assert!(out[..done].iter().all(|q| unit(*q)));
                }
                5 if !handles.is_empty() => {
                    let h = handles[pick(&mut b, handles.len())];
                    let mut e = OrientEuler::default();
                    let mut v = OrientVec3::default();
                    let mut d = MaybeUninit::<OrientDiagnostics>::uninit();
                    let mut m = [0.0; 9];
                    let mut f = 0u32;
                    for s in [
                        orient_filter_euler(h, &mut e),
                        orient_filter_gravity(h, &mut v),
                        orient_filter_linear_accel(h, &mut v),
                        orient_filter_linear_accel_earth(h, &mut v),
                        orient_filter_diagnostics(h, d.as_mut_ptr()),
                        orient_filter_rotation_matrix(h, m.as_mut_ptr()),
                        orient_filter_flags(h, &mut f),
                    ] {
                        assert_ne!(s, OrientStatus::Panic);
                    }
                }
                6 if !handles.is_empty() => {
                    let h = handles[pick(&mut b, handles.len())];
                    let q = OrientQuaternion { w: b.f64(), x: b.f64(), y: b.f64(), z: b.f64() };
                    let s = match b.u8() % 3 {
                        0 => orient_filter_set_quaternion(h, &q),
                        1 => orient_filter_reset(h),
                        _ => orient_filter_set_param(h, (b.u8() % 80) as u32, b.f64()),
                    };
                    assert_ne!(s, OrientStatus::Panic);
                    assert!(unit(quaternion(h)));
                }
                7 if !handles.is_empty() => {
                    let h = handles[pick(&mut b, handles.len())];
                    let mut size = 0;
                    assert_eq!(orient_filter_state_size(h, &mut size), OrientStatus::Ok);
                    blob.resize(size, 0);
                    let mut written = 0;
                    assert_eq!(
                        orient_filter_save(h, blob.as_mut_ptr(), size, &mut written),
                        OrientStatus::Ok
                    );
                }
                8 if !handles.is_empty() => {
                    // Load the last blob, often damaged or cut.
                    let h = handles[pick(&mut b, handles.len())];
                    let mut data = blob.clone();
                    match b.u8() % 4 {
                        0 if !data.is_empty() => {
                            let i = (b.u64() as usize) % data.len();
                            data[i] ^= b.u8() | 1;
                        }
                        1 => data.truncate((b.u64() as usize) % (data.len() + 1)),
                        2 => data.extend((0..b.u8() % 32).map(|_| b.u8())),
                        _ => {}
                    }
                    let before = quaternion(h);
                    let s = orient_filter_load(h, data.as_ptr(), data.len());
                    assert_ne!(s, OrientStatus::Panic);
                    if s != OrientStatus::Ok {
                        assert!(same(before, quaternion(h)), "refused load changed the state");
                    }
                }
                9 if !handles.is_empty() => {
                    let i = pick(&mut b, handles.len());
                    assert_eq!(orient_filter_free(handles.swap_remove(i)), OrientStatus::Ok);
                }
                _ => {}
            }
        }
    }
    for h in handles {
        unsafe { assert_eq!(orient_filter_free(h), OrientStatus::Ok) };
    }
});
