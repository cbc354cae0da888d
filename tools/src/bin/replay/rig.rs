//! `replay --rig`: a rig recording (RIG-FORMAT.md) through one filter per sensor.
//!
//! ```text
//! replay --rig DIR/rig.json --out-dir OUT [--no-mag] [--kind KIND] [--set KEY=VALUE]...
//!     [--joint-set KEY=VALUE]... [--no-align] [--no-joints] [--svg FILE]
//! ```
//!
//! - KIND: one of orient's kinds (default robust), or `vqf` (vqf-rs, its defaults) to
//!   compare; every sensor runs its own filter, mounting from rig.json.
//! - Headings are aligned once, at the last row of the reference pose (every segment
//!   turned to the segments' mean heading, `Filter::align_rig_heading`), unless
//!   `--no-align` or the description has no reference pose. Without the alignment the
//!   joints start with the relative headings unknown (`heading_std0` π, unless
//!   `--joint-set` gives it): each joint then finds its heading from the motion within
//!   about a minute (a 100 Hz glove without its reference pose: 2.07 deg over all
//!   joints, 0.75 over the last minute, against 29.5 and 5.8 at the default 1 deg). Rows
//!   before the alignment run so too, and at the alignment the joints start over with
//!   their own `heading_std0`: a pose later in the recording leaves no row without
//!   joints. A pose where a sensor has no orientation (no valid reading yet) aligns
//!   nothing; replay says so, and the joints go on finding the headings from the motion.
//! - The joints (`orient::joints`, default tuning, `--joint-set` changes a parameter of
//!   `orient::joints::JOINT_PARAMS` by name; repeatable) then hold every child to its parent:
//!   each child's heading relative to its parent from the joint constraints, from the
//!   first row. The joints run on 6D estimates: every
//!   magnetometer is left out, and the rig's common heading is the reference pose's (the
//!   segments' mean at the alignment; without one, wherever the filters started), which
//!   RIG-FORMAT.md leaves free. Each sensor's
//!   filter takes the settings for joints (`Config::for_joints`) before any `--set`. A
//!   magnetometer read near a hand or a desk turns a 9D estimate faster than the joints
//!   follow (a simulated 5-minute glove with a magnet under the desk: 4.0 deg with every
//!   sensor 9D, 3.5 deg with the hand 9D and the fingers 6D, 0.9 deg all 6D). `--no-joints`:
//!   every sensor alone, with its magnetometer unless `--no-mag`.
//! - Writes `OUT/<sensor>.csv` (`t,quat_w,quat_x,quat_y,quat_z`: the sensor's
//!   orientation, sensor to earth, ENU, one row per input row, RIG-FORMAT.md's estimate)
//!   and `OUT/joints.csv` (`OUT/joints_angles.csv` if a sensor is named `joints`, and so
//!   on with more `_angles`, so that no sensor's file is overwritten): `t`
//!   and per joint its angles in degrees (`orient_tools::rig::joint_angles`): a hinge's
//!   `<joint>` about its axis, a 2-DoF joint's `<joint>_1` about `axis_parent` then
//!   `<joint>_2` about `axis_child`, right-handed about the axes as given, zero where
//!   the segments coincide (the reference pose).
//! - With truth (`quat_*`) in the sensors' files: prints the scores of RIG-FORMAT.md (RMSE
//!   over all joints' rows with t ≥ 10 s, the worst joint, the last minute) and each
//!   joint's RMSE, over the joints whose two sensors have truth (the others are named and
//!   left out); `--svg` plots each joint's error over time. A NaN cell is a missing value
//!   (FORMAT.md): a row's reading with one is left out of that sensor's sample, the rest
//!   of the sample kept; a row whose truth has one is not scored.
//!
//! The per-row loop is `orient_tools::rig::run_rig`, with the joints as its
//! `JointStage` (`orient_tools::joints`).

use super::{fail, plot};
use orient::joints::JOINT_PARAMS;
use orient::{Config, Filter, Kind};
use orient_tools::joints::{JointParams, Joints};
use orient_tools::rig::{
    joint_angles, joint_errors, reference_row, run_rig, score_rig, Alone, JointKind, RigRecording,
    SensorFilter,
};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::exit;

pub const USAGE: &str = "usage: replay --rig DIR/rig.json --out-dir OUT [--no-mag] [--kind KIND] \
                         [--set KEY=VALUE]... [--joint-set KEY=VALUE]... [--no-align] [--no-joints] \
                         [--svg FILE]";

struct Args {
    rig: PathBuf,
    out_dir: PathBuf,
    no_mag: bool,
    /// None: VQF.
    kind: Option<Kind>,
    sets: Vec<(String, f64)>,
    /// The joints' tuning: the defaults with each `--joint-set` applied.
    joint_params: JointParams,
    /// `--joint-set` gave `heading_std0`.
    heading_std0_given: bool,
    align: bool,
    joints: bool,
    svg: Option<PathBuf>,
}

fn parse(args: Vec<String>) -> Args {
    let (mut rig, mut out_dir, mut no_mag, mut kind, mut sets, mut align, mut svg) =
        (None, None, false, Some(Kind::Robust), Vec::new(), true, None);
    let mut joints = true;
    let mut joint_params = JointParams::default();
    let mut heading_std0_given = false;
    let mut it = args.into_iter();
    while let Some(arg) = it.next() {
        let mut value =
            |name: &str| it.next().unwrap_or_else(|| fail(format!("{name} needs a value\n{USAGE}")));
        match arg.as_str() {
            "--rig" => rig = Some(PathBuf::from(value("--rig"))),
            "--out-dir" => out_dir = Some(PathBuf::from(value("--out-dir"))),
            "--no-mag" => no_mag = true,
            "--no-align" => align = false,
            "--no-joints" => joints = false,
            "--kind" | "--filter" => {
                let v = value(&arg);
                kind = match v.trim() {
                    "vqf" => None,
                    name => Some(Kind::from_name(name).unwrap_or_else(|| {
                        let names: Vec<&str> = Kind::ALL.iter().map(|k| k.name()).collect();
                        fail(format!("unknown kind '{v}' (one of: {}, vqf)", names.join(", ")))
                    })),
                };
            }
            "--set" => sets.push(key_value("--set", &value("--set"))),
            "--joint-set" => {
                let (key, val) = key_value("--joint-set", &value("--joint-set"));
                heading_std0_given |= key == "heading_std0";
                match joint_params.set(&key, val) {
                    None => {
                        let names: Vec<&str> = JOINT_PARAMS.iter().map(|p| p.name).collect();
                        fail(format!(
                            "--joint-set: no joint parameter '{key}' (one of: {})",
                            names.join(", ")
                        ))
                    }
                    Some(false) => {
                        let p = JOINT_PARAMS.iter().find(|p| p.name == key).expect("set found it");
                        fail(format!("--joint-set {key}={val}: outside [{}, {}] {}", p.min, p.max, p.unit))
                    }
                    Some(true) => {}
                }
            }
            "--svg" => svg = Some(PathBuf::from(value("--svg"))),
            s => fail(format!("unknown argument '{s}' in rig mode\n{USAGE}")),
        }
    }
    Args {
        rig: rig.unwrap_or_else(|| fail(USAGE)),
        out_dir: out_dir.unwrap_or_else(|| fail(format!("--out-dir is required with --rig\n{USAGE}"))),
        no_mag,
        kind,
        sets,
        joint_params,
        heading_std0_given,
        align,
        joints,
        svg,
    }
}

/// `KEY=VALUE` of `option`, the value a number.
fn key_value(option: &str, v: &str) -> (String, f64) {
    let (key, val) =
        v.split_once('=').unwrap_or_else(|| fail(format!("{option} wants KEY=VALUE, got '{v}'")));
    let val: f64 =
        val.trim().parse().unwrap_or_else(|_| fail(format!("{option} {key}: '{val}' is not a number")));
    (key.trim().to_string(), val)
}

fn write_csv(path: &Path, header: &str, rows: impl Iterator<Item = String>) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(w, "{header}")?;
    for r in rows {
        writeln!(w, "{r}")?;
    }
    w.flush()
}

pub fn main(args: Vec<String>) {
    let args = parse(args);
    // With joints the rig runs 6D (see the module doc).
    let with_mag = !args.no_mag && !args.joints;
    let rec = RigRecording::read(&args.rig, with_mag).unwrap_or_else(|e| fail(e));
    let spec = &rec.spec;
    let has_truth: Vec<bool> = rec.sensors.iter().map(|r| !r.truth.is_empty()).collect();
    // A joint is scored where both its sensors' files have truth.
    let scored: Vec<bool> = spec.joints.iter().map(|j| has_truth[j.parent] && has_truth[j.child]).collect();
    if args.svg.is_some() && !scored.contains(&true) {
        fail("--svg: no truth to plot (no joint has quat_* columns in both its sensors' files)");
    }
    // VQF takes one sampling period: the recording's median step (a gap does not move
    // it), which `rate_hz` only names.
    let t = rec.t();
    let mut steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).filter(|d| *d > 0.0).collect();
    steps.sort_by(f64::total_cmp);
    let dt = steps.get(steps.len() / 2).copied().unwrap_or(1.0 / spec.rate_hz);
    let mut filters: Vec<SensorFilter> = (0..spec.sensors.len())
        .map(|_| match args.kind {
            None => SensorFilter::vqf(dt, with_mag),
            Some(kind) => {
                let mut config = Config::new(kind).unwrap_or_else(|e| fail(e));
                if args.joints {
                    config.for_joints();
                }
                for (key, value) in &args.sets {
                    match config.set(key, *value) {
                        None => fail(format!("{} has no parameter '{key}'", kind.name())),
                        Some(Err(e)) => fail(format!("--set {key}={value}: {e}")),
                        Some(Ok(())) => {}
                    }
                }
                SensorFilter::Orient(Box::new(Filter::new(&config).unwrap_or_else(|e| fail(e))))
            }
        })
        .collect();
    if args.kind.is_none() && !args.sets.is_empty() {
        fail("--set applies to orient's kinds, not to vqf");
    }
    let pose = if args.align { reference_row(spec, t) } else { None };
    let run = if args.joints && !spec.joints.is_empty() {
        let mut unknown = args.joint_params;
        if !args.heading_std0_given {
            unknown.heading_std0 = std::f64::consts::PI;
        }
        let mut stage = match pose {
            Some(_) => Joints::until_aligned(spec, unknown, args.joint_params),
            None => Joints::new(spec, 0, unknown),
        };
        run_rig(&rec, &mut filters, &mut stage, args.align)
    } else {
        run_rig(&rec, &mut filters, &mut Alone, args.align)
    };
    let stage = if args.joints { "joints" } else { "every sensor alone" };
    let names: Vec<&str> = spec.sensors.iter().map(|s| s.name.as_str()).collect();
    let mut angles_file = String::from("joints");
    // (A case-insensitive file system takes `Joints` for `joints`.)
    while names.iter().any(|n| n.eq_ignore_ascii_case(&angles_file)) {
        angles_file += "_angles";
    }

    let write = || -> std::io::Result<()> {
        std::fs::create_dir_all(&args.out_dir)?;
        for (s, q) in spec.sensors.iter().zip(&run.sensors) {
            let rows = t.iter().zip(q).map(|(t, q)| format!("{t},{},{},{},{}", q.w, q.x, q.y, q.z));
            write_csv(&args.out_dir.join(format!("{}.csv", s.name)), "t,quat_w,quat_x,quat_y,quat_z", rows)?;
        }
        let mut header = String::from("t");
        for j in &spec.joints {
            match j.kind {
                JointKind::Hinge => header += &format!(",{}", j.name),
                JointKind::TwoDof => header += &format!(",{0}_1,{0}_2", j.name),
            }
        }
        let rows = (0..t.len()).map(|i| {
            let mut line = format!("{}", t[i]);
            for j in &spec.joints {
                let (a, b) = joint_angles(spec, j, run.sensors[j.parent][i], run.sensors[j.child][i]);
                line += &format!(",{:.4}", a.to_degrees());
                if j.kind == JointKind::TwoDof {
                    line += &format!(",{:.4}", b.to_degrees());
                }
            }
            line
        });
        write_csv(&args.out_dir.join(format!("{angles_file}.csv")), &header, rows)
    };
    if let Err(e) = write() {
        eprintln!("replay: cannot write to {}: {e}", args.out_dir.display());
        exit(1);
    }

    let name = args.kind.map_or("vqf", |k| k.name());
    let dims = if with_mag { "9D" } else { "6D" };
    say!(
        "{name} {dims} ({stage}), {} sensors, {} joints, {} rows from {} in {:.1} ms of CPU time, {} rejected, headings {}",
        spec.sensors.len(),
        spec.joints.len(),
        t.len(),
        args.rig.display(),
        run.elapsed.as_secs_f64() * 1e3,
        run.rejected,
        match (run.aligned_at, pose) {
            (Some(i), _) => format!("aligned at t = {}", t[i]),
            (None, Some(i)) => format!(
                "not aligned: at the reference pose's last row (t = {}) {} had no orientation yet{}",
                t[i],
                run.unaligned.iter().map(|&s| spec.sensors[s].name.as_str()).collect::<Vec<_>>().join(", "),
                if args.joints { "; the joints find the headings from the motion" } else { "" }
            ),
            (None, None) => "not aligned".into(),
        }
    );
    if angles_file != "joints" {
        say!("joint angles: {}.csv (a sensor is named joints)", angles_file);
    }
    if !has_truth.contains(&true) {
        say!("no truth columns (quat_*): nothing to score");
        return;
    }
    let no_truth: Vec<&str> =
        spec.sensors.iter().zip(&has_truth).filter(|(_, h)| !**h).map(|(s, _)| s.name.as_str()).collect();
    let left_out: Vec<&str> =
        spec.joints.iter().zip(&scored).filter(|(_, s)| !**s).map(|(j, _)| j.name.as_str()).collect();
    if !left_out.is_empty() {
        say!("no truth in {}: not scored: {}", no_truth.join(", "), left_out.join(", "));
    }
    if !scored.contains(&true) {
        say!("no joint has truth in both its sensors' files: nothing to score");
        return;
    }
    let missing = vec![orient::Quat::new(f64::NAN, f64::NAN, f64::NAN, f64::NAN); t.len()];
    let truth: Vec<&[orient::Quat]> = rec
        .sensors
        .iter()
        .map(|r| if r.truth.is_empty() { &missing[..] } else { r.truth.as_slice() })
        .collect();
    let errors = joint_errors(spec, &run.sensors, &truth);
    let s = score_rig(spec, t, &errors);
    say!(
        "rig RMSE [deg]: all joints {:.2}  worst {:.2} ({})  last minute {:.2}   ({} rows over all joints, t >= 10 s)",
        s.all,
        s.worst.1,
        s.worst.0,
        s.last_minute,
        s.rows
    );
    for (j, e) in spec.joints.iter().zip(&s.joints) {
        let e = if e.is_nan() { "not scored".to_string() } else { format!("{e:7.2}") };
        say!("  {:<20} {:>6} {e}", j.name, j.kind.name());
    }
    if let Some(path) = &args.svg {
        // The joints scored, each with its error over time.
        let names: Vec<&str> =
            spec.joints.iter().zip(&scored).filter(|(_, s)| **s).map(|(j, _)| j.name.as_str()).collect();
        let errors: Vec<Vec<f64>> =
            errors.into_iter().zip(&scored).filter(|(_, s)| **s).map(|(e, _)| e).collect();
        let title = format!("{} ({name} {dims}, {stage})", args.rig.display());
        if let Err(e) = plot::write_rig_svg(path, &title, t, &names, &errors) {
            eprintln!("replay: cannot write {}: {e}", path.display());
            exit(1);
        }
        say!("svg: {}", path.display());
    }
}
