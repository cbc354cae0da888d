//! The kinds: one module per paper (its `settings!` parameter table, its state and its
//! update in the paper's terms, and its `Estimator` implementation), and the parts two or
//! more of them share: rest detection and the still start-up period.

pub mod complementary;
pub mod ekf;
pub mod gmvdk;
pub mod madgwick;
pub mod mahony;
pub(crate) mod rest;
pub mod robust;
pub(crate) mod startup;
