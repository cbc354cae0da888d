//! The pipeline and lifecycle every kind shares.

pub(crate) mod estimator;
pub(crate) mod filter;
pub(crate) mod host;
pub(crate) mod runner;
pub(crate) mod sample;
pub(crate) mod watch;
