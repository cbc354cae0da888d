use super::*;
use nalgebra::{SMatrix, SVector};

type M10 = SMatrix<f64, 10, 10>;

fn vec4(q: Quat) -> nalgebra::Vector4<f64> {
    nalgebra::Vector4::new(q.w, q.x, q.y, q.z)
}
type V10 = SVector<f64, 10>;

impl Ekf {
    /// P as a full 10×10 matrix.
    fn covariance(&mut self) -> M10 {
        M10::from_fn(|r, c| *self.p.entry_mut(r, c))
    }

    fn state(&self) -> V10 {
        V10::from_iterator(self.x.clone().values_mut().map(|v| *v))
    }
}

/// The state and P as bit patterns, in snapshot order.
fn bits(f: &mut Ekf) -> Vec<u64> {
    let mut out = vec![0; 8 * f.state_len()];
    let mut w = crate::filters::state::Writer { buf: Some(&mut out), pos: 0 };
    f.codec(&mut w);
    out.chunks(8).map(|c| u64::from_le_bytes(c.try_into().unwrap())).collect()
}

impl Ekf {
    fn state_len(&mut self) -> usize {
        let mut w = crate::filters::state::Writer { buf: None, pos: 0 };
        self.codec(&mut w);
        w.pos / 8
    }
}

/// `update` runs with the widest lanes the CPU has (256-bit AVX registers on most
/// x86-64 machines); the baseline `f64x4` lanes, compiled into this test, must give
/// the same bits at every step, with and without the magnetometer and at rest.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_wide_lanes_give_the_baseline_bits() {
    let settings = EkfSettings { rest_rate_std: 0.01, ..EkfSettings::default() };
    let (mut wide, mut base) = (Ekf::new(settings), Ekf::new(settings));
    for i in 0..3000 {
        let t = i as f64 * 0.01;
        let moving = (i / 300) % 2 == 0;
        let r = if moving { 1.0 } else { 0.0 };
        let gyro = Vec3::new(0.5 * r * t.sin(), 0.3 * r * (1.3 * t).cos(), 0.01 + 0.2 * r);
        let accel = Vec3::new(0.3 * r * t.cos(), 0.2 * r * t.sin() + 0.1, -9.8);
        let mag = (i % 3 != 0).then(|| Vec3::new(20.0 + t.sin(), 3.0, 40.0));
        let accel = (i % 7 != 3).then_some(accel);
        let a = wide.update(0.01, gyro, accel, mag);
        let b = base.update_in::<f64x4>((), 0.01, gyro, accel, mag, true).ok();
        assert_eq!(a, b, "step {i}");
        assert!(bits(&mut wide) == bits(&mut base), "the states differ after step {i}");
    }
}

/// One update in dense 10×10 algebra, the textbook way: F P Fᵀ + G Q Gᵀ, then one
/// batch Joseph-form correction with all six rows and a Cholesky solve, then the
/// heading correction with its restricted gain in Joseph form.
fn dense_update(f: &mut Ekf, dt: f64, gyro: Vec3, accel: Vec3, mag: Vec3) -> (V10, M10) {
    let s = f.settings;
    let (mut x, p0) = (f.state(), f.covariance());
    let q = Quat::new(x[0], x[1], x[2], x[3]);
    let (a_w, a_d) = (libm::exp(-dt / s.tau_omega), libm::exp(-dt / s.tau_drift));
    for i in 4..7 {
        x[i] *= a_w;
        x[i + 3] *= a_d;
    }
    let (e, de) = exp_and_jacobian(Vec3::new(x[4], x[5], x[6]), 0.5 * dt);
    let qp = q * e;
    x.fixed_rows_mut::<4>(0).copy_from(&vec4(qp));
    let d = left(q) * de;
    let mut fm = M10::zeros();
    fm.fixed_view_mut::<4, 4>(0, 0).copy_from(&right(e));
    fm.fixed_view_mut::<4, 3>(0, 4).copy_from(&(d * a_w));
    let mut g = SMatrix::<f64, 10, 3>::zeros();
    g.fixed_view_mut::<4, 3>(0, 0).copy_from(&d);
    for i in 0..3 {
        fm[(4 + i, 4 + i)] = a_w;
        fm[(7 + i, 7 + i)] = a_d;
        g[(4 + i, i)] = 1.0;
    }
    let mut p = fm * p0 * fm.transpose() + g * g.transpose() * (s.omega_std.powi(2) * (1.0 - a_w * a_w));
    for i in 7..10 {
        p[(i, i)] += s.drift_std.powi(2) * (1.0 - a_d * a_d);
    }
    let (fh, hf) = gravity_model(qp, s.gravity);
    let nu = accel * (s.gravity / accel.norm()) - fh;
    let dev = accel.norm() - s.gravity;
    let ra = s.accel_noise.powi(2) / (2.0 * dt)
        + (s.accel_motion.powi(2) + dev * dev) * (2.0 * s.motion_tau / dt).max(1.0);
    let mut h = SMatrix::<f64, 6, 10>::zeros();
    h.fixed_view_mut::<3, 4>(0, 0).copy_from(&hf);
    let mut r = SMatrix::<f64, 6, 6>::zeros();
    for i in 0..3 {
        h[(3 + i, 4 + i)] = 1.0;
        h[(3 + i, 7 + i)] = 1.0;
        r[(i, i)] = ra;
        r[(3 + i, 3 + i)] = s.gyro_noise.powi(2) / (2.0 * dt);
    }
    let z = SVector::<f64, 6>::from_column_slice(&[
        nu.x,
        nu.y,
        nu.z,
        gyro.x - x[4] - x[7],
        gyro.y - x[5] - x[8],
        gyro.z - x[6] - x[9],
    ]);
    let pht = p * h.transpose();
    let k = (h * pht + r).cholesky().unwrap().solve(&pht.transpose()).transpose();
    x += k * z;
    let ikh = M10::identity() - k * h;
    p = ikh * p * ikh.transpose() + k * r * k.transpose();
    let n = x.fixed_rows::<4>(0).norm();
    x.fixed_rows_mut::<4>(0).scale_mut(1.0 / n);
    let q = Quat::new(x[0], x[1], x[2], x[3]);
    let me = q.rotate(mag);
    let innovation = -libm::atan2(me.y, me.x);
    let dq = vec4(Quat::new(0.0, 0.0, 0.0, 0.5) * q);
    let mut hrow = SMatrix::<f64, 1, 10>::zeros();
    hrow.fixed_view_mut::<1, 4>(0, 0).copy_from(&(dq * 4.0).transpose());
    let r_psi = s.heading_std.powi(2) * (2.0 * s.heading_tau / dt).max(1.0);
    let p_psi = (hrow * p * hrow.transpose())[0];
    let k_psi = p_psi / (p_psi + r_psi);
    let mut k = V10::zeros();
    k.fixed_rows_mut::<4>(0).copy_from(&(dq * k_psi));
    let turned = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), k_psi * innovation) * q;
    x.fixed_rows_mut::<4>(0).copy_from(&vec4(turned));
    let ikh = M10::identity() - k * hrow;
    p = ikh * p * ikh.transpose() + k * k.transpose() * r_psi;
    (x, p)
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn block_algebra_equals_the_dense_textbook_update() {
    // Adaptive noise off: it only raises R, which the dense version takes as given.
    let settings = EkfSettings { accel_adapt_tau: 0.0, heading_adapt_tau: 0.0, ..Default::default() };
    let mut f = Ekf::new(settings);
    let truth = Quat::from_axis_angle(Vec3::new(0.2, -1.0, 0.4), 0.9);
    let mut worst = (0.0f64, 0.0f64);
    for i in 0..400 {
        let t = i as f64 * 0.01;
        let gyro = Vec3::new(0.8 * t.sin(), -0.5, 0.3 * t.cos());
        // A tilted, moving reading, so every row has a sizeable innovation.
        let accel = truth.rotate_inverse(Vec3::new(0.9 * (3.0 * t).sin(), 0.4, -9.80665));
        let mag = truth.rotate_inverse(Vec3::new(18.0, 3.0, 42.0));
        let (x, p) = dense_update(&mut f.clone(), 0.01, gyro, accel, mag);
        f.update(0.01, gyro, Some(accel), Some(mag)).unwrap();
        worst.0 = worst.0.max((f.state() - x).abs().max());
        worst.1 = worst.1.max((f.covariance() - p).abs().max() / p.abs().max());
    }
    // Same algebra, other rounding: two batches of three rows, a 3×3 Cholesky factor
    // and block products re-associate the sums.
    assert!(worst.0 < 1e-12 && worst.1 < 1e-12, "state {:e}, covariance (relative) {:e}", worst.0, worst.1);
}

#[test]
fn eq13_matches_rotating_gravity_into_the_body() {
    let q = Quat::from_axis_angle(Vec3::new(0.3, -0.5, 0.8), 1.1);
    let (f, _) = gravity_model(q, 9.81);
    // C_o^b [0 0 -g] = R(q)ᵀ [0 0 -g]: in NED, gravity's reaction points up (−z).
    let direct = q.rotate_inverse(Vec3::new(0.0, 0.0, -9.81));
    assert!((f - direct).norm() < 1e-12, "{f:?} {direct:?}");
}

/// `all_finite`: true for finite lanes, false for an infinite or NaN lane, for
/// infinities of both signs (whose sum is NaN), and for finite lanes whose sum
/// overflows (the covariance is then refused like a non-finite one).
#[test]
fn the_finiteness_test_answers_for_every_lane() {
    let v = |x: [f64; 4]| f64x4::new(x);
    let ok = [v([1.0, -2.0, 3e200, 0.0]), v([-1e300, 5.0, 0.0, -3e200])];
    assert!(all_finite(&ok));
    for (lane, bad) in [(0, f64::INFINITY), (1, f64::NEG_INFINITY), (2, f64::NAN), (3, -f64::NAN)] {
        let mut c = ok;
        let mut x = c[1].to_array();
        x[lane] = bad;
        c[1] = v(x);
        assert!(!all_finite(&c), "lane {lane} = {bad}");
    }
    assert!(!all_finite(&[v([f64::INFINITY; 4]), v([f64::NEG_INFINITY; 4])]));
    assert!(!all_finite(&[v([1e308, 0.0, 0.0, 0.0]), v([1e308, 0.0, 0.0, 0.0])]));
}

/// `exp_and_d`'s multiplied-out D against `L(q) J` with J from `exp_and_jacobian` (the
/// readable form), on both sides of that function's small-angle branch, of the series'
/// range and at large angles: each entry within 4ε h (D's entries are at most h, so 4
/// to 8 units in the last place of h); the same exponential beyond the series' range,
/// within 3 ulp inside it.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn exp_and_d_is_left_of_q_times_the_jacobian() {
    let q = Quat::new(0.7, -0.2, 0.5, 0.3).normalized();
    let cases = [
        (Vec3::new(0.3, -1.2, 0.8), 0.0025),
        (Vec3::new(5.0, 2.0, -7.0), 0.01),
        (Vec3::new(40.0, -30.0, 10.0), 0.05),
        (Vec3::new(3.0, -4.0, 12.0), 0.0048), // θ² just under 1/256
        (Vec3::new(3.0, -4.0, 12.0), 0.0049), // and just over
        (Vec3::new(1e-7, 0.0, 2e-7), 0.005),
        (Vec3::new(3e-6, -1e-6, 2e-6), 0.005),
        (Vec3::ZERO, 0.005),
    ];
    for (omega, h) in cases {
        let (e0, j) = exp_and_jacobian(omega, h);
        let (e, d) = exp_and_d::<f64x4>((), q, omega, h);
        if omega.norm_squared() * h * h > 1.0 / 256.0 {
            assert_eq!([e.w, e.x, e.y, e.z].map(f64::to_bits), [e0.w, e0.x, e0.y, e0.z].map(f64::to_bits));
        } else {
            // The series against the sine and cosine: 3 ulp, as in `complementary`.
            for (a, b) in [(e.w, e0.w), (e.x, e0.x), (e.y, e0.y), (e.z, e0.z)] {
                assert!((a - b).abs() <= 3.0 * f64::EPSILON * b.abs(), "{omega:?} {h}: {e:?} vs {e0:?}");
            }
        }
        let dense = left(q) * j;
        for (c, col) in d.iter().enumerate() {
            for (r, v) in col.to_array().into_iter().enumerate() {
                let err = (v - dense[(r, c)]).abs();
                assert!(err <= 4.0 * f64::EPSILON * h, "{omega:?} {h}: D[{r}][{c}] {v} vs {}", dense[(r, c)]);
            }
        }
    }
}

#[test]
fn analytic_jacobians_match_finite_differences() {
    let q = Quat::from_axis_angle(Vec3::new(0.3, -0.5, 0.8), 1.1);
    let (_, hf) = gravity_model(q, 9.81);
    let eps = 1e-6;
    for c in 0..4 {
        let mut dq = [0.0; 4];
        dq[c] = eps;
        let plus = gravity_model(Quat::new(q.w + dq[0], q.x + dq[1], q.y + dq[2], q.z + dq[3]), 9.81).0;
        let minus = gravity_model(Quat::new(q.w - dq[0], q.x - dq[1], q.y - dq[2], q.z - dq[3]), 9.81).0;
        let d = (plus - minus) * (0.5 / eps);
        for (r, v) in [d.x, d.y, d.z].into_iter().enumerate() {
            assert!((hf[(r, c)] - v).abs() < 1e-7, "H[{r}][{c}]");
        }
    }
    for omega in [Vec3::new(0.4, -1.3, 2.0), Vec3::new(1e-10, 0.0, 2e-10)] {
        let h = 0.05;
        let (_, j) = exp_and_jacobian(omega, h);
        for c in 0..3 {
            let mut d = [0.0; 3];
            d[c] = eps;
            let plus = exp_and_jacobian(omega + Vec3::new(d[0], d[1], d[2]), h).0;
            let minus = exp_and_jacobian(omega - Vec3::new(d[0], d[1], d[2]), h).0;
            let num = [plus.w - minus.w, plus.x - minus.x, plus.y - minus.y, plus.z - minus.z];
            for r in 0..4 {
                assert!((j[(r, c)] - num[r] / (2.0 * eps)).abs() < 1e-8, "dexp[{r}][{c}] at {omega:?}");
            }
        }
    }
}

#[test]
fn predict_integrates_the_rate_exactly() {
    let (e, _) = exp_and_jacobian(Vec3::new(0.0, 0.0, 2.0), 0.25);
    assert!((e.w - 0.5f64.cos()).abs() < 1e-15 && (e.z - 0.5f64.sin()).abs() < 1e-15);
}

/// The heading and inclination σ read the earth-frame error angle: with P_qq the
/// outer product of one error Δq (a known small rotation ε about an earth axis, applied
/// as q' = Δ ⊗ q), heading σ is |ε| for a vertical axis and inclination σ |ε| for a
/// horizontal one, to first order.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn attitude_sigmas_read_the_earth_frame_error_angle() {
    let mut f = Ekf::new(EkfSettings::default());
    let q = Quat::from_axis_angle(Vec3::new(0.3, -0.5, 0.8).normalized(), 1.1);
    f.set_quaternion(q);
    let eps = 1e-6;
    for (axis, vertical) in [(Vec3::new(0.0, 0.0, 1.0), true), (Vec3::new(0.6, 0.8, 0.0), false)] {
        let d = Quat::from_axis_angle(axis, eps) * q;
        let dq = [d.w - q.w, d.x - q.x, d.y - q.y, d.z - q.z];
        for (j, col) in f.p.qq.iter_mut().enumerate() {
            *col = f64x4::new(dq.map(|v| v * dq[j]));
        }
        let (heading, inclination) = f.attitude_sigmas();
        let (along, across) = if vertical { (heading, inclination) } else { (inclination, heading) };
        assert!((along - eps).abs() < 1e-6 * eps, "{axis:?}: {along} {across}");
        assert!(across < 1e-6 * eps, "{axis:?}: {across}");
    }
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn covariance_stays_symmetric_positive_definite() {
    let mut f = Ekf::new(EkfSettings::default());
    let truth = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 0.5), 0.4);
    for i in 0..3000 {
        let t = i as f64 * 0.01;
        let accel = truth.rotate_inverse(Vec3::new(0.3 * t.sin(), 0.0, -9.80665));
        let mag = truth.rotate_inverse(Vec3::new(20.0, 0.0, 40.0));
        f.update(0.01, Vec3::new(0.01, 0.0, -0.02), Some(accel), Some(mag)).unwrap();
    }
    let p = f.covariance();
    assert!((p - p.transpose()).abs().max() == 0.0);
    assert!(p.cholesky().is_some());
    assert!((f.quaternion().norm() - 1.0).abs() < 1e-12);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn adaptive_noise_keeps_sustained_acceleration_out_of_the_attitude() {
    // Level and still, then 3 s of a steady 4 m/s² push along north (NED x): an
    // accelerometer-only tilt of 22°. The adaptive variance must keep the estimate
    // closer to level than the fixed-noise filter does (both follow the push in the
    // end: over tens of seconds a push is indistinguishable from a tilt).
    let tilt_after = |settings: EkfSettings| {
        let mut f = Ekf::new(settings);
        f.set_quaternion(Quat::IDENTITY);
        let up = Vec3::new(0.0, 0.0, -9.80665);
        for i in 0..1300 {
            let push = if i >= 1000 { Vec3::new(-4.0, 0.0, 0.0) } else { Vec3::ZERO };
            f.update(0.01, Vec3::ZERO, Some(up + push), None).unwrap();
        }
        let q = f.quaternion();
        let down = q.rotate(Vec3::new(0.0, 0.0, 1.0));
        libm::acos(down.z.clamp(-1.0, 1.0)).to_degrees()
    };
    let fixed = tilt_after(EkfSettings { accel_adapt_tau: 0.0, ..Default::default() });
    let adaptive = tilt_after(EkfSettings::default());
    assert!(adaptive < 0.7 * fixed, "adaptive {adaptive:.2} deg, fixed {fixed:.2} deg");
}
