//! The C calls around a filter's outputs (issue 20): mounting, heading, declination and
//! rig calibration. See `filters/host.rs` for the mathematics.

use super::{
    fail, fail_item, from_core, guard, handle, handle_mut, items, need, put, quat_from, quat_to,
    OrientFilter, OrientQuaternion, OrientStatus,
};
use crate::filters::{Error, Filter, RigHeading};
use crate::math::Quat;

/// Sets the mounting: the rotation from the sensor's frame to its body segment's
/// (v_segment = m v_sensor; normalised). From then on orient_filter_quaternion,
/// orient_filter_euler, orient_filter_rotation_matrix and
/// orient_filter_linear_accel_earth give the segment's orientation (sensor orientation
/// times the mounting's inverse); orient_filter_gravity and orient_filter_linear_accel
/// stay in the sensor's frame. Kept by orient_filter_reset and saved in snapshots.
/// NON_FINITE, ZERO_VECTOR or TOO_LARGE for an unusable quaternion.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_set_mounting(
    filter: *mut OrientFilter,
    mounting: *const OrientQuaternion,
) -> OrientStatus {
    guard(|| {
        need(mounting.is_null())?;
        let h = handle_mut(filter)?;
        h.filter.set_mounting(quat_from(*mounting)).map_err(from_core)
    })
}

/// The mounting (sensor to segment): the identity unless set. Its inverse (w, -x, -y,
/// -z) takes the segment's frame to the sensor's.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_mounting(
    filter: *const OrientFilter,
    mounting: *mut OrientQuaternion,
) -> OrientStatus {
    guard(|| put(mounting, || Ok(quat_to(handle(filter)?.filter.mounting()))))
}

/// The sensor's own orientation (sensor to earth), with the heading offset and the
/// declination applied but not the mounting; with the identity mounting it equals
/// orient_filter_quaternion. Identity before initialisation.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_sensor_quaternion(
    filter: *const OrientFilter,
    q: *mut OrientQuaternion,
) -> OrientStatus {
    guard(|| put(q, || Ok(quat_to(handle(filter)?.filter.sensor_quaternion()))))
}

/// Turns the outputs about the vertical so that the yaw of orient_filter_euler becomes
/// `yaw` (radians, wrapped to (-pi, pi]); inclination and mounting are kept and the
/// filter's own estimate is untouched, so a magnetometer does not undo it. The offset
/// is kept by orient_filter_reset and saved in snapshots. NOT_INITIALIZED before the
/// filter has an orientation, NON_FINITE for a NaN or infinite `yaw`.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_set_heading(filter: *mut OrientFilter, yaw: f64) -> OrientStatus {
    guard(|| handle_mut(filter)?.filter.set_heading(yaw).map_err(from_core))
}

/// orient_filter_set_heading(filter, 0): the yaw becomes 0, the inclination is kept.
/// NOT_INITIALIZED before the filter has an orientation.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_reset_heading(filter: *mut OrientFilter) -> OrientStatus {
    guard(|| handle_mut(filter)?.filter.reset_heading().map_err(from_core))
}

/// The heading offset (radians, in (-pi, pi]) set by orient_filter_set_heading and the
/// rig calls; 0 unless set.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_heading_offset(
    filter: *const OrientFilter,
    offset: *mut f64,
) -> OrientStatus {
    guard(|| put(offset, || Ok(handle(filter)?.filter.heading_offset())))
}

/// Sets the magnetic declination (radians, east positive, within [-pi, pi]), the angle
/// from true north to magnetic north: the outputs' heading is turned by it, so that a
/// heading from the magnetometer reads against true north (the NED yaw grows by it, the
/// ENU and NWU yaws shrink by it). Kept by orient_filter_reset and saved in snapshots.
/// NON_FINITE for NaN or infinity, TOO_LARGE beyond pi.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_set_declination(
    filter: *mut OrientFilter,
    declination: f64,
) -> OrientStatus {
    guard(|| handle_mut(filter)?.filter.set_declination(declination).map_err(from_core))
}

/// The magnetic declination (radians); 0 unless set.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_declination(
    filter: *const OrientFilter,
    declination: *mut f64,
) -> OrientStatus {
    guard(|| put(declination, || Ok(handle(filter)?.filter.declination())))
}

/// A rig call: checks its arguments ([`rig`]), runs `call` on the filters and
/// references, and turns a refusal `(index, error)` into a status naming the filter.
unsafe fn rig_call(
    filters: *const *mut OrientFilter,
    references: *const OrientQuaternion,
    n: usize,
    call: impl FnOnce(&mut [&mut Filter], &[Quat]) -> Result<(), (usize, Error)>,
) -> Result<(), OrientStatus> {
    let (mut fs, refs) = rig(filters, references, n)?;
    call(&mut fs, &refs).map_err(|(i, e)| fail_item(core::ptr::null_mut(), "filter", i, from_core(e)))
}

/// Checks a rig call's arguments: `n` live, distinct handles and `n` references.
unsafe fn rig<'a>(
    filters: *const *mut OrientFilter,
    references: *const OrientQuaternion,
    n: usize,
) -> Result<(Vec<&'a mut Filter>, Vec<Quat>), OrientStatus> {
    if n == 0 {
        return Err(fail(OrientStatus::InvalidArgument, format_args!("a rig needs at least one filter")));
    }
    let handles = items(filters, n, "filters")?;
    let refs = items(references, n, "references")?;
    if let Some(i) = handles.iter().position(|h| h.is_null()) {
        return Err(fail(OrientStatus::NullPointer, format_args!("filter {i} is NULL")));
    }
    for (i, h) in handles.iter().enumerate() {
        if let Err(status) = handle(*h) {
            return Err(fail(status, format_args!("filter {i}: not a live OrientFilter handle")));
        }
        if handles[..i].contains(h) {
            return Err(fail(OrientStatus::InvalidArgument, format_args!("filter {i} is listed twice")));
        }
    }
    let fs = handles.iter().map(|h| &mut (**h).filter).collect();
    Ok((fs, refs.iter().map(|q| quat_from(*q)).collect()))
}

/// Rig calibration from a reference posture. While the rig's segments hold known
/// orientations (an N-pose, a T-pose, a hand flat on a table), `references[i]` is the
/// orientation of `filters[i]`'s segment (segment to the posture's frame). The call
/// sets every filter's heading offset to one common value and its mounting so that each
/// filter reads its reference exactly, and its segment's orientation afterwards.
/// `heading` is the yaw (radians, about the frame's z axis) of the posture's frame in
/// the filters' earth frame (the way the subject faces); the outputs are then in the
/// posture's frame. A NaN `heading` estimates it: the yaw that brings the sensors'
/// headings nearest their segments' on average, exact when the mountings have no
/// heading part on average. The filters must share one earth frame (a magnetometer); 6D
/// filters, whose headings are each their own, take orient_rig_calibrate_each, or else
/// each one's heading goes into its mounting. Declinations are kept. Every handle and
/// reference is checked before anything changes: INVALID_ARGUMENT for n = 0 or a handle
/// listed twice, COUNT_TOO_LARGE for an `n` no array can hold, NULL_POINTER for a NULL
/// handle and INVALID_HANDLE for one that is not live; NOT_INITIALIZED for a filter
/// without an orientation; a reference is checked as orient_filter_set_quaternion
/// checks its quaternion: NON_FINITE, ZERO_VECTOR (a norm too small to normalise) or
/// TOO_LARGE (a norm that overflows); the detail names the index. NON_FINITE for an
/// infinite `heading`.
#[no_mangle]
pub unsafe extern "C" fn orient_rig_calibrate(
    filters: *const *mut OrientFilter,
    references: *const OrientQuaternion,
    n: usize,
    heading: f64,
) -> OrientStatus {
    guard(|| {
        let how = if heading.is_nan() { RigHeading::Estimated } else { RigHeading::Given(heading) };
        rig_call(filters, references, n, |fs, refs| Filter::calibrate_rig(fs, refs, how))
    })
}

/// Rig calibration for filters that share no earth frame (6D: each heading is its
/// filter's own), from a reference posture as orient_rig_calibrate's: sets each
/// filter's heading offset so that its sensor's heading is its segment's, each sensor
/// taken as strapped along its segment (a turn of the sensor about the segment's
/// vertical is not seen without a magnetometer), and its mounting so that it reads its
/// reference exactly, and its segment's orientation afterwards: each mounting is the
/// sensor's tilt on its segment, whatever heading offsets were set before; the outputs
/// are in the posture's frame. A host that knows its mountings sets them and calls
/// orient_rig_align_heading instead. Errors and checks as orient_rig_calibrate (without
/// `heading`).
#[no_mangle]
pub unsafe extern "C" fn orient_rig_calibrate_each(
    filters: *const *mut OrientFilter,
    references: *const OrientQuaternion,
    n: usize,
) -> OrientStatus {
    guard(|| rig_call(filters, references, n, |fs, refs| Filter::calibrate_rig(fs, refs, RigHeading::Each)))
}

/// Rig heading alignment: while the segments hold `references[i]` (as for
/// orient_rig_calibrate), turns each filter's heading offset so that its segment's
/// heading is its reference's; mountings and inclinations are kept. For rigs whose
/// mountings are known or were calibrated before, and whose headings drifted apart
/// (IMU-only filters, a restart). Errors and checks as orient_rig_calibrate.
#[no_mangle]
pub unsafe extern "C" fn orient_rig_align_heading(
    filters: *const *mut OrientFilter,
    references: *const OrientQuaternion,
    n: usize,
) -> OrientStatus {
    guard(|| rig_call(filters, references, n, Filter::align_rig_heading))
}
