//! Sensor models at the extremes, every kind and sensor, through the C API: a model is
//! refused with a status orient_filter_set_sensor_model's header sentence lists and the
//! state unchanged, or accepted; then the sensor's plausible readings (the header's:
//! gyroscope 0 and up to 1 rad/s, accelerometer standard gravity in any direction,
//! magnetometer the earth's field from 0.25 to 65000 with the hard-iron offset added)
//! are accepted, and still samples that the model maps to the truth (where such raw
//! readings lie within the physical bounds) bring the inclination within 2 deg
//! (Madgwick: after its beta bound).

#[allow(dead_code)]
#[path = "common/header_statuses.rs"]
mod header_statuses;

use orient::ffi::*;

const G: f64 = 9.80665;

fn new_filter(kind: i32) -> *mut OrientFilter {
    let mut c = core::mem::MaybeUninit::<OrientConfig>::uninit();
    unsafe {
        assert_eq!(orient_config_default(kind, c.as_mut_ptr()), OrientStatus::Ok);
        let mut f = core::ptr::null_mut();
        assert_eq!(orient_filter_new(c.as_ptr(), &mut f), OrientStatus::Ok);
        f
    }
}

fn blob(f: *mut OrientFilter) -> Vec<u8> {
    let mut size = 0usize;
    unsafe {
        assert_eq!(orient_filter_state_size(f, &mut size), OrientStatus::Ok);
        let mut b = vec![0u8; size];
        let mut written = 0;
        assert_eq!(orient_filter_save(f, b.as_mut_ptr(), size, &mut written), OrientStatus::Ok);
        b
    }
}

fn copy_of(kind: i32, b: &[u8]) -> *mut OrientFilter {
    let c = new_filter(kind);
    assert_eq!(unsafe { orient_filter_load(c, b.as_ptr(), b.len()) }, OrientStatus::Ok);
    c
}

fn v(x: [f64; 3]) -> OrientVec3 {
    OrientVec3 { x: x[0], y: x[1], z: x[2] }
}

fn normalise(a: [f64; 3]) -> [f64; 3] {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// `M⁻¹ y` for the model's matrix (Cramer's rule), `None` when it overflows.
fn solve(m: &[f64; 9], y: [f64; 3]) -> Option<[f64; 3]> {
    let det3 = |a: [f64; 9]| {
        a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6])
            + a[2] * (a[3] * a[7] - a[4] * a[6])
    };
    let d = det3(*m);
    let mut x = [0.0; 3];
    for (j, xj) in x.iter_mut().enumerate() {
        let mut a = *m;
        for i in 0..3 {
            a[3 * i + j] = y[i];
        }
        *xj = det3(a) / d;
    }
    x.iter().all(|c| c.is_finite()).then_some(x)
}

fn sample(gyro: [f64; 3], accel: [f64; 3], mag: [f64; 3]) -> OrientSample {
    OrientSample {
        dt: 0.01,
        gyro: v(gyro),
        accel: v(accel),
        mag: v(mag),
        flags: ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG,
        reserved: 0,
    }
}

/// The models under test: scales 10^k of the identity and of a skewed matrix, offsets
/// 10^k along a diagonal, and both together.
fn models() -> Vec<OrientSensorModel> {
    let mut out = Vec::new();
    let exps = [
        -300, -200, -160, -155, -150, -120, -60, -10, -5, -2, 0, 1, 3, 4, 5, 6, 7, 8, 10, 11, 12, 13, 20, 60,
        150, 249, 300,
    ];
    let skew = [1.0, 0.1, 0.0, -0.05, 0.9, 0.2, 0.0, 0.03, 1.1];
    for &e in &exps {
        let k = 10f64.powi(e);
        for m in [[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], skew] {
            out.push(OrientSensorModel { matrix: m.map(|x| x * k), offset: OrientVec3::default() });
        }
        let o = OrientVec3 { x: k, y: -0.5 * k, z: 0.25 * k };
        out.push(OrientSensorModel { matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], offset: o });
        for s in [1e-3, 1e3] {
            out.push(OrientSensorModel { matrix: skew.map(|x| x * s), offset: o });
        }
    }
    // An accelerometer offset of gravity's length: a reading along it calibrates to zero.
    out.push(OrientSensorModel {
        matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        offset: OrientVec3 { x: 0.0, y: 0.0, z: G },
    });
    out
}

#[test]
fn an_accepted_model_maps_plausible_readings_to_usable_ones_and_recovers() {
    let table = header_statuses::Table::parse(include_str!("../include/orient.h"));
    let name = "orient_filter_set_sensor_model";
    // The truth: "up" in the sensor frame, tilted 27 deg; north horizontal, dip 63 deg.
    let up = normalise([0.35, -0.25, 0.9]);
    let d = up[1];
    let north = normalise([-d * up[0], 1.0 - d * up[1], -d * up[2]]);
    let field = [0, 1, 2].map(|i| 20.0 * north[i] - 40.0 * up[i]);
    let gravity = up.map(|x| G * x);
    let (mut refused, mut accepted, mut recovered) = (0, 0, 0);
    for kind in [
        OrientKind::Madgwick,
        OrientKind::Mahony,
        OrientKind::Complementary,
        OrientKind::Ekf,
        OrientKind::Gmvdk,
        OrientKind::Robust,
    ] {
        let kind = kind as i32;
        // A running filter, started level and then tilted: 2 s still.
        let f = new_filter(kind);
        for _ in 0..200 {
            let s = sample([0.0; 3], [0.0, 0.0, G], [0.0, 20.0, -40.0]);
            assert_eq!(unsafe { orient_filter_update(f, &s) }, OrientStatus::Ok);
        }
        let start = blob(f);
        let beta_bound = if kind == OrientKind::Madgwick as i32 {
            let mut b = 0.0;
            assert_eq!(
                unsafe { orient_filter_get_param(f, ORIENT_PARAM_MADGWICK_BETA_IMU, &mut b) },
                OrientStatus::Ok
            );
            (2.0 * std::f64::consts::PI / b).max(60.0)
        } else {
            60.0
        };
        for sensor in [ORIENT_SENSOR_GYRO, ORIENT_SENSOR_ACCEL, ORIENT_SENSOR_MAG] {
            for model in models() {
                let what = format!("kind {kind} sensor {sensor} {model:?}");
                let h = copy_of(kind, &start);
                let status = unsafe { orient_filter_set_sensor_model(h, sensor, &model) };
                assert!(table.allows(name, status as i32), "{what}: {status:?} is not listed");
                if status != OrientStatus::Ok {
                    assert!(
                        [OrientStatus::TooLarge, OrientStatus::ZeroVector].contains(&status),
                        "{what}: {status:?}"
                    );
                    assert!(blob(h) == start, "{what}: refused and changed the state");
                    refused += 1;
                    unsafe { orient_filter_free(h) };
                    continue;
                }
                accepted += 1;
                // The plausible readings of the header's sentence, each accepted.
                let o = [model.offset.x, model.offset.y, model.offset.z];
                let c = copy_of(kind, &blob(h));
                let dirs = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], up, normalise([-1.0, 2.0, -3.0])];
                for (i, u) in dirs.iter().enumerate() {
                    let mut s = sample([0.0; 3], gravity, field);
                    match sensor {
                        ORIENT_SENSOR_GYRO => s.gyro = v(u.map(|x| x * (i as f64 / 3.0))),
                        ORIENT_SENSOR_ACCEL => s.accel = v(u.map(|x| G * x)),
                        _ => {
                            for f in [0.25, 44.7, 65000.0] {
                                s.mag = v([0, 1, 2].map(|j| o[j] + f * u[j]));
                                let st = unsafe { orient_filter_update(c, &s) };
                                assert_eq!(st, OrientStatus::Ok, "{what}: field {f} along {u:?}");
                            }
                            continue;
                        }
                    }
                    let st = unsafe { orient_filter_update(c, &s) };
                    assert_eq!(st, OrientStatus::Ok, "{what}: reading along {u:?}");
                }
                unsafe { orient_filter_free(c) };
                // Still samples the model maps to the truth, where they are readings.
                let truth = match sensor {
                    ORIENT_SENSOR_GYRO => [0.0; 3],
                    ORIENT_SENSOR_ACCEL => gravity,
                    _ => field,
                };
                let raw = solve(&model.matrix, truth).map(|x| [0, 1, 2].map(|j| x[j] + o[j]));
                let bound = [1e4, 1e5, 1e12][sensor as usize];
                let Some(raw) = raw.filter(|r| r.iter().all(|x| x.abs() < 0.5 * bound)) else {
                    unsafe { orient_filter_free(h) };
                    continue;
                };
                let mut s = sample([0.0; 3], gravity, field);
                match sensor {
                    ORIENT_SENSOR_GYRO => s.gyro = v(raw),
                    ORIENT_SENSOR_ACCEL => s.accel = v(raw),
                    _ => s.mag = v(raw),
                }
                for i in 0..(beta_bound * 100.0) as usize {
                    let st = unsafe { orient_filter_update(h, &s) };
                    assert_eq!(st, OrientStatus::Ok, "{what}: still sample {i}");
                }
                let mut gv = OrientVec3::default();
                assert_eq!(unsafe { orient_filter_gravity(h, &mut gv) }, OrientStatus::Ok);
                let est = normalise([gv.x, gv.y, gv.z]);
                let cos = est[0] * up[0] + est[1] * up[1] + est[2] * up[2];
                let error = cos.clamp(-1.0, 1.0).acos().to_degrees();
                assert!(error < 2.0, "{what}: {error:.2} deg off after {beta_bound} s still");
                recovered += 1;
                unsafe { orient_filter_free(h) };
            }
        }
        unsafe { orient_filter_free(f) };
    }
    println!("{refused} refused, {accepted} accepted, {recovered} of them checked for recovery");
    assert!(refused > 100 && accepted > 100 && recovered > 100);
}
