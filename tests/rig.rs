//! Issue 20's rig checks with simulated truth: a rig of 20 sensors with random mountings,
//! calibrated from a reference posture, reads each segment within 0.5 degrees of truth.

mod common;

use common::rig_sim::{random_rotation, rig, Segment};
use common::sim::Noise;
use orient::filters::RigHeading;
use orient::{Config, Filter, Kind, Quat, Vec3};

const STILL: f64 = 5.0;
const MOVING: f64 = 10.0;

/// Runs one filter per segment, calibrates at the end of the still period, and returns
/// the largest error (degrees) after calibration and each filter's mounting error; prints
/// the filters' own largest error (sensor orientation against its truth) beside it.
fn calibrated_error(kind: Kind, segments: &[Segment], heading: RigHeading, subject: f64) -> (f64, Vec<f64>) {
    let mut own: f64 = 0.0;
    let mut filters: Vec<Filter> =
        segments.iter().map(|_| Filter::new(&Config::new(kind).unwrap()).unwrap()).collect();
    let n = segments[0].run.samples.len();
    let calibrate_at = (STILL * 100.0) as usize - 1;
    let refs: Vec<Quat> = segments.iter().map(|s| s.reference).collect();
    let mut worst: f64 = 0.0;
    let mut mounting_errors = Vec::new();
    for i in 0..n {
        for (f, s) in filters.iter_mut().zip(segments) {
            f.update(&s.run.samples[i]).unwrap();
        }
        if i == calibrate_at {
            let mut views: Vec<&mut Filter> = filters.iter_mut().collect();
            Filter::calibrate_rig(&mut views, &refs, heading).unwrap();
            mounting_errors = filters
                .iter()
                .zip(segments)
                .map(|(f, s)| f.mounting().angle_to(s.mounting).to_degrees())
                .collect();
        }
        if i > calibrate_at {
            for (f, s) in filters.iter().zip(segments) {
                worst = worst.max(f.quaternion().angle_to(s.truth(i, subject)).to_degrees());
                let g = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), subject);
                let sensor = (g.conj() * s.run.truth[i]).normalized();
                own = own.max(f.sensor_quaternion().angle_to(sensor).to_degrees());
            }
        }
    }
    println!("{kind:?}: the filters' own worst error {own:.3} deg");
    (worst, mounting_errors)
}

#[test]
fn twenty_random_mountings_calibrated_from_a_t_pose_read_their_segments() {
    let mut rng = Noise(20);
    let refs: Vec<Quat> = (0..20).map(|_| random_rotation(&mut rng)).collect();
    let mountings: Vec<Quat> = (0..20).map(|_| random_rotation(&mut rng)).collect();
    let subject = 0.8;
    let segments = rig(&refs, &mountings, subject, STILL, MOVING);
    for kind in [Kind::Mahony, Kind::Robust, Kind::Ekf] {
        let (worst, mounting) = calibrated_error(kind, &segments, RigHeading::Given(subject), subject);
        let worst_mounting = mounting.iter().cloned().fold(0.0, f64::max);
        println!(
            "{kind:?}: worst segment error {worst:.3} deg, worst mounting error {worst_mounting:.3} deg"
        );
        assert!(worst < 0.5, "{kind:?}: {worst} deg");
        assert!(worst_mounting < 0.5, "{kind:?}: mounting {worst_mounting} deg");
    }
    // Without calibration (identity mountings) the outputs are far off: the check can fail.
    let (uncalibrated, _) = {
        let mut f = Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap();
        let s = &segments[3];
        for x in &s.run.samples {
            f.update(x).unwrap();
        }
        (f.quaternion().angle_to(s.truth(s.run.samples.len() - 1, subject)).to_degrees(), ())
    };
    assert!(uncalibrated > 5.0, "{uncalibrated}");
}

#[test]
fn a_flat_hand_with_tilted_mountings_gets_its_heading_estimated() {
    // A hand flat on a table: every segment level, pointing its own way; sensors tilted
    // on their segments (about horizontal axes), so the estimate of the subject's
    // heading is exact.
    let mut rng = Noise(7);
    let refs: Vec<Quat> =
        (0..20).map(|_| Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.3 * rng.next())).collect();
    let mountings: Vec<Quat> = (0..20)
        .map(|_| {
            let a = std::f64::consts::PI * rng.next();
            Quat::from_axis_angle(Vec3::new(a.cos(), a.sin(), 0.0), 0.7 * rng.next())
        })
        .collect();
    let subject = -2.1;
    let segments = rig(&refs, &mountings, subject, STILL, MOVING);
    let (worst, _) = calibrated_error(Kind::Robust, &segments, RigHeading::Estimated, subject);
    println!("estimated heading: worst segment error {worst:.3} deg");
    assert!(worst < 0.5, "{worst} deg");
}

#[test]
fn heading_alignment_brings_drifted_filters_back() {
    let mut rng = Noise(3);
    let refs: Vec<Quat> = (0..5).map(|_| random_rotation(&mut rng)).collect();
    let mountings: Vec<Quat> = (0..5).map(|_| random_rotation(&mut rng)).collect();
    let segments = rig(&refs, &mountings, 0.0, STILL, 0.0);
    let mut filters: Vec<Filter> =
        segments.iter().map(|_| Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap()).collect();
    for (f, s) in filters.iter_mut().zip(&segments) {
        for x in &s.run.samples {
            f.update(x).unwrap();
        }
        f.set_mounting(s.mounting).unwrap();
        f.set_heading(1.0 + f.euler().yaw).unwrap(); // drifted by a radian
    }
    let last = segments[0].run.samples.len() - 1;
    assert!(filters[0].quaternion().angle_to(segments[0].truth(last, 0.0)) > 0.5);
    let mut views: Vec<&mut Filter> = filters.iter_mut().collect();
    Filter::align_rig_heading(&mut views, &refs).unwrap();
    for (f, s) in filters.iter().zip(&segments) {
        let e = f.quaternion().angle_to(s.truth(last, 0.0)).to_degrees();
        assert!(e < 0.5, "{e} deg");
    }
}
