//! The handle: what OrientFilter is, the registry lookups before any read, and the
//! calls that make, free and name one.

use super::*;

/// An orientation filter. Opaque to C (the header declares it with cbindgen.toml's
/// `after_includes`): create with orient_filter_new(), release with orient_filter_free().
/// Its address is its identity in the registry of live handles.
pub struct OrientFilter {
    pub(crate) filter: Filter,
}

pub(crate) type Res = Result<(), OrientStatus>;

pub(crate) fn null() -> OrientStatus {
    fail(OrientStatus::NullPointer, format_args!("a required pointer argument is NULL"))
}

/// Checks a handle and borrows it. Nothing is read through `h` unless the registry
/// holds it as a live handle.
///
/// # Safety
/// A live handle is not freed, nor used mutably by another thread, while the borrow lasts.
pub(crate) unsafe fn handle<'a>(h: *const OrientFilter) -> Result<&'a OrientFilter, OrientStatus> {
    if h.is_null() {
        return Err(null());
    }
    // A handle is an 8-byte aligned box: a pointer that is not (a joints handle's key,
    // bit 1 set, among them) is refused before the lookup.
    if h as usize & 7 != 0 || !registry::HANDLES.contains(h as usize) {
        return Err(invalid_handle(h));
    }
    Ok(&*h)
}

pub(crate) fn invalid_handle(h: *const OrientFilter) -> OrientStatus {
    fail(OrientStatus::InvalidHandle, format_args!("not a live OrientFilter handle: {h:p}"))
}

/// Checks a handle and borrows it mutably. Same contract as [`handle`].
pub(crate) unsafe fn handle_mut<'a>(h: *mut OrientFilter) -> Result<&'a mut OrientFilter, OrientStatus> {
    handle(h)?;
    Ok(&mut *h)
}

/// Writes through an out-pointer: checks it for NULL before anything else, then
/// computes the value (handle checks included) and writes it.
pub(crate) unsafe fn put<T>(out: *mut T, value: impl FnOnce() -> Result<T, OrientStatus>) -> Res {
    if out.is_null() {
        return Err(null());
    }
    out.write(value()?);
    Ok(())
}

/// NULL_POINTER when any of a call's required pointers is NULL.
pub(crate) fn need(any_null: bool) -> Res {
    if any_null {
        return Err(null());
    }
    Ok(())
}

/// Creates a filter from `config`. On success `*out` is a new handle; on failure it is
/// set to NULL (when `out` is not NULL). The configuration is checked as
/// orient_config_set_param and the OrientConfig fields document (VERSION_MISMATCH,
/// INVALID_ARGUMENT, UNKNOWN_PARAM, PARAM_OUT_OF_RANGE); with ORIENT_INIT_GIVEN, an
/// unusable `initial` quaternion is NON_FINITE, ZERO_VECTOR or TOO_LARGE, as for
/// orient_filter_set_quaternion. COUNT_TOO_LARGE when the most filters the library
/// holds are live.
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
        if filter as usize & 7 != 0 || !registry::HANDLES.remove(filter as usize) {
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
