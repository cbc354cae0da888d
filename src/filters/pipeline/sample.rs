//! Samples, the physical bounds on them, and the checks of vectors and quaternions.

use crate::filters::error::Error;
use crate::filters::error::Field;
use crate::math::frame::NO_HEADING_SINE;
use crate::math::{Quat, Vec3};

/// One sensor sample. Units: gyro rad/s, accel m/s², mag any unit (consistent over a
/// run); `dt` in seconds since the previous sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    pub dt: f64,
    pub gyro: Option<Vec3>,
    pub accel: Option<Vec3>,
    pub mag: Option<Vec3>,
}

/// A reading the usual update's quick check passed, with its squared norm, which the
/// check found in `(1e-300, 1e300)` ([`crate::math::inv_sqrt`]'s fast range).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Checked {
    pub v: Vec3,
    n2: f64,
}

impl Checked {
    #[inline(always)]
    pub(crate) fn of(v: Vec3) -> Checked {
        Checked { v, n2: v.norm_squared() }
    }

    /// The squared norm is in `(1e-300, bound)`, `bound ≤ 1e300`.
    #[inline(always)]
    pub(crate) fn within(&self, bound: f64) -> bool {
        self.n2 > 1e-300 && self.n2 < bound
    }

    /// `|v|²`, as the check computed it.
    #[inline(always)]
    pub(crate) fn norm_squared(self) -> f64 {
        self.n2
    }

    /// `|v|`: the bits of [`Vec3::norm`].
    #[inline(always)]
    pub(crate) fn norm(self) -> f64 {
        self.n2.sqrt()
    }

    /// `v / |v|`: the bits of [`Vec3::normalized`], without its range test (the check
    /// made it).
    #[inline(always)]
    pub(crate) fn unit(self) -> Vec3 {
        self.v * crate::math::inv_sqrt_in_range(self.n2)
    }

    /// The unit vectors of an accelerometer reading `a` and a magnetometer reading `m`,
    /// when the field surely gives a heading by `no_heading`'s rule: `cos² ∠(a, m) < 1 −
    /// 2 sin²`, twice the rule's sin² leaving room for rounding. `None` when it may not:
    /// a usual step then declines, and the general step applies the rule exactly. On the
    /// unit vectors the kinds compute anyway, inside their step: tested in the quick
    /// check, the rule cost the usual MARG update 20 to 24 instructions (callgrind).
    #[inline(always)]
    pub(crate) fn heading_units(a: Checked, m: Checked) -> Option<(Vec3, Vec3)> {
        let (a, m) = (a.unit(), m.unit());
        let c = a.dot(m);
        (c * c < 1.0 - 2.0 * NO_HEADING_SINE * NO_HEADING_SINE).then_some((a, m))
    }
}

/// A sample the usual update's quick check passed (see `Runner::usual`): a gyroscope
/// reading, and the other readings [`Checked`]. Its field may still be one that gives no
/// heading (`math::frame::no_heading`): a step applies that rule.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Usual {
    pub dt: f64,
    pub gyro: Vec3,
    pub accel: Option<Checked>,
    pub mag: Option<Checked>,
}

impl Usual {
    /// No field, no accelerometer reading, or a field that surely gives a heading by
    /// `no_heading`'s rule, from the squared norms the check computed (Lagrange's
    /// identity, |a × m|² = |a|²|m|² − (a·m)², gives (a·m)² < (1 − 2 sin²) |a|²|m|²:
    /// twice the rule's sin² leaves room for rounding, and a product of squared norms
    /// that underflows fails).
    #[inline(always)]
    pub(crate) fn surely_gives_heading(&self) -> bool {
        match (self.accel, self.mag) {
            (Some(a), Some(m)) => {
                let p = a.norm_squared() * m.norm_squared();
                let am = a.v.dot(m.v);
                am * am < (1.0 - 2.0 * NO_HEADING_SINE * NO_HEADING_SINE) * p && p > 1e-290
            }
            _ => true,
        }
    }
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

pub(crate) fn check_vector(v: Vec3, field: Field) -> Result<(), Error> {
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

/// A gyroscope reading's checks, as every update makes them after the configured range:
/// NonFinite for a NaN or infinite component, TooLarge for one at or beyond
/// [`MAX_GYRO`]. Zero is a reading (a still sensor).
pub(crate) fn check_gyro(g: Vec3) -> Result<(), Error> {
    if !g.is_finite() {
        return Err(Error::NonFinite(Field::Gyro));
    }
    if g.max_abs() >= MAX_GYRO {
        return Err(Error::TooLarge(Field::Gyro));
    }
    Ok(())
}

/// A magnetometer reading's checks, as every update makes them: [`check_vector`]
/// (NonFinite, TooLarge for a norm that overflows, ZeroVector for a zero or subnormal
/// norm), then TooLarge for a component at or beyond [`MAX_MAG`].
pub(crate) fn check_mag(m: Vec3) -> Result<(), Error> {
    check_vector(m, Field::Mag)?;
    if m.max_abs() >= MAX_MAG {
        return Err(Error::TooLarge(Field::Mag));
    }
    Ok(())
}

pub(crate) fn check_quaternion(q: Quat) -> Result<(), Error> {
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
