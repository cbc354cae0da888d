//! Updates: one sample, a batch, and one sample each for many filters.

use super::*;

/// One update. On any status but OK the filter's state is exactly as before.
///
/// Checks, in order: flags and reserved (INVALID_ARGUMENT); dt finite, at least 1e-9 s
/// and at most 1e6 s (INVALID_DT; in a batch this catches timestamps going backwards;
/// ORIENT_PARAM_SAME_INSTANT makes dt = 0 a burst sample instead);
/// gyroscope present (MISSING_SENSOR), finite (NON_FINITE), within
/// ORIENT_PARAM_GYRO_RANGE (SATURATED, unless ORIENT_PARAM_SATURATION_RECOVERY uses it
/// clipped), every component below 1e4 rad/s (TOO_LARGE);
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
/// magnetometer within 1e-6 rad of parallel to the sample's accelerometer reading
/// (gravity) gives no heading, so that step is the kind's IMU update, bit for bit
/// (ORIENT_FLAG_MAG_USED clear, ORIENT_FLAG_MAG_REJECTED set), in every kind: at the
/// first sample, in a start-up period, after a gap and in the running filter.
/// NUMERIC guards a step whose result would not be
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
pub(crate) unsafe fn items<'a, T>(ptr: *const T, n: usize, what: &str) -> Result<&'a [T], OrientStatus> {
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
pub(crate) unsafe fn fail_item(
    processed: *mut usize,
    what: &str,
    i: usize,
    status: OrientStatus,
) -> OrientStatus {
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
        // NULL pointers first (the handle too), then the count, then the handle.
        if filter.is_null() {
            return Err(null());
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
/// is `n`. `filters` and `samples` may be NULL only when `n` is 0. On x86-64 and
/// aarch64, two consecutive distinct Madgwick filters may be updated side by side, which
/// takes fewer instructions; on every target the results and statuses are those of
/// separate calls, bit for bit.
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
        // A NULL `filters` comes before the samples' count (items tests one array at a
        // time): tested on that error's path only, which leaves the loop below as it was.
        let samples = items(samples, n, "samples").map_err(|e| if filters.is_null() { null() } else { e })?;
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
        const LANES: usize = Filter::GROUP_LANES;
        let mut i = 0;
        while i < n {
            let group = &handles[i..n.min(i + LANES)];
            // Where the lanes do not pay (LANES_PAY), one filter at a time.
            let distinct = crate::filters::pipeline::filter::LANES_PAY
                && group.len() == LANES
                && (0..LANES).all(|a| (a + 1..LANES).all(|b| group[a] != group[b]));
            if distinct {
                // Different filters, LANES of them: their steps may run side by side.
                // The host's samples, read in place (see SampleView), up to the first
                // whose flag word is refused.
                let mut views = [None; LANES];
                let mut bad = None;
                for (k, v) in views.iter_mut().enumerate() {
                    match host_sample(&samples[i + k]) {
                        Ok(s) => *v = Some(s),
                        Err(status) => {
                            bad = Some((k, status));
                            break;
                        }
                    }
                }
                let ptrs: [*mut OrientFilter; LANES] = core::array::from_fn(|k| group[k]);
                let mut fs = ptrs.map(|p| &mut (*p).filter);
                // Every filter the group updates has its output written, also when a
                // later one in the group refuses its sample.
                let write = |k: usize, q: Quat| {
                    if !quaternions.is_null() {
                        quaternions.add(i + k).write(quat_to(q));
                    }
                };
                let result = match bad {
                    None => {
                        let views = views.map(|v| v.expect("every sample viewed"));
                        let refs = core::array::from_fn(|k| &views[k]);
                        // The outputs read only when they are wanted.
                        if quaternions.is_null() {
                            Filter::update_group_view::<_, LANES, false>(&mut fs, refs, |_, _| ())
                        } else {
                            Filter::update_group_view::<_, LANES, true>(&mut fs, refs, write)
                        }
                        .map_err(|(k, e)| (k, from_core(e)))
                    }
                    // The ones before the bad sample still get their update.
                    Some((k, status)) => (0..k)
                        .try_for_each(|j| match &views[j] {
                            Some(v) => {
                                fs[j].update_inline(v).map_err(|e| (j, from_core(e)))?;
                                write(j, fs[j].quaternion());
                                Ok(())
                            }
                            None => unreachable!("viewed before the refused one"),
                        })
                        .and(Err((k, status))),
                };
                result.map_err(|(k, status)| failed(i + k, status))?;
                i += LANES;
                continue;
            }
            // One mutable borrow at a time, so a handle listed twice is simply updated
            // twice, in order.
            let f = &mut (*handles[i]).filter;
            host_sample(&samples[i])
                .and_then(|s| f.update_inline(&s).map_err(from_core))
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
