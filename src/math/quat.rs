use super::Vec3;
use core::ops::{Add, Mul, Sub};

/// A Hamilton quaternion, scalar first.
///
/// As an orientation it maps body coordinates to earth coordinates:
/// `v_earth = q ⊗ [0, v_body] ⊗ q*`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quat {
    pub w: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// Euler angles of the intrinsic Z-Y'-X'' sequence (yaw, then pitch, then roll), in radians:
/// `R(q) = Rz(yaw) · Ry(pitch) · Rx(roll)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Euler {
    /// Rotation about the earth z axis, in (-π, π].
    pub yaw: f64,
    /// Rotation about the once-rotated y axis, in [-π/2, π/2].
    pub pitch: f64,
    /// Rotation about the body x axis, in (-π, π].
    pub roll: f64,
}

impl Default for Quat {
    fn default() -> Quat {
        Quat::IDENTITY
    }
}

impl Quat {
    pub const IDENTITY: Quat = Quat::new(1.0, 0.0, 0.0, 0.0);

    #[inline]
    pub const fn new(w: f64, x: f64, y: f64, z: f64) -> Quat {
        Quat { w, x, y, z }
    }

    /// The pure quaternion `[0, v]`.
    #[inline]
    pub const fn pure(v: Vec3) -> Quat {
        Quat::new(0.0, v.x, v.y, v.z)
    }

    /// The vector part `(x, y, z)`.
    #[inline]
    pub fn vector(self) -> Vec3 {
        Vec3::new(self.x, self.y, self.z)
    }

    #[inline]
    pub fn conj(self) -> Quat {
        Quat::new(self.w, -self.x, -self.y, -self.z)
    }

    #[inline]
    pub fn dot(self, o: Quat) -> f64 {
        (self.w * o.w + self.x * o.x) + (self.y * o.y + self.z * o.z)
    }

    #[inline]
    pub fn norm_squared(self) -> f64 {
        self.dot(self)
    }

    #[inline]
    pub fn norm(self) -> f64 {
        self.norm_squared().sqrt()
    }

    #[inline]
    pub fn scale(self, s: f64) -> Quat {
        Quat::new(self.w * s, self.x * s, self.y * s, self.z * s)
    }

    /// The quaternion divided by its norm. The caller makes sure the norm is not zero.
    #[inline(always)]
    pub fn normalized(self) -> Quat {
        self.scale(super::inv_sqrt(self.norm_squared()))
    }

    /// [`Quat::normalized`] for a quaternion whose squared norm the caller knows to lie in
    /// [`super::inv_sqrt`]'s fast range, (1e-300, 1e300): a product of unit quaternions,
    /// say. The same bits, without the range test. (A NaN or infinite squared norm gives
    /// NaN components, for the caller's finiteness test.)
    #[inline(always)]
    pub(crate) fn normalized_in_range(self) -> Quat {
        let n2 = self.norm_squared();
        debug_assert!(!(n2 <= 1e-300 || n2 >= 1e300) || !n2.is_finite(), "|q|² = {n2}");
        self.scale(super::inv_sqrt_in_range(n2))
    }

    /// The quaternion divided by its norm, or `None` when the norm is zero, overflows or
    /// the result is not finite (the check every filter's update makes before it commits).
    #[inline]
    pub fn try_normalized(self) -> Option<Quat> {
        self.normalized_with(self.norm_squared())
    }

    /// [`Quat::try_normalized`] for a quaternion known to be unit up to rounding (a
    /// product of unit quaternions, say): when `|q|² = 1 + ε` with `|ε| < 1e-8`, one
    /// Newton step for `1/√(1 + ε)`, `q (3 − |q|²)/2`, whose error `3ε²/8` is below
    /// half an ulp, so the result is as unit as the division would make it without a
    /// root or a division on the update's chain; otherwise `try_normalized`.
    #[inline]
    pub fn renormalized(self) -> Option<Quat> {
        match self.renormalized_usual() {
            Some(q) => Some(q),
            None => self.normalized_with(self.norm_squared()),
        }
    }

    /// [`Quat::try_normalized`] in [`super::inv_sqrt`]'s fast range: the same result
    /// there, and `None` outside it (where `try_normalized` may still have one). For an
    /// update's usual path, which calls no function and leaves the rest to its general path.
    #[inline(always)]
    pub(crate) fn try_normalized_usual(self) -> Option<Quat> {
        Some(self.scale(super::inv_sqrt_fast(self.norm_squared())?)).filter(|q| q.is_finite())
    }

    /// [`Quat::renormalized`]'s usual case, `|q|² = 1 + ε` with `|ε| < 1e-8`: its Newton
    /// step there, `None` otherwise. For an update's usual path, which calls no function
    /// and leaves the rest to its general path.
    #[inline(always)]
    pub(crate) fn renormalized_usual(self) -> Option<Quat> {
        let n2 = self.norm_squared();
        ((n2 - 1.0).abs() < 1e-8).then(|| self.scale(0.5 * (3.0 - n2)))
    }

    /// [`Quat::try_normalized`] with the squared norm `n2` computed by the caller, for an
    /// update that knows it before the quaternion's last components are ready.
    ///
    /// The usual case, `n2` in [`super::inv_sqrt`]'s fast range, is tested first with two
    /// comparisons; a zero, non-finite or extreme `n2` goes out of line
    /// (`math::try_inv_sqrt`).
    #[inline]
    pub fn normalized_with(self, n2: f64) -> Option<Quat> {
        Some(self.scale(super::try_inv_sqrt(n2)?)).filter(|q| q.is_finite())
    }

    /// No NaN or infinite component. Tested as `Σ c · 0 == 0`, which is `±0` for finite
    /// components and NaN otherwise: four multiplications, three additions and one
    /// comparison on the floating-point side, against four integer masks and compares.
    #[inline]
    pub fn is_finite(self) -> bool {
        (self.w * 0.0 + self.x * 0.0) + (self.y * 0.0 + self.z * 0.0) == 0.0
    }

    /// `q ⊗ [0, v] ⊗ q*` for a unit quaternion: body to earth when `q` is an orientation.
    ///
    /// Computed as `v + w t + u × t` with `u` the vector part and `t = 2 u × v` (the same
    /// rotation for unit `q`): 18 multiplications instead of two Hamilton products' 28,
    /// and a dependency chain of five operations instead of eight, which matters because
    /// every filter's update is one chain from the old estimate to the new.
    #[inline]
    pub fn rotate(self, v: Vec3) -> Vec3 {
        let u = self.vector();
        let t = u.cross(v) * 2.0;
        v + t * self.w + u.cross(t)
    }

    /// `q* ⊗ [0, v] ⊗ q` for a unit quaternion: earth to body when `q` is an orientation.
    #[inline]
    pub fn rotate_inverse(self, v: Vec3) -> Vec3 {
        self.conj().rotate(v)
    }

    /// `rotate_inverse((0, 0, 1))`, the earth's z axis in the sensor frame (the third row
    /// of `R(q)`), from the direct formula: the generic rotation would multiply by the
    /// zero components, which IEEE arithmetic may not fold away.
    #[inline]
    pub fn z_axis_in_body(self) -> Vec3 {
        let Quat { w, x, y, z } = self;
        Vec3::new(2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z)
    }

    /// The rows of `R(q)` for a unit `q`, in the homogeneous form (`w² + x² − y² − z²` on
    /// the diagonal): `rotate(v)` is `(r0·v, r1·v, r2·v)` and `rotate_inverse(v)` is
    /// `v_x r0 + v_y r1 + v_z r2`. The third row is [`Quat::z_axis_in_body`]'s value,
    /// bit for bit.
    #[inline]
    pub fn rows(self) -> [Vec3; 3] {
        let Quat { w, x, y, z } = self;
        [
            Vec3::new(w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)),
            Vec3::new(2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x)),
            self.z_axis_in_body(),
        ]
    }

    /// The rotation matrix `R(q)` (row-major) with `v_earth = R · v_body`, for a unit `q`.
    pub fn to_matrix(self) -> [[f64; 3]; 3] {
        let Quat { w, x, y, z } = self;
        [
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
            [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
            [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
        ]
    }

    /// The unit quaternion of a proper rotation matrix (row-major), by Shepperd's method:
    /// the largest of the four diagonal combinations is taken under the square root, so
    /// the result is accurate for every rotation. Uses only `sqrt`. The sign is chosen
    /// so that `w >= 0`.
    pub fn from_matrix(m: [[f64; 3]; 3]) -> Quat {
        let trace = m[0][0] + m[1][1] + m[2][2];
        let q = if trace >= m[0][0] && trace >= m[1][1] && trace >= m[2][2] {
            let s = 2.0 * (1.0 + trace).sqrt();
            Quat::new(0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s)
        } else if m[0][0] >= m[1][1] && m[0][0] >= m[2][2] {
            let s = 2.0 * (1.0 + m[0][0] - m[1][1] - m[2][2]).sqrt();
            Quat::new((m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s)
        } else if m[1][1] >= m[2][2] {
            let s = 2.0 * (1.0 + m[1][1] - m[0][0] - m[2][2]).sqrt();
            Quat::new((m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s)
        } else {
            let s = 2.0 * (1.0 + m[2][2] - m[0][0] - m[1][1]).sqrt();
            Quat::new((m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s)
        };
        let q = q.normalized();
        if q.w < 0.0 {
            q.scale(-1.0)
        } else {
            q
        }
    }

    /// The rotation about `axis` (need not be unit, must not be zero) by `angle` radians.
    pub fn from_axis_angle(axis: Vec3, angle: f64) -> Quat {
        let a = axis.normalized();
        let (s, c) = (libm::sin(0.5 * angle), libm::cos(0.5 * angle));
        Quat::new(c, a.x * s, a.y * s, a.z * s)
    }

    /// The shortest rotation that takes the direction `from` onto the direction `to`
    /// (neither needs to be unit; neither may be zero). For opposite directions the
    /// rotation is half a turn about an axis perpendicular to `from`.
    #[inline(always)]
    pub fn from_two_vectors(from: Vec3, to: Vec3) -> Quat {
        let (f, t) = (from.normalized(), to.normalized());
        let c = f.dot(t);
        if c < -1.0 + 1e-12 {
            // Any axis perpendicular to `f` will do: take the one nearest to a
            // coordinate axis that `f` is least aligned with.
            let helper = if f.x.abs() <= f.y.abs() && f.x.abs() <= f.z.abs() {
                Vec3::new(1.0, 0.0, 0.0)
            } else if f.y.abs() <= f.z.abs() {
                Vec3::new(0.0, 1.0, 0.0)
            } else {
                Vec3::new(0.0, 0.0, 1.0)
            };
            // |f × helper|² ≥ 2/3: no range test.
            let axis = f.cross(helper).normalized_in_range();
            return Quat::new(0.0, axis.x, axis.y, axis.z);
        }
        let axis = f.cross(t);
        // |[1 + c, f × t]|² = 2 (1 + c) > 2e-12 for unit f and t: no range test.
        Quat::new(1.0 + c, axis.x, axis.y, axis.z).normalized_in_range()
    }

    /// The angle in radians of the rotation `self ⊗ other*`, in [0, π]. Computed from the
    /// vector part with `atan2`, so it stays accurate for tiny angles (where `acos` of the
    /// scalar part loses half the digits).
    pub fn angle_to(self, other: Quat) -> f64 {
        let e = self * other.conj();
        2.0 * libm::atan2(e.vector().norm(), e.w.abs())
    }

    /// Euler angles (Z-Y'-X'') of a unit quaternion: yaw and roll in (-π, π], pitch in
    /// [-π/2, π/2]; the angles rebuild the rotation, `Rz(yaw) Ry(pitch) Rx(roll) = R(q)`,
    /// at every pitch.
    ///
    /// With the half angles `ψ/2`, `θ/2`, `φ/2` of `q = qz(ψ) ⊗ qy(θ) ⊗ qx(φ)`, the sums
    /// `w + y`, `z − x` are `√2 cos(θ/2 − π/4) (cos, sin)((ψ − φ)/2)` and `w − y`,
    /// `z + x` are `√2 cos(θ/2 + π/4) (cos, sin)((ψ + φ)/2)`. So `θ = 2 atan2(|(w + y,
    /// z − x)|, |(w − y, z + x)|) − π/2` and the half sum and half difference of yaw and
    /// roll are two `atan2`s, each of a pair whose length is known: no `asin` (which
    /// loses half the digits near ±90°, where its argument is within rounding of ±1) and
    /// no angle from two rounded near-zero matrix entries. At gimbal lock, θ = ±90°, only
    /// `ψ − φ` (at +90°) or `ψ + φ` (at −90°) is defined: the convention is roll = 0 and
    /// yaw carries the whole rotation about the vertical. A pair counts as zero when its
    /// length is below `LOCK` = 1e-15 of the other's, where the rotation it stands for
    /// changes the quaternion by less than rounding does. (Bernardes and Viollet, "Quaternion
    /// to Euler angles conversion: a direct, general and computationally efficient
    /// method", PLoS ONE 17(11), 2022, derive the same sums for every sequence.)
    pub fn to_euler(self) -> Euler {
        use core::f64::consts::{FRAC_PI_2, PI};
        const LOCK: f64 = 1e-15;
        let Quat { w, x, y, z } = self;
        let (a, b) = (w + y, z - x); // √2 cos(θ/2 − π/4) (cos, sin)((ψ − φ)/2)
        let (c, d) = (w - y, z + x); // √2 cos(θ/2 + π/4) (cos, sin)((ψ + φ)/2)
        let (m, n) = (libm::hypot(a, b), libm::hypot(c, d));
        // sin θ = (m² − n²)/2 (|q| = 1): its asin is accurate, relative to θ, away from
        // ±90°, and the atan2 near them.
        let sin_pitch = 2.0 * (w * y - z * x);
        let pitch = if sin_pitch.abs() < 0.5 {
            libm::asin(sin_pitch)
        } else {
            (2.0 * libm::atan2(m, n) - FRAC_PI_2).clamp(-FRAC_PI_2, FRAC_PI_2)
        };
        let half_difference = libm::atan2(b, a);
        let half_sum = libm::atan2(d, c);
        let (yaw, roll) = if n <= LOCK * m {
            // θ = +90°: only ψ − φ is defined.
            (2.0 * half_difference, 0.0)
        } else if m <= LOCK * n {
            // θ = −90°: only ψ + φ is defined.
            (2.0 * half_sum, 0.0)
        } else {
            (half_sum + half_difference, half_sum - half_difference)
        };
        // Each sum lies in [−2π, 2π]: one turn at most brings it into (−π, π].
        let wrap = |v: f64| {
            let r = if v > PI {
                v - 2.0 * PI
            } else if v <= -PI {
                v + 2.0 * PI
            } else {
                v
            };
            // A result that rounds onto −π is the same angle as π.
            if r <= -PI {
                PI
            } else {
                r
            }
        };
        Euler { yaw: wrap(yaw), pitch, roll: wrap(roll) }
    }
}

impl Mul for Quat {
    type Output = Quat;
    /// The Hamilton product `self ⊗ o`, each component summed as two pairs (three
    /// levels of operations instead of four).
    #[inline]
    fn mul(self, o: Quat) -> Quat {
        Quat::new(
            (self.w * o.w - self.x * o.x) - (self.y * o.y + self.z * o.z),
            (self.w * o.x + self.x * o.w) + (self.y * o.z - self.z * o.y),
            (self.w * o.y - self.x * o.z) + (self.y * o.w + self.z * o.x),
            (self.w * o.z + self.x * o.y) - (self.y * o.x - self.z * o.w),
        )
    }
}

impl Quat {
    /// `self ⊗ [0, v]`: the Hamilton product with a pure quaternion, without the terms
    /// of its zero scalar. Each component is summed as in [`Mul`] with those terms
    /// dropped; adding `w · 0` changes nothing but the sign of an exact zero, so the
    /// bits equal `self * Quat::pure(v)` but for that sign.
    #[inline]
    pub fn mul_pure(self, v: Vec3) -> Quat {
        Quat::new(
            -(self.x * v.x) - (self.y * v.y + self.z * v.z),
            self.w * v.x + (self.y * v.z - self.z * v.y),
            (self.w * v.y - self.x * v.z) + self.z * v.x,
            (self.w * v.z + self.x * v.y) - self.y * v.x,
        )
    }

    /// `self + self.mul_pure(v).scale(h)` with the scalar part's negation taken into its
    /// subtraction (`−a − b = −(a + b)` and `w + (−s) h = w − s h`): one negation fewer
    /// (docs/PERFORMANCE.md has what it saves). The same bits, but for the
    /// sign of a zero scalar part (`w = −0` and an exactly cancelling `x v_x + (y v_y +
    /// z v_z)`, where this gives −0 and the readable form +0).
    #[inline(always)]
    pub fn plus_mul_pure_scaled(self, v: Vec3, h: f64) -> Quat {
        let p = self;
        Quat::new(
            p.w - (p.x * v.x + (p.y * v.y + p.z * v.z)) * h,
            p.x + (p.w * v.x + (p.y * v.z - p.z * v.y)) * h,
            p.y + ((p.w * v.y - p.x * v.z) + p.z * v.x) * h,
            p.z + ((p.w * v.z + p.x * v.y) - p.y * v.x) * h,
        )
    }
}

impl Sub for Quat {
    type Output = Quat;
    #[inline]
    fn sub(self, o: Quat) -> Quat {
        Quat::new(self.w - o.w, self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Add for Quat {
    type Output = Quat;
    #[inline]
    fn add(self, o: Quat) -> Quat {
        Quat::new(self.w + o.w, self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn is_finite_is_false_for_any_nan_or_infinite_component_only() {
        let bad = [f64::NAN, -f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
        let good = [0.0, -0.0, 1.0, -f64::MAX, f64::MAX, f64::MIN_POSITIVE, 5e-324, -3e-310];
        for i in 0..4 {
            for &v in &good {
                let mut c = [0.5; 4];
                c[i] = v;
                assert!(Quat::new(c[0], c[1], c[2], c[3]).is_finite(), "{i} {v}");
                if i < 3 {
                    assert!(Vec3::new(c[0], c[1], c[2]).is_finite(), "{i} {v}");
                }
            }
            for &v in &bad {
                let mut c = [f64::MAX; 4];
                c[i] = v;
                assert!(!Quat::new(c[0], c[1], c[2], c[3]).is_finite(), "{i} {v}");
                if i < 3 {
                    assert!(!Vec3::new(c[0], c[1], c[2]).is_finite(), "{i} {v}");
                }
            }
        }
    }

    #[test]
    fn normalized_with_uses_the_plain_root_outside_the_fast_range() {
        let q = Quat::new(0.7, -0.2, 0.5, 0.3);
        for n2 in [1e-310, 5e-301, 2e300, f64::MAX] {
            let want = q.scale(1.0 / n2.sqrt());
            assert_eq!(q.normalized_with(n2), want.is_finite().then_some(want), "{n2}");
        }
        for n2 in [0.0, -0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(q.normalized_with(n2), None, "{n2}");
        }
        let n2 = q.norm_squared();
        assert_eq!(q.normalized_with(n2), Some(q.scale(n2.sqrt() * (1.0 / n2))));
    }

    #[test]
    fn renormalized_matches_the_exact_normalisation() {
        let unit = Quat::new(0.7, -0.2, 0.5, 0.3).normalized();
        // Near unit (a product of unit quaternions): the Newton step, as unit as division.
        for eps in [0.0, 3e-16, -7e-16, 4e-12, -9e-9] {
            let q = unit.scale(1.0 + eps);
            let (newton, exact) = (q.renormalized().unwrap(), q.try_normalized().unwrap());
            assert!((newton.norm() - 1.0).abs() <= 2.0 * f64::EPSILON, "{eps}: {}", newton.norm());
            assert!((newton.dot(exact) - 1.0).abs() <= 2.0 * f64::EPSILON, "{eps}");
        }
        // Farther from unit: the exact normalisation, bit for bit; none for zero or NaN.
        let q = unit.scale(1.5);
        assert_eq!(q.renormalized(), q.try_normalized());
        assert_eq!(Quat::new(0.0, 0.0, 0.0, 0.0).renormalized(), None);
        assert_eq!(Quat::new(f64::NAN, 0.0, 0.0, 1.0).renormalized(), None);
    }

    #[test]
    fn mul_pure_is_the_product_with_a_pure_quaternion() {
        let q = Quat::new(0.7, -0.2, 0.5, 0.3);
        for v in [Vec3::new(0.3, -1.2, 0.8), Vec3::new(1e-300, 2.0, -3e200), Vec3::new(0.0, 0.5, 0.0)] {
            let (a, b) = (q.mul_pure(v), q * Quat::pure(v));
            // The same bits (no exact zero arises here).
            assert_eq!([a.w, a.x, a.y, a.z].map(f64::to_bits), [b.w, b.x, b.y, b.z].map(f64::to_bits));
        }
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn plus_mul_pure_scaled_is_the_readable_form() {
        let mut r = crate::math::test_uniform(7);
        let bits = |q: Quat| [q.w, q.x, q.y, q.z].map(f64::to_bits);
        for i in 0..20_000 {
            let q = Quat::new(r(), r(), r(), r());
            // Signed zeros and exact cancellations too.
            let v = if i % 7 == 0 { Vec3::new(0.0, -0.0, r()) } else { Vec3::new(r(), r(), r()) * 5.0 };
            let h = if i % 11 == 0 { 0.0 } else { r().abs() * 0.01 };
            let (a, b) = (q.plus_mul_pure_scaled(v, h), q + q.mul_pure(v).scale(h));
            assert_eq!(bits(a), bits(b), "{q:?} {v:?} {h}");
        }
        // The one difference: w = −0 and a scalar product that cancels exactly.
        let q = Quat::new(-0.0, 0.5, 0.5, 0.0);
        let v = Vec3::new(1.0, -1.0, 0.0);
        let (a, b) = (q.plus_mul_pure_scaled(v, 0.01), q + q.mul_pure(v).scale(0.01));
        assert_eq!((a.w.to_bits(), b.w.to_bits()), ((-0.0f64).to_bits(), 0.0f64.to_bits()));
        assert_eq!(bits(a)[1..], bits(b)[1..]);
    }

    #[test]
    fn rows_rotate_both_ways() {
        let q = Quat::new(0.7, -0.2, 0.5, 0.3).normalized();
        let [r0, r1, r2] = q.rows();
        let v = Vec3::new(0.3, -1.2, 0.8);
        let forward = Vec3::new(r0.dot(v), r1.dot(v), r2.dot(v));
        let inverse = r0 * v.x + r1 * v.y + r2 * v.z;
        assert!((forward - q.rotate(v)).norm() < 1e-15 && (inverse - q.rotate_inverse(v)).norm() < 1e-15);
        let m = q.to_matrix();
        for (i, r) in [r0, r1, r2].into_iter().enumerate() {
            assert!((r - Vec3::new(m[i][0], m[i][1], m[i][2])).norm() < 1e-15, "row {i}");
        }
    }

    #[test]
    fn z_axis_in_body_is_the_inverse_rotation_of_z() {
        let q = Quat::new(0.7, -0.2, 0.5, 0.3).normalized();
        let direct = q.z_axis_in_body();
        let general = q.rotate_inverse(Vec3::new(0.0, 0.0, 1.0));
        let hamilton = (q.conj() * Quat::pure(Vec3::new(0.0, 0.0, 1.0)) * q).vector();
        assert!((direct - general).norm() < 1e-15 && (direct - hamilton).norm() < 1e-15);
    }

    #[test]
    fn hamilton_units_multiply_as_i_j_equals_k() {
        let i = Quat::new(0.0, 1.0, 0.0, 0.0);
        let j = Quat::new(0.0, 0.0, 1.0, 0.0);
        assert_eq!(i * j, Quat::new(0.0, 0.0, 0.0, 1.0));
        assert_eq!(j * i, Quat::new(0.0, 0.0, 0.0, -1.0));
    }

    #[test]
    fn rotation_of_x_by_quarter_turn_about_z_is_y() {
        let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), core::f64::consts::FRAC_PI_2);
        let v = q.rotate(Vec3::new(1.0, 0.0, 0.0));
        assert!(close(v.x, 0.0) && close(v.y, 1.0) && close(v.z, 0.0), "{v:?}");
        let back = q.rotate_inverse(v);
        assert!(close(back.x, 1.0) && close(back.y, 0.0), "{back:?}");
    }

    #[test]
    fn matrix_round_trip_covers_every_shepperd_branch() {
        let axes = [
            Vec3::new(0.3, -0.2, 0.9),
            Vec3::new(1.0, 0.1, 0.0),
            Vec3::new(0.0, 1.0, 0.1),
            Vec3::new(0.1, 0.0, 1.0),
        ];
        for axis in axes {
            for angle in [0.1, 1.0, 2.5, 3.1] {
                let q = Quat::from_axis_angle(axis, angle);
                let m = q.to_matrix();
                let back = Quat::from_matrix(m);
                assert!(q.angle_to(back) < 1e-12, "{q:?} {back:?}");
                // The matrix rotates vectors exactly as the quaternion does.
                let v = Vec3::new(0.4, -1.2, 2.0);
                let r = q.rotate(v);
                let mv = Vec3::new(
                    m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                    m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                    m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z,
                );
                assert!((r - mv).norm() < 1e-12);
            }
        }
    }

    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn euler_zyx_recomposes_the_quaternion() {
        let q = Quat::from_axis_angle(Vec3::new(0.3, -0.7, 0.5), 1.2);
        let e = q.to_euler();
        let z = Vec3::new(0.0, 0.0, 1.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        let x = Vec3::new(1.0, 0.0, 0.0);
        let r = Quat::from_axis_angle(z, e.yaw)
            * Quat::from_axis_angle(y, e.pitch)
            * Quat::from_axis_angle(x, e.roll);
        assert!(q.angle_to(r) < 1e-12, "{e:?}");
    }

    /// The ranges the header states: yaw and roll in (-π, π], pitch in [-π/2, π/2], for
    /// random unit quaternions and for the edge cases (half turns, signed zeros, gimbal
    /// lock), and the angles recompose the rotation away from gimbal lock.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn euler_angles_stay_in_their_stated_ranges() {
        use core::f64::consts::{FRAC_PI_2, PI};
        let mut cases = vec![
            Quat::IDENTITY,
            Quat::new(0.0, 0.0, 0.0, 1.0),
            Quat::new(-0.0, -0.0, -0.0, 1.0),
            Quat::new(-0.0, -0.0, 0.0, 1.0),
            Quat::new(-0.0, 1.0, 0.0, -0.0),
            Quat::new(0.0, 1.0, 0.0, 0.0),
            Quat::new(-0.0, 1.0, -0.0, -0.0),
            Quat::new(0.0, -0.0, 1.0, -0.0),
            Quat::new(FRAC_1_SQRT_2_F, 0.0, FRAC_1_SQRT_2_F, 0.0),
            Quat::new(FRAC_1_SQRT_2_F, 0.0, -FRAC_1_SQRT_2_F, 0.0),
        ];
        let mut s: u64 = 0x2545_f491;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..2000 {
            cases.push(Quat::new(next(), next(), next(), next()).normalized());
        }
        for q in cases {
            let e = q.to_euler();
            assert!(e.yaw > -PI && e.yaw <= PI, "{q:?}: yaw {}", e.yaw);
            assert!(e.roll > -PI && e.roll <= PI, "{q:?}: roll {}", e.roll);
            assert!((-FRAC_PI_2..=FRAC_PI_2).contains(&e.pitch), "{q:?}: pitch {}", e.pitch);
            assert!(q.angle_to(rebuilt(e)) < 1e-14, "{q:?}: {e:?}");
        }
    }

    /// `Rz(yaw) Ry(pitch) Rx(roll)`.
    fn rebuilt(e: Euler) -> Quat {
        Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), e.yaw)
            * Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), e.pitch)
            * Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), e.roll)
    }

    /// At and around gimbal lock (pitch ±90° and within 1e-12 to 1e-3 rad of it, both
    /// sides, for yaws and rolls around the circle) the angles rebuild the rotation to
    /// within a few rounding errors, and at exact lock roll is 0 and yaw carries the
    /// rotation about the vertical (issue 40: Rz(0.7) Ry(π/2) read as a rotation 12°
    /// away).
    #[test]
    #[cfg_attr(miri, ignore = "a long loop: too slow under Miri")]
    fn euler_angles_rebuild_the_rotation_at_and_near_gimbal_lock() {
        use core::f64::consts::{FRAC_PI_2, PI};
        let (z, y) = (Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 0.0));
        let mut worst = 0.0f64;
        for sign in [1.0, -1.0] {
            for yaw in [0.7, -2.9, 3.0, PI, 0.0, -1e-9] {
                let q = Quat::from_axis_angle(z, yaw) * Quat::from_axis_angle(y, sign * FRAC_PI_2);
                let e = q.to_euler();
                assert_eq!(e.roll, 0.0, "{q:?}: {e:?}");
                assert!((e.pitch - sign * FRAC_PI_2).abs() < 1e-15, "{q:?}: {e:?}");
                let dy = (e.yaw - yaw).rem_euclid(2.0 * PI);
                assert!(dy.min(2.0 * PI - dy) < 1e-14, "{q:?}: {e:?}");
                worst = worst.max(q.angle_to(rebuilt(e)));
            }
        }
        let x = Vec3::new(1.0, 0.0, 0.0);
        for sign in [1.0, -1.0] {
            for k in 0..=90 {
                // Offsets from 1e-12 to 1e-3 rad, ten per decade, and exact lock.
                let offset = if k == 90 { 0.0 } else { 10f64.powf(-12.0 + k as f64 / 10.0) };
                for side in [1.0, -1.0] {
                    let pitch = sign * (FRAC_PI_2 - side * offset);
                    for (yaw, roll) in [(0.7, 0.0), (-2.5, 1.1), (3.1, -3.1), (0.0, 0.3), (1e-7, -2.0)] {
                        let q = Quat::from_axis_angle(z, yaw)
                            * Quat::from_axis_angle(y, pitch)
                            * Quat::from_axis_angle(x, roll);
                        let e = q.to_euler();
                        assert!((-FRAC_PI_2..=FRAC_PI_2).contains(&e.pitch), "{q:?}: {e:?}");
                        let err = q.angle_to(rebuilt(e));
                        assert!(err < 1e-14, "pitch {pitch:e}, yaw {yaw}, roll {roll}: {err:e} rad, {e:?}");
                        worst = worst.max(err);
                    }
                }
            }
        }
        println!("worst rebuild error near gimbal lock: {worst:e} rad");
    }

    const FRAC_1_SQRT_2_F: f64 = core::f64::consts::FRAC_1_SQRT_2;

    #[test]
    fn two_vector_rotation_maps_from_onto_to() {
        let cases = [
            (Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.3, 0.4, 0.5)),
            (Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, -2.0, -3.0)),
            (Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.0, 0.0, 5.0)),
        ];
        for (f, t) in cases {
            let q = Quat::from_two_vectors(f, t);
            let r = q.rotate(f.normalized());
            assert!((r - t.normalized()).norm() < 1e-12, "{f:?} -> {t:?}: {r:?}");
            assert!(close(q.norm(), 1.0));
        }
    }

    #[test]
    fn angle_to_is_accurate_for_tiny_angles() {
        let q = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0), 0.7);
        let d = Quat::from_axis_angle(Vec3::new(-1.0, 0.5, 0.2), 1e-10);
        let a = (d * q).angle_to(q);
        assert!((a - 1e-10).abs() < 1e-16, "{a}");
    }
}
