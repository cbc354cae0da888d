//! Tunable parameters: one numbered slot per setting, described by a static table so
//! that hosts (a Unity inspector, the replay tool's `--set`) can list and set them by
//! name without knowing each filter.
//!
//! The first slots are common to every kind, then each kind has its own block, then the
//! rest are free for later versions: [`BLOCKS`] is that map. A slot number is never reused
//! for a different meaning.

/// Number of parameter slots in a configuration.
pub const MAX_PARAMS: usize = 128;

/// A run of parameter slots and whom it belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SlotBlock {
    /// `common` (the [`COMMON`] settings), a kind's name ([`crate::Kind::name`]), or
    /// `free`.
    pub owner: &'static str,
    /// How documentation names the owner.
    pub label: &'static str,
    /// The first slot.
    pub first: u32,
    /// One past the last slot.
    pub end: u32,
}

/// Which slots belong to whom, in slot order, covering every slot once. The one place
/// this map is written: the header's `ORIENT_MAX_PARAMS` documentation is rendered from
/// it, and a test holds every parameter to its owner's block.
pub const BLOCKS: [SlotBlock; 8] = [
    SlotBlock { owner: "common", label: "common to every kind", first: 0, end: 8 },
    SlotBlock { owner: "madgwick", label: "Madgwick", first: 8, end: 16 },
    SlotBlock { owner: "mahony", label: "Mahony", first: 16, end: 24 },
    SlotBlock { owner: "complementary", label: "complementary", first: 24, end: 40 },
    SlotBlock { owner: "ekf", label: "EKF", first: 40, end: 56 },
    SlotBlock { owner: "gmvdk", label: "GMVDK", first: 56, end: 80 },
    SlotBlock { owner: "robust", label: "robust", first: 80, end: 104 },
    SlotBlock { owner: "free", label: "free for later versions", first: 104, end: 128 },
];

/// Slot numbers. Common slots first, then one block per kind ([`BLOCKS`]).
pub mod id {
    /// Magnitude of gravity used for the gravity and linear-acceleration outputs.
    pub const GRAVITY: u32 = 0;
    /// Gyroscope full-scale range; readings at or beyond it are rejected as saturated.
    pub const GYRO_RANGE: u32 = 1;
    /// Accelerometer full-scale range; readings at or beyond it are rejected as saturated.
    pub const ACCEL_RANGE: u32 = 2;
    /// The longest dt taken as given; a larger one is a gap, re-acquired (see `GAP` flag).
    pub const GAP_DT: u32 = 3;
    /// Saturation policy (issue 20): 0 rejects a saturated sample, 1 uses it clipped and
    /// recovers.
    pub const SATURATION_RECOVERY: u32 = 4;
    /// Burst policy for dt = 0 (issue 20): 0 rejects it, 1 takes it as the same instant.
    pub const SAME_INSTANT: u32 = 5;

    // Each kind's slots, defined beside its settings (the `settings!` tables).
    pub use crate::filters::complementary::id::*;
    pub use crate::filters::ekf::id::*;
    pub use crate::filters::gmvdk::id::*;
    pub use crate::filters::madgwick::id::*;
    pub use crate::filters::mahony::id::*;
    pub use crate::filters::robust::id::*;
}

/// What one parameter slot means.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// Slot number in [`crate::Config`] (see [`id`]).
    pub id: u32,
    /// Lower-case identifier, e.g. `beta_imu`.
    pub name: &'static str,
    /// Unit, e.g. `rad/s`; `1` for a dimensionless value.
    pub unit: &'static str,
    /// One sentence: meaning, and where the default comes from.
    pub doc: &'static str,
    pub default: f64,
    /// Smallest accepted value (inclusive), besides the 0 that `zero_off` allows.
    pub min: f64,
    /// Largest accepted value (inclusive).
    pub max: f64,
    /// 0 is also accepted and turns the feature off; `min` is then the smallest value
    /// that has it on (smaller ones would mean no filter, only broken arithmetic).
    pub zero_off: bool,
}

impl ParamSpec {
    /// True when `value` is finite and within `[min, max]`, or 0 where that turns the
    /// feature off. Subnormal values are never accepted (a ±0 is a 0).
    pub fn accepts(&self, value: f64) -> bool {
        let zero = value == 0.0;
        let normal = zero || value.abs() >= f64::MIN_POSITIVE;
        value.is_finite() && normal && ((zero && self.zero_off) || (value >= self.min && value <= self.max))
    }

    /// The smallest positive value accepted: `min`, or the smallest normal number for a
    /// range that starts at 0.
    pub fn smallest_positive(&self) -> f64 {
        if self.min > 0.0 {
            self.min
        } else {
            f64::MIN_POSITIVE
        }
    }
}

/// The settings every kind has.
pub const COMMON: [ParamSpec; 6] = [
    ParamSpec {
        id: id::GRAVITY,
        name: "gravity",
        unit: "m/s^2",
        doc: "Gravity magnitude for the gravity and linear-acceleration outputs; default \
              9.80665 (orient: standard gravity, CGPM 1901).",
        default: 9.80665,
        min: 1e-3,
        max: 1e3,
        zero_off: false,
    },
    ParamSpec {
        id: id::GYRO_RANGE,
        name: "gyro_range",
        unit: "rad/s",
        doc: "Gyroscope full scale: a sample with any axis at or beyond it is rejected as \
              saturated; 0 turns the check off (default; orient: the range is the sensor's, which a \
              configuration has to give).",
        default: 0.0,
        min: 0.1,
        max: 1e4,
        zero_off: true,
    },
    ParamSpec {
        id: id::ACCEL_RANGE,
        name: "accel_range",
        unit: "m/s^2",
        doc: "Accelerometer full scale: a sample with any axis at or beyond it is rejected as \
              saturated; 0 turns the check off (default; orient: as gyro_range).",
        default: 0.0,
        min: 1.0,
        max: 1e5,
        zero_off: true,
    },
    ParamSpec {
        id: id::GAP_DT,
        name: "gap_dt",
        unit: "s",
        doc: "Longest dt taken as given: a larger dt is a gap in the data (dropped packets), and \
              the update re-acquires the orientation from the sensors instead of integrating \
              over it (GAP and REACQUIRED flags); default 0.25 (orient: over a quarter second \
              a hand's rate changes enough that integrating the next sample's rate errs more \
              than one accelerometer reading; 10 periods of a 40 Hz sensor); 0 turns it off.",
        default: 0.25,
        min: 1e-3,
        max: 1e6,
        zero_off: true,
    },
    ParamSpec {
        id: id::SATURATION_RECOVERY,
        name: "saturation_recovery",
        unit: "1",
        doc: "What a reading at or beyond gyro_range or accel_range does: 0 (default; orient: a \
              clipped reading is wrong, so by default it is refused) rejects the sample as \
              saturated; 1 uses it clipped (a gyroscope reading clipped just under \
              the range, a saturated accelerometer reading left out), sets the SATURATED flag, \
              and after gyroscope saturation re-acquires the orientation from the next \
              unsaturated sample with an accelerometer reading (x-io Fusion's angular-rate \
              recovery). The physical bounds stay errors.",
        default: 0.0,
        min: 1.0,
        max: 1.0,
        zero_off: true,
    },
    ParamSpec {
        id: id::SAME_INSTANT,
        name: "same_instant",
        unit: "1",
        doc: "What a sample with dt = 0 does (bursts of packets with one timestamp): 0 \
              (default; orient: dt = 0 is an error unless the host says its sensor sends bursts) \
              rejects it as an invalid dt; 1 takes it as the same instant as the \
              next sample with dt > 0: nothing is integrated then, its gyroscope reading is \
              averaged with the following ones up to and including that sample, which \
              integrates the average over its dt, so no rotation is lost (the SAME_INSTANT \
              flag is set). Its accelerometer and magnetometer readings are not used.",
        default: 0.0,
        min: 1.0,
        max: 1.0,
        zero_off: true,
    },
];

/// A settings field's value as its `f64` slot holds it, without loss.
pub trait SlotValue: Copy {
    fn from_slot(v: f64) -> Self;
    fn to_slot(self) -> f64;
}

impl SlotValue for f64 {
    #[inline]
    fn from_slot(v: f64) -> f64 {
        v
    }
    #[inline]
    fn to_slot(self) -> f64 {
        self
    }
}

/// A setting that is on or off: 1 is on, 0 off (the slot keeps the value it was given;
/// any value from 0.5 up reads as on).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Switch(pub f64);

impl Switch {
    pub const ON: Switch = Switch(1.0);
    pub const OFF: Switch = Switch(0.0);

    #[inline]
    pub fn on(self) -> bool {
        self.0 >= 0.5
    }
}

impl SlotValue for Switch {
    #[inline]
    fn from_slot(v: f64) -> Switch {
        Switch(v)
    }
    #[inline]
    fn to_slot(self) -> f64 {
        self.0
    }
}

/// The mapping between a kind's settings struct and a configuration's slots (made by
/// `settings!`).
pub trait Settings: Copy + core::fmt::Debug + PartialEq + Default + Send + Sync + 'static {
    /// The kind's own parameters, the table `settings!` makes (`PARAMS`).
    const PARAMS: &'static [ParamSpec];
    /// The settings held in a configuration's slots.
    fn from_slots(s: &[f64; MAX_PARAMS]) -> Self;
    /// Writes the settings into their slots (shared ones included).
    fn write_slots(&self, s: &mut [f64; MAX_PARAMS]);
}

/// The default of a common slot (see [`COMMON`]).
pub const fn common_default(id: u32) -> f64 {
    let mut i = 0;
    while i < COMMON.len() {
        if COMMON[i].id == id {
            return COMMON[i].default;
        }
        i += 1;
    }
    panic!("not a common slot")
}

/// The one place a kind's parameters are defined. From one entry per parameter (field,
/// type, slot id and number, unit, default, range, and the sentence that gives its
/// meaning and the source of its default) it makes:
/// - the settings struct, each field documented by that sentence, and its `Default`;
/// - the slot numbers (`id::NAME`), re-exported by [`id`];
/// - the kind's [`ParamSpec`] table `PARAMS`, which the C API (`orient_param_info`), the
///   C constants (`src/ffi/param_ids.rs`, generated from it and checked by a test), the
///   C#, C++ and Python bindings and the replay tool read;
/// - `from_slots` / `write_slots`, the mapping between the struct and a [`crate::Config`]'s
///   slots.
///
/// `shared` fields are read from common slots (see [`COMMON`]), which have their
/// entries there.
macro_rules! settings {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $(
                $field:ident: $ty:ty = $id:ident $num:literal {
                    unit: $unit:literal,
                    default: $default:expr,
                    min: $min:expr,
                    max: $max:expr,
                    zero_off: $zero_off:literal,
                    doc: $doc:literal $(,)?
                }
            ),* $(,)?
        }
        $(shared { $($sfield:ident: $sty:ty = $sid:ident),* $(,)? })?
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name {
            $(
                #[doc = $doc]
                #[doc = concat!("\n\nUnit: ", $unit, "; range ", stringify!($min), " to ", stringify!($max),
                    "; slot ", stringify!($num), ".")]
                pub $field: $ty,
            )*
            $($(
                #[doc = concat!("From the common slot `", stringify!($sid), "`.")]
                pub $sfield: $sty,
            )*)?
        }

        /// Slot numbers of this kind's parameters.
        pub mod id {
            $(
                #[doc = $doc]
                pub const $id: u32 = $num;
            )*
        }

        /// This kind's own parameters (the common ones are [`crate::filters::params::COMMON`]).
        pub(crate) const PARAMS: &[$crate::filters::params::ParamSpec] = &[
            $(
                $crate::filters::params::ParamSpec {
                    id: $num,
                    name: stringify!($field),
                    unit: $unit,
                    doc: $doc,
                    default: $default,
                    min: $min,
                    max: $max,
                    zero_off: $zero_off,
                },
            )*
        ];

        impl Default for $name {
            fn default() -> Self {
                use $crate::filters::params::SlotValue;
                $name {
                    $($field: <$ty>::from_slot($default),)*
                    $($($sfield: <$sty>::from_slot(
                        $crate::filters::params::common_default($crate::filters::params::id::$sid)),)*)?
                }
            }
        }

        impl $crate::filters::params::Settings for $name {
            const PARAMS: &'static [$crate::filters::params::ParamSpec] = self::PARAMS;
            fn from_slots(s: &[f64; $crate::filters::params::MAX_PARAMS]) -> Self {
                use $crate::filters::params::SlotValue;
                $name {
                    $($field: <$ty>::from_slot(s[$num]),)*
                    $($($sfield: <$sty>::from_slot(s[$crate::filters::params::id::$sid as usize]),)*)?
                }
            }

            fn write_slots(&self, s: &mut [f64; $crate::filters::params::MAX_PARAMS]) {
                use $crate::filters::params::SlotValue;
                $(s[$num] = self.$field.to_slot();)*
                $($(s[$crate::filters::params::id::$sid as usize] = self.$sfield.to_slot();)*)?
            }
        }
    };
}
pub(crate) use settings;
