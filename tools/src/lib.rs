//! orient's tools, kept out of the shipped library: reading recordings (CSV) and scoring
//! estimates with BROAD's rule ([`eval`]), and the bench's bare filter arithmetic
//! ([`floor`]), used by the binaries in `src/bin` (replay,
//! broad_table, bench, make_golden, precision_cost) and by the accuracy tests.
//!
//! This crate depends on `orient`; `orient` never depends on it, so the C library
//! (liborient.so / .a) contains no CSV or file code.

pub mod eval;
pub mod floor;
