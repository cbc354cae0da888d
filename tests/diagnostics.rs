//! What `flags` and `diagnostics` report, for every kind: each present reading is either
//! used or rejected, rest and magnetic disturbance are read from the kinds' detectors, and
//! a field a kind does not have is absent.

use orient::filters::{diag, params::id};
use orient::{flags, Config, Filter, Kind, Sample, Vec3};

const STILL: Vec3 = Vec3::new(0.0, 0.0, 9.81);
const FIELD: Vec3 = Vec3::new(0.0, 20.0, -40.0);

fn still(dt: f64, mag: Option<Vec3>) -> Sample {
    Sample { dt, gyro: Some(Vec3::new(0.001, -0.002, 0.0015)), accel: Some(STILL), mag }
}

fn moving(i: usize, mag: Option<Vec3>) -> Sample {
    let t = i as f64 * 0.01;
    Sample {
        dt: 0.01,
        gyro: Some(Vec3::new(1.5 * t.sin(), 1.0 * (1.3 * t).cos(), 0.8)),
        accel: Some(Vec3::new(3.0 * t.cos(), 2.0 * t.sin(), 9.8)),
        mag,
    }
}

fn filter(kind: Kind, set: &[(u32, f64)]) -> Filter {
    let mut c = Config::new(kind).unwrap();
    for &(slot, v) in set {
        c.set_param(slot, v).unwrap();
    }
    Filter::new(&c).unwrap()
}

#[test]
fn every_present_reading_is_used_or_rejected_and_an_absent_one_neither() {
    for kind in Kind::ALL {
        let mut f = filter(kind, &[]);
        let mut started = false;
        for i in 0..3000 {
            let mag = (i % 3 != 0).then_some(FIELD);
            let s = if i < 1000 { still(0.01, mag) } else { moving(i, mag) };
            // Gyroscope-only samples once every kind is past its start-up.
            let s = if i > 1500 && i % 5 == 0 { Sample { accel: None, ..s } } else { s };
            f.update(&s).unwrap();
            let fl = f.flags();
            if fl & flags::INITIALIZED == 0 || !started {
                // A start-up period, and its last step, which may use the period's mean
                // magnetometer reading when this sample has none.
                started = fl & flags::INITIALIZED != 0;
                continue;
            }
            let one = |used: u32, rejected: u32, had: bool| {
                let bits = (fl & used != 0, fl & rejected != 0);
                if had {
                    bits == (true, false) || bits == (false, true)
                } else {
                    bits == (false, false)
                }
            };
            assert!(
                one(flags::ACCEL_USED, flags::ACCEL_REJECTED, s.accel.is_some()),
                "{kind:?} {i}: {fl:#x}"
            );
            assert!(one(flags::MAG_USED, flags::MAG_REJECTED, s.mag.is_some()), "{kind:?} {i}: {fl:#x}");
        }
    }
}

#[test]
fn a_kind_without_heading_correction_rejects_the_magnetometer() {
    // McGinnis' filter uses the magnetometer only with align_heading (and then only at
    // start-up): every later reading is reported as not used.
    let mut f = filter(Kind::Complementary, &[]);
    for _ in 0..500 {
        f.update(&still(0.01, Some(FIELD))).unwrap();
    }
    assert!(f.is_initialized());
    assert_ne!(f.flags() & flags::MAG_REJECTED, 0);
    assert_eq!(f.flags() & flags::MAG_USED, 0);
}

#[test]
fn rest_is_reported_by_the_kinds_that_detect_it() {
    for (kind, set) in [
        (Kind::Robust, vec![]),
        (Kind::Complementary, vec![]),
        (Kind::Ekf, vec![(id::EKF_REST_RATE_STD, 0.01)]),
        (Kind::Madgwick, vec![(id::MADGWICK_REST_BIAS_TAU, 5.0)]),
        (Kind::Mahony, vec![(id::MAHONY_REST_BIAS_TAU, 5.0)]),
    ] {
        let mut f = filter(kind, &set);
        for _ in 0..600 {
            f.update(&still(0.01, None)).unwrap();
        }
        assert_ne!(f.flags() & flags::REST, 0, "{kind:?} at rest");
        let d = f.diagnostics();
        assert_ne!(d.present & diag::REST, 0, "{kind:?}");
        assert_eq!(d.rest, 1.0, "{kind:?}");
        for i in 0..300 {
            f.update(&moving(i, None)).unwrap();
        }
        assert_eq!(f.flags() & flags::REST, 0, "{kind:?} moving");
        assert_eq!(f.diagnostics().rest, 0.0, "{kind:?}");
    }
    // Without their options, Madgwick, Mahony and the EKF detect nothing and say so.
    for kind in [Kind::Madgwick, Kind::Mahony, Kind::Ekf] {
        let mut f = filter(kind, &[]);
        for _ in 0..600 {
            f.update(&still(0.01, None)).unwrap();
        }
        assert_eq!(f.flags() & flags::REST, 0, "{kind:?}");
        let d = f.diagnostics();
        assert_eq!(d.present & diag::REST, 0, "{kind:?}");
        assert!(d.rest.is_nan(), "{kind:?}");
    }
    let d = filter(Kind::Madgwick, &[]).diagnostics();
    assert_eq!(d.present & diag::GYRO_BIAS, 0);
    let d = filter(Kind::Madgwick, &[(id::MADGWICK_REST_BIAS_TAU, 5.0)]).diagnostics();
    assert_ne!(d.present & diag::GYRO_BIAS, 0);
}

#[test]
fn a_disturbed_field_is_flagged_and_not_used() {
    let mut f = filter(Kind::Robust, &[]);
    for _ in 0..1000 {
        f.update(&still(0.01, Some(FIELD))).unwrap();
    }
    assert_ne!(f.flags() & flags::MAG_USED, 0);
    assert_eq!(f.flags() & flags::MAG_DISTURBED, 0);
    // A magnet nearby: twice the norm, another direction.
    f.update(&still(0.01, Some(Vec3::new(60.0, 40.0, -60.0)))).unwrap();
    assert_ne!(f.flags() & flags::MAG_DISTURBED, 0, "{:#x}", f.flags());
    assert_ne!(f.flags() & flags::MAG_REJECTED, 0);
    // Back to the earth's field.
    for _ in 0..10 {
        f.update(&still(0.01, Some(FIELD))).unwrap();
    }
    assert_eq!(f.flags() & flags::MAG_DISTURBED, 0, "{:#x}", f.flags());
}

#[test]
fn flags_read_from_the_state_survive_a_snapshot() {
    let mut f = filter(Kind::Robust, &[]);
    for _ in 0..600 {
        f.update(&still(0.01, None)).unwrap();
    }
    let mut blob = vec![0; f.state_size()];
    f.save(&mut blob).unwrap();
    let mut g = filter(Kind::Robust, &[]);
    g.load(&blob).unwrap();
    assert_eq!(g.flags(), f.flags());
    assert_ne!(g.flags() & flags::REST, 0);
}

/// REST follows the option: switched off, a filter that was resting no longer says so.
#[test]
fn rest_is_not_reported_once_the_option_is_off() {
    for (kind, slot) in
        [(Kind::Madgwick, id::MADGWICK_REST_BIAS_TAU), (Kind::Mahony, id::MAHONY_REST_BIAS_TAU)]
    {
        let mut f = filter(kind, &[(slot, 5.0)]);
        for _ in 0..600 {
            f.update(&still(0.01, None)).unwrap();
        }
        assert_ne!(f.flags() & flags::REST, 0, "{kind:?}");
        f.set_param(slot, 0.0).unwrap();
        assert_eq!(f.flags() & flags::REST, 0, "{kind:?}");
    }
}

/// `Filter::uncertainty`: the mounting, the heading offset, the declination and a rig
/// calibration add nothing to it (they are exact: the same bits), nor does the frame (to
/// rounding), for both kinds that have it.
#[test]
fn the_uncertainty_does_not_depend_on_the_hosts_offsets() {
    use orient::{filters::RigHeading, Frame, Quat};
    for kind in [Kind::Robust, Kind::Ekf] {
        let mut enu = Filter::new(&Config::new(kind).unwrap()).unwrap();
        let mut config = Config::new(kind).unwrap();
        config.frame = Frame::Ned;
        let mut ned = Filter::new(&config).unwrap();
        for i in 0..500 {
            enu.update(&moving(i, Some(FIELD))).unwrap();
            ned.update(&moving(i, Some(FIELD))).unwrap();
        }
        let u = enu.uncertainty();
        assert!(u.heading.is_some(), "{kind:?}");
        // The configured frame adds nothing either, but it is not a host offset on the same
        // state: the start attitude is computed in the configured frame and rotated to the
        // kind's native one, so the two filters' states differ by rounding from the first
        // sample (the EKF's, whose native frame is NED, in 181 snapshot bytes after 500
        // samples). Equal to rounding, not in every bit.
        let v = ned.uncertainty();
        for (a, b) in [(v.heading, u.heading), (v.inclination, u.inclination)] {
            assert_eq!(a.is_some(), b.is_some(), "{kind:?}");
            if let (Some(a), Some(b)) = (a, b) {
                assert!((a - b).abs() <= 1e-12 * b, "{kind:?}: {a} vs {b}");
            }
        }
        enu.set_mounting(Quat::new(0.8, 0.2, 0.5, -0.1).normalized()).unwrap();
        enu.set_heading(1.0).unwrap();
        enu.set_declination(0.2).unwrap();
        assert_eq!(enu.uncertainty(), u, "{kind:?}");
        let reference = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.3);
        Filter::calibrate_rig(&mut [&mut enu], &[reference], RigHeading::Given(0.0)).unwrap();
        assert_eq!(enu.uncertainty(), u, "{kind:?}");
    }
}
