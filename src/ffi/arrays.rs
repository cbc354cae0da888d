//! Batch update from separate arrays (structure of arrays), for hosts whose data already
//! sit in one array per sensor: NumPy, MATLAB, Eigen. Read in place, not copied into
//! OrientSample records, and with the flags and diagnostics after every sample.

use super::{
    diagnostics_to, fail, fail_item, from_core, guard, handle_mut, null, quat_to, OrientDiagnostics,
    OrientFilter, OrientQuaternion, OrientStatus,
};
use crate::filters::pipeline::sample::SampleView;
use crate::math::Vec3;

/// One row of the arrays, read in place.
struct ArrayRow<'a> {
    dt: f64,
    gyro: &'a [f64],
    accel: Option<&'a [f64]>,
    mag: Option<&'a [f64]>,
}

#[inline(always)]
fn vec3(v: &[f64]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

impl SampleView for ArrayRow<'_> {
    #[inline(always)]
    fn dt(&self) -> f64 {
        self.dt
    }
    #[inline(always)]
    fn gyro(&self) -> Option<Vec3> {
        Some(vec3(self.gyro))
    }
    #[inline(always)]
    fn accel(&self) -> Option<Vec3> {
        self.accel.map(vec3)
    }
    #[inline(always)]
    fn mag(&self) -> Option<Vec3> {
        self.mag.map(vec3)
    }
}

/// `3 n` doubles at `ptr`, or None for NULL.
unsafe fn rows<'a>(ptr: *const f64, n: usize) -> Option<&'a [f64]> {
    (!ptr.is_null()).then(|| core::slice::from_raw_parts(ptr, 3 * n))
}

/// Updates with `n` samples given as arrays, in order; the same updates as
/// orient_filter_update_batch with the same samples, bit for bit.
///
/// `gyro` holds `3 n` doubles (x, y, z of sample 0, then of sample 1, ...; a C-ordered
/// n x 3 array); `accel` and `mag` likewise, or NULL when the samples have no such
/// reading. `dt` holds `dt_count` doubles: 1 (every sample takes `dt[0]`) or `n` (one
/// per sample); any other count is ORIENT_STATUS_INVALID_ARGUMENT. After each sample,
/// `quaternions[i]`, `flags[i]` (orient_filter_flags) and `diagnostics[i]`
/// (orient_filter_diagnostics) receive the filter's outputs; each may be NULL when not
/// wanted. Stops at the first bad sample exactly as orient_filter_update_batch does: the
/// samples before it stay applied, the bad one changes nothing, and `*processed` (when
/// not NULL) is its index; on success it is `n`. `gyro` and `dt` may be NULL only when
/// `n` is 0.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn orient_filter_update_arrays(
    filter: *mut OrientFilter,
    n: usize,
    dt: *const f64,
    dt_count: usize,
    gyro: *const f64,
    accel: *const f64,
    mag: *const f64,
    quaternions: *mut OrientQuaternion,
    flags: *mut u32,
    diagnostics: *mut OrientDiagnostics,
    processed: *mut usize,
) -> OrientStatus {
    guard(|| {
        if !processed.is_null() {
            processed.write(0);
        }
        // NULL pointers first, as for every call; then the handle and the counts.
        if filter.is_null() || (n > 0 && (gyro.is_null() || dt.is_null())) {
            return Err(null());
        }
        let h = handle_mut(filter)?;
        if dt_count != 1 && dt_count != n {
            return Err(fail(
                OrientStatus::InvalidArgument,
                format_args!("dt_count is {dt_count}: it must be 1 or n = {n}"),
            ));
        }
        if n == 0 {
            return Ok(());
        }
        if n > isize::MAX as usize / (3 * core::mem::size_of::<f64>()) {
            return Err(fail(
                OrientStatus::CountTooLarge,
                format_args!("n = {n} samples cannot fit in memory"),
            ));
        }
        let dts = core::slice::from_raw_parts(dt, dt_count);
        let (gyro, accel, mag) = (rows(gyro, n).unwrap_or(&[]), rows(accel, n), rows(mag, n));
        for i in 0..n {
            let row = ArrayRow {
                dt: dts[if dt_count == 1 { 0 } else { i }],
                gyro: &gyro[3 * i..3 * i + 3],
                accel: accel.map(|a| &a[3 * i..3 * i + 3]),
                mag: mag.map(|m| &m[3 * i..3 * i + 3]),
            };
            h.filter.update_inline(&row).map_err(|e| fail_item(processed, "sample", i, from_core(e)))?;
            if !quaternions.is_null() {
                quaternions.add(i).write(quat_to(h.filter.quaternion()));
            }
            if !flags.is_null() {
                flags.add(i).write(h.filter.flags());
            }
            if !diagnostics.is_null() {
                diagnostics.add(i).write(diagnostics_to(&h.filter.diagnostics()));
            }
        }
        if !processed.is_null() {
            processed.write(n);
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::super::*;

    #[test]
    fn arrays_equal_the_record_batch_and_stop_at_a_bad_sample() {
        unsafe {
            let mut c = core::mem::MaybeUninit::<OrientConfig>::uninit();
            assert_eq!(orient_config_default(OrientKind::Mahony as i32, c.as_mut_ptr()), OrientStatus::Ok);
            let (mut a, mut b) = (core::ptr::null_mut(), core::ptr::null_mut());
            assert_eq!(orient_filter_new(c.as_ptr(), &mut a), OrientStatus::Ok);
            assert_eq!(orient_filter_new(c.as_ptr(), &mut b), OrientStatus::Ok);
            let n = 6;
            let gyro: Vec<f64> = (0..3 * n).map(|i| 0.01 * i as f64).collect();
            let mut accel: Vec<f64> = (0..n).flat_map(|i| [0.1 * i as f64, 0.2, 9.8]).collect();
            let mag: Vec<f64> = (0..n).flat_map(|_| [10.0, 20.0, -40.0]).collect();
            let dt = [0.01];
            accel[3 * 4 + 1] = f64::NAN;
            let records: Vec<OrientSample> = (0..n)
                .map(|i| OrientSample {
                    dt: 0.01,
                    gyro: OrientVec3 { x: gyro[3 * i], y: gyro[3 * i + 1], z: gyro[3 * i + 2] },
                    accel: OrientVec3 { x: accel[3 * i], y: accel[3 * i + 1], z: accel[3 * i + 2] },
                    mag: OrientVec3 { x: 10.0, y: 20.0, z: -40.0 },
                    flags: ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG,
                    reserved: 0,
                })
                .collect();
            let mut qa = vec![OrientQuaternion::default(); n];
            let mut qb = qa.clone();
            let mut flags = vec![0u32; n];
            let mut diags = vec![diagnostics_to(&Default::default()); n];
            let (mut pa, mut pb) = (99, 99);
            let sa = orient_filter_update_arrays(
                a,
                n,
                dt.as_ptr(),
                1,
                gyro.as_ptr(),
                accel.as_ptr(),
                mag.as_ptr(),
                qa.as_mut_ptr(),
                flags.as_mut_ptr(),
                diags.as_mut_ptr(),
                &mut pa,
            );
            let sb = orient_filter_update_batch(b, records.as_ptr(), n, qb.as_mut_ptr(), &mut pb);
            assert_eq!((sa, pa), (OrientStatus::NonFinite, 4));
            assert_eq!((sb, pb), (OrientStatus::NonFinite, 4));
            assert_eq!(qa[..4], qb[..4]);
            let mut f = 0;
            assert_eq!(orient_filter_flags(b, &mut f), OrientStatus::Ok);
            assert_eq!(flags[3], f);
            assert_eq!(diags[3].present, (*b).filter.diagnostics().present);
            assert_eq!(orient_filter_free(a), OrientStatus::Ok);
            assert_eq!(orient_filter_free(b), OrientStatus::Ok);
        }
    }
}
