//! The offline mode (`orient::offline`): on simulated motion with exact truth it beats
//! the causal filter, and on the shared BROAD trials it stays within its measured
//! bounds (docs/ACCURACY.md, "Offline mode").
//!
//! Its memory: bit-identical to the form that kept every pass (an oracle below), at 8
//! bytes per sample (a counting allocator), and a clean status when memory runs out.
//!
//! The BROAD tests need ../shared/data/broad beside the repository, as CI has it; set
//! ORIENT_SKIP_SHARED_DATA=1 to skip them where it is absent.

mod common;

use common::sim::{inclination_error, simulate, Moment};
use orient::ffi::{orient_smooth_arrays, orient_smooth_memory, OrientConfig, OrientQuaternion, OrientStatus};
use orient::offline::SmoothError;
use orient::{offline, Config, Error, Field, Filter, Frame, Init, Kind, Quat, Sample, Vec3};
use orient_tools::eval::{decimate, score, Recording};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::PathBuf;

/// Tracks the bytes live on threads that armed it, and their peak: the harness allocates
/// on its threads at any time, and the tests run side by side.
struct Peak;

thread_local! {
    static ARMED: Cell<bool> = const { Cell::new(false) };
    /// (bytes allocated minus bytes freed since arming, the most of that).
    static LIVE: Cell<(isize, isize)> = const { Cell::new((0, 0)) };
}

fn note(delta: isize) {
    if ARMED.try_with(|a| a.get()).unwrap_or(false) {
        let _ = LIVE.try_with(|l| {
            let now = l.get().0 + delta;
            l.set((now, now.max(l.get().1)));
        });
    }
}

unsafe impl GlobalAlloc for Peak {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size() as isize);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        note(-(layout.size() as isize));
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size as isize - layout.size() as isize);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Peak = Peak;

/// What `f` returns, and the peak of the bytes it held allocated on this thread.
fn peak_of<R>(f: impl FnOnce() -> R) -> (R, usize) {
    LIVE.with(|l| l.set((0, 0)));
    ARMED.with(|a| a.set(true));
    let r = f();
    ARMED.with(|a| a.set(false));
    (r, LIVE.with(|l| l.get().1) as usize)
}

/// The smoother as it was before issue 40 (commit 57c98c1, `passes` and `fuse`), word
/// for word through the public API: a forward track and a backward track of every
/// sample, then their fusion. The oracle the in-place smoother must match bit for bit.
mod oracle {
    use orient::offline::{slerp, DRIFT, FLOOR, RECOVERY};
    use orient::{flags, Config, Error, Filter, Init, Quat, Sample, Vec3};

    struct Pass {
        filter: Filter,
        sign: f64,
        offset: Vec3,
    }

    impl Pass {
        fn step(&mut self, s: &Sample, gyro: Option<Vec3>) -> Result<(), Error> {
            let gyro = gyro.map(|g| g * self.sign + self.offset);
            self.filter.update(&Sample { gyro, ..*s })
        }
        fn subtracted(&self) -> Vec3 {
            let b = self.filter.diagnostics().gyro_bias;
            if b.is_finite() {
                b
            } else {
                Vec3::ZERO
            }
        }
        fn bias(&self) -> Vec3 {
            (self.subtracted() - self.offset) * self.sign
        }
        fn turned(&self) -> Pass {
            let sign = -self.sign;
            Pass { filter: self.filter.clone(), sign, offset: self.subtracted() - self.bias() * sign }
        }
    }

    fn heading_sigma(sigma: f64, dt: f64, filter: &Filter) -> f64 {
        let mut s = sigma + DRIFT * dt;
        if filter.flags() & flags::MAG_USED != 0 {
            s -= (s - FLOOR) * (dt / (RECOVERY + dt));
        }
        s
    }

    /// The smoothed orientations, or the index and error of the first refused step.
    pub fn smooth(config: &Config, samples: &[Sample]) -> Result<Vec<Quat>, (usize, Error)> {
        let n = samples.len();
        if n == 0 {
            return Ok(Vec::new());
        }
        let fail = |index: usize| move |error: Error| (index, error);
        let mut prime = Pass { filter: Filter::new(config).map_err(fail(0))?, sign: 1.0, offset: Vec3::ZERO };
        for (i, s) in samples.iter().enumerate() {
            prime.step(s, s.gyro).map_err(fail(i))?;
        }
        let mut backward = prime.turned();
        let (mut back_q, mut back_sigma) = (vec![Quat::IDENTITY; n], vec![0.0; n]);
        let mut sigma = FLOOR;
        for j in (0..n).rev() {
            let gyro = samples.get(j + 1).map_or(Some(Vec3::ZERO), |s| s.gyro);
            let dt = samples.get(j + 1).map_or(samples[j].dt, |s| s.dt);
            backward.step(&Sample { dt, ..samples[j] }, gyro).map_err(fail(j))?;
            sigma = heading_sigma(sigma, dt, &backward.filter);
            back_q[j] = backward.filter.quaternion();
            back_sigma[j] = sigma;
        }
        let mut fore_pass = backward.turned();
        if !matches!(config.init, Init::AccMag) {
            fore_pass = Pass { filter: Filter::new(config).map_err(fail(0))?, sign: 1.0, offset: Vec3::ZERO };
        }
        let (mut fore_q, mut fore_sigma) = (Vec::with_capacity(n), Vec::with_capacity(n));
        let mut sigma = FLOOR;
        for (i, s) in samples.iter().enumerate() {
            fore_pass.step(s, s.gyro).map_err(fail(i))?;
            sigma = heading_sigma(sigma, s.dt, &fore_pass.filter);
            fore_q.push(fore_pass.filter.quaternion());
            fore_sigma.push(sigma);
        }
        Ok((0..n)
            .map(|i| {
                let (vf, vb) = (fore_sigma[i] * fore_sigma[i], back_sigma[i] * back_sigma[i]);
                slerp(fore_q[i], back_q[i], vf / (vf + vb))
            })
            .collect())
    }
}

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
    // Measured: 2.33 (2.32 with the rest detector's earlier tilt test, 2.35 with the rest
    // time constant at 2 s, 2.32 before the motion bias
    // filter, 2.25 before issue 19's changes to the causal robust kind); VQF's offline mode 2.41 (../shared/data/README.md,
    // issue 19).
    assert!(first < 2.41, "offline total over the first eight trials {first:.3} (VQF offline: 2.41)");
    if cross {
        return;
    }
    let mean = |f: fn(&TrialScores) -> f64| scores.iter().map(f).sum::<f64>() / scores.len() as f64;
    let (ct, ci, ot, oi, lt) = (mean(|s| s.0), mean(|s| s.1), mean(|s| s.2), mean(|s| s.3), mean(|s| s.4));
    println!(
        "14 trials, robust 9D: causal {ct:.3} ({ci:.3}), offline {ot:.3} ({oi:.3}), offline at 48 Hz {lt:.3}"
    );
    // Measured: offline 2.19 (0.61) against causal 2.23 (0.80); at 48 Hz 2.14. (Before
    // the causal robust kind's motion bias filter, issue 42: 2.21 against 2.32; before
    // issue 19's changes: 2.23 against 2.52.)
    assert!(ot < 2.26 && ot < ct - 0.02, "offline total {ot:.3} against causal {ct:.3}");
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

/// The sample arrays of orient_smooth_arrays (per-sample dt), from `samples`.
struct Arrays {
    dt: Vec<f64>,
    gyro: Vec<f64>,
    accel: Vec<f64>,
    mag: Vec<f64>,
}

fn arrays(samples: &[Sample]) -> Arrays {
    let rows = |f: fn(&Sample) -> Option<Vec3>| -> Vec<f64> {
        samples.iter().flat_map(|s| f(s).map(|v| [v.x, v.y, v.z]).expect("every reading present")).collect()
    };
    Arrays {
        dt: samples.iter().map(|s| s.dt).collect(),
        gyro: rows(|s| s.gyro),
        accel: rows(|s| s.accel),
        mag: rows(|s| s.mag),
    }
}

fn c_config(kind: Option<Kind>) -> OrientConfig {
    let mut c = std::mem::MaybeUninit::<OrientConfig>::uninit();
    // SAFETY: both write a whole OrientConfig on success, which is checked.
    unsafe {
        let status = match kind {
            None => orient::ffi::orient_smooth_config_default(c.as_mut_ptr()),
            Some(k) => {
                orient::ffi::orient_config_default(orient::ffi::OrientKind::from(k) as i32, c.as_mut_ptr())
            }
        };
        assert_eq!(status, OrientStatus::Ok);
        c.assume_init()
    }
}

/// orient_smooth_arrays over `a` into `out`: the status and `*processed`.
fn c_smooth(c: &OrientConfig, a: &Arrays, out: &mut [OrientQuaternion]) -> (OrientStatus, usize) {
    let mut processed = usize::MAX;
    // SAFETY: every array holds its n rows, `out` n slots.
    let status = unsafe {
        orient_smooth_arrays(
            c,
            out.len(),
            a.dt.as_ptr(),
            a.dt.len(),
            a.gyro.as_ptr(),
            a.accel.as_ptr(),
            a.mag.as_ptr(),
            out.as_mut_ptr(),
            &mut processed,
        )
    };
    (status, processed)
}

fn bits(q: Quat) -> [u64; 4] {
    [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()]
}

fn c_bits(q: OrientQuaternion) -> [u64; 4] {
    bits(Quat::new(q.w, q.x, q.y, q.z))
}

/// Every form of the smoother against the oracle on `samples`, bit for bit: `smooth`,
/// `smooth_into`, `passes` + `fuse`, and (with `c` given, its configuration) the C call.
fn same_as_the_oracle(what: &str, config: &Config, c: Option<&OrientConfig>, samples: &[Sample]) {
    let expected: Vec<[u64; 4]> = oracle::smooth(config, samples).unwrap().into_iter().map(bits).collect();
    let smoothed = offline::smooth(config, samples).unwrap();
    assert!(smoothed.iter().map(|q| bits(*q)).eq(expected.iter().copied()), "{what}: smooth");
    let mut into = vec![Quat::new(7.0, 7.0, 7.0, 7.0); samples.len()];
    offline::smooth_into(config, samples, &mut into[..]).unwrap();
    assert!(into.iter().map(|q| bits(*q)).eq(expected.iter().copied()), "{what}: smooth_into");
    let (fore, back) = offline::passes(config, samples).unwrap();
    let fused = offline::fuse(&fore, &back);
    assert!(fused.iter().map(|q| bits(*q)).eq(expected.iter().copied()), "{what}: passes + fuse");
    if let Some(c) = c {
        let mut out = vec![OrientQuaternion::default(); samples.len()];
        assert_eq!(c_smooth(c, &arrays(samples), &mut out), (OrientStatus::Ok, samples.len()), "{what}");
        assert!(out.iter().map(|q| c_bits(*q)).eq(expected.iter().copied()), "{what}: orient_smooth_arrays");
    }
}

fn moving_run(seconds: f64) -> common::sim::Run {
    let bias = Vec3::new(0.01, -0.008, 0.005);
    simulate(Quat::from_axis_angle(Vec3::new(1.0, 0.5, 0.2), 0.6), seconds, 100.0, (0.01, 0.1, 0.5), |t| {
        Moment {
            omega: Vec3::new(
                (1.3 * t).sin() * 0.8,
                (0.7 * t + 1.0).sin() * 0.6,
                (0.45 * t + 2.0).sin() * 0.9,
            ),
            linear: Vec3::new((2.1 * t).sin(), (1.7 * t).cos(), (2.9 * t).sin() * 0.5),
            bias,
            ..Moment::default()
        }
    })
}

#[test]
fn the_in_place_smoother_matches_the_form_that_kept_every_pass() {
    let run = moving_run(40.0);
    for kind in Kind::ALL {
        let config = Config::new(kind).unwrap();
        same_as_the_oracle(&format!("{kind:?}"), &config, Some(&c_config(Some(kind))), &run.samples);
        // A host's own initial orientation: the last pass starts afresh.
        let mut given = config.clone();
        given.init = Init::Given(Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.3));
        given.frame = Frame::Ned;
        same_as_the_oracle(&format!("{kind:?}, given, NED"), &given, None, &run.samples);
    }
    same_as_the_oracle("one sample", &offline::config(), Some(&c_config(None)), &run.samples[..1]);
    // A shared BROAD recording with the offline defaults.
    let Some(dir) = broad_dir() else { return };
    let file = orient_tools::eval::csv_files(&dir).unwrap().into_iter().next().unwrap();
    let samples = Recording::read(&file, true).unwrap().samples();
    same_as_the_oracle(&file.display().to_string(), &offline::config(), Some(&c_config(None)), &samples);
}

#[test]
fn a_step_only_the_turned_passes_refuse_is_held() {
    // Still, with a gyroscope bias of -0.2 rad/s about x that the robust kind learns at
    // rest, and one reading of 4.99 rad/s under a 5 rad/s range: the forward run accepts
    // it; the backward pass feeds -4.99 + 2 (-0.2), beyond the range.
    let run = simulate(Quat::IDENTITY, 30.0, 100.0, (0.001, 0.01, 0.1), |_| Moment {
        bias: Vec3::new(-0.05, 0.0, 0.0),
        ..Moment::default()
    });
    let mut samples = run.samples;
    samples[2000].gyro = Some(Vec3::new(4.99, 0.0, 0.0));
    let mut config = Config::new(Kind::Robust).unwrap();
    config.set("gyro_range", 5.0).unwrap().unwrap();
    let mut forward = Filter::new(&config).unwrap();
    assert!(samples.iter().all(|s| forward.update(s).is_ok()), "the forward run accepts every sample");
    // Before: the call failed at that sample, which the header does not allow.
    assert_eq!(oracle::smooth(&config, &samples).unwrap_err(), (1999, Error::Saturated(Field::Gyro)));
    let smoothed = offline::smooth(&config, &samples).unwrap();
    let causal = causal(&config, &samples);
    let worst = |e: &[Quat]| e.iter().map(|q| q.angle_to(Quat::IDENTITY)).fold(0.0, f64::max);
    assert!(
        worst(&smoothed) < worst(&causal),
        "held over the step: {} rad from the truth at worst, the causal filter {}",
        worst(&smoothed),
        worst(&causal)
    );
    // Through the C ABI: OK, every sample processed.
    let mut c = c_config(Some(Kind::Robust));
    // SAFETY: c is a whole configuration.
    let set =
        unsafe { orient::ffi::orient_config_set_param(&mut c, orient::ffi::ORIENT_PARAM_GYRO_RANGE, 5.0) };
    assert_eq!(set, OrientStatus::Ok);
    let mut out = vec![OrientQuaternion::default(); samples.len()];
    assert_eq!(c_smooth(&c, &arrays(&samples), &mut out), (OrientStatus::Ok, samples.len()));
    assert!(out.iter().zip(&smoothed).all(|(o, q)| c_bits(*o) == bits(*q)));
}

/// A still, rolled recording of `n` samples at 100 Hz with a little deterministic noise.
fn still(n: usize) -> Vec<Sample> {
    let mut noise = common::sim::Noise(0x2545_f491);
    let (s, c) = (0.2f64.sin(), 0.2f64.cos());
    (0..n)
        .map(|_| Sample {
            dt: 0.01,
            gyro: Some(noise.vec(0.002)),
            accel: Some(Vec3::new(0.0, 9.81 * 2.0 * s * c, 9.81 * (c * c - s * s)) + noise.vec(0.02)),
            mag: Some(Vec3::new(0.0, 20.0, -40.0) + noise.vec(0.2)),
        })
        .collect()
}

#[test]
fn smoothing_allocates_eight_bytes_per_sample_and_one_filter() {
    let n = 1_000_000;
    let samples = still(n);
    let config = offline::config();
    let bound = offline::memory(n).unwrap();
    let mut bytes = 0;
    // SAFETY: a valid out pointer.
    assert_eq!(unsafe { orient_smooth_memory(n, &mut bytes) }, OrientStatus::Ok);
    assert_eq!(bytes, bound);
    assert_eq!(bound, 8 * n + 32768);
    let mut out = vec![Quat::IDENTITY; n];
    let (r, rust) = peak_of(|| offline::smooth_into(&config, &samples[..], &mut out[..]));
    r.unwrap();
    let a = arrays(&samples);
    let mut c_out = vec![OrientQuaternion::default(); n];
    let (r, c) = peak_of(|| c_smooth(&c_config(None), &a, &mut c_out));
    assert_eq!(r, (OrientStatus::Ok, n));
    assert!(c_out.iter().zip(&out).all(|(o, q)| c_bits(*o) == bits(*q)));
    // The output overlapping the gyroscope array: the samples are copied first.
    let mut shared = vec![0.0; 4 * n];
    shared[..3 * n].copy_from_slice(&a.gyro);
    let mut processed = 0;
    // SAFETY: `shared` holds the 3 n gyroscope doubles and room for n quaternions.
    let (status, aliased) = peak_of(|| unsafe {
        orient_smooth_arrays(
            &c_config(None),
            n,
            a.dt.as_ptr(),
            n,
            shared.as_ptr(),
            a.accel.as_ptr(),
            a.mag.as_ptr(),
            shared.as_mut_ptr() as *mut OrientQuaternion,
            &mut processed,
        )
    });
    assert_eq!((status, processed), (OrientStatus::Ok, n));
    let q = |i: usize| Quat::new(shared[4 * i], shared[4 * i + 1], shared[4 * i + 2], shared[4 * i + 3]);
    assert!((0..n).all(|i| bits(q(i)) == bits(out[i])), "aliased output");
    let (r, old) = peak_of(|| oracle::smooth(&config, &samples));
    assert!(r.unwrap().iter().zip(&out).all(|(o, q)| bits(*o) == bits(*q)));
    println!(
        "n = {n}: smooth_into {rust} B, orient_smooth_arrays {c} B, aliased {aliased} B \
         (bound {bound} B); the form that kept every pass {old} B"
    );
    for (what, peak) in [("smooth_into", rust), ("orient_smooth_arrays", c)] {
        assert!(peak >= 8 * n && peak <= bound, "{what}: {peak} bytes at peak, bound {bound}");
    }
    let copy = n * std::mem::size_of::<Sample>();
    assert_eq!(std::mem::size_of::<Sample>(), 104, "the header's figure for a copied sample");
    assert!(aliased >= copy && aliased <= bound + copy, "aliased: {aliased} bytes at peak");
    assert!(old > 100 * n, "the oracle keeps every pass: {old} bytes");
}

#[test]
#[cfg(target_pointer_width = "64")]
fn a_buffer_that_cannot_be_allocated_is_a_status() {
    // The largest count the output array allows: its 8 bytes per sample (2^61 bytes) fit
    // no address space, so the allocation fails before any sample is read; the arrays
    // (a few samples) are never read past.
    let n = offline::max_samples();
    assert_eq!(offline::memory(n), Some(8 * n + 32768));
    let a = arrays(&still(4));
    let mut out = [OrientQuaternion { w: 7.0, x: 7.0, y: 7.0, z: 7.0 }; 4];
    let mut processed = usize::MAX;
    // SAFETY: the call allocates before it reads; see above.
    let status = unsafe {
        orient_smooth_arrays(
            &c_config(None),
            n,
            a.dt.as_ptr(),
            1,
            a.gyro.as_ptr(),
            a.accel.as_ptr(),
            a.mag.as_ptr(),
            out.as_mut_ptr(),
            &mut processed,
        )
    };
    assert_eq!((status, processed), (OrientStatus::OutOfMemory, 0));
    assert!(out.iter().all(|q| q.w == 7.0 && q.z == 7.0), "the output is left unwritten");
    // SAFETY: orient_last_error returns this thread's NUL-terminated detail.
    let detail = unsafe { std::ffi::CStr::from_ptr(orient::ffi::orient_last_error()) }.to_str().unwrap();
    // (The claimed arrays, exabytes each, overlap the output: the call would copy them.)
    assert!(detail.contains("bytes could not be allocated"), "{detail}");
    // The Rust form says so too, over a recording and slots that exist only by index.
    struct Endless(usize, Sample);
    impl offline::SampleSource for Endless {
        fn len(&self) -> usize {
            self.0
        }
        fn sample(&self, _: usize) -> Sample {
            self.1
        }
    }
    impl offline::Orientations for Endless {
        fn len(&self) -> usize {
            self.0
        }
        fn get(&self, _: usize) -> Quat {
            panic!("nothing is read back before the buffer is allocated")
        }
        fn set(&mut self, _: usize, _: Quat) {
            panic!("nothing is written before the buffer is allocated")
        }
    }
    let (source, mut slots) = (Endless(n, still(1)[0]), Endless(n, still(1)[0]));
    let e = offline::smooth_into(&offline::config(), &source, &mut slots).unwrap_err();
    assert_eq!(e, SmoothError::OutOfMemory { bytes: 8 * n });
    assert_eq!(e.to_string(), format!("a buffer of {} bytes could not be allocated", 8 * n));
    // One past the largest count: no such recording.
    let mut bytes = 5;
    // SAFETY: a valid out pointer.
    assert_eq!(unsafe { orient_smooth_memory(n + 1, &mut bytes) }, OrientStatus::CountTooLarge);
    assert_eq!(unsafe { orient_smooth_memory(usize::MAX, &mut bytes) }, OrientStatus::CountTooLarge);
    assert_eq!(bytes, 5);
    assert_eq!(unsafe { orient_smooth_memory(1, std::ptr::null_mut()) }, OrientStatus::NullPointer);
    // SAFETY: as above.
    let status = unsafe {
        orient_smooth_arrays(
            &c_config(None),
            n + 1,
            a.dt.as_ptr(),
            1,
            a.gyro.as_ptr(),
            a.accel.as_ptr(),
            a.mag.as_ptr(),
            out.as_mut_ptr(),
            &mut processed,
        )
    };
    assert_eq!((status, processed), (OrientStatus::CountTooLarge, 0));
}
