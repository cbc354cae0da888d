//! Offline mode through the C ABI: a whole recording in, the smoothed orientation of
//! every sample out (`orient::offline`, forward-backward smoothing).

use super::{
    config_from, config_to, fail, fail_item, from_core, guard, null, quat_to, OrientConfig, OrientQuaternion,
    OrientStatus,
};
use crate::filters::Sample;
use crate::math::Vec3;

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

/// Smooths a whole recording offline (non-causal: every output uses the samples before
/// and after it) and writes the orientation at each sample to `quaternions` (room for
/// `n`, in the configuration's frame). Runs the kind and parameters of `config` forward,
/// then backward over the time-reversed recording, then forward again, and fuses the two
/// directions at each sample by a SLERP weighted by each direction's confidence. For
/// motion-capture post-processing; allocates memory for the recording, unlike
/// orient_filter_update.
///
/// The arrays are those of orient_filter_update_arrays: `gyro` holds `3 n` doubles (x,
/// y, z of sample 0, then of sample 1, ...), `accel` and `mag` likewise or NULL, `dt`
/// holds `dt_count` doubles, 1 or `n` (any other count is
/// ORIENT_STATUS_INVALID_ARGUMENT). A sample that orient_filter_update would refuse in a
/// forward run of a new filter of this configuration fails the call with that status;
/// `*processed` (when not NULL) is then its index and `quaternions` is left unwritten. On
/// success `*processed` is `n`. `gyro`, `dt` and `quaternions` may be NULL only when `n`
/// is 0.
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
        if n > isize::MAX as usize / (3 * core::mem::size_of::<f64>()) {
            return Err(fail(
                OrientStatus::CountTooLarge,
                format_args!("n = {n} samples cannot fit in memory"),
            ));
        }
        let dts = core::slice::from_raw_parts(dt, dt_count);
        let row = |p: *const f64, i: usize| {
            (!p.is_null()).then(|| {
                let v = core::slice::from_raw_parts(p.add(3 * i), 3);
                Vec3::new(v[0], v[1], v[2])
            })
        };
        let samples: Vec<Sample> = (0..n)
            .map(|i| Sample {
                dt: dts[if dt_count == 1 { 0 } else { i }],
                gyro: row(gyro, i),
                accel: row(accel, i),
                mag: row(mag, i),
            })
            .collect();
        let smoothed = crate::offline::smooth(&config, &samples)
            .map_err(|e| fail_item(processed, "sample", e.index, from_core(e.error)))?;
        for (i, q) in smoothed.iter().enumerate() {
            quaternions.add(i).write(quat_to(*q));
        }
        if !processed.is_null() {
            processed.write(n);
        }
        Ok(())
    })
}
