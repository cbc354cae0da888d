//! Issue 20's calibration checks with simulated truth: a magnetometer with known soft-
//! and hard-iron distortion, rotated over the sphere, is recovered within 1 % of the
//! field's norm, and a filter's heading error after calibration is as without the
//! distortion; a gyroscope offset from a still period.

mod common;

use common::rig_sim::{distort, tumble, HARD_IRON};
use common::sim::{simulate, Moment, FIELD};
use orient::filters::calibration::{GyroOffset, MagCalibrator, Sensor};
use orient::{Config, Filter, Kind, Quat, Sample, Vec3};

fn yaw_error(est: Quat, truth: Quat) -> f64 {
    let d = (est.to_euler().yaw - truth.to_euler().yaw).to_degrees();
    (d + 180.0).rem_euclid(360.0) - 180.0
}

#[test]
fn a_distorted_magnetometer_over_the_sphere_is_recovered() {
    let run = tumble(120.0);
    let mut cal = MagCalibrator::new();
    for s in &run.samples {
        cal.add(distort(s.mag.unwrap())).unwrap();
    }
    let fit = cal.solve().expect("a fit");
    let f = FIELD.norm();
    println!(
        "field {:.3} (true {:.3}), hard iron {:?}, residual {:.5}, coverage {:.3}",
        fit.field, f, fit.model.offset, fit.residual, fit.coverage
    );
    let hard_err = (fit.model.offset - HARD_IRON).norm() / f;
    assert!(hard_err < 0.01, "hard iron off by {hard_err} of the field");
    // Each calibrated reading is the true field, scaled to the fit's norm, within 1 %.
    let mut worst: f64 = 0.0;
    for (s, q) in run.samples.iter().zip(&run.truth) {
        let truth = q.rotate_inverse(FIELD) * (fit.field / f);
        let c = fit.model.apply(distort(s.mag.unwrap()));
        worst = worst.max((c - truth).norm() / fit.field);
    }
    println!("worst calibrated reading error: {:.4} of the field", worst);
    assert!(worst < 0.01, "{worst}");
    assert!(fit.coverage > 0.9 && fit.residual < 0.01 && fit.trustworthy(), "{fit:?}");
    // A quarter of the sphere is not enough to trust.
    let mut partial = MagCalibrator::new();
    for s in &tumble(4.0).samples {
        partial.add(distort(s.mag.unwrap())).unwrap();
    }
    assert!(partial.coverage() < 0.5, "{}", partial.coverage());
}

/// The largest |yaw error| (degrees) of a robust filter over the run's last 30 s.
fn heading_error(
    kind: Kind,
    samples: &[Sample],
    truth: &[Quat],
    model: bool,
    fit_model: orient::filters::calibration::Model,
) -> f64 {
    let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
    if model {
        f.set_sensor_model(Sensor::Mag, Some(fit_model)).unwrap();
    }
    let n = samples.len();
    let mut worst: f64 = 0.0;
    for (i, (s, q)) in samples.iter().zip(truth).enumerate() {
        f.update(s).unwrap();
        if i > n - 1500 {
            worst = worst.max(yaw_error(f.quaternion(), *q).abs());
        }
    }
    worst
}

#[test]
fn heading_after_calibration_is_as_without_distortion() {
    let run = tumble(60.0);
    let mut cal = MagCalibrator::new();
    for s in &run.samples {
        cal.add(distort(s.mag.unwrap())).unwrap();
    }
    let fit = cal.solve().unwrap();
    // A slower motion to score the heading on (tilted, turning about the vertical).
    let score =
        simulate(Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.3), 60.0, 50.0, (0.001, 0.02, 0.2), |t| {
            Moment {
                omega: Vec3::new(0.2 * (0.5 * t).sin(), 0.15 * (0.3 * t).cos(), 0.4 * (0.2 * t).sin()),
                ..Moment::default()
            }
        });
    let distorted: Vec<Sample> =
        score.samples.iter().map(|s| Sample { mag: s.mag.map(distort), ..*s }).collect();
    for kind in [Kind::Madgwick, Kind::Mahony, Kind::Robust] {
        let clean = heading_error(kind, &score.samples, &score.truth, false, fit.model);
        let raw = heading_error(kind, &distorted, &score.truth, false, fit.model);
        let calibrated = heading_error(kind, &distorted, &score.truth, true, fit.model);
        println!("{kind:?}: worst heading error clean {clean:.3}, distorted {raw:.3}, calibrated {calibrated:.3} deg");
        assert!(raw > clean + 2.0, "the distortion must matter for the check to mean anything");
        assert!(calibrated < clean + 0.3, "{kind:?}: {calibrated} vs {clean}");
    }
}

#[test]
fn a_gyro_offset_from_a_still_period_removes_the_bias() {
    let bias = Vec3::new(0.02, -0.01, 0.015);
    let still =
        simulate(Quat::IDENTITY, 2.0, 100.0, (0.002, 0.02, 0.2), |_| Moment { bias, ..Moment::default() });
    let mut g = GyroOffset::default();
    for s in &still.samples {
        g.add(s.gyro.unwrap()).unwrap();
    }
    let est = g.offset().unwrap();
    assert!((est - bias).norm() < 5e-4, "{est:?}");
    assert!(g.spread() < 0.002, "{}", g.spread());
    // A filter given the model drifts no more than one fed a bias-free gyroscope.
    let turning = simulate(Quat::IDENTITY, 30.0, 100.0, (0.0, 0.0, 0.0), |_| Moment {
        bias,
        omega: Vec3::new(0.0, 0.0, 0.3),
        ..Moment::default()
    });
    let imu: Vec<Sample> = turning.samples.iter().map(|s| Sample { mag: None, ..*s }).collect();
    let run = |model: bool| {
        let mut f = Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap();
        if model {
            f.set_sensor_model(Sensor::Gyro, g.model()).unwrap();
        }
        for s in &imu {
            f.update(s).unwrap();
        }
        yaw_error(f.quaternion(), *turning.truth.last().unwrap()).abs()
    };
    let (without, with) = (run(false), run(true));
    println!("yaw drift after 30 s: {without:.3} deg without the offset, {with:.3} deg with it");
    assert!(without > 10.0 && with < 0.1, "{without} {with}");
}

#[test]
fn models_and_host_frames_survive_reset_and_snapshots() {
    use orient::filters::calibration::Model;
    let mut c = Config::new(Kind::Robust).unwrap();
    c.init = orient::Init::Identity;
    let mut f = Filter::new(&c).unwrap();
    let gyro = Model { offset: Vec3::new(0.01, 0.0, -0.02), ..Model::IDENTITY };
    let mag = Model {
        matrix: [[1.1, 0.0, 0.0], [0.0, 0.9, 0.0], [0.0, 0.0, 1.0]],
        offset: Vec3::new(3.0, -2.0, 1.0),
    };
    f.set_sensor_model(Sensor::Gyro, Some(gyro)).unwrap();
    f.set_sensor_model(Sensor::Mag, Some(mag)).unwrap();
    f.set_mounting(Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 0.4)).unwrap();
    f.set_declination(0.1).unwrap();
    f.set_heading(0.7).unwrap();
    let (mounting, offset) = (f.mounting(), f.heading_offset());
    assert!(offset != 0.0);
    f.reset();
    // The header: reset keeps the parameters, the mounting, the heading offset, the
    // declination and the sensor models.
    assert_eq!((f.mounting(), f.heading_offset()), (mounting, offset));
    assert_eq!(f.sensor_model(Sensor::Gyro), Some(gyro));
    assert_eq!(f.sensor_model(Sensor::Mag), Some(mag));
    assert_eq!(f.sensor_model(Sensor::Accel), None);
    assert_eq!(f.declination(), 0.1);
    let s = Sample {
        dt: 0.01,
        gyro: Some(Vec3::new(0.1, 0.2, 0.3)),
        accel: Some(Vec3::new(0.0, 0.5, 9.8)),
        mag: Some(Vec3::new(20.0, 10.0, -40.0)),
    };
    f.update(&s).unwrap();
    let mut blob = vec![0u8; f.state_size()];
    f.save(&mut blob).unwrap();
    let mut g = Filter::new(&Config::new(Kind::Robust).unwrap()).unwrap();
    g.load(&blob).unwrap();
    assert_eq!(g.sensor_model(Sensor::Mag), Some(mag));
    assert_eq!(g.mounting(), f.mounting());
    f.update(&s).unwrap();
    g.update(&s).unwrap();
    assert_eq!(f.quaternion(), g.quaternion());
    // A singular matrix is refused and changes nothing.
    let singular = Model { matrix: [[0.0; 3]; 3], offset: Vec3::ZERO };
    assert_eq!(
        f.set_sensor_model(Sensor::Accel, Some(singular)),
        Err(orient::Error::ZeroVector(orient::Field::Accel))
    );
    assert_eq!(f.sensor_model(Sensor::Accel), None);
}

/// A blob of format version 2 (before issue 20's fields) is refused as another version,
/// as are those of version 3 (before the robust kind's heading uncertainty), 4 (the
/// robust kind's heading as an angle, not a half-angle pair), 5 (Mahony's estimate
/// North-West-Up), 6 (before the robust kind's innovation evidence, eq. H5, and the
/// EKF's mean gravity innovation), 7 (before the rest watch), 8 (before the robust
/// kind's motion bias filter) and 9 (before the rest detector's mean of the still
/// period).
#[test]
fn a_version_2_snapshot_is_refused_as_another_version() {
    use orient::filters::state::{checksum, StateError, VERSION};
    assert_eq!(VERSION, 10);
    let mut f = Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap();
    let before = f.clone();
    for old in [2u16, 3, 4, 5, 6, 7, 8, 9] {
        let mut blob = vec![0u8; f.state_size()];
        f.save(&mut blob).unwrap();
        blob[4..6].copy_from_slice(&old.to_le_bytes());
        let end = blob.len() - 8;
        let sum = checksum(&blob[..end]);
        blob[end..].copy_from_slice(&sum.to_le_bytes());
        assert_eq!(f.load(&blob), Err(StateError::Version(old)));
        assert_eq!(f, before);
    }
}

/// The configured ranges are the raw sensor's full scale: a raw reading at or beyond one
/// is refused (or clipped), a calibrated one past it is not, so that a model whose offset
/// moves a still sensor's reading past a small range leaves the filter usable.
#[test]
fn a_range_applies_to_the_raw_reading_not_the_calibrated_one() {
    for recover in [0.0, 1.0] {
        let mut c = Config::new(Kind::Madgwick).unwrap();
        c.set("gyro_range", 0.25).unwrap().unwrap();
        c.set("saturation_recovery", recover).unwrap().unwrap();
        let mut f = Filter::new(&c).unwrap();
        let offset = orient::Model {
            matrix: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            offset: Vec3::new(0.0, 0.0, -0.254),
        };
        f.set_sensor_model(Sensor::Gyro, Some(offset)).unwrap();
        let still =
            Sample { dt: 0.01, gyro: Some(Vec3::ZERO), accel: Some(Vec3::new(0.0, 0.0, 9.81)), mag: None };
        for _ in 0..100 {
            f.update(&still).unwrap();
        }
        assert_eq!(f.flags() & orient::flags::SATURATED, 0);
        // The calibrated reading, 0.254 rad/s about z, turned the estimate.
        assert!(f.quaternion().z.abs() > 0.05, "{:?}", f.quaternion());
        // A raw reading at the range is the sensor's saturation.
        let at_range = Sample { gyro: Some(Vec3::new(0.0, 0.25, 0.0)), ..still };
        if recover == 0.0 {
            assert_eq!(f.update(&at_range), Err(orient::Error::Saturated(orient::Field::Gyro)));
        } else {
            f.update(&at_range).unwrap();
            assert_ne!(f.flags() & orient::flags::SATURATED, 0);
        }
    }
}
