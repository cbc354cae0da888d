//! Update cost of every filter kind, IMU and MARG: through the Rust API, through the C
//! ABI (called through an opaque function pointer, as a host's call through the shared
//! library is), and per sample of the batch call. Prints medians over repeated rounds
//! and ratios to the Rust API in the same run.
//!
//!     cargo run --release --example bench [-- --rounds N]
//!
//! Input: the real recording in examples/data (13,500 samples, cycled).

use orient::eval::Recording;
use orient::ffi::{
    orient_config_default, orient_filter_free, orient_filter_new, orient_filter_update,
    orient_filter_update_batch, OrientConfig, OrientFilter, OrientQuaternion, OrientSample, OrientStatus,
    OrientVec3, ORIENT_SAMPLE_ACCEL, ORIENT_SAMPLE_GYRO, ORIENT_SAMPLE_MAG,
};
use orient::filters::madgwick::{Madgwick, MadgwickSettings};
use orient::{Config, Filter, Kind, Sample, Vec3};
use std::hint::black_box;
use std::time::Instant;

const PER_ROUND: usize = 20_000;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[v.len() / 2]
}

/// Median ns per sample of each variant, each of which processes PER_ROUND samples per
/// call. Variants run interleaved, round by round, so that a slow phase of the machine
/// (frequency, another process) hits them all alike.
fn time_interleaved(rounds: usize, variants: &mut [Box<dyn FnMut() + '_>]) -> Vec<f64> {
    for v in variants.iter_mut() {
        v(); // warm up
    }
    let mut runs = vec![Vec::with_capacity(rounds); variants.len()];
    for _ in 0..rounds {
        for (v, r) in variants.iter_mut().zip(runs.iter_mut()) {
            let t = Instant::now();
            v();
            r.push(t.elapsed().as_secs_f64() * 1e9 / PER_ROUND as f64);
        }
    }
    runs.into_iter().map(median).collect()
}

fn c_sample(s: &Sample) -> OrientSample {
    let v = |v: Option<Vec3>| v.map_or(OrientVec3::default(), |v| OrientVec3 { x: v.x, y: v.y, z: v.z });
    let flags = ORIENT_SAMPLE_GYRO
        | if s.accel.is_some() { ORIENT_SAMPLE_ACCEL } else { 0 }
        | if s.mag.is_some() { ORIENT_SAMPLE_MAG } else { 0 };
    OrientSample { dt: s.dt, gyro: v(s.gyro), accel: v(s.accel), mag: v(s.mag), flags, reserved: 0 }
}

fn new_c_filter(kind: Kind) -> *mut OrientFilter {
    let k = Kind::ALL.iter().position(|x| *x == kind).unwrap() as i32 + 1;
    let mut c = std::mem::MaybeUninit::<OrientConfig>::uninit();
    let mut h = std::ptr::null_mut();
    unsafe {
        assert_eq!(orient_config_default(k, c.as_mut_ptr()), OrientStatus::Ok);
        assert_eq!(orient_filter_new(c.as_ptr(), &mut h), OrientStatus::Ok);
    }
    h
}

struct Row {
    label: String,
    ns: f64,
    baseline: f64,
}

fn main() {
    let mut rounds = 21;
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--rounds") {
        rounds = args.get(i + 1).and_then(|v| v.parse().ok()).expect("--rounds N");
    }
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/data/broad_01_excerpt.csv");
    let marg_rec = Recording::read(path.as_ref(), true).expect("demo recording");
    let mut rows: Vec<Row> = Vec::new();

    for kind in Kind::ALL {
        for (mode, with_mag) in [("IMU", false), ("MARG", true)] {
            let mut samples = marg_rec.samples();
            if !with_mag {
                samples.iter_mut().for_each(|s| s.mag = None);
            }
            let samples: Vec<Sample> = samples.iter().cycle().take(PER_ROUND).copied().collect();
            let c_samples: Vec<OrientSample> = samples.iter().map(c_sample).collect();

            // Every variant starts from the same state: past start-up, on the recording.
            let mut core = Madgwick::new(MadgwickSettings::default());
            let mut filter = Filter::new(&Config::new(kind).unwrap()).unwrap();
            let handles = [new_c_filter(kind), new_c_filter(kind), new_c_filter(kind)];
            for s in &samples[..1000] {
                filter.update(s).unwrap();
            }
            for h in handles {
                let mut n = 0;
                let status = unsafe {
                    orient_filter_update_batch(h, c_samples.as_ptr(), 1000, std::ptr::null_mut(), &mut n)
                };
                assert_eq!(status, OrientStatus::Ok);
            }
            let update: unsafe extern "C" fn(*mut OrientFilter, *const OrientSample) -> OrientStatus =
                black_box(orient_filter_update);
            let batch_fn = black_box(orient_filter_update_batch);
            let mut out = vec![OrientQuaternion::default(); PER_ROUND];
            let mut processed = 0usize;
            let medians = {
                let mut variants: Vec<Box<dyn FnMut() + '_>> = vec![
                    Box::new(|| {
                        for s in black_box(&samples) {
                            let _ = black_box(filter.update(s));
                        }
                    }),
                    Box::new(|| {
                        for s in &c_samples {
                            black_box(unsafe { update(handles[0], s) });
                        }
                    }),
                    Box::new(|| unsafe {
                        let n = c_samples.len();
                        black_box(batch_fn(
                            handles[1],
                            c_samples.as_ptr(),
                            n,
                            std::ptr::null_mut(),
                            &mut processed,
                        ));
                    }),
                    Box::new(|| unsafe {
                        let n = c_samples.len();
                        black_box(batch_fn(
                            handles[2],
                            c_samples.as_ptr(),
                            n,
                            out.as_mut_ptr(),
                            std::ptr::null_mut(),
                        ));
                    }),
                ];
                if kind == Kind::Madgwick {
                    // The bare Madgwick core: no checks, no frame handling.
                    variants.push(Box::new(|| {
                        for s in &samples {
                            black_box(core.update(s.dt, s.gyro.unwrap(), s.accel, s.mag));
                        }
                    }));
                }
                time_interleaved(rounds, &mut variants)
            };
            for h in handles {
                unsafe { orient_filter_free(h) };
            }
            let labels = [
                "Rust Filter::update",
                "C orient_filter_update",
                "C update_batch",
                "C update_batch, quaternions out",
                "bare Madgwick core (no checks)",
            ];
            for (label, ns) in labels.iter().zip(&medians) {
                rows.push(Row {
                    label: format!("{:<13} {mode:<4} {label}", kind.name()),
                    ns: *ns,
                    baseline: medians[0],
                });
            }
        }
    }

    println!(
        "orient {} bench: median of {rounds} rounds x {PER_ROUND} samples (BROAD excerpt)",
        env!("CARGO_PKG_VERSION")
    );
    println!("{:<52} {:>10} {:>14}", "path", "ns/update", "vs Rust API");
    for r in &rows {
        println!("{:<52} {:>10.1} {:>13.2}x", r.label, r.ns, r.ns / r.baseline);
    }
}
