use super::{Quat, Vec3};
use core::f64::consts::FRAC_1_SQRT_2;

/// The earth frame an orientation is expressed in.
///
/// "North" is magnetic north as the magnetometer sees it; declination is not applied.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Frame {
    /// x East, y North, z Up (the default).
    #[default]
    Enu,
    /// x North, y East, z Down.
    Ned,
    /// x North, y West, z Up.
    Nwu,
}

impl Frame {
    pub const ALL: [Frame; 3] = [Frame::Enu, Frame::Ned, Frame::Nwu];

    /// The lower-case name: `enu`, `ned` or `nwu`.
    pub fn name(self) -> &'static str {
        match self {
            Frame::Enu => "enu",
            Frame::Ned => "ned",
            Frame::Nwu => "nwu",
        }
    }

    pub fn from_name(name: &str) -> Option<Frame> {
        Frame::ALL.into_iter().find(|f| f.name().eq_ignore_ascii_case(name))
    }

    /// The constant rotation `c` with `q_self = c ⊗ q_enu` for any orientation `q`.
    pub fn from_enu(self) -> Quat {
        match self {
            Frame::Enu => Quat::IDENTITY,
            // Half a turn about the horizontal (x + y) diagonal: swaps x and y, flips z.
            Frame::Ned => Quat::new(0.0, FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0),
            // A quarter turn about z, clockwise seen from above: East -> -West, North -> North.
            Frame::Nwu => Quat::new(FRAC_1_SQRT_2, 0.0, 0.0, -FRAC_1_SQRT_2),
        }
    }

    /// The constant rotation `c` with `q_to = c ⊗ q_self`; `None` when the frames are
    /// the same (no product is taken, so the quaternion passes through bit for bit).
    ///
    /// The six rotations are constants: `(to.from_enu() ⊗ self.from_enu()*)` normalised,
    /// written out (a test checks them bit for bit against that product), so that an
    /// output read costs no product of constants.
    pub const fn rotation_to(self, to: Frame) -> Option<Quat> {
        // 1/√2 rounded as the product gives it (one ulp under FRAC_1_SQRT_2).
        const H: f64 = 0.7071067811865475;
        match (self, to) {
            (Frame::Enu, Frame::Ned) => Some(Quat::new(0.0, H, H, 0.0)),
            (Frame::Enu, Frame::Nwu) => Some(Quat::new(H, 0.0, 0.0, -H)),
            (Frame::Ned, Frame::Enu) => Some(Quat::new(0.0, -H, -H, 0.0)),
            (Frame::Ned, Frame::Nwu) => Some(Quat::new(0.0, -1.0, 0.0, -0.0)),
            (Frame::Nwu, Frame::Enu) => Some(Quat::new(H, 0.0, 0.0, H)),
            (Frame::Nwu, Frame::Ned) => Some(Quat::new(0.0, 1.0, 0.0, 0.0)),
            _ => None,
        }
    }

    /// `q` given in this frame, expressed in `to`: `rotation_to(to) ⊗ q`, with the
    /// product written out for each pair. Each rotation's components are 0, ±1 or ±1/√2,
    /// so the product is a sum or difference of two components per output, scaled by
    /// 1/√2 (8 operations against the general product's 28; each component within 2⁻⁵² of
    /// the product's, which a test checks), or a signed permutation (the same values).
    #[inline(always)]
    pub fn express(self, to: Frame, q: Quat) -> Quat {
        const H: f64 = 0.7071067811865475;
        let Quat { w, x, y, z } = q;
        match (self, to) {
            (Frame::Enu, Frame::Ned) => Quat::new(-(x + y) * H, (w + z) * H, (w - z) * H, (y - x) * H),
            (Frame::Enu, Frame::Nwu) => Quat::new((w + z) * H, (x + y) * H, (y - x) * H, (z - w) * H),
            (Frame::Ned, Frame::Enu) => Quat::new((x + y) * H, -(w + z) * H, (z - w) * H, (x - y) * H),
            (Frame::Ned, Frame::Nwu) => Quat::new(x, -w, z, -y),
            (Frame::Nwu, Frame::Enu) => Quat::new((w - z) * H, (x - y) * H, (x + y) * H, (w + z) * H),
            (Frame::Nwu, Frame::Ned) => Quat::new(-x, w, -z, y),
            _ => q,
        }
    }

    /// The direction "up" (opposite to gravity) in this frame.
    pub fn up(self) -> Vec3 {
        match self {
            Frame::Enu | Frame::Nwu => Vec3::new(0.0, 0.0, 1.0),
            Frame::Ned => Vec3::new(0.0, 0.0, -1.0),
        }
    }

    /// The orientation whose earth frame is `self`, built from one accelerometer
    /// reading (specific force: points up at rest) and, when given, one magnetometer
    /// reading. With a magnetometer, up = a/|a|, east = (m × up)/|m × up|,
    /// north = up × east, and the rows of `R_ES` are those axes written in sensor
    /// coordinates. Without one, heading is set so that the sensor's x axis points to
    /// the frame's x axis as nearly as possible: the smallest rotation that takes the
    /// measured up onto the frame's up.
    ///
    /// Returns `None` when the magnetometer is parallel to the accelerometer (no
    /// horizontal field to define north, `no_heading`); the caller then falls back to
    /// `mag = None`.
    pub fn attitude_from(self, accel: Vec3, mag: Option<Vec3>) -> Option<Quat> {
        let up = accel.normalized();
        let Some(mag) = mag else {
            return Some(Quat::from_two_vectors(up, self.up()));
        };
        if no_heading(accel, mag) {
            return None;
        }
        let east = mag.cross(up);
        let east_norm = east.norm();
        let east = east * (1.0 / east_norm);
        let north = up.cross(east);
        let rows = |a: Vec3, b: Vec3, c: Vec3| [[a.x, a.y, a.z], [b.x, b.y, b.z], [c.x, c.y, c.z]];
        let m = match self {
            Frame::Enu => rows(east, north, up),
            Frame::Ned => rows(north, east, -up),
            Frame::Nwu => rows(north, -east, up),
        };
        Some(Quat::from_matrix(m))
    }
}

/// The sine of the largest angle between a magnetometer reading and the accelerometer
/// reading at which the field counts as parallel to gravity: 1e-6 (rad), the bound of
/// the EKF's and the robust kind's tests (horizontal part at most 1e-6 of the norm).
pub(crate) const NO_HEADING_SINE: f64 = 1e-6;

/// The rule every kind follows for "a magnetometer parallel to gravity gives no
/// heading": `mag` within [`NO_HEADING_SINE`] of parallel (or antiparallel) to the
/// sample's accelerometer reading `accel` has no horizontal part to define north: the
/// lifecycle (`filters::Runner`) leaves it out of every kind's step, which is then the
/// kind's IMU update, and [`Frame::attitude_from`] takes no heading from it (the start
/// from a first sample, a start-up period's means, a re-acquisition). Both vectors
/// finite and not zero.
#[inline]
pub(crate) fn no_heading(accel: Vec3, mag: Vec3) -> bool {
    // |a × m|² = sin² ∠(a, m) |a|² |m|²: compared directly while the product is in
    // range, else from the unit vectors.
    let p = accel.norm_squared() * mag.norm_squared();
    if p > 1e-290 && p < 1e290 {
        return accel.cross(mag).norm_squared() <= NO_HEADING_SINE * NO_HEADING_SINE * p;
    }
    no_heading_by_units(accel, mag)
}

#[cold]
#[inline(never)]
fn no_heading_by_units(accel: Vec3, mag: Vec3) -> bool {
    accel.normalized().cross(mag.normalized()).norm_squared() <= NO_HEADING_SINE * NO_HEADING_SINE
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_rotation_constants_are_the_products_of_the_frames() {
        for a in Frame::ALL {
            for b in Frame::ALL {
                let product = (a != b).then(|| (b.from_enu() * a.from_enu().conj()).normalized());
                let bits = |q: Option<Quat>| q.map(|q| [q.w, q.x, q.y, q.z].map(f64::to_bits));
                assert_eq!(bits(a.rotation_to(b)), bits(product), "{a:?} -> {b:?}");
            }
        }
    }

    use super::*;

    /// `express` is the product with `rotation_to`'s constant: each component within 2⁻⁵²,
    /// and equal (up to the sign of a zero) for the signed permutations.
    #[test]
    #[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
    fn express_is_the_product_with_the_rotation() {
        let mut r = crate::math::test_uniform(5);
        for i in 0..2000 {
            let q = if i == 0 {
                Quat::new(0.5, 0.0, -0.0, 0.5)
            } else {
                Quat::new(r(), r(), r(), r()).normalized()
            };
            for a in Frame::ALL {
                for b in Frame::ALL {
                    let got = a.express(b, q);
                    let want = a.rotation_to(b).map_or(q, |c| c * q);
                    let (g, w) = ([got.w, got.x, got.y, got.z], [want.w, want.x, want.y, want.z]);
                    let exact =
                        matches!((a, b), (Frame::Ned, Frame::Nwu) | (Frame::Nwu, Frame::Ned)) || a == b;
                    for k in 0..4 {
                        if exact {
                            assert_eq!(g[k], w[k], "{a:?} -> {b:?} {q:?}");
                        } else {
                            assert!(
                                (g[k] - w[k]).abs() <= f64::EPSILON,
                                "{a:?} -> {b:?} {q:?}: {g:?} vs {w:?}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn frame_rotations_map_the_axes_as_named() {
        // East, North, Up written in ENU, then in each frame.
        let east = Vec3::new(1.0, 0.0, 0.0);
        let north = Vec3::new(0.0, 1.0, 0.0);
        let up = Vec3::new(0.0, 0.0, 1.0);
        let ned = Frame::Ned.from_enu();
        assert!((ned.rotate(north) - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
        assert!((ned.rotate(east) - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
        assert!((ned.rotate(up) - Vec3::new(0.0, 0.0, -1.0)).norm() < 1e-15);
        let nwu = Frame::Nwu.from_enu();
        assert!((nwu.rotate(north) - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
        assert!((nwu.rotate(east) - Vec3::new(0.0, -1.0, 0.0)).norm() < 1e-15);
        assert!((nwu.rotate(up) - up).norm() < 1e-15);
    }

    #[test]
    fn attitude_from_level_sensor_facing_north() {
        // Sensor x = North, y = West, z = Up; field points north and down (dip 60°).
        let accel = Vec3::new(0.0, 0.0, 9.81);
        let mag = Vec3::new(20.0, 0.0, -34.6);
        let q = Frame::Nwu.attitude_from(accel, Some(mag)).unwrap();
        assert!(q.angle_to(Quat::IDENTITY) < 1e-12, "{q:?}");
        let q_enu = Frame::Enu.attitude_from(accel, Some(mag)).unwrap();
        // In ENU the sensor's x axis (north) is the earth's y axis.
        let x = q_enu.rotate(Vec3::new(1.0, 0.0, 0.0));
        assert!((x - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-12, "{x:?}");
        let q_ned = Frame::Ned.attitude_from(accel, Some(mag)).unwrap();
        let d = q_ned.rotate(Vec3::new(0.0, 0.0, -1.0));
        assert!((d - Vec3::new(0.0, 0.0, 1.0)).norm() < 1e-12, "{d:?}");
    }

    #[test]
    fn attitude_from_agrees_across_frames() {
        let accel = Vec3::new(1.2, -3.0, 8.9);
        let mag = Vec3::new(-14.0, 22.0, -31.0);
        let enu = Frame::Enu.attitude_from(accel, Some(mag)).unwrap();
        for f in Frame::ALL {
            let q = f.attitude_from(accel, Some(mag)).unwrap();
            let via = Frame::Enu.rotation_to(f).map_or(enu, |c| c * enu);
            assert!(q.angle_to(via) < 1e-12, "{f:?}");
            // Gravity direction: the accelerometer reading maps onto the frame's up.
            assert!((q.rotate(accel.normalized()) - f.up()).norm() < 1e-12);
        }
    }

    #[test]
    fn attitude_without_field_direction_is_refused() {
        let accel = Vec3::new(0.0, 0.0, 9.81);
        assert!(Frame::Enu.attitude_from(accel, Some(Vec3::new(0.0, 0.0, -40.0))).is_none());
        let q = Frame::Enu.attitude_from(accel, None).unwrap();
        assert!(q.angle_to(Quat::IDENTITY) < 1e-15);
    }
}
