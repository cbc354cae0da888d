//! The filter kinds and what each one has: parameters, diagnostics.

use crate::filters::params::{ParamSpec, Settings, COMMON};
use crate::filters::pipeline::estimator::Estimator;
use crate::filters::pipeline::filter::with_kind;

/// The filter kinds. Hosts swap filters by changing this value alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// Madgwick 2010, gradient descent (IMU and MARG).
    Madgwick,
    /// Mahony's nonlinear complementary filter (IMU and MARG).
    Mahony,
    /// McGinnis 2014 PI complementary filter, gains at rest only (IMU).
    Complementary,
    /// Kim & Golnaraghi 2004 quaternion EKF (IMU, magnetometer heading optional).
    Ekf,
    /// GMVDK 2024 double-SLERP filter (MARG; IMU without its magnetometer pipeline).
    Gmvdk,
    /// orient's recommended filter: quasi-inertial accelerometer low-pass, rest and motion
    /// bias estimation, magnetic disturbance rejection with hard-iron compensation.
    Robust,
}

impl Kind {
    pub const ALL: [Kind; 6] =
        [Kind::Madgwick, Kind::Mahony, Kind::Complementary, Kind::Ekf, Kind::Gmvdk, Kind::Robust];

    /// The lower-case name used by the replay tool: `madgwick`, `mahony`, ...
    pub fn name(self) -> &'static str {
        match self {
            Kind::Madgwick => "madgwick",
            Kind::Mahony => "mahony",
            Kind::Complementary => "complementary",
            Kind::Ekf => "ekf",
            Kind::Gmvdk => "gmvdk",
            Kind::Robust => "robust",
        }
    }

    pub fn from_name(name: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.name().eq_ignore_ascii_case(name))
    }

    /// The settings this kind has beyond the common ones: its settings table's.
    fn own_params(self) -> &'static [ParamSpec] {
        with_kind!(self, E => <<E as Estimator>::Settings as Settings>::PARAMS)
    }

    /// Which [`Diagnostics`](crate::filters::Diagnostics) fields this kind can report (an
    /// option that is off clears its bits in a filter's `present`: Madgwick's bias and
    /// rest, Mahony's and the EKF's rest, without their rest options).
    pub fn diagnostics(self) -> u32 {
        with_kind!(self, E => E::DIAGNOSTICS)
    }

    /// Every parameter of this kind: the common ones, then its own.
    pub fn params(self) -> impl Iterator<Item = &'static ParamSpec> {
        COMMON.iter().chain(self.own_params())
    }

    /// The parameter in slot `id`, if this kind has one there.
    pub fn param(self, id: u32) -> Option<&'static ParamSpec> {
        self.params().find(|p| p.id == id)
    }

    /// The parameter called `name`, if this kind has one.
    pub fn param_by_name(self, name: &str) -> Option<&'static ParamSpec> {
        self.params().find(|p| p.name == name)
    }
}
