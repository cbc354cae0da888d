//! Issue 42 item 3: a joint's axes from a few seconds of motion, on simulated rigs. Per
//! case, seed and window: each joint's axes estimated from the window's readings (a
//! hinge: the gyroscopes, `estimate_hinge_axes`; a 2-DoF joint: the robust kind's 6D
//! orientations, `estimate_two_dof_axes`), started from the rig description's axes turned
//! a further `--guess-off` degrees, against the true axes; degrees, and the quality.
//!
//! ```text
//! cargo run --release -p orient-tools --bin rig_axes [-- --seeds A-B] [--cases a,b,..]
//!     [--windows 5,10,30] [--guess-off DEG]
//! ```
//!
//! A benchmark, not a test: it asserts nothing.

use orient::joints::{estimate_hinge_axes, estimate_two_dof_axes, JointKind};
use orient::{Config, Filter, Kind, Quat, Vec3};
use orient_tools::rig::{run_rig, Alone, SensorFilter};
use orient_tools::rigsim::{seed_range, unknown_preset, SimConfig, Simulation};

const USAGE: &str = "usage: rig_axes [--seeds A-B] [--cases a,b,..] [--windows 5,10,30] [--guess-off DEG]";

fn angle(a: Vec3, b: Vec3) -> f64 {
    libm::atan2(a.cross(b).norm(), a.dot(b)).to_degrees()
}

/// The usage on stderr after `what`, and exit status 2.
fn usage_error(what: &str) -> ! {
    eprintln!("rig_axes: {what}\n{USAGE}");
    std::process::exit(2)
}

fn main() {
    let (mut s0, mut s1) = (1u64, 3u64);
    let mut cases: Vec<String> =
        ["100hz", "60hz-vigorous", "axes-5deg-off", "leg"].map(String::from).to_vec();
    let mut windows = vec![5.0, 10.0, 30.0];
    let mut guess_off = 10.0f64;
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        let mut val = || it.next().expect("a value");
        match a.as_str() {
            "--seeds" => (s0, s1) = seed_range(&val()),
            "--cases" => cases = val().split(',').map(String::from).collect(),
            "--windows" => windows = val().split(',').map(|w| w.parse().unwrap()).collect(),
            "--guess-off" => guess_off = val().parse().unwrap(),
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
    println!("axes from motion, from t = 10 s: error (deg, the worse of the two axes) mean / max over joints and seeds {s0}-{s1}; quality mean / max; guesses {guess_off} deg further off\n");
    println!("| case | kind | window (s) | error mean / max | quality mean / max |");
    println!("|---|---|---|---|---|");
    for case in &cases {
        // [kind][window] -> (error, quality) per joint and seed.
        let mut res = vec![vec![Vec::new(); windows.len()]; 2];
        for seed in s0..=s1 {
            let mut config = SimConfig::preset(case, seed).expect("a preset");
            config.duration_s = 10.0 + windows.iter().fold(0.0f64, |a, b| a.max(*b)) + 1.0;
            let mut sim = Simulation::new(config).run();
            for s in &mut sim.recording.sensors {
                s.mag.clear();
            }
            let rec = &sim.recording;
            let n = rec.spec.sensors.len();
            let mut filters: Vec<SensorFilter> = (0..n)
                .map(|_| {
                    SensorFilter::Orient(Box::new(Filter::new(&Config::new(Kind::Robust).unwrap()).unwrap()))
                })
                .collect();
            let run = run_rig(rec, &mut filters, &mut Alone, true);
            let t = rec.t();
            let first = t.iter().position(|&x| x >= 10.0).unwrap();
            for (k, j) in rec.spec.joints.iter().enumerate() {
                let (tp, tc) = sim.true_axes[k];
                let turn = |v: Vec3, sign: f64| {
                    let perp = Vec3::new(0.3, 0.5, 1.0).cross(v).normalized();
                    Quat::from_axis_angle(perp, sign * guess_off.to_radians()).rotate(v)
                };
                let guess = (turn(j.axis_parent, 1.0), turn(j.axis_child, -1.0));
                for (w, len) in windows.iter().enumerate() {
                    let last = t.iter().position(|&x| x >= 10.0 + len).unwrap_or(t.len());
                    let rows = first..last;
                    let found = match j.kind {
                        JointKind::Hinge => estimate_hinge_axes(
                            &rec.sensors[j.parent].gyro[rows.clone()],
                            &rec.sensors[j.child].gyro[rows],
                            guess,
                        ),
                        JointKind::TwoDof => estimate_two_dof_axes(
                            &run.sensors[j.parent][rows.clone()],
                            &run.sensors[j.child][rows],
                            guess,
                        ),
                    }
                    .expect("finite readings");
                    let err = angle(found.axis_parent, tp).max(angle(found.axis_child, tc));
                    res[j.kind as usize][w].push((err, found.quality));
                }
            }
        }
        for (kind, per) in res.iter().enumerate() {
            for (w, v) in per.iter().enumerate() {
                if v.is_empty() {
                    continue;
                }
                let m = |f: fn(&(f64, f64)) -> f64| v.iter().map(f).sum::<f64>() / v.len() as f64;
                let x = |f: fn(&(f64, f64)) -> f64| v.iter().map(f).fold(0.0, f64::max);
                println!(
                    "| {case} | {} | {} | {:.2} / {:.2} | {:.3} / {:.3} |",
                    ["hinge", "2dof"][kind],
                    windows[w],
                    m(|p| p.0),
                    x(|p| p.0),
                    m(|p| p.1),
                    x(|p| p.1)
                );
            }
        }
    }
}
