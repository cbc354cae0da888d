//! # orient
//!
//! IMU/MARG orientation filters with one lifecycle for every kind, usable from Rust and,
//! through a C ABI (`include/orient.h`), from C, C++ and C#.
//!
//! Conventions: earth frame ENU by default (NED and NWU selectable); right-handed sensor
//! frame; Hamilton quaternions, scalar first, body to earth (`v_earth = q v_body q*`);
//! gyroscope rad/s, accelerometer m/s², magnetometer any consistent unit; `f64`; `dt` in
//! seconds with every sample.
//!
//! ```
//! use orient::{Config, Filter, Kind, Sample, Vec3};
//! let mut filter = Filter::new(&Config::new(Kind::Madgwick)?)?;
//! filter.update(&Sample {
//!     dt: 0.01,
//!     gyro: Some(Vec3::new(0.0, 0.0, 0.1)),
//!     accel: Some(Vec3::new(0.0, 0.0, 9.81)),
//!     mag: Some(Vec3::new(0.0, 20.0, -40.0)),
//! })?;
//! let q = filter.quaternion();
//! assert!((q.norm() - 1.0).abs() < 1e-12);
//! # Ok::<(), orient::Error>(())
//! ```

/// cbindgen:ignore
pub mod filters;
mod isa;
/// cbindgen:ignore
pub mod joints;
/// cbindgen:ignore
pub mod math;
/// cbindgen:ignore
pub mod offline;

pub mod ffi;

pub use filters::calibration::{MagCalibrator, MagFit, Model, Sensor};
pub use filters::params::{ParamSpec, MAX_PARAMS};
pub use filters::{flags, Config, Error, Field, Filter, Init, Kind, RigHeading, Sample, Uncertainty};
pub use math::{Euler, Frame, Quat, Vec3};
