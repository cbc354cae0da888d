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
pub mod kinds;
pub mod params;
pub(crate) mod pipeline;
pub mod state;

mod config;
mod diagnostics;
mod error;
pub mod flags;
mod kind;

// The public paths of the kinds and of what every kind shares.
pub use config::{Config, Init};
pub use diagnostics::{diag, Diagnostics, Uncertainty};
pub use error::{Error, Field};
pub use kind::Kind;
pub use kinds::{complementary, ekf, gmvdk, madgwick, mahony, robust};
pub use pipeline::estimator::Step;
pub use pipeline::filter::Filter;
pub use pipeline::host::RigHeading;
pub use pipeline::sample::{Sample, MAX_ACCEL, MAX_DT, MAX_GYRO, MAX_MAG, MIN_DT};

#[cfg(test)]
mod tests;
