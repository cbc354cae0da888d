use super::*;
use crate::filters::{Config, Init, Kind};
use crate::math::Frame;

fn filter(frame: Frame) -> Filter {
    let mut c = Config::new(Kind::Madgwick).unwrap();
    c.frame = frame;
    c.init = Init::Given(Quat::from_axis_angle(Vec3::new(0.3, -0.5, 0.8).normalized(), 0.9));
    Filter::new(&c).unwrap()
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_identity_host_leaves_the_bits_alone() {
    let mut f = filter(Frame::Enu);
    let before = f.quaternion();
    f.set_mounting(Quat::IDENTITY).unwrap();
    f.set_declination(0.0).unwrap();
    assert_eq!(f.quaternion(), before);
    assert_eq!(f.sensor_quaternion(), before);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_mounting_gives_the_segment_and_set_quaternion_inverts_it() {
    let mut f = filter(Frame::Ned);
    let q = f.quaternion();
    let m = Quat::from_axis_angle(Vec3::new(1.0, 2.0, -0.5).normalized(), 1.3);
    f.set_mounting(m).unwrap();
    assert!(f.quaternion().angle_to(q * m.conj()) < 1e-12);
    assert!(f.sensor_quaternion().angle_to(q) < 1e-12);
    let target = Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0).normalized(), -0.4);
    f.set_quaternion(target).unwrap();
    assert!(f.quaternion().angle_to(target) < 1e-12);
    assert_eq!(f.set_mounting(Quat::new(f64::NAN, 0.0, 0.0, 0.0)), Err(Error::NonFinite(Field::Quaternion)));
    assert_eq!(f.mounting(), m.normalized());
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn set_heading_sets_the_yaw_and_keeps_the_inclination() {
    for frame in Frame::ALL {
        let mut f = filter(frame);
        let before = f.euler();
        f.set_heading(2.5).unwrap();
        let after = f.euler();
        assert!((after.yaw - 2.5).abs() < 1e-12, "{frame:?}");
        assert!((after.pitch - before.pitch).abs() < 1e-12 && (after.roll - before.roll).abs() < 1e-12);
        f.reset_heading().unwrap();
        assert!(f.euler().yaw.abs() < 1e-12);
        assert_eq!(f.set_heading(f64::INFINITY), Err(Error::NonFinite(Field::Angle)));
    }
    let mut fresh = Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap();
    assert_eq!(fresh.set_heading(1.0), Err(Error::NotInitialized));
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn declination_turns_a_magnetic_heading_into_a_true_one() {
    // Heading (clockwise from north) is the NED yaw; ENU's yaw is counter-clockwise
    // from east. East declination adds to the first and subtracts from the second.
    for (frame, sign) in [(Frame::Ned, 1.0), (Frame::Enu, -1.0), (Frame::Nwu, -1.0)] {
        let mut f = filter(frame);
        let before = f.euler().yaw;
        f.set_declination(0.2).unwrap();
        assert!((wrap(f.euler().yaw - before) - sign * 0.2).abs() < 1e-12, "{frame:?}");
        assert_eq!(f.declination(), 0.2);
    }
    let mut f = filter(Frame::Enu);
    assert_eq!(f.set_declination(3.2), Err(Error::TooLarge(Field::Angle)));
    assert_eq!(f.declination(), 0.0);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn rig_calls_refuse_bad_input_and_change_nothing() {
    let mut a = filter(Frame::Enu);
    let mut b = Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap();
    let refs = [Quat::IDENTITY, Quat::IDENTITY];
    let before = (a.clone(), b.clone());
    let r = Filter::calibrate_rig(&mut [&mut a, &mut b], &refs, RigHeading::Estimated);
    assert_eq!(r, Err((1, Error::NotInitialized)));
    let r = Filter::align_rig_heading(&mut [&mut a], &refs);
    assert_eq!(r, Err((0, Error::MissingSensor(Field::Quaternion))));
    assert_eq!((a, b), before);
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_calibrated_rig_reads_its_references() {
    let mut fs: Vec<Filter> = (0..3).map(|_| filter(Frame::Enu)).collect();
    let refs = [
        Quat::IDENTITY,
        Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 1.0),
        Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0).normalized(), -2.0),
    ];
    let mut views: Vec<&mut Filter> = fs.iter_mut().collect();
    Filter::calibrate_rig(&mut views, &refs, RigHeading::Given(0.7)).unwrap();
    for (f, r) in fs.iter().zip(&refs) {
        assert!(f.quaternion().angle_to(*r) < 1e-12);
        assert!((f.heading_offset() + 0.7).abs() < 1e-15);
    }
}

/// A 6D rig: every filter's heading its own, each sensor tilted on its segment (no turn
/// about the segment's vertical). Calibrated each on its own ([`RigHeading::Each`]), each
/// mounting is the sensor's tilt, whatever offsets the filters had; with one common
/// heading, each filter's own heading goes into its mounting.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_6d_rig_calibrated_each_on_its_own_finds_its_sensors_tilts() {
    let z = Vec3::new(0.0, 0.0, 1.0);
    // A flat hand's segments: level, facing their own ways.
    let refs = [0.0, 0.4, -0.3].map(|yaw| Quat::from_axis_angle(z, yaw));
    // The sensors tilted about horizontal axes of their segments.
    let tilts = [(0.2, 0.35), (1.9, -0.3), (-2.4, 0.25)].map(|(axis, angle): (f64, f64)| {
        Quat::from_axis_angle(Vec3::new(axis.cos(), axis.sin(), 0.0), angle)
    });
    // Each 6D filter's heading, its own.
    let headings = [1.1, -2.0, 0.3];
    let rig = |frame: Frame, declination: f64| -> Vec<Filter> {
        (0..3)
            .map(|i| {
                let mut f = filter(frame);
                f.set_declination(declination).unwrap();
                f.set_quaternion(Quat::from_axis_angle(z, headings[i]) * refs[i] * tilts[i]).unwrap();
                f
            })
            .collect()
    };
    // In every frame (z is vertical in each), with a declination, which is kept.
    for frame in Frame::ALL {
        for declination in [0.0, 0.2] {
            let mut each = rig(frame, declination);
            // An offset set before changes nothing.
            each[1].set_heading(0.7).unwrap();
            let mut views: Vec<&mut Filter> = each.iter_mut().collect();
            Filter::calibrate_rig(&mut views, &refs, RigHeading::Each).unwrap();
            for (i, f) in each.iter().enumerate() {
                assert!(f.quaternion().angle_to(refs[i]) < 1e-12, "{frame:?} {declination}");
                assert!(
                    f.mounting().angle_to(tilts[i]) < 1e-12,
                    "{frame:?} {declination} {i}: {:?}",
                    f.mounting()
                );
                assert_eq!(f.declination(), declination);
            }
        }
    }
    let mut common = rig(Frame::Enu, 0.0);
    let mut views: Vec<&mut Filter> = common.iter_mut().collect();
    Filter::calibrate_rig(&mut views, &refs, RigHeading::Estimated).unwrap();
    let mean = headings.iter().sum::<f64>() / 3.0;
    for (i, f) in common.iter().enumerate() {
        assert!(f.quaternion().angle_to(refs[i]) < 1e-12);
        let off = f.mounting().angle_to(tilts[i]);
        assert!(off > 0.5 * (headings[i] - mean).abs(), "{i}: {off}");
    }
}
