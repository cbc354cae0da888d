//! Offline mode through the C ABI: a whole recording in, the smoothed orientation of
//! every sample out (`orient::offline`, forward-backward smoothing). The host's arrays
//! are read in place and the backward pass's estimates kept in the host's output array,
//! so the call allocates 8 bytes per sample and one filter (orient_smooth_memory).

use super::{
    config_from, config_to, fail, fail_item, from_core, guard, null, put, quat_from, quat_to, OrientConfig,
    OrientQuaternion, OrientStatus,
};
use crate::filters::Sample;
use crate::math::{Quat, Vec3};
use crate::offline::{self, Orientations, SampleSource, SmoothError};

/// Writes the offline defaults to `*config`: the recommended kind
/// (ORIENT_KIND_ROBUST) with its defaults except for a heading time constant `tau_mag`
/// of 27 s, three times the causal default (the forward and backward passes' heading
/// drifts cancel in the fusion, so each can lean on the gyroscope longer). Pass it to
/// orient_smooth_arrays, changed or not.
#[no_mangle]
pub unsafe extern "C" fn orient_smooth_config_default(config: *mut OrientConfig) -> OrientStatus {
    guard(|| {
        if config.is_null() {
            return Err(null());
        }
        config.write(config_to(&crate::offline::config()));
        Ok(())
    })
}

/// Writes to `*bytes` the most memory orient_smooth_arrays allocates for `n` samples
/// whose output array does not overlap an input array: 8 bytes per sample (the backward
/// pass's heading uncertainty; its orientations are kept in `quaternions`) plus 32768
/// for the filter, `8 n + 32768`, whatever the kind. Allocates nothing. The largest `n`
/// is PTRDIFF_MAX / 32 (the output array's size in bytes must fit a ptrdiff_t: 2^58 - 1
/// on 64-bit targets, 2^26 - 1 on 32-bit ones); a larger `n` is
/// ORIENT_STATUS_COUNT_TOO_LARGE and leaves `*bytes` unwritten.
#[no_mangle]
pub unsafe extern "C" fn orient_smooth_memory(n: usize, bytes: *mut usize) -> OrientStatus {
    guard(|| {
        put(bytes, || {
            offline::memory(n).ok_or_else(|| {
                fail(OrientStatus::CountTooLarge, format_args!("n = {n} samples cannot fit in memory"))
            })
        })
    })
}

/// The host's arrays, read in place one sample at a time: no slice over them is formed,
/// so nothing of them is touched before the smoother's buffer is allocated and a sample
/// is asked for (orient_smooth_arrays' contract: `n` samples behind each pointer).
struct Arrays {
    n: usize,
    dt: *const f64,
    dt_count: usize,
    gyro: *const f64,
    accel: *const f64,
    mag: *const f64,
}

impl SampleSource for Arrays {
    fn len(&self) -> usize {
        self.n
    }
    fn sample(&self, i: usize) -> Sample {
        assert!(i < self.n, "sample {i} of {}", self.n);
        // SAFETY: i < n, and the caller gave 3 n doubles behind each non-NULL sensor
        // pointer and dt_count (1 or n) behind `dt`.
        unsafe {
            let row = |p: *const f64| {
                (!p.is_null()).then(|| Vec3::new(*p.add(3 * i), *p.add(3 * i + 1), *p.add(3 * i + 2)))
            };
            Sample {
                dt: *self.dt.add(if self.dt_count == 1 { 0 } else { i }),
                gyro: row(self.gyro),
                accel: row(self.accel),
                mag: row(self.mag),
            }
        }
    }
}

/// The host's output array, written and read back one slot at a time.
struct Outputs {
    n: usize,
    q: *mut OrientQuaternion,
}

impl Orientations for Outputs {
    fn len(&self) -> usize {
        self.n
    }
    fn get(&self, i: usize) -> Quat {
        assert!(i < self.n, "slot {i} of {}", self.n);
        // SAFETY: i < n, and the caller gave room for n quaternions.
        quat_from(unsafe { self.q.add(i).read() })
    }
    fn set(&mut self, i: usize, q: Quat) {
        assert!(i < self.n, "slot {i} of {}", self.n);
        // SAFETY: as in get.
        unsafe { self.q.add(i).write(quat_to(q)) }
    }
}

/// True when `count` values of `T` at `a` share a byte with the output array.
fn overlaps<T>(a: *const T, count: usize, out: *const OrientQuaternion, n: usize) -> bool {
    let (a0, a1) = (a as usize, (a as usize).saturating_add(count * core::mem::size_of::<T>()));
    let (o0, o1) =
        (out as usize, (out as usize).saturating_add(n * core::mem::size_of::<OrientQuaternion>()));
    !a.is_null() && a0 < o1 && o0 < a1
}

/// Smooths a whole recording offline (non-causal: every output uses the samples before
/// and after it) and writes the orientation at each sample to `quaternions` (room for
/// `n`, in the configuration's frame). Runs the kind and parameters of `config` forward,
/// then backward over the time-reversed recording, then forward again, and fuses the two
/// directions at each sample by a SLERP weighted by each direction's confidence. For
/// motion-capture post-processing.
///
/// The arrays are those of orient_filter_update_arrays: `gyro` holds `3 n` doubles (x,
/// y, z of sample 0, then of sample 1, ...), `accel` and `mag` likewise or NULL, `dt`
/// holds `dt_count` doubles, 1 or `n` (any other count is
/// ORIENT_STATUS_INVALID_ARGUMENT). A sample that orient_filter_update would refuse in a
/// forward run of a new filter of this configuration fails the call with that status;
/// `*processed` (when not NULL) is then its index and `quaternions` is left unwritten. No
/// other sample fails the call: a step the backward or the final forward pass refuses
/// (a gyroscope reading re-signed and offset by the bias estimate reaching a bound the
/// reading itself stayed within) is skipped, that pass holding its estimate over it. On
/// success `*processed` is `n`. `gyro`, `dt` and `quaternions` may be NULL only when `n`
/// is 0.
///
/// Memory: the arrays are read in place and `quaternions` holds the backward pass's
/// estimates until the fusion overwrites them, so the call allocates 8 bytes per sample
/// and one filter, at most orient_smooth_memory(n) bytes (8 n + 32768), in one block
/// reserved before the first sample is read. When that block cannot be allocated the
/// call returns ORIENT_STATUS_OUT_OF_MEMORY, `quaternions` is left unwritten and
/// `*processed` is 0. `n` above PTRDIFF_MAX / 32 is ORIENT_STATUS_COUNT_TOO_LARGE. When
/// `quaternions` overlaps an input array, the inputs are first copied (104 more bytes
/// per sample, OUT_OF_MEMORY as well when they cannot be had), so the results are those
/// of separate arrays.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn orient_smooth_arrays(
    config: *const OrientConfig,
    n: usize,
    dt: *const f64,
    dt_count: usize,
    gyro: *const f64,
    accel: *const f64,
    mag: *const f64,
    quaternions: *mut OrientQuaternion,
    processed: *mut usize,
) -> OrientStatus {
    guard(|| {
        if !processed.is_null() {
            processed.write(0);
        }
        let config = config_from(config)?;
        if n == 0 {
            return Ok(());
        }
        if gyro.is_null() || dt.is_null() || quaternions.is_null() {
            return Err(null());
        }
        if dt_count != 1 && dt_count != n {
            return Err(fail(
                OrientStatus::InvalidArgument,
                format_args!("dt_count is {dt_count}: it must be 1 or n = {n}"),
            ));
        }
        // Before anything is read: the output array (32 n bytes, the largest) must be
        // able to exist.
        if n > offline::max_samples() {
            return Err(fail(
                OrientStatus::CountTooLarge,
                format_args!("n = {n} samples cannot fit in memory"),
            ));
        }
        let smoothed = |e: SmoothError| match e {
            SmoothError::Sample { index, error } => fail_item(processed, "sample", index, from_core(error)),
            SmoothError::OutOfMemory { bytes } => fail(
                OrientStatus::OutOfMemory,
                format_args!("smoothing n = {n} samples: {bytes} bytes could not be allocated"),
            ),
        };
        let arrays = Arrays { n, dt, dt_count, gyro, accel, mag };
        let mut out = Outputs { n, q: quaternions };
        let aliased = overlaps(dt, dt_count, quaternions, n)
            || [gyro, accel, mag].into_iter().any(|p| overlaps(p, 3 * n, quaternions, n));
        if aliased {
            // The backward pass's estimates would overwrite samples the last pass reads:
            // the samples are copied first.
            let mut copy: Vec<Sample> = Vec::new();
            copy.try_reserve_exact(n).map_err(|_| {
                smoothed(SmoothError::OutOfMemory { bytes: n.saturating_mul(core::mem::size_of::<Sample>()) })
            })?;
            copy.extend((0..n).map(|i| arrays.sample(i)));
            offline::smooth_into(&config, &copy[..], &mut out).map_err(smoothed)?;
        } else {
            offline::smooth_into(&config, &arrays, &mut out).map_err(smoothed)?;
        }
        if !processed.is_null() {
            processed.write(n);
        }
        Ok(())
    })
}
