//! Snapshots, reset and a set orientation.

use super::*;

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
        let n = h.filter.save(blob_out(buffer, capacity)?).map_err(from_state)?;
        written.write(n);
        Ok(())
    })
}

/// A save's output buffer: COUNT_TOO_LARGE for a `capacity` no buffer can have.
pub(crate) unsafe fn blob_out<'a>(buffer: *mut u8, capacity: usize) -> Result<&'a mut [u8], OrientStatus> {
    if capacity > isize::MAX as usize {
        return Err(fail(
            OrientStatus::CountTooLarge,
            format_args!("capacity {capacity} cannot be a buffer"),
        ));
    }
    Ok(core::slice::from_raw_parts_mut(buffer, capacity))
}

/// A load's blob: COUNT_TOO_LARGE for a `size` no buffer can have.
pub(crate) unsafe fn blob_in<'a>(buffer: *const u8, size: usize) -> Result<&'a [u8], OrientStatus> {
    if size > isize::MAX as usize {
        return Err(fail(OrientStatus::CountTooLarge, format_args!("size {size} cannot be a buffer")));
    }
    Ok(core::slice::from_raw_parts(buffer, size))
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
        h.filter.load(blob_in(buffer, size)?).map_err(from_state)
    })
}

/// Back to the state right after orient_filter_new(); parameters set since are kept, and
/// so are the mounting, heading offset, declination and sensor models set since (see
/// their functions).
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
