//! The bad-input matrix: every kind × every sample field × NaN, ±Inf, subnormal, -0,
//! huge; zero, near-zero and overflowing vectors; a gap; dt going backwards. Each case
//! returns its documented result (orient_filter_update's doc in include/orient.h), and a
//! rejected sample leaves the state bit-identical.

mod common;

use common::sim::{simulate, Moment};
use orient::{Config, Error, Field, Filter, Kind, Quat, Sample, Vec3};

fn warmed(kind: Kind) -> (Filter, Sample) {
    let run = simulate(Quat::IDENTITY, 4.0, 100.0, (0.002, 0.02, 0.2), |t| Moment {
        omega: if t < 3.0 { Vec3::ZERO } else { Vec3::new(0.2, -0.1, 0.3) },
        ..Default::default()
    });
    let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
    for s in &run.samples {
        f.update(s).unwrap();
    }
    assert!(f.is_initialized());
    (f, *run.samples.last().unwrap())
}

fn set(s: &mut Sample, field: usize, v: f64) {
    let comp = |o: &mut Option<Vec3>, i: usize| {
        let mut x = o.unwrap();
        match i {
            0 => x.x = v,
            1 => x.y = v,
            _ => x.z = v,
        }
        *o = Some(x);
    };
    match field {
        0 => s.dt = v,
        1..=3 => comp(&mut s.gyro, field - 1),
        4..=6 => comp(&mut s.accel, field - 4),
        _ => comp(&mut s.mag, field - 7),
    }
}

#[test]
fn every_field_of_every_kind_against_every_bad_value() {
    let sub = f64::from_bits(1); // smallest subnormal
    for kind in Kind::ALL {
        let (f0, good) = warmed(kind);
        for field in 0..10 {
            for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, sub, -0.0, 1e300] {
                let mut f = f0.clone();
                let mut s = good;
                set(&mut s, field, v);
                let result = f.update(&s);
                let name = format!("{kind:?} field {field} = {v:e}");
                let sensor = match field {
                    1..=3 => Field::Gyro,
                    4..=6 => Field::Accel,
                    _ => Field::Mag,
                };
                let expected_rejection = if !v.is_finite() {
                    Some(if field == 0 { Error::InvalidDt(v) } else { Error::NonFinite(sensor) })
                } else if field == 0 && !(orient::filters::MIN_DT..=orient::filters::MAX_DT).contains(&v) {
                    Some(Error::InvalidDt(v))
                } else if v == 1e300 && field >= 1 {
                    // Beyond every physical bound: refused before any arithmetic.
                    Some(Error::TooLarge(sensor))
                } else {
                    None
                };
                match (result, expected_rejection) {
                    (Err(e), Some(want)) => {
                        let same = match (e, want) {
                            (Error::InvalidDt(a), Error::InvalidDt(b)) => a.to_bits() == b.to_bits(),
                            _ => e == want,
                        };
                        assert!(same, "{name}: {e:?}, documented {want:?}");
                        assert_eq!(f, f0, "{name}: rejected, yet the state changed");
                    }
                    (Ok(()), None) => {
                        let q = f.quaternion();
                        assert!(q.is_finite() && (q.norm() - 1.0).abs() < 1e-12, "{name}: {q:?}");
                    }
                    (r, want) => panic!("{name}: got {r:?}, documented {want:?}"),
                }
            }
        }
        // Whole vectors: zero, all-subnormal, near-zero (norm² below DBL_MIN), tiny but
        // usable, overflowing.
        for (v, accel_result) in [
            (Vec3::ZERO, Some(Error::ZeroVector(Field::Accel))),
            (Vec3::new(sub, sub, sub), Some(Error::ZeroVector(Field::Accel))),
            (Vec3::new(1e-160, 1e-160, 1e-160), Some(Error::ZeroVector(Field::Accel))),
            (Vec3::new(1e-150, 2e-150, 1e-150), None),
            (Vec3::new(1e200, 0.0, 1e200), Some(Error::TooLarge(Field::Accel))),
        ] {
            for (is_mag, want) in [
                (false, accel_result),
                (
                    true,
                    accel_result.map(|e| match e {
                        Error::ZeroVector(_) => Error::ZeroVector(Field::Mag),
                        _ => Error::TooLarge(Field::Mag),
                    }),
                ),
            ] {
                let mut f = f0.clone();
                let s =
                    if is_mag { Sample { mag: Some(v), ..good } } else { Sample { accel: Some(v), ..good } };
                match (f.update(&s), want) {
                    (Err(e), Some(w)) => {
                        assert_eq!(e, w, "{kind:?} {v:?}");
                        assert_eq!(f, f0);
                    }
                    (Ok(()), None) => assert!((f.quaternion().norm() - 1.0).abs() < 1e-12),
                    (r, w) => panic!("{kind:?} mag={is_mag} {v:?}: got {r:?}, documented {w:?}"),
                }
            }
        }
        // Timestamps going backwards in a batch: the step has dt <= 0.
        let mut f = f0.clone();
        let back = Sample { dt: -0.004, ..good };
        assert_eq!(f.update(&back), Err(Error::InvalidDt(-0.004)));
        assert_eq!(f, f0);
    }
}
