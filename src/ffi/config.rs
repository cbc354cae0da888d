//! Configurations and parameters: defaults, slots, the parameter tables, and a live
//! filter's parameters.

use super::*;

/// Fills `config` with the defaults of `kind` (one of ORIENT_KIND_*): ENU, initial
/// orientation from the first accelerometer/magnetometer sample, every parameter at its
/// documented default. ORIENT_STATUS_INVALID_ARGUMENT for a number that is not an
/// ORIENT_KIND_*.
#[no_mangle]
pub unsafe extern "C" fn orient_config_default(kind: i32, config: *mut OrientConfig) -> OrientStatus {
    guard(|| {
        put(config, || {
            let c = Config::new(kind_from(kind)?).map_err(from_core)?;
            Ok(config_to(&c))
        })
    })
}

/// Sets parameter slot `id` of `config` after checking it against the kind's range.
#[no_mangle]
pub unsafe extern "C" fn orient_config_set_param(
    config: *mut OrientConfig,
    id: u32,
    value: f64,
) -> OrientStatus {
    guard(|| {
        let mut c = config_from(config)?;
        c.set_param(id, value).map_err(from_core)?;
        (*config).params[id as usize] = value;
        Ok(())
    })
}

/// Reads parameter slot `id` of `config` into `value`.
#[no_mangle]
pub unsafe extern "C" fn orient_config_get_param(
    config: *const OrientConfig,
    id: u32,
    value: *mut f64,
) -> OrientStatus {
    guard(|| {
        need(config.is_null())?;
        put(value, || config_from(config)?.param(id).map_err(from_core))
    })
}

/// Number of parameters of `kind` (common ones included), for orient_param_info().
#[no_mangle]
pub unsafe extern "C" fn orient_param_count(kind: i32, count: *mut u32) -> OrientStatus {
    guard(|| put(count, || Ok(kind_from(kind)?.params().count() as u32)))
}

/// Describes parameter number `index` (0 <= index < orient_param_count) of `kind`.
#[no_mangle]
pub unsafe extern "C" fn orient_param_info(
    kind: i32,
    index: u32,
    info: *mut OrientParamInfo,
) -> OrientStatus {
    guard(|| {
        need(info.is_null())?;
        let k = kind_from(kind)?;
        let Some(spec) = k.params().nth(index as usize) else {
            return Err(fail(
                OrientStatus::InvalidArgument,
                format_args!("parameter index {index} out of range"),
            ));
        };
        let text = strings::param_text(spec.id).ok_or_else(|| {
            fail(OrientStatus::Panic, format_args!("no strings for parameter slot {}", spec.id))
        })?;
        put(info, || Ok(param_info(spec, text)))
    })
}

/// A parameter's description as C sees it: the table's entry with its static strings.
pub(super) fn param_info(
    spec: &crate::filters::params::ParamSpec,
    text: strings::ParamText,
) -> OrientParamInfo {
    OrientParamInfo {
        id: spec.id,
        flags: if spec.zero_off { ORIENT_PARAM_FLAG_ZERO_OFF } else { 0 },
        name: text.name,
        unit: text.unit,
        description: text.doc,
        default_value: spec.default,
        min: spec.min,
        max: spec.max,
    }
}

/// Looks up the slot of the parameter called `name` (NUL-terminated) for `kind`.
#[no_mangle]
pub unsafe extern "C" fn orient_param_find(kind: i32, name: *const c_char, id: *mut u32) -> OrientStatus {
    guard(|| {
        need(name.is_null() || id.is_null())?;
        let k = kind_from(kind)?;
        let name = CStr::from_ptr(name).to_str().unwrap_or("");
        let spec = k.param_by_name(name).ok_or_else(|| {
            fail(OrientStatus::UnknownParam, format_args!("no parameter '{name}' for this kind"))
        })?;
        put(id, || Ok(spec.id))
    })
}

/// Changes parameter slot `id` of a running filter; the estimate is kept. One setting
/// changes what the output means, and so the output: GMVDK's relative_output switches
/// between the earth frame and the start-up pose.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_set_param(
    filter: *mut OrientFilter,
    id: u32,
    value: f64,
) -> OrientStatus {
    guard(|| handle_mut(filter)?.filter.set_param(id, value).map_err(from_core))
}

/// Reads parameter slot `id` of a filter.
#[no_mangle]
pub unsafe extern "C" fn orient_filter_get_param(
    filter: *const OrientFilter,
    id: u32,
    value: *mut f64,
) -> OrientStatus {
    guard(|| put(value, || handle(filter)?.filter.param(id).map_err(from_core)))
}
