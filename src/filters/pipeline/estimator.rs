//! The trait every filter kind implements, and what its update and re-acquisition
//! exchange with the common lifecycle ([`super::Runner`]).

use crate::filters::diagnostics::Diagnostics;
use crate::filters::diagnostics::Uncertainty;
use crate::filters::kind::Kind;
use crate::filters::params::Settings;
use crate::filters::pipeline::sample::Usual;
use crate::filters::state::Codec;
use crate::math::{Frame, Quat, Vec3};

/// One filter kind: its settings and parameter table, its native frame, and its state
/// with the update written in the paper's terms. Everything else (checks, start-up from
/// the first sample, gaps, frames, flags, snapshots' framing, outputs) is the common
/// lifecycle's, the same for every kind.
pub(crate) trait Estimator: Clone + core::fmt::Debug + PartialEq + Send + Sync + 'static {
    /// The settings struct made by the kind's `settings!` table.
    type Settings: Settings;
    const KIND: Kind;
    /// The earth frame the kind's equations are written in.
    const NATIVE: Frame;
    /// True for kinds that estimate their start from a period of samples themselves.
    const OWN_STARTUP: bool = false;
    /// Which [`Diagnostics`](crate::filters::Diagnostics) fields this kind can report
    /// (`diag` bits; an option that is off clears its bits in a filter's `present`).
    const DIAGNOSTICS: u32;

    fn create(settings: Self::Settings) -> Self;
    fn settings(&self) -> &Self::Settings;
    fn settings_mut(&mut self) -> &mut Self::Settings;
    /// Takes new settings; the state is kept.
    fn configure(&mut self, settings: Self::Settings) {
        *self.settings_mut() = settings;
    }
    /// Bytes of the heap blocks the state holds besides itself (its boxes), for
    /// [`crate::Filter::memory`]: none unless a kind says so.
    fn heap_bytes(&self) -> usize {
        0
    }
    /// Back to the state of [`Estimator::create`] with these settings (kinds with boxed
    /// state override it to keep their boxes).
    fn restart(&mut self, settings: Self::Settings) {
        *self = Self::create(settings);
    }
    /// One update in the native frame; `None` (and no change) on numerical failure,
    /// except for a kind with [`Estimator::FAILURE_RESTARTS`].
    fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step>;
    /// True while a kind with [`Estimator::OWN_STARTUP`] is in its start-up period and
    /// has taken a sample of it: the lifecycle's start-up stage, where the filter has no
    /// orientation yet but waits for nothing other than more samples of the period.
    fn starting(&self) -> bool {
        false
    }
    /// True for a kind whose update keeps no copy of its state to put back: an argument
    /// at its update shows that no sample within the runner's bounds makes it fail, and a
    /// failure beyond them (a core driven directly) starts it over from the orientation
    /// it had, with its settings, so that good samples bring it back. Read by the shared
    /// tests (`filters::tests`), which hold each kind to its rule.
    #[cfg_attr(not(test), allow(dead_code))]
    const FAILURE_RESTARTS: bool = false;
    /// True for kinds with an [`Estimator::update_usual`] of their own; the others'
    /// updates call functions anyway, and the lifecycle calls their `update` directly.
    const USUAL: bool = false;
    /// True when the settings let [`Estimator::update_usual`] stand for the update (an
    /// option with a path of its own, such as a rest-bias learner, makes it false). The
    /// lifecycle asks whenever the settings change, and does not take the usual step
    /// while it is false.
    fn usual_settings(&self) -> bool {
        true
    }
    /// [`Estimator::update`]'s usual case, which calls no function: the same result, or
    /// `None` with nothing changed when the case is not the usual one (the caller then
    /// takes [`Estimator::update`]). Called only while [`Estimator::usual_settings`].
    /// Returns the flags the step leaves ([`Step::flags`]), computed in the kind's copy of
    /// the step for each case, where they are constants or nearly.
    #[inline(always)]
    fn update_usual(&mut self, s: &Usual) -> Option<u32> {
        let step = self.update(s.dt, s.gyro, s.accel.map(|a| a.v), s.mag.map(|m| m.v))?;
        Some(step.flags(s.accel.is_some(), s.mag.is_some()))
    }
    /// The output orientation (native frame, or relative for GMVDK's relative output).
    fn quaternion(&self) -> Quat;
    /// The orientation in the native earth frame (GMVDK's, not its relative output).
    fn absolute_quaternion(&self) -> Quat {
        self.quaternion()
    }
    /// True when the output is not in an earth frame (GMVDK's relative output).
    fn relative(&self) -> bool {
        false
    }
    /// Sets the estimate (native frame, unit quaternion).
    fn set_quaternion(&mut self, q: Quat);
    /// Re-acquisition after a gap (native frame): `keep` has the accelerometer's
    /// inclination and the heading held before the gap, `with_mag` the accelerometer's
    /// and magnetometer's attitude when the sample has a usable magnetometer. Each kind
    /// takes one, starts its low-passes and detectors over and keeps its bias estimate,
    /// but for the rest watch's still reading ([`Reacquisition::still`]), which becomes
    /// the bias of a kind that learns one. Returns true when the magnetometer's attitude
    /// was taken.
    fn reacquire(&mut self, r: &Reacquisition) -> bool;
    /// The [`Diagnostics`] fields this filter reports with its settings: those of
    /// [`Kind::diagnostics`], less those of an option that is off.
    fn fields(&self) -> u32 {
        Self::KIND.diagnostics()
    }
    /// Fills the fields of [`Diagnostics`] this filter has (its `present` bits are set to
    /// [`Estimator::fields`] before; a kind clears those it has no value for yet).
    fn diagnose(&self, d: &mut Diagnostics);
    /// The kind's model of its error, where it has one (none by default).
    fn uncertainty(&self) -> Uncertainty {
        Uncertainty::default()
    }
    /// True when the kind counts the sensor as resting now ([`crate::filters::flags::REST`]).
    fn at_rest(&self) -> bool {
        false
    }
    /// True when the kind, with its settings, learns its gyroscope bias in motion: the
    /// horizontal part, which its inclination correction measures (the joints' prediction
    /// takes that learning: [`crate::joints::JointParams::bias_learn_rate`]). A kind that
    /// learns its bias only at rest, or not at all, says false (the default).
    fn learns_bias_in_motion(&self) -> bool {
        false
    }
    /// True when the kind counts the magnetic field as disturbed now
    /// ([`crate::filters::flags::MAG_DISTURBED`]).
    fn mag_disturbed(&self) -> bool {
        false
    }
    /// The state fields of a snapshot, in order.
    fn codec(&mut self, c: &mut dyn Codec);
    /// True when every value is one the kind's updates could have left (a decoded
    /// snapshot is checked with it).
    fn valid(&self) -> bool;
}

/// What a core needs to re-acquire its orientation after a gap (native frame).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Reacquisition {
    /// Inclination from the accelerometer, heading as before the gap.
    pub keep: Quat,
    /// Inclination from the accelerometer, heading from the magnetometer.
    pub with_mag: Option<Quat>,
    /// The sample's time step (the gap, s) and readings.
    pub dt: f64,
    pub gyro: Vec3,
    pub accel: Vec3,
    pub mag: Option<Vec3>,
    /// The rest watch asked for this re-acquisition and the sensor still lies still: its
    /// gyroscope reading, a bias estimate for a kind that learns one
    /// ([`crate::filters::pipeline::watch::Watch::still`]).
    pub still: Option<Vec3>,
}

impl Reacquisition {
    /// The orientation a kind without its own magnetometer test takes, and whether the
    /// magnetometer's heading is in it.
    pub fn plain(&self) -> (Quat, bool) {
        match self.with_mag {
            Some(q) => (q, true),
            None => (self.keep, false),
        }
    }
}

/// The rotation about `up` (earth frame) in `d`: its twist, the rotation about that axis
/// nearest to `d`; the identity when `d` has none (a half turn about a horizontal axis).
pub(crate) fn twist_about(d: Quat, up: Vec3) -> Quat {
    let along = up * d.vector().dot(up);
    Quat::new(d.w, along.x, along.y, along.z).try_normalized().unwrap_or(Quat::IDENTITY)
}

/// What one core update did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Step {
    pub used_accel: bool,
    pub used_mag: bool,
    /// The filter is still in its start-up period and has no orientation yet.
    pub initializing: bool,
}

impl Step {
    /// The [`crate::filters::flags`] an update past initialisation leaves: initialised, and each
    /// reading the sample had either used or rejected.
    #[inline(always)]
    pub(crate) fn flags(self, had_accel: bool, had_mag: bool) -> u32 {
        let bit = |used: bool, had: bool, used_bit: u32, rejected_bit: u32| {
            if used {
                used_bit
            } else if had {
                rejected_bit
            } else {
                0
            }
        };
        crate::filters::flags::INITIALIZED
            | bit(
                self.used_accel,
                had_accel,
                crate::filters::flags::ACCEL_USED,
                crate::filters::flags::ACCEL_REJECTED,
            )
            | bit(
                self.used_mag,
                had_mag,
                crate::filters::flags::MAG_USED,
                crate::filters::flags::MAG_REJECTED,
            )
    }
}

/// An [`Estimator`] impl: the kind's identity (with the `diag` bits it can report, written
/// with the bits' names) and the items every kind writes the same
/// way (construction, settings, and the forwards to its inherent `quaternion`,
/// `set_quaternion`, `reacquire`, `codec` and `valid`; with `usual: true`, also
/// `update_usual` and `usual_settings`), then the kind's own items in braces (`update`,
/// `diagnose`, and whatever it overrides).
macro_rules! estimator {
    // A kind with a usual step: also the forwards to its inherent `update_usual` and
    // `usual_settings`.
    (impl for $T:ident { settings: $S:ty, native: $frame:ident, own_startup: $own:expr, diagnostics: $d:expr, usual: true $(,)? } { $($item:tt)* }) => {
        $crate::filters::pipeline::estimator::estimator!(impl for $T { settings: $S, native: $frame, own_startup: $own, diagnostics: $d } {
            const USUAL: bool = true;

            fn usual_settings(&self) -> bool {
                $T::usual_settings(self)
            }

            #[inline(always)]
            fn update_usual(&mut self, s: &$crate::filters::pipeline::sample::Usual) -> Option<u32> {
                $T::update_usual(self, s)
            }

            $($item)*
        });
    };
    (impl for $T:ident { settings: $S:ty, native: $frame:ident, own_startup: $own:expr, diagnostics: $d:expr $(,)? } { $($item:tt)* }) => {
        impl $crate::filters::pipeline::estimator::Estimator for $T {
            type Settings = $S;
            const KIND: $crate::filters::Kind = $crate::filters::kind::Kind::$T;
            const NATIVE: $crate::math::Frame = $crate::math::Frame::$frame;
            const OWN_STARTUP: bool = $own;
            const DIAGNOSTICS: u32 = {
                #[allow(unused_imports)]
                use $crate::filters::diagnostics::diag::*;
                $d
            };

            fn create(settings: $S) -> Self {
                $T::new(settings)
            }

            fn settings(&self) -> &$S {
                &self.settings
            }

            fn settings_mut(&mut self) -> &mut $S {
                &mut self.settings
            }

            #[inline(always)]
            fn quaternion(&self) -> $crate::math::Quat {
                $T::quaternion(self)
            }

            fn set_quaternion(&mut self, q: $crate::math::Quat) {
                $T::set_quaternion(self, q)
            }

            fn reacquire(&mut self, r: &$crate::filters::pipeline::estimator::Reacquisition) -> bool {
                $T::reacquire(self, r)
            }

            fn codec(&mut self, c: &mut dyn $crate::filters::state::Codec) {
                $T::codec(self, c)
            }

            fn valid(&self) -> bool {
                $T::valid(self)
            }

            $($item)*
        }
    };
}
pub(crate) use estimator;
