//! The offline mode (`orient::offline`): on simulated motion with exact truth it beats
//! the causal filter, and on the shared BROAD trials it stays within its measured
//! bounds (docs/ACCURACY.md, "Offline mode").
//!
//! The BROAD test needs ../shared/data/broad beside the repository, as CI has it; set
//! ORIENT_SKIP_SHARED_DATA=1 to skip it where it is absent.

mod common;

use common::sim::{inclination_error, simulate, Moment};
use orient::{offline, Config, Filter, Frame, Kind, Quat, Sample, Vec3};
use orient_tools::eval::{decimate, score, Recording};
use std::path::PathBuf;

fn causal(config: &Config, samples: &[Sample]) -> Vec<Quat> {
    let mut f = Filter::new(config).unwrap();
    samples
        .iter()
        .map(|s| {
            f.update(s).unwrap();
            f.quaternion()
        })
        .collect()
}

fn rms_deg(est: &[Quat], truth: &[Quat], err: impl Fn(Quat, Quat) -> f64) -> f64 {
    let s: f64 = est.iter().zip(truth).map(|(e, t)| err(*e, *t).powi(2)).sum();
    (s / est.len() as f64).sqrt().to_degrees()
}

#[test]
fn offline_beats_the_causal_filter_on_simulated_motion() {
    // Two minutes of hand-held-like motion at 100 Hz with a gyro bias the filters must
    // learn: 20 s still, then sums of sines about every axis, with linear accelerations.
    let bias = Vec3::new(0.01, -0.008, 0.005);
    let run =
        simulate(Quat::from_axis_angle(Vec3::new(1.0, 0.5, 0.2), 0.6), 120.0, 100.0, (0.01, 0.1, 0.5), |t| {
            let moving = t > 20.0;
            let omega = if moving {
                Vec3::new((1.3 * t).sin() * 0.8, (0.7 * t + 1.0).sin() * 0.6, (0.45 * t + 2.0).sin() * 0.9)
            } else {
                Vec3::ZERO
            };
            let linear = if moving {
                Vec3::new((2.1 * t).sin(), (1.7 * t).cos(), (2.9 * t).sin() * 0.5)
            } else {
                Vec3::ZERO
            };
            Moment { omega, linear, bias, ..Moment::default() }
        });
    for kind in [Kind::Robust, Kind::Madgwick, Kind::Ekf] {
        let config = Config::new(kind).unwrap();
        let c = causal(&config, &run.samples);
        let o = offline::smooth(&config, &run.samples).unwrap();
        let total = |e: &[Quat]| rms_deg(e, &run.truth, |a, b| a.angle_to(b));
        let incl = |e: &[Quat]| rms_deg(e, &run.truth, inclination_error);
        println!(
            "{kind:?}: causal {:.3} ({:.3}), offline {:.3} ({:.3})",
            total(&c),
            incl(&c),
            total(&o),
            incl(&o)
        );
        assert!(total(&o) < total(&c), "{kind:?}: offline {:.3} against causal {:.3}", total(&o), total(&c));
        assert!(incl(&o) < incl(&c), "{kind:?}: offline {:.3} against causal {:.3}", incl(&o), incl(&c));
    }
}

fn broad_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data/broad");
    if dir.is_dir() {
        return Some(dir);
    }
    if std::env::var_os("ORIENT_SKIP_SHARED_DATA").is_some() {
        eprintln!("skipping: {} not found", dir.display());
        return None;
    }
    panic!("{} not found (set ORIENT_SKIP_SHARED_DATA=1 to skip)", dir.display());
}

/// The offline scores of one trial: causal total and inclination, offline total and
/// inclination, offline total at 48 Hz (NaN where not run).
type TrialScores = (f64, f64, f64, f64, f64);

#[test]
fn offline_broad_means_stay_within_their_measured_bounds() {
    let Some(dir) = broad_dir() else { return };
    let first_eight = |p: &PathBuf| {
        let name = p.file_name().unwrap().to_string_lossy();
        ["01_", "06_", "08_", "15_", "24_", "26_", "28_", "32_"].iter().any(|n| name.starts_with(n))
    };
    let mut files = orient_tools::eval::csv_files(&dir).unwrap();
    assert_eq!(files.len(), 14);
    // Under emulation, only the first eight trials' offline scores (minutes otherwise).
    let cross = common::native::cross();
    if cross {
        files.retain(first_eight);
    }
    let config = Config::new(Kind::Robust).unwrap();
    let offline_config = offline::config();
    let scores: Vec<TrialScores> = std::thread::scope(|s| {
        let jobs: Vec<_> = files
            .iter()
            .map(|p| {
                let (config, offline_config) = (&config, &offline_config);
                s.spawn(move || {
                    let rec = Recording::read(p, true).unwrap();
                    let samples = rec.samples();
                    let o = offline::smooth(offline_config, &samples).unwrap();
                    let o = score(&o, &rec.truth, &rec.movement);
                    if cross {
                        return (f64::NAN, f64::NAN, o.total, o.inclination, f64::NAN);
                    }
                    let c = score(&causal(config, &samples), &rec.truth, &rec.movement);
                    // At 48 Hz (a sixth of the recording rate), as a board would log.
                    let (low, low_samples) = decimate(&rec, &samples, 6);
                    let l = offline::smooth(offline_config, &low_samples).unwrap();
                    let l = score(&l, &low.truth, &low.movement);
                    (c.total, c.inclination, o.total, o.inclination, l.total)
                })
            })
            .collect();
        jobs.into_iter().map(|j| j.join().unwrap()).collect()
    });
    let first =
        files.iter().zip(&scores).filter(|(p, _)| first_eight(p)).map(|(_, s)| s.2).sum::<f64>() / 8.0;
    println!("first 8 trials, offline 9D: {first:.3}");
    // Measured: 2.32 (2.25 before issue 19's changes to the causal robust kind); VQF's
    // offline mode 2.41 (../shared/data/README.md, issue 19).
    assert!(first < 2.41, "offline total over the first eight trials {first:.3} (VQF offline: 2.41)");
    if cross {
        return;
    }
    let mean = |f: fn(&TrialScores) -> f64| scores.iter().map(f).sum::<f64>() / scores.len() as f64;
    let (ct, ci, ot, oi, lt) = (mean(|s| s.0), mean(|s| s.1), mean(|s| s.2), mean(|s| s.3), mean(|s| s.4));
    println!(
        "14 trials, robust 9D: causal {ct:.3} ({ci:.3}), offline {ot:.3} ({oi:.3}), offline at 48 Hz {lt:.3}"
    );
    // Measured: offline 2.21 (0.61) against causal 2.32 (0.80); at 48 Hz 2.16. (Before
    // issue 19's changes to the causal robust kind: 2.23 against 2.52.)
    assert!(ot < 2.26 && ot < ct - 0.08, "offline total {ot:.3} against causal {ct:.3}");
    assert!(oi < 0.65 && oi < ci - 0.15, "offline inclination {oi:.3} against causal {ci:.3}");
    assert!(lt < 2.30, "offline total at 48 Hz {lt:.3}");
}

#[test]
fn offline_covers_the_start_up_and_keeps_the_frame() {
    // Started in motion with linear acceleration and a gyro bias: a causal filter starts
    // from a wrong accelerometer and magnetometer reading and converges; the offline
    // mode's passes both start converged (the backward pass reaches the first sample
    // with the whole recording behind it).
    let bias = Vec3::new(0.02, -0.01, 0.015);
    let run =
        simulate(Quat::from_axis_angle(Vec3::new(0.3, 1.0, 0.2), 1.1), 60.0, 100.0, (0.01, 0.1, 0.5), |t| {
            Moment {
                omega: Vec3::new((1.1 * t).sin() * 0.7, (0.8 * t + 1.0).cos() * 0.5, (0.5 * t).sin() * 0.6),
                linear: Vec3::new(3.0 * (2.0 * t).sin(), 2.0 * (1.5 * t).cos(), 0.0),
                bias,
                ..Moment::default()
            }
        });
    let first = 300; // 3 s
    for kind in [Kind::Robust, Kind::Madgwick, Kind::Mahony, Kind::Ekf] {
        let config = Config::new(kind).unwrap();
        let c = causal(&config, &run.samples);
        let o = offline::smooth(&config, &run.samples).unwrap();
        let start = |e: &[Quat]| rms_deg(&e[..first], &run.truth[..first], |a, b| a.angle_to(b));
        println!("{kind:?}: first 3 s, causal {:.3}°, offline {:.3}°", start(&c), start(&o));
        assert!(
            start(&o) < 0.5 * start(&c),
            "{kind:?}: offline {:.3}° against causal {:.3}°",
            start(&o),
            start(&c)
        );
    }
    // The configured frame: NED output is the ENU output turned into NED.
    let mut ned = offline::config();
    ned.frame = Frame::Ned;
    let (e, n) =
        (offline::smooth_default(&run.samples).unwrap(), offline::smooth(&ned, &run.samples).unwrap());
    let to_ned = Frame::Enu.rotation_to(Frame::Ned).unwrap();
    let worst = e.iter().zip(&n).map(|(e, n)| (to_ned * *e).angle_to(*n)).fold(0.0, f64::max);
    assert!(worst < 1e-9, "NED differs from ENU turned by {worst} rad");
}
