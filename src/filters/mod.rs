//! The filters, and [`Filter`]: one lifecycle and one set of outputs for every kind.
//!
//! Everything here is safe Rust with no FFI types; `update` does not allocate.

pub mod calibration; // issue 20: sensor models and estimators
pub mod complementary;
pub mod ekf;
pub mod gmvdk;
mod host; // issue 20: mounting, heading, declination, rig calibration
pub mod madgwick;
pub mod mahony;
pub mod params;
mod rest;
pub mod robust;
mod saturation; // issue 20: clip-and-recover policy and the dt = 0 policy
mod startup;
pub mod state;

use crate::math::{Euler, Frame, Quat, Vec3};
use complementary::{Complementary, ComplementarySettings};
use core::fmt;
use ekf::{Ekf, EkfSettings};
use gmvdk::{Gmvdk, GmvdkSettings};
pub use host::RigHeading;
use madgwick::{Madgwick, MadgwickSettings, LANES};
use mahony::{Mahony, MahonySettings};
use params::{id, ParamSpec, COMMON, MAX_PARAMS};
use robust::{Robust, RobustSettings};
use state::{Codec, Reader, StateError, Writer}; // issue 20

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

    /// The settings this kind has beyond the common ones.
    fn own_params(self) -> &'static [ParamSpec] {
        match self {
            Kind::Madgwick => &madgwick::PARAMS,
            Kind::Mahony => &mahony::PARAMS,
            Kind::Complementary => &complementary::PARAMS,
            Kind::Ekf => &ekf::PARAMS,
            Kind::Gmvdk => &gmvdk::PARAMS,
            Kind::Robust => &robust::PARAMS,
        }
    }

    /// Which [`Diagnostics`] fields this kind reports.
    pub fn diagnostics(self) -> u32 {
        use diag::*;
        match self {
            Kind::Madgwick => 0,
            Kind::Mahony => GYRO_BIAS,
            Kind::Complementary => GYRO_BIAS | REST,
            Kind::Ekf => GYRO_BIAS | RATE | COVARIANCE,
            Kind::Gmvdk => GYRO_BIAS | ALPHA | MU_KA | MU_KM | MU_K,
            Kind::Robust => GYRO_BIAS | REST,
        }
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

/// How the filter gets its first orientation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Init {
    /// From the first sample that has an accelerometer reading (and, if it has one, the
    /// magnetometer): see [`Frame::attitude_from`]. That sample is then also used for a
    /// normal update. Until then the filter reports that it is not initialised.
    #[default]
    AccMag,
    /// The identity orientation in the configured frame.
    Identity,
    /// This orientation, in the configured frame (normalised on use).
    Given(Quat),
}

/// Which quantity a problem was found in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    Dt,
    Gyro,
    Accel,
    Mag,
    Quaternion,
    /// An angle argument (heading, declination).
    Angle,
}

impl Field {
    fn name(self) -> &'static str {
        match self {
            Field::Dt => "dt",
            Field::Gyro => "gyroscope",
            Field::Accel => "accelerometer",
            Field::Mag => "magnetometer",
            Field::Quaternion => "quaternion",
            Field::Angle => "angle",
        }
    }
}

/// Why a call was refused. A refused call changes nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Error {
    /// This kind has no parameter in that slot.
    UnknownParam(u32),
    /// A parameter value outside its range or not finite.
    ParamOutOfRange { id: u32, value: f64 },
    /// A NaN or infinite value in a present field.
    NonFinite(Field),
    /// dt is below 1 ns (zero, negative, subnormal), above [`MAX_DT`] or not finite.
    InvalidDt(f64),
    /// A vector whose norm is zero or too small to normalise.
    ZeroVector(Field),
    /// A vector whose squared norm overflows, or a reading at or beyond its physical
    /// bound ([`MAX_GYRO`], [`MAX_ACCEL`], [`MAX_MAG`]).
    TooLarge(Field),
    /// A reading at or beyond the configured full-scale range.
    Saturated(Field),
    /// A sensor the filter needs is absent from the sample.
    MissingSensor(Field),
    /// The filter waits for an accelerometer reading to initialise.
    NotInitialized,
    /// The update would have produced a non-finite orientation.
    Numeric,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::UnknownParam(id) => write!(f, "this filter kind has no parameter {id}"),
            Error::ParamOutOfRange { id, value } => {
                write!(f, "parameter {id}: value {value} is out of range")
            }
            Error::NonFinite(field) => write!(f, "{} has a NaN or infinite value", field.name()),
            Error::InvalidDt(dt) => {
                write!(f, "dt must be finite, at least 1e-9 s and at most 1e6 s, got {dt:e}")
            }
            Error::ZeroVector(field) => {
                write!(f, "{} vector is zero or too small to normalise", field.name())
            }
            Error::TooLarge(field) => {
                write!(
                    f,
                    "{} reading is too large (beyond its physical bound, or its norm overflows)",
                    field.name()
                )
            }
            Error::Saturated(field) => {
                write!(f, "{} reading is at or beyond its configured range", field.name())
            }
            Error::MissingSensor(field) => {
                write!(f, "sample has no {} reading, which this filter needs", field.name())
            }
            Error::NotInitialized => write!(f, "filter waits for an accelerometer reading to initialise"),
            Error::Numeric => write!(f, "update would produce a non-finite orientation"),
        }
    }
}

impl std::error::Error for Error {}

/// One sensor sample. Units: gyro rad/s, accel m/s², mag any unit (consistent over a
/// run); `dt` in seconds since the previous sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    pub dt: f64,
    pub gyro: Option<Vec3>,
    pub accel: Option<Vec3>,
    pub mag: Option<Vec3>,
}

/// Read access to a sample where it lies: a [`Sample`], or a host's own struct (the C
/// API's), so that an update reads the host's memory in place rather than a copy just
/// written, which the processor reads back only after a stall (store-to-load
/// forwarding fails when the copy was written in narrower pieces than it is read).
pub(crate) trait SampleView {
    fn dt(&self) -> f64;
    fn gyro(&self) -> Option<Vec3>;
    fn accel(&self) -> Option<Vec3>;
    fn mag(&self) -> Option<Vec3>;
    /// The sample as a [`Sample`].
    #[inline]
    fn to_sample(&self) -> Sample {
        Sample { dt: self.dt(), gyro: self.gyro(), accel: self.accel(), mag: self.mag() }
    }
}

impl SampleView for Sample {
    #[inline(always)]
    fn dt(&self) -> f64 {
        self.dt
    }
    #[inline(always)]
    fn gyro(&self) -> Option<Vec3> {
        self.gyro
    }
    #[inline(always)]
    fn accel(&self) -> Option<Vec3> {
        self.accel
    }
    #[inline(always)]
    fn mag(&self) -> Option<Vec3> {
        self.mag
    }
}

/// A filter's configuration: kind, frame, initial orientation and parameter slots.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    kind: Kind,
    pub frame: Frame,
    pub init: Init,
    params: [f64; MAX_PARAMS],
}

impl Config {
    /// The defaults of `kind`: ENU, initialised from the first accelerometer (and
    /// magnetometer) sample, every parameter at its documented default. Every kind is
    /// built today; the `Result` leaves room for kinds a build may leave out.
    pub fn new(kind: Kind) -> Result<Config, Error> {
        let mut params = [0.0; MAX_PARAMS];
        for p in kind.params() {
            params[p.id as usize] = p.default;
        }
        Ok(Config { kind, frame: Frame::Enu, init: Init::AccMag, params })
    }

    /// A configuration from raw slots, every known slot checked against its range.
    /// Slots this kind does not use are ignored.
    pub fn from_slots(
        kind: Kind,
        frame: Frame,
        init: Init,
        slots: &[f64; MAX_PARAMS],
    ) -> Result<Config, Error> {
        let mut config = Config::new(kind)?;
        config.frame = frame;
        config.init = init;
        for p in kind.params() {
            config.set_param(p.id, slots[p.id as usize])?;
        }
        Ok(config)
    }

    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// The value in slot `id`.
    pub fn param(&self, id: u32) -> Result<f64, Error> {
        self.kind.param(id).map(|p| self.params[p.id as usize]).ok_or(Error::UnknownParam(id))
    }

    /// Sets slot `id` after checking the value against the parameter's range.
    pub fn set_param(&mut self, id: u32, value: f64) -> Result<(), Error> {
        let spec = self.kind.param(id).ok_or(Error::UnknownParam(id))?;
        if !spec.accepts(value) {
            return Err(Error::ParamOutOfRange { id, value });
        }
        self.params[id as usize] = value;
        Ok(())
    }

    /// Sets the parameter called `name`; `None` when the kind has no such parameter.
    pub fn set(&mut self, name: &str, value: f64) -> Option<Result<(), Error>> {
        let spec = self.kind.param_by_name(name)?;
        Some(self.set_param(spec.id, value))
    }

    /// All slots (unused ones are zero).
    pub fn slots(&self) -> &[f64; MAX_PARAMS] {
        &self.params
    }

    fn slot(&self, id: u32) -> f64 {
        self.params[id as usize]
    }
}

/// The smallest dt accepted (s): 1 ns.
pub const MIN_DT: f64 = 1e-9;
/// The largest dt accepted (s): 10⁶ s, eleven and a half days. Beyond `gap_dt` a step is
/// a gap and re-acquires; with the gap policy off, this bounds what one step integrates.
pub const MAX_DT: f64 = 1e6;

/// Physical bounds on the readings, applied whatever the configured sensor ranges: a
/// component at or beyond one is refused as [`Error::TooLarge`] before any arithmetic,
/// so that no accepted reading can overflow a filter's equations.
///
/// Gyroscope (rad/s): 10⁴ rad/s, about 573,000 °/s, over 100 times the largest MEMS
/// full scale (±4,000 °/s).
pub const MAX_GYRO: f64 = 1e4;
/// Accelerometer (m/s²): 10⁵ m/s², about 10,000 g, over 30 times the largest
/// consumer full scale (±400 g).
pub const MAX_ACCEL: f64 = 1e5;
/// Magnetometer (any unit): 10¹² in whatever unit the host uses; the earth's field is
/// 0.65 G, 65 µT, 65,000 nT or a few thousand counts at most.
pub const MAX_MAG: f64 = 1e12;

/// State flags reported by [`Filter::flags`].
pub mod flags {
    /// The filter has an orientation (always set unless waiting for acc/mag init).
    pub const INITIALIZED: u32 = 1;
    /// The last accepted update used the accelerometer.
    pub const ACCEL_USED: u32 = 2;
    /// The last accepted update used the magnetometer.
    pub const MAG_USED: u32 = 4;
    /// The last accepted update followed a gap: its dt was above `gap_dt`. Nothing was
    /// integrated over the gap (the motion in it is unknown): the update re-acquired the
    /// orientation from the sensors ([`REACQUIRED`]) or, without an accelerometer
    /// reading, held it ([`REACQUIRE_PENDING`]).
    pub const GAP: u32 = 8;
    /// The last accepted update re-acquired the orientation after a gap: inclination from
    /// the accelerometer, heading from the magnetometer when the sample has one (and the
    /// kind accepts it), else the heading held before the gap; the kind's internal
    /// low-passes and detectors started over, its bias estimate was kept.
    pub const REACQUIRED: u32 = 16;
    /// A gap ended on a sample without an accelerometer reading: the orientation is held
    /// (then integrated from the gyroscope) until the next sample that has one, which
    /// re-acquires it.
    pub const REACQUIRE_PENDING: u32 = 32;
    /// The last accepted update had a reading at or beyond its configured range, used
    /// clipped (`saturation_recovery` = 1): a gyroscope reading clipped just under the
    /// range, an accelerometer reading left out. After gyroscope saturation
    /// [`REACQUIRE_PENDING`] is set: the next unsaturated sample with an accelerometer
    /// reading re-acquires the orientation.
    pub const SATURATED: u32 = 64;
    /// The last accepted sample had dt = 0 and was taken as the same instant as the next
    /// sample with dt > 0 (`same_instant` = 1): nothing was integrated, its gyroscope
    /// reading waits to be averaged into that sample's step.
    pub const SAME_INSTANT: u32 = 128;
    /// Every bit above.
    pub const ALL: u32 =
        INITIALIZED | ACCEL_USED | MAG_USED | GAP | REACQUIRED | REACQUIRE_PENDING | SATURATED | SAME_INSTANT;
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
fn twist_about(d: Quat, up: Vec3) -> Quat {
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

/// Bits of [`Diagnostics::present`] and [`Kind::diagnostics`].
pub mod diag {
    pub const GYRO_BIAS: u32 = 1;
    pub const REST: u32 = 2;
    pub const ALPHA: u32 = 4;
    pub const MU_KA: u32 = 8;
    pub const MU_KM: u32 = 16;
    pub const MU_K: u32 = 32;
    pub const RATE: u32 = 64;
    pub const COVARIANCE: u32 = 128;
}

/// Internal states a host may show, the same struct for every kind. A field whose bit in
/// `present` is clear does not apply to this kind (or not yet) and holds NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diagnostics {
    /// [`diag`] bits of the fields that hold values.
    pub present: u32,
    /// Gyroscope bias being subtracted (rad/s): Mahony's b, McGinnis' ω_b, the EKF's drift
    /// δ, GMVDK's regression bias.
    pub gyro_bias: Vec3,
    /// McGinnis: the last sample counted as rest (gains active): 1.0, else 0.0.
    pub rest: f64,
    /// GMVDK accelerometer trust α of the last update.
    pub alpha: f64,
    /// GMVDK μ_KA, μ_KM and μ_K of the last update with a magnetometer.
    pub mu_ka: f64,
    pub mu_km: f64,
    pub mu_k: f64,
    /// EKF angular rate state ω (rad/s).
    pub rate: Vec3,
    /// EKF covariance diagonal, state order [q0, q1, q2, q3, ω, δ].
    pub covariance: [f64; 10],
}

impl Default for Diagnostics {
    fn default() -> Self {
        let nan = f64::NAN;
        Diagnostics {
            present: 0,
            gyro_bias: Vec3::new(nan, nan, nan),
            rest: nan,
            alpha: nan,
            mu_ka: nan,
            mu_km: nan,
            mu_k: nan,
            rate: Vec3::new(nan, nan, nan),
            covariance: [nan; 10],
        }
    }
}

// The EKF (about 1 KiB: a 10×10 covariance) sets the size of every handle. Boxing it
// would add a pointer chase to each EKF update to save under 1 KiB per handle.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
enum Core {
    Madgwick(Madgwick),
    Mahony(Mahony),
    Complementary(Complementary),
    Ekf(Ekf),
    Gmvdk(Gmvdk),
    Robust(Robust),
}

/// Runs the same expression on whichever filter the core holds.
macro_rules! each {
    ($core:expr, $f:ident => $body:expr) => {
        match $core {
            Core::Madgwick($f) => $body,
            Core::Mahony($f) => $body,
            Core::Complementary($f) => $body,
            Core::Ekf($f) => $body,
            Core::Gmvdk($f) => $body,
            Core::Robust($f) => $body,
        }
    };
}

impl Core {
    fn new(config: &Config) -> Core {
        match config.kind {
            Kind::Madgwick => Core::Madgwick(Madgwick::new(madgwick_settings(config))),
            Kind::Mahony => Core::Mahony(Mahony::new(mahony_settings(config))),
            Kind::Complementary => Core::Complementary(Complementary::new(complementary_settings(config))),
            Kind::Ekf => Core::Ekf(Ekf::new(ekf_settings(config))),
            Kind::Gmvdk => Core::Gmvdk(Gmvdk::new(gmvdk_settings(config))),
            Kind::Robust => Core::Robust(Robust::new(robust_settings(config))),
        }
    }

    /// The frame the filter's own equations are written in.
    fn native_frame(&self) -> Frame {
        match self {
            Core::Madgwick(_) | Core::Mahony(_) => Frame::Nwu,
            Core::Complementary(_) | Core::Gmvdk(_) | Core::Robust(_) => Frame::Enu,
            Core::Ekf(_) => Frame::Ned,
        }
    }

    /// True for filters that estimate their start from a period of samples themselves.
    fn own_startup(&self) -> bool {
        matches!(self, Core::Complementary(_) | Core::Gmvdk(_))
    }

    /// True when the output is not in an earth frame (GMVDK's relative output).
    fn relative(&self) -> bool {
        matches!(self, Core::Gmvdk(g) if g.settings.relative_output)
    }

    fn quaternion(&self) -> Quat {
        each!(self, f => f.quaternion())
    }

    /// The orientation in the native earth frame (GMVDK's, not its relative output).
    fn absolute_quaternion(&self) -> Quat {
        match self {
            Core::Gmvdk(f) => f.absolute_quaternion(),
            _ => self.quaternion(),
        }
    }

    /// Re-acquisition after a gap (native frame): `keep` has the accelerometer's
    /// inclination and the heading held before the gap, `with_mag` the accelerometer's
    /// and magnetometer's attitude when the sample has a usable magnetometer. Each kind
    /// takes one, starts its low-passes and detectors over and keeps its bias estimate.
    /// Returns true when the magnetometer's attitude was taken.
    fn reacquire(&mut self, r: &Reacquisition) -> bool {
        each!(self, f => f.reacquire(r))
    }

    fn set_quaternion(&mut self, q: Quat) {
        each!(self, f => f.set_quaternion(q))
    }

    /// Back to the state of [`Core::new`] without touching the heap.
    fn reset(&mut self, config: &Config) {
        match self {
            Core::Gmvdk(g) => {
                g.settings = gmvdk_settings(config);
                g.reset();
            }
            _ => *self = Core::new(config),
        }
    }

    /// Takes new settings from the configuration; the state is kept.
    fn configure(&mut self, config: &Config) {
        match self {
            Core::Madgwick(f) => f.settings = madgwick_settings(config),
            Core::Mahony(f) => f.settings = mahony_settings(config),
            Core::Complementary(f) => f.settings = complementary_settings(config),
            Core::Ekf(f) => f.settings = ekf_settings(config),
            Core::Gmvdk(f) => f.settings = gmvdk_settings(config),
            Core::Robust(f) => f.settings = robust_settings(config),
        }
    }

    /// One update in the native frame; `None` (and no change) on numerical failure.
    fn update(&mut self, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
        match self {
            Core::Madgwick(f) => f.update(dt, gyro, accel, mag),
            Core::Mahony(f) => f.update(dt, gyro, accel, mag),
            Core::Complementary(f) => f.update(dt, gyro, accel, mag),
            // Dispatches itself: 256-bit lanes with AVX (crate::isa::widest_lanes).
            Core::Ekf(f) => f.update(dt, gyro, accel, mag),
            Core::Gmvdk(f) => gmvdk_update(f, dt, gyro, accel, mag),
            Core::Robust(f) => f.update(dt, gyro, accel, mag),
        }
    }

    fn diagnostics(&self) -> Diagnostics {
        let mut d = Diagnostics::default();
        match self {
            Core::Madgwick(_) => {}
            Core::Mahony(f) => d.gyro_bias = f.bias(),
            Core::Complementary(f) => {
                d.gyro_bias = f.bias();
                d.rest = if f.at_rest() { 1.0 } else { 0.0 };
            }
            Core::Ekf(f) => {
                d.gyro_bias = f.drift();
                d.rate = f.rate();
                d.covariance = f.covariance_diagonal();
            }
            Core::Robust(f) => {
                d.gyro_bias = f.bias();
                d.rest = if f.at_rest() { 1.0 } else { 0.0 };
            }
            Core::Gmvdk(f) => {
                d.gyro_bias = f.bias();
                let t = f.trust();
                d.alpha = t.alpha;
                if f.mag_seen() {
                    d.mu_ka = t.mu_ka;
                    d.mu_km = t.mu_km;
                    d.mu_k = t.mu_k;
                }
            }
        }
        d.present = self.kind().diagnostics();
        if let Core::Gmvdk(f) = self {
            if !f.mag_seen() {
                d.present &= !(diag::MU_KA | diag::MU_KM | diag::MU_K);
            }
        }
        d
    }

    fn codec(&mut self, c: &mut dyn Codec) {
        each!(self, f => f.codec(c))
    }

    /// True when every value is one the kind's updates could have left (a decoded
    /// snapshot is checked with it).
    fn valid(&self) -> bool {
        each!(self, f => f.valid())
    }

    fn kind(&self) -> Kind {
        match self {
            Core::Madgwick(_) => Kind::Madgwick,
            Core::Mahony(_) => Kind::Mahony,
            Core::Complementary(_) => Kind::Complementary,
            Core::Ekf(_) => Kind::Ekf,
            Core::Gmvdk(_) => Kind::Gmvdk,
            Core::Robust(_) => Kind::Robust,
        }
    }
}

/// GMVDK's update in the widest copy the CPU has (crate::isa::widest). Out of line: inlined
/// into [`Core::update`], its large frame made every kind's dispatch save six registers
/// and set up that frame before the jump to its own update.
#[inline(never)]
fn gmvdk_update(f: &mut Gmvdk, dt: f64, gyro: Vec3, accel: Option<Vec3>, mag: Option<Vec3>) -> Option<Step> {
    crate::isa::widest(
        #[inline(always)]
        || f.update(dt, gyro, accel, mag),
    )
}

fn madgwick_settings(c: &Config) -> MadgwickSettings {
    MadgwickSettings {
        beta_imu: c.slot(id::MADGWICK_BETA_IMU),
        beta_marg: c.slot(id::MADGWICK_BETA_MARG),
        rest_bias_tau: c.slot(id::MADGWICK_REST_BIAS_TAU),
    }
}

fn mahony_settings(c: &Config) -> MahonySettings {
    MahonySettings {
        kp: c.slot(id::MAHONY_KP),
        ki: c.slot(id::MAHONY_KI),
        rest_bias_tau: c.slot(id::MAHONY_REST_BIAS_TAU),
    }
}

fn complementary_settings(c: &Config) -> ComplementarySettings {
    ComplementarySettings {
        kp: c.slot(id::COMPLEMENTARY_KP),
        ki: c.slot(id::COMPLEMENTARY_KI),
        gyro_rest: c.slot(id::COMPLEMENTARY_GYRO_REST),
        accel_rest: c.slot(id::COMPLEMENTARY_ACCEL_REST),
        init_duration: c.slot(id::COMPLEMENTARY_INIT_DURATION),
        align_heading: c.slot(id::COMPLEMENTARY_ALIGN_HEADING) >= 0.5,
    }
}

fn ekf_settings(c: &Config) -> EkfSettings {
    EkfSettings {
        tau_omega: c.slot(id::EKF_TAU_OMEGA),
        omega_std: c.slot(id::EKF_OMEGA_STD),
        tau_drift: c.slot(id::EKF_TAU_DRIFT),
        drift_std: c.slot(id::EKF_DRIFT_STD),
        gyro_noise: c.slot(id::EKF_GYRO_NOISE),
        accel_noise: c.slot(id::EKF_ACCEL_NOISE),
        accel_motion: c.slot(id::EKF_ACCEL_MOTION),
        heading_std: c.slot(id::EKF_HEADING_STD),
        motion_tau: c.slot(id::EKF_MOTION_TAU),
        heading_tau: c.slot(id::EKF_HEADING_TAU),
        gravity: c.slot(id::GRAVITY),
        rest_rate_std: c.slot(id::EKF_REST_RATE_STD),
        accel_adapt_tau: c.slot(id::EKF_ACCEL_ADAPT_TAU),
        heading_adapt_tau: c.slot(id::EKF_HEADING_ADAPT_TAU),
    }
}

fn gmvdk_settings(c: &Config) -> GmvdkSettings {
    GmvdkSettings {
        slope_alpha: c.slot(id::GMVDK_SLOPE_ALPHA),
        slope_muk: c.slot(id::GMVDK_SLOPE_MUK),
        mu_window: c.slot(id::GMVDK_MU_WINDOW),
        init_duration: c.slot(id::GMVDK_INIT_DURATION),
        activity_tau: c.slot(id::GMVDK_ACTIVITY_TAU),
        gyro_activity: c.slot(id::GMVDK_GYRO_ACTIVITY),
        accel_activity: c.slot(id::GMVDK_ACCEL_ACTIVITY),
        bias_window: c.slot(id::GMVDK_BIAS_WINDOW),
        static_alpha: c.slot(id::GMVDK_STATIC_ALPHA),
        relative_output: c.slot(id::GMVDK_RELATIVE_OUTPUT) >= 0.5,
    }
}

fn robust_settings(c: &Config) -> RobustSettings {
    RobustSettings {
        tau_acc: c.slot(id::ROBUST_TAU_ACC),
        tau_mag: c.slot(id::ROBUST_TAU_MAG),
        rest_gyro: c.slot(id::ROBUST_REST_GYRO),
        rest_accel: c.slot(id::ROBUST_REST_ACCEL),
        rest_time: c.slot(id::ROBUST_REST_TIME),
        rest_tilt: c.slot(id::ROBUST_REST_TILT),
        rest_tau: c.slot(id::ROBUST_REST_TAU),
        bias_tau_rest: c.slot(id::ROBUST_BIAS_TAU_REST),
        bias_tau_motion: c.slot(id::ROBUST_BIAS_TAU_MOTION),
        bias_limit: c.slot(id::ROBUST_BIAS_LIMIT),
        mag_norm_th: c.slot(id::ROBUST_MAG_NORM_TH),
        mag_dip_th: c.slot(id::ROBUST_MAG_DIP_TH),
        hard_iron_time: c.slot(id::ROBUST_HARD_IRON_TIME),
    }
}

/// An orientation filter of any kind, with the common lifecycle:
/// [`Filter::new`], [`Filter::update`], the getters, [`Filter::reset`].
#[derive(Clone, Debug, PartialEq)]
pub struct Filter {
    config: Config,
    core: Core,
    /// Rotation from the native frame to the configured one; `None` when they are equal.
    to_frame: Option<Quat>,
    flags: u32,
    last_accel: Option<Vec3>,
    /// The sample limits of the configuration, kept ready for each update.
    limits: Limits,
    /// issue 20: mounting, heading offset and declination around the outputs (host.rs).
    host: host::Host,
    /// issue 20: sensor models applied before the update (calibration.rs).
    models: calibration::Models,
    /// issue 20: the gyroscope readings of dt = 0 samples waiting for the next step
    /// (sum, count; saturation.rs).
    burst: (Vec3, u32),
}

/// The thresholds the per-sample checks compare with, from the configuration's slots:
/// a range of zero (none set) is `+∞` here, so each test is one comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Limits {
    /// Gyroscope full-scale range, or [`MAX_GYRO`] (rad/s).
    gyro: f64,
    /// Accelerometer full-scale range, or [`MAX_ACCEL`] (m/s²).
    accel: f64,
    /// dt above which a step counts as a gap and integrates over this instead (s).
    gap: f64,
    /// issue 20: readings beyond the ranges are clipped and recovered from.
    recover: bool,
    /// issue 20: dt = 0 is the same instant as the next step.
    same_instant: bool,
}

impl Limits {
    fn of(config: &Config) -> Limits {
        let limit = |id: u32, bound: f64| {
            let v = config.slot(id);
            if v > 0.0 {
                v.min(bound)
            } else {
                bound
            }
        };
        Limits {
            gyro: limit(id::GYRO_RANGE, MAX_GYRO),
            accel: limit(id::ACCEL_RANGE, MAX_ACCEL),
            gap: limit(id::GAP_DT, f64::INFINITY),
            recover: config.slot(id::SATURATION_RECOVERY) != 0.0,
            same_instant: config.slot(id::SAME_INSTANT) != 0.0,
        }
    }
}

impl Filter {
    pub fn new(config: &Config) -> Result<Filter, Error> {
        // Re-check every slot: a Config can only hold valid values, but be strict.
        let config = Config::from_slots(config.kind, config.frame, config.init, &config.params)?;
        if let Init::Given(q) = config.init {
            check_quaternion(q)?;
        }
        let core = Core::new(&config);
        let limits = Limits::of(&config);
        let mut filter = Filter {
            config,
            core,
            to_frame: None,
            flags: 0,
            last_accel: None,
            limits,
            host: host::Host::default(),
            models: Default::default(),
            burst: (Vec3::ZERO, 0),
        };
        filter.to_frame = filter.frame_rotation();
        filter.reset();
        Ok(filter)
    }

    /// Native frame to configured frame; none for a relative output.
    fn frame_rotation(&self) -> Option<Quat> {
        if self.core.relative() {
            None
        } else {
            self.core.native_frame().rotation_to(self.config.frame)
        }
    }

    pub fn kind(&self) -> Kind {
        self.config.kind
    }

    pub fn config(&self) -> &Config {
        &self.config
    }

    /// Back to the state right after [`Filter::new`]; the settings are kept.
    pub fn reset(&mut self) {
        self.core.reset(&self.config);
        self.last_accel = None;
        self.flags = 0;
        match self.config.init {
            // From the first sample, or the core's own start-up period.
            Init::AccMag => {}
            Init::Identity => self.set_frame_quaternion(Quat::IDENTITY),
            Init::Given(q) => self.set_frame_quaternion(q.normalized()),
        }
    }

    /// Changes a parameter while running; the orientation is kept.
    pub fn set_param(&mut self, id: u32, value: f64) -> Result<(), Error> {
        self.config.set_param(id, value)?;
        self.core.configure(&self.config);
        self.to_frame = self.frame_rotation();
        self.limits = Limits::of(&self.config);
        Ok(())
    }

    pub fn param(&self, id: u32) -> Result<f64, Error> {
        self.config.param(id)
    }

    /// Sets the orientation (in the configured frame; normalised). The filter counts as
    /// initialised afterwards.
    pub fn set_quaternion(&mut self, q: Quat) -> Result<(), Error> {
        check_quaternion(q)?;
        // issue 20: `q` is the output's (segment's) orientation.
        self.set_frame_quaternion(self.host.sensor_for(q.normalized()));
        Ok(())
    }

    fn set_frame_quaternion(&mut self, q: Quat) {
        let native = match self.to_frame {
            Some(c) => c.conj() * q,
            None => q,
        };
        self.core.set_quaternion(native);
        self.flags |= flags::INITIALIZED;
    }

    /// Checks a sample against every rule without touching the state.
    #[inline]
    pub fn check(&self, s: &Sample) -> Result<(), Error> {
        self.check_view(s)
    }

    /// [`Filter::check`] for any [`SampleView`]: the quick test on the sample where it
    /// lies, the exact rules (on a copy) only when it fails.
    #[inline(always)]
    fn check_view<S: SampleView>(&self, s: &S) -> Result<(), Error> {
        if self.plainly_valid(s) {
            Ok(())
        } else {
            self.check_exactly(&s.to_sample())
        }
    }

    /// A conservative test that `check_exactly` would accept the sample, with one branch:
    /// every component of the readings is under the sensor's range or physical bound
    /// (`|x| < limit` is false for NaN and ±∞);
    /// the accelerometer's and magnetometer's squared norms lie in [MIN_POSITIVE, MAX]
    /// (not zero, no overflow, finite components); dt is in range; and a sample without
    /// an accelerometer reading comes after initialisation. A sample it turns down goes
    /// through the exact rules, which tell the reason (or accept it: a zero gyroscope
    /// reading's components, say, or a finite vector whose squared norm overflows).
    ///
    /// About 85 instructions, against about 114 for the previous form (callgrind, per
    /// source line, McGinnis IMU), which cost Mahony 3.5 / 7.5 ns (IMU / MARG) and
    /// McGinnis 4-5 ns an update, measured against no check at all.
    #[inline(always)]
    fn plainly_valid<S: SampleView>(&self, s: &S) -> bool {
        let under = |v: Vec3, limit: f64| (v.x.abs() < limit) & (v.y.abs() < limit) & (v.z.abs() < limit);
        let usable = |v: Vec3| (f64::MIN_POSITIVE..=f64::MAX).contains(&v.norm_squared());
        let gyro = match s.gyro() {
            Some(g) => under(g, self.limits.gyro),
            None => false,
        };
        let accel = match s.accel() {
            Some(a) => under(a, self.limits.accel) & usable(a),
            None => self.flags & flags::INITIALIZED != 0,
        };
        let mag = match s.mag() {
            Some(m) => under(m, MAX_MAG) & usable(m),
            None => true,
        };
        (s.dt() >= MIN_DT) & (s.dt() <= MAX_DT) & gyro & accel & mag
    }

    /// The rules one by one, in the order that picks the reported error.
    #[cold]
    #[inline(never)]
    fn check_exactly(&self, s: &Sample) -> Result<(), Error> {
        // No sensor samples faster than 1 GHz: a smaller dt (a subnormal one, say) is a
        // host bug, and would overflow noise variances that scale with 1/dt.
        if !(s.dt.is_finite() && (MIN_DT..=MAX_DT).contains(&s.dt)) {
            return Err(Error::InvalidDt(s.dt));
        }
        let gyro = s.gyro.ok_or(Error::MissingSensor(Field::Gyro))?;
        if !gyro.is_finite() {
            return Err(Error::NonFinite(Field::Gyro));
        }
        let gyro_range = self.config.slot(id::GYRO_RANGE);
        if gyro_range > 0.0 && gyro.max_abs() >= gyro_range {
            return Err(Error::Saturated(Field::Gyro));
        }
        if gyro.max_abs() >= MAX_GYRO {
            return Err(Error::TooLarge(Field::Gyro));
        }
        if let Some(a) = s.accel {
            check_vector(a, Field::Accel)?;
            let accel_range = self.config.slot(id::ACCEL_RANGE);
            if accel_range > 0.0 && a.max_abs() >= accel_range {
                return Err(Error::Saturated(Field::Accel));
            }
            if a.max_abs() >= MAX_ACCEL {
                return Err(Error::TooLarge(Field::Accel));
            }
        }
        if let Some(m) = s.mag {
            check_vector(m, Field::Mag)?;
            if m.max_abs() >= MAX_MAG {
                return Err(Error::TooLarge(Field::Mag));
            }
        }
        if self.flags & flags::INITIALIZED == 0 && s.accel.is_none() {
            return Err(Error::NotInitialized);
        }
        Ok(())
    }

    /// One step. On error nothing changes: the state is bit-identical to before.
    pub fn update(&mut self, s: &Sample) -> Result<(), Error> {
        self.update_inline(s)
    }

    /// [`Filter::update`] for any [`SampleView`], inlined into its caller: the C calls
    /// pass the host's struct and the update reads it in place, where converting it to
    /// a [`Sample`] first cost 10-20 ns an update (the copy, read back at once, stalls
    /// on store-to-load forwarding).
    #[inline(always)]
    pub(crate) fn update_inline<S: SampleView>(&mut self, s: &S) -> Result<(), Error> {
        if self.limits.same_instant && (s.dt() == 0.0 || self.burst.1 != 0) {
            return self.update_same_instant(s); // issue 20: bursts
        }
        if self.limits.recover && self.saturated(s) {
            return self.update_saturated(s); // issue 20: clipped, then recovered from
        }
        if self.models.any() {
            return self.update_calibrated(s); // issue 20: sensor models first
        }
        self.check_view(s)?;
        // check() guarantees a gyro reading.
        let gyro = s.gyro().unwrap_or_default();
        let gap = s.dt() > self.limits.gap;
        let pending = self.flags & flags::REACQUIRE_PENDING;
        if self.flags & flags::INITIALIZED != 0 && (gap || pending != 0) {
            match s.accel() {
                Some(accel) => return self.reacquire(s.dt(), gyro, accel, s.mag(), gap),
                None if gap => {
                    // Nothing to re-acquire from: hold the orientation until a sample
                    // with an accelerometer reading.
                    self.flags = flags::INITIALIZED | flags::GAP | flags::REACQUIRE_PENDING;
                    return Ok(());
                }
                // Gyroscope only while pending: integrate as usual, still pending.
                None => {}
            }
        }
        let initial = if self.flags & flags::INITIALIZED == 0 && !self.core.own_startup() {
            // check() guarantees an accelerometer reading here.
            let accel = s.accel().unwrap_or_default();
            let frame = self.config.frame;
            let q = frame
                .attitude_from(accel, s.mag())
                .or_else(|| frame.attitude_from(accel, None))
                .ok_or(Error::Numeric)?;
            Some(q)
        } else {
            None
        };
        // The core's update is transactional; only an initialisation needs undoing.
        let saved = initial.map(|q| {
            let saved = (self.core.clone(), self.flags);
            self.set_frame_quaternion(q);
            saved
        });
        // Only a start-up period (an own start-up, or the initialising sample) meets a
        // gap here. An own start-up's still period is broken by it: it starts over with
        // this sample, counted as gap_dt.
        if gap && initial.is_none() && self.flags & flags::INITIALIZED == 0 {
            self.core.reset(&self.config);
        }
        let dt = if gap { self.limits.gap } else { s.dt() };
        // Recorded before the core's update and put back if it fails: stored after the
        // core's own state, these 32 bytes cost Mahony's IMU update 17 ns (54 -> 37 ns,
        // measured; the time goes with the store's position, not its size).
        let prev_accel = self.last_accel;
        if s.accel().is_some() {
            self.last_accel = s.accel();
        }
        match self.core.update(dt, gyro, s.accel(), s.mag()) {
            Some(step) => {
                self.flags = if step.initializing {
                    0
                } else {
                    flags::INITIALIZED
                        | if step.used_accel { flags::ACCEL_USED } else { 0 }
                        | if step.used_mag { flags::MAG_USED } else { 0 }
                        | if gap { flags::GAP } else { 0 }
                        | pending
                };
                Ok(())
            }
            None => {
                self.last_accel = prev_accel;
                if let Some((core, flags)) = saved {
                    self.core = core;
                    self.flags = flags;
                }
                Err(Error::Numeric)
            }
        }
    }

    /// Re-acquisition after a gap (see [`flags::REACQUIRED`]): inclination from this
    /// accelerometer reading; heading from the magnetometer when the sample has one that
    /// defines north (and the kind accepts it), else the heading held before the gap.
    #[cold]
    #[inline(never)]
    fn reacquire(
        &mut self,
        dt: f64,
        gyro: Vec3,
        accel: Vec3,
        mag: Option<Vec3>,
        gap: bool,
    ) -> Result<(), Error> {
        let native = self.core.native_frame();
        let tilt = native.attitude_from(accel, None).ok_or(Error::Numeric)?;
        // The rotation about the vertical that brings the tilt nearest to the old
        // orientation: that orientation's heading on the new inclination.
        let before = self.core.absolute_quaternion();
        let keep = (twist_about(before * tilt.conj(), native.up()) * tilt).normalized();
        let with_mag = mag.and_then(|m| native.attitude_from(accel, Some(m)));
        let r = Reacquisition { keep, with_mag, dt, gyro, accel, mag };
        let used_mag = self.core.reacquire(&r);
        self.last_accel = Some(accel);
        self.flags = flags::INITIALIZED
            | flags::ACCEL_USED
            | flags::REACQUIRED
            | if used_mag { flags::MAG_USED } else { 0 }
            | if gap { flags::GAP } else { 0 };
        Ok(())
    }

    /// Updates `N` distinct filters, `filters[i]` with `samples[i]`, in order: the result
    /// is exactly that of calling [`Filter::update`] on each (same bits, same errors),
    /// stopping at the first error, whose index is returned with it. When all are
    /// Madgwick filters past initialisation with the same sensors present, their steps run
    /// side by side in lanes (see the Madgwick module), which overlaps their work.
    pub fn update_group<const N: usize>(
        filters: &mut [&mut Filter; N],
        samples: [&Sample; N],
    ) -> Result<(), (usize, Error)> {
        let lanes = (
            <&mut [&mut Filter; LANES]>::try_from(&mut filters[..]),
            <[&Sample; LANES]>::try_from(&samples[..]),
        );
        if let (Ok(fs), Ok(ss)) = lanes {
            if let Some(result) = Filter::try_lanes(fs, ss) {
                return result;
            }
        }
        for (i, (f, s)) in filters.iter_mut().zip(samples).enumerate() {
            f.update(s).map_err(|e| (i, e))?;
        }
        Ok(())
    }

    /// The lane path of [`Filter::update_group`]; `None` when it does not apply (nothing
    /// changed then).
    fn try_lanes(
        filters: &mut [&mut Filter; LANES],
        samples: [&Sample; LANES],
    ) -> Option<Result<(), (usize, Error)>> {
        let with_mag = samples[0].mag.is_some();
        for (f, s) in filters.iter().zip(samples) {
            let eligible = matches!(f.core, Core::Madgwick(_))
                // issue 20: models, clipping and bursts take the single path.
                && !f.models.any()
                && !f.limits.recover
                && !f.limits.same_instant
                && f.flags & (flags::INITIALIZED | flags::REACQUIRE_PENDING) == flags::INITIALIZED
                && s.dt <= f.limits.gap
                && s.accel.is_some()
                && s.mag.is_some() == with_mag;
            if !eligible {
                return None;
            }
        }
        // A rejected sample: the filters before it are updated (one by one, which gives
        // the same bits), and its index is reported.
        for (i, s) in samples.iter().enumerate() {
            if let Err(e) = filters[i].check(s) {
                for j in 0..i {
                    if let Err(e) = filters[j].update(samples[j]) {
                        return Some(Err((j, e)));
                    }
                }
                return Some(Err((i, e)));
            }
        }
        // Gaps were sent down the single path above.
        let dt = samples.map(|s| s.dt);
        // check() guarantees the readings are present.
        let gyro = samples.map(|s| s.gyro.unwrap_or_default());
        let accel = samples.map(|s| s.accel.unwrap_or_default());
        let mag = with_mag.then(|| samples.map(|s| s.mag.unwrap_or_default()));
        let step = {
            let mut cores = filters.each_mut().map(|f| match &mut f.core {
                Core::Madgwick(m) => Some(m),
                _ => None,
            });
            if cores.iter().any(Option::is_none) {
                return None;
            }
            let mut cores = cores.each_mut().map(|c| c.take().expect("checked above"));
            Madgwick::update_lanes(&mut cores, dt, gyro, accel, mag)?
        };
        for i in 0..LANES {
            let f = &mut filters[i];
            f.flags = flags::INITIALIZED
                | if step.used_accel { flags::ACCEL_USED } else { 0 }
                | if step.used_mag { flags::MAG_USED } else { 0 };
            f.last_accel = samples[i].accel;
        }
        Some(Ok(()))
    }

    /// Internal states for display: bias, trust values, rest flag, covariance (see
    /// [`Diagnostics`]; fields that do not apply are absent and NaN).
    pub fn diagnostics(&self) -> Diagnostics {
        self.core.diagnostics()
    }

    /// The configuration and state fields of a snapshot, in order (see [`state`]).
    fn codec(&mut self, c: &mut dyn Codec) {
        let mut head = ConfigFields::of(&self.config);
        head.codec(c);
        c.u32(&mut self.flags);
        c.opt_vec3(&mut self.last_accel);
        // issue 20 (format version 3): the host's frames.
        c.quat(&mut self.host.mounting);
        c.f64(&mut self.host.heading);
        c.f64(&mut self.host.declination);
        calibration::codec(&mut self.models, c);
        c.vec3(&mut self.burst.0);
        let mut n = self.burst.1 as u64;
        c.u64(&mut n);
        self.burst.1 = n as u32;
        self.core.codec(c);
    }

    fn kind_byte(&self) -> u8 {
        Kind::ALL.iter().position(|k| *k == self.kind()).unwrap_or(0) as u8 + 1
    }

    fn payload_len(&self) -> usize {
        let mut counter = Writer { buf: None, pos: 0 };
        self.clone().codec(&mut counter);
        counter.pos
    }

    /// Size in bytes of [`Filter::save`]'s blob for this filter (constant per kind).
    pub fn state_size(&self) -> usize {
        state::HEADER + self.payload_len() + state::TRAILER
    }

    /// Writes a snapshot of the configuration and state into `out`; returns its length.
    /// Loading it into a filter of the same kind continues bit for bit as this one would.
    pub fn save(&self, out: &mut [u8]) -> Result<usize, StateError> {
        let len = self.payload_len();
        let mut copy = self.clone();
        state::seal(out, self.kind_byte(), len, |w| copy.codec(w))
    }

    /// Restores a snapshot from [`Filter::save`]. On error nothing changes: the blob
    /// must be whole, unmodified (checksum), of this format version and of this kind.
    pub fn load(&mut self, blob: &[u8]) -> Result<(), StateError> {
        let payload = state::open(blob, self.kind_byte(), self.payload_len())?;
        let mut r = Reader { buf: payload, pos: 0, ok: true };
        let mut head = ConfigFields::of(&self.config);
        head.codec(&mut r);
        let config = head.config(self.kind()).filter(|_| r.ok).ok_or(StateError::Corrupt)?;
        let mut fresh = Filter::new(&config).map_err(|_| StateError::Corrupt)?;
        r.u32(&mut fresh.flags);
        r.opt_vec3(&mut fresh.last_accel);
        r.quat(&mut fresh.host.mounting);
        r.f64(&mut fresh.host.heading);
        r.f64(&mut fresh.host.declination);
        calibration::codec(&mut fresh.models, &mut r);
        r.vec3(&mut fresh.burst.0);
        let mut n = 0u64;
        r.u64(&mut n);
        let burst_ok =
            n <= u32::MAX as u64 && fresh.burst.0.is_finite() && (n > 0 || fresh.burst.0 == Vec3::ZERO);
        fresh.burst.1 = n as u32;
        fresh.host.refresh(fresh.config.frame.up().z);
        fresh.core.codec(&mut r);
        // Slots this kind does not use are zero in every snapshot it writes: a blob of
        // another kind relabelled (with a fresh checksum) has its own kind's slots set.
        let kind = self.kind();
        let foreign =
            head.params.iter().enumerate().any(|(i, v)| *v != 0.0 && kind.param(i as u32).is_none());
        let accel_ok = fresh.last_accel.map_or(true, holds::accel);
        if !r.ok
            || r.pos != payload.len()
            || foreign
            || fresh.flags & !flags::ALL != 0
            || !accel_ok
            || !fresh.host.valid()
            || !fresh.models.valid()
            || !burst_ok
            || !fresh.core.valid()
        {
            return Err(StateError::Corrupt);
        }
        *self = fresh;
        Ok(())
    }

    /// True once the filter has an orientation.
    pub fn is_initialized(&self) -> bool {
        self.flags & flags::INITIALIZED != 0
    }

    /// [`flags`] bits.
    pub fn flags(&self) -> u32 {
        self.flags
    }

    /// The orientation in the configured frame (identity before initialisation): the
    /// segment's when a mounting is set, with the heading offset and declination applied
    /// (see `host.rs`).
    pub fn quaternion(&self) -> Quat {
        self.host.output(self.frame_quaternion()) // issue 20
    }

    /// The sensor's orientation as the core estimates it, in the configured frame.
    fn frame_quaternion(&self) -> Quat {
        if !self.is_initialized() {
            return Quat::IDENTITY;
        }
        let q = self.core.quaternion();
        match self.to_frame {
            Some(c) => c * q,
            None => q,
        }
    }

    /// Euler angles (Z-Y'-X'': yaw, pitch, roll) of [`Filter::quaternion`], radians.
    pub fn euler(&self) -> Euler {
        self.quaternion().to_euler()
    }

    /// Rotation matrix (row-major, body to earth) of [`Filter::quaternion`].
    pub fn rotation_matrix(&self) -> [[f64; 3]; 3] {
        self.quaternion().to_matrix()
    }

    /// What the accelerometer reads at rest in the current orientation: gravity's
    /// reaction (pointing up) in the sensor frame, m/s², magnitude `gravity`.
    pub fn gravity(&self) -> Vec3 {
        let up = self.frame_quaternion().rotate_inverse(self.config.frame.up()); // issue 20
        up * self.config.slot(id::GRAVITY)
    }

    /// The last accelerometer reading minus [`Filter::gravity`], in the sensor frame;
    /// `None` before the first accelerometer reading.
    pub fn linear_accel(&self) -> Option<Vec3> {
        self.last_accel.map(|a| a - self.gravity())
    }

    /// [`Filter::linear_accel`] rotated into the earth frame.
    pub fn linear_accel_earth(&self) -> Option<Vec3> {
        self.linear_accel().map(|a| self.host.earth(self.frame_quaternion().rotate(a)))
        // issue 20
    }
}

/// The configuration as it travels in a snapshot.
struct ConfigFields {
    frame: u32,
    init: u32,
    initial: Quat,
    params: [f64; MAX_PARAMS],
}

impl ConfigFields {
    fn of(c: &Config) -> ConfigFields {
        let (init, initial) = match c.init {
            Init::AccMag => (0, Quat::IDENTITY),
            Init::Identity => (1, Quat::IDENTITY),
            Init::Given(q) => (2, q),
        };
        let frame = Frame::ALL.iter().position(|f| *f == c.frame).unwrap_or(0) as u32;
        ConfigFields { frame, init, initial, params: c.params }
    }

    fn codec(&mut self, c: &mut dyn Codec) {
        c.u32(&mut self.frame);
        c.u32(&mut self.init);
        c.quat(&mut self.initial);
        for p in self.params.iter_mut() {
            c.f64(p);
        }
    }

    /// The configuration, if every field is valid for `kind`.
    fn config(&self, kind: Kind) -> Option<Config> {
        let frame = *Frame::ALL.get(self.frame as usize)?;
        let init = match self.init {
            0 => Init::AccMag,
            1 => Init::Identity,
            2 => Init::Given(self.initial),
            _ => return None,
        };
        Config::from_slots(kind, frame, init, &self.params).ok()
    }
}

/// What a decoded snapshot may hold (see [`Filter::load`]): the checks each kind's
/// `valid` is built from. The codec already refuses NaN and infinities.
pub(crate) mod holds {
    use super::{MAX_ACCEL, MAX_GYRO, MAX_MAG};
    use crate::math::{Quat, Vec3};

    /// A unit quaternion, as every update leaves one (normalised to rounding).
    pub fn unit(q: Quat) -> bool {
        (q.norm_squared() - 1.0).abs() <= 1e-9
    }

    /// Estimates follow the readings, and a blend of bounded readings and predictions
    /// may overshoot them a little: a decoded estimate must stay within ten times the
    /// readings' physical bound (a forged 1e300 is refused).
    const MARGIN: f64 = 10.0;

    /// A rate: a bias or a rate estimate.
    pub fn rate(v: Vec3) -> bool {
        v.max_abs() < MARGIN * MAX_GYRO
    }

    /// An accelerometer-like value (a low-pass of readings, a reference).
    pub fn accel(v: Vec3) -> bool {
        v.max_abs() < MARGIN * MAX_ACCEL
    }

    /// A magnetometer-like value.
    pub fn mag(v: Vec3) -> bool {
        v.max_abs() < MARGIN * MAX_MAG
    }

    /// A mean of magnetometer norms: no more than a reading's largest norm, √3 · bound.
    pub fn mag_norm(x: f64) -> bool {
        (0.0..=3f64.sqrt() * MAX_MAG).contains(&x)
    }

    /// A squared deviation between magnetometer-like values.
    pub fn mag_spread(x: f64) -> bool {
        (0.0..(2.0 * MARGIN * MAX_MAG).powi(2)).contains(&x)
    }

    /// A value in `[lo, hi]`.
    pub fn within(x: f64, lo: f64, hi: f64) -> bool {
        (lo..=hi).contains(&x)
    }
}

fn check_vector(v: Vec3, field: Field) -> Result<(), Error> {
    if !v.is_finite() {
        return Err(Error::NonFinite(field));
    }
    let n2 = v.norm_squared();
    if !n2.is_finite() {
        return Err(Error::TooLarge(field));
    }
    if n2 < f64::MIN_POSITIVE {
        return Err(Error::ZeroVector(field));
    }
    Ok(())
}

fn check_quaternion(q: Quat) -> Result<(), Error> {
    if !q.is_finite() {
        return Err(Error::NonFinite(Field::Quaternion));
    }
    let n2 = q.norm_squared();
    if !n2.is_finite() {
        return Err(Error::TooLarge(Field::Quaternion));
    }
    if n2 < f64::MIN_POSITIVE {
        return Err(Error::ZeroVector(Field::Quaternion));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    /// Deterministic test motion for filter `k` at step `i`.
    fn rig_sample(k: usize, i: usize, mag: bool) -> Sample {
        let t = i as f64 * 0.01 + k as f64;
        Sample {
            dt: 0.01 + 0.001 * (k as f64),
            gyro: Some(Vec3::new(0.5 * t.sin(), 0.3 * (1.3 * t).cos(), 0.2 + 0.1 * k as f64)),
            accel: Some(Vec3::new(0.3 * t.cos(), 0.2 * t.sin() + 0.1, 9.8)),
            mag: mag.then(|| Vec3::new(20.0 + t.sin(), 3.0 * k as f64, -40.0)),
        }
    }

    /// The EKF and GMVDK updates run in the AVX copy where the CPU has it
    /// (crate::isa; 256-bit lanes in the EKF). Forced onto the baseline code, the same
    /// steps must give the same bits, step by step, in every kind's whole state. (On a
    /// CPU without AVX, or off x86-64, both are the same code.)
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn the_wide_encoding_gives_the_baseline_bits() {
        for kind in Kind::ALL {
            for mag in [false, true] {
                let config = Config::new(kind).unwrap();
                let (mut wide, mut base) = (Filter::new(&config).unwrap(), Filter::new(&config).unwrap());
                let (mut a, mut b) = (vec![0; wide.state_size()], vec![0; base.state_size()]);
                for i in 0..3000 {
                    let mut s = rig_sample(1, i, mag);
                    if i % 7 == 3 {
                        s.accel = None; // a gyro-only step
                    }
                    if i % 500 == 250 {
                        s.dt = 5.0; // a gap
                    }
                    let baseline = crate::isa::baseline(|| base.update(&s));
                    assert_eq!(wide.update(&s), baseline, "{kind:?} step {i}");
                    wide.save(&mut a).unwrap();
                    base.save(&mut b).unwrap();
                    assert!(a == b, "{kind:?} (mag {mag}): the states differ after step {i}");
                }
            }
        }
    }

    /// Readings beyond the physical bounds, which could overflow a step, are refused by the
    /// checks, before any arithmetic, and change nothing; readings just inside them give a
    /// finite unit quaternion. (They once reached the cores: GMVDK answered Ok with a zero
    /// quaternion, and the EKF was left refusing every later sample.)
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn readings_beyond_the_physical_bounds_are_refused_before_any_arithmetic() {
        for kind in Kind::ALL {
            let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
            // Long enough for the start-up periods' patience with a sensor in motion.
            for i in 0..1500 {
                f.update(&rig_sample(0, i, true)).unwrap();
            }
            assert!(f.is_initialized(), "{kind:?}");
            let base = rig_sample(0, 1500, true);
            let cases = [
                (
                    Sample { gyro: Some(Vec3::new(1e300, -1e300, 1e300)), ..base },
                    Error::TooLarge(Field::Gyro),
                ),
                (Sample { gyro: Some(Vec3::new(0.0, -MAX_GYRO, 0.0)), ..base }, Error::TooLarge(Field::Gyro)),
                (
                    Sample { gyro: Some(Vec3::new(0.0, 1e156, -2.25)), accel: None, mag: None, dt: 0.0011 },
                    Error::TooLarge(Field::Gyro),
                ),
                (
                    Sample { accel: Some(Vec3::new(MAX_ACCEL, 0.0, 1.0)), ..base },
                    Error::TooLarge(Field::Accel),
                ),
                (Sample { mag: Some(Vec3::new(1.0, -MAX_MAG, 1.0)), ..base }, Error::TooLarge(Field::Mag)),
                (Sample { dt: 2.0 * MAX_DT, ..base }, Error::InvalidDt(2.0 * MAX_DT)),
            ];
            for (s, want) in cases {
                let before = f.clone();
                assert_eq!(f.update(&s), Err(want), "{kind:?} {s:?}");
                assert_eq!(f, before, "{kind:?}");
            }
            let inside = MAX_GYRO * 0.999_999;
            for s in [
                Sample { gyro: Some(Vec3::new(inside, -inside, inside)), ..base },
                Sample { gyro: Some(Vec3::new(0.0, -inside, -2.25)), accel: None, mag: None, dt: 0.2 },
                Sample { accel: Some(Vec3::new(MAX_ACCEL * 0.999, 0.0, 1.0)), ..base },
            ] {
                f.update(&s).unwrap_or_else(|e| panic!("{kind:?} {s:?}: {e}"));
                let q = f.quaternion();
                assert!(q.is_finite() && (q.norm() - 1.0).abs() < 1e-9, "{kind:?}: {q:?}");
            }
        }
    }

    /// The cores' own rule, shared by every kind: an update that returns `None` has
    /// changed nothing (each computes into locals and commits at the end; the Filter
    /// restores nothing but an initialisation). Driven past the Filter's checks with
    /// values that overflow, fresh and warmed. (The complementary filter once kept the
    /// g₀ of a step it refused.)
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_core_update_that_fails_changes_nothing() {
        let mut failures = 0;
        for kind in Kind::ALL {
            for warm in [0, 300] {
                let config = Config::new(kind).unwrap();
                let mut core = Core::new(&config);
                core.set_quaternion(Quat::IDENTITY);
                for i in 0..warm {
                    let s = rig_sample(0, i, true);
                    core.update(s.dt, s.gyro.unwrap(), s.accel, s.mag);
                }
                let still = Vec3::new(0.0, 0.0, 9.81);
                let field = Some(Vec3::new(0.0, 20.0, -40.0));
                let cases = [
                    (1e300, Vec3::ZERO, Some(still), field),
                    (f64::MAX, Vec3::ZERO, Some(still), None),
                    (0.01, Vec3::new(1e300, -1e300, 1e300), Some(still), field),
                    (0.01, Vec3::new(0.0, f64::MAX, 0.0), None, None),
                    (1e300, Vec3::new(3.0, 0.0, 0.0), None, None),
                    (0.01, Vec3::ZERO, Some(Vec3::new(1e300, 1e300, 0.0)), field),
                    // McGinnis at rest, tilted: the bias step (10) overflows.
                    (1e300, Vec3::ZERO, Some(Vec3::new(1.0, 0.0, 9.75)), None),
                ];
                for (dt, gyro, accel, mag) in cases {
                    let before = core.clone();
                    if core.update(dt, gyro, accel, mag).is_none() {
                        failures += 1;
                        assert_eq!(core, before, "{kind:?} (warm {warm}) dt {dt} {gyro:?} {accel:?}");
                    }
                    core = before;
                }
            }
        }
        // Not vacuous: these inputs do make cores fail.
        assert!(failures >= 6, "{failures}");
    }

    /// set_param keeps the estimate; GMVDK's relative_output changes what the output is
    /// relative to (the header says so), and switching back gives the same bits.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn set_param_keeps_the_estimate_and_relative_output_changes_the_reference() {
        let mut f = Filter::new(&Config::new(Kind::Gmvdk).unwrap()).unwrap();
        for i in 0..400 {
            let s = Sample { gyro: Some(Vec3::ZERO), ..rig_sample(0, 0, true) };
            let s = if i < 150 { s } else { rig_sample(0, i, true) };
            f.update(&s).unwrap();
        }
        assert!(f.is_initialized());
        let absolute = f.quaternion();
        f.set_param(id::GMVDK_RELATIVE_OUTPUT, 1.0).unwrap();
        let relative = f.quaternion();
        let Core::Gmvdk(g) = &f.core else { unreachable!() };
        assert!(relative.angle_to(g.start_pose().conj() * absolute) < 1e-12);
        assert!(relative.angle_to(absolute) > 1e-3, "the start-up pose is not the earth frame here");
        f.set_param(id::GMVDK_RELATIVE_OUTPUT, 0.0).unwrap();
        assert_eq!(f.quaternion(), absolute);
        // Any other setting keeps the output as it was.
        f.set_param(id::GMVDK_SLOPE_ALPHA, 0.5).unwrap();
        f.set_param(id::GAP_DT, 2.0).unwrap();
        assert_eq!(f.quaternion(), absolute);
    }

    #[test]
    fn the_quick_check_accepts_only_what_the_exact_rules_accept() {
        let values = [
            0.0,
            -0.0,
            1e-200,
            -1e-170,
            f64::MIN_POSITIVE,
            5e-324,
            1e-9,
            0.01,
            -3.0,
            9.81,
            1e154,
            -1e160,
            1e300,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let pick = |i: usize| values[i % values.len()];
        let vector = |i: usize| match i % 7 {
            0 => None,
            _ => Some(Vec3::new(pick(i), pick(i / 3 + 1), pick(i / 5 + 2))),
        };
        // Fewer under Miri, where each sample costs a thousand times more.
        let n = if cfg!(miri) { 4_000 } else { 20_000 };
        let mut accepted = 0;
        for (range, initialised) in [(0.0, false), (0.0, true), (20.0, true), (1e4, true)] {
            let mut f = Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap();
            f.set_param(id::GYRO_RANGE, range).unwrap();
            f.set_param(id::ACCEL_RANGE, 0.5 * range).unwrap();
            if initialised {
                f.set_quaternion(Quat::IDENTITY).unwrap();
            }
            for i in 0..n {
                let s = Sample {
                    dt: pick(i / 11),
                    gyro: vector(i),
                    accel: vector(i / 2 + 3),
                    mag: vector(i / 4 + 5),
                };
                let quick = f.plainly_valid(&s);
                assert!(!quick || f.check_exactly(&s).is_ok(), "{s:?}");
                accepted += quick as usize;
            }
        }
        // Not a vacuous check: ordinary samples take the quick path, with or without
        // sensor ranges set.
        assert!(accepted > n / 200, "{accepted}");
        let mut f = Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap();
        assert!(f.plainly_valid(&rig_sample(0, 0, true)));
        f.set_param(id::GYRO_RANGE, 35.0).unwrap();
        f.set_param(id::ACCEL_RANGE, 160.0).unwrap();
        assert!(f.plainly_valid(&rig_sample(0, 0, true)));
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn a_group_update_is_bit_identical_to_single_updates() {
        for mag in [false, true] {
            let config = Config::new(Kind::Madgwick).unwrap();
            let mut group: Vec<Filter> = (0..4).map(|_| Filter::new(&config).unwrap()).collect();
            let mut single = group.clone();
            for i in 0..500 {
                let samples: Vec<Sample> = (0..4).map(|k| rig_sample(k, i, mag)).collect();
                {
                    let [a, b, c, d] = &mut group[..] else { unreachable!() };
                    let refs = [&samples[0], &samples[1], &samples[2], &samples[3]];
                    if i == 0 {
                        // Initialisation takes the scalar path.
                        Filter::update_group(&mut [a, b, c, d], refs).unwrap();
                    } else {
                        // Afterwards the lanes must take every step.
                        assert_eq!(Filter::try_lanes(&mut [a, b, c, d], refs), Some(Ok(())), "step {i}");
                    }
                }
                for (f, s) in single.iter_mut().zip(&samples) {
                    f.update(s).unwrap();
                }
                for (g, s) in group.iter().zip(&single) {
                    let (a, b) = (g.quaternion(), s.quaternion());
                    assert!(
                        a.w.to_bits() == b.w.to_bits()
                            && a.x.to_bits() == b.x.to_bits()
                            && a.y.to_bits() == b.y.to_bits()
                            && a.z.to_bits() == b.z.to_bits()
                            && g.flags() == s.flags(),
                        "mag {mag} step {i}: {a:?} vs {b:?}"
                    );
                }
            }
            assert_eq!(group, single);
        }
    }

    #[test]
    fn a_group_stops_at_a_bad_sample_like_single_updates() {
        let config = Config::new(Kind::Madgwick).unwrap();
        let mut group: Vec<Filter> = (0..4).map(|_| Filter::new(&config).unwrap()).collect();
        let mut single = group.clone();
        let mut samples: Vec<Sample> = (0..4).map(|k| rig_sample(k, 0, true)).collect();
        for (f, s) in group.iter_mut().zip(&samples) {
            f.update(s).unwrap();
        }
        for (f, s) in single.iter_mut().zip(&samples) {
            f.update(s).unwrap();
        }
        samples[2].mag = Some(Vec3::new(f64::NAN, 0.0, 0.0));
        let result = {
            let [a, b, c, d] = &mut group[..] else { unreachable!() };
            Filter::update_group(&mut [a, b, c, d], [&samples[0], &samples[1], &samples[2], &samples[3]])
        };
        assert_eq!(result, Err((2, Error::NonFinite(Field::Mag))));
        single[0].update(&samples[0]).unwrap();
        single[1].update(&samples[1]).unwrap();
        assert_eq!(group, single);
        // A gap (dt above gap_dt) takes the same path as alone, flag included.
        samples[2] = rig_sample(2, 1, true);
        samples[1].dt = 5.0;
        {
            let [a, b, c, d] = &mut group[..] else { unreachable!() };
            Filter::update_group(&mut [a, b, c, d], [&samples[0], &samples[1], &samples[2], &samples[3]])
                .unwrap();
        }
        for (f, s) in single.iter_mut().zip(&samples) {
            f.update(s).unwrap();
        }
        assert_eq!(group, single);
        assert!(group[1].flags() & flags::GAP != 0);
    }

    use super::*;

    fn madgwick() -> Filter {
        Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap()
    }

    fn good() -> Sample {
        Sample {
            dt: 0.01,
            gyro: Some(Vec3::new(0.1, -0.2, 0.3)),
            accel: Some(Vec3::new(0.5, 0.2, 9.7)),
            mag: Some(Vec3::new(10.0, 20.0, -40.0)),
        }
    }

    #[test]
    fn every_kind_is_built_and_has_documented_parameters() {
        for k in Kind::ALL {
            assert!(Config::new(k).is_ok());
            for p in k.params() {
                assert!(p.accepts(p.default), "{k:?} {}", p.name);
                assert!(p.doc.contains("default") || p.doc.contains("Default"), "{k:?} {}", p.name);
                assert_eq!(k.param_by_name(p.name).map(|q| q.id), Some(p.id), "duplicate name {}", p.name);
            }
        }
    }

    #[test]
    fn defaults_come_from_the_tables() {
        let c = Config::new(Kind::Madgwick).unwrap();
        assert_eq!(c.param(id::MADGWICK_BETA_IMU), Ok(0.041));
        assert_eq!(c.param(id::MADGWICK_BETA_MARG), Ok(0.041));
        assert_eq!(c.param(id::GRAVITY), Ok(9.80665));
        assert_eq!(c.param(40), Err(Error::UnknownParam(40)));
    }

    #[test]
    fn bad_samples_leave_the_state_bit_identical() {
        let mut f = madgwick();
        f.update(&good()).unwrap();
        f.set_param(id::GYRO_RANGE, 30.0).unwrap();
        f.set_param(id::ACCEL_RANGE, 150.0).unwrap();
        let before = f.clone();
        let nan = f64::NAN;
        let cases: Vec<(Sample, Error)> = vec![
            (Sample { dt: 0.0, ..good() }, Error::InvalidDt(0.0)),
            (Sample { dt: -0.01, ..good() }, Error::InvalidDt(-0.01)),
            (Sample { gyro: None, ..good() }, Error::MissingSensor(Field::Gyro)),
            (Sample { gyro: Some(Vec3::new(nan, 0.0, 0.0)), ..good() }, Error::NonFinite(Field::Gyro)),
            (Sample { gyro: Some(Vec3::new(0.0, 31.0, 0.0)), ..good() }, Error::Saturated(Field::Gyro)),
            (Sample { accel: Some(Vec3::ZERO), ..good() }, Error::ZeroVector(Field::Accel)),
            (Sample { accel: Some(Vec3::new(0.0, 0.0, -150.0)), ..good() }, Error::Saturated(Field::Accel)),
            (
                Sample { accel: Some(Vec3::new(f64::INFINITY, 0.0, 1.0)), ..good() },
                Error::NonFinite(Field::Accel),
            ),
            (Sample { mag: Some(Vec3::ZERO), ..good() }, Error::ZeroVector(Field::Mag)),
            (Sample { mag: Some(Vec3::new(1e200, 1e200, 0.0)), ..good() }, Error::TooLarge(Field::Mag)),
        ];
        for (s, e) in cases {
            let got = f.update(&s).unwrap_err();
            match (got, e) {
                (Error::InvalidDt(a), Error::InvalidDt(b)) => assert_eq!(a.to_bits(), b.to_bits()),
                _ => assert_eq!(got, e),
            }
            assert_eq!(f, before, "{s:?}");
        }
        let nan_dt = f.update(&Sample { dt: nan, ..good() });
        assert!(matches!(nan_dt, Err(Error::InvalidDt(_))));
        assert_eq!(f, before);
    }

    #[test]
    fn acc_mag_init_waits_for_an_accelerometer() {
        let mut f = madgwick();
        assert!(!f.is_initialized());
        let gyro_only = Sample { accel: None, mag: None, ..good() };
        assert_eq!(f.update(&gyro_only), Err(Error::NotInitialized));
        f.update(&good()).unwrap();
        assert!(f.is_initialized());
        // Right after init the reported gravity points along the measured accelerometer.
        let g = f.gravity().normalized();
        assert!((g - good().accel.unwrap().normalized()).norm() < 0.01);
        f.update(&gyro_only).unwrap();
        assert_eq!(f.flags() & flags::ACCEL_USED, 0);
    }

    #[test]
    fn frames_differ_by_their_constant_rotation() {
        // Start away from the measurements: at a perfectly consistent estimate the
        // gradient is rounding noise and (30) steps in its arbitrary direction, which
        // would make the runs differ by β·dt for reasons unrelated to frames.
        let q0 = Quat::from_axis_angle(Vec3::new(0.3, -0.2, 1.0), 0.8);
        let run = |frame: Frame| {
            let mut c = Config::new(Kind::Madgwick).unwrap();
            c.frame = frame;
            c.init = Init::Given(Frame::Enu.rotation_to(frame).map_or(q0, |r| r * q0));
            let mut f = Filter::new(&c).unwrap();
            for i in 0..200 {
                let t = i as f64 * 0.01;
                f.update(&Sample { dt: 0.01, gyro: Some(Vec3::new(0.3 * t.sin(), 0.2, -0.1)), ..good() })
                    .unwrap();
            }
            f.quaternion()
        };
        let enu = run(Frame::Enu);
        for frame in [Frame::Ned, Frame::Nwu] {
            let q = run(frame);
            let c = Frame::Enu.rotation_to(frame).unwrap();
            assert!(q.angle_to(c * enu) < 1e-12, "{frame:?} {}", q.angle_to(c * enu));
        }
    }

    #[test]
    fn reset_returns_to_the_fresh_state_and_keeps_settings() {
        let mut f = madgwick();
        f.set_param(id::MADGWICK_BETA_IMU, 0.2).unwrap();
        f.update(&good()).unwrap();
        f.reset();
        let mut fresh = Filter::new(f.config()).unwrap();
        fresh.set_param(id::MADGWICK_BETA_IMU, 0.2).unwrap();
        assert_eq!(f, fresh);
        assert!(!f.is_initialized());
    }

    #[test]
    fn linear_accel_is_zero_for_a_pure_gravity_reading() {
        let mut c = Config::new(Kind::Madgwick).unwrap();
        c.init = Init::Given(Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.4));
        let f = Filter::new(&c).unwrap();
        let mut g = f.clone();
        let reading = f.gravity();
        assert!((reading.norm() - 9.80665).abs() < 1e-12);
        g.update(&Sample { dt: 1e-9, gyro: Some(Vec3::ZERO), accel: Some(reading), mag: None }).unwrap();
        assert!(g.linear_accel().unwrap().norm() < 1e-6);
        assert!(f.linear_accel().is_none());
    }
}
