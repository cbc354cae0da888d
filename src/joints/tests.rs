use super::estimator::DEG;
use super::*;

const G: f64 = 9.81;
const X: Vec3 = Vec3::new(1.0, 0.0, 0.0);
const Y: Vec3 = Vec3::new(0.0, 1.0, 0.0);
const Z: Vec3 = Vec3::new(0.0, 0.0, 1.0);

fn rot(axis: Vec3, angle: f64) -> Quat {
    Quat::from_axis_angle(axis, angle)
}

fn hinge(parent: usize, child: usize, axis: Vec3) -> JointSpec {
    JointSpec { kind: JointKind::Hinge, parent, child, axis_parent: axis, axis_child: axis }
}

/// Body rates (rad/s) that take `a` to `b` in `dt`.
fn rate(a: Quat, b: Quat, dt: f64) -> Vec3 {
    let d = (a.conj() * b).normalized();
    let d = if d.w < 0.0 { d.scale(-1.0) } else { d };
    let s = d.vector().norm();
    if s < 1e-15 {
        return Vec3::ZERO;
    }
    d.vector() * (2.0 * libm::atan2(s, d.w) / s / dt)
}

/// A sample of a sensor at the joint centre (no lever arm, no linear acceleration) whose
/// orientation goes from `q0` to `q1` in `dt`.
fn sample(q0: Quat, q1: Quat, dt: f64) -> Sample {
    Sample { dt, gyro: Some(rate(q0, q1, dt)), accel: Some(q1.rotate_inverse(Z * G)), mag: None }
}

/// The parent's motion: turns about every axis, its x axis mostly horizontal.
fn parent_at(t: f64) -> Quat {
    rot(Z, 0.5 * libm::sin(0.3 * t)) * rot(Y, 0.6 * libm::sin(0.7 * t)) * rot(X, 0.4 * libm::sin(1.1 * t))
}

fn flexion_at(t: f64) -> f64 {
    0.5 + 0.8 * libm::sin(1.9 * t)
}

/// The angle (rad) of the child's orientation relative to its parent's, estimate against
/// truth.
fn relative_error(est_p: Quat, est_c: Quat, true_p: Quat, true_c: Quat) -> f64 {
    let e = (est_p.conj() * est_c).conj() * (true_p.conj() * true_c);
    2.0 * libm::atan2(e.vector().norm(), e.w.abs())
}

/// A parent and a hinged child over `seconds` at 100 Hz, the child's filter drifting in
/// heading at `drift` rad/s: the largest relative error over the last 10 s.
fn run_hinge(axis: Vec3, drift: f64, seconds: f64) -> (Joints, f64) {
    run_hinge_with(axis, drift, seconds, JointParams::default())
}

/// [`run_hinge`] with the tuning `params`.
fn run_hinge_with(axis: Vec3, drift: f64, seconds: f64, params: JointParams) -> (Joints, f64) {
    let dt = 0.01;
    let mut joints = Joints::new(2, &[hinge(0, 1, axis)], &[], params).unwrap();
    let child_at = |t: f64| parent_at(t) * rot(axis, flexion_at(t));
    let mut worst: f64 = 0.0;
    let steps = (seconds / dt) as usize;
    for i in 1..=steps {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
        // The child's filter: the truth turned about the vertical by its heading drift.
        let c_filter = rot(Z, drift * t1) * c1;
        joints.update(&[p1, c_filter], &[sample(p0, p1, dt), sample(c0, c1, dt)]).unwrap();
        if t1 > seconds - 10.0 {
            let e = relative_error(joints.sensor_quaternion(0), joints.sensor_quaternion(1), p1, c1);
            worst = worst.max(e);
        }
    }
    (joints, worst)
}

#[test]
fn a_hinge_holds_the_child_to_its_parent_while_its_heading_drifts() {
    // Alone, the child would be 30 degrees off after a minute.
    let drift = 0.5f64.to_radians();
    let (joints, worst) = run_hinge(X, drift, 60.0);
    assert!(worst < 1f64.to_radians(), "{} deg", worst.to_degrees());
    // The correction is the drift undone, and the rating says the axis told it.
    let expected = -drift * 60.0;
    assert!(
        (joints.relative_heading(0) - expected).abs() < 1f64.to_radians(),
        "{}",
        joints.relative_heading(0)
    );
    assert!(joints.rating(0) > 0.3, "{}", joints.rating(0));
    // The correction's drift is the child's heading drift, undone: within 10 % by a joint
    // that expects no learning (bias_learn_rate 0). This filter's drift stays whatever its
    // sensor turns, which no bias a filter learns from gravity does (the part of it that
    // turns into the horizontal would be learned): the default (0.1/s) expects less and
    // settles within 30 %.
    assert!((joints.drift(0) + drift).abs() < 0.3 * drift, "{}", joints.drift(0));
    let steady = JointParams { bias_learn_rate: 0.0, ..JointParams::default() };
    let (j0, worst0) = run_hinge_with(X, drift, 60.0, steady);
    assert!(worst0 < 1f64.to_radians(), "{} deg", worst0.to_degrees());
    assert!((j0.drift(0) + drift).abs() < 0.1 * drift, "{}", j0.drift(0));
}

#[test]
fn the_hinge_angle_is_the_flexion() {
    let (joints, _) = run_hinge(X, 0.0, 20.0);
    let [theta, other] = joints.angles(0);
    assert!((theta - flexion_at(20.0)).abs() < 0.5f64.to_radians(), "{theta}");
    assert!(other.is_nan());
}

#[test]
fn a_vertical_hinge_says_nothing_and_the_heading_holds() {
    // A door: the parent upright turning about the vertical, the child about the same
    // vertical axis. Nothing fixes the relative heading; it must not move.
    let dt = 0.01;
    let mut joints = Joints::new(2, &[hinge(0, 1, Z)], &[], JointParams::default()).unwrap();
    let p_at = |t: f64| rot(Z, 0.7 * libm::sin(0.9 * t));
    let c_at = |t: f64| p_at(t) * rot(Z, 0.6 * libm::sin(1.7 * t));
    let mut most: f64 = 0.0;
    for i in 1..=3000 {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let (p0, p1, c0, c1) = (p_at(t0), p_at(t1), c_at(t0), c_at(t1));
        let offset = rot(Z, 0.3);
        joints.update(&[p1, offset * c1], &[sample(p0, p1, dt), sample(c0, c1, dt)]).unwrap();
        most = most.max(joints.relative_heading(0).abs());
    }
    assert!(joints.rating(0) < 0.01, "{}", joints.rating(0));
    assert!(most < 0.5f64.to_radians(), "{} deg", most.to_degrees());
}

/// `rows` rows of 10 ms of [`run_hinge`]'s rig lying still where it was at 30 s.
fn lie_still(joints: &mut Joints, rows: usize) {
    let q = parent_at(30.0);
    let c = q * rot(X, flexion_at(30.0));
    let still = |q: Quat| Sample {
        dt: 0.01,
        gyro: Some(Vec3::ZERO),
        accel: Some(q.rotate_inverse(Z * G)),
        mag: None,
    };
    for _ in 0..rows {
        joints.update(&[q, c], &[still(q), still(c)]).unwrap();
    }
}

/// At rest the constraints are left out: without the drift measurement (`r_drift` 0)
/// nothing moves; with it, the drift the joint learned in motion (the child's filter
/// turning at 0.5 deg/s) goes, since the filters lie still without drifting.
#[test]
fn at_rest_the_estimate_holds_and_the_rating_falls() {
    for r_drift in [0.0, JointParams::default().r_drift] {
        let (mut joints, _) = run_hinge(X, 0.5f64.to_radians(), 30.0);
        joints.set_param("r_drift", r_drift).unwrap();
        // Learned in part after 30 s (0.3 deg/s without the filters' learning).
        let drift = joints.drift(0);
        assert!(drift < -0.2f64.to_radians(), "{drift}");
        // The rig stops (the rest detector needs `rest_time`), then lies still for 20 s.
        lie_still(&mut joints, 100);
        let resting = (joints.relative_heading(0), joints.drift(0));
        lie_still(&mut joints, 2000);
        if r_drift == 0.0 {
            assert_eq!((joints.relative_heading(0), joints.drift(0)), resting);
        } else {
            assert!(joints.drift(0).abs() < 0.01 * drift.abs(), "{}", joints.drift(0));
        }
        assert!(joints.rating(0) < 0.01, "{}", joints.rating(0));
    }
}

/// At rest each filter's heading turns at the gyroscope bias it leaves. Here the child's
/// filter drifts at 0.5 deg/s while the rig moves and stops drifting at rest (as a filter
/// that learns its bias at rest does): the joint measures that and goes into the next
/// motion without the old drift; without the measurement (`r_drift` 0) it carries the old
/// drift into the motion, where the constraints must undo it.
#[test]
fn at_rest_the_filters_drift_is_measured() {
    let dt = 0.01;
    let drift = 0.5f64.to_radians();
    let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
    // The rig moves from `from` to `to` s, the child's filter turned by `heading(t)`: the
    // RMS relative error.
    let moved = |joints: &mut Joints, from: f64, to: f64, heading: &dyn Fn(f64) -> f64| {
        let (mut sum, mut n) = (0.0, 0.0);
        for i in 1..=((to - from) / dt).round() as usize {
            let (t0, t1) = (from + (i - 1) as f64 * dt, from + i as f64 * dt);
            let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
            joints
                .update(&[p1, rot(Z, heading(t1)) * c1], &[sample(p0, p1, dt), sample(c0, c1, dt)])
                .unwrap();
            let e = relative_error(joints.sensor_quaternion(0), joints.sensor_quaternion(1), p1, c1);
            sum += e * e;
            n += 1.0;
        }
        (sum / n).sqrt()
    };
    // A drift that stays whatever the sensor turns: the joint that expects it
    // (bias_learn_rate 0, as in a_hinge_holds_the_child_to_its_parent_while_its_heading_drifts).
    let steady = JointParams { bias_learn_rate: 0.0, ..JointParams::default() };
    let run = |params: JointParams| {
        let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[], params).unwrap();
        moved(&mut joints, 0.0, 60.0, &|t| drift * t);
        let learned = joints.drift(0);
        // 10 s still at 60 s; the child's filter keeps the heading it had.
        let (p, c) = (parent_at(60.0), child_at(60.0));
        let still =
            |q: Quat| Sample { dt, gyro: Some(Vec3::ZERO), accel: Some(q.rotate_inverse(Z * G)), mag: None };
        for _ in 0..1000 {
            joints.update(&[p, rot(Z, drift * 60.0) * c], &[still(p), still(c)]).unwrap();
        }
        let after_rest = joints.drift(0);
        // The motion goes on from where it stopped, the child's filter no longer drifting.
        let rms = moved(&mut joints, 60.0, 70.0, &|_| drift * 60.0);
        (learned, after_rest, rms)
    };
    let (learned, measured, rms_with) = run(steady);
    let (_, kept, rms_without) = run(JointParams { r_drift: 0.0, ..steady });
    // With every default the rest measures what the motion left just as well.
    let (learned_default, measured_default, _) = run(JointParams::default());
    assert!((learned_default + drift).abs() < 0.3 * drift, "{learned_default}");
    assert!(measured_default.abs() < 0.01 * drift, "{measured_default}");
    // The drift learned in motion: the child's filter's 0.5 deg/s, negated.
    assert!((learned + drift).abs() < 0.1 * drift, "{learned}");
    // Measured at rest: none left (0.0003 deg/s); without the measurement, kept.
    assert!(measured.abs() < 0.01 * drift, "{measured}");
    assert!((kept - learned).abs() < 0.01 * drift, "{kept}");
    // And the next motion starts without it (RMS 1.06 deg against 1.20).
    assert!(rms_with < 0.95 * rms_without, "{rms_with} {rms_without}");
}

/// The rating is a low-pass over `rating_tau` of what the constraints told: at rest they
/// tell nothing, and it decays by `1 − α` a row, `α = dt / (rating_tau + dt)` (once: an
/// earlier version decayed it twice a row, at half the documented time constant).
#[test]
fn at_rest_the_rating_decays_with_its_time_constant() {
    let (mut joints, _) = run_hinge(X, 0.5f64.to_radians(), 30.0);
    let prm = JointParams::default();
    lie_still(&mut joints, (prm.rest_time / 0.01).ceil() as usize + 1);
    let r0 = joints.rating(0);
    assert!(r0 > 0.1, "{r0}");
    let rows = (prm.rating_tau / 0.01) as i32;
    lie_still(&mut joints, rows as usize);
    let alpha = 0.01 / (prm.rating_tau + 0.01);
    let want = r0 * (1.0 - alpha).powi(rows);
    assert!((joints.rating(0) - want).abs() <= 1e-12 * r0, "{} vs {want}", joints.rating(0));
    // About e⁻¹ of where it was after one time constant.
    assert!((joints.rating(0) / r0 - (-1f64).exp()).abs() < 0.01, "{}", joints.rating(0) / r0);
}

#[test]
fn a_chain_composes_the_corrections_down_from_its_root() {
    // Segment 2 hangs from 1, which hangs from 0: listed child first, estimated in order.
    let joints = [hinge(1, 2, X), hinge(0, 1, X)];
    let mut rig = Joints::new(3, &joints, &[], JointParams::default()).unwrap();
    let dt = 0.01;
    let at = |t: f64| {
        let p = parent_at(t);
        let c = p * rot(X, flexion_at(t));
        (p, c, c * rot(X, 0.3 * flexion_at(t + 1.0)))
    };
    for i in 1..=1000 {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let ((p0, c0, g0), (p1, c1, g1)) = (at(t0), at(t1));
        let drift = |k: f64| rot(Z, k * 0.01 * t1);
        let sensors = [p1, drift(1.0) * c1, drift(-1.0) * g1];
        rig.update(&sensors, &[sample(p0, p1, dt), sample(c0, c1, dt), sample(g0, g1, dt)]).unwrap();
    }
    assert_eq!(rig.correction(0), Quat::IDENTITY);
    let own = |k: usize| rot(Z, rig.relative_heading(k));
    let chained = rig.correction(1) * own(0);
    let d = chained.conj() * rig.correction(2);
    assert!(d.vector().norm() < 1e-3, "{d:?}");
    let ((_, _, _), (p, c, g)) = (at(0.0), at(10.0));
    for (est, truth) in [(1, c), (2, g)] {
        let e = relative_error(rig.sensor_quaternion(0), rig.sensor_quaternion(est), p, truth);
        assert!(e < 1.5f64.to_radians(), "segment {est}: {} deg", e.to_degrees());
    }
}

#[test]
fn two_dof_angles_are_the_turns_about_the_two_axes() {
    for (alpha, beta) in [(0.3, -0.2), (-1.0, 0.7), (0.0, 0.0), (1.2, 1.1)] {
        let q_p = parent_at(alpha * 3.0);
        let q_c = q_p * rot(Z, alpha) * rot(X, beta);
        let [a, b] = angles(JointKind::TwoDof, Z, X, Quat::IDENTITY, Quat::IDENTITY, q_p, q_c);
        assert!((a - alpha).abs() < 1e-12 && (b - beta).abs() < 1e-12, "{a} {b} for {alpha} {beta}");
    }
}

#[test]
fn angles_are_zero_in_the_reference_pose_whatever_the_mountings() {
    let (m_p, m_c) = (rot(Vec3::new(1.0, 2.0, 3.0), 0.7), rot(Vec3::new(-1.0, 0.5, 0.2), 1.9));
    // The reference pose: both segments' frames the same, q_sensor = q_segment ⊗ m.
    let seg = parent_at(1.3);
    let (q_p, q_c) = (seg * m_p, seg * m_c);
    for kind in [JointKind::Hinge, JointKind::TwoDof] {
        let r = angles(kind, X, Y, m_p, m_c, q_p, q_c);
        assert!(r[0].abs() < 1e-12, "{kind:?} {r:?}");
        assert!(kind == JointKind::Hinge || r[1].abs() < 1e-12, "{kind:?} {r:?}");
    }
}

#[test]
fn a_segment_is_its_corrected_sensor_with_the_mounting_applied() {
    let m = rot(Vec3::new(0.3, -1.0, 0.4), 0.8);
    let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[Quat::IDENTITY, m], JointParams::default()).unwrap();
    let (p, c) = (parent_at(0.5), parent_at(0.9));
    let s = |q: Quat| Sample {
        dt: 0.01,
        gyro: Some(Vec3::new(1.0, 0.0, 0.0)),
        accel: Some(q.rotate_inverse(Z * G)),
        mag: None,
    };
    joints.update(&[p, c], &[s(p), s(c)]).unwrap();
    let expected = (joints.correction(1) * c * m.conj()).normalized();
    assert!(joints.segment_quaternion(1).angle_to(expected) < 1e-12);
    assert!(joints.segment_quaternion(0).angle_to(p) < 1e-12);
}

#[test]
fn bad_rigs_are_refused_naming_the_joint() {
    let p = JointParams::default();
    let ok = hinge(0, 1, X);
    let cases: [(usize, Vec<JointSpec>, JointError); 7] = [
        (2, vec![hinge(0, 2, X)], JointError::NoSuchSegment(0)),
        (2, vec![hinge(1, 1, X)], JointError::OwnParent(0)),
        (3, vec![ok, hinge(2, 1, X)], JointError::TwoParents(1)),
        (2, vec![ok, hinge(1, 0, X)], JointError::Cycle(1)),
        (4, vec![hinge(0, 1, X), hinge(1, 2, X), hinge(2, 3, X), hinge(3, 0, X)], JointError::Cycle(3)),
        (2, vec![hinge(0, 1, Vec3::ZERO)], JointError::BadAxis(0)),
        (2, vec![JointSpec { axis_child: Vec3::new(f64::NAN, 0.0, 1.0), ..ok }], JointError::BadAxis(0)),
    ];
    for (segments, joints, error) in cases {
        assert_eq!(Joints::new(segments, &joints, &[], p).unwrap_err(), error, "{joints:?}");
    }
    let many = vec![ok; MAX_JOINTS + 1];
    assert_eq!(Joints::new(2, &many, &[], p).unwrap_err(), JointError::TooMany(MAX_JOINTS + 1));
    assert_eq!(Joints::new(2, &[ok], &[Quat::IDENTITY], p).unwrap_err(), JointError::WrongLength(1));
    let zero = Quat::new(0.0, 0.0, 0.0, 0.0);
    assert_eq!(Joints::new(2, &[ok], &[Quat::IDENTITY, zero], p).unwrap_err(), JointError::BadMounting(1));
    for bad in [
        JointParams { gate: 0.0, ..p },
        JointParams { q_rate: -1.0, ..p },
        JointParams { r_acc: f64::NAN, ..p },
        JointParams { max_rate: 0.0, ..p },
        JointParams { acc_rate_scale: 0.0, ..p },
        JointParams { acc_accel_scale: 0.0, ..p },
    ] {
        assert_eq!(Joints::new(2, &[ok], &[], bad).unwrap_err(), JointError::BadParams);
    }
    // Axes: any squared norm that is a normal finite double.
    let tiny = Vec3::new(1e-150, 0.0, 0.0);
    assert!(Joints::new(2, &[hinge(0, 1, tiny)], &[], p).is_ok());
    for bad in [Vec3::new(1e-170, 0.0, 0.0), Vec3::new(1e200, 0.0, 0.0)] {
        assert_eq!(Joints::new(2, &[hinge(0, 1, bad)], &[], p).unwrap_err(), JointError::BadAxis(0));
    }
    assert_eq!(
        Joints::new(MAX_SEGMENTS + 1, &[ok], &[], p).unwrap_err(),
        JointError::TooManySegments(MAX_SEGMENTS + 1)
    );
    // A forest: two roots, and a segment in no joint.
    assert!(Joints::new(5, &[ok, hinge(2, 3, Y)], &[], p).is_ok());
}

#[test]
fn a_bad_row_changes_nothing() {
    let (mut joints, _) = run_hinge(X, 0.01, 5.0);
    // Debug's text: a hinge's second angle is NaN, which `==` never equals.
    let before = format!("{joints:?}");
    let heading = joints.relative_heading(0);
    let q = parent_at(5.0);
    let good = Sample { dt: 0.01, gyro: Some(X), accel: Some(Z * G), mag: None };
    let nan = Vec3::new(f64::NAN, 0.0, 0.0);
    let rows: [(Vec<Quat>, Vec<Sample>, JointError); 5] = [
        (vec![q], vec![good, good], JointError::WrongLength(1)),
        (vec![q, q], vec![good], JointError::WrongLength(1)),
        (vec![q, Quat::new(f64::NAN, 0.0, 0.0, 0.0)], vec![good, good], JointError::NonFinite(1)),
        (vec![q, Quat::new(0.0, 0.0, 0.0, 0.0)], vec![good, good], JointError::NonFinite(1)),
        (vec![q, q], vec![Sample { gyro: Some(nan), ..good }, good], JointError::NonFinite(0)),
    ];
    for (sensors, samples, error) in rows {
        assert_eq!(joints.update(&sensors, &samples), Err(error));
        assert_eq!(format!("{joints:?}"), before);
    }
    // A row without an accelerometer reading is accepted: the joint holds.
    let gyro_only = Sample { accel: None, ..good };
    joints.update(&[q, q], &[gyro_only, gyro_only]).unwrap();
    assert_eq!(joints.relative_heading(0), heading);
}

#[test]
fn reset_starts_every_joint_over() {
    let (mut joints, _) = run_hinge(X, 0.5f64.to_radians(), 10.0);
    assert!(joints.relative_heading(0) != 0.0);
    joints.reset();
    let fresh = Joints::new(2, &[hinge(0, 1, X)], &[], JointParams::default()).unwrap();
    assert_eq!(joints.relative_heading(0), 0.0);
    assert_eq!(joints.correction(1), Quat::IDENTITY);
    assert_eq!(joints.estimators, fresh.estimators);
    // The outputs are the filters' own, uncorrected: the last orientations given.
    assert_eq!(joints.sensor_quaternion(1), joints.raw[1]);
    let [theta, other] = joints.angles(0);
    assert!(theta.is_finite() && other.is_nan());
    // A snapshot taken now loads to the same outputs.
    let mut blob = vec![0u8; joints.state_size()];
    joints.save(&mut blob).unwrap();
    let mut twin = fresh.clone();
    twin.load(&blob).unwrap();
    assert_eq!(format!("{twin:?}"), format!("{joints:?}"));
}

#[test]
fn the_hinge_axes_come_from_motion() {
    // The true axes: x in the parent's frame, and x turned by the child's mounting.
    let tilt = rot(Vec3::new(0.2, 1.0, -0.3), 0.5);
    let (jp, jc) = (X, tilt.rotate_inverse(X));
    let dt = 0.01;
    let (mut wp, mut wc) = (Vec::new(), Vec::new());
    for i in 1..=500 {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let c = |t: f64| parent_at(t) * rot(X, flexion_at(t)) * tilt;
        wp.push(rate(parent_at(t0), parent_at(t1), dt));
        wc.push(rate(c(t0), c(t1), dt));
    }
    let off = |v: Vec3| rot(Vec3::new(0.3, 0.5, 1.0).cross(v), 5f64.to_radians()).rotate(v);
    let h = estimate_hinge_axes(&wp, &wc, (off(jp), off(jc))).unwrap();
    let angle = |a: Vec3, b: Vec3| libm::atan2(a.cross(b).norm(), a.dot(b)).to_degrees();
    assert!(angle(h.axis_parent, jp) < 0.1 && angle(h.axis_child, jc) < 0.1, "{h:?}");
    assert!(h.quality < 0.01, "{h:?}");
    // Not a hinge: the child turns about two axes; the quality says so.
    let wc2: Vec<Vec3> = wc.iter().enumerate().map(|(i, w)| *w + Y * libm::sin(i as f64 * 0.05)).collect();
    let bad = estimate_hinge_axes(&wp, &wc2, (jp, jc)).unwrap();
    assert!(bad.quality > 0.1, "{bad:?}");
    // What it refuses.
    assert!(estimate_hinge_axes(&wp, &wc[1..], (jp, jc)).is_none());
    assert!(estimate_hinge_axes(&[], &[], (jp, jc)).is_none());
    assert!(estimate_hinge_axes(&wp, &wc, (Vec3::ZERO, jc)).is_none());
    let mut nan = wp.clone();
    nan[3] = Vec3::new(f64::NAN, 0.0, 0.0);
    assert!(estimate_hinge_axes(&nan, &wc, (jp, jc)).is_none());
}

/// A 2-DoF joint's sensor orientations over `seconds` at 100 Hz: the child turns about
/// `j1` (parent frame) by `alpha(t)`, then about `j2` (child frame) by `beta(t)`, from the
/// reference relative orientation `r0` (which makes `j1` and `r0 j2` perpendicular); the
/// child's orientation is seen `offset` rad off in heading.
fn two_dof_motion(
    j1: Vec3,
    j2: Vec3,
    r0: Quat,
    alpha: impl Fn(f64) -> f64,
    beta: impl Fn(f64) -> f64,
    offset: f64,
    seconds: f64,
) -> (Vec<Quat>, Vec<Quat>) {
    let n = (seconds * 100.0) as usize;
    let p: Vec<Quat> = (0..n).map(|i| parent_at(i as f64 * 0.01)).collect();
    let c = (0..n)
        .map(|i| {
            let t = i as f64 * 0.01;
            rot(Z, offset) * parent_at(t) * rot(j1, alpha(t)) * r0 * rot(j2, beta(t))
        })
        .collect();
    (p, c)
}

#[test]
fn a_two_dof_joints_axes_come_from_motion() {
    // An MCP-like joint: flexion about the parent's y, abduction about the child's z,
    // the child's sensor mounted turned.
    let r0 = rot(Vec3::new(0.3, -0.2, 1.0), 0.7);
    let j1 = Vec3::new(0.1, 1.0, 0.05).normalized();
    // A second axis perpendicular to j1 in the reference pose, in the child's frame.
    let j2 = r0.rotate_inverse(j1.cross(Vec3::new(1.0, 0.0, 0.2)).normalized());
    let flex = |t: f64| 0.6 + 0.7 * libm::sin(1.3 * t);
    let abd = |t: f64| 0.25 * libm::sin(2.1 * t + 0.4);
    let (p, c) = two_dof_motion(j1, j2, r0, flex, abd, 0.7, 10.0);
    let off = |v: Vec3, by: f64| rot(Vec3::new(0.3, 0.5, 1.0).cross(v), by.to_radians()).rotate(v);
    let angle = |a: Vec3, b: Vec3| libm::atan2(a.cross(b).norm(), a.dot(b)).to_degrees();
    for by in [5.0, 15.0] {
        let h = estimate_two_dof_axes(&p, &c, (off(j1, by), off(j2, -by))).unwrap();
        assert!(angle(h.axis_parent, j1) < 0.01 && angle(h.axis_child, j2) < 0.01, "{by}: {h:?}");
        assert!(h.quality < 0.05, "{h:?}");
    }
    // On the guess's side.
    let h = estimate_two_dof_axes(&p, &c, (-off(j1, 10.0), off(j2, 10.0))).unwrap();
    assert!(angle(h.axis_parent, -j1) < 0.01 && angle(h.axis_child, j2) < 0.01, "{h:?}");
    // Soft tissue: each orientation wobbles by a degree or so; the axes stay within one.
    let wobble = |q: Quat, i: usize| {
        let k = i as f64;
        rot(Vec3::new(libm::sin(0.7 * k), libm::cos(1.3 * k), libm::sin(2.9 * k)), 0.02 * libm::sin(0.05 * k))
            * q
    };
    let pw: Vec<Quat> = p.iter().enumerate().map(|(i, q)| wobble(*q, i)).collect();
    let cw: Vec<Quat> = c.iter().enumerate().map(|(i, q)| wobble(*q, i + 7)).collect();
    let h = estimate_two_dof_axes(&pw, &cw, (off(j1, 10.0), off(j2, 10.0))).unwrap();
    assert!(angle(h.axis_parent, j1) < 1.0 && angle(h.axis_child, j2) < 1.0, "{h:?}");
    assert!(h.quality < 0.1, "{h:?}");
    // A hinge (no abduction) leaves the second axis free: the quality says so.
    let (p1, c1) = two_dof_motion(j1, j2, r0, flex, |_| 0.0, 0.7, 10.0);
    let hinge = estimate_two_dof_axes(&p1, &c1, (off(j1, 10.0), off(j2, 10.0))).unwrap();
    assert!(hinge.quality > 0.1, "{hinge:?}");
    // A ball joint (a third turn about the child's own axis) is no 2-DoF joint.
    let twist = |i: usize| rot(j1.cross(j2).normalized(), 0.5 * libm::sin(0.9 * i as f64 * 0.01));
    let c3: Vec<Quat> = c.iter().enumerate().map(|(i, q)| *q * twist(i)).collect();
    let ball = estimate_two_dof_axes(&p, &c3, (off(j1, 10.0), off(j2, 10.0))).unwrap();
    assert!(ball.quality > 0.1, "{ball:?}");
    // What it refuses.
    let (y, z) = (Y, Z);
    assert!(estimate_two_dof_axes(&p, &c[1..], (y, z)).is_none());
    assert!(estimate_two_dof_axes(&[], &[], (y, z)).is_none());
    assert!(estimate_two_dof_axes(&p, &c, (Vec3::ZERO, z)).is_none());
    assert!(estimate_two_dof_axes(&p, &c, (y, Vec3::new(f64::NAN, 0.0, 0.0))).is_none());
    let mut bad = p.clone();
    bad[3] = Quat::new(0.0, 0.0, 0.0, 0.0);
    assert!(estimate_two_dof_axes(&bad, &c, (y, z)).is_none());
    bad[3] = Quat::new(f64::INFINITY, 0.0, 0.0, 0.0);
    assert!(estimate_two_dof_axes(&bad, &c, (y, z)).is_none());
}

#[test]
fn a_snapshot_continues_bit_for_bit_and_bad_blobs_change_nothing() {
    let (mut joints, _) = run_hinge(X, 0.5f64.to_radians(), 30.0);
    let mut blob = vec![0u8; joints.state_size()];
    assert_eq!(joints.save(&mut blob[..10]), Err(StateError::BufferTooSmall(blob.len())));
    assert_eq!(joints.save(&mut blob), Ok(blob.len()));
    let mut twin = Joints::new(2, &[hinge(0, 1, X)], &[], JointParams::default()).unwrap();
    twin.load(&blob).unwrap();
    assert_eq!(format!("{twin:?}"), format!("{joints:?}"));
    // Both go on alike.
    let dt = 0.01;
    for i in 1..=300 {
        let (t0, t1) = (30.0 + (i - 1) as f64 * dt, 30.0 + i as f64 * dt);
        let (p0, p1) = (parent_at(t0), parent_at(t1));
        let (c0, c1) = (parent_at(t0) * rot(X, flexion_at(t0)), parent_at(t1) * rot(X, flexion_at(t1)));
        let row = [sample(p0, p1, dt), sample(c0, c1, dt)];
        let sensors = [p1, rot(Z, 0.01 * t1) * c1];
        joints.update(&sensors, &row).unwrap();
        twin.update(&sensors, &row).unwrap();
    }
    assert_eq!(format!("{twin:?}"), format!("{joints:?}"));

    let before = format!("{twin:?}");
    let mut refused = |b: &[u8], e: StateError| {
        assert_eq!(twin.load(b), Err(e));
        assert_eq!(format!("{twin:?}"), before);
    };
    refused(&blob[..blob.len() - 1], StateError::Truncated);
    refused(&blob[..5], StateError::Truncated);
    let mut flipped = blob.clone();
    flipped[40] ^= 1;
    refused(&flipped, StateError::Checksum);
    // Another rig's blob: a 2-DoF joint, other axes, other mountings.
    let other = Joints::new(
        2,
        &[JointSpec { kind: JointKind::TwoDof, ..hinge(0, 1, X) }],
        &[],
        JointParams::default(),
    )
    .unwrap();
    let mut b2 = vec![0u8; other.state_size()];
    other.save(&mut b2).unwrap();
    refused(&b2, StateError::Corrupt);
    let other = Joints::new(2, &[hinge(0, 1, Y)], &[], JointParams::default()).unwrap();
    other.save(&mut b2).unwrap();
    refused(&b2, StateError::Corrupt);
    let m = [Quat::IDENTITY, rot(X, 0.1)];
    let other = Joints::new(2, &[hinge(0, 1, X)], &m, JointParams::default()).unwrap();
    other.save(&mut b2).unwrap();
    refused(&b2, StateError::Corrupt);
    // A filter's blob.
    let f = Filter::new(&crate::filters::Config::new(crate::filters::Kind::Madgwick).unwrap()).unwrap();
    let mut fb = vec![0u8; f.state_size()];
    f.save(&mut fb).unwrap();
    refused(&fb, StateError::Kind(1));
    // States no estimate could hold, sealed with a good checksum.
    for how in 0..9 {
        let mut bad = joints.clone();
        bad.estimators[0].corrupt_for_test(how);
        let mut b3 = vec![0u8; bad.state_size()];
        bad.save(&mut b3).unwrap();
        refused(&b3, StateError::Corrupt);
    }
}

#[test]
fn segment_axes_go_into_the_sensor_frames_through_the_mountings() {
    // The child's sensor sits a quarter turn about z on its segment: the segment's x is
    // the sensor's -y; the parent's sensor is the segment.
    let m = rot(Z, core::f64::consts::FRAC_PI_2);
    let j = hinge(0, 1, X).in_sensor_frames(Quat::IDENTITY, m);
    assert!((j.axis_parent - X).norm() < 1e-15);
    assert!((j.axis_child - Vec3::new(0.0, -1.0, 0.0)).norm() < 1e-15, "{:?}", j.axis_child);
    // Back through the mounting: the segment's axis.
    assert!((m.rotate(j.axis_child) - X).norm() < 1e-15);
}

/// A hinge whose child's filter is `offset` off in heading from the start, over
/// `seconds`: the relative heading at the end and at `probe` s, each row's step checked
/// against the bound (max_rate * dt, besides the drift the prediction adds).
fn take_up(params: JointParams, offset: f64, seconds: f64, probe: f64) -> (f64, f64) {
    let dt = 0.01;
    let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[], params).unwrap();
    let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
    let (mut last, mut at_probe) = (0.0, 0.0);
    for i in 1..=(seconds / dt) as usize {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
        joints.update(&[p1, rot(Z, offset) * c1], &[sample(p0, p1, dt), sample(c0, c1, dt)]).unwrap();
        let h = joints.relative_heading(0);
        let bound = (params.max_rate + 1.1 * joints.drift(0).abs()) * dt;
        assert!((h - last).abs() <= bound, "row {i}: {last} -> {h}, drift {}", joints.drift(0));
        last = h;
        if i == (probe / dt) as usize {
            at_probe = h;
        }
    }
    (last, at_probe)
}

#[test]
fn a_large_offset_is_taken_up_without_a_jump() {
    let offset = 30f64.to_radians();
    // The defaults expect headings aligned (heading_std0 1 degree): the innovations of a
    // 30 degree error lie far outside the gate and the axes' refinement takes part of
    // it, so it is taken up slowly (24.8 degrees of the 30 after two minutes): the
    // headings are to be aligned first (docs/C-API.md).
    let (last, _) = take_up(JointParams::default(), offset, 120.0, 0.0);
    assert!((last + offset).abs() < 0.25 * offset, "{} deg", last.to_degrees());
    // Told that the heading may be 30 degrees off (heading_std0), the joint turns at up
    // to the bound (5 degrees a second) and is within a degree in 20 s.
    let wide = JointParams { heading_std0: offset, ..JointParams::default() };
    let (last, at_4s) = take_up(wide, offset, 20.0, 4.0);
    assert!((last + offset).abs() < 1f64.to_radians(), "{} deg", last.to_degrees());
    assert!(at_4s < -15f64.to_radians(), "{} deg after 4 s", at_4s.to_degrees());
}

#[test]
fn headings_not_aligned_are_acquired_within_a_minute() {
    use estimator::{ACQUIRE_RATE, ACQUIRE_STD, ACQUIRE_TIME};
    // Told that the headings are unknown (heading_std0 above 45 degrees, here 180), a
    // joint whose child's filter is 150 or 179 degrees off corrects at up to 1 rad/s for
    // its first minute of motion, then within max_rate, and is within a degree in 30 s,
    // the joint centre accelerating horizontally (both sensors sit on it), as a hand's
    // does. With that acceleration only from 65 s on (before, the hinge alone does not
    // acquire it), the heading is taken up at max_rate.
    let dt = 0.01;
    let lin = |t: f64| Vec3::new(2.0 * libm::sin(1.3 * t), 1.5 * libm::cos(0.9 * t), 0.0);
    let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
    let unknown = JointParams { heading_std0: core::f64::consts::PI, ..JointParams::default() };
    assert!(unknown.heading_std0 > ACQUIRE_STD && ACQUIRE_RATE > unknown.max_rate);
    let row = |joints: &mut Joints, i: usize, offset: f64| {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
        let a = lin(t1);
        let at =
            |q0: Quat, q1: Quat| Sample { accel: Some(q1.rotate_inverse(Z * G + a)), ..sample(q0, q1, dt) };
        joints.update(&[p1, rot(Z, offset) * c1], &[at(p0, p1), at(c0, c1)]).unwrap();
    };
    for offset in [150f64.to_radians(), 179f64.to_radians()] {
        let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[], unknown).unwrap();
        let mut last = 0.0;
        for i in 1..=9000 {
            let t1 = i as f64 * dt;
            row(&mut joints, i, offset);
            let h = joints.relative_heading(0);
            // The seconds left are counted down row by row: one row more by rounding.
            let rate = if t1 <= ACQUIRE_TIME + 1.5 * dt { ACQUIRE_RATE } else { unknown.max_rate };
            assert!((h - last).abs() <= (rate + 1.1 * joints.drift(0).abs()) * dt, "row {i}: {last} -> {h}");
            last = h;
            if t1 >= 30.0 {
                // The correction turns the child back by the offset, either way round.
                let e = libm::remainder(h + offset, 2.0 * core::f64::consts::PI);
                assert!(e.abs() < 1f64.to_radians(), "{} deg at {t1} s", h.to_degrees());
            }
        }
        // The minute of motion is over (the joint never reopened: its rows agree).
        assert_eq!(joints.estimators[0].acquiring(), 0.0);
    }
    // Rest does not count: 20 s of motion, then 30 s still take only the 0.3 s before
    // the joint rests (rest_time).
    let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[], unknown).unwrap();
    for i in 1..=2000 {
        row(&mut joints, i, 2.0);
    }
    let before = joints.estimators[0].acquiring();
    let (p, c) = (parent_at(20.0), child_at(20.0));
    let still =
        |q: Quat| Sample { dt, gyro: Some(Vec3::ZERO), accel: Some(q.rotate_inverse(Z * G)), mag: None };
    for _ in 0..3000 {
        joints.update(&[p, rot(Z, 2.0) * c], &[still(p), still(c)]).unwrap();
    }
    let left = joints.estimators[0].acquiring();
    assert!(before < ACQUIRE_TIME && (before - left - unknown.rest_time).abs() < 0.02, "{before} {left}");
    // Saved in the middle of the acquisition, loaded into new joints: the same bits on.
    let mut blob = vec![0u8; joints.state_size()];
    joints.save(&mut blob).unwrap();
    let mut twin = Joints::new(2, &[hinge(0, 1, X)], &[], unknown).unwrap();
    twin.load(&blob).unwrap();
    for i in 2001..=3000 {
        row(&mut joints, i, 2.0);
        row(&mut twin, i, 2.0);
    }
    assert_eq!(joints.relative_heading(0).to_bits(), twin.relative_heading(0).to_bits());
    assert_eq!(joints.estimators[0].acquiring().to_bits(), twin.estimators[0].acquiring().to_bits());
    // 45 degrees or less: the bound is max_rate from the start
    // (a_large_offset_is_taken_up_without_a_jump).
    let wide = JointParams { heading_std0: ACQUIRE_STD, ..JointParams::default() };
    take_up(wide, 40f64.to_radians(), 20.0, 0.0);
}

/// `for_joints` sets the table's values on the recommended kind, in range, and nothing
/// else; a kind without those parameters is left as it was.
#[test]
fn for_joints_sets_the_sensor_settings_where_the_kind_has_them() {
    use crate::filters::Kind;
    for kind in Kind::ALL {
        let before = Config::new(kind).unwrap();
        let mut c = before.clone();
        c.for_joints();
        let mut changed = 0;
        for (id, (a, b)) in before.slots().iter().zip(c.slots()).enumerate() {
            if a.to_bits() != b.to_bits() {
                let spec = kind.param(id as u32).unwrap();
                let want = &SENSOR_SETTINGS.iter().find(|s| s.name == spec.name).unwrap().value;
                assert_eq!(b.to_bits(), want.to_bits());
                assert!(spec.accepts(*want));
                changed += 1;
            }
        }
        let has = SENSOR_SETTINGS.iter().filter(|s| kind.param_by_name(s.name).is_some()).count();
        assert_eq!(changed, has, "{kind:?}");
        assert_eq!(has, if kind == Kind::Robust { SENSOR_SETTINGS.len() } else { 0 }, "{kind:?}");
    }
}

/// A robust filter (under the settings for joints or with the defaults) fed 5 s at 100 Hz
/// of a constant gyroscope reading `gyro` and gravity along its z axis: its bias at the
/// end (deg/s) and the number of rows it called rest.
fn steady_reading(gyro: Vec3, joints: bool) -> (Vec3, usize) {
    let mut c = Config::new(crate::filters::Kind::Robust).unwrap();
    if joints {
        c.for_joints();
    }
    let mut f = Filter::new(&c).unwrap();
    let s = Sample { dt: 0.01, gyro: Some(gyro), accel: Some(Vec3::new(0.0, 0.0, 9.81)), mag: None };
    let mut rest = 0;
    for _ in 0..500 {
        f.update(&s).unwrap();
        rest += usize::from(f.diagnostics().rest > 0.5);
    }
    (f.diagnostics().gyro_bias * (1.0 / DEG), rest)
}

/// A sensor whose bias is longer than the default rest threshold (2 deg/s; 3.8 deg/s here,
/// within the threshold under joints, 4 deg/s), lying still for a 5 s reference pose:
/// under the settings for joints it is found at rest and has learned its bias by the
/// pose's end; with the defaults it is never at rest and keeps most of the bias.
#[test]
fn a_bias_above_the_default_rest_threshold_is_learned_in_the_reference_pose() {
    let b = Vec3::new(2.0, -2.0, 2.5);
    let (learned, rest) = steady_reading(b * DEG, true);
    let left = (learned - b).norm();
    // Rest from 1.5 s (rest_time), the bias following with bias_tau_rest (1 s): e^(-3.5)
    // of 3.8 deg/s is 0.11 deg/s.
    assert!(rest >= 340 && left < 0.15, "under joints: {left} deg/s left, {rest} rows at rest");
    let (learned, rest) = steady_reading(b * DEG, false);
    let left = (learned - b).norm();
    assert!(rest == 0 && left > 3.0, "defaults: {left} deg/s left, {rest} rows at rest");
}

/// The cost of that threshold, as the docs state it: a turn about the vertical at 3 deg/s
/// (between the two thresholds) held for 5 s keeps the accelerometer and the rate steady,
/// so under the settings for joints it is taken for rest from 1.5 s on and learned as
/// bias; with the defaults it is not.
#[test]
fn a_slow_turn_about_the_vertical_is_taken_for_rest_under_joints() {
    let turn = Vec3::new(0.0, 0.0, 3.0 * DEG);
    let (learned, rest) = steady_reading(turn, true);
    // 350 rows at rest, the bias following with 1 s: 3 (1 - 1.01^-350) = 2.91 deg/s.
    assert!(rest >= 340 && learned.z > 2.8, "under joints: {learned:?} deg/s learned, {rest} rows at rest");
    let (learned, rest) = steady_reading(turn, false);
    assert!(rest == 0 && learned.z.abs() < 0.5, "defaults: {learned:?} deg/s learned, {rest} rows at rest");
}

/// The tuning as a table: ids in order, one entry per name, each default in its range,
/// its ranges what [`Joints::new`] accepts, and `set_param` takes a value in range, refuses
/// others (and unknown names) with nothing changed.
#[test]
fn the_parameter_table_is_the_tuning() {
    for (k, spec) in JOINT_PARAMS.iter().enumerate() {
        assert_eq!(spec.id as usize, k);
        assert!(spec.accepts(spec.default) && spec.min <= spec.max, "{}", spec.name);
        assert_eq!(JOINT_PARAMS.iter().filter(|s| s.name == spec.name).count(), 1);
    }
    let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[], JointParams::default()).unwrap();
    for spec in &JOINT_PARAMS {
        let before = joints.clone();
        for bad in [spec.min - 1e-3 * spec.min.abs().max(1e-300), spec.max * 2.0, f64::NAN, f64::INFINITY] {
            if spec.accepts(bad) {
                continue;
            }
            assert!(matches!(joints.set_param(spec.name, bad), Err(JointError::ParamOutOfRange(_))));
            assert_eq!(joints, before, "{}", spec.name);
            let params = {
                let mut p = JointParams::default();
                *p.fields_mut()[spec.id as usize] = bad;
                p
            };
            assert_eq!(Joints::new(2, &[hinge(0, 1, X)], &[], params).err(), Some(JointError::BadParams));
        }
        for good in [spec.min, spec.max, spec.default] {
            joints.set_param(spec.name, good).unwrap();
            assert_eq!(joints.param(spec.name), Some(good));
        }
        joints.set_param(spec.name, spec.default).unwrap();
    }
    assert_eq!(joints.set_param("no_such", 1.0), Err(JointError::UnknownParam));
    assert_eq!(joints.param("no_such"), None);
}

/// Filters whose headings were never aligned: told how far they may be off
/// (heading_std0 30 degrees, set before the first update, which applies it at once), a
/// hinge finds its relative heading from motion, within a degree in a minute.
#[test]
fn unaligned_headings_are_found_with_a_wide_heading_std0() {
    let dt = 0.01;
    for offset_deg in [30.0f64, 15.0, -15.0, -30.0] {
        let offset = offset_deg.to_radians();
        let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[], JointParams::default()).unwrap();
        joints.set_param("heading_std0", 30f64.to_radians()).unwrap();
        assert!((joints.heading_std(0) - 30f64.to_radians()).abs() < 1e-12);
        let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
        for i in 1..=6000 {
            let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
            let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
            joints.update(&[p1, rot(Z, offset) * c1], &[sample(p0, p1, dt), sample(c0, c1, dt)]).unwrap();
        }
        let e = joints.relative_heading(0) + offset;
        assert!(e.abs() < 1f64.to_radians(), "{offset_deg} deg: {} deg off", e.to_degrees());
    }
}

/// Each name reaches its own field: every field set by name to a value of its own, then
/// read from the struct.
#[test]
fn each_parameter_name_sets_its_own_field() {
    let mut p = JointParams::default();
    for (k, spec) in JOINT_PARAMS.iter().enumerate() {
        // A value in range that no other field gets: the minimum plus a step of its own.
        let v = spec.min + (spec.max - spec.min) * (k as f64 + 1.0) / 64.0;
        assert_eq!(p.set(spec.name, v), Some(true), "{}", spec.name);
    }
    let step = |k: usize| {
        let s = &JOINT_PARAMS[k];
        s.min + (s.max - s.min) * (k as f64 + 1.0) / 64.0
    };
    let got = [
        p.r_hinge,
        p.r_2dof,
        p.q_heading,
        p.q_rate,
        p.q_axis,
        p.heading_std0,
        p.rate_std0,
        p.axis_std0,
        p.max_rate,
        p.rest_gyro,
        p.rest_time,
        p.r_acc,
        p.acc_rate_scale,
        p.acc_accel_scale,
        p.lever_std0,
        p.q_lever,
        p.tilt_std0,
        p.q_tilt,
        p.gate,
        p.rating_tau,
        p.r_drift,
        p.bias_learn_rate,
    ];
    assert_eq!(got.len(), JOINT_PARAMS.len());
    for (k, v) in got.iter().enumerate() {
        assert_eq!(v.to_bits(), step(k).to_bits(), "{}", JOINT_PARAMS[k].name);
    }
    // Subnormal values are refused, even where the range starts at 0.
    for spec in JOINT_PARAMS.iter().filter(|s| s.min == 0.0) {
        assert_eq!(p.set(spec.name, 5e-324), Some(false), "{}", spec.name);
    }
}

/// A setting taken after updates applies from the next update on (a rest threshold above
/// any motion: the joint holds at once), and an initial standard deviation only when the
/// estimate starts again.
#[test]
fn a_setting_applies_from_the_next_update_and_an_initial_one_at_the_reset() {
    let (mut joints, _) = run_hinge(X, 0.5f64.to_radians(), 20.0);
    let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
    let dt = 0.01;
    let row = |joints: &mut Joints, i: usize| {
        let (t0, t1) = (20.0 + (i - 1) as f64 * dt, 20.0 + i as f64 * dt);
        let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
        joints
            .update(&[p1, rot(Z, 0.5f64.to_radians() * t1) * c1], &[sample(p0, p1, dt), sample(c0, c1, dt)])
            .unwrap();
    };
    let sigma = joints.heading_std(0);
    joints.set_param("heading_std0", 0.5).unwrap();
    assert_eq!(joints.heading_std(0), sigma, "kept until the estimate starts again");
    joints.set_param("rest_gyro", 100.0).unwrap();
    joints.set_param("rest_time", 0.0).unwrap();
    // (At rest only the drift measurement moves the estimate: off here.)
    joints.set_param("r_drift", 0.0).unwrap();
    let heading = joints.relative_heading(0);
    for i in 1..=100 {
        row(&mut joints, i);
    }
    assert_eq!(joints.relative_heading(0), heading, "at rest by the new threshold, the joint holds");
    joints.reset();
    assert_eq!(joints.heading_std(0), 0.5);
}

/// A rest time of 0 holds the joint whenever both gyroscopes are below the threshold, not
/// always: in motion it goes on estimating.
#[test]
fn a_zero_rest_time_still_estimates_in_motion() {
    let dt = 0.01;
    let drift = 0.5f64.to_radians();
    let params = JointParams { rest_time: 0.0, ..JointParams::default() };
    let mut joints = Joints::new(2, &[hinge(0, 1, X)], &[], params).unwrap();
    let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
    for i in 1..=6000 {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
        joints.update(&[p1, rot(Z, drift * t1) * c1], &[sample(p0, p1, dt), sample(c0, c1, dt)]).unwrap();
    }
    assert!(
        (joints.relative_heading(0) + drift * 60.0).abs() < 1f64.to_radians(),
        "{}",
        joints.relative_heading(0)
    );
    assert!(joints.rating(0) > 0.3);
}

/// A state nothing tells about (a vertical hinge, every random walk at its largest)
/// keeps a covariance a blob of it loads with: each variance held to its ceiling. Without
/// the ceiling the heading's variance passes 1e6, which no blob may hold, in about 19
/// minutes here (2/3 q_rate t³): 30 minutes are run.
#[test]
fn unobserved_states_keep_a_loadable_covariance() {
    let dt = 0.05;
    let mut params = JointParams::default();
    for name in ["q_heading", "q_rate", "q_axis", "q_lever", "q_tilt", "rate_std0", "heading_std0"] {
        let max = JOINT_PARAMS.iter().find(|s| s.name == name).unwrap().max;
        assert_eq!(params.set(name, max), Some(true));
    }
    let mut joints = Joints::new(2, &[hinge(0, 1, Z)], &[], params).unwrap();
    let p_at = |t: f64| rot(Z, 0.7 * libm::sin(0.9 * t));
    let c_at = |t: f64| p_at(t) * rot(Z, 0.6 * libm::sin(1.7 * t));
    for i in 1..=36_000 {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let (p0, p1, c0, c1) = (p_at(t0), p_at(t1), c_at(t0), c_at(t1));
        joints.update(&[p1, c1], &[sample(p0, p1, dt), sample(c0, c1, dt)]).unwrap();
    }
    let mut blob = vec![0u8; joints.state_size()];
    joints.save(&mut blob).unwrap();
    let mut twin = Joints::new(2, &[hinge(0, 1, Z)], &[], params).unwrap();
    twin.load(&blob).expect("its own blob loads");
    let mut again = vec![0u8; twin.state_size()];
    twin.save(&mut again).unwrap();
    assert!(again == blob);
    assert!(joints.heading_std(0) <= 4.0 * (1.0 + 1e-15), "{}", joints.heading_std(0));
}

/// A row whose dt is outside [1 ns, 1 s) holds the joint: nothing moves.
#[test]
fn a_dt_outside_its_range_holds_the_joint() {
    let (mut joints, _) = run_hinge(X, 0.5f64.to_radians(), 10.0);
    let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
    let (t0, t1) = (10.0, 10.01);
    let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
    // The readings of a 10 ms step, the dt given.
    let with_dt = |q0: Quat, q1: Quat, dt: f64| Sample { dt, ..sample(q0, q1, 0.01) };
    for dt in [5e-10, 1.0, 2.0, 0.0] {
        let before = (joints.relative_heading(0), joints.heading_std(0), joints.axes(0));
        joints.update(&[p1, c1], &[with_dt(p0, p1, dt), with_dt(c0, c1, dt)]).unwrap();
        assert_eq!((joints.relative_heading(0), joints.heading_std(0), joints.axes(0)), before, "dt {dt}");
    }
    // The next row's angular acceleration is not taken across the held row: the same as
    // after a row without readings.
    let mut twin = joints.clone();
    let bare = Sample { gyro: None, accel: None, ..sample(p0, p1, 0.01) };
    twin.update(&[p1, c1], &[bare, bare]).unwrap();
    let (p2, c2) = (parent_at(10.02), child_at(10.02));
    for j in [&mut joints, &mut twin] {
        j.update(&[p2, c2], &[sample(p1, p2, 0.01), sample(c1, c2, 0.01)]).unwrap();
    }
    let blob = |j: &Joints| {
        let mut b = vec![0u8; j.state_size()];
        j.save(&mut b).unwrap();
        b
    };
    assert!(blob(&joints) == blob(&twin));
    // A dt of 1 ns moves it (the estimate takes the row), a little: consistent rows with
    // one short dt among them are no contradiction (the check once compared a low-pass
    // over many rows with the short row's own dt, and widened every variance).
    let before = joints.heading_std(0);
    // The axis corrections' variances (states 7-10), which a contradiction widens to
    // axis_std0² again.
    let axis_std0 = JointParams::default().axis_std0;
    let smallest = |j: &Joints| (7..11).map(|i| j.estimators[0].variance(i)).fold(f64::MAX, f64::min);
    let least = smallest(&joints);
    assert!(least < 0.5 * axis_std0 * axis_std0, "{least}");
    joints.update(&[p1, c1], &[with_dt(p0, p1, 1e-9), with_dt(c0, c1, 1e-9)]).unwrap();
    assert_ne!(joints.heading_std(0), before);
    assert!(smallest(&joints) < 1.001 * least, "{} after {least}", smallest(&joints));
}

/// Rows that contradict themselves for minutes (rates that disagree with the
/// orientations, forces no joint centre feels, orientations at random) drove the residual
/// biases to radians a second and the tilt to turn the child upside down, so that the
/// joint's own blob no longer loaded (with the random walks but q_heading's, the residual
/// biases', lever arms' and heading's initial deviations, and max_rate at their maxima); and with the defaults
/// they turned the hinge's axes 60 deg, which good rows then moved back by a degree or two
/// a minute (6 deg off after two minutes). Both hold now.
#[test]
fn contradicting_rows_leave_a_joint_good_rows_bring_back() {
    let dt = 0.01;
    let mut widest = JointParams::default();
    for name in
        ["q_rate", "q_axis", "q_lever", "q_tilt", "rate_std0", "lever_std0", "max_rate", "heading_std0"]
    {
        let max = JOINT_PARAMS.iter().find(|s| s.name == name).unwrap().max;
        assert_eq!(widest.set(name, max), Some(true));
    }
    let two_dof = JointSpec { kind: JointKind::TwoDof, parent: 0, child: 1, axis_parent: Z, axis_child: X };
    for params in [JointParams::default(), widest] {
        for (pattern, spec) in [hinge(0, 1, X), two_dof, hinge(0, 1, X), two_dof].into_iter().enumerate() {
            let mut joints = Joints::new(2, &[spec], &[], params).unwrap();
            let mut seed = 0x9e37_79b9_7f4a_7c15u64 + pattern as u64;
            let mut uniform = move || {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            };
            let row = |g: Vec3, a: Vec3| Sample { dt, gyro: Some(g), accel: Some(a), mag: None };
            for i in 0..60_000 {
                let t = i as f64 * dt;
                let (q, samples) = if pattern < 2 {
                    // Fast rates the orientations do not show; the child's force sideways.
                    let p = parent_at(t);
                    let gp = Vec3::new(20.0 * libm::sin(9.0 * t), 5.0, 0.0);
                    let gc = Vec3::new(0.0, 20.0 * libm::cos(7.0 * t), 3.0);
                    ([p, p * rot(Y, 1.0)], [row(gp, p.rotate_inverse(Z * G)), row(gc, X * 30.0)])
                } else {
                    let mut u = [0.0; 20];
                    u.iter_mut().for_each(|x| *x = uniform());
                    let q = |k: usize| Quat::new(u[k], u[k + 1], u[k + 2], u[k + 3]).normalized();
                    let v = |k: usize, scale: f64| Vec3::new(u[k], u[k + 1], u[k + 2]) * scale;
                    ([q(0), q(4)], [row(v(8, 30.0), v(11, 100.0)), row(v(14, 30.0), v(17, 100.0))])
                };
                joints.update(&q, &samples).unwrap();
            }
            let mut blob = vec![0u8; joints.state_size()];
            joints.save(&mut blob).unwrap();
            let mut twin = Joints::new(2, &[spec], &[], params).unwrap();
            assert!(twin.load(&blob).is_ok(), "pattern {pattern}: its own blob loads");
            // Good rows: the child on its joint, the rig accelerating horizontally (what
            // a 2-DoF joint needs to tell its heading from the mirror solution).
            let child_at = |t: f64| match spec.kind {
                JointKind::Hinge => parent_at(t) * rot(X, flexion_at(t)),
                JointKind::TwoDof => parent_at(t) * rot(Z, 0.2 * libm::sin(0.5 * t)) * rot(X, flexion_at(t)),
            };
            let mut worst: f64 = 0.0;
            for i in 1..=12_000 {
                let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
                let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
                let lin = Vec3::new(2.0 * libm::sin(1.3 * t1), 2.0 * libm::cos(0.9 * t1), 0.0);
                let good = |q0: Quat, q1: Quat| Sample {
                    accel: Some(q1.rotate_inverse(Z * G + lin)),
                    ..sample(q0, q1, dt)
                };
                joints.update(&[p1, c1], &[good(p0, p1), good(c0, c1)]).unwrap();
                if t1 > 110.0 {
                    worst = worst.max(relative_error(
                        joints.sensor_quaternion(0),
                        joints.sensor_quaternion(1),
                        p1,
                        c1,
                    ));
                }
            }
            // With those maxima a 2-DoF joint's heading wanders by degrees
            // (its standard deviation is 0.2 rad on these rows).
            let bound = if params == widest && spec.kind == JointKind::TwoDof { 10.0 } else { 2.0 };
            assert!(
                worst.to_degrees() < bound,
                "pattern {pattern}: {:.2} deg off after 2 min",
                worst.to_degrees()
            );
        }
    }
}

/// Which filters learn their bias in motion, by kind and settings, and the joints taking
/// it from them: a joint updated from filters that learn none is, bit for bit, one with
/// `bias_learn_rate` 0; from filters that learn, the default's.
#[test]
fn the_joints_apply_the_learning_to_the_filters_that_learn_in_motion() {
    use crate::filters::Kind;
    let filter = |kind: Kind, set: Option<(&str, f64)>| {
        let mut c = Config::new(kind).unwrap();
        if let Some((name, value)) = set {
            c.set(name, value).unwrap().unwrap();
        }
        Filter::new(&c).unwrap()
    };
    for (kind, set, learns) in [
        (Kind::Madgwick, None, false),
        (Kind::Mahony, None, false),
        (Kind::Mahony, Some(("rest_bias_tau", 2.0)), false),
        (Kind::Mahony, Some(("ki", 0.3)), true),
        (Kind::Complementary, None, false),
        (Kind::Ekf, None, true),
        (Kind::Gmvdk, None, false),
        (Kind::Robust, None, true),
        (Kind::Robust, Some(("bias_sigma_motion", 0.0)), false),
        (Kind::Robust, Some(("bias_walk", 0.0)), false),
        (Kind::Robust, Some(("bias_sigma", 0.0)), false),
    ] {
        let mut f = [filter(kind, set), filter(kind, set)];
        assert_eq!(f[0].learns_bias_in_motion(), learns, "{kind:?} {set:?}");
        let steady = JointParams { bias_learn_rate: 0.0, ..JointParams::default() };
        let new = |p| Joints::new(2, &[hinge(0, 1, X)], &[], p).unwrap();
        let (mut from, mut without, mut with) =
            (new(JointParams::default()), new(steady), new(JointParams::default()));
        // 3 s still (the complementary filter and GMVDK start from a still period), then
        // the hinge turning.
        let dt = 0.01;
        let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
        let time = |i: usize| if i < 300 { 0.0 } else { (i - 300) as f64 * dt };
        for i in 1..=800 {
            let (t0, t1) = (time(i - 1), time(i));
            let s = [sample(parent_at(t0), parent_at(t1), dt), sample(child_at(t0), child_at(t1), dt)];
            for (f, s) in f.iter_mut().zip(&s) {
                f.update(s).unwrap();
            }
            from.update_from(&[&f[0], &f[1]], &s).unwrap();
            let q = [f[0].sensor_quaternion(), f[1].sensor_quaternion()];
            without.update(&q, &s).unwrap();
            with.update(&q, &s).unwrap();
        }
        let expected = if learns { &with } else { &without };
        assert_eq!(
            from.relative_heading(0).to_bits(),
            expected.relative_heading(0).to_bits(),
            "{kind:?} {set:?}"
        );
        assert_eq!(from.drift(0).to_bits(), expected.drift(0).to_bits(), "{kind:?} {set:?}");
        assert_ne!(with.drift(0).to_bits(), without.drift(0).to_bits(), "{kind:?} {set:?}");
    }
    // The parent's filter learning, the child's not (its heading drifts at a steady rate,
    // as run_hinge's child's does): the joint told so finds that drift within 15 % (one
    // that expects no learning at all, within 10 %), closer than the default told both
    // learn.
    let drift = 0.5f64.to_radians();
    let mut told = Joints::new(2, &[hinge(0, 1, X)], &[], JointParams::default()).unwrap();
    let dt = 0.01;
    let child_at = |t: f64| parent_at(t) * rot(X, flexion_at(t));
    for i in 1..=6000 {
        let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
        let (p0, p1, c0, c1) = (parent_at(t0), parent_at(t1), child_at(t0), child_at(t1));
        let q = [p1, rot(Z, drift * t1) * c1];
        let s = [sample(p0, p1, dt), sample(c0, c1, dt)];
        told.update_each(|k| (q[k], s[k], k == 0)).unwrap();
    }
    let (both, _) = run_hinge(X, drift, 60.0);
    let error = |j: &Joints| (j.drift(0) + drift).abs();
    assert!(error(&told) < 0.15 * drift, "{}", told.drift(0));
    assert!(error(&told) < error(&both), "{} {}", told.drift(0), both.drift(0));
}
