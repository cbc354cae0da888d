use super::*;

#[test]
fn correction_rotates_the_estimate_towards_the_measurement() {
    // Estimate level; the sensor is actually tilted 0.2 rad about x.
    let truth = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.2);
    let accel = truth.rotate_inverse(Vec3::new(0.0, 0.0, 9.81));
    let (e, _) = Mahony::correction(Quat::IDENTITY, accel, None);
    // â × v̂ with â = (0, sin .2, cos .2) and v̂ = (0, 0, 1): (sin .2, 0, 0).
    assert!((e - Vec3::new(0.2f64.sin(), 0.0, 0.0)).norm() < 1e-12, "{e:?}");
    // A step with that correction reduces the error.
    let mut f = Mahony::new(MahonySettings { kp: 1.0, ki: 0.0, ..Default::default() });
    let before = f.quaternion().angle_to(truth);
    f.update(0.1, Vec3::ZERO, Some(accel), None).unwrap();
    assert!(f.quaternion().angle_to(truth) < before);
}

/// The correction with one cross product, `(â + b_z m̂) × r2 + b_y (m̂ × r1)`, is the
/// readable `â × v̂ + m̂ × ŵ` with `ŵ = Rᵀ [0 b_y b_z]` to rounding.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_correction_is_the_sum_of_both_cross_products() {
    let mut r = crate::math::test_uniform(11);
    for _ in 0..10_000 {
        let q = Quat::new(r(), r(), r(), r()).normalized();
        let a = Vec3::new(r(), r(), r()).normalized();
        let m = Vec3::new(r(), r(), r()).normalized();
        let (e, used) = Mahony::correction_of_units(q, a, Some(m));
        let h = q.rotate(m);
        let w = q.rotate_inverse(Vec3::new(0.0, (h.x * h.x + h.y * h.y).sqrt(), h.z));
        let readable = a.cross(q.rotate_inverse(Vec3::new(0.0, 0.0, 1.0))) + m.cross(w);
        assert!(used);
        assert!((e - readable).norm() < 1e-14, "{e:?} {readable:?}");
    }
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn integral_term_learns_a_constant_gyro_bias() {
    let bias = Vec3::new(0.02, -0.03, 0.01);
    let truth = Quat::from_axis_angle(Vec3::new(0.3, 0.5, 0.1), 0.7);
    let accel = truth.rotate_inverse(Vec3::new(0.0, 0.0, 9.81));
    // North (y, East-North-Up) and down.
    let mag = truth.rotate_inverse(Vec3::new(0.0, 20.0, -40.0));
    let mut f = Mahony::new(MahonySettings { kp: 1.0, ki: 0.3, ..Default::default() });
    f.set_quaternion(truth);
    // 240 s: the PI loop is underdamped with these gains and settles in about 200 s.
    for _ in 0..24000 {
        f.update(0.01, bias, Some(accel), Some(mag)).unwrap();
    }
    assert!((f.bias() - bias).norm() < 1e-6, "{:?}", f.bias());
    assert!(f.quaternion().angle_to(truth) < 1e-6);
}
