//! Library version, ABI version, status messages, the last error, and eq. (33).

use super::*;

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
