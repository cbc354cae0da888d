//! The C ABI. It only translates: pointer and handle checks, conversions between C and
//! core types, status codes, and a panic boundary inside every exported body.
//!
//! Handle checks look the address up in the registry of live handles
//! ([`registry`]) before anything is read through it: a freed handle, a copy of a
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
mod error;
mod registry;
mod rig; // issue 20
mod strings;
mod types;

pub use arrays::*;
pub use calib::*; // issue 20
pub use rig::*; // issue 20
pub use types::*;

use crate::filters::{Config, Filter, Init, Kind, Sample, SampleView};
use crate::math::{Frame, Quat, Vec3};
use core::ffi::{c_char, CStr};
use error::{detail_ptr, fail, from_core, from_state, guard, guard_value, status_message};

/// An orientation filter. Opaque to C (the header declares it with cbindgen.toml's
/// `after_includes`): create with orient_filter_new(), release with orient_filter_free().
/// Its address is its identity in the registry of live handles.
pub struct OrientFilter {
    filter: Filter,
}

type Res = Result<(), OrientStatus>;

fn null() -> OrientStatus {
    fail(OrientStatus::NullPointer, format_args!("a required pointer argument is NULL"))
}

/// Checks a handle and borrows it. Nothing is read through `h` unless the registry
/// holds it as a live handle.
///
/// # Safety
/// A live handle is not freed, nor used mutably by another thread, while the borrow lasts.
unsafe fn handle<'a>(h: *const OrientFilter) -> Result<&'a OrientFilter, OrientStatus> {
    if h.is_null() {
        return Err(null());
    }
    if !registry::HANDLES.contains(h as usize) {
        return Err(invalid_handle(h));
    }
    Ok(&*h)
}

fn invalid_handle(h: *const OrientFilter) -> OrientStatus {
    fail(OrientStatus::InvalidHandle, format_args!("not a live OrientFilter handle: {h:p}"))
}

/// Checks a handle and borrows it mutably. Same contract as [`handle`].
unsafe fn handle_mut<'a>(h: *mut OrientFilter) -> Result<&'a mut OrientFilter, OrientStatus> {
    handle(h)?;
    Ok(&mut *h)
}

/// Writes through an out-pointer: checks it for NULL before anything else, then
/// computes the value (handle checks included) and writes it.
unsafe fn put<T>(out: *mut T, value: impl FnOnce() -> Result<T, OrientStatus>) -> Res {
    if out.is_null() {
        return Err(null());
    }
    out.write(value()?);
    Ok(())
}

/// NULL_POINTER when any of a call's required pointers is NULL.
fn need(any_null: bool) -> Res {
    if any_null {
        return Err(null());
    }
    Ok(())
}

/// An output that needs an accelerometer reading, or NO_DATA.
fn measured(value: Option<Vec3>) -> Result<OrientVec3, OrientStatus> {
    let v = value.ok_or_else(|| fail(OrientStatus::NoData, format_args!("no accelerometer reading yet")))?;
    Ok(vec_to(v))
}

fn kind_from(kind: i32) -> Result<Kind, OrientStatus> {
    Kind::ALL
        .into_iter()
        .find(|k| OrientKind::from(*k) as i32 == kind)
        .ok_or_else(|| fail(OrientStatus::InvalidArgument, format_args!("unknown filter kind {kind}")))
}

fn kind_to(kind: Kind) -> i32 {
    OrientKind::from(kind) as i32
}

fn frame_from(frame: i32) -> Result<Frame, OrientStatus> {
    match frame {
        0 => Ok(Frame::Enu),
        1 => Ok(Frame::Ned),
        2 => Ok(Frame::Nwu),
        _ => Err(fail(OrientStatus::InvalidArgument, format_args!("unknown frame {frame}"))),
    }
}

fn frame_to(frame: Frame) -> i32 {
    (match frame {
        Frame::Enu => OrientFrame::Enu,
        Frame::Ned => OrientFrame::Ned,
        Frame::Nwu => OrientFrame::Nwu,
    }) as i32
}

fn vec_from(v: OrientVec3) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}

fn vec_to(v: Vec3) -> OrientVec3 {
    OrientVec3 { x: v.x, y: v.y, z: v.z }
}

fn quat_from(q: OrientQuaternion) -> Quat {
    Quat::new(q.w, q.x, q.y, q.z)
}

fn quat_to(q: Quat) -> OrientQuaternion {
    OrientQuaternion { w: q.w, x: q.x, y: q.y, z: q.z }
}

const SAMPLE_ALL: u32 = ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG;

/// A host's sample whose flags and reserved field have been checked, read in place.
struct HostSample<'a>(&'a OrientSample);

impl HostSample<'_> {
    #[inline(always)]
    fn has(&self, bit: u32, v: &OrientVec3) -> Option<Vec3> {
        (self.0.flags & bit != 0).then(|| vec_from(*v))
    }
}

impl SampleView for HostSample<'_> {
    #[inline(always)]
    fn dt(&self) -> f64 {
        self.0.dt
    }
    #[inline(always)]
    fn gyro(&self) -> Option<Vec3> {
        self.has(ORIENT_SAMPLE_GYRO, &self.0.gyro)
    }
    #[inline(always)]
    fn accel(&self) -> Option<Vec3> {
        self.has(ORIENT_SAMPLE_ACCEL, &self.0.accel)
    }
    #[inline(always)]
    fn mag(&self) -> Option<Vec3> {
        self.has(ORIENT_SAMPLE_MAG, &self.0.mag)
    }
}

/// Checks a host's sample's flags and reserved field.
#[inline(always)]
fn host_sample(s: &OrientSample) -> Result<HostSample<'_>, OrientStatus> {
    if s.flags & !SAMPLE_ALL != 0 || s.reserved != 0 {
        return Err(fail(
            OrientStatus::InvalidArgument,
            format_args!("unknown sample flag bits {:#x} or non-zero reserved field", s.flags & !SAMPLE_ALL),
        ));
    }
    Ok(HostSample(s))
}

fn sample_from(s: &OrientSample) -> Result<Sample, OrientStatus> {
    host_sample(s).map(|h| h.to_sample())
}

fn config_to(c: &Config) -> OrientConfig {
    let (init, initial) = match c.init {
        Init::AccMag => (OrientInit::AccMag, Quat::IDENTITY),
        Init::Identity => (OrientInit::Identity, Quat::IDENTITY),
        Init::Given(q) => (OrientInit::Given, q),
    };
    OrientConfig {
        struct_size: core::mem::size_of::<OrientConfig>() as u32,
        kind: kind_to(c.kind()),
        frame: frame_to(c.frame),
        init: init as i32,
        initial: quat_to(initial),
        params: *c.slots(),
    }
}

/// Checks a C configuration and turns it into a core one.
unsafe fn config_from(c: *const OrientConfig) -> Result<Config, OrientStatus> {
    if c.is_null() {
        return Err(null());
    }
    // Read the size first: an older or newer caller's struct may be shorter or longer.
    let size = core::ptr::addr_of!((*c).struct_size).read();
    if size as usize != core::mem::size_of::<OrientConfig>() {
        return Err(fail(
            OrientStatus::VersionMismatch,
            format_args!(
                "OrientConfig.struct_size is {size}, this library's is {}",
                core::mem::size_of::<OrientConfig>()
            ),
        ));
    }
    let c = &*c;
    let kind = kind_from(c.kind)?;
    let frame = frame_from(c.frame)?;
    let init = match c.init {
        0 => Init::AccMag,
        1 => Init::Identity,
        2 => Init::Given(quat_from(c.initial)),
        other => return Err(fail(OrientStatus::InvalidArgument, format_args!("unknown init mode {other}"))),
    };
    Config::from_slots(kind, frame, init, &c.params).map_err(from_core)
}

/// The library version, e.g. "0.1.0" (static, NUL-terminated).
#[no_mangle]
pub extern "C" fn orient_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr() as *const c_char
}

/// ORIENT_ABI_VERSION of the loaded library; compare with the header's to detect a
/// mismatched binary.
#[no_mangle]
pub extern "C" fn orient_abi_version() -> u32 {
    ORIENT_ABI_VERSION
}

/// A fixed English message for a status code (static, NUL-terminated; never NULL).
#[no_mangle]
pub extern "C" fn orient_status_message(status: i32) -> *const c_char {
    guard_value(c"".as_ptr(), || status_message(status).as_ptr() as *const c_char)
}

/// Detail of the last failed call on this thread (NUL-terminated, "" if none). Valid
/// until the next failing orient call on the same thread; never NULL.
#[no_mangle]
pub extern "C" fn orient_last_error() -> *const c_char {
    guard_value(c"".as_ptr(), detail_ptr)
}

/// beta from the maximum gyroscope error of each axis, Madgwick 2010 eq. (33):
/// beta = sqrt(3/4) * gyro_error (both rad/s). NaN for a negative or non-finite input.
#[no_mangle]
pub extern "C" fn orient_madgwick_beta(gyro_error: f64) -> f64 {
    if gyro_error.is_finite() && gyro_error >= 0.0 {
        crate::filters::madgwick::beta_from_gyro_error(gyro_error)
    } else {
        f64::NAN
    }
}

/// Fills `config` with the defaults of `kind` (one of ORIENT_KIND_*): ENU, initial
/// orientation from the first accelerometer/magnetometer sample, every parameter at its
/// documented default. ORIENT_STATUS_INVALID_ARGUMENT for a number that is not an
/// ORIENT_KIND_*.
#[no_mangle]
pub unsafe extern "C" fn orient_config_default(kind: i32, config: *mut OrientConfig) -> OrientStatus {
    guard(|| {
        put(config, || {
            let c = Config::new(kind_from(kind)?).map_err(from_core)?;
            Ok(config_to(&c))
        })
    })
}

/// Sets parameter slot `id` of `config` after checking it against the kind's range.
#[no_mangle]
pub unsafe extern "C" fn orient_config_set_param(
    config: *mut OrientConfig,
    id: u32,
    value: f64,
) -> OrientStatus {
    guard(|| {
        let mut c = config_from(config)?;
        c.set_param(id, value).map_err(from_core)?;
        (*config).params[id as usize] = value;
        Ok(())
    })
}

/// Reads parameter slot `id` of `config` into `value`.
#[no_mangle]
pub unsafe extern "C" fn orient_config_get_param(
    config: *const OrientConfig,
    id: u32,
    value: *mut f64,
) -> OrientStatus {
    guard(|| {
        need(config.is_null())?;
        put(value, || config_from(config)?.param(id).map_err(from_core))
    })
}

/// Number of parameters of `kind` (common ones included), for orient_param_info().
#[no_mangle]
pub unsafe extern "C" fn orient_param_count(kind: i32, count: *mut u32) -> OrientStatus {
    guard(|| put(count, || Ok(kind_from(kind)?.params().count() as u32)))
}

/// Describes parameter number `index` (0 <= index < orient_param_count) of `kind`.
#[no_mangle]
pub unsafe extern "C" fn orient_param_info(
    kind: i32,
    index: u32,
    info: *mut OrientParamInfo,
) -> OrientStatus {
    guard(|| {
        need(info.is_null())?;
        let k = kind_from(kind)?;
        let Some(spec) = k.params().nth(index as usize) else {
            return Err(fail(
                OrientStatus::InvalidArgument,
                format_args!("parameter index {index} out of range"),
            ));
        };
        let text = strings::param_text(spec.id).ok_or_else(|| {
            fail(OrientStatus::Panic, format_args!("no strings for parameter slot {}", spec.id))
        })?;
        put(info, || {
            Ok(OrientParamInfo {
                id: spec.id,
                flags: if spec.zero_off { ORIENT_PARAM_FLAG_ZERO_OFF } else { 0 },
                name: text.name,
                unit: text.unit,
                description: text.doc,
                default_value: spec.default,
                min: spec.min,
                max: spec.max,
            })
        })
    })
}

/// Looks up the slot of the parameter called `name` (NUL-terminated) for `kind`.
#[no_mangle]
pub unsafe extern "C" fn orient_param_find(kind: i32, name: *const c_char, id: *mut u32) -> OrientStatus {
    guard(|| {
        need(name.is_null() || id.is_null())?;
        let k = kind_from(kind)?;
        let name = CStr::from_ptr(name).to_str().unwrap_or("");
        let spec = k.param_by_name(name).ok_or_else(|| {
            fail(OrientStatus::UnknownParam, format_args!("no parameter '{name}' for this kind"))
        })?;
        put(id, || Ok(spec.id))
    })
}

/// Creates a filter from `config`. On success `*out` is a new handle; on failure it is
/// set to NULL (when `out` is not NULL).
#[no_mangle]
pub unsafe extern "C" fn orient_filter_new(
    config: *const OrientConfig,
    out: *mut *mut OrientFilter,
) -> OrientStatus {
    guard(|| {
        if out.is_null() {
            return Err(null());
        }
        out.write(core::ptr::null_mut());
        let c = config_from(config)?;
        let filter = Filter::new(&c).map_err(from_core)?;
        let h = Box::into_raw(Box::new(OrientFilter { filter }));
        if !registry::HANDLES.insert(h as usize) {
            drop(Box::from_raw(h));
            return Err(fail(
                OrientStatus::CountTooLarge,
                format_args!("{} filters are live, the most this library holds at once", registry::CAPACITY),
            ));
        }
        out.write(h);
        Ok(())
    })
}

/// Releases a filter. NULL is a no-op (ORIENT_STATUS_OK); a handle that was already
/// freed, or any pointer orient_filter_new did not return, is reported with
/// ORIENT_STATUS_INVALID_HANDLE and nothing is read or freed through it.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_free(filter: *mut OrientFilter) -> OrientStatus {
    guard(|| {
        if filter.is_null() {
            return Ok(());
        }
        // Taken out of the registry first: of two frees of one handle, even from two
        // threads, exactly one gets here.
        if !registry::HANDLES.remove(filter as usize) {
            return Err(invalid_handle(filter));
        }
        drop(Box::from_raw(filter));
        Ok(())
    })
}

/// The kind (ORIENT_KIND_*) of a filter.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_kind(filter: *const OrientFilter, kind: *mut i32) -> OrientStatus {
    guard(|| put(kind, || Ok(kind_to(handle(filter)?.filter.kind()))))
}

/// Changes parameter slot `id` of a running filter; the estimate is kept. One setting
/// changes what the output means, and so the output: GMVDK's relative_output switches
/// between the earth frame and the start-up pose.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_set_param(
    filter: *mut OrientFilter,
    id: u32,
    value: f64,
) -> OrientStatus {
    guard(|| handle_mut(filter)?.filter.set_param(id, value).map_err(from_core))
}

/// Reads parameter slot `id` of a filter.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_get_param(
    filter: *const OrientFilter,
    id: u32,
    value: *mut f64,
) -> OrientStatus {
    guard(|| put(value, || handle(filter)?.filter.param(id).map_err(from_core)))
}

/// One update. On any status but OK the filter's state is exactly as before.
///
/// Checks, in order: flags and reserved (INVALID_ARGUMENT); dt finite, at least 1e-9 s
/// and at most 1e6 s (INVALID_DT; in a batch this catches timestamps going backwards);
/// gyroscope present (MISSING_SENSOR), finite (NON_FINITE), within
/// ORIENT_PARAM_GYRO_RANGE (SATURATED), every component below 1e4 rad/s (TOO_LARGE);
/// accelerometer and magnetometer, when present: finite (NON_FINITE), squared norm not
/// below DBL_MIN (ZERO_VECTOR: zero, or so small that normalising it is meaningless)
/// nor overflowing (TOO_LARGE), accelerometer within ORIENT_PARAM_ACCEL_RANGE
/// (SATURATED), every component below its physical bound, 1e5 m/s^2 and 1e12
/// (TOO_LARGE); until the filter has an orientation, every sample must carry an
/// accelerometer (NOT_INITIALIZED). Subnormal components in an otherwise usable vector
/// are accepted. Fields whose ORIENT_SAMPLE_* bit is clear are never read.
///
/// Recoveries that are not errors: after a dt above ORIENT_PARAM_GAP_DT (a gap: dropped
/// packets) the filter re-acquires its orientation from the sensors (ORIENT_FLAG_GAP,
/// ORIENT_FLAG_REACQUIRED, ORIENT_FLAG_REACQUIRE_PENDING); a
/// magnetometer parallel to gravity gives no heading, so that step is an IMU update
/// (ORIENT_FLAG_MAG_USED clear). NUMERIC guards a step whose result would not be
/// finite; the bounds on dt and on the readings keep every accepted sample from reaching
/// it, and no test has found one that does.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_update(
    filter: *mut OrientFilter,
    sample: *const OrientSample,
) -> OrientStatus {
    guard(|| {
        need(sample.is_null())?;
        let h = handle_mut(filter)?;
        let s = host_sample(&*sample)?;
        h.filter.update_inline(&s).map_err(from_core)
    })
}

/// The `n` items at `ptr` of a multi-item call: NULL only when `n` is 0, and `n` small
/// enough for the items to fit in memory.
unsafe fn items<'a, T>(ptr: *const T, n: usize, what: &str) -> Result<&'a [T], OrientStatus> {
    if n == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(null());
    }
    if n > isize::MAX as usize / core::mem::size_of::<T>().max(1) {
        return Err(fail(OrientStatus::CountTooLarge, format_args!("n = {n} {what} cannot fit in memory")));
    }
    Ok(core::slice::from_raw_parts(ptr, n))
}

/// A multi-item call's failure at item `i`: `*processed = i` (when not NULL) and the
/// current detail prefixed with `what i: `.
unsafe fn fail_item(processed: *mut usize, what: &str, i: usize, status: OrientStatus) -> OrientStatus {
    if !processed.is_null() {
        processed.write(i);
    }
    // Copy the detail out first: fail() rewrites its buffer.
    let detail = CStr::from_ptr(detail_ptr()).to_bytes();
    let mut copy = [0u8; 200];
    let len = detail.len().min(copy.len());
    copy[..len].copy_from_slice(&detail[..len]);
    let detail = core::str::from_utf8(&copy[..len]).unwrap_or("");
    fail(status, format_args!("{what} {i}: {detail}"))
}

/// Updates with `n` samples in order. When `quaternions` is not NULL it receives the
/// orientation after each sample (room for `n`; on failure the entries before
/// `*processed` are written and the others are not). Stops at the first bad sample: the
/// samples before it stay applied, the bad one changes nothing, and `*processed` (when
/// not NULL) is its index; on success `*processed` is `n`. `samples` may be NULL only
/// when `n` is 0.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_update_batch(
    filter: *mut OrientFilter,
    samples: *const OrientSample,
    n: usize,
    quaternions: *mut OrientQuaternion,
    processed: *mut usize,
) -> OrientStatus {
    guard(|| {
        if !processed.is_null() {
            processed.write(0);
        }
        let samples = items(samples, n, "samples")?;
        let h = handle_mut(filter)?;
        if n == 0 {
            return Ok(());
        }
        let failed = |i: usize, status: OrientStatus| fail_item(processed, "sample", i, status);
        // Each update reads the host's sample in place (see SampleView): nothing is
        // copied, so nothing is read back right after it was written.
        for (i, s) in samples.iter().enumerate() {
            let s = host_sample(s).map_err(|status| failed(i, status))?;
            h.filter.update_inline(&s).map_err(|e| failed(i, from_core(e)))?;
            if !quaternions.is_null() {
                quaternions.add(i).write(quat_to(h.filter.quaternion()));
            }
        }
        if !processed.is_null() {
            processed.write(n);
        }
        Ok(())
    })
}

/// One frame of a multi-sensor rig in one call: updates `filters[i]` with `samples[i]`
/// for i < n (say the 16-20 bones of a hand). The filters may be of any kinds; each
/// behaves exactly as with orient_filter_update. When `quaternions` is not NULL it
/// receives each filter's orientation after its sample (room for `n`; on failure the
/// entries of the filters before the bad sample are written and the others are not).
/// Every handle is checked before any filter changes, so a NULL or foreign handle
/// changes nothing. A bad
/// sample stops the call: the filters before it stay updated, its filter and those
/// after it are unchanged, and `*processed` (when not NULL) is its index; on success it
/// is `n`. `filters` and `samples` may be NULL only when `n` is 0. Four consecutive
/// distinct Madgwick filters with the same sensors present are updated side by side,
/// with the same bits as separate calls.
#[no_mangle]
pub unsafe extern "C" fn orient_filters_update(
    filters: *const *mut OrientFilter,
    samples: *const OrientSample,
    n: usize,
    quaternions: *mut OrientQuaternion,
    processed: *mut usize,
) -> OrientStatus {
    guard(|| {
        if !processed.is_null() {
            processed.write(0);
        }
        if n == 0 {
            return Ok(());
        }
        let samples = items(samples, n, "samples")?;
        let handles = items(filters, n, "filters")?;
        if let Some(i) = handles.iter().position(|h| h.is_null()) {
            return Err(fail(OrientStatus::NullPointer, format_args!("filter {i} is NULL")));
        }
        for (i, h) in handles.iter().enumerate() {
            if let Err(status) = handle(*h) {
                return Err(fail(status, format_args!("filter {i}: not a live OrientFilter handle")));
            }
        }
        // Reports a bad sample at `i`: its index in `*processed`, the detail prefixed.
        let failed = |i: usize, status: OrientStatus| fail_item(processed, "filter", i, status);
        const LANES: usize = 4;
        let mut i = 0;
        while i < n {
            let group = &handles[i..n.min(i + LANES)];
            let distinct =
                group.len() == LANES && (0..LANES).all(|a| (a + 1..LANES).all(|b| group[a] != group[b]));
            if distinct {
                // Four different filters: their steps may run side by side.
                let mut converted = [Sample::default(); LANES];
                let mut bad = None;
                for (k, c) in converted.iter_mut().enumerate() {
                    match sample_from(&samples[i + k]) {
                        Ok(s) => *c = s,
                        Err(status) => {
                            bad = Some((k, status));
                            break;
                        }
                    }
                }
                let ptrs: [*mut OrientFilter; LANES] = [group[0], group[1], group[2], group[3]];
                let mut fs = ptrs.map(|p| &mut (*p).filter);
                let result = match bad {
                    None => {
                        let refs = [0, 1, 2, 3].map(|k| &converted[k]);
                        Filter::update_group(&mut fs, refs).map_err(|(k, e)| (k, from_core(e)))
                    }
                    // The ones before the bad sample still get their update.
                    Some((k, status)) => (0..k)
                        .try_for_each(|j| fs[j].update(&converted[j]).map_err(|e| (j, from_core(e))))
                        .and(Err((k, status))),
                };
                // Every filter the group updated has its output written, also when a
                // later one in the group refused its sample.
                let updated = result.map_or_else(|(k, _)| k, |()| LANES);
                if !quaternions.is_null() {
                    for (k, f) in fs[..updated].iter().enumerate() {
                        quaternions.add(i + k).write(quat_to(f.quaternion()));
                    }
                }
                result.map_err(|(k, status)| failed(i + k, status))?;
                i += LANES;
                continue;
            }
            // One mutable borrow at a time, so a handle listed twice is simply updated
            // twice, in order.
            let f = &mut (*handles[i]).filter;
            sample_from(&samples[i])
                .and_then(|s| f.update(&s).map_err(from_core))
                .map_err(|status| failed(i, status))?;
            if !quaternions.is_null() {
                quaternions.add(i).write(quat_to(f.quaternion()));
            }
            i += 1;
        }
        if !processed.is_null() {
            processed.write(n);
        }
        Ok(())
    })
}

/// The orientation (sensor to earth, configured frame). Identity before initialisation.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_quaternion(
    filter: *const OrientFilter,
    q: *mut OrientQuaternion,
) -> OrientStatus {
    guard(|| put(q, || Ok(quat_to(handle(filter)?.filter.quaternion()))))
}

/// Euler angles (yaw, pitch, roll; Z-Y'-X'') of the orientation, radians.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_euler(
    filter: *const OrientFilter,
    euler: *mut OrientEuler,
) -> OrientStatus {
    guard(|| {
        put(euler, || {
            let e = handle(filter)?.filter.euler();
            Ok(OrientEuler { yaw: e.yaw, pitch: e.pitch, roll: e.roll })
        })
    })
}

/// Rotation matrix of the orientation, row-major, 9 doubles: v_earth = R * v_sensor.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_rotation_matrix(
    filter: *const OrientFilter,
    matrix: *mut f64,
) -> OrientStatus {
    guard(|| {
        need(matrix.is_null())?;
        let m = handle(filter)?.filter.rotation_matrix();
        for (i, v) in m.iter().flatten().enumerate() {
            matrix.add(i).write(*v);
        }
        Ok(())
    })
}

/// What the accelerometer reads at rest in the current orientation (gravity's reaction,
/// pointing up), sensor frame, m/s^2, magnitude ORIENT_PARAM_GRAVITY.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_gravity(
    filter: *const OrientFilter,
    gravity: *mut OrientVec3,
) -> OrientStatus {
    guard(|| put(gravity, || Ok(vec_to(handle(filter)?.filter.gravity()))))
}

/// Last accelerometer reading minus orient_filter_gravity(), sensor frame, m/s^2.
/// ORIENT_STATUS_NO_DATA before the first accelerometer reading (NULL_POINTER, as
/// always, when `accel` is NULL).
#[no_mangle]
pub unsafe extern "C" fn orient_filter_linear_accel(
    filter: *const OrientFilter,
    accel: *mut OrientVec3,
) -> OrientStatus {
    guard(|| put(accel, || measured(handle(filter)?.filter.linear_accel())))
}

/// orient_filter_linear_accel() rotated into the earth frame, m/s^2.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_linear_accel_earth(
    filter: *const OrientFilter,
    accel: *mut OrientVec3,
) -> OrientStatus {
    guard(|| put(accel, || measured(handle(filter)?.filter.linear_accel_earth())))
}

/// Internal states (bias, trust values, rest flag, covariance), the same struct for
/// every kind; fields that do not apply are marked absent in `present` and hold NaN.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_diagnostics(
    filter: *const OrientFilter,
    diagnostics: *mut OrientDiagnostics,
) -> OrientStatus {
    guard(|| put(diagnostics, || Ok(diagnostics_to(&handle(filter)?.filter.diagnostics()))))
}

fn diagnostics_to(d: &crate::filters::Diagnostics) -> OrientDiagnostics {
    OrientDiagnostics {
        present: d.present,
        reserved: 0,
        gyro_bias: vec_to(d.gyro_bias),
        rest: d.rest,
        alpha: d.alpha,
        mu_ka: d.mu_ka,
        mu_km: d.mu_km,
        mu_k: d.mu_k,
        rate: vec_to(d.rate),
        covariance: d.covariance,
    }
}

/// Size in bytes of this filter's state blob (orient_filter_save); constant per kind.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_state_size(
    filter: *const OrientFilter,
    size: *mut usize,
) -> OrientStatus {
    guard(|| put(size, || Ok(handle(filter)?.filter.state_size())))
}

/// Saves the configuration and state as a versioned, checksummed blob into `buffer`
/// (`capacity` bytes); `*written` receives its length. ORIENT_STATUS_BUFFER_TOO_SMALL
/// when `capacity` is below orient_filter_state_size(). A filter loaded with the blob
/// continues bit for bit as this one would.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_save(
    filter: *const OrientFilter,
    buffer: *mut u8,
    capacity: usize,
    written: *mut usize,
) -> OrientStatus {
    guard(|| {
        need(buffer.is_null() || written.is_null())?;
        let h = handle(filter)?;
        if capacity > isize::MAX as usize {
            return Err(fail(
                OrientStatus::CountTooLarge,
                format_args!("capacity {capacity} cannot be a buffer"),
            ));
        }
        let out = core::slice::from_raw_parts_mut(buffer, capacity);
        let n = h.filter.save(out).map_err(from_state)?;
        written.write(n);
        Ok(())
    })
}

/// Restores a blob from orient_filter_save into a filter of the same kind (configuration
/// included). ORIENT_STATUS_INVALID_STATE, with the filter unchanged, for a blob that is
/// truncated, corrupted, of another format version or of another kind.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_load(
    filter: *mut OrientFilter,
    buffer: *const u8,
    size: usize,
) -> OrientStatus {
    guard(|| {
        need(buffer.is_null())?;
        let h = handle_mut(filter)?;
        if size > isize::MAX as usize {
            return Err(fail(OrientStatus::CountTooLarge, format_args!("size {size} cannot be a buffer")));
        }
        h.filter.load(core::slice::from_raw_parts(buffer, size)).map_err(from_state)
    })
}

/// ORIENT_FLAG_* bits of the filter's state.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_flags(filter: *const OrientFilter, flags: *mut u32) -> OrientStatus {
    guard(|| put(flags, || Ok(handle(filter)?.filter.flags())))
}

/// Back to the state right after orient_filter_new(); parameters set since are kept.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_reset(filter: *mut OrientFilter) -> OrientStatus {
    guard(|| {
        handle_mut(filter)?.filter.reset();
        Ok(())
    })
}

/// Sets the orientation (configured frame; normalised). NON_FINITE, ZERO_VECTOR or
/// TOO_LARGE for an unusable quaternion. The filter counts as initialised afterwards.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_set_quaternion(
    filter: *mut OrientFilter,
    q: *const OrientQuaternion,
) -> OrientStatus {
    guard(|| {
        need(q.is_null())?;
        let h = handle_mut(filter)?;
        h.filter.set_quaternion(quat_from(*q)).map_err(from_core)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filters::params;

    /// A new Madgwick filter with the default configuration.
    unsafe fn new_madgwick() -> *mut OrientFilter {
        let mut c = core::mem::MaybeUninit::<OrientConfig>::uninit();
        assert_eq!(orient_config_default(OrientKind::Madgwick as i32, c.as_mut_ptr()), OrientStatus::Ok);
        let mut h = core::ptr::null_mut();
        assert_eq!(orient_filter_new(c.as_ptr(), &mut h), OrientStatus::Ok);
        h
    }

    #[test]
    fn header_constants_match_the_core() {
        assert_eq!(ORIENT_MAX_PARAMS, params::MAX_PARAMS);
        assert_eq!(ORIENT_PARAM_GRAVITY, params::id::GRAVITY);
        assert_eq!(ORIENT_PARAM_GYRO_RANGE, params::id::GYRO_RANGE);
        assert_eq!(ORIENT_PARAM_ACCEL_RANGE, params::id::ACCEL_RANGE);
        assert_eq!(ORIENT_PARAM_MADGWICK_BETA_IMU, params::id::MADGWICK_BETA_IMU);
        assert_eq!(ORIENT_PARAM_MADGWICK_BETA_MARG, params::id::MADGWICK_BETA_MARG);
        use crate::filters::flags;
        assert_eq!(ORIENT_FLAG_INITIALIZED, flags::INITIALIZED);
        assert_eq!(ORIENT_FLAG_ACCEL_USED, flags::ACCEL_USED);
        assert_eq!(ORIENT_FLAG_MAG_USED, flags::MAG_USED);
        assert_eq!(ORIENT_FLAG_GAP, flags::GAP);
        assert_eq!(ORIENT_FLAG_REACQUIRED, flags::REACQUIRED);
        assert_eq!(ORIENT_FLAG_REACQUIRE_PENDING, flags::REACQUIRE_PENDING);
        assert_eq!(ORIENT_PARAM_GAP_DT, params::id::GAP_DT);
        assert_eq!(ORIENT_PARAM_SATURATION_RECOVERY, params::id::SATURATION_RECOVERY);
        assert_eq!(ORIENT_FLAG_SATURATED, flags::SATURATED);
        assert_eq!(ORIENT_FLAG_SAME_INSTANT, flags::SAME_INSTANT);
        assert_eq!(ORIENT_PARAM_SAME_INSTANT, params::id::SAME_INSTANT);
        assert_eq!(core::mem::size_of::<OrientSample>(), 88);
        assert_eq!(core::mem::size_of::<OrientConfig>(), 1072);
        use crate::filters::diag;
        assert_eq!(ORIENT_DIAG_GYRO_BIAS, diag::GYRO_BIAS);
        assert_eq!(ORIENT_DIAG_REST, diag::REST);
        assert_eq!(ORIENT_DIAG_ALPHA, diag::ALPHA);
        assert_eq!(ORIENT_DIAG_MU_KA, diag::MU_KA);
        assert_eq!(ORIENT_DIAG_MU_KM, diag::MU_KM);
        assert_eq!(ORIENT_DIAG_MU_K, diag::MU_K);
        assert_eq!(ORIENT_DIAG_RATE, diag::RATE);
        assert_eq!(ORIENT_DIAG_COVARIANCE, diag::COVARIANCE);
        let slots = [
            (ORIENT_PARAM_MAHONY_KP, params::id::MAHONY_KP),
            (ORIENT_PARAM_MAHONY_KI, params::id::MAHONY_KI),
            (ORIENT_PARAM_MAHONY_REST_BIAS_TAU, params::id::MAHONY_REST_BIAS_TAU),
            (ORIENT_PARAM_MADGWICK_REST_BIAS_TAU, params::id::MADGWICK_REST_BIAS_TAU),
            (ORIENT_PARAM_COMPLEMENTARY_KP, params::id::COMPLEMENTARY_KP),
            (ORIENT_PARAM_COMPLEMENTARY_KI, params::id::COMPLEMENTARY_KI),
            (ORIENT_PARAM_COMPLEMENTARY_GYRO_REST, params::id::COMPLEMENTARY_GYRO_REST),
            (ORIENT_PARAM_COMPLEMENTARY_ACCEL_REST, params::id::COMPLEMENTARY_ACCEL_REST),
            (ORIENT_PARAM_COMPLEMENTARY_INIT_DURATION, params::id::COMPLEMENTARY_INIT_DURATION),
            (ORIENT_PARAM_COMPLEMENTARY_ALIGN_HEADING, params::id::COMPLEMENTARY_ALIGN_HEADING),
            (ORIENT_PARAM_EKF_TAU_OMEGA, params::id::EKF_TAU_OMEGA),
            (ORIENT_PARAM_EKF_OMEGA_STD, params::id::EKF_OMEGA_STD),
            (ORIENT_PARAM_EKF_TAU_DRIFT, params::id::EKF_TAU_DRIFT),
            (ORIENT_PARAM_EKF_DRIFT_STD, params::id::EKF_DRIFT_STD),
            (ORIENT_PARAM_EKF_GYRO_NOISE, params::id::EKF_GYRO_NOISE),
            (ORIENT_PARAM_EKF_ACCEL_NOISE, params::id::EKF_ACCEL_NOISE),
            (ORIENT_PARAM_EKF_ACCEL_MOTION, params::id::EKF_ACCEL_MOTION),
            (ORIENT_PARAM_EKF_HEADING_STD, params::id::EKF_HEADING_STD),
            (ORIENT_PARAM_EKF_MOTION_TAU, params::id::EKF_MOTION_TAU),
            (ORIENT_PARAM_EKF_HEADING_TAU, params::id::EKF_HEADING_TAU),
            (ORIENT_PARAM_EKF_REST_RATE_STD, params::id::EKF_REST_RATE_STD),
            (ORIENT_PARAM_EKF_ACCEL_ADAPT_TAU, params::id::EKF_ACCEL_ADAPT_TAU),
            (ORIENT_PARAM_EKF_HEADING_ADAPT_TAU, params::id::EKF_HEADING_ADAPT_TAU),
            (ORIENT_PARAM_GMVDK_SLOPE_ALPHA, params::id::GMVDK_SLOPE_ALPHA),
            (ORIENT_PARAM_GMVDK_SLOPE_MUK, params::id::GMVDK_SLOPE_MUK),
            (ORIENT_PARAM_GMVDK_MU_WINDOW, params::id::GMVDK_MU_WINDOW),
            (ORIENT_PARAM_GMVDK_INIT_DURATION, params::id::GMVDK_INIT_DURATION),
            (ORIENT_PARAM_GMVDK_ACTIVITY_TAU, params::id::GMVDK_ACTIVITY_TAU),
            (ORIENT_PARAM_GMVDK_GYRO_ACTIVITY, params::id::GMVDK_GYRO_ACTIVITY),
            (ORIENT_PARAM_GMVDK_ACCEL_ACTIVITY, params::id::GMVDK_ACCEL_ACTIVITY),
            (ORIENT_PARAM_GMVDK_BIAS_WINDOW, params::id::GMVDK_BIAS_WINDOW),
            (ORIENT_PARAM_GMVDK_STATIC_ALPHA, params::id::GMVDK_STATIC_ALPHA),
            (ORIENT_PARAM_GMVDK_RELATIVE_OUTPUT, params::id::GMVDK_RELATIVE_OUTPUT),
            (ORIENT_PARAM_ROBUST_TAU_ACC, params::id::ROBUST_TAU_ACC),
            (ORIENT_PARAM_ROBUST_TAU_MAG, params::id::ROBUST_TAU_MAG),
            (ORIENT_PARAM_ROBUST_REST_GYRO, params::id::ROBUST_REST_GYRO),
            (ORIENT_PARAM_ROBUST_REST_ACCEL, params::id::ROBUST_REST_ACCEL),
            (ORIENT_PARAM_ROBUST_REST_TIME, params::id::ROBUST_REST_TIME),
            (ORIENT_PARAM_ROBUST_REST_TAU, params::id::ROBUST_REST_TAU),
            (ORIENT_PARAM_ROBUST_BIAS_TAU_REST, params::id::ROBUST_BIAS_TAU_REST),
            (ORIENT_PARAM_ROBUST_BIAS_TAU_MOTION, params::id::ROBUST_BIAS_TAU_MOTION),
            (ORIENT_PARAM_ROBUST_BIAS_LIMIT, params::id::ROBUST_BIAS_LIMIT),
            (ORIENT_PARAM_ROBUST_MAG_NORM_TH, params::id::ROBUST_MAG_NORM_TH),
            (ORIENT_PARAM_ROBUST_MAG_DIP_TH, params::id::ROBUST_MAG_DIP_TH),
            (ORIENT_PARAM_ROBUST_HARD_IRON_TIME, params::id::ROBUST_HARD_IRON_TIME),
            (ORIENT_PARAM_ROBUST_REST_TILT, params::id::ROBUST_REST_TILT),
        ];
        for (c, r) in slots {
            assert_eq!(c, r);
        }
        // Every parameter of every kind has its ORIENT_PARAM_* constant above (the
        // common six and Madgwick's two are checked first).
        let all: std::collections::BTreeSet<u32> =
            Kind::ALL.iter().flat_map(|k| k.params().map(|p| p.id)).collect();
        assert_eq!(all.len(), slots.len() + 8);
    }

    #[test]
    fn every_kind_keeps_to_its_block_of_parameter_slots() {
        // ORIENT_MAX_PARAMS' documentation: 0-7 common, then one block per kind.
        let blocks = [
            (Kind::Madgwick, 8..16),
            (Kind::Mahony, 16..24),
            (Kind::Complementary, 24..40),
            (Kind::Ekf, 40..56),
            (Kind::Gmvdk, 56..80),
            (Kind::Robust, 80..104),
        ];
        assert_eq!(blocks.len(), Kind::ALL.len());
        assert!(params::COMMON.iter().all(|p| p.id < 8));
        for (kind, block) in blocks {
            for p in kind.params().skip(params::COMMON.len()) {
                assert!(block.contains(&p.id), "{kind:?}: {} in slot {}", p.name, p.id);
            }
        }
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
        // A lane group of four distinct Madgwick filters whose third sample is refused,
        // once by the flag check and once by the reading checks.
        let unwritten = OrientQuaternion { w: f64::NAN, x: 7.0, y: 7.0, z: 7.0 };
        let spoil: [fn(&mut OrientSample); 2] = [|s| s.reserved = 1, |s| s.gyro.y = f64::NAN];
        for spoil in spoil {
            unsafe {
                let hs: Vec<*mut OrientFilter> = (0..4).map(|_| new_madgwick()).collect();
                let twins: Vec<*mut OrientFilter> = (0..4).map(|_| new_madgwick()).collect();
                let mut frame = [moving_sample(); 4];
                spoil(&mut frame[2]);
                let mut out = [unwritten; 4];
                let mut n = 99;
                let status = orient_filters_update(hs.as_ptr(), frame.as_ptr(), 4, out.as_mut_ptr(), &mut n);
                assert_ne!(status, OrientStatus::Ok);
                assert_eq!(n, 2);
                for k in 0..2 {
                    assert_eq!(orient_filter_update(twins[k], &frame[k]), OrientStatus::Ok);
                    let mut q = OrientQuaternion::default();
                    assert_eq!(orient_filter_quaternion(twins[k], &mut q), OrientStatus::Ok);
                    assert_eq!(quat_bits(out[k]), quat_bits(q), "filter {k}: output not written");
                    assert_eq!(orient_filter_quaternion(hs[k], &mut q), OrientStatus::Ok);
                    assert_eq!(quat_bits(out[k]), quat_bits(q), "filter {k}");
                }
                for o in &out[2..] {
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
                // Four distinct handles (a lane group), then one more.
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
