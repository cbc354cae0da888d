//! Issue 20: the dt = 0 policy (parameter same_instant) loses no rotation: samples that
//! arrive in bursts of four with one timestamp (dt = 0.04, 0, 0, 0) end where the same
//! samples spaced 0.01 s apart end; the default still refuses dt = 0.

mod common;

use common::sim::{simulate, Moment};
use orient::filters::params::id;
use orient::{flags, Config, Error, Filter, Kind, Quat, Sample, Vec3};

#[test]
fn bursts_lose_no_rotation() {
    // Turning about the vertical (and a little about x) at a steady rate, gyroscope only
    // after the first sample, so that only integration moves the estimate.
    let run = simulate(Quat::IDENTITY, 20.0, 100.0, (0.0, 0.0, 0.0), |_| Moment {
        omega: Vec3::new(0.05, 0.0, 0.8),
        ..Moment::default()
    });
    let imu: Vec<Sample> = run
        .samples
        .iter()
        .enumerate()
        .map(|(i, s)| Sample { accel: if i == 0 { s.accel } else { None }, mag: None, ..*s })
        .collect();
    for kind in [Kind::Madgwick, Kind::Mahony, Kind::Ekf, Kind::Robust] {
        let mut c = Config::new(kind).unwrap();
        c.set_param(id::SAME_INSTANT, 1.0).unwrap();
        let (mut even, mut burst) = (Filter::new(&c).unwrap(), Filter::new(&c).unwrap());
        even.update(&imu[0]).unwrap();
        burst.update(&imu[0]).unwrap();
        let mut same = 0;
        // Samples 1..=1996: 499 whole groups of four, the same 19.96 s in both.
        for (i, s) in imu.iter().enumerate().take(1997).skip(1) {
            even.update(s).unwrap();
            // In each group of four, the first carries the group's time.
            let dt = if i % 4 == 1 { 0.04 } else { 0.0 };
            burst.update(&Sample { dt, ..*s }).unwrap();
            same += usize::from(burst.flags() & flags::SAME_INSTANT != 0);
        }
        // The last group's three dt = 0 readings still wait (their time was integrated
        // with the group's first sample at the previous readings' average).
        let (a, b) = (even.quaternion(), burst.quaternion());
        let e = a.angle_to(b).to_degrees();
        let turned = run.truth[0].angle_to(*run.truth.last().unwrap()).to_degrees();
        println!("{kind:?}: {same} same-instant samples; bursts end {e:.4} deg from even spacing (turned {turned:.0} deg)");
        assert!(same > 1000, "{kind:?}");
        // What is left is the integrators' own error at 0.04 s steps instead of 0.01 s
        // (first order: about 0.07 deg for Madgwick and Mahony, 0.14 for the EKF, over
        // the 162 deg turned), not lost rotation.
        assert!(e < 0.2, "{kind:?}: {e} deg");
        // Without the policy the bursts' rotation would be a quarter: check it can fail.
        let mut dropped = Filter::new(&Config::new(kind).unwrap()).unwrap();
        dropped.update(&imu[0]).unwrap();
        for (i, s) in imu.iter().enumerate().take(1997).skip(1) {
            if i % 4 == 1 {
                dropped.update(&Sample { dt: 0.01, ..*s }).unwrap();
            }
        }
        assert!(dropped.quaternion().angle_to(a).to_degrees() > 10.0);
    }
}

#[test]
fn dt_zero_is_refused_by_default_and_a_burst_survives_a_snapshot() {
    let mut f = Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap();
    let s = Sample {
        dt: 0.01,
        gyro: Some(Vec3::new(0.1, 0.2, 0.3)),
        accel: Some(Vec3::new(0.0, 0.0, 9.8)),
        mag: None,
    };
    f.update(&s).unwrap();
    assert_eq!(f.update(&Sample { dt: 0.0, ..s }), Err(Error::InvalidDt(0.0)));
    f.set_param(id::SAME_INSTANT, 1.0).unwrap();
    f.update(&Sample { dt: 0.0, ..s }).unwrap();
    assert_eq!(f.update(&Sample { dt: -0.01, ..s }), Err(Error::InvalidDt(-0.01)));
    let mut blob = vec![0u8; f.state_size()];
    f.save(&mut blob).unwrap();
    let mut g = Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap();
    g.load(&blob).unwrap();
    f.update(&s).unwrap();
    g.update(&s).unwrap();
    assert_eq!(f.quaternion(), g.quaternion());
}

/// Four Madgwick filters updated as a group (the lane path) give what single updates
/// give, also with dt = 0 and clipped samples under the issue-20 policies.
#[test]
fn group_updates_follow_the_policies_like_single_updates() {
    let mut c = Config::new(Kind::Madgwick).unwrap();
    c.set_param(id::SAME_INSTANT, 1.0).unwrap();
    c.set_param(id::SATURATION_RECOVERY, 1.0).unwrap();
    c.set_param(id::GYRO_RANGE, 1.0).unwrap();
    let mut group: Vec<Filter> = (0..4).map(|_| Filter::new(&c).unwrap()).collect();
    let mut single = group.clone();
    for i in 0..40 {
        let s = Sample {
            dt: if i % 3 == 2 { 0.0 } else { 0.01 },
            gyro: Some(Vec3::new(0.1 * i as f64, 0.2, -0.1)),
            accel: Some(Vec3::new(0.3, 0.1, 9.7)),
            mag: None,
        };
        let [a, b, c2, d] = &mut group[..] else { unreachable!() };
        Filter::update_group(&mut [a, b, c2, d], [&s, &s, &s, &s]).unwrap();
        for f in single.iter_mut() {
            f.update(&s).unwrap();
        }
    }
    for (g, s) in group.iter().zip(&single) {
        assert_eq!(g.quaternion(), s.quaternion());
        assert_eq!(g.flags(), s.flags());
    }
}

fn filter_with(kind: Kind, set: &[(u32, f64)]) -> Filter {
    let mut c = Config::new(kind).unwrap();
    for &(slot, v) in set {
        c.set_param(slot, v).unwrap();
    }
    let mut f = Filter::new(&c).unwrap();
    f.update(&still(0.01)).unwrap();
    f
}

fn still(dt: f64) -> Sample {
    Sample { dt, gyro: Some(Vec3::new(0.0, 0.0, 0.1)), accel: Some(Vec3::new(0.0, 0.0, 9.81)), mag: None }
}

/// Every sample of a burst meets the rules of a lone sample: the one that closes it is
/// checked as it is, not only the average it makes.
#[test]
fn the_sample_that_closes_a_burst_is_checked_as_it_is() {
    let mut f = filter_with(Kind::Mahony, &[(id::SAME_INSTANT, 1.0), (id::GYRO_RANGE, 10.0)]);
    for _ in 0..3 {
        f.update(&still(0.0)).unwrap();
    }
    let before = f.clone();
    let hot = Sample { gyro: Some(Vec3::new(20.0, 0.0, 0.0)), ..still(0.01) };
    assert_eq!(f.update(&hot), Err(Error::Saturated(orient::Field::Gyro)));
    assert_eq!(f, before, "a refused sample changes nothing");
    let huge = Sample { gyro: Some(Vec3::new(5e4, 0.0, 0.0)), ..still(0.01) };
    let mut g = filter_with(Kind::Mahony, &[(id::SAME_INSTANT, 1.0)]);
    g.update(&still(0.0)).unwrap();
    assert_eq!(g.update(&huge), Err(Error::TooLarge(orient::Field::Gyro)));
}

/// Under the clipping policy a saturated dt = 0 sample is still checked (its clipped form)
/// and flagged; the closing sample carries the flag and the re-acquisition.
#[test]
fn a_saturated_burst_sample_is_checked_and_flagged() {
    let set = [(id::SAME_INSTANT, 1.0), (id::GYRO_RANGE, 10.0), (id::SATURATION_RECOVERY, 1.0)];
    let mut f = filter_with(Kind::Robust, &set);
    let bad = Sample {
        gyro: Some(Vec3::new(20.0, 0.0, 0.0)),
        mag: Some(Vec3::new(f64::NAN, 0.0, 0.0)),
        ..still(0.0)
    };
    assert!(f.update(&bad).is_err(), "a NaN magnetometer reading is refused inside a burst too");
    let hot = Sample { gyro: Some(Vec3::new(20.0, 0.0, 0.0)), ..still(0.0) };
    f.update(&hot).unwrap();
    assert_ne!(f.flags() & flags::SATURATED, 0);
    assert_ne!(f.flags() & flags::REACQUIRE_PENDING, 0);
}

/// reset() is the state right after new(): readings held for a burst are dropped, and so
/// are they when the policy is switched off.
#[test]
fn reset_and_switching_the_policy_off_drop_held_readings() {
    let fresh = filter_with(Kind::Madgwick, &[(id::SAME_INSTANT, 1.0)]);
    let mut f = fresh.clone();
    f.update(&Sample { gyro: Some(Vec3::new(3.0, 0.0, 0.0)), ..still(0.0) }).unwrap();
    f.reset();
    let mut g = fresh.clone();
    g.reset();
    assert_eq!(f, g);
    let mut h = fresh.clone();
    h.update(&Sample { gyro: Some(Vec3::new(3.0, 0.0, 0.0)), ..still(0.0) }).unwrap();
    h.set_param(id::SAME_INSTANT, 0.0).unwrap();
    let mut k = fresh;
    k.set_param(id::SAME_INSTANT, 0.0).unwrap();
    h.update(&still(0.01)).unwrap();
    k.update(&still(0.01)).unwrap();
    assert_eq!(h.quaternion(), k.quaternion(), "the held reading was not averaged in");
}
