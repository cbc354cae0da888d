//! The filters, and [`Filter`]: one lifecycle and one set of outputs for every kind.
//!
//! Everything here is safe Rust with no FFI types; `update` does not allocate.
//!
//! Where each stage lives, in the order a sample meets them:
//! - `pipeline` (crate-private): the lifecycle every kind shares. `filter` holds one
//!   `runner` of any kind and dispatches to it. `runner` holds the lifecycle's state
//!   (settings, flags, snapshots, outputs); its `update` module is the update, stage by
//!   stage in one file: same-instant bursts, clipping, the sensor models (from
//!   [`calibration`](crate::filters::calibration)), the checks, the start, gaps and
//!   re-acquisition, the kind's step. `sample` is the sample and its checked form;
//!   `host` the host's frames (mounting, heading offset, declination); `watch` the rest
//!   watch; `estimator` the trait a kind implements.
//! - [`kinds`](crate::filters::kinds): one module per paper, in the paper's symbols and equation numbers, and
//!   what two or more kinds share (rest detection, the still start-up period).
//! - [`state`](crate::filters::state): the snapshot codec and the bounds a loaded state must hold.
//! - [`calibration`](crate::filters::calibration): sensor models and the host-side estimators (magnetometer
//!   calibrator, gyroscope offset).
//! - At the top, what every part shares: [`Kind`], [`Config`] and its [`params`](crate::filters::params) table,
//!   [`Sample`], [`Error`], [`flags`](crate::filters::flags) and [`Diagnostics`](crate::filters::Diagnostics).

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
