//! Random sequences of C-ABI calls with random bytes as samples, configurations,
//! parameters and state blobs, on every kind (taken from `Kind::ALL`). Checked on every
//! call:
//! - no panic reaches the boundary (ORIENT_STATUS_PANIC never comes back);
//! - a refused call changes nothing: the filter's whole state, saved as a blob before
//!   and after, is the same bytes (a refused configuration change leaves the
//!   configuration's bytes as they were);
//! - a batch or rig call that stops at item k leaves exactly the state that the first k
//!   items, one call each, give (replayed on copies loaded from the blobs before), and
//!   writes the outputs of those k items and no other;
//! - an accepted call leaves a usable filter: its blob loads into a new filter, and
//!   `GOOD` plausible samples later that copy has updated OK every time and holds a
//!   finite unit quaternion;
//! - freed (and not handed out again), copied and forged handles are refused.
//!
//! Blobs are loaded as saved (into filters of any kind), damaged, cut, and forged
//! with a recomputed checksum.
#![no_main]

use libfuzzer_sys::fuzz_target;
use orient::ffi::*;
use orient::Kind;
use std::mem::MaybeUninit;

/// Plausible samples fed after an accepted call to check that the filter recovers.
const GOOD: usize = 100;
/// Calls per input: enough for sequences, few enough that every input is quick.
const MAX_CALLS: usize = 48;

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
    fn pick(&mut self, n: usize) -> usize {
        (self.u8() as usize) % n.max(1)
    }
    /// Mostly plausible values, sometimes any bit pattern (NaN, Inf, subnormal, huge),
    /// sometimes a large power of ten (readings that overflow the arithmetic).
    fn f64(&mut self) -> f64 {
        match self.u8() % 8 {
            0 => f64::from_bits(self.u64()),
            1 => (if self.u8() % 2 == 0 { 1.0 } else { -1.0 }) * 10f64.powi(self.u8() as i32 + 1),
            _ => (self.u8() as i8 as f64) * 0.25,
        }
    }
    fn vec(&mut self) -> OrientVec3 {
        OrientVec3 { x: self.f64(), y: self.f64(), z: self.f64() }
    }
    fn dt(&mut self) -> f64 {
        match self.u8() % 8 {
            0 => self.f64(),
            1 => 0.1 + self.u8() as f64 * 0.05, // around and beyond the default gap_dt
            _ => 0.001 + (self.u8() as f64) * 1e-4,
        }
    }
    fn sample(&mut self) -> OrientSample {
        OrientSample {
            dt: self.dt(),
            gyro: self.vec(),
            accel: self.vec(),
            mag: self.vec(),
            flags: if self.u8() % 16 == 0 { self.u8() as u32 } else { (self.u8() % 8) as u32 },
            reserved: if self.u8() % 32 == 0 { 1 } else { 0 },
        }
    }
    /// A value for parameter `p`: mostly within its documented range (its ends, its
    /// default, a uniform or a log-uniform point), sometimes any value.
    fn param_value(&mut self, p: &OrientParamInfo) -> f64 {
        let u = self.u8() as f64 / 255.0;
        match self.u8() % 8 {
            0 => p.min,
            1 => p.max,
            2 => p.default_value,
            3 | 4 => p.min + u * (p.max - p.min),
            5 if p.min >= 0.0 && p.max > 0.0 => {
                // Log-uniform over [max * 1e-12, max], and the smallest subnormal.
                if u == 0.0 {
                    f64::from_bits(1).max(p.min)
                } else {
                    (p.max * 10f64.powf(-12.0 * (1.0 - u))).max(p.min)
                }
            }
            _ => self.f64(),
        }
    }
    fn empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// The C numbers of every kind, from the kind enum.
fn kinds() -> Vec<i32> {
    Kind::ALL.iter().map(|k| OrientKind::from(*k) as i32).collect()
}

/// Every parameter of `kind`, from the library's own table.
fn params(kind: i32) -> Vec<OrientParamInfo> {
    let mut n = 0;
    assert_eq!(unsafe { orient_param_count(kind, &mut n) }, OrientStatus::Ok);
    (0..n)
        .map(|i| unsafe {
            let mut info = MaybeUninit::<OrientParamInfo>::uninit();
            assert_eq!(orient_param_info(kind, i, info.as_mut_ptr()), OrientStatus::Ok);
            info.assume_init()
        })
        .collect()
}

fn kind_of(h: *mut OrientFilter) -> i32 {
    let mut k = 0;
    assert_eq!(unsafe { orient_filter_kind(h, &mut k) }, OrientStatus::Ok);
    k
}

/// The filter's whole state (configuration included), as orient_filter_save writes it.
fn blob(h: *mut OrientFilter) -> Vec<u8> {
    let mut size = 0;
    assert_eq!(unsafe { orient_filter_state_size(h, &mut size) }, OrientStatus::Ok);
    let mut b = vec![0u8; size];
    let mut written = 0;
    assert_eq!(unsafe { orient_filter_save(h, b.as_mut_ptr(), size, &mut written) }, OrientStatus::Ok);
    assert_eq!(written, size);
    b
}

/// A new filter of `kind` loaded with `state`; the blob of a live filter must load.
fn copy_of(kind: i32, state: &[u8], what: &str) -> *mut OrientFilter {
    unsafe {
        let mut c = MaybeUninit::<OrientConfig>::uninit();
        assert_eq!(orient_config_default(kind, c.as_mut_ptr()), OrientStatus::Ok);
        let mut h = std::ptr::null_mut();
        assert_eq!(orient_filter_new(c.as_ptr(), &mut h), OrientStatus::Ok);
        let s = orient_filter_load(h, state.as_ptr(), state.len());
        let detail = std::ffi::CStr::from_ptr(orient_last_error()).to_string_lossy();
        assert_eq!(s, OrientStatus::Ok, "{what}: the filter's own blob does not load ({detail})");
        h
    }
}

fn quaternion(h: *mut OrientFilter) -> OrientQuaternion {
    let mut q = OrientQuaternion::default();
    assert_eq!(unsafe { orient_filter_quaternion(h, &mut q) }, OrientStatus::Ok);
    q
}

fn bits(q: OrientQuaternion) -> [u64; 4] {
    [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()]
}

fn unit(q: OrientQuaternion) -> bool {
    let n = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    bits(q).iter().all(|b| f64::from_bits(*b).is_finite()) && (n - 1.0).abs() < 1e-9
}

/// A still, level sensor with a magnetometer, within the filter's configured ranges.
fn good_sample(h: *mut OrientFilter) -> OrientSample {
    let mut accel_range = 0.0;
    assert_eq!(
        unsafe { orient_filter_get_param(h, ORIENT_PARAM_ACCEL_RANGE, &mut accel_range) },
        OrientStatus::Ok
    );
    let g = if accel_range > 0.0 { 9.81f64.min(0.5 * accel_range) } else { 9.81 };
    OrientSample {
        dt: 0.01,
        gyro: OrientVec3::default(),
        accel: OrientVec3 { x: 0.0, y: 0.0, z: g },
        mag: OrientVec3 { x: 0.0, y: 20.0, z: -40.0 },
        flags: ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG,
        reserved: 0,
    }
}

/// After an accepted call: a copy through the blob takes `GOOD` plausible samples, each
/// accepted, and ends finite and unit.
fn assert_usable(h: *mut OrientFilter, what: &str) {
    assert!(unit(quaternion(h)), "{what}: accepted, and left {:?}", quaternion(h));
    let copy = copy_of(kind_of(h), &blob(h), what);
    let s = good_sample(h);
    for i in 0..GOOD {
        let status = unsafe { orient_filter_update(copy, &s) };
        let detail = unsafe { std::ffi::CStr::from_ptr(orient_last_error()) }.to_string_lossy();
        assert_eq!(status, OrientStatus::Ok, "{what}: good sample {i} afterwards refused ({detail})");
    }
    let q = quaternion(copy);
    assert!(unit(q), "{what}: {GOOD} good samples later {q:?}");
    assert_eq!(unsafe { orient_filter_free(copy) }, OrientStatus::Ok);
}

fn config_bytes(c: &OrientConfig) -> Vec<u8> {
    // SAFETY: OrientConfig is plain data without padding (four i32/u32, then f64s).
    unsafe {
        std::slice::from_raw_parts(c as *const OrientConfig as *const u8, std::mem::size_of::<OrientConfig>())
    }
    .to_vec()
}

/// A random configuration of `kind` (every parameter of the kind reachable) and the
/// changes it took, or `None` when the kind number is one the library refuses (checked
/// to be so).
fn config(b: &mut Bytes, kind: i32) -> Option<(OrientConfig, String)> {
    let mut c = MaybeUninit::<OrientConfig>::uninit();
    let s = unsafe { orient_config_default(kind, c.as_mut_ptr()) };
    if !kinds().contains(&kind) {
        assert_eq!(s, OrientStatus::InvalidArgument, "kind {kind}");
        return None;
    }
    assert_eq!(s, OrientStatus::Ok);
    let mut c = unsafe { c.assume_init() };
    c.frame = (b.u8() % 4) as i32;
    c.init = (b.u8() % 4) as i32;
    c.initial = OrientQuaternion { w: b.f64(), x: b.f64(), y: b.f64(), z: b.f64() };
    let table = params(kind);
    let mut taken = format!("kind {kind} frame {} init {} initial {:?}", c.frame, c.init, c.initial);
    for _ in 0..b.u8() % 6 {
        let (id, v) = if b.u8() % 8 == 0 {
            (b.u8() as u32 % (ORIENT_MAX_PARAMS as u32 + 8), b.f64())
        } else {
            let p = &table[b.pick(table.len())];
            (p.id, b.param_value(p))
        };
        let before = config_bytes(&c);
        let s = unsafe { orient_config_set_param(&mut c, id, v) };
        assert_ne!(s, OrientStatus::Panic);
        if s != OrientStatus::Ok {
            assert_eq!(
                config_bytes(&c),
                before,
                "refused config_set_param({id}, {v:e}) changed the configuration"
            );
        } else {
            taken += &format!(", param {id} = {v:e}");
        }
    }
    Some((c, taken))
}

/// The handles of one input: live ones, and freed addresses not handed out again.
#[derive(Default)]
struct Handles {
    live: Vec<*mut OrientFilter>,
    freed: Vec<*mut OrientFilter>,
}

impl Handles {
    fn add(&mut self, h: *mut OrientFilter) {
        self.freed.retain(|f| *f != h);
        self.live.push(h);
    }
}

/// A refused call must leave `before` as the state; an accepted one a usable filter.
fn after_call(h: *mut OrientFilter, s: OrientStatus, before: &[u8], what: &str) {
    assert_ne!(s, OrientStatus::Panic, "{what}");
    if s == OrientStatus::Ok {
        assert_usable(h, what);
    } else {
        assert!(blob(h) == before, "{what}: refused with {s:?} and changed the state");
    }
}

/// Checks a batch or rig call that processed `done` items: every distinct filter is in
/// the state the first `done` items give one call at a time, `out[..done]` holds the
/// orientation after each item and `out[done..]` is untouched.
fn check_items(
    targets: &[*mut OrientFilter],
    samples: &[OrientSample],
    before: &[(*mut OrientFilter, Vec<u8>)],
    out: &[OrientQuaternion],
    done: usize,
    what: &str,
) {
    let copies: Vec<(*mut OrientFilter, *mut OrientFilter)> =
        before.iter().map(|(h, b)| (*h, copy_of(kind_of(*h), b, what))).collect();
    let copy = |h: *mut OrientFilter| copies.iter().find(|(o, _)| *o == h).unwrap().1;
    for i in 0..done {
        let c = copy(targets[i]);
        assert_eq!(
            unsafe { orient_filter_update(c, &samples[i]) },
            OrientStatus::Ok,
            "{what}: item {i} alone"
        );
        assert_eq!(bits(out[i]), bits(quaternion(c)), "{what}: output {i}");
    }
    for o in &out[done..] {
        assert_eq!(bits(*o), [7.0f64.to_bits(); 4], "{what}: an output past item {done} was written");
    }
    for (h, c) in copies {
        assert!(blob(h) == blob(c), "{what}: state differs from {done} items one at a time");
        assert_eq!(unsafe { orient_filter_free(c) }, OrientStatus::Ok);
    }
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let mut hs = Handles::default();
    let mut saved: Vec<u8> = Vec::new();
    let unwritten = OrientQuaternion { w: 7.0, x: 7.0, y: 7.0, z: 7.0 };
    let all_kinds = kinds();
    let mut calls = 0;
    while !b.empty() && calls < MAX_CALLS {
        calls += 1;
        let op = b.u8() % 12;
        let any = !hs.live.is_empty();
        let h = if any { hs.live[b.pick(hs.live.len())] } else { std::ptr::null_mut() };
        unsafe {
            match op {
                0 if hs.live.len() < 8 => {
                    // Every kind, and the numbers just outside them (0 and one past the last).
                    let kind = b.pick(all_kinds.len() + 2) as i32;
                    let Some((c, taken)) = config(&mut b, kind) else { continue };
                    let mut nh = std::ptr::null_mut();
                    let s = orient_filter_new(&c, &mut nh);
                    assert_ne!(s, OrientStatus::Panic);
                    if s == OrientStatus::Ok {
                        hs.add(nh);
                        assert_usable(nh, &format!("orient_filter_new({taken})"));
                    } else {
                        assert!(nh.is_null());
                    }
                }
                1..=3 if any => {
                    let sample = b.sample();
                    let before = blob(h);
                    let s = orient_filter_update(h, &sample);
                    after_call(h, s, &before, &format!("kind {}: update {sample:?}", kind_of(h)));
                }
                4 if any => {
                    let n = b.pick(12);
                    let samples: Vec<OrientSample> = (0..n).map(|_| b.sample()).collect();
                    let before = vec![(h, blob(h))];
                    let mut out = vec![unwritten; n];
                    let mut done = usize::MAX;
                    let s = orient_filter_update_batch(h, samples.as_ptr(), n, out.as_mut_ptr(), &mut done);
                    assert_ne!(s, OrientStatus::Panic);
                    assert!(done <= n && (s == OrientStatus::Ok) == (done == n), "{s:?} {done}/{n}");
                    let what = format!("kind {}: batch, {done} done: {samples:?}", kind_of(h));
                    check_items(&vec![h; n], &samples, &before, &out, done, &what);
                    if done > 0 {
                        assert_usable(h, &what);
                    }
                }
                5 if any => {
                    // Getters change nothing.
                    let before = blob(h);
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
                    assert!(blob(h) == before, "a getter changed the state");
                }
                6 if any => {
                    let before = blob(h);
                    let (s, what) = match b.u8() % 4 {
                        0 => {
                            let q = OrientQuaternion { w: b.f64(), x: b.f64(), y: b.f64(), z: b.f64() };
                            (orient_filter_set_quaternion(h, &q), format!("set_quaternion {q:?}"))
                        }
                        1 => (orient_filter_reset(h), "reset".to_string()),
                        _ => {
                            let table = params(kind_of(h));
                            let (id, v) = if b.u8() % 8 == 0 {
                                (b.u8() as u32 % (ORIENT_MAX_PARAMS as u32 + 8), b.f64())
                            } else {
                                let p = &table[b.pick(table.len())];
                                (p.id, b.param_value(p))
                            };
                            let kind = kind_of(h);
                            (
                                orient_filter_set_param(h, id, v),
                                format!("kind {kind}: set_param({id}, {v:e})"),
                            )
                        }
                    };
                    after_call(h, s, &before, &what);
                }
                7 if any => {
                    saved = blob(h);
                    let mut written = 0;
                    let mut small = vec![0u8; saved.len() - 1];
                    let s = orient_filter_save(h, small.as_mut_ptr(), small.len(), &mut written);
                    assert_eq!(s, OrientStatus::BufferTooSmall);
                }
                8 if any => {
                    // Load the last blob (of any kind), often damaged or cut, sometimes
                    // forged: bytes changed and the checksum recomputed, so that only the
                    // decoded values can tell.
                    let mut data = saved.clone();
                    match b.u8() % 5 {
                        0 if !data.is_empty() => {
                            let i = (b.u64() as usize) % data.len();
                            data[i] ^= b.u8() | 1;
                        }
                        4 if data.len() > 8 => {
                            let end = data.len() - 8;
                            for _ in 0..1 + b.u8() % 4 {
                                let i = (b.u64() as usize) % end;
                                data[i] = b.u8();
                            }
                            let sum = orient::filters::state::checksum(&data[..end]);
                            data[end..].copy_from_slice(&sum.to_le_bytes());
                        }
                        1 => data.truncate((b.u64() as usize) % (data.len() + 1)),
                        2 => data.extend((0..b.u8() % 32).map(|_| b.u8())),
                        _ => {}
                    }
                    let before = blob(h);
                    let s = orient_filter_load(h, data.as_ptr(), data.len());
                    after_call(h, s, &before, &format!("kind {}: load", kind_of(h)));
                }
                9 if any => {
                    let i = b.pick(hs.live.len());
                    let f = hs.live.swap_remove(i);
                    assert_eq!(orient_filter_free(f), OrientStatus::Ok);
                    hs.freed.push(f);
                }
                10 => {
                    // Not handles: a freed one (not handed out again), a byte copy of a
                    // live one, a block that starts with the tag older versions checked.
                    let size = std::mem::size_of::<OrientFilter>();
                    let mut block = vec![0u64; size / 8 + 1];
                    if any && b.u8() % 2 == 0 {
                        std::ptr::copy_nonoverlapping(h as *const u8, block.as_mut_ptr() as *mut u8, size);
                    } else {
                        block[0] = 0x4f52_4945_4e54_2e31;
                    }
                    let mut bad = vec![block.as_mut_ptr() as *mut OrientFilter];
                    bad.extend(hs.freed.iter().copied());
                    let sample = b.sample();
                    for p in bad {
                        let mut k = 0;
                        assert_eq!(orient_filter_kind(p, &mut k), OrientStatus::InvalidHandle);
                        assert_eq!(orient_filter_update(p, &sample), OrientStatus::InvalidHandle);
                        assert_eq!(orient_filter_free(p), OrientStatus::InvalidHandle);
                    }
                }
                11 if any => {
                    // One rig frame over the live handles, repeats allowed.
                    let n = b.pick(10);
                    let targets: Vec<*mut OrientFilter> =
                        (0..n).map(|_| hs.live[b.pick(hs.live.len())]).collect();
                    let samples: Vec<OrientSample> = (0..n).map(|_| b.sample()).collect();
                    let mut distinct = targets.clone();
                    distinct.sort();
                    distinct.dedup();
                    let before: Vec<_> = distinct.iter().map(|h| (*h, blob(*h))).collect();
                    let mut out = vec![unwritten; n];
                    let mut done = usize::MAX;
                    let s = orient_filters_update(
                        targets.as_ptr(),
                        samples.as_ptr(),
                        n,
                        out.as_mut_ptr(),
                        &mut done,
                    );
                    assert_ne!(s, OrientStatus::Panic);
                    assert!(done <= n && (s == OrientStatus::Ok) == (done == n), "{s:?} {done}/{n}");
                    let kinds: Vec<i32> = targets.iter().map(|h| kind_of(*h)).collect();
                    let what = format!("rig of kinds {kinds:?}, {done} done: {samples:?}");
                    check_items(&targets, &samples, &before, &out, done, &what);
                    for h in distinct.into_iter().filter(|h| targets[..done].contains(h)) {
                        assert_usable(h, &what);
                    }
                }
                _ => {}
            }
        }
    }
    for h in hs.live {
        unsafe { assert_eq!(orient_filter_free(h), OrientStatus::Ok) };
    }
});
