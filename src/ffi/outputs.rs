//! What a filter reports: orientation in its forms, gravity, linear acceleration,
//! diagnostics and flags.

use super::*;

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

/// One standard deviation (radians) of the heading and inclination errors, from the kinds
/// that model them: ORIENT_KIND_EKF (both, from its covariance) and ORIENT_KIND_ROBUST
/// (heading: it grows while the magnetometer is distrusted or absent, faster while the
/// sensor turns; while it is used it settles to about
/// sqrt(sigma_v^2 + (sigma_b tau)^2 + sigma_s^2 w tau / 2), with sigma_v^2 = sigma_m^2 +
/// kappa^2 (d_n^2 + d_d^2) for a used field whose norm is off the reference by the
/// fraction d_n and whose dip is off by d_d rad, w the turn rate (rad/s), sigma_m =
/// ORIENT_PARAM_ROBUST_MAG_HEADING_SIGMA (what a clean field at rest settles to), kappa =
/// ORIENT_PARAM_ROBUST_MAG_DEVIATION_GAIN, sigma_s = ORIENT_PARAM_ROBUST_GYRO_SCALE_SIGMA,
/// tau = ORIENT_PARAM_ROBUST_TAU_MAG and sigma_b the bias uncertainty,
/// ORIENT_PARAM_ROBUST_BIAS_SIGMA_REST after a rest, else
/// ORIENT_PARAM_ROBUST_BIAS_SIGMA). For the other kinds, and before initialisation,
/// `present` is 0 and both fields are NaN. The heading is against the filter's reference
/// (magnetic north once a magnetometer was used, else the start heading); offsets the
/// host sets (heading, declination, rig calibration, mounting, frame) are exact and add
/// none. The robust kind's heading sigma also takes what the filter observes: a used
/// field whose heading disagrees with the estimate beyond the model's 2 sigma raises it
/// (the innovation, low-passed over 4 s, fading as the correction removes it), and a
/// gyroscope step faster than 2000 deg/s counts its whole angle (a glitch, not a turn).
/// orient_filter_set_quaternion makes the robust kind's heading exact (0 until the next
/// update, then as above); the EKF keeps its covariance.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_uncertainty(
    filter: *const OrientFilter,
    uncertainty: *mut OrientUncertainty,
) -> OrientStatus {
    guard(|| put(uncertainty, || Ok(uncertainty_to(&handle(filter)?.filter.uncertainty()))))
}

/// ORIENT_FLAG_* bits of the filter's state.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_flags(filter: *const OrientFilter, flags: *mut u32) -> OrientStatus {
    guard(|| put(flags, || Ok(handle(filter)?.filter.flags())))
}
