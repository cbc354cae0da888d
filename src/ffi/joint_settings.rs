//! orient_config_for_joints, whose doc is generated from `joints::SENSOR_SETTINGS` by the
//! test `joint_settings_are_generated_from_the_tables` in `src/ffi/render.rs`; do not
//! edit. Regenerate: ORIENT_BLESS=1 cargo test -p orient --lib generated_from_the_tables

use super::*;

/// Sets in `config` what a sensor's filter runs with under joints: for
/// ORIENT_KIND_ROBUST, ORIENT_PARAM_ROBUST_BIAS_WALK at 8.727e-4 rad/s/sqrt(s) (0.05
/// deg/s/sqrt(s); its default 0.01 deg/s/sqrt(s)), so the motion bias filter follows a
/// drifting bias more closely (the joints hold the relative heading that a faster bias
/// estimate would otherwise let wander); ORIENT_PARAM_ROBUST_BIAS_LIMIT at 0.06981 rad/s
/// (4 deg/s; its default 2 deg/s), a bound on each axis, so a glove's bias up to 3 deg/s
/// per axis is learned whole in motion; and ORIENT_PARAM_ROBUST_REST_GYRO at 0.06981
/// rad/s (4 deg/s; its default 2 deg/s), a bound on the rate's length, so a sensor whose
/// bias is up to that long is still found at rest (the reference pose among its rests)
/// and learns its bias there; a turn about the vertical slower than it, held as long as
/// rest takes (ORIENT_PARAM_ROBUST_REST_TIME), is then taken for rest too. Other kinds
/// have none of them and `config` is left as it was. Call it after
/// orient_config_default() for each sensor of a rig whose joints hold its heading
/// (docs/ACCURACY.md has the simulated gloves' figures); a sensor alone keeps the
/// defaults. NULL_POINTER for a NULL `config`; VERSION_MISMATCH for a `struct_size` other
/// than this header's; INVALID_ARGUMENT for an unknown kind, frame or init;
/// PARAM_OUT_OF_RANGE for a slot outside its parameter's range; a refused `config` is
/// left as it was.
#[no_mangle]
pub unsafe extern "C" fn orient_config_for_joints(config: *mut OrientConfig) -> OrientStatus {
    joints::config_for_joints(config)
}
