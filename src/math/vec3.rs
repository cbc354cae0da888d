use core::ops::{Add, Mul, Neg, Sub};

/// A 3-vector of `f64`, passed by value.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl Vec3 {
    pub const ZERO: Vec3 = Vec3::new(0.0, 0.0, 0.0);

    #[inline]
    pub const fn new(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3 { x, y, z }
    }

    #[inline]
    pub fn dot(self, o: Vec3) -> f64 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline]
    pub fn cross(self, o: Vec3) -> Vec3 {
        Vec3::new(self.y * o.z - self.z * o.y, self.z * o.x - self.x * o.z, self.x * o.y - self.y * o.x)
    }

    #[inline]
    pub fn norm_squared(self) -> f64 {
        self.dot(self)
    }

    #[inline]
    pub fn norm(self) -> f64 {
        self.norm_squared().sqrt()
    }

    /// The vector divided by its norm. The caller makes sure the norm is not zero.
    #[inline]
    pub fn normalized(self) -> Vec3 {
        self * super::inv_sqrt(self.norm_squared())
    }

    /// [`Vec3::normalized`] for a vector whose squared norm the caller knows to lie in
    /// [`super::inv_sqrt`]'s fast range, (1e-300, 1e300): the same bits, without the range
    /// test. (A NaN or infinite squared norm gives NaN components, for the caller's
    /// finiteness test.)
    #[inline(always)]
    pub(crate) fn normalized_in_range(self) -> Vec3 {
        let n2 = self.norm_squared();
        debug_assert!(!(n2 <= 1e-300 || n2 >= 1e300) || !n2.is_finite(), "|v|² = {n2}");
        self * super::inv_sqrt_in_range(n2)
    }

    /// True when all three components are finite (not NaN, not ±Inf); tested as
    /// [`crate::math::Quat::is_finite`] is.
    #[inline]
    pub fn is_finite(self) -> bool {
        (self.x * 0.0 + self.y * 0.0) + self.z * 0.0 == 0.0
    }

    /// The largest absolute component.
    #[inline]
    pub fn max_abs(self) -> f64 {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    #[inline]
    fn add(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    #[inline]
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    #[inline]
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<f64> for Vec3 {
    type Output = Vec3;
    #[inline]
    fn mul(self, s: f64) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}
