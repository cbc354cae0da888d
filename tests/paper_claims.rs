//! The seed kinds against their papers' claims, on the papers' own protocols simulated
//! with exact truth (tests/common/sim.rs). Where a faithful implementation does not
//! reach a claim, the test asserts what it does reach and docs/ACCURACY.md ("Paper
//! claims") says which statement of the paper the figure contradicts.

mod common;

use common::sim::{self, inclination_error, Run};
use orient::{Config, Filter, Kind, Quat, Vec3};

/// Runs `kind` (defaults, with `set` applied) over a run; the estimate after each sample.
fn run(kind: Kind, set: &[(&str, f64)], r: &Run, with_mag: bool) -> (Vec<Quat>, Vec<Vec3>) {
    let mut c = Config::new(kind).unwrap();
    for (k, v) in set {
        c.set(k, *v).unwrap().unwrap();
    }
    let mut f = Filter::new(&c).unwrap();
    let mut bias = Vec::with_capacity(r.samples.len());
    let est = r
        .samples
        .iter()
        .map(|s| {
            let mut s = *s;
            if !with_mag {
                s.mag = None;
            }
            f.update(&s).unwrap();
            bias.push(f.diagnostics().gyro_bias);
            f.quaternion()
        })
        .collect();
    (est, bias)
}

/// RMS in degrees of `err` over the samples whose time passes `keep`.
fn rms(est: &[Quat], r: &Run, keep: impl Fn(f64) -> bool, err: impl Fn(Quat, Quat) -> f64) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for ((e, t), time) in est.iter().zip(&r.truth).zip(&r.t) {
        if keep(*time) {
            s += err(*e, *t).powi(2);
            n += 1;
        }
    }
    (s / n as f64).sqrt().to_degrees()
}

fn total(a: Quat, b: Quat) -> f64 {
    a.angle_to(b)
}

/// Heading error (rad, signed): rotation about the earth's vertical between the two.
fn heading(est: Quat, truth: Quat) -> f64 {
    let e = est * truth.conj();
    2.0 * e.z.atan2(e.w)
}

#[test]
fn madgwick_hand_held_at_256_hz_and_64_hz() {
    let at = |rate: f64| {
        let r = sim::hand_held(rate);
        let (est, _) = run(Kind::Madgwick, &[], &r, true);
        rms(&est, &r, |t| t > 10.0, total)
    };
    let (e256, e64) = (at(256.0), at(64.0));
    println!("Madgwick MARG hand-held: 256 Hz {e256:.3}°, 64 Hz {e64:.3}°");
    // Claim (abstract, Table I): < 2° RMS hand-held at 256 Hz, and 64 Hz within 10 %.
    assert!(e256 <= 2.0, "256 Hz: {e256:.3}°");
    assert!((e64 - e256).abs() <= 0.1 * e256, "64 Hz {e64:.3}° against 256 Hz {e256:.3}°");
}

#[test]
fn mahony_hand_held_at_256_hz() {
    let r = sim::hand_held(256.0);
    let (est, _) = run(Kind::Mahony, &[], &r, true);
    let e = rms(&est, &r, |t| t > 10.0, total);
    println!("Mahony MARG hand-held 256 Hz: {e:.3}°");
    assert!(e <= 3.0, "{e:.3}°");
}

#[test]
fn mcginnis_up_down_inclination_and_rifle_heading_drift() {
    let (r, _) = sim::up_down();
    let (est, _) = run(Kind::Complementary, &[], &r, false);
    let incl = rms(&est, &r, |t| t > 5.0, inclination_error);
    let (r2, _) = sim::rifle_aiming();
    let (est2, _) = run(Kind::Complementary, &[], &r2, false);
    let h0 = heading(est2[(5.0 * 100.0) as usize], r2.truth[(5.0 * 100.0) as usize]);
    let drift = est2
        .iter()
        .zip(&r2.truth)
        .map(|(e, t)| (heading(*e, *t) - h0).abs())
        .fold(0.0, f64::max)
        .to_degrees();
    println!("McGinnis: up-down inclination RMS {incl:.3}°, rifle heading drift {drift:.3}°");
    assert!(incl <= 1.0, "up-down inclination {incl:.3}°");
    assert!(drift <= 2.7, "rifle heading drift {drift:.3}°");
}

/// The EKF's drift estimate against the truth: the largest per-axis error (°/s) from
/// 10 s on, and the inclination RMS (°) over the run.
fn ekf_drift(set: &[(&str, f64)]) -> (f64, f64) {
    let (r, drift) = sim::drifting_bias();
    let (est, bias) = run(Kind::Ekf, set, &r, false);
    let worst = bias
        .iter()
        .zip(&drift)
        .zip(&r.t)
        .filter(|(_, t)| **t >= 10.0)
        .map(|((b, d), _)| {
            let e = *b - *d;
            e.x.abs().max(e.y.abs()).max(e.z.abs())
        })
        .fold(0.0, f64::max)
        .to_degrees();
    (worst, rms(&est, &r, |_| true, inclination_error))
}

#[test]
fn ekf_tracks_a_drifting_bias_within_ten_seconds() {
    // The paper's measurement model: accelerometer noise only (accel_motion = 0).
    let (worst, incl) = ekf_drift(&[("accel_motion", 0.0)]);
    // orient's default adds 0.5 m/s² for linear acceleration, which slows the drift
    // estimate: the accelerometer is trusted less.
    let (worst_d, incl_d) = ekf_drift(&[]);
    println!("EKF drift after 10 s: paper's model {worst:.3}°/s ({incl:.3}°), defaults {worst_d:.3}°/s ({incl_d:.3}°)");
    // Claim (section 5, Fig. 4): within 0.2°/s after 10 s. Measured 0.23-0.25°/s at the
    // worst instant of one axis (docs/ACCURACY.md).
    assert!(worst <= 0.26, "paper's model: drift estimate off by {worst:.3}°/s");
    assert!(incl <= 1.0 && incl_d <= 1.0, "inclination {incl:.3}° / {incl_d:.3}°");
    assert!(worst_d <= 2.0, "defaults: drift estimate off by {worst_d:.3}°/s");
}

#[test]
fn gmvdk_at_the_disturbed_location_and_still() {
    // A distortion of 1 µT turns the horizontal field (20 µT) by 2.9°; 5 µT by 14°.
    let at_b = |size: f64| {
        let (r, b) = sim::disturbed_pose_sequence(Vec3::new(size, 0.0, 0.0));
        let (est, _) = run(Kind::Gmvdk, &[], &r, true);
        (rms(&est, &r, |t| t > 5.0 && t < b - 3.0, total), rms(&est, &r, |t| t > b, total))
    };
    let (a1, b1) = at_b(1.0);
    let (_, b5) = at_b(5.0);
    println!("GMVDK: Location A {a1:.3}°, Location B {b1:.3}° (1 µT), {b5:.3}° (5 µT)");
    assert!(a1 <= 0.45 && b1 <= 3.0, "A {a1:.3}°, B {b1:.3}°");
    // A static distortion is followed: the error at B is the field's turn, atan(5/20).
    let turn = (5.0f64 / 20.0).atan().to_degrees();
    assert!((b5 - turn).abs() < 0.1 * turn, "B {b5:.3}° against the field's turn {turn:.3}°");

    // The long static test (section 3.3: 0.4447° RMS over 10 h): an hour here, with the
    // bias estimate checked too (true 0.002 rad/s; issue 19 saw a day-long run's drift to
    // -0.08 rad/s).
    let bias = Vec3::new(0.002, 0.0, 0.0);
    let q0 = Quat::from_axis_angle(Vec3::new(0.3, -0.2, 1.0), 0.4);
    let r =
        sim::simulate(q0, 3600.0, 100.0, (0.0016, 0.03, 0.3), |_| sim::Moment { bias, ..Default::default() });
    let (est, b) = run(Kind::Gmvdk, &[], &r, true);
    let still = rms(&est, &r, |t| t > 5.0, total);
    let worst_bias = b.iter().skip(1000).map(|x| (*x - bias).norm()).fold(0.0, f64::max);
    println!("GMVDK static hour: {still:.3}° RMS, worst bias error {worst_bias:.5} rad/s");
    assert!(still <= 0.45, "{still:.3}°");
    assert!(worst_bias < 0.002, "bias error {worst_bias} rad/s");
}
