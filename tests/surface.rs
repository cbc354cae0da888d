//! Issue 40, classes 4, 5, 8 and 9, over every kind: Euler angles and set_heading at
//! gimbal lock; same-instant samples during a start-up period; a magnetometer parallel
//! to gravity; the physical bounds under saturation recovery.

use orient::filters::params::id;
use orient::{flags, Config, Error, Field, Filter, Kind, Quat, Sample, Vec3};

const G: Vec3 = Vec3::new(0.0, 0.0, 9.81);

fn still(dt: f64) -> Sample {
    Sample { dt, gyro: Some(Vec3::new(0.001, -0.002, 0.001)), accel: Some(G), mag: None }
}

fn filter_with(kind: Kind, set: &[(u32, f64)]) -> Filter {
    let mut c = Config::new(kind).unwrap();
    for &(slot, v) in set {
        c.set_param(slot, v).unwrap();
    }
    Filter::new(&c).unwrap()
}

fn rz(a: f64) -> Quat {
    Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), a)
}
fn ry(a: f64) -> Quat {
    Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), a)
}
fn rx(a: f64) -> Quat {
    Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), a)
}

fn wrap(a: f64) -> f64 {
    let r = a.rem_euclid(2.0 * core::f64::consts::PI);
    r.min(2.0 * core::f64::consts::PI - r)
}

/// Class 4: at and near ±90° pitch, for every kind and frame, orient_filter_euler's
/// angles rebuild the output orientation, and set_heading sets the yaw it reads back
/// (keeping the inclination). Issue 40: Rz(0.7) Ry(π/2) read as a rotation 12° away,
/// and set_heading(0.5) read back 0.0.
#[test]
fn euler_angles_and_set_heading_hold_at_gimbal_lock() {
    use core::f64::consts::FRAC_PI_2;
    let mut worst = 0.0f64;
    for kind in Kind::ALL {
        for frame in orient::Frame::ALL {
            let mut c = Config::new(kind).unwrap();
            c.frame = frame;
            let mut f = Filter::new(&c).unwrap();
            for sign in [1.0, -1.0] {
                for offset in [0.0, 1e-12, 1e-9, 1e-7f64.to_radians(), 1e-5, 1e-3] {
                    let q = rz(0.7) * ry(sign * (FRAC_PI_2 - offset)) * rx(0.2);
                    f.set_quaternion(q).unwrap();
                    let e = f.euler();
                    let err = f.quaternion().angle_to(rz(e.yaw) * ry(e.pitch) * rx(e.roll));
                    assert!(err < 1e-13, "{kind:?} {frame:?} {sign} {offset:e}: {err:e} {e:?}");
                    worst = worst.max(err);
                    for yaw in [0.5, 3.0, -2.0] {
                        let (before, now) = (f.quaternion(), f.euler().yaw);
                        f.set_heading(yaw).unwrap();
                        // The output turned about the frame's z axis by yaw − the yaw read
                        // before, and nothing else.
                        let turned = rz(yaw - now) * before;
                        let err = f.quaternion().angle_to(turned);
                        assert!(err < 1e-12, "{kind:?} {frame:?} {offset:e}: {err:e}");
                        // The yaw reads back: exactly at lock (roll 0 there); near it, to
                        // the angles' own conditioning (a rounding error of the rotation,
                        // 1e-16, moves yaw and roll by about 1e-16 / the offset, in
                        // opposite senses, with the rotation unchanged).
                        let e = f.euler();
                        let tolerance = 1e-12 + 1e-15 / offset.max(1e-300);
                        assert!(
                            wrap(e.yaw - yaw) < tolerance,
                            "{kind:?} {frame:?} {offset:e}: yaw {} for {yaw}",
                            e.yaw
                        );
                    }
                    f.set_heading(0.0).unwrap();
                }
            }
        }
    }
    println!("worst rebuild error at and near gimbal lock: {worst:e} rad");
}

/// Class 5: with same_instant on, dt = 0 samples are refused (NOT_INITIALIZED) only
/// before the first sample with dt > 0; during a start-up period (complementary, GMVDK)
/// they are samples of that period, and every kind gets its orientation from bursty
/// data. INITIALIZED is clear only while waiting for that first sample and, for the two
/// kinds with a start-up period, through it, whose samples report the accelerometer used.
#[test]
fn bursts_during_start_up_are_samples_of_it() {
    for kind in Kind::ALL {
        let mut f = filter_with(kind, &[(id::SAME_INSTANT, 1.0)]);
        // Before any sample with dt > 0: refused, nothing changed.
        let fresh = f.clone();
        assert_eq!(f.update(&still(0.0)), Err(Error::NotInitialized), "{kind:?}");
        assert_eq!(f, fresh);
        let starts = matches!(kind, Kind::Complementary | Kind::Gmvdk);
        let mut initialised_at = None;
        // Groups of four samples with one timestamp: 0.04, 0, 0, 0, for 4 s.
        for i in 0..400 {
            let dt = if i % 4 == 0 { 0.04 } else { 0.0 };
            let r = f.update(&still(dt));
            assert_eq!(r, Ok(()), "{kind:?}: sample {i}, dt {dt}");
            let fl = f.flags();
            if fl & flags::INITIALIZED != 0 {
                initialised_at.get_or_insert(i);
            } else {
                assert!(starts, "{kind:?}: sample {i} has no orientation");
                let want = if dt == 0.0 { flags::SAME_INSTANT } else { flags::ACCEL_USED };
                assert_eq!(fl, want, "{kind:?}: start-up sample {i}");
            }
        }
        let at = initialised_at.unwrap_or_else(|| panic!("{kind:?} never initialised"));
        // The period's time is the dt > 0 samples' (2 s and 1 s by default): it ends on
        // the 50th (25th) such sample, every 4th from index 0.
        let expect = match kind {
            Kind::Complementary => 4 * 49,
            Kind::Gmvdk => 4 * 24,
            _ => 0,
        };
        assert_eq!(at, expect, "{kind:?}");
        let up = f.quaternion().rotate_inverse(f.frame().up());
        assert!((up - G * (1.0 / G.norm())).norm() < 1e-2, "{kind:?}: {up:?}");
    }
}

/// Class 5, the multi-sample calls: arrays (which run the batch's updates) and the
/// smoother go through bursty start-up data without stopping.
#[test]
fn batch_and_arrays_do_not_stop_on_bursts_during_start_up() {
    for kind in Kind::ALL {
        let samples: Vec<Sample> = (0..600).map(|i| still(if i % 4 == 0 { 0.04 } else { 0.0 })).collect();
        let mut c = Config::new(kind).unwrap();
        c.set_param(id::SAME_INSTANT, 1.0).unwrap();
        let mut f = Filter::new(&c).unwrap();
        use orient::ffi::*;
        let handle = unsafe {
            let mut cc = std::mem::MaybeUninit::<OrientConfig>::uninit();
            assert_eq!(
                orient_config_default(OrientKind::from(kind) as i32, cc.as_mut_ptr()),
                OrientStatus::Ok
            );
            assert_eq!(orient_config_set_param(cc.as_mut_ptr(), id::SAME_INSTANT, 1.0), OrientStatus::Ok);
            let mut h = std::ptr::null_mut();
            assert_eq!(orient_filter_new(cc.as_ptr(), &mut h), OrientStatus::Ok);
            h
        };
        let dt: Vec<f64> = samples.iter().map(|s| s.dt).collect();
        let gyro: Vec<f64> = samples.iter().flat_map(|s| s.gyro.map(|v| [v.x, v.y, v.z]).unwrap()).collect();
        let accel: Vec<f64> =
            samples.iter().flat_map(|s| s.accel.map(|v| [v.x, v.y, v.z]).unwrap()).collect();
        let mut processed = usize::MAX;
        let status = unsafe {
            orient_filter_update_arrays(
                handle,
                samples.len(),
                dt.as_ptr(),
                dt.len(),
                gyro.as_ptr(),
                accel.as_ptr(),
                core::ptr::null(),
                core::ptr::null_mut(),
                core::ptr::null_mut(),
                core::ptr::null_mut(),
                &mut processed,
            )
        };
        assert_eq!((status, processed), (OrientStatus::Ok, samples.len()), "{kind:?}");
        assert_eq!(unsafe { orient_filter_free(handle) }, OrientStatus::Ok);
        for s in &samples {
            f.update(s).unwrap();
        }
        assert!(f.is_initialized(), "{kind:?}");
        let smoothed = orient::offline::smooth(&c, &samples);
        assert!(smoothed.is_ok(), "{kind:?}: {:?}", smoothed.err());
    }
}

/// Class 8: a magnetometer parallel to gravity (exactly, within 1e-7 rad, antiparallel)
/// gives no heading, so the step is the IMU update bit for bit, with MAG_USED clear and
/// MAG_REJECTED set, for every kind and every option that routes the update elsewhere
/// (the estimate a little off level, so that a kind's own field reference has a tiny
/// horizontal part). Issue 40: Madgwick and Mahony set MAG_USED, Madgwick's step 0.02°
/// from the IMU step.
#[test]
fn a_field_parallel_to_gravity_gives_the_imu_step() {
    let fields = [Vec3::new(0.0, 0.0, -45.0), Vec3::new(4.5e-6, 0.0, -45.0), Vec3::new(0.0, 0.0, 30.0)];
    for kind in Kind::ALL {
        for options in [&[][..], &[(id::SATURATION_RECOVERY, 1.0), (id::GYRO_RANGE, 30.0)][..]] {
            let mut f = filter_with(kind, options);
            // Past any start-up period, then a little off level.
            while !f.is_initialized() {
                f.update(&still(0.01)).unwrap();
            }
            for _ in 0..50 {
                f.update(&still(0.01)).unwrap();
            }
            let tilt = rx(3e-3) * f.quaternion();
            f.set_quaternion(tilt).unwrap();
            for m in fields {
                let mut imu = f.clone();
                let mut marg = f.clone();
                imu.update(&still(0.01)).unwrap();
                marg.update(&Sample { mag: Some(m), ..still(0.01) }).unwrap();
                assert_eq!(marg.flags() & flags::MAG_USED, 0, "{kind:?} {m:?}");
                assert_ne!(marg.flags() & flags::MAG_REJECTED, 0, "{kind:?} {m:?}");
                assert_eq!(marg.flags() & !flags::MAG_REJECTED, imu.flags(), "{kind:?} {m:?}");
                let (a, b) = (imu.quaternion(), marg.quaternion());
                assert_eq!([a.w, a.x, a.y, a.z], [b.w, b.x, b.y, b.z], "{kind:?} {m:?}");
            }
            // A field 1e-5 rad off vertical has a heading to give: the rule is no wider.
            let mut marg = f.clone();
            marg.update(&Sample { mag: Some(Vec3::new(4.5e-4, 0.0, -45.0)), ..still(0.01) }).unwrap();
            if matches!(kind, Kind::Madgwick | Kind::Mahony) {
                assert_ne!(marg.flags() & flags::MAG_USED, 0, "{kind:?}");
            }
        }
    }
}

/// Class 8 at the first sample and after a gap: a vertical field gives no heading to
/// the start or the re-acquisition either.
#[test]
fn a_field_parallel_to_gravity_gives_no_heading_at_start_or_reacquisition() {
    let vertical = Sample { mag: Some(Vec3::new(0.0, 0.0, -45.0)), ..still(0.01) };
    for kind in Kind::ALL {
        let mut f = filter_with(kind, &[]);
        let mut imu = f.clone();
        while !f.is_initialized() {
            f.update(&vertical).unwrap();
            imu.update(&still(0.01)).unwrap();
            assert_eq!(f.flags() & flags::MAG_USED, 0, "{kind:?}");
        }
        assert_eq!(f.quaternion(), imu.quaternion(), "{kind:?}");
        f.update(&Sample { dt: 1.0, ..vertical }).unwrap();
        assert_ne!(f.flags() & flags::REACQUIRED, 0, "{kind:?}");
        assert_eq!(f.flags() & flags::MAG_USED, 0, "{kind:?}");
    }
}

/// Class 9: under saturation recovery a reading at or beyond its physical bound is
/// TOO_LARGE (the documented order: the range's SATURATED applies only without recovery),
/// for every kind and field, in lone samples and in bursts, with nothing changed; a
/// reading between the range and the bound is used clipped. Filter::check agrees.
#[test]
fn physical_bounds_stay_errors_under_saturation_recovery() {
    let big = |field: Field| match field {
        Field::Gyro => Sample { gyro: Some(Vec3::new(0.0, 2e4, 0.0)), ..still(0.01) },
        Field::Accel => Sample { accel: Some(Vec3::new(0.0, 0.0, 2e5)), ..still(0.01) },
        _ => Sample { mag: Some(Vec3::new(2e12, 0.0, 0.0)), ..still(0.01) },
    };
    let clipped = |field: Field| match field {
        Field::Gyro => Sample { gyro: Some(Vec3::new(0.0, 5.0, 0.0)), ..still(0.01) },
        _ => Sample { accel: Some(Vec3::new(0.0, 0.0, 25.0)), ..still(0.01) },
    };
    let ranges = [(id::GYRO_RANGE, 4.0), (id::ACCEL_RANGE, 20.0)];
    for kind in Kind::ALL {
        for burst in [false, true] {
            for recover in [true, false] {
                let mut set = ranges.to_vec();
                set.push((id::SATURATION_RECOVERY, if recover { 1.0 } else { 0.0 }));
                set.push((id::SAME_INSTANT, if burst { 1.0 } else { 0.0 }));
                let mut f = filter_with(kind, &set);
                while !f.is_initialized() {
                    f.update(&still(0.01)).unwrap();
                }
                if burst {
                    f.update(&still(0.0)).unwrap();
                }
                for field in [Field::Gyro, Field::Accel, Field::Mag] {
                    for dt in if burst { vec![0.0, 0.01] } else { vec![0.01] } {
                        let s = Sample { dt, ..big(field) };
                        let want = match field {
                            Field::Mag => Error::TooLarge(field),
                            _ if recover => Error::TooLarge(field),
                            // Without recovery the range comes first, as documented.
                            _ => Error::Saturated(field),
                        };
                        let before = f.clone();
                        assert_eq!(
                            f.update(&s),
                            Err(want),
                            "{kind:?} burst {burst} recover {recover} dt {dt}"
                        );
                        assert_eq!(f, before, "{kind:?}: a refused sample changes nothing");
                        if dt > 0.0 {
                            assert_eq!(f.check(&s), Err(want), "{kind:?}: check");
                        }
                    }
                }
                for field in [Field::Gyro, Field::Accel] {
                    let s = clipped(field);
                    let r = f.update(&s);
                    if recover {
                        assert_eq!(r, Ok(()), "{kind:?} {field:?}");
                        assert_ne!(f.flags() & flags::SATURATED, 0, "{kind:?} {field:?}");
                        assert_eq!(f.check(&s), Ok(()), "{kind:?}: check");
                    } else {
                        assert_eq!(r, Err(Error::Saturated(field)), "{kind:?}");
                    }
                }
            }
        }
    }
}
