use super::*;
use crate::math::Vec3;

fn sample_q() -> Quat {
    Quat::new(0.7, -0.2, 0.5, 0.3).normalized()
}

/// `∇f` as (21) writes it: `J_gᵀ f_g`, plus `J_bᵀ f_b` with a field `(b_x, b_z, m̂)`.
fn gradient(q: Quat, a: Vec3, field: Option<(f64, f64, Vec3)>) -> Quat {
    let g = jt_f(&jacobian_g(q), &objective_g(q, a));
    match field {
        Some((bx, bz, m)) => g + jt_f(&jacobian_b(q, bx, bz), &objective_b(q, bx, bz, m)),
        None => g,
    }
}

/// The objective (6) computed directly with quaternion products.
fn objective_direct(q: Quat, d: Vec3, s: Vec3) -> [f64; 3] {
    let v = q.rotate_inverse(d);
    [v.x - s.x, v.y - s.y, v.z - s.z]
}

#[test]
fn eq12_matches_the_general_objective_term_by_term() {
    let q = sample_q();
    let a = Vec3::new(0.1, -0.3, 0.9).normalized();
    let f = objective_g(q, a);
    let direct = objective_direct(q, Vec3::new(0.0, 0.0, 1.0), a);
    // Term by term with independent arithmetic (q1..q4 = w, x, y, z):
    let (q1, q2, q3, q4) = (q.w, q.x, q.y, q.z);
    let hand = [
        2.0 * q2 * q4 - 2.0 * q1 * q3 - a.x,
        2.0 * q1 * q2 + 2.0 * q3 * q4 - a.y,
        1.0 - 2.0 * q2 * q2 - 2.0 * q3 * q3 - a.z,
    ];
    for i in 0..3 {
        assert!((f[i] - direct[i]).abs() < 1e-15, "row {i}");
        assert!((f[i] - hand[i]).abs() < 1e-15, "row {i}");
    }
}

#[test]
fn eq16_uses_2b_and_matches_the_general_objective() {
    let q = sample_q();
    let (bx, bz) = (0.4, -0.9165);
    let m = Vec3::new(0.3, 0.5, -0.8).normalized();
    let f = objective_b(q, bx, bz, m);
    let direct = objective_direct(q, Vec3::new(bx, 0.0, bz), m);
    for i in 0..3 {
        assert!((f[i] - direct[i]).abs() < 1e-15, "row {i}: {} vs {}", f[i], direct[i]);
    }
    // With b halved, as in the 2012 C code, the field would not match: the factor 2
    // is needed.
    let wrong = objective_direct(q, Vec3::new(bx / 2.0, 0.0, bz / 2.0), m);
    assert!((f[0] - wrong[0]).abs() > 1e-3);
}

/// Central finite difference of a 3-vector function of q, column by column.
fn numeric_jacobian(f: impl Fn(Quat) -> [f64; 3], q: Quat) -> [[f64; 4]; 3] {
    let h = 1e-6;
    let mut j = [[0.0; 4]; 3];
    for c in 0..4 {
        let mut dq = [0.0; 4];
        dq[c] = h;
        let plus = f(Quat::new(q.w + dq[0], q.x + dq[1], q.y + dq[2], q.z + dq[3]));
        let minus = f(Quat::new(q.w - dq[0], q.x - dq[1], q.y - dq[2], q.z - dq[3]));
        for r in 0..3 {
            j[r][c] = (plus[r] - minus[r]) / (2.0 * h);
        }
    }
    j
}

#[test]
fn eq13_and_eq17_are_the_jacobians_of_eq12_and_eq16() {
    let q = sample_q();
    let a = Vec3::new(0.2, 0.1, 0.97).normalized();
    let (bx, bz) = (0.35, -0.93);
    let m = Vec3::new(0.1, 0.4, -0.9).normalized();
    let jg = numeric_jacobian(|q| objective_g(q, a), q);
    let jb = numeric_jacobian(|q| objective_b(q, bx, bz, m), q);
    let (ag, ab) = (jacobian_g(q), jacobian_b(q, bx, bz));
    for r in 0..3 {
        for c in 0..4 {
            assert!((jg[r][c] - ag[r][c]).abs() < 1e-8, "J_g[{r}][{c}]");
            assert!((jb[r][c] - ab[r][c]).abs() < 1e-8, "J_b[{r}][{c}]");
        }
    }
}

/// The halved forms the update uses are half of (21) written as `Jᵀ f`, to the bit.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn half_gradients_are_half_of_eq21_bit_for_bit() {
    let mut r = crate::math::test_uniform(11);
    let bits = |q: Quat| [q.w, q.x, q.y, q.z].map(f64::to_bits);
    for _ in 0..1000 {
        let q = Quat::new(r(), r(), r(), r()).normalized();
        let a = Vec3::new(r(), r(), r()).normalized();
        let m = Vec3::new(r(), r(), r()).normalized();
        let (bx, bz) = reference_field(q, m);
        // IMU: (13)'s two zeros dropped, as the readable form adds them.
        let g = jt_f(&jacobian_g(q), &objective_g(q, a));
        assert_eq!(bits(half_gradient_imu(q, a).scale(2.0)), bits(g));
        // MARG: the field part through half of (17), then the sum.
        let jb = jt_f(&jacobian_b(q, bx, bz), &objective_b(q, bx, bz, m));
        assert_eq!(bits(jt_f(&half_jacobian_b(q, bx, bz), &objective_b(q, bx, bz, m)).scale(2.0)), bits(jb));
        assert_eq!(bits(half_gradient_marg(q, a, bx, bz, m).scale(2.0)), bits(g + jb));
    }
}

#[test]
fn gradient_is_the_gradient_of_half_the_squared_objective() {
    // ∇(½‖f‖²) = Jᵀ f, eq. (8); check with a finite difference of the scalar objective.
    let q = sample_q();
    let a = Vec3::new(-0.3, 0.2, 0.93).normalized();
    let m = Vec3::new(0.5, -0.1, -0.85).normalized();
    let (bx, bz) = reference_field(q, m);
    let cost = |q: Quat| {
        let g = objective_g(q, a);
        let b = objective_b(q, bx, bz, m);
        0.5 * (g.iter().chain(b.iter()).map(|v| v * v).sum::<f64>())
    };
    let grad = gradient(q, a, Some((bx, bz, m)));
    let h = 1e-6;
    let num = |d: Quat| (cost(q + d.scale(h)) - cost(q + d.scale(-h))) / (2.0 * h);
    let numeric = Quat::new(
        num(Quat::new(1.0, 0.0, 0.0, 0.0)),
        num(Quat::new(0.0, 1.0, 0.0, 0.0)),
        num(Quat::new(0.0, 0.0, 1.0, 0.0)),
        num(Quat::new(0.0, 0.0, 0.0, 1.0)),
    );
    for (g, n) in [(grad.w, numeric.w), (grad.x, numeric.x), (grad.y, numeric.y), (grad.z, numeric.z)] {
        assert!((g - n).abs() < 1e-8, "{grad:?} vs {numeric:?}");
    }
    // And it vanishes at the true orientation.
    let truth = sample_q();
    let a_true = truth.rotate_inverse(Vec3::new(0.0, 0.0, 1.0));
    let m_true = truth.rotate_inverse(Vec3::new(0.6, 0.0, -0.8));
    let (bx, bz) = reference_field(truth, m_true);
    assert!((bx - 0.6).abs() < 1e-12 && (bz + 0.8).abs() < 1e-12);
    assert!(gradient(truth, a_true, Some((bx, bz, m_true))).norm() < 1e-12);
}

#[test]
fn reference_field_keeps_the_measured_inclination() {
    // (32): b has the inclination of h and no y component; |b| = |m̂| = 1.
    let q = sample_q();
    let m = Vec3::new(0.2, -0.7, 0.4).normalized();
    let (bx, bz) = reference_field(q, m);
    let h = q.rotate(m);
    assert!((bx * bx + bz * bz - 1.0).abs() < 1e-15);
    assert_eq!(bz, h.z);
    assert!(bx >= 0.0);
}

#[test]
fn beta_from_gyro_error_is_eq33() {
    let w = 0.1;
    let q = sample_q();
    let direct = (q * Quat::new(0.0, w, w, w)).scale(0.5).norm();
    assert!((beta_from_gyro_error(w) - direct).abs() < 1e-15);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn converges_from_a_wrong_initial_attitude() {
    let truth = Quat::from_axis_angle(Vec3::new(0.2, 1.0, -0.4), 1.1);
    let accel = truth.rotate_inverse(Vec3::new(0.0, 0.0, 9.81));
    let mag = truth.rotate_inverse(Vec3::new(18.0, 0.0, -42.0));
    let mut f = Madgwick::new(MadgwickSettings { beta_imu: 0.5, beta_marg: 0.5, ..Default::default() });
    // Start 150° away.
    f.set_quaternion(Quat::from_axis_angle(Vec3::new(1.0, 0.3, 0.0), 2.6) * truth);
    let start = f.quaternion().angle_to(truth);
    let mut last = Vec::new();
    for i in 0..4000 {
        f.update(0.01, Vec3::ZERO, Some(accel), Some(mag)).unwrap();
        if i >= 3990 {
            last.push(f.quaternion().angle_to(truth));
        }
    }
    // With no gyro signal each step moves q by β·dt = 5e-3 along the normalised
    // gradient (eq. (30)), which turns the attitude by up to 2β·dt = 1e-2 rad. The
    // estimate ends in a limit cycle around the truth, one step wide: never more than
    // a step away, and within half a step at least every other sample.
    let worst = last.iter().cloned().fold(0.0, f64::max);
    let best = last.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(start > 2.0 && worst < 1e-2 && best < 2.5e-3, "start {start} last {last:?}");
}

/// Eqs. (29)-(30) as the paper writes them: integrate, then divide by the norm.
fn direct_step(q: Quat, dt: f64, beta: f64, gyro: Vec3, a: Vec3) -> Quat {
    let g = gradient(q, a.normalized(), None);
    let q_dot = (q * Quat::pure(gyro)).scale(0.5);
    let s = beta / g.norm();
    let next = Quat::new(
        q.w + dt * (q_dot.w - s * g.w),
        q.x + dt * (q_dot.x - s * g.x),
        q.y + dt * (q_dot.y - s * g.y),
        q.z + dt * (q_dot.z - s * g.z),
    );
    next.scale(1.0 / next.norm())
}

#[test]
fn the_update_is_eqs_29_and_30() {
    let gyro = Vec3::new(0.3, -0.2, 0.4);
    // An ordinary step.
    let q = sample_q();
    let a = Vec3::new(0.2, -0.4, 9.7);
    let mut f = Madgwick::new(MadgwickSettings { beta_imu: 0.041, ..Default::default() });
    f.set_quaternion(q);
    f.update(0.01, gyro, Some(a), None).unwrap();
    // Within rounding of the literal form: a few ulp of each component.
    assert!((f.quaternion() - direct_step(q, 0.01, 0.041, gyro, a)).norm() < 4.0 * f64::EPSILON);
    // Estimate upside down (half a turn about x) while the sensor is level: the
    // gradient of (12)-(13) is then 8q, parallel to the estimate, and with dt β = 0.5
    // the correction removes half of the prediction before the normalisation.
    let q = Quat::new(0.0, 1.0, 0.0, 0.0);
    let a = Vec3::new(0.0, 0.0, 9.81);
    let g = gradient(q, a.normalized(), None);
    assert_eq!((g.w, g.x, g.y, g.z), (0.0, 8.0, 0.0, 0.0));
    let mut f = Madgwick::new(MadgwickSettings { beta_imu: 50.0, ..Default::default() });
    f.set_quaternion(q);
    f.update(0.01, gyro, Some(a), None).unwrap();
    let direct = direct_step(q, 0.01, 50.0, gyro, a);
    assert!((f.quaternion() - direct).norm() < 4.0 * f64::EPSILON, "{:?} vs {direct:?}", f.quaternion());
    assert!((f.quaternion().norm() - 1.0).abs() < 1e-15);
}

/// The usual case written inline in `step` gives the bits of the general
/// correction, `Madgwick::correct`, with its tests.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_inline_correction_is_the_general_one() {
    let mut r = crate::math::test_uniform(7);
    for i in 0..2000 {
        let q = Quat::new(r(), r(), r(), r()).normalized();
        let gyro = Vec3::new(r(), r(), r()) * 5.0;
        let accel = Vec3::new(r(), r(), r()) * 10.0;
        let mag = Vec3::new(r(), r(), r()) * 50.0;
        let (dt, beta) = (0.01, [0.041, 2.0, 60.0][i % 3]);
        for with_mag in [false, true] {
            let settings = MadgwickSettings { beta_imu: beta, beta_marg: beta, ..Default::default() };
            let mut f = Madgwick::new(settings);
            f.set_quaternion(q);
            f.update(dt, gyro, Some(accel), with_mag.then_some(mag)).unwrap();
            let p = q + q.mul_pure(gyro).scale(0.5 * dt);
            let a = accel.normalized();
            let m = mag.normalized();
            let (bx, bz) = reference_field(q, m);
            let g = if with_mag && bx > 0.0 {
                half_gradient_marg(q, a, bx, bz, m)
            } else {
                half_gradient_imu(q, a)
            };
            let expected = Madgwick::correct(p, g, g.norm_squared(), beta * dt).unwrap();
            assert_eq!(f.quaternion(), expected, "{i} {with_mag}");
        }
    }
}

#[test]
fn gyro_only_step_integrates_eq4() {
    let mut f = Madgwick::new(MadgwickSettings::default());
    let w = Vec3::new(0.0, 0.0, 1.0);
    f.update(0.01, w, None, None).unwrap();
    let q = f.quaternion();
    let expected = Quat::new(1.0, 0.0, 0.0, 0.005).normalized();
    assert_eq!(q, expected);
}

#[test]
fn overflowing_step_leaves_the_state_alone() {
    let mut f = Madgwick::new(MadgwickSettings::default());
    f.set_quaternion(sample_q());
    let before = f.clone();
    assert!(f.update(1e300, Vec3::new(1e300, 1e300, 0.0), None, None).is_none());
    assert_eq!(f, before);
}
