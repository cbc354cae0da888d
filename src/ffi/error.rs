//! The panic boundary, the thread-local error detail and the mapping from core errors
//! to status codes.

use super::types::OrientStatus;
use crate::filters::state::StateError;
use crate::filters::Error;
use core::cell::RefCell;
use core::ffi::c_char;
use core::fmt::{self, Write};
use std::panic::{catch_unwind, AssertUnwindSafe};

const DETAIL_CAPACITY: usize = 256;

thread_local! {
    // A fixed buffer: recording an error never allocates.
    static DETAIL: RefCell<[u8; DETAIL_CAPACITY]> = const { RefCell::new([0; DETAIL_CAPACITY]) };
}

/// Writes into a byte buffer, truncating at a character boundary and keeping a final NUL.
struct Truncating<'a> {
    buf: &'a mut [u8],
    len: usize,
}

impl Write for Truncating<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let room = self.buf.len() - 1 - self.len;
        let mut take = s.len().min(room);
        while !s.is_char_boundary(take) {
            take -= 1;
        }
        self.buf[self.len..self.len + take].copy_from_slice(&s.as_bytes()[..take]);
        self.len += take;
        Ok(())
    }
}

/// Records `detail` as this thread's last error and returns `status`.
pub(crate) fn fail(status: OrientStatus, detail: fmt::Arguments<'_>) -> OrientStatus {
    DETAIL.with(|cell| {
        if let Ok(mut buf) = cell.try_borrow_mut() {
            let mut w = Truncating { buf: &mut buf[..], len: 0 };
            // Truncating never fails.
            let _ = w.write_fmt(detail);
            let end = w.len;
            buf[end] = 0;
        }
    });
    status
}

/// The status for a core error, with its message recorded.
pub(crate) fn from_core(e: Error) -> OrientStatus {
    let status = match e {
        Error::UnknownParam(_) => OrientStatus::UnknownParam,
        Error::ParamOutOfRange { .. } => OrientStatus::ParamOutOfRange,
        Error::NonFinite(_) => OrientStatus::NonFinite,
        Error::InvalidDt(_) => OrientStatus::InvalidDt,
        Error::ZeroVector(_) => OrientStatus::ZeroVector,
        Error::TooLarge(_) => OrientStatus::TooLarge,
        Error::Saturated(_) => OrientStatus::Saturated,
        Error::MissingSensor(_) => OrientStatus::MissingSensor,
        Error::NotInitialized => OrientStatus::NotInitialized,
        Error::Numeric => OrientStatus::Numeric,
    };
    fail(status, format_args!("{e}"))
}

/// The status for a snapshot error, with its message recorded.
pub(crate) fn from_state(e: StateError) -> OrientStatus {
    let status = match e {
        StateError::BufferTooSmall(_) => OrientStatus::BufferTooSmall,
        _ => OrientStatus::InvalidState,
    };
    fail(status, format_args!("{e}"))
}

/// A pointer to this thread's last error detail (NUL-terminated, empty if none).
pub(crate) fn detail_ptr() -> *const c_char {
    DETAIL.with(|cell| cell.as_ptr() as *const c_char)
}

/// Runs an exported function's body behind the panic boundary.
pub(crate) fn guard(body: impl FnOnce() -> Result<(), OrientStatus>) -> OrientStatus {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => OrientStatus::Ok,
        Ok(Err(status)) => status,
        Err(payload) => {
            let text = payload
                .downcast_ref::<&str>()
                .copied()
                .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
                .unwrap_or("(no message)");
            fail(OrientStatus::Panic, format_args!("internal panic: {text}"))
        }
    }
}

/// Runs a body that cannot report a status behind the panic boundary.
pub(crate) fn guard_value<T>(fallback: T, body: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or(fallback)
}

/// The fixed message of a status code, NUL-terminated.
pub(crate) fn status_message(status: i32) -> &'static [u8] {
    match status {
        0 => b"ok\0",
        1 => b"a required pointer argument is NULL\0",
        2 => b"the handle is not a live OrientFilter or OrientJoints\0",
        3 => b"this filter kind is not built in this version\0",
        4 => b"unknown enum value, flag bit or index\0",
        5 => b"the filter kind has no such parameter\0",
        6 => b"parameter value not finite or out of range\0",
        7 => b"a sample field holds NaN or infinity\0",
        8 => b"dt must be finite, at least 1e-9 s and at most 1e6 s\0",
        9 => b"zero vector: norm too small to normalise\0",
        10 => b"reading too large: beyond its physical bound, or its norm overflows\0",
        11 => b"sensor reading at or beyond its configured range\0",
        12 => b"sample lacks a sensor the filter needs\0",
        13 => b"filter waits for its first accelerometer sample (with dt > 0)\0",
        14 => b"no data yet for this output\0",
        15 => b"update would produce a non-finite orientation\0",
        16 => b"count too large for any buffer\0",
        17 => b"struct_size does not match this library's OrientConfig\0",
        18 => b"internal panic caught at the C boundary\0",
        19 => b"output buffer too small\0",
        20 => b"state blob truncated, corrupted, or of another version or kind\0",
        21 => b"a buffer the call needs could not be allocated\0",
        22 => b"a joint names a missing segment, its own child, a second parent, a cycle or a bad axis\0",
        _ => b"unknown status code\0",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    fn detail() -> String {
        // SAFETY: detail_ptr points at this thread's NUL-terminated buffer.
        unsafe { CStr::from_ptr(detail_ptr()) }.to_str().unwrap().to_owned()
    }

    #[test]
    fn long_details_are_truncated_on_a_char_boundary() {
        let long = "é".repeat(400);
        fail(OrientStatus::Panic, format_args!("{long}"));
        let d = detail();
        assert!(d.len() < DETAIL_CAPACITY && d.len() >= DETAIL_CAPACITY - 3);
        assert!(d.chars().all(|c| c == 'é'));
    }

    #[test]
    fn panics_become_a_status() {
        let s = guard(|| panic!("boom"));
        assert_eq!(s, OrientStatus::Panic);
        assert_eq!(detail(), "internal panic: boom");
    }

    #[test]
    fn every_status_has_a_message() {
        for code in 0..=21 {
            assert_ne!(status_message(code), b"unknown status code\0", "{code}");
        }
        assert_eq!(status_message(99), b"unknown status code\0");
    }
}
