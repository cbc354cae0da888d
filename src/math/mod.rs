//! Vectors, quaternions and earth frames.
//!
//! Conventions used everywhere in orient:
//! - quaternions are Hamilton (`i*j = k`), scalar first, fields named `w, x, y, z`;
//! - an orientation `q` rotates body (sensor) coordinates into earth coordinates:
//!   `v_earth = q ⊗ [0, v_body] ⊗ q*`, which is `v_earth = R(q) · v_body`;
//! - transcendental functions come from the `libm` crate so that results are
//!   bit-identical on every platform (std's `sqrt` is exact everywhere and is kept).

mod frame;
mod quat;
mod vec3;

pub use frame::Frame;
pub use quat::{Euler, Quat};
pub use vec3::Vec3;
