//! orient's tools, kept out of the shipped library: reading recordings (CSV) and scoring
//! estimates with BROAD's rule ([`eval`]), the bench's bare filter arithmetic
//! ([`floor`]) and the clock every timing uses ([`clock`]: thread CPU time), used by the binaries in `src/bin` (replay,
//! broad_table, bench, make_golden, precision_cost, simulate_rig, rig_baseline) and by the
//! accuracy tests; rig recordings ([`rig`], RIG-FORMAT.md) and their simulator ([`rigsim`]).
//!
//! This crate depends on `orient`; `orient` never depends on it, so the C library
//! (liborient.so / .a) contains no CSV or file code.

pub mod clock;
pub mod eval;
pub mod floor;
pub mod joints;
pub mod json;
pub mod rig;
pub mod rigsim;
