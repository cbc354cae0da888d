//! Update cost of every filter kind, IMU and MARG: through the Rust API, through the C
//! ABI (called through an opaque function pointer, as a host's call through the shared
//! library is), and per sample of the batch call; beside them, in the same process and
//! on the same samples, the fastest existing Rust implementations of the same filters
//! (the `ahrs` crate's Madgwick and Mahony, `fusion-ahrs`, a port of x-io Fusion, and
//! `vqf-rs`, a port of VQF). For Madgwick and Mahony, also the floor under any update of
//! theirs: the same arithmetic with nothing else (module `floor`), once with the state
//! read from and written to memory each step, as a call must, and once held in
//! registers. Then one frame of a 20-sensor rig through the multi-sensor call. Prints
//! medians over interleaved rounds and ratios measured in the same run.
//!
//!     cargo run --release --bin bench [-- --rounds N]
//!     bench --check                      (only the check that each floor computes its
//!                                        core's numbers, which the timing run and
//!                                        tools/tests/floor.rs also make)
//!     bench --count KIND imu|marg N [c] (N updates and orientation reads only, through the
//!                                        Rust API or with `c` the C ABI; KIND may also be an
//!                                        anchor, ahrs-madgwick, ahrs-mahony or vqf: for
//!                                        instruction counts under callgrind, see
//!                                        scripts/callgrind-counts.sh)
//!
//! Input: the real recording in examples/data (13,500 samples, cycled).

use orient::ffi::{
    orient_config_default, orient_filter_free, orient_filter_new, orient_filter_quaternion,
    orient_filter_update, orient_filter_update_batch, orient_filters_update, OrientConfig, OrientFilter,
    OrientQuaternion, OrientSample, OrientStatus, OrientVec3, ORIENT_SAMPLE_ACCEL, ORIENT_SAMPLE_GYRO,
    ORIENT_SAMPLE_MAG,
};
use orient::filters::madgwick::{Madgwick, MadgwickSettings};
use orient::filters::mahony::{Mahony, MahonySettings};
use orient::{Config, Filter, Kind, Quat, Sample, Vec3};
use orient_tools::clock;
use orient_tools::eval::Recording;
use std::hint::black_box;

const PER_ROUND: usize = 20_000;
/// Sensors in the rig of the multi-sensor benchmark (the bones of a hand).
const RIG: usize = 20;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[v.len() / 2]
}

/// Median ns per unit of work of each variant, each of which does `units` units per
/// call. Variants run interleaved, round by round, so that a slow phase of the machine
/// (frequency, another process) hits them all alike.
fn time_interleaved(rounds: usize, units: usize, variants: &mut [Box<dyn FnMut() + '_>]) -> Vec<f64> {
    for v in variants.iter_mut() {
        v(); // warm up
    }
    let mut runs = vec![Vec::with_capacity(rounds); variants.len()];
    for _ in 0..rounds {
        for (v, r) in variants.iter_mut().zip(runs.iter_mut()) {
            let ((), t) = clock::time(&mut *v);
            r.push(t.as_secs_f64() * 1e9 / units as f64);
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

fn na(v: Vec3) -> nalgebra_ahrs::Vector3<f64> {
    nalgebra_ahrs::Vector3::new(v.x, v.y, v.z)
}

/// One anchor: a name and a closure that runs PER_ROUND samples.
struct Anchor<'a> {
    name: &'static str,
    run: Box<dyn FnMut() + 'a>,
}

/// One of the `ahrs` crate's filters (f64) over the samples.
fn ahrs_anchor<'a, F: ahrs::Ahrs<f64> + 'a>(
    name: &'static str,
    mut f: F,
    samples: &'a [Sample],
    mag: bool,
) -> Anchor<'a> {
    Anchor {
        name,
        run: Box::new(move || {
            for s in samples {
                let (g, a) = (na(s.gyro.unwrap()), na(s.accel.unwrap()));
                let r = if mag { f.update(&g, &a, &na(s.mag.unwrap())) } else { f.update_imu(&g, &a) };
                let _ = black_box(r);
            }
        }),
    }
}

fn anchors<'a>(kind: Kind, samples: &'a [Sample], mag: bool) -> Vec<Anchor<'a>> {
    let dt = samples[0].dt;
    let mut out: Vec<Anchor<'a>> = Vec::new();
    match kind {
        Kind::Madgwick => {
            out.push(ahrs_anchor("ahrs Madgwick (f64)", ahrs::Madgwick::new(dt, 0.041), samples, mag));
            out.push(fusion_anchor(samples, mag));
        }
        Kind::Mahony => {
            out.push(ahrs_anchor("ahrs Mahony (f64)", ahrs::Mahony::new(dt, 0.5, 0.0), samples, mag));
            out.push(fusion_anchor(samples, mag));
        }
        Kind::Robust => {
            let mut f = vqf_rs::VQF::new(dt, None, None, None);
            out.push(Anchor {
                name: "vqf-rs VQF (f64)",
                run: Box::new(move || {
                    for s in samples {
                        let v = |v: Vec3| [v.x, v.y, v.z];
                        f.update(v(s.gyro.unwrap()), v(s.accel.unwrap()), s.mag.map(v));
                        black_box(f.quat_9d());
                    }
                }),
            });
        }
        _ => {}
    }
    out
}

/// x-io Fusion through `fusion-ahrs` (f32; degrees per second and g).
fn fusion_anchor(samples: &[Sample], mag: bool) -> Anchor<'_> {
    let mut f = fusion_ahrs::Ahrs::new();
    Anchor {
        name: "fusion-ahrs Fusion (f32)",
        run: Box::new(move || {
            for s in samples {
                let deg = |v: Vec3| fusion_ahrs::Vector::new(v.x as f32, v.y as f32, v.z as f32) * 57.29578;
                let g = |v: Vec3| fusion_ahrs::Vector::new(v.x as f32, v.y as f32, v.z as f32) * 0.10197162;
                f.set_sample_period(s.dt as f32);
                if mag {
                    let m = s.mag.unwrap();
                    f.update(
                        deg(s.gyro.unwrap()),
                        g(s.accel.unwrap()),
                        fusion_ahrs::Vector::new(m.x as f32, m.y as f32, m.z as f32),
                    );
                } else {
                    f.update_no_magnetometer(deg(s.gyro.unwrap()), g(s.accel.unwrap()));
                }
                black_box(f.quaternion());
            }
        }),
    }
}

use orient_tools::floor;

/// `f` on `n` items: whole passes over `items`, then a part of one.
#[inline(always)]
fn run<T>(items: &[T], n: usize, mut f: impl FnMut(&T)) {
    for _ in 0..n / items.len() {
        items.iter().for_each(&mut f);
    }
    items[..n % items.len()].iter().for_each(f);
}

/// [`count`] for one of the `ahrs` crate's filters (f64); its update returns the orientation.
/// Out of line, as [`orient_count`] is.
#[inline(never)]
fn ahrs_count<F: ahrs::Ahrs<f64>>(mut f: F, samples: &[Sample], mag: bool, n: usize) {
    run(samples, n, |s| {
        let (g, a) = (na(s.gyro.unwrap()), na(s.accel.unwrap()));
        let r = if mag { f.update(&g, &a, &na(s.mag.unwrap())) } else { f.update_imu(&g, &a) };
        let _ = black_box(r.copied());
    });
}

/// `n` updates of one contender, each followed by one orientation read, for instruction
/// counts under callgrind (`scripts/callgrind-counts.sh`). Every contender runs the same
/// loop (whole passes over the recording, then a part of one), so that the loop's
/// instructions, a few per update, are the same in each count. `who` is an orient kind
/// (through the Rust API, or the C ABI with `c`), or an anchor: `ahrs-madgwick`,
/// `ahrs-mahony` (the `ahrs` crate, f64) or `vqf` (`vqf-rs`).
fn count(who: &str, mag: bool, n: usize, samples: &[Sample], c: bool) {
    let dt = samples[0].dt;
    match who {
        "ahrs-madgwick" => ahrs_count(ahrs::Madgwick::new(dt, 0.041), samples, mag, n),
        "ahrs-mahony" => ahrs_count(ahrs::Mahony::new(dt, 0.5, 0.0), samples, mag, n),
        "vqf" => vqf_count(dt, samples, mag, n),
        _ if c => {
            // The same through the C ABI, called through a pointer as a host calls it.
            let kind = Kind::from_name(who).expect("--count KIND|ANCHOR imu|marg N [c]");
            let cs: Vec<OrientSample> = samples.iter().map(c_sample).collect();
            let h = new_c_filter(kind);
            let update: unsafe extern "C" fn(*mut OrientFilter, *const OrientSample) -> OrientStatus =
                black_box(orient_filter_update);
            let read: unsafe extern "C" fn(*const OrientFilter, *mut OrientQuaternion) -> OrientStatus =
                black_box(orient_filter_quaternion);
            run(&cs, n, |s| {
                let mut q = OrientQuaternion::default();
                black_box(unsafe { update(h, s) });
                black_box(unsafe { read(h, &mut q) });
            });
            unsafe { orient_filter_free(h) };
        }
        _ => orient_count(Kind::from_name(who).expect("--count KIND|ANCHOR imu|marg N [c]"), samples, n),
    }
}

/// [`count`] for `vqf-rs`. Out of line, as [`orient_count`] is.
#[inline(never)]
fn vqf_count(dt: f64, samples: &[Sample], mag: bool, n: usize) {
    let mut f = vqf_rs::VQF::new(dt, None, None, None);
    run(samples, n, |s| {
        let v = |v: Vec3| [v.x, v.y, v.z];
        f.update(v(s.gyro.unwrap()), v(s.accel.unwrap()), s.mag.map(v));
        black_box(if mag { f.quat_9d() } else { f.quat_6d() });
    });
}

/// [`count`] for an orient kind through the Rust API. A function of its own, so that its
/// loop's registers are allocated apart from `main`'s: inlined into `main`, the counts
/// moved by a few instructions whenever unrelated code in `main` changed.
#[inline(never)]
fn orient_count(kind: Kind, samples: &[Sample], n: usize) {
    let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
    // Inlined into the loop, as the anchors' closures are (LLVM left this one out of
    // line, whose call and register saves then counted as orient's).
    run(
        samples,
        n,
        #[inline(always)]
        |s| {
            let _ = black_box(f.update(s));
            black_box(f.quaternion());
        },
    );
}

fn main() {
    let mut rounds = 21;
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--rounds") {
        rounds = args.get(i + 1).and_then(|v| v.parse().ok()).expect("--rounds N");
    }
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/data/broad_01_excerpt.csv");
    let marg_rec = Recording::read(path.as_ref(), true).expect("demo recording");
    if let Some(i) = args.iter().position(|a| a == "--count-frame") {
        count_frame(&args[i + 1], args[i + 2].parse().expect("frames"), &marg_rec);
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--count-joints") {
        count_joints(&args[i + 1], args[i + 2].parse().expect("rows"));
        return;
    }
    if args.iter().any(|a| a == "--check") {
        floor::check_all(&marg_rec.samples()[..2000]);
        println!("the floors compute the cores' numbers");
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--count") {
        let with_mag = args[i + 2] == "marg";
        let n: usize = args[i + 3].parse().expect("N");
        let mut samples = marg_rec.samples();
        if !with_mag {
            samples.iter_mut().for_each(|s| s.mag = None);
        }
        count(&args[i + 1], with_mag, n, &samples, args.get(i + 4).is_some_and(|a| a == "c"));
        return;
    }
    println!(
        "orient {} bench: median ns per update (thread CPU time) over {rounds} rounds x {PER_ROUND} samples \
         (BROAD excerpt) on {}",
        env!("CARGO_PKG_VERSION"),
        clock::cpu_model()
    );
    println!(
        "{:<20} {:>7} {:>7} {:>9} {:>7} {:>8} {:>9}   anchors (ns, orient Rust / anchor)",
        "kind", "Rust", "C", "C-Rust", "batch", "batch/R", "batch+q"
    );

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
            let mut mahony_core = Mahony::new(MahonySettings::default());
            // The floor (`floor`) computes what the core computes: checked on these samples.
            if matches!(kind, Kind::Madgwick | Kind::Mahony) {
                floor::check(kind, with_mag, &samples[..2000]);
            }
            let (mut floor_mem, mut floor_reg) = (Quat::IDENTITY, Quat::IDENTITY);
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
            let mut anchor_list = anchors(kind, &samples, with_mag);
            let names: Vec<&str> = anchor_list.iter().map(|a| a.name).collect();
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
                for a in anchor_list.iter_mut() {
                    variants.push(Box::new(|| (a.run)()));
                }
                if kind == Kind::Mahony {
                    // The bare Mahony core, its state behind a pointer as in a host's.
                    variants.push(Box::new(|| {
                        for s in &samples {
                            let f = black_box(&mut mahony_core);
                            black_box(f.update(s.dt, s.gyro.unwrap(), s.accel, s.mag));
                        }
                    }));
                }
                if kind == Kind::Madgwick {
                    // The bare Madgwick core: no checks, no frame handling.
                    variants.push(Box::new(|| {
                        for s in &samples {
                            black_box(core.update(s.dt, s.gyro.unwrap(), s.accel, s.mag));
                        }
                    }));
                }
                if matches!(kind, Kind::Madgwick | Kind::Mahony) {
                    // The paper's arithmetic alone: state in memory, then in registers.
                    variants.push(Box::new(|| {
                        floor::run(kind, with_mag, black_box(&mut floor_mem), black_box(&samples), true);
                    }));
                    variants.push(Box::new(|| {
                        floor::run(kind, with_mag, black_box(&mut floor_reg), black_box(&samples), false);
                    }));
                }
                time_interleaved(rounds, PER_ROUND, &mut variants)
            };
            for h in handles {
                unsafe { orient_filter_free(h) };
            }
            let (rust, c, batch, batch_q) = (medians[0], medians[1], medians[2], medians[3]);
            print!(
                "{:<20} {rust:>7.1} {c:>7.1} {:>+9.1} {batch:>7.1} {:>8.3} {batch_q:>9.1}  ",
                format!("{} {mode}", kind.name()),
                c - rust,
                batch / rust
            );
            for (name, ns) in names.iter().zip(&medians[4..]) {
                print!(" {name} {ns:.1} ({:.2}x)", rust / ns);
            }
            if matches!(kind, Kind::Madgwick | Kind::Mahony) {
                let n = medians.len();
                print!(
                    " | bare core {:.1} | arithmetic alone {:.1}, state in registers {:.1}",
                    medians[n - 3],
                    medians[n - 2],
                    medians[n - 1]
                );
            }
            println!();
        }
    }
    multi_sensor(rounds, &marg_rec);
}

/// `frames` frames of the RIG-sensor Madgwick MARG rig of [`multi_sensor`], for
/// instruction counts (`--count-frame multi|single|rust FRAMES`; callgrind, as
/// `scripts/callgrind-counts.sh` does for single filters): `multi` is one
/// `orient_filters_update` per frame with quaternions out, `single` RIG calls of
/// `orient_filter_update` each with `orient_filter_quaternion` (the same outputs), `rust`
/// RIG calls of `Filter::update`.
fn count_frame(how: &str, frames: usize, rec: &Recording) {
    // 64 frames made beforehand and cycled, so that making them is no per-frame cost.
    let all = rec.samples();
    let made: Vec<[Sample; RIG]> = (0..64).map(|f| core::array::from_fn(|i| all[f + i])).collect();
    let made_c: Vec<[OrientSample; RIG]> = made.iter().map(|fr| fr.map(|s| c_sample(&s))).collect();
    let mut out = [OrientQuaternion::default(); RIG];
    match how {
        "multi" | "single" => {
            let rig: Vec<*mut OrientFilter> = (0..RIG).map(|_| new_c_filter(Kind::Madgwick)).collect();
            for f in 0..frames {
                let fr = &made_c[f % 64];
                if how == "multi" {
                    let st = unsafe {
                        orient_filters_update(
                            rig.as_ptr(),
                            fr.as_ptr(),
                            RIG,
                            out.as_mut_ptr(),
                            std::ptr::null_mut(),
                        )
                    };
                    black_box(st);
                } else {
                    for ((h, s), q) in rig.iter().zip(fr).zip(&mut out) {
                        black_box(unsafe { orient_filter_update(*h, s) });
                        black_box(unsafe { orient_filter_quaternion(*h, q) });
                    }
                }
            }
            for h in rig {
                unsafe { orient_filter_free(h) };
            }
        }
        "rust" => {
            let mut rig: Vec<Filter> =
                (0..RIG).map(|_| Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap()).collect();
            for f in 0..frames {
                for (filter, s) in rig.iter_mut().zip(&made[f % 64]) {
                    let _ = black_box(filter.update(s));
                }
            }
        }
        _ => panic!("--count-frame multi|single|rust FRAMES"),
    }
    black_box(out);
}

/// Instruction counts of a joint beside its two filters (`--count-joints filters|hinge|2dof
/// ROWS`; callgrind, as `scripts/callgrind-counts.sh` runs it): two robust IMU filters on
/// a hand and a finger in motion the whole time (the joint tests' motion: the hand turning
/// about every axis, the finger flexing about a hinge; 1,300 rows made beforehand, so that
/// up to that many rows are one continuous motion) and, unless `filters`, one joint of that kind updated after them each row and
/// its child segment read (`orient::joints`, Rust API).
fn count_joints(how: &str, rows: usize) {
    use orient::joints::{JointKind, JointParams, JointSpec, Joints};
    let rot = |x: f64, y: f64, z: f64, a: f64| Quat::from_axis_angle(Vec3::new(x, y, z), a);
    let hand = |t: f64| {
        rot(0.0, 0.0, 1.0, 0.5 * (0.3 * t).sin())
            * rot(0.0, 1.0, 0.0, 0.6 * (0.7 * t).sin())
            * rot(1.0, 0.0, 0.0, 0.4 * (1.1 * t).sin())
    };
    let finger = |t: f64| hand(t) * rot(1.0, 0.0, 0.0, 0.5 + 0.8 * (1.9 * t).sin());
    let dt = 0.01;
    let sample = |a: Quat, b: Quat| {
        let d = (a.conj() * b).normalized();
        let d = if d.w < 0.0 { d.scale(-1.0) } else { d };
        let s = d.vector().norm();
        let gyro = if s > 1e-15 { d.vector() * (2.0 * s.atan2(d.w) / s / dt) } else { Vec3::ZERO };
        Sample { dt, gyro: Some(gyro), accel: Some(b.rotate_inverse(Vec3::new(0.0, 0.0, 9.81))), mag: None }
    };
    const MADE: usize = 1300;
    let made: Vec<[Sample; 2]> = (1..=MADE)
        .map(|i| {
            let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
            [sample(hand(t0), hand(t1)), sample(finger(t0), finger(t1))]
        })
        .collect();
    let mut filters: Vec<Filter> =
        (0..2).map(|_| Filter::new(&Config::new(Kind::Robust).unwrap()).unwrap()).collect();
    let kind = match how {
        "filters" => None,
        "hinge" => Some(JointKind::Hinge),
        "2dof" => Some(JointKind::TwoDof),
        _ => panic!("--count-joints filters|hinge|2dof ROWS"),
    };
    let (z, x) = (Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 0.0));
    let (axis_parent, axis_child) = if kind == Some(JointKind::TwoDof) { (z, x) } else { (x, x) };
    let spec =
        JointSpec { kind: kind.unwrap_or(JointKind::Hinge), parent: 0, child: 1, axis_parent, axis_child };
    let mut joints = Joints::new(2, &[spec], &[], JointParams::default()).unwrap();
    for r in 0..rows {
        let row = &made[r % MADE];
        for (f, s) in filters.iter_mut().zip(row) {
            let _ = black_box(f.update(s));
        }
        if kind.is_some() {
            let refs = [&filters[0], &filters[1]];
            let _ = black_box(joints.update_from(&refs, row));
            black_box(joints.segment_quaternion(1));
        }
    }
}

/// One frame of RIG Madgwick MARG filters: one multi-sensor call against one C call
/// per sensor and the Rust API.
fn multi_sensor(rounds: usize, rec: &Recording) {
    const FRAMES: usize = 1000;
    let samples: Vec<OrientSample> = rec.samples().iter().take(FRAMES + RIG).map(c_sample).collect();
    // Sensor i of frame f reads recording sample f + i, so the sensors differ.
    let frames: Vec<[OrientSample; RIG]> =
        (0..FRAMES).map(|f| core::array::from_fn(|i| samples[f + i])).collect();
    let rig_a: Vec<*mut OrientFilter> = (0..RIG).map(|_| new_c_filter(Kind::Madgwick)).collect();
    let rig_b: Vec<*mut OrientFilter> = (0..RIG).map(|_| new_c_filter(Kind::Madgwick)).collect();
    let rig_c: Vec<*mut OrientFilter> = (0..RIG).map(|_| new_c_filter(Kind::Madgwick)).collect();
    let mut rig_r: Vec<Filter> =
        (0..RIG).map(|_| Filter::new(&Config::new(Kind::Madgwick).unwrap()).unwrap()).collect();
    let rust_frames: Vec<[Sample; RIG]> =
        (0..FRAMES).map(|f| core::array::from_fn(|i| rec.samples()[f + i])).collect();
    let multi = black_box(orient_filters_update);
    let single: unsafe extern "C" fn(*mut OrientFilter, *const OrientSample) -> OrientStatus =
        black_box(orient_filter_update);
    let read: unsafe extern "C" fn(*const OrientFilter, *mut OrientQuaternion) -> OrientStatus =
        black_box(orient_filter_quaternion);
    let mut out = [OrientQuaternion::default(); RIG];
    let mut out_c = [OrientQuaternion::default(); RIG];
    let m = {
        let mut variants: Vec<Box<dyn FnMut() + '_>> = vec![
            Box::new(|| {
                for fr in &frames {
                    black_box(unsafe {
                        multi(rig_a.as_ptr(), fr.as_ptr(), RIG, out.as_mut_ptr(), std::ptr::null_mut())
                    });
                }
            }),
            Box::new(|| {
                for fr in &frames {
                    for (h, s) in rig_b.iter().zip(fr) {
                        black_box(unsafe { single(*h, s) });
                    }
                }
            }),
            // Like for like with the multi-sensor call: each sensor's quaternion read out.
            Box::new(|| {
                for fr in &frames {
                    for ((h, s), q) in rig_c.iter().zip(fr).zip(out_c.iter_mut()) {
                        black_box(unsafe { single(*h, s) });
                        black_box(unsafe { read(*h, q) });
                    }
                }
            }),
            Box::new(|| {
                for fr in &rust_frames {
                    for (f, s) in rig_r.iter_mut().zip(fr) {
                        let _ = black_box(f.update(s));
                    }
                }
            }),
        ];
        time_interleaved(rounds, FRAMES, &mut variants)
    };
    for h in rig_a.into_iter().chain(rig_b).chain(rig_c) {
        unsafe { orient_filter_free(h) };
    }
    println!(
        "\n{RIG}-sensor Madgwick MARG frame (ns per frame): orient_filters_update {:.0} (with quaternions out), \
         {RIG} x orient_filter_update {:.0} ({:.2}x), {RIG} x (orient_filter_update + orient_filter_quaternion) {:.0} \
         ({:.2}x), Rust loop {:.0} ({:.2}x)",
        m[0],
        m[1],
        m[0] / m[1],
        m[2],
        m[0] / m[2],
        m[3],
        m[0] / m[3]
    );
}
