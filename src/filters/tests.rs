//! Tests of the common lifecycle over every kind.

use super::*;
use crate::filters::kinds::madgwick::LANES;
use crate::filters::params::{id, Settings};
use crate::filters::pipeline::estimator::Estimator;
use crate::filters::pipeline::filter::with_kind;
use crate::math::{Frame, Quat, Vec3};

/// Deterministic test motion for filter `k` at step `i`.
fn rig_sample(k: usize, i: usize, mag: bool) -> Sample {
    let t = i as f64 * 0.01 + k as f64;
    Sample {
        dt: 0.01 + 0.001 * (k as f64),
        gyro: Some(Vec3::new(0.5 * t.sin(), 0.3 * (1.3 * t).cos(), 0.2 + 0.1 * k as f64)),
        accel: Some(Vec3::new(0.3 * t.cos(), 0.2 * t.sin() + 0.1, 9.8)),
        mag: mag.then(|| Vec3::new(20.0 + t.sin(), 3.0 * k as f64, -40.0)),
    }
}

/// The EKF and GMVDK updates run in the AVX copy where the CPU has it
/// (crate::isa; 256-bit lanes in the EKF). Forced onto the baseline code, the same
/// steps must give the same bits, step by step, in every kind's whole state. (On a
/// CPU without AVX, or off x86-64, both are the same code.)
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_wide_encoding_gives_the_baseline_bits() {
    for kind in Kind::ALL {
        for mag in [false, true] {
            let config = Config::new(kind).unwrap();
            let (mut wide, mut base) = (Filter::new(&config).unwrap(), Filter::new(&config).unwrap());
            let (mut a, mut b) = (vec![0; wide.state_size()], vec![0; base.state_size()]);
            for i in 0..3000 {
                let mut s = rig_sample(1, i, mag);
                if i % 7 == 3 {
                    s.accel = None; // a gyro-only step
                }
                if i % 500 == 250 {
                    s.dt = 5.0; // a gap
                }
                let baseline = crate::isa::baseline(|| base.update(&s));
                assert_eq!(wide.update(&s), baseline, "{kind:?} step {i}");
                wide.save(&mut a).unwrap();
                base.save(&mut b).unwrap();
                assert!(a == b, "{kind:?} (mag {mag}): the states differ after step {i}");
            }
        }
    }
}

/// Readings beyond the physical bounds, which could overflow a step, are refused by the
/// checks, before any arithmetic, and change nothing; readings just inside them give a
/// finite unit quaternion. (They once reached the cores: GMVDK answered Ok with a zero
/// quaternion, and the EKF was left refusing every later sample.)
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn readings_beyond_the_physical_bounds_are_refused_before_any_arithmetic() {
    for kind in Kind::ALL {
        let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
        // Long enough for the start-up periods' patience with a sensor in motion.
        for i in 0..1500 {
            f.update(&rig_sample(0, i, true)).unwrap();
        }
        assert!(f.is_initialized(), "{kind:?}");
        let base = rig_sample(0, 1500, true);
        let cases = [
            (Sample { gyro: Some(Vec3::new(1e300, -1e300, 1e300)), ..base }, Error::TooLarge(Field::Gyro)),
            (Sample { gyro: Some(Vec3::new(0.0, -MAX_GYRO, 0.0)), ..base }, Error::TooLarge(Field::Gyro)),
            (
                Sample { gyro: Some(Vec3::new(0.0, 1e156, -2.25)), accel: None, mag: None, dt: 0.0011 },
                Error::TooLarge(Field::Gyro),
            ),
            (Sample { accel: Some(Vec3::new(MAX_ACCEL, 0.0, 1.0)), ..base }, Error::TooLarge(Field::Accel)),
            (Sample { mag: Some(Vec3::new(1.0, -MAX_MAG, 1.0)), ..base }, Error::TooLarge(Field::Mag)),
            (Sample { dt: 2.0 * MAX_DT, ..base }, Error::InvalidDt(2.0 * MAX_DT)),
        ];
        for (s, want) in cases {
            let before = f.clone();
            assert_eq!(f.update(&s), Err(want), "{kind:?} {s:?}");
            assert_eq!(f, before, "{kind:?}");
        }
        let inside = MAX_GYRO * 0.999_999;
        for s in [
            Sample { gyro: Some(Vec3::new(inside, -inside, inside)), ..base },
            Sample { gyro: Some(Vec3::new(0.0, -inside, -2.25)), accel: None, mag: None, dt: 0.2 },
            Sample { accel: Some(Vec3::new(MAX_ACCEL * 0.999, 0.0, 1.0)), ..base },
        ] {
            f.update(&s).unwrap_or_else(|e| panic!("{kind:?} {s:?}: {e}"));
            let q = f.quaternion();
            assert!(q.is_finite() && (q.norm() - 1.0).abs() < 1e-9, "{kind:?}: {q:?}");
        }
    }
}

/// The cores' own rule, shared by every kind: an update that returns `None` has
/// changed nothing (each computes into locals and commits at the end; the Filter
/// restores nothing but an initialisation), or, for a kind with
/// `Estimator::FAILURE_RESTARTS`, has started over from the orientation it had, with its
/// settings, and good samples then bring it back. Driven past the Filter's checks with
/// values that overflow, fresh and warmed. (The complementary filter once kept the
/// g₀ of a step it refused.)
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_core_update_that_fails_changes_nothing() {
    fn failures<E: Estimator>(config: &Config) -> usize {
        let mut failures = 0;
        for warm in [0, 300] {
            let mut core = E::create(E::Settings::from_slots(config.slots()));
            core.set_quaternion(Quat::IDENTITY);
            for i in 0..warm {
                let s = rig_sample(0, i, true);
                core.update(s.dt, s.gyro.unwrap(), s.accel, s.mag);
            }
            let still = Vec3::new(0.0, 0.0, 9.81);
            let field = Some(Vec3::new(0.0, 20.0, -40.0));
            let cases = [
                (1e300, Vec3::ZERO, Some(still), field),
                (f64::MAX, Vec3::ZERO, Some(still), None),
                (0.01, Vec3::new(1e300, -1e300, 1e300), Some(still), field),
                (0.01, Vec3::new(0.0, f64::MAX, 0.0), None, None),
                (1e300, Vec3::new(3.0, 0.0, 0.0), None, None),
                (0.01, Vec3::ZERO, Some(Vec3::new(1e300, 1e300, 0.0)), field),
                // McGinnis at rest, tilted: the bias step (10) overflows.
                (1e300, Vec3::ZERO, Some(Vec3::new(1.0, 0.0, 9.75)), None),
            ];
            for (dt, gyro, accel, mag) in cases {
                let before = core.clone();
                if core.update(dt, gyro, accel, mag).is_none() {
                    failures += 1;
                    let case = format!("{:?} (warm {warm}) dt {dt} {gyro:?} {accel:?}", E::KIND);
                    if !E::FAILURE_RESTARTS {
                        assert_eq!(core, before, "{case}");
                    } else {
                        assert_eq!(core.quaternion(), before.quaternion(), "{case}");
                        assert_eq!(core.settings(), before.settings(), "{case}");
                        for i in 0..300 {
                            let s = rig_sample(0, i, true);
                            assert!(core.update(s.dt, s.gyro.unwrap(), s.accel, s.mag).is_some(), "{case}");
                        }
                        assert!(core.quaternion().is_finite(), "{case}");
                    }
                }
                core = before;
            }
        }
        failures
    }
    let mut total = 0;
    for kind in Kind::ALL {
        let config = Config::new(kind).unwrap();
        total += with_kind!(kind, E => failures::<E>(&config));
    }
    // Not vacuous: these inputs do make cores fail.
    assert!(total >= 6, "{total}");
}

/// set_param keeps the estimate; GMVDK's relative_output changes what the output is
/// relative to (the header says so), and switching back gives the same bits.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn set_param_keeps_the_estimate_and_relative_output_changes_the_reference() {
    let mut f = Filter::new(&Config::new(Kind::Gmvdk).unwrap()).unwrap();
    for i in 0..400 {
        let s = Sample { gyro: Some(Vec3::ZERO), ..rig_sample(0, 0, true) };
        let s = if i < 150 { s } else { rig_sample(0, i, true) };
        f.update(&s).unwrap();
    }
    assert!(f.is_initialized());
    let absolute = f.quaternion();
    f.set_param(id::GMVDK_RELATIVE_OUTPUT, 1.0).unwrap();
    let relative = f.quaternion();
    let g = f.gmvdk().unwrap();
    assert!(relative.angle_to(g.start_pose().conj() * absolute) < 1e-12);
    assert!(relative.angle_to(absolute) > 1e-3, "the start-up pose is not the earth frame here");
    f.set_param(id::GMVDK_RELATIVE_OUTPUT, 0.0).unwrap();
    assert_eq!(f.quaternion(), absolute);
    // Any other setting keeps the output as it was.
    f.set_param(id::GMVDK_SLOPE_ALPHA, 0.5).unwrap();
    f.set_param(id::GAP_DT, 2.0).unwrap();
    assert_eq!(f.quaternion(), absolute);
}

#[test]
fn the_quick_check_accepts_only_what_the_exact_rules_accept() {
    let values = [
        0.0,
        -0.0,
        1e-200,
        -1e-170,
        f64::MIN_POSITIVE,
        5e-324,
        1e-9,
        0.01,
        -3.0,
        9.81,
        1e154,
        -1e160,
        1e300,
        f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
    ];
    let pick = |i: usize| values[i % values.len()];
    let vector = |i: usize| match i % 7 {
        0 => None,
        _ => Some(Vec3::new(pick(i), pick(i / 3 + 1), pick(i / 5 + 2))),
    };
    // Fewer under Miri, where each sample costs a thousand times more.
    let n = if cfg!(miri) { 4_000 } else { 20_000 };
    let mut accepted = 0;
    for (range, initialised) in [(0.0, false), (0.0, true), (20.0, true), (1e4, true)] {
        let mut f = Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap();
        f.set_param(id::GYRO_RANGE, range).unwrap();
        f.set_param(id::ACCEL_RANGE, 0.5 * range).unwrap();
        if initialised {
            f.set_quaternion(Quat::IDENTITY).unwrap();
        }
        for i in 0..n {
            let s = Sample {
                dt: pick(i / 11),
                gyro: vector(i),
                accel: vector(i / 2 + 3),
                mag: vector(i / 4 + 5),
            };
            let quick = f.plainly_valid(&s);
            assert!(!quick || f.check_exactly(&s).is_ok(), "{s:?}");
            accepted += quick as usize;
        }
    }
    // Not a vacuous check: ordinary samples take the quick path, with or without
    // sensor ranges set.
    assert!(accepted > n / 200, "{accepted}");
    let mut f = Filter::new(&Config::new(Kind::Mahony).unwrap()).unwrap();
    assert!(f.plainly_valid(&rig_sample(0, 0, true)));
    f.set_param(id::GYRO_RANGE, 35.0).unwrap();
    f.set_param(id::ACCEL_RANGE, 160.0).unwrap();
    assert!(f.plainly_valid(&rig_sample(0, 0, true)));
}

#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_group_update_is_bit_identical_to_single_updates() {
    for mag in [false, true] {
        let config = Config::new(Kind::Madgwick).unwrap();
        let mut group: Vec<Filter> = (0..4).map(|_| Filter::new(&config).unwrap()).collect();
        let mut single = group.clone();
        for i in 0..500 {
            let samples: Vec<Sample> = (0..4).map(|k| rig_sample(k, i, mag)).collect();
            {
                let [a, b, c, d] = &mut group[..] else { unreachable!() };
                let refs = [&samples[0], &samples[1], &samples[2], &samples[3]];
                if i == 0 {
                    // Initialisation takes the scalar path.
                    Filter::update_group(&mut [a, b, c, d], refs).unwrap();
                } else {
                    // Afterwards the lanes must take every step, a group of LANES at a time,
                    // but the rest watch's looks (every WATCH_EVERY steps after the first),
                    // which the policies' path takes alone.
                    let looks = i % usize::from(crate::filters::pipeline::watch::WATCH_EVERY) == 0;
                    let mut fs: Vec<&mut Filter> = vec![a, b, c, d];
                    for (k, (chunk, ss)) in fs.chunks_mut(LANES).zip(refs.chunks(LANES)).enumerate() {
                        let chunk = <&mut [&mut Filter; LANES]>::try_from(chunk).unwrap();
                        let ss = <[&Sample; LANES]>::try_from(ss).unwrap();
                        let laned = Filter::try_lanes::<_, false>(chunk, ss, |_, _| ());
                        assert_eq!(laned, (!looks).then_some(()), "step {i} group {k}");
                        if looks {
                            for (f, s) in chunk.iter_mut().zip(ss) {
                                f.update(s).unwrap();
                            }
                        }
                    }
                }
            }
            for (f, s) in single.iter_mut().zip(&samples) {
                f.update(s).unwrap();
            }
            for (g, s) in group.iter().zip(&single) {
                let (a, b) = (g.quaternion(), s.quaternion());
                assert!(
                    a.w.to_bits() == b.w.to_bits()
                        && a.x.to_bits() == b.x.to_bits()
                        && a.y.to_bits() == b.y.to_bits()
                        && a.z.to_bits() == b.z.to_bits()
                        && g.flags() == s.flags(),
                    "mag {mag} step {i}: {a:?} vs {b:?}"
                );
            }
        }
        assert_eq!(group, single);
    }
}

/// A pair whose lanes disagree (one sample with a magnetometer reading and one without,
/// either way round; or a field with a horizontal part in one lane only) is declined
/// by the lanes with nothing changed, and the group gives what single updates give.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_pair_whose_lanes_differ_is_declined_and_matches_single_updates() {
    let config = Config::new(Kind::Madgwick).unwrap();
    let warm = |k: usize| {
        let mut f = Filter::new(&config).unwrap();
        for i in 0..50 {
            f.update(&rig_sample(k, i, true)).unwrap();
        }
        f
    };
    let bits = |f: &Filter| {
        let q = f.quaternion();
        ([q.w, q.x, q.y, q.z].map(f64::to_bits), f.flags())
    };
    // Straight down: with the estimate level (set below), no horizontal part.
    let vertical = Sample { mag: Some(Vec3::new(0.0, 0.0, -40.0)), ..rig_sample(1, 50, true) };
    let cases = [
        ("MARG, IMU", rig_sample(0, 50, true), rig_sample(1, 50, false), false),
        ("IMU, MARG", rig_sample(0, 50, false), rig_sample(1, 50, true), false),
        ("a vertical field in the second lane", rig_sample(0, 50, true), vertical, true),
    ];
    for (what, s0, s1, level) in cases {
        let (mut a, mut b) = (warm(0), warm(1));
        if level {
            b.set_quaternion(Quat::IDENTITY).unwrap();
            // Not declined for another reason: with a horizontal field the pair takes
            // the lanes.
            let (mut a2, mut b2) = (a.clone(), b.clone());
            let s = rig_sample(1, 50, true);
            assert_eq!(
                Filter::try_lanes::<_, false>(&mut [&mut a2, &mut b2], [&s0, &s], |_, _| ()),
                Some(())
            );
        }
        let (mut a1, mut b1) = (a.clone(), b.clone());
        assert_eq!(
            Filter::try_lanes::<_, false>(&mut [&mut a, &mut b], [&s0, &s1], |_, _| ()),
            None,
            "{what}"
        );
        assert_eq!((&a, &b), (&a1, &b1), "{what}: declined with a change");
        Filter::update_group(&mut [&mut a, &mut b], [&s0, &s1]).unwrap();
        a1.update(&s0).unwrap();
        b1.update(&s1).unwrap();
        assert_eq!([bits(&a), bits(&b)], [bits(&a1), bits(&b1)], "{what}");
        assert_eq!((&a, &b), (&a1, &b1), "{what}");
    }
}

#[test]
fn a_group_stops_at_a_bad_sample_like_single_updates() {
    let config = Config::new(Kind::Madgwick).unwrap();
    let mut group: Vec<Filter> = (0..4).map(|_| Filter::new(&config).unwrap()).collect();
    let mut single = group.clone();
    let mut samples: Vec<Sample> = (0..4).map(|k| rig_sample(k, 0, true)).collect();
    for (f, s) in group.iter_mut().zip(&samples) {
        f.update(s).unwrap();
    }
    for (f, s) in single.iter_mut().zip(&samples) {
        f.update(s).unwrap();
    }
    // The bad sample second in its lane pair (its pair's first filter is updated), then
    // first in it.
    for bad in [3, 2] {
        let mut spoiled = samples.clone();
        spoiled[bad].mag = Some(Vec3::new(f64::NAN, 0.0, 0.0));
        let result = {
            let [a, b, c, d] = &mut group[..] else { unreachable!() };
            Filter::update_group(&mut [a, b, c, d], [&spoiled[0], &spoiled[1], &spoiled[2], &spoiled[3]])
        };
        assert_eq!(result, Err((bad, Error::NonFinite(Field::Mag))));
        for (f, s) in single.iter_mut().zip(&spoiled).take(bad) {
            f.update(s).unwrap();
        }
        assert_eq!(group, single, "bad sample {bad}");
    }
    // A gap (dt above gap_dt) takes the same path as alone, flag included.
    samples[2] = rig_sample(2, 1, true);
    samples[1].dt = 5.0;
    {
        let [a, b, c, d] = &mut group[..] else { unreachable!() };
        Filter::update_group(&mut [a, b, c, d], [&samples[0], &samples[1], &samples[2], &samples[3]])
            .unwrap();
    }
    for (f, s) in single.iter_mut().zip(&samples) {
        f.update(s).unwrap();
    }
    assert_eq!(group, single);
    assert!(group[1].flags() & flags::GAP != 0);
}

fn madgwick() -> Filter {
    Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap()
}

fn good() -> Sample {
    Sample {
        dt: 0.01,
        gyro: Some(Vec3::new(0.1, -0.2, 0.3)),
        accel: Some(Vec3::new(0.5, 0.2, 9.7)),
        mag: Some(Vec3::new(10.0, 20.0, -40.0)),
    }
}

/// Whether a parameter's sentence names where its default comes from: the paper (or VQF,
/// robust's reference), or orient, as a word ("orientation" does not count).
fn names_a_source(doc: &str) -> bool {
    let orient_word = doc.match_indices("orient").any(|(i, w)| {
        let before = doc[..i].chars().next_back().map_or(true, |c| !c.is_alphanumeric());
        let after = doc[i + w.len()..].chars().next().map_or(true, |c| !c.is_alphanumeric());
        before && after
    });
    doc.contains("paper") || doc.contains("VQF") || orient_word
}

#[test]
fn every_kind_is_built_and_has_documented_parameters() {
    assert!(!names_a_source("the orientation, default 1") && names_a_source("default 1 (orient: x)"));
    for k in Kind::ALL {
        assert!(Config::new(k).is_ok());
        for p in k.params() {
            assert!(p.accepts(p.default), "{k:?} {}", p.name);
            assert!(p.doc.contains("default") || p.doc.contains("Default"), "{k:?} {}", p.name);
            assert!(names_a_source(p.doc), "{k:?} {}: the default's source (paper, VQF or orient)", p.name);
            assert_eq!(k.param_by_name(p.name).map(|q| q.id), Some(p.id), "duplicate name {}", p.name);
        }
    }
}

#[test]
fn defaults_come_from_the_tables() {
    let c = Config::new(Kind::Madgwick).unwrap();
    assert_eq!(c.param(id::MADGWICK_BETA_IMU), Ok(0.041));
    assert_eq!(c.param(id::MADGWICK_BETA_MARG), Ok(0.041));
    assert_eq!(c.param(id::GRAVITY), Ok(9.80665));
    assert_eq!(c.param(40), Err(Error::UnknownParam(40)));
}

#[test]
fn bad_samples_leave_the_state_bit_identical() {
    let mut f = madgwick();
    f.update(&good()).unwrap();
    f.set_param(id::GYRO_RANGE, 30.0).unwrap();
    f.set_param(id::ACCEL_RANGE, 150.0).unwrap();
    let before = f.clone();
    let nan = f64::NAN;
    let cases: Vec<(Sample, Error)> = vec![
        (Sample { dt: 0.0, ..good() }, Error::InvalidDt(0.0)),
        (Sample { dt: -0.01, ..good() }, Error::InvalidDt(-0.01)),
        (Sample { gyro: None, ..good() }, Error::MissingSensor(Field::Gyro)),
        (Sample { gyro: Some(Vec3::new(nan, 0.0, 0.0)), ..good() }, Error::NonFinite(Field::Gyro)),
        (Sample { gyro: Some(Vec3::new(0.0, 31.0, 0.0)), ..good() }, Error::Saturated(Field::Gyro)),
        (Sample { accel: Some(Vec3::ZERO), ..good() }, Error::ZeroVector(Field::Accel)),
        (Sample { accel: Some(Vec3::new(0.0, 0.0, -150.0)), ..good() }, Error::Saturated(Field::Accel)),
        (
            Sample { accel: Some(Vec3::new(f64::INFINITY, 0.0, 1.0)), ..good() },
            Error::NonFinite(Field::Accel),
        ),
        (Sample { mag: Some(Vec3::ZERO), ..good() }, Error::ZeroVector(Field::Mag)),
        (Sample { mag: Some(Vec3::new(1e200, 1e200, 0.0)), ..good() }, Error::TooLarge(Field::Mag)),
    ];
    for (s, e) in cases {
        let got = f.update(&s).unwrap_err();
        match (got, e) {
            (Error::InvalidDt(a), Error::InvalidDt(b)) => assert_eq!(a.to_bits(), b.to_bits()),
            _ => assert_eq!(got, e),
        }
        assert_eq!(f, before, "{s:?}");
    }
    let nan_dt = f.update(&Sample { dt: nan, ..good() });
    assert!(matches!(nan_dt, Err(Error::InvalidDt(_))));
    assert_eq!(f, before);
}

#[test]
fn acc_mag_init_waits_for_an_accelerometer() {
    let mut f = madgwick();
    assert!(!f.is_initialized());
    let gyro_only = Sample { accel: None, mag: None, ..good() };
    assert_eq!(f.update(&gyro_only), Err(Error::NotInitialized));
    f.update(&good()).unwrap();
    assert!(f.is_initialized());
    // Right after init the reported gravity points along the measured accelerometer.
    let g = f.gravity().normalized();
    assert!((g - good().accel.unwrap().normalized()).norm() < 0.01);
    f.update(&gyro_only).unwrap();
    assert_eq!(f.flags() & flags::ACCEL_USED, 0);
}

#[test]
fn frames_differ_by_their_constant_rotation() {
    // Start away from the measurements: at a perfectly consistent estimate the
    // gradient is rounding noise and (30) steps in its arbitrary direction, which
    // would make the runs differ by β·dt for reasons unrelated to frames.
    let q0 = Quat::from_axis_angle(Vec3::new(0.3, -0.2, 1.0), 0.8);
    let run = |frame: Frame| {
        let mut c = Config::new(Kind::Madgwick).unwrap();
        c.frame = frame;
        c.init = Init::Given(Frame::Enu.rotation_to(frame).map_or(q0, |r| r * q0));
        let mut f = Filter::new(&c).unwrap();
        for i in 0..200 {
            let t = i as f64 * 0.01;
            f.update(&Sample { dt: 0.01, gyro: Some(Vec3::new(0.3 * t.sin(), 0.2, -0.1)), ..good() })
                .unwrap();
        }
        f.quaternion()
    };
    let enu = run(Frame::Enu);
    for frame in [Frame::Ned, Frame::Nwu] {
        let q = run(frame);
        let c = Frame::Enu.rotation_to(frame).unwrap();
        assert!(q.angle_to(c * enu) < 1e-12, "{frame:?} {}", q.angle_to(c * enu));
    }
}

/// The read's quick path (one test of `Runner::UNINIT` with the relative and hosted
/// bits, and `Runner::REFRAME` for a kind native in the default frame) gives what the
/// orientation in the configured frame gives, the identity exactly before
/// initialisation, in every frame and through every way in and out of it: the first
/// samples (and start-up periods), `set_quaternion`, `reset`, and snapshots of either
/// state.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_read_is_the_identity_exactly_until_initialisation() {
    let q0 = Quat::from_axis_angle(Vec3::new(0.3, -0.2, 1.0), 0.8);
    for (kind, frame) in Kind::ALL.into_iter().flat_map(|k| Frame::ALL.map(|f| (k, f))) {
        let mut config = Config::new(kind).unwrap();
        config.frame = frame;
        let mut f = Filter::new(&config).unwrap();
        let same = |f: &Filter| f.quaternion() == f.frame_quaternion();
        let mut blob = vec![0u8; f.state_size()];
        f.save(&mut blob).unwrap();
        let fresh_blob = blob.clone();
        assert!(!f.is_initialized() && f.quaternion() == Quat::IDENTITY, "{kind:?} {frame:?}");
        // Still samples, so that the kinds with a start-up period (a still period for
        // the complementary filter) finish it.
        let still = Sample { gyro: Some(Vec3::new(0.001, -0.002, 0.001)), ..good() };
        for i in 0..400 {
            f.update(&still).unwrap();
            assert!(same(&f), "{kind:?} {frame:?} {i}");
            assert!(f.is_initialized() || f.quaternion() == Quat::IDENTITY, "{kind:?} {frame:?} {i}");
        }
        assert!(f.is_initialized(), "{kind:?} {frame:?}");
        f.load(&fresh_blob).unwrap();
        assert!(!f.is_initialized() && f.quaternion() == Quat::IDENTITY && same(&f), "{kind:?} {frame:?}");
        f.set_quaternion(q0).unwrap();
        assert!(f.is_initialized() && f.quaternion().angle_to(q0) < 1e-12 && same(&f), "{kind:?} {frame:?}");
        f.save(&mut blob).unwrap();
        f.reset();
        assert!(!f.is_initialized() && f.quaternion() == Quat::IDENTITY && same(&f), "{kind:?} {frame:?}");
        f.load(&blob).unwrap();
        assert!(f.is_initialized() && f.quaternion().angle_to(q0) < 1e-12 && same(&f), "{kind:?} {frame:?}");
    }
}

/// A pending re-acquisition keeps every kind off its usual step (`Runner::UNSETTLED`)
/// through each way it can be left pending: a gap without an accelerometer reading, a
/// snapshot of that state loaded into a fresh filter, and a clipped gyroscope reading
/// whose policy is then turned off. The next sample with an accelerometer reading
/// re-acquires, and the one after it is a usual step again.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn a_pending_reacquisition_is_never_skipped() {
    let reacquisition = |f: &Filter| f.flags() & (flags::REACQUIRED | flags::REACQUIRE_PENDING);
    let still = Sample { gyro: Some(Vec3::new(0.001, -0.002, 0.001)), ..good() };
    for kind in Kind::ALL {
        let mut c = Config::new(kind).unwrap();
        c.init = Init::Identity;
        c.set_param(id::GYRO_RANGE, 10.0).unwrap();
        // Past any start-up period.
        let mut f = Filter::new(&c).unwrap();
        for _ in 0..400 {
            f.update(&still).unwrap();
        }
        assert_eq!(reacquisition(&f), 0, "{kind:?}");
        let mut blob = vec![0u8; f.state_size()];
        // A gap ending on a gyroscope-only sample; then a snapshot, loaded into a fresh
        // filter.
        let mut gapped = f.clone();
        gapped.update(&Sample { dt: 5.0, accel: None, mag: None, ..still }).unwrap();
        assert_eq!(reacquisition(&gapped), flags::REACQUIRE_PENDING, "{kind:?}");
        gapped.save(&mut blob).unwrap();
        let mut loaded = Filter::new(&c).unwrap();
        loaded.load(&blob).unwrap();
        // A clipped gyroscope reading under the recovery policy, then the policy off.
        let mut clipped = f.clone();
        clipped.set_param(id::SATURATION_RECOVERY, 1.0).unwrap();
        clipped.update(&Sample { gyro: Some(Vec3::new(12.0, 0.0, 0.0)), ..still }).unwrap();
        assert_eq!(reacquisition(&clipped), flags::REACQUIRE_PENDING, "{kind:?}");
        clipped.set_param(id::SATURATION_RECOVERY, 0.0).unwrap();
        // The rig's group step (the lanes, for Madgwick) re-acquires too.
        let (mut a, mut b) = (gapped.clone(), loaded.clone());
        Filter::update_group(&mut [&mut a, &mut b], [&still, &still]).unwrap();
        assert_eq!([reacquisition(&a), reacquisition(&b)], [flags::REACQUIRED; 2], "{kind:?} group");
        for (how, g) in [("gap", &mut gapped), ("loaded", &mut loaded), ("clipped", &mut clipped)] {
            g.update(&still).unwrap();
            assert_eq!(reacquisition(g), flags::REACQUIRED, "{kind:?} {how}");
            g.update(&still).unwrap();
            assert_eq!(reacquisition(g), 0, "{kind:?} {how}");
        }
    }
}

#[test]
fn reset_returns_to_the_fresh_state_and_keeps_settings() {
    let mut f = madgwick();
    f.set_param(id::MADGWICK_BETA_IMU, 0.2).unwrap();
    f.update(&good()).unwrap();
    f.reset();
    let mut fresh = Filter::new(&f.config()).unwrap();
    fresh.set_param(id::MADGWICK_BETA_IMU, 0.2).unwrap();
    assert_eq!(f, fresh);
    assert!(!f.is_initialized());
}

#[test]
fn linear_accel_is_zero_for_a_pure_gravity_reading() {
    let mut c = Config::new(Kind::Madgwick).unwrap();
    c.init = Init::Given(Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.4));
    let f = Filter::new(&c).unwrap();
    let mut g = f.clone();
    let reading = f.gravity();
    assert!((reading.norm() - 9.80665).abs() < 1e-12);
    g.update(&Sample { dt: 1e-9, gyro: Some(Vec3::ZERO), accel: Some(reading), mag: None }).unwrap();
    assert!(g.linear_accel().unwrap().norm() < 1e-6);
    assert!(f.linear_accel().is_none());
}

/// Each kind's usual step ([`Estimator::update_usual`]) gives what its update gives, bit
/// for bit, and changes nothing when it declines (the lifecycle then takes the update):
/// random estimates and readings, with and without each reading, with each kind's
/// options (those that keep it from its usual step too), and readings that make the step
/// decline.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn the_usual_step_is_the_update() {
    let (mut taken, mut declined, mut rests) = (0, 0, 0);
    for kind in Kind::ALL {
        let (t, d, r) = with_kind!(kind, E => usual_is_update::<E>());
        taken += t;
        declined += d;
        rests += r;
    }
    // Not vacuous: the usual steps, their declines and steps at rest are exercised.
    assert!(taken > 10_000 && declined > 1_000 && rests > 100, "{taken} {declined} {rests}");
}

fn usual_is_update<E: Estimator>() -> (usize, usize, usize) {
    use crate::filters::pipeline::sample::{Checked, Usual};
    if !E::USUAL {
        return (0, 0, 0);
    }
    let mut u = crate::math::test_uniform(5);
    let (mut taken, mut declined, mut rests) = (0, 0, 0);
    for options in [&[][..], &[("ki", 0.3)][..], &[("rest_bias_tau", 2.0)][..]] {
        let mut config = Config::new(E::KIND).unwrap();
        for (name, value) in options {
            if let Some(r) = config.set(name, *value) {
                r.unwrap();
            }
        }
        let mut core = E::create(E::Settings::from_slots(config.slots()));
        for i in 0..6000 {
            if i % 50 == 0 {
                let q = Quat::new(u(), u(), u(), u()).normalized();
                core.set_quaternion(if i % 100 == 0 { Quat::IDENTITY } else { q });
            }
            let mut v = |scale: f64| Vec3::new(u(), u(), u()) * scale;
            // Slow turns, for the kinds' rest tests, and fast ones.
            let gyro = if i % 4 == 0 { v(0.01) } else { v(3.0) };
            // Level and still against an identity estimate: a zero gradient. Gravity's
            // norm half the time, for the rest tests.
            let accel = match i {
                _ if i % 100 == 0 => Vec3::new(0.0, 0.0, 9.81),
                _ if i % 2 == 0 => v(1.0).normalized() * 9.81,
                _ => v(12.0),
            };
            let (accel, mag) = ((i % 7 != 3).then_some(accel), (i % 3 != 0).then(|| v(50.0)));
            let s = Usual {
                dt: 0.01 * (1.0 + u()),
                gyro,
                accel: accel.map(Checked::of),
                mag: mag.map(Checked::of),
            };
            let mut usual = core.clone();
            let mut general = core.clone();
            // The lifecycle takes the usual step only with the settings it is for.
            let result = if core.usual_settings() { usual.update_usual(&s) } else { None };
            match result {
                Some(flags) => {
                    let step = general.update(s.dt, gyro, accel, mag);
                    assert_eq!(step.map(|st| st.flags(accel.is_some(), mag.is_some())), Some(flags), "{i}");
                    assert_eq!(usual, general, "{i}");
                    taken += 1;
                    rests += usual.at_rest() as usize;
                }
                None => {
                    assert_eq!(usual, core, "{i}");
                    declined += 1;
                }
            }
            core.update(s.dt, gyro, accel, mag);
        }
    }
    (taken, declined, rests)
}

/// An option that keeps a kind from its usual step (the rest-bias learner) takes effect
/// however it is set: in the `Config`, by `set_param` on a running filter, or in a
/// loaded snapshot. All three learn the bias at rest.
#[test]
#[cfg_attr(miri, ignore = "libm's inline-asm sqrt or a long loop: too slow or unsupported under Miri")]
fn options_that_keep_a_kind_from_its_usual_step_take_effect_however_set() {
    for (kind, slot) in
        [(Kind::Madgwick, id::MADGWICK_REST_BIAS_TAU), (Kind::Mahony, id::MAHONY_REST_BIAS_TAU)]
    {
        let still = Sample {
            dt: 0.01,
            gyro: Some(Vec3::new(0.001, -0.002, 0.01)),
            accel: Some(Vec3::new(0.0, 0.0, 9.81)),
            mag: None,
        };
        let mut config = Config::new(kind).unwrap();
        config.set_param(slot, 2.0).unwrap();
        let mut by_config = Filter::new(&config).unwrap();
        let mut by_param = Filter::new(&Config::new(kind).unwrap()).unwrap();
        for f in [&mut by_config, &mut by_param] {
            f.update(&still).unwrap();
        }
        by_param.set_param(slot, 2.0).unwrap();
        let mut blob = vec![0; by_param.state_size()];
        by_param.save(&mut blob).unwrap();
        let mut by_load = Filter::new(&Config::new(kind).unwrap()).unwrap();
        by_load.load(&blob).unwrap();
        for _ in 0..600 {
            for f in [&mut by_config, &mut by_param, &mut by_load] {
                f.update(&still).unwrap();
            }
        }
        for f in [&by_config, &by_param, &by_load] {
            let bias = f.diagnostics().gyro_bias;
            assert!(bias.z > 0.008 && f.flags() & flags::REST != 0, "{kind:?}: {bias:?}");
        }
        // The loaded filter goes on exactly as the one it was saved from (by_config's
        // detector started a sample earlier).
        assert_eq!(by_load.diagnostics().gyro_bias, by_param.diagnostics().gyro_bias, "{kind:?}");
        assert_eq!(by_load.quaternion(), by_param.quaternion(), "{kind:?}");
    }
}

/// `Common` keeps the squares of the gyroscope's and accelerometer's limits (the quick
/// check compares squared norms) and gives the limits back as their roots: in binary
/// floating point `√(x²)` rounds to `x` when `x²` neither overflows nor underflows.
/// Checked over both ranges, log-uniform, and at their ends.
#[test]
#[cfg_attr(miri, ignore = "a long loop: too slow under Miri")]
fn the_root_of_a_squared_limit_is_the_limit() {
    let mut u = crate::math::test_uniform(41);
    for (lo, hi) in [(0.1, MAX_GYRO), (1.0, MAX_ACCEL)] {
        for i in 0..200_000 {
            let x = match i {
                0 => lo,
                1 => hi,
                _ => lo * (hi / lo).powf(0.5 * (u() + 1.0)),
            };
            assert_eq!((x * x).sqrt(), x, "{x:e}");
        }
    }
}

/// The lanes negate as IEEE arithmetic does (−0 stays −0), so a pair gives the single
/// updates' bits even with zeros: an estimate with a −0 component, no rotation, readings
/// with zero components.
#[test]
fn a_pair_keeps_the_sign_of_zero_like_single_updates() {
    let mut config = Config::new(Kind::Madgwick).unwrap();
    config.frame = Frame::Nwu; // Madgwick's native frame: the estimate is stored as set.
    let mut pair: Vec<Filter> = (0..LANES).map(|_| Filter::new(&config).unwrap()).collect();
    for f in &mut pair {
        f.set_quaternion(Quat::new(-0.0, 1.0, 0.0, 0.0)).unwrap();
    }
    let mut single = pair.clone();
    for mag in [None, Some(Vec3::new(0.0, 20.0, -40.0))] {
        let s = Sample { dt: 0.01, gyro: Some(Vec3::ZERO), accel: Some(Vec3::new(1.0, 0.0, -9.7)), mag };
        let mut fs: Vec<&mut Filter> = pair.iter_mut().collect();
        let fs = <&mut [&mut Filter; LANES]>::try_from(&mut fs[..]).unwrap();
        assert_eq!(Filter::try_lanes::<_, false>(fs, [&s; LANES], |_, _| ()), Some(()), "{mag:?}");
        for (g, f) in pair.iter().zip(&mut single) {
            f.update(&s).unwrap();
            let (a, b) = (g.quaternion(), f.quaternion());
            let bits = |q: Quat| [q.w, q.x, q.y, q.z].map(f64::to_bits);
            assert_eq!(bits(a), bits(b), "{mag:?}: {a:?} vs {b:?}");
        }
    }
}

/// The header's "a magnetometer parallel to gravity gives no heading, so that step is an
/// IMU update (ORIENT_FLAG_MAG_USED clear)", for every kind: on the step that ends
/// start-up (the still period's mean field vertical; McGinnis' filter taking its heading
/// from the field) and on a step afterwards.
#[test]
#[cfg_attr(miri, ignore = "start-up periods of a few hundred samples per kind")]
fn a_field_parallel_to_gravity_is_not_used_for_heading() {
    let accel = Vec3::new(0.0, 0.0, 9.81);
    let vertical = Sample {
        dt: 0.01,
        gyro: Some(Vec3::ZERO),
        accel: Some(accel),
        mag: Some(Vec3::new(0.0, 0.0, -45.0)),
    };
    for kind in Kind::ALL {
        let mut config = Config::new(kind).unwrap();
        if kind == Kind::Complementary {
            config.set("align_heading", 1.0).unwrap().unwrap();
        }
        let mut f = Filter::new(&config).unwrap();
        let mut n = 0;
        while f.flags() & flags::INITIALIZED == 0 && n < 10_000 {
            f.update(&vertical).unwrap();
            n += 1;
        }
        assert!(f.flags() & flags::INITIALIZED != 0, "{kind:?}");
        assert_eq!(f.flags() & flags::MAG_USED, 0, "{kind:?}: start-up with a vertical field");
        f.update(&vertical).unwrap();
        assert_eq!(f.flags() & flags::MAG_USED, 0, "{kind:?}: a step with a vertical field");
        assert!(f.quaternion().is_finite(), "{kind:?}");
    }
}
