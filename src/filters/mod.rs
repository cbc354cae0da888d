//! The filters, and [`Filter`]: one lifecycle and one set of outputs for every kind.
//!
//! Everything here is safe Rust with no FFI types; `update` does not allocate.
//!
//! Layout: each kind is one module (its `settings!` parameter table, its state and its
//! update in the paper's terms) implementing `estimator::Estimator`; `runner` is the
//! common lifecycle generic over the kind; [`Filter`] holds one runner of any kind.
//! [`Kind`], [`Config`], [`Sample`], [`Error`], [`flags`],
//! [`Diagnostics`](crate::filters::Diagnostics) and the snapshot format
//! ([`state`](crate::filters::state), `holds`) are what every kind shares.

#![forbid(unsafe_code)]

pub mod calibration;
pub mod complementary;
pub mod ekf;
pub mod gmvdk;
pub mod madgwick;
pub mod mahony;
pub mod params;
mod rest;
pub mod robust;
mod startup;
pub mod state;

mod config;
mod diagnostics;
mod error;
pub(crate) mod estimator;
mod filter;
pub mod flags;
pub(crate) mod holds;
mod host;
mod kind;
pub(crate) mod runner;
mod sample;
mod saturation;
mod watch;

pub use config::{Config, Init};
pub use diagnostics::{diag, Diagnostics, Uncertainty};
pub use error::{Error, Field};
pub(crate) use estimator::twist_about;
pub(crate) use estimator::Reacquisition;
pub use estimator::Step;
pub use filter::Filter;
pub(crate) use filter::LANES_PAY;
pub use host::RigHeading;
pub use kind::Kind;
pub(crate) use sample::{check_quaternion, SampleView};
pub use sample::{Sample, MAX_ACCEL, MAX_DT, MAX_GYRO, MAX_MAG, MIN_DT};

#[cfg(test)]
mod tests;
