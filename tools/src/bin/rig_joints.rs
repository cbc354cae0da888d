//! Issue 42 deliverable 6: the joint-constraint heading estimator (`orient_tools::joints`)
//! under robust 6D and VQF 6D, on the issue's five simulated glove cases (and the leg),
//! over several seeds, beside every sensor alone. RIG-FORMAT.md's scores, degrees.
//!
//! ```text
//! cargo run --release -p orient-tools --bin rig_joints [-- --seeds A-B] [--minutes M] [--gyro-scale PCT]
//!     [--cases a,b,..] [--filters robust,vqf] [--set KEY=VALUE].. [--oracle] [--cost]
//!     [--debias true|initial] [--filter-set NAME=VALUE].. [--plain] [--bias-drift F]
//!     [--no-alone] [--verbose] [--trace FILE [--truth-input]]
//! ```
//!
//! - `--seeds A-B` (default 1-3): the seeds per case (design on 1-3, hold out 4-8).
//! - `--bias-drift F`: the share of each case's bias bound that the biases drift (the
//!   simulator's 0.2 unless given; 0 for constant biases).
//! - `--set KEY=VALUE`: a [`JointParams`] field (`q_heading`, `r_hinge`, ...; angles in
//!   the units of the field's doc).
//! - `--oracle`: also the floor: each child's relative heading set from the truth (what
//!   remains is the filters' inclination and the joints' truth not in any heading).
//! - `--cost`: the time of the joint stage beside the filters' in the same run (thread CPU
//!   time, [`orient_tools::clock`]).
//! - `--filter-set NAME=VALUE`: a robust filter parameter by its name (`bias_limit`, ...).
//! - Under joints (and for the oracle) the filters take the settings for joints
//!   (`Config::for_joints`, before `--filter-set`); every sensor alone, the defaults.
//!   `--plain`: the defaults under joints too.
//! - `--debias true|initial`: the gyroscopes' readings less the true bias (`true`) or
//!   less the bias at the start (`initial`, what the still reference pose could give):
//!   how much of the error a better bias estimate could remove.
//!
//! - `--no-alone`: without the every-sensor-alone runs; `--verbose`: each seed's error
//!   per joint under joints (stderr).
//! - `--trace FILE`: one more run under joints per case, seed and filter (the last one stays in
//!   FILE), a CSV row per sample: t, the first sensor's rate (rad/s), then per joint the
//!   relative heading error after and before the joint stage (deg), its rating and its
//!   measured drift (deg/s); `--truth-input`: the joint stage is given the true sensor
//!   orientations.
//!
//! A benchmark, not a test: it asserts nothing.

use orient::{Config, Filter, Kind, Quat, Sample, Vec3};

const USAGE: &str = "usage: rig_joints [--seeds A-B] [--minutes M] [--gyro-scale PCT] [--cases a,b,..] \
                     [--filters robust,vqf] [--set KEY=VALUE].. [--oracle] [--no-alone] [--cost] [--trace FILE] \
                     [--truth-input] [--debias true|initial] [--filter-set NAME=VALUE].. [--verbose] [--plain] \
                     [--bias-drift F]\n(the options are described at the top of tools/src/bin/rig_joints.rs)";
use orient_tools::joints::{JointParams, Joints};
use orient_tools::rig::{
    joint_errors, reference_row, run_rig, score_rig, twist_angle, Alone, JointStage, RigRecording, RigScores,
    SensorFilter,
};
use orient_tools::rigsim::{bias_drift_arg, seed_range, unknown_preset, SimConfig, Simulation};

/// Sets each child's heading relative to its parent from the truth.
struct Oracle<'a> {
    rec: &'a RigRecording,
    start: usize,
}

impl JointStage for Oracle<'_> {
    fn update(&mut self, row: usize, _: &[Sample], _: &[bool], sensors: &mut [Quat]) {
        if row < self.start {
            return;
        }
        let spec = &self.rec.spec;
        let mut depth: Vec<(usize, usize)> = Vec::new();
        for (k, j) in spec.joints.iter().enumerate() {
            let mut d = 0;
            let mut s = j.child;
            while let Some(jj) = spec.joints.iter().find(|x| x.child == s) {
                s = jj.parent;
                d += 1;
            }
            depth.push((d, k));
        }
        depth.sort_unstable();
        for (_, k) in depth {
            let j = &spec.joints[k];
            let (tp, tc) = (self.rec.sensors[j.parent].truth[row], self.rec.sensors[j.child].truth[row]);
            let rt = tp.conj() * tc;
            let want = sensors[j.parent] * rt;
            let d = twist_angle(want * sensors[j.child].conj(), Vec3::new(0.0, 0.0, 1.0));
            sensors[j.child] = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), d) * sensors[j.child];
        }
    }
}

/// Runs [`Joints`] and writes, per row, each joint's heading error (deg, the turn about
/// the vertical that would make the child right relative to its parent) and rating.
struct Trace<'a> {
    rec: &'a RigRecording,
    joints: Joints,
    truth_input: bool,
    out: std::io::BufWriter<std::fs::File>,
}

impl JointStage for Trace<'_> {
    fn update(&mut self, row: usize, samples: &[Sample], learns: &[bool], sensors: &mut [Quat]) {
        use std::io::Write;
        if self.truth_input {
            for (s, q) in sensors.iter_mut().enumerate() {
                *q = self.rec.sensors[s].truth[row];
            }
        }
        let raw: Vec<Quat> = sensors.to_vec();
        self.joints.update(row, samples, learns, sensors);
        let spec = &self.rec.spec;
        let _ = write!(self.out, "{:.3},{:.3}", self.rec.t()[row], samples[0].gyro.unwrap().norm());
        for (k, j) in spec.joints.iter().enumerate() {
            let (tp, tc) = (self.rec.sensors[j.parent].truth[row], self.rec.sensors[j.child].truth[row]);
            let want = sensors[j.parent] * (tp.conj() * tc);
            let d = twist_angle(want * sensors[j.child].conj(), Vec3::new(0.0, 0.0, 1.0));
            let d0 =
                twist_angle(raw[j.parent] * (tp.conj() * tc) * raw[j.child].conj(), Vec3::new(0.0, 0.0, 1.0));
            let e = &self.joints.joints;
            let _ = write!(
                self.out,
                ",{:.3},{:.3},{:.3},{:.4}",
                d.to_degrees(),
                d0.to_degrees(),
                e.rating(k),
                e.drift(k).to_degrees()
            );
        }
        let _ = writeln!(self.out);
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Base {
    Robust,
    Vqf,
}

/// The sensors' filters; `under_joints`: with the settings for joints (`Config::for_joints`)
/// before `tuning`.
fn filters(b: Base, n: usize, dt: f64, tuning: &[(String, f64)], under_joints: bool) -> Vec<SensorFilter> {
    let mut config = Config::new(Kind::Robust).unwrap();
    if under_joints {
        config.for_joints();
    }
    for (name, value) in tuning {
        config.set(name, *value).expect("a robust parameter's name").expect("a value in range");
    }
    (0..n)
        .map(|_| match b {
            Base::Robust => SensorFilter::Orient(Box::new(Filter::new(&config).unwrap())),
            Base::Vqf => SensorFilter::vqf(dt, false),
        })
        .collect()
}

fn set_param(p: &mut JointParams, kv: &str) {
    let (k, v) = kv.split_once('=').expect("--set KEY=VALUE");
    let v: f64 = v.parse().expect("a number");
    match p.set(k, v) {
        Some(true) => {}
        Some(false) => panic!("{k} = {v} is out of its range (orient::joints::JOINT_PARAMS)"),
        None => panic!("unknown parameter {k}"),
    }
}

/// The usage on stderr after `what`, and exit status 2.
fn usage_error(what: &str) -> ! {
    eprintln!("rig_joints: {what}\n{USAGE}");
    std::process::exit(2)
}

fn main() {
    let (mut s0, mut s1) = (1u64, 3u64);
    let mut minutes = 10.0;
    let mut gyro_scale = 0.0;
    let mut drift = None;
    let mut cases: Vec<String> =
        ["100hz", "60hz-vigorous", "palm-sideways", "bias-3dps", "axes-5deg-off"].map(String::from).to_vec();
    let mut bases = vec![Base::Robust, Base::Vqf];
    let mut params = JointParams::default();
    let mut trace: Option<String> = None;
    let mut truth_input = false;
    let mut debias = String::new();
    let mut tuning: Vec<(String, f64)> = Vec::new();
    let (mut oracle, mut cost, mut alone, mut verbose, mut plain) = (false, false, true, false, false);
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        let mut val = || it.next().expect("a value");
        match a.as_str() {
            "--seeds" => (s0, s1) = seed_range(&val()),
            "--minutes" => minutes = val().parse().unwrap(),
            "--gyro-scale" => gyro_scale = val().parse().unwrap(),
            "--bias-drift" => drift = Some(bias_drift_arg(&val()).unwrap_or_else(|e| panic!("{e}"))),
            "--cases" => cases = val().split(',').map(String::from).collect(),
            "--filters" => {
                bases = val()
                    .split(',')
                    .map(|f| match f {
                        "robust" => Base::Robust,
                        "vqf" => Base::Vqf,
                        _ => usage_error(&format!("unknown filter '{f}' (robust, vqf)")),
                    })
                    .collect()
            }
            "--set" => set_param(&mut params, &val()),
            "--oracle" => oracle = true,
            "--no-alone" => alone = false,
            "--cost" => cost = true,
            "--trace" => trace = Some(val()),
            "--truth-input" => truth_input = true,
            "--debias" => debias = val(),
            "--filter-set" => {
                let v = val();
                let (k, x) = v.split_once('=').expect("--filter-set NAME=VALUE");
                tuning.push((k.to_string(), x.parse().expect("a number")));
            }
            "--verbose" => verbose = true,
            "--plain" => plain = true,
            "-h" | "--help" => {
                println!("{USAGE}");
                std::process::exit(0)
            }
            _ => usage_error(&format!("unknown argument '{a}'")),
        }
    }
    if let Some(e) = unknown_preset(&cases) {
        usage_error(&e);
    }
    eprintln!("{params:?}");
    // [case][base][method] -> scores per seed; methods: alone, joints, oracle.
    let methods = ["alone", "joints", "oracle"];
    let mut res: Vec<Vec<Vec<Vec<RigScores>>>> = vec![vec![vec![Vec::new(); 3]; bases.len()]; cases.len()];
    let (mut t_filters, mut t_joints, mut samples) = (0.0, 0.0, 0usize);
    for (c, case) in cases.iter().enumerate() {
        for seed in s0..=s1 {
            let mut config = SimConfig::preset(case, seed).expect("a preset");
            config.duration_s = minutes * 60.0;
            config.gyro_scale_pct = gyro_scale;
            config.bias_drift = drift.unwrap_or(config.bias_drift);
            let mut sim = Simulation::new(config).run();
            for (s, bias) in sim.recording.sensors.iter_mut().zip(&sim.bias) {
                s.mag.clear();
                for (g, b) in s.gyro.iter_mut().zip(bias) {
                    match debias.as_str() {
                        "true" => *g = *g - *b,
                        "initial" => *g = *g - bias[0],
                        "" => {}
                        _ => panic!("--debias true|initial"),
                    }
                }
            }
            let rec = &sim.recording;
            let truth: Vec<&[Quat]> = rec.sensors.iter().map(|r| r.truth.as_slice()).collect();
            let start = reference_row(&rec.spec, rec.t()).unwrap_or(0);
            let dt = 1.0 / rec.spec.rate_hz;
            for (b, base) in bases.iter().enumerate() {
                let score = |run: &orient_tools::rig::RigRun| {
                    score_rig(&rec.spec, rec.t(), &joint_errors(&rec.spec, &run.sensors, &truth))
                };
                let mut line = format!(
                    "{case:<14} seed {seed} {:<7}",
                    if *base == Base::Vqf { "VQF" } else { "robust" }
                );
                for (m, name) in methods.iter().enumerate().chain(trace.iter().map(|_| (3, &"trace"))) {
                    let run = match m {
                        0 if alone || cost => {
                            let mut f = filters(*base, rec.spec.sensors.len(), dt, &tuning, false);
                            run_rig(rec, &mut f, &mut Alone, true)
                        }
                        1 => {
                            let mut f = filters(*base, rec.spec.sensors.len(), dt, &tuning, !plain);
                            let mut st = Joints::new(&rec.spec, start, params);
                            run_rig(rec, &mut f, &mut st, true)
                        }
                        3 => {
                            let mut f = filters(*base, rec.spec.sensors.len(), dt, &tuning, !plain);
                            let out = std::io::BufWriter::new(
                                std::fs::File::create(trace.as_ref().unwrap()).unwrap(),
                            );
                            let joints = Joints::new(&rec.spec, start, params);
                            run_rig(rec, &mut f, &mut Trace { rec, joints, out, truth_input }, true)
                        }
                        2 if oracle => {
                            let mut f = filters(*base, rec.spec.sensors.len(), dt, &tuning, !plain);
                            run_rig(rec, &mut f, &mut Oracle { rec, start }, true)
                        }
                        _ => continue,
                    };
                    if cost {
                        match m {
                            0 => t_filters += run.elapsed.as_secs_f64(),
                            1 => t_joints += run.elapsed.as_secs_f64(),
                            _ => {}
                        }
                        if m == 1 {
                            samples += rec.rows() * rec.spec.joints.len();
                        }
                    }
                    let s = score(&run);
                    line += &format!("  {name} {:5.2} / {:5.2} / {:5.2}", s.all, s.worst.1, s.last_minute);
                    if verbose && m == 1 {
                        let per: Vec<String> = rec
                            .spec
                            .joints
                            .iter()
                            .zip(&s.joints)
                            .map(|(j, e)| format!("{} {:.2}", j.name, e))
                            .collect();
                        eprintln!("    {}", per.join(", "));
                    }
                    if m < 3 {
                        res[c][b][m].push(s);
                    }
                }
                eprintln!("{line}");
            }
        }
    }
    println!("\nRIG-FORMAT.md scores, 6D, deg: all joints / worst joint / last minute; mean over seeds {s0}-{s1} [max over seeds of all], {minutes} min, biases drifting by {} of their bound\n", drift.unwrap_or(SimConfig::glove(0).bias_drift));
    println!(
        "| case | filter | alone | joints | {}",
        if oracle { "oracle (heading from truth) |" } else { "" }
    );
    println!("|---|---|---|---|{}", if oracle { "---|" } else { "" });
    let mean = |v: &[RigScores], f: fn(&RigScores) -> f64| v.iter().map(f).sum::<f64>() / v.len() as f64;
    let maxall = |v: &[RigScores]| v.iter().map(|s| s.all).fold(0.0, f64::max);
    for (c, case) in cases.iter().enumerate() {
        for (b, base) in bases.iter().enumerate() {
            let cell = |v: &[RigScores]| {
                if v.is_empty() {
                    String::from("-")
                } else {
                    format!(
                        "{:.2} / {:.2} / {:.2} [{:.2}]",
                        mean(v, |s| s.all),
                        mean(v, |s| s.worst.1),
                        mean(v, |s| s.last_minute),
                        maxall(v)
                    )
                }
            };
            let r = &res[c][b];
            println!(
                "| {case} | {} | {} | {} |{}",
                if *base == Base::Vqf { "VQF 6D" } else { "robust 6D" },
                cell(&r[0]),
                cell(&r[1]),
                if oracle { format!(" {} |", cell(&r[2])) } else { String::new() }
            );
        }
    }
    if cost && samples > 0 {
        println!(
            "\ncost (thread CPU time on {}): joint stage {:.1} ns per joint update; time ratio \
             (filters + joints) / filters = {:.3}",
            orient_tools::clock::cpu_model(),
            (t_joints - t_filters) * 1e9 / samples as f64,
            t_joints / t_filters
        );
    }
}
