//! Issue 40, classes 6, 7 and 10: the magnetometer calibrator, the gyroscope offset,
//! the sensor models and the rig calls driven as an adversarial host would, through the
//! C API. Every call returns only the statuses its header sentence lists (read from
//! include/orient.h), a refused call leaves its object exactly as it was, and after any
//! accepted input good readings give a good fit.
#![cfg(not(miri))]

mod common;

use common::rig_sim::{distort, tumble, HARD_IRON};
use common::sim::{Noise, FIELD};
use orient::ffi::*;
use orient::Vec3;
use std::collections::{BTreeMap, BTreeSet};

// ---- The header's status lists ---------------------------------------------------------

/// Each function's doc comment in include/orient.h.
fn header_docs() -> BTreeMap<String, String> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/include/orient.h")).unwrap();
    let mut docs = BTreeMap::new();
    let mut comment = String::new();
    let mut in_comment = false;
    for line in text.lines() {
        let t = line.trim();
        if t.starts_with("/**") {
            in_comment = true;
            comment.clear();
            continue;
        }
        if in_comment {
            if t.starts_with("*/") {
                in_comment = false;
            } else {
                comment.push_str(t.trim_start_matches('*').trim());
                comment.push(' ');
            }
            continue;
        }
        if let Some(i) = t.find(" orient_") {
            if t.contains('(') && !t.starts_with('#') {
                let name: String =
                    t[i + 1..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                docs.insert(name, comment.clone());
            }
        }
        if !t.is_empty() {
            comment.clear();
        }
    }
    docs
}

/// The status names of the header's enum, by value.
fn status_names() -> BTreeMap<i32, String> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/include/orient.h")).unwrap();
    text.lines()
        .filter_map(|l| {
            let l = l.trim().strip_prefix("ORIENT_STATUS_")?;
            let (name, value) = l.split_once(" = ")?;
            Some((value.trim_end_matches(',').parse().ok()?, name.to_string()))
        })
        .collect()
}

/// The statuses `function`'s header sentence lists, with OK and the preamble's
/// NULL_POINTER and INVALID_HANDLE; "Errors ... as orient_x" adds orient_x's.
fn listed(
    docs: &BTreeMap<String, String>,
    names: &BTreeMap<i32, String>,
    function: &str,
) -> BTreeSet<String> {
    let doc = docs.get(function).unwrap_or_else(|| panic!("{function} is not in the header"));
    let mut out: BTreeSet<String> = ["OK", "NULL_POINTER", "INVALID_HANDLE"].map(String::from).into();
    let words: Vec<&str> = doc.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).collect();
    for name in names.values() {
        if words.iter().any(|w| *w == name || w.strip_prefix("ORIENT_STATUS_") == Some(name)) {
            out.insert(name.clone());
        }
    }
    if let Some(i) = doc.find("Errors and checks as orient_") {
        let other: String = doc[i + 21..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        out.extend(listed(docs, names, &other));
    }
    out
}

struct Statuses {
    docs: BTreeMap<String, String>,
    names: BTreeMap<i32, String>,
}

impl Statuses {
    fn new() -> Statuses {
        Statuses { docs: header_docs(), names: status_names() }
    }

    /// Asserts that `status` is one `function`'s header sentence lists.
    fn check(&self, function: &str, status: OrientStatus, what: &str) {
        let name = &self.names[&(status as i32)];
        let allowed = listed(&self.docs, &self.names, function);
        assert!(
            allowed.contains(name),
            "{function}({what}) returned {name}, its header lists only {allowed:?}"
        );
    }
}

const EXTREMES: [f64; 16] = [
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    1e-300,
    -1e-300,
    1e300,
    -1e300,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    -1.0,
    -50.0,
    1e12,
    2e12,
    1e4,
];

fn v3(v: Vec3) -> OrientVec3 {
    OrientVec3 { x: v.x, y: v.y, z: v.z }
}

/// Vectors made of one extreme value: all three components, or one beside ordinary ones.
fn extreme_vectors() -> Vec<OrientVec3> {
    EXTREMES
        .iter()
        .flat_map(|&x| {
            [
                OrientVec3 { x, y: x, z: x },
                OrientVec3 { x, y: 20.0, z: -40.0 },
                OrientVec3 { x: 1.0, y: -2.0, z: x },
            ]
        })
        .collect()
}

// ---- The calibrator ---------------------------------------------------------------------

fn calibrator() -> OrientMagCalibrator {
    let mut c = core::mem::MaybeUninit::<OrientMagCalibrator>::uninit();
    assert_eq!(unsafe { orient_mag_calibrator_init(c.as_mut_ptr()) }, OrientStatus::Ok);
    unsafe { c.assume_init() }
}

fn add(c: &mut OrientMagCalibrator, m: Vec3) -> OrientStatus {
    unsafe { orient_mag_calibrator_add(c, &v3(m)) }
}

fn solve(c: &OrientMagCalibrator) -> Result<OrientMagFit, OrientStatus> {
    let mut fit = OrientMagFit::default();
    match unsafe { orient_mag_calibrator_solve(c, &mut fit) } {
        OrientStatus::Ok => Ok(fit),
        s => Err(s),
    }
}

fn rejected(c: &OrientMagCalibrator) -> u64 {
    let mut n = u64::MAX;
    assert_eq!(unsafe { orient_mag_calibrator_rejected(c, &mut n) }, OrientStatus::Ok);
    n
}

/// The distorted tumble's readings: a sensor with soft and hard iron turned over the
/// sphere at 50 Hz.
fn readings(seconds: f64) -> Vec<Vec3> {
    tumble(seconds).samples.iter().map(|s| distort(s.mag.unwrap())).collect()
}

/// How far a fit's hard-iron offset is from the truth, as a fraction of the field.
fn hard_iron_error(fit: &OrientMagFit) -> f64 {
    let o = fit.model.offset;
    (Vec3::new(o.x, o.y, o.z) - HARD_IRON).norm() / FIELD.norm()
}

fn same(a: &OrientMagCalibrator, b: &OrientMagCalibrator) -> bool {
    format!("{a:?}") == format!("{b:?}")
}

/// Class 6: values the filters refuse as a magnetometer reading are refused by the
/// calibrator with the same status, and leave it as it was; 3,000 good readings after
/// them give the fit they give alone.
#[test]
fn the_calibrator_refuses_what_the_filters_refuse() {
    let good = readings(60.0);
    let mut clean = calibrator();
    for m in &good[..3000] {
        assert_eq!(add(&mut clean, *m), OrientStatus::Ok);
    }
    let reference = solve(&clean).unwrap();
    assert!(hard_iron_error(&reference) < 0.01 && reference.trustworthy == 1, "{reference:?}");
    for (bad, status) in [
        (2e12, OrientStatus::TooLarge),
        (1e50, OrientStatus::TooLarge),
        (1e100, OrientStatus::TooLarge),
        (1e300, OrientStatus::TooLarge),
        (-1e300, OrientStatus::TooLarge),
        (f64::NAN, OrientStatus::NonFinite),
        (0.0, OrientStatus::ZeroVector),
        (5e-324, OrientStatus::ZeroVector),
    ] {
        for at in [0usize, 1, 500] {
            let mut c = calibrator();
            for m in &good[..at] {
                assert_eq!(add(&mut c, *m), OrientStatus::Ok);
            }
            let before = c;
            assert_eq!(add(&mut c, Vec3::new(bad, bad, bad)), status, "{bad:e} after {at}");
            assert!(same(&c, &before), "{bad:e} after {at} changed the calibrator");
            for m in &good[at..3000] {
                assert_eq!(add(&mut c, *m), OrientStatus::Ok);
            }
            assert!(same(&c, &clean), "{bad:e} after {at}: not the calibrator of the good readings");
        }
    }
}

/// Class 6: a gross outlier (a value within the bound: 1e11; a byte dropped so that a
/// component is 256 times too large; a magnet passing: two seconds at three times the
/// field) is set aside and counted, at the start, in the middle and at the end.
#[test]
fn outliers_are_set_aside_and_counted() {
    let good = readings(60.0);
    let mut clean = calibrator();
    for m in &good {
        add(&mut clean, *m);
    }
    let reference = solve(&clean).unwrap();
    assert_eq!(reference.samples, good.len() as u64);
    assert_eq!(rejected(&clean), 0, "no good reading may be set aside");
    let gross = |m: Vec3, k: usize| match k {
        0 => Vec3::new(1e11, -1e11, 1e11),
        1 => Vec3::new(m.x * 256.0, m.y, m.z),
        _ => m * 3.0,
    };
    for kind in 0..3 {
        // The magnet only once the readings kept give a trustworthy fit over three
        // quarters of the directions (here after 896 readings): before, the gate sets
        // aside only readings 8 times too large or small (the header's rule).
        let starts: &[usize] = if kind == 2 { &[1200, 1800, 2899] } else { &[0, 1, 700, 1500, 2999] };
        for &at in starts {
            let burst = if kind == 2 { 100 } else { 1 };
            let mut c = calibrator();
            for (i, m) in good.iter().enumerate() {
                let m = if (at..at + burst).contains(&i) { gross(*m, kind) } else { *m };
                assert_eq!(add(&mut c, m), OrientStatus::Ok);
            }
            let fit = solve(&c).unwrap();
            let err = hard_iron_error(&fit);
            let n = rejected(&c);
            println!("outlier {kind} at {at}: rejected {n}, kept {}, hard iron off {err:.5}", fit.samples);
            assert!(err < 0.01 && fit.trustworthy == 1, "outlier {kind} at {at}: {fit:?}");
            assert!((fit.residual - reference.residual).abs() < 0.1 * reference.residual, "{fit:?}");
            // What was set aside: the outliers, and at the start (where the first reading
            // is the outlier) the readings before the restart.
            // A gross first reading: 31 good ones set aside in a row, then the restart
            // counts the one kept.
            let expected = if at == 0 { 32 } else { burst as u64 };
            assert_eq!(n, expected, "outlier {kind} at {at}");
            assert_eq!(fit.samples + n, good.len() as u64);
        }
    }
}

/// The header's figure: one reading 2.5 times the field off, kept before the gate acts,
/// lifts the residual of 3,000 readings by about 0.04, and the fit is not trustworthy.
#[test]
fn a_reading_kept_before_the_gate_acts_is_diluted() {
    let good = readings(60.0);
    let off = Vec3::new(-50.0, -50.0, -50.0);
    let distance = (off - HARD_IRON).norm() / FIELD.norm();
    assert!((distance - 2.5).abs() < 0.05, "{distance}");
    let (mut clean, mut c) = (calibrator(), calibrator());
    assert_eq!(add(&mut c, off), OrientStatus::Ok);
    for m in &good[..3000] {
        add(&mut clean, *m);
        add(&mut c, *m);
    }
    let (a, b) = (solve(&clean).unwrap(), solve(&c).unwrap());
    let lift = b.residual - a.residual;
    println!("residual {:.5} -> {:.5}", a.residual, b.residual);
    assert!((0.03..0.05).contains(&lift), "{lift}");
    assert_eq!((rejected(&c), b.trustworthy), (0, 0));
}

/// A large hard-iron offset (ten times the field) and a small one (about the field) keep
/// every reading.
#[test]
fn hard_iron_alone_is_no_outlier() {
    let run = tumble(60.0);
    for offset in [Vec3::new(300.0, -200.0, 250.0), Vec3::new(30.0, 30.0, -10.0), Vec3::ZERO] {
        let mut c = calibrator();
        for s in &run.samples {
            assert_eq!(add(&mut c, distort(s.mag.unwrap()) - HARD_IRON + offset), OrientStatus::Ok);
        }
        let fit = solve(&c).unwrap();
        assert_eq!(rejected(&c), 0, "{offset:?}");
        let o = fit.model.offset;
        assert!((Vec3::new(o.x, o.y, o.z) - offset).norm() < 0.01 * FIELD.norm(), "{fit:?}");
    }
}

/// Class 7: the residual is the RMS of |calibrated|/field - 1 over the readings, for a
/// full sphere and for a near-planar circle (where the fit is not trustworthy).
#[test]
fn the_residual_is_the_rms_of_the_norm_error() {
    let mut rng = Noise(0x5eed_1234);
    let circle: Vec<Vec3> = (0..2000)
        .map(|i| {
            let a = i as f64 * 0.0131;
            Vec3::new(a.cos(), a.sin(), 0.0) + rng.vec(0.01 * 3f64.sqrt())
        })
        .collect();
    let sphere: Vec<Vec3> = readings(60.0).iter().map(|m| *m + rng.vec(0.4)).collect();
    for (name, set) in [("circle", &circle), ("sphere", &sphere)] {
        let mut c = calibrator();
        for m in set {
            assert_eq!(add(&mut c, *m), OrientStatus::Ok);
        }
        let fit = solve(&c).unwrap();
        let model = orient::Model {
            matrix: [
                [fit.model.matrix[0], fit.model.matrix[1], fit.model.matrix[2]],
                [fit.model.matrix[3], fit.model.matrix[4], fit.model.matrix[5]],
                [fit.model.matrix[6], fit.model.matrix[7], fit.model.matrix[8]],
            ],
            offset: Vec3::new(fit.model.offset.x, fit.model.offset.y, fit.model.offset.z),
        };
        let rms = (set.iter().map(|m| (model.apply(*m).norm() / fit.field - 1.0).powi(2)).sum::<f64>()
            / set.len() as f64)
            .sqrt();
        println!(
            "{name}: residual {:.6}, RMS of |cal|/field - 1 {rms:.6}, coverage {:.3}",
            fit.residual, fit.coverage
        );
        assert!(rms > 1e-3, "{name}: the noise must show for the check to mean anything");
        assert!((fit.residual - rms).abs() < 0.03 * rms, "{name}: residual {} vs {rms}", fit.residual);
        if name == "circle" {
            assert_eq!(fit.trustworthy, 0, "a circle covers too few directions: {fit:?}");
        }
    }
}

/// Class 6 and 10: every extreme reading gives a listed status; a refused one leaves
/// the calibrator as it was, an accepted one does not stop good readings from giving
/// the fit.
#[test]
fn calibrator_calls_return_only_listed_statuses() {
    let st = Statuses::new();
    let good = readings(90.0);
    let mut worst: f64 = 0.0;
    for start in [0usize, 1, 20, 1200] {
        for bad in extreme_vectors() {
            let mut c = calibrator();
            for m in &good[..start] {
                assert_eq!(add(&mut c, *m), OrientStatus::Ok);
            }
            let before = c;
            let status = unsafe { orient_mag_calibrator_add(&mut c, &bad) };
            st.check("orient_mag_calibrator_add", status, &format!("{bad:?} after {start}"));
            if status != OrientStatus::Ok {
                assert!(same(&c, &before), "{bad:?}: refused but changed");
            }
            match solve(&c) {
                Ok(_) => {}
                Err(s) => st.check("orient_mag_calibrator_solve", s, &format!("{bad:?}")),
            }
            for m in &good[start..start + 3000] {
                assert_eq!(add(&mut c, *m), OrientStatus::Ok);
            }
            // A reading kept before the gate acts stays in the sums (the header says so):
            // a fit that says it is trustworthy is within 1 % of the field. Once the gate
            // acts, whatever came, the fit is the good readings'.
            let fit = solve(&c).unwrap_or_else(|s| panic!("{bad:?} after {start}: {s:?}"));
            let err = hard_iron_error(&fit);
            assert!(err < 0.01 || fit.trustworthy == 0, "{bad:?} after {start}: {fit:?}");
            if start >= 1200 {
                assert!(err < 0.01 && fit.trustworthy == 1, "{bad:?} after {start}: {fit:?}");
            }
            worst = worst.max(fit.residual);
        }
    }
    println!("largest residual after an extreme reading and 3,000 good ones: {worst:.5}");
    // A struct that is no calibrator's state.
    for x in [f64::NAN, f64::INFINITY, -1.0, 0.0] {
        let mut c = calibrator();
        c.scale = x;
        let before = c;
        let status = add(&mut c, Vec3::new(1.0, 2.0, 3.0));
        st.check("orient_mag_calibrator_add", status, "scale {x}");
        assert_eq!(status, OrientStatus::InvalidArgument);
        assert!(same(&c, &before));
        let mut fit = OrientMagFit::default();
        let s = unsafe { orient_mag_calibrator_solve(&c, &mut fit) };
        st.check("orient_mag_calibrator_solve", s, "scale {x}");
        let mut n = 7u64;
        let s = unsafe { orient_mag_calibrator_rejected(&c, &mut n) };
        st.check("orient_mag_calibrator_rejected", s, "scale {x}");
        assert_eq!((s, n), (OrientStatus::InvalidArgument, 7));
    }
    let s = unsafe { orient_mag_calibrator_init(core::ptr::null_mut()) };
    st.check("orient_mag_calibrator_init", s, "NULL");
    let s = unsafe { orient_mag_calibrator_rejected(core::ptr::null(), &mut 0) };
    st.check("orient_mag_calibrator_rejected", s, "NULL");
}

// ---- The gyroscope offset ---------------------------------------------------------------

/// Class 10: readings the filters refuse as a gyroscope reading are refused by
/// orient_gyro_offset (+-1e200 was OK with spread = inf), and nothing is written then.
#[test]
fn gyro_offset_returns_only_listed_statuses() {
    let st = Statuses::new();
    let still = [OrientVec3 { x: 0.01, y: -0.02, z: 0.03 }; 4];
    let mut model = OrientSensorModel::default();
    let mut spread = 0.0;
    assert_eq!(unsafe { orient_gyro_offset(still.as_ptr(), 4, &mut model, &mut spread) }, OrientStatus::Ok);
    let big = [OrientVec3 { x: 1e200, y: -1e200, z: 1e200 }, OrientVec3 { x: -1e200, y: 1e200, z: -1e200 }];
    let mut m = OrientSensorModel::default();
    let mut sp = -1.0;
    let s = unsafe { orient_gyro_offset(big.as_ptr(), 2, &mut m, &mut sp) };
    assert_eq!(s, OrientStatus::TooLarge);
    assert_eq!((m, sp), (OrientSensorModel::default(), -1.0));
    for bad in extreme_vectors() {
        let readings = [still[0], bad, still[1]];
        let (mut m, mut sp) = (OrientSensorModel::default(), -1.0);
        let s = unsafe { orient_gyro_offset(readings.as_ptr(), 3, &mut m, &mut sp) };
        st.check("orient_gyro_offset", s, &format!("{bad:?}"));
        if s == OrientStatus::Ok {
            assert!(sp.is_finite() && m.offset.x.is_finite(), "{bad:?}: {sp} {m:?}");
        } else {
            assert_eq!((m, sp), (OrientSensorModel::default(), -1.0), "{bad:?}");
        }
    }
    for n in [0usize, usize::MAX, usize::MAX / 8] {
        let s = unsafe { orient_gyro_offset(still.as_ptr(), n, &mut m, core::ptr::null_mut()) };
        st.check("orient_gyro_offset", s, &format!("n = {n}"));
        assert_ne!(s, OrientStatus::Ok);
    }
    let s = unsafe { orient_gyro_offset(core::ptr::null(), 2, &mut m, core::ptr::null_mut()) };
    st.check("orient_gyro_offset", s, "NULL");
}

// ---- Filters: sensor models, mounting, heading, declination, rigs ----------------------

fn new_filter(kind: i32) -> *mut OrientFilter {
    let mut c = core::mem::MaybeUninit::<OrientConfig>::uninit();
    unsafe {
        assert_eq!(orient_config_default(kind, c.as_mut_ptr()), OrientStatus::Ok);
        let mut f = core::ptr::null_mut();
        assert_eq!(orient_filter_new(c.as_ptr(), &mut f), OrientStatus::Ok);
        f
    }
}

/// A filter that has an orientation.
fn running_filter(kind: i32) -> *mut OrientFilter {
    let f = new_filter(kind);
    let s = OrientSample {
        dt: 0.01,
        gyro: OrientVec3 { x: 0.01, y: 0.02, z: -0.01 },
        accel: OrientVec3 { x: 0.5, y: -0.3, z: 9.8 },
        mag: OrientVec3 { x: 10.0, y: 20.0, z: -40.0 },
        flags: ORIENT_SAMPLE_GYRO | ORIENT_SAMPLE_ACCEL | ORIENT_SAMPLE_MAG,
        reserved: 0,
    };
    for _ in 0..10 {
        assert_eq!(unsafe { orient_filter_update(f, &s) }, OrientStatus::Ok);
    }
    f
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

/// Class 10: a pure scale of the identity is no singular matrix, whatever the scale: it
/// is accepted, or refused by the rule on plausible readings (TOO_LARGE when a plausible
/// reading calibrates beyond the physical bound, ZERO_VECTOR when one calibrates to
/// zero), never as singular.
#[test]
fn a_scaled_identity_is_no_singular_model() {
    let f = running_filter(OrientKind::Madgwick as i32);
    use OrientStatus::{Ok as A, TooLarge as L, ZeroVector as Z};
    // Gyroscope, accelerometer, magnetometer.
    let expected = [
        (1e-110, [A, A, A]),
        (1e110, [L, L, L]),
        (1e-300, [A, Z, Z]),
        (1e300, [L, L, L]),
        (5e-324, [A, Z, Z]),
        (-1e-200, [A, Z, Z]),
        (3.0, [A, A, A]),
        // 1 rad/s, gravity and 65000 reach the bounds (1e4, 1e5, 1e12) beyond these.
        (9999.0, [A, A, A]),
        (1e4, [L, A, A]),
        (1.1e4, [L, L, A]),
        (1.5e7, [L, L, A]),
        (1.6e7, [L, L, L]),
    ];
    for (scale, statuses) in expected {
        let model = OrientSensorModel {
            matrix: [scale, 0.0, 0.0, 0.0, scale, 0.0, 0.0, 0.0, scale],
            offset: OrientVec3::default(),
        };
        for (sensor, status) in
            [ORIENT_SENSOR_GYRO, ORIENT_SENSOR_ACCEL, ORIENT_SENSOR_MAG].into_iter().zip(statuses)
        {
            unsafe { orient_filter_set_sensor_model(f, sensor, std::ptr::null()) };
            let before = blob(f);
            let s = unsafe { orient_filter_set_sensor_model(f, sensor, &model) };
            assert_eq!(s, status, "{scale:e}, sensor {sensor}");
            let mut back = OrientSensorModel::default();
            if s == OrientStatus::Ok {
                assert_eq!(unsafe { orient_filter_sensor_model(f, sensor, &mut back) }, OrientStatus::Ok);
                assert_eq!(back, model);
            } else {
                assert_eq!(blob(f), before);
            }
        }
    }
    // Singular at any scale: a rank-2 matrix, and a nearly singular one.
    for scale in [1e-110, 1.0, 1e110] {
        for m in
            [[1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1e-14]]
        {
            let model = OrientSensorModel { matrix: m.map(|x| x * scale), offset: OrientVec3::default() };
            let before = blob(f);
            let s = unsafe { orient_filter_set_sensor_model(f, ORIENT_SENSOR_ACCEL, &model) };
            assert_eq!(s, OrientStatus::ZeroVector, "{scale:e} {m:?}");
            assert_eq!(blob(f), before);
        }
    }
    unsafe { orient_filter_free(f) };
}

/// Class 10: every sensor-model, mounting, heading, declination and rig call, driven
/// with extreme values, returns only the statuses its header sentence lists, and a
/// refused call leaves every filter's state (snapshot bytes) as it was.
#[test]
fn filter_calls_return_only_listed_statuses() {
    let st = Statuses::new();
    for kind in [OrientKind::Madgwick as i32, OrientKind::Ekf as i32, OrientKind::Robust as i32] {
        for fresh in [false, true] {
            let make = || if fresh { new_filter(kind) } else { running_filter(kind) };
            let f = make();
            let g = make();
            let check = |name: &str, what: &str, call: &mut dyn FnMut() -> OrientStatus| {
                let before = (blob(f), blob(g));
                let status = call();
                st.check(name, status, what);
                if status != OrientStatus::Ok {
                    assert_eq!((blob(f), blob(g)), before, "{name}({what}) refused but changed a filter");
                }
            };
            for &x in &EXTREMES {
                let w = format!("{x:e}");
                let matrices = [
                    [x, 0.0, 0.0, 0.0, x, 0.0, 0.0, 0.0, x],
                    [x; 9],
                    [1.0, 0.0, 0.0, 0.0, 1.0, x, 0.0, 0.0, 1.0],
                    [x, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                ];
                for sensor in [ORIENT_SENSOR_GYRO, ORIENT_SENSOR_ACCEL, ORIENT_SENSOR_MAG, 3, u32::MAX] {
                    for matrix in matrices {
                        let model = OrientSensorModel { matrix, offset: OrientVec3::default() };
                        check("orient_filter_set_sensor_model", &w, &mut || unsafe {
                            orient_filter_set_sensor_model(f, sensor, &model)
                        });
                    }
                    let model = OrientSensorModel {
                        matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                        offset: OrientVec3 { x, y: 0.0, z: x },
                    };
                    check("orient_filter_set_sensor_model", &w, &mut || unsafe {
                        orient_filter_set_sensor_model(f, sensor, &model)
                    });
                    let mut out = OrientSensorModel::default();
                    check("orient_filter_sensor_model", &w, &mut || unsafe {
                        orient_filter_sensor_model(f, sensor, &mut out)
                    });
                }
                let quats = [
                    OrientQuaternion { w: x, x, y: x, z: x },
                    OrientQuaternion { w: x, x: 0.0, y: 0.0, z: 0.0 },
                    OrientQuaternion { w: 1.0, x, y: 0.0, z: 0.0 },
                ];
                for q in quats {
                    check("orient_filter_set_mounting", &w, &mut || unsafe {
                        orient_filter_set_mounting(f, &q)
                    });
                    let refs = [q, OrientQuaternion { w: 1.0, x: 0.0, y: 0.0, z: 0.0 }];
                    let handles = [f, g];
                    for heading in [x, 0.3, f64::NAN] {
                        check("orient_rig_calibrate", &w, &mut || unsafe {
                            orient_rig_calibrate(handles.as_ptr(), refs.as_ptr(), 2, heading)
                        });
                    }
                    check("orient_rig_align_heading", &w, &mut || unsafe {
                        orient_rig_align_heading(handles.as_ptr(), refs.as_ptr(), 2)
                    });
                    check("orient_rig_calibrate_each", &w, &mut || unsafe {
                        orient_rig_calibrate_each(handles.as_ptr(), refs.as_ptr(), 2)
                    });
                }
                check("orient_filter_set_heading", &w, &mut || unsafe { orient_filter_set_heading(f, x) });
                check("orient_filter_set_declination", &w, &mut || unsafe {
                    orient_filter_set_declination(f, x)
                });
            }
            let refs = [OrientQuaternion { w: 1.0, x: 0.0, y: 0.0, z: 0.0 }; 2];
            for (handles, n) in
                [([f, f], 2usize), ([f, g], 0), ([f, core::ptr::null_mut()], 2), ([f, g], usize::MAX)]
            {
                check("orient_rig_calibrate", "handles", &mut || unsafe {
                    orient_rig_calibrate(handles.as_ptr(), refs.as_ptr(), n, 0.0)
                });
                check("orient_rig_align_heading", "handles", &mut || unsafe {
                    orient_rig_align_heading(handles.as_ptr(), refs.as_ptr(), n)
                });
                check("orient_rig_calibrate_each", "handles", &mut || unsafe {
                    orient_rig_calibrate_each(handles.as_ptr(), refs.as_ptr(), n)
                });
            }
            check("orient_filter_reset_heading", "", &mut || unsafe { orient_filter_reset_heading(f) });
            let (mut q, mut a) = (OrientQuaternion::default(), 0.0);
            check("orient_filter_mounting", "", &mut || unsafe { orient_filter_mounting(f, &mut q) });
            check("orient_filter_sensor_quaternion", "", &mut || unsafe {
                orient_filter_sensor_quaternion(f, &mut q)
            });
            check("orient_filter_heading_offset", "", &mut || unsafe {
                orient_filter_heading_offset(f, &mut a)
            });
            check("orient_filter_declination", "", &mut || unsafe { orient_filter_declination(f, &mut a) });
            unsafe {
                orient_filter_free(f);
                orient_filter_free(g);
            }
        }
    }
}
