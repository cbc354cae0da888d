//! Replays a recording through a filter and scores it against ground truth.
//!
//! ```text
//! cargo run --release --bin replay -- --filter NAME[,NAME...] [--offline] [--no-mag]
//!     [--frame enu|ned|nwu] [--set KEY=VALUE]... [--out OUT.csv] [--svg OUT.svg] INPUT.csv
//! ```
//!
//! - NAME: madgwick, mahony, complementary, ekf, gmvdk or robust; several (comma-separated
//!   or `--filter` repeated) replay the same recording through each in turn.
//! - `--offline` smooths the whole recording instead of filtering it sample by sample
//!   (`orient::offline::smooth_into`, C `orient_smooth_arrays`): every output uses the
//!   samples before and after it. Without `--filter` it runs the offline defaults
//!   (`offline::config()`: the robust kind with `tau_mag` 27 s), and `--filter robust`
//!   starts from them too (`--set tau_mag=9` gives the causal default back); the other
//!   kinds start from their own defaults. A sample the smoother refuses (one that a
//!   forward run of a new filter refuses) ends the tool with status 2, naming it: the
//!   smoother takes only recordings it accepts whole. OUT has `t,qw,qx,qy,qz` only (the
//!   smoother reports no diagnostics) and the SVG no lanes.
//! - `--no-mag` ignores the magnetometer columns (6D).
//! - `--set` changes a parameter by name (see the filter's parameter table); repeatable;
//!   with several filters it applies to each that has the parameter.
//! - INPUT: CSV as in shared/data/FORMAT.md (header row, columns by name, extra columns
//!   ignored); dt from consecutive `t`.
//! - OUT (one filter only): `t,qw,qx,qy,qz` followed by the filter's diagnostics (`bias_x,bias_y,bias_z`,
//!   `rest`, `alpha,mu_ka,mu_km,mu_k`, `rate_*`, `p0..p9`, as the kind offers them; NaN
//!   where a value is absent), one row per input row, quaternion in the chosen frame.
//! - With ground truth (`quat_*`, `movement`), prints BROAD's total / heading /
//!   inclination RMSE in degrees over `movement == 1` rows; with `--no-mag` also after
//!   removing one constant heading offset.
//! - SVG (needs ground truth): the total, heading and inclination error over time of
//!   every filter replayed, and a lane per filter with bands where it reported rest, a
//!   magnetometer it did not use (magnetic disturbance), an accelerometer it did not use
//!   (acceleration rejection) or a gap (see `replay/plot.rs`); with `--no-mag` the
//!   error after removing the heading offset.
//! - Standard output closed early (`| head`): the tool stops quietly, status 0.
//!
//! Rig mode (`--rig DIR/rig.json --out-dir OUT ...`, RIG-FORMAT.md): one filter per
//! sensor, outputs per sensor and joint, the rig scores; see `replay/rig.rs`.
//!
//! Exit status: 0 on success, 2 on bad arguments or malformed input (the message names
//! the line and column), 1 when writing the output fails.

mod plot;

use orient::filters::{diag, Diagnostics};
use orient::{Config, Filter, Frame, Kind, Quat};
use orient_tools::clock;
use orient_tools::eval::{remove_heading_offset, score, Recording, Scores};
use std::io::Write;
use std::path::PathBuf;
use std::process::exit;

const USAGE: &str = "usage: replay --filter NAME[,NAME...] [--offline] [--no-mag] [--frame enu|ned|nwu] \
                     [--set KEY=VALUE]... [--out OUT.csv] [--svg OUT.svg] INPUT.csv";

/// Both modes' usage: this file's and the rig mode's (`rig::USAGE`).
fn usage() -> String {
    format!("{USAGE}\n   or: {}", rig::USAGE.trim_start_matches("usage: "))
}

/// println! that stops the tool quietly (status 0) when standard output was closed, as
/// `| head` does, instead of panicking on the broken pipe; other write errors are status 1.
macro_rules! say {
    ($($arg:tt)*) => {
        if let Err(e) = writeln!(std::io::stdout().lock(), $($arg)*) {
            if e.kind() != std::io::ErrorKind::BrokenPipe {
                eprintln!("replay: cannot write to standard output: {e}");
                exit(1);
            }
            exit(0);
        }
    };
}

mod rig;

struct Args {
    kinds: Vec<Kind>,
    offline: bool,
    no_mag: bool,
    frame: Frame,
    sets: Vec<(String, f64)>,
    out: Option<PathBuf>,
    svg: Option<PathBuf>,
    input: PathBuf,
}

fn fail(message: impl std::fmt::Display) -> ! {
    eprintln!("replay: {message}");
    exit(2)
}

fn parse_args() -> Args {
    let mut kinds = Vec::new();
    let mut no_mag = false;
    let mut offline = false;
    let mut frame = Frame::Enu;
    let mut sets = Vec::new();
    let mut out = None;
    let mut svg = None;
    let mut input = None;
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value =
            |name: &str| it.next().unwrap_or_else(|| fail(format!("{name} needs a value\n{}", usage())));
        match arg.as_str() {
            "--filter" => {
                let names: Vec<&str> = Kind::ALL.iter().map(|k| k.name()).collect();
                for v in value("--filter").split(',') {
                    kinds.push(Kind::from_name(v.trim()).unwrap_or_else(|| {
                        fail(format!("unknown filter '{v}' (one of: {})", names.join(", ")))
                    }));
                }
            }
            "--no-mag" => no_mag = true,
            "--offline" => offline = true,
            "--frame" => {
                let v = value("--frame");
                frame = Frame::from_name(&v)
                    .unwrap_or_else(|| fail(format!("unknown frame '{v}' (enu, ned, nwu)")));
            }
            "--set" => {
                let v = value("--set");
                let (key, val) =
                    v.split_once('=').unwrap_or_else(|| fail(format!("--set wants KEY=VALUE, got '{v}'")));
                let val: f64 = val
                    .trim()
                    .parse()
                    .unwrap_or_else(|_| fail(format!("--set {key}: '{val}' is not a number")));
                sets.push((key.trim().to_string(), val));
            }
            "--out" => out = Some(PathBuf::from(value("--out"))),
            "--svg" => svg = Some(PathBuf::from(value("--svg"))),
            "-h" | "--help" => {
                say!("{}", usage());
                exit(0)
            }
            s if s.starts_with("--") => fail(format!("unknown option '{s}'\n{}", usage())),
            _ if input.is_some() => fail(format!("more than one input file\n{}", usage())),
            _ => input = Some(PathBuf::from(arg)),
        }
    }
    if kinds.is_empty() && offline {
        kinds.push(Kind::Robust);
    }
    if kinds.is_empty() {
        fail(format!("--filter is required (or --offline, which defaults to robust)\n{}", usage()));
    }
    if out.is_some() && kinds.len() > 1 {
        fail("--out takes one filter (its columns depend on the kind)");
    }
    Args {
        kinds,
        offline,
        no_mag,
        frame,
        sets,
        out,
        svg,
        input: input.unwrap_or_else(|| fail(format!("no input file\n{}", usage()))),
    }
}

/// The extra output columns a kind offers: its diagnostics.
fn extra_columns(present: u32) -> Vec<String> {
    let mut c: Vec<String> = Vec::new();
    if present & diag::GYRO_BIAS != 0 {
        c.extend(["bias_x", "bias_y", "bias_z"].map(String::from));
    }
    if present & diag::REST != 0 {
        c.push("rest".into());
    }
    for (bit, name) in
        [(diag::ALPHA, "alpha"), (diag::MU_KA, "mu_ka"), (diag::MU_KM, "mu_km"), (diag::MU_K, "mu_k")]
    {
        if present & bit != 0 {
            c.push(name.into());
        }
    }
    if present & diag::RATE != 0 {
        c.extend(["rate_x", "rate_y", "rate_z"].map(String::from));
    }
    if present & diag::COVARIANCE != 0 {
        c.extend((0..10).map(|i| format!("p{i}")));
    }
    c
}

/// The values of [`extra_columns`] for one sample (NaN where a value is absent now).
fn extra_values(d: &Diagnostics, present: u32) -> Vec<f64> {
    let mut v = Vec::new();
    if present & diag::GYRO_BIAS != 0 {
        v.extend([d.gyro_bias.x, d.gyro_bias.y, d.gyro_bias.z]);
    }
    if present & diag::REST != 0 {
        v.push(d.rest);
    }
    for (bit, x) in
        [(diag::ALPHA, d.alpha), (diag::MU_KA, d.mu_ka), (diag::MU_KM, d.mu_km), (diag::MU_K, d.mu_k)]
    {
        if present & bit != 0 {
            v.push(x);
        }
    }
    if present & diag::RATE != 0 {
        v.extend([d.rate.x, d.rate.y, d.rate.z]);
    }
    if present & diag::COVARIANCE != 0 {
        v.extend(d.covariance);
    }
    v
}

fn print_scores(label: &str, s: &Scores) {
    say!(
        "{label:<28} total {:6.2}  heading {:6.2}  inclination {:6.2}   ({} samples)",
        s.total,
        s.heading,
        s.inclination,
        s.count
    );
}

/// One filter's run over the recording.
struct Run {
    /// The kind's name, with " offline" for a smoothed run.
    label: String,
    /// The estimates in ENU (what BROAD scores).
    enu: Vec<Quat>,
    /// orient_filter_flags after each sample (0 for a rejected one) and the diagnostics'
    /// rest flag (false where the kind has none); None for a smoothed run.
    reports: Option<(Vec<u32>, Vec<bool>)>,
}

fn configure(kind: Kind, args: &Args) -> Config {
    let mut config = if args.offline && kind == Kind::Robust {
        orient::offline::config()
    } else {
        Config::new(kind).unwrap_or_else(|e| fail(e))
    };
    config.frame = args.frame;
    for (key, value) in &args.sets {
        match config.set(key, *value) {
            None if args.kinds.len() > 1 => {}
            None => {
                let names: Vec<&str> = kind.params().map(|p| p.name).collect();
                fail(format!("{} has no parameter '{key}' (it has: {})", kind.name(), names.join(", ")))
            }
            Some(Err(e)) => fail(format!("--set {key}={value}: {e}")),
            Some(Ok(())) => {}
        }
    }
    config
}

fn main() {
    let raw: Vec<String> = std::env::args().skip(1).collect();
    if raw.iter().any(|a| a == "--rig") {
        rig::main(raw);
        return;
    }
    let args = parse_args();
    if args.kinds.len() > 1 {
        for (key, _) in &args.sets {
            if !args.kinds.iter().any(|k| k.param_by_name(key).is_some()) {
                fail(format!("none of the filters has a parameter '{key}'"));
            }
        }
    }
    let configs: Vec<Config> = args.kinds.iter().map(|k| configure(*k, &args)).collect();
    let rec = Recording::read(&args.input, !args.no_mag)
        .unwrap_or_else(|e| fail(format!("{}: {e}", args.input.display())));
    if args.svg.is_some() && !rec.has_truth() {
        fail(format!("--svg: {} has no ground truth columns (quat_*, movement)", args.input.display()));
    }
    let samples = rec.samples();
    let mut runs = Vec::new();
    for (i, config) in configs.iter().enumerate() {
        if i > 0 {
            say!();
        }
        runs.push(if args.offline {
            smooth(&args, config, &rec, &samples)
        } else {
            replay(&args, config, &rec, &samples)
        });
    }
    if let Some(path) = &args.svg {
        let series: Vec<plot::Series> = runs
            .iter()
            .map(|r| plot::Series {
                label: &r.label,
                estimates: &r.enu,
                reports: r.reports.as_ref().map(|(flags, rest)| plot::Reports { flags, rest }),
            })
            .collect();
        let title = format!(
            "{} ({})",
            args.input.file_name().map_or(String::new(), |n| n.to_string_lossy().into_owned()),
            if args.no_mag { "6D" } else { "9D" }
        );
        if let Err(e) = plot::write_svg(path, &title, &rec, &series, !args.no_mag) {
            eprintln!("replay: cannot write {}: {e}", path.display());
            exit(1);
        }
        say!("svg: {}", path.display());
    }
}

fn replay(args: &Args, config: &Config, rec: &Recording, samples: &[orient::Sample]) -> Run {
    let kind = config.kind();
    let mut filter = Filter::new(config).unwrap_or_else(|e| fail(e));
    let mut estimates: Vec<Quat> = Vec::with_capacity(samples.len());
    let mut sample_flags: Vec<u32> = Vec::with_capacity(samples.len());
    let mut rest: Vec<bool> = Vec::with_capacity(samples.len());
    let columns = extra_columns(filter.diagnostic_fields());
    let mut extras: Vec<Vec<f64>> = Vec::with_capacity(if args.out.is_some() { samples.len() } else { 0 });
    let mut rejected = 0usize;
    let mut first_rejection = None;
    let start = clock::thread_cpu();
    for (i, s) in samples.iter().enumerate() {
        let accepted = match filter.update(s) {
            Ok(()) => true,
            Err(e) => {
                rejected += 1;
                first_rejection.get_or_insert((i, e));
                false
            }
        };
        estimates.push(filter.quaternion());
        sample_flags.push(if accepted { filter.flags() } else { 0 });
        if args.svg.is_some() {
            rest.push(accepted && filter.diagnostics().rest == 1.0);
        }
        if args.out.is_some() {
            extras.push(extra_values(&filter.diagnostics(), filter.diagnostic_fields()));
        }
    }
    let elapsed = clock::thread_cpu().saturating_sub(start);

    if let Some(path) = &args.out {
        let write = || -> std::io::Result<()> {
            let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
            let header: String = columns.iter().map(|c| format!(",{c}")).collect();
            writeln!(w, "t,qw,qx,qy,qz{header}")?;
            for ((t, q), x) in rec.t.iter().zip(&estimates).zip(&extras) {
                let values: String = x.iter().map(|v| format!(",{v}")).collect();
                writeln!(w, "{t},{},{},{},{}{values}", q.w, q.x, q.y, q.z)?;
            }
            w.flush()
        };
        if let Err(e) = write() {
            eprintln!("replay: cannot write {}: {e}", path.display());
            exit(1);
        }
    }

    let dims = dims(args);
    say!(
        "{} {dims}, frame {}, {} samples from {} in {:.1} ms of CPU time ({:.0} ns/sample), {rejected} rejected",
        kind.name(),
        args.frame.name(),
        samples.len(),
        args.input.display(),
        elapsed.as_secs_f64() * 1e3,
        elapsed.as_secs_f64() * 1e9 / samples.len().max(1) as f64,
    );
    if let Some((i, e)) = first_rejection {
        say!("first rejected sample: row {} (line {}): {e}", i, i + 2);
    }
    let enu = score_and_print(args, rec, &estimates);
    Run { label: kind.name().to_string(), enu, reports: Some((sample_flags, rest)) }
}

fn dims(args: &Args) -> &'static str {
    if args.no_mag {
        "6D"
    } else {
        "9D"
    }
}

/// The estimates turned to ENU (what BROAD scores: q_ES), scored and printed when the
/// recording has ground truth; with `--no-mag`, returned after removing the heading
/// offset, as scored.
fn score_and_print(args: &Args, rec: &Recording, estimates: &[Quat]) -> Vec<Quat> {
    let to_enu = args.frame.rotation_to(Frame::Enu);
    let mut enu: Vec<Quat> = estimates.iter().map(|q| to_enu.map_or(*q, |c| c * *q)).collect();
    if !rec.has_truth() {
        say!("no ground truth columns (quat_*, movement): nothing to score");
        return enu;
    }
    print_scores("BROAD RMSE [deg]:", &score(&enu, &rec.truth, &rec.movement));
    if args.no_mag {
        let offset = remove_heading_offset(&mut enu, &rec.truth, &rec.movement);
        let label = format!("heading offset {:+.1} deg removed:", offset.to_degrees());
        print_scores(&label, &score(&enu, &rec.truth, &rec.movement));
    }
    enu
}

/// `--offline`: the whole recording smoothed at once (forward, backward, forward again,
/// the two directions fused per sample).
fn smooth(args: &Args, config: &Config, rec: &Recording, samples: &[orient::Sample]) -> Run {
    let kind = config.kind();
    let mut estimates = vec![Quat::IDENTITY; samples.len()];
    let start = clock::thread_cpu();
    let result = orient::offline::smooth_into(config, samples, &mut estimates[..]);
    let elapsed = clock::thread_cpu().saturating_sub(start);
    match result {
        Ok(()) => {}
        Err(orient::offline::SmoothError::Sample { index, error }) => fail(format!(
            "--offline: {}: row {index} (line {}) is refused: {error}; the smoother takes only \
             recordings that a forward run accepts whole",
            args.input.display(),
            index + 2
        )),
        Err(e) => {
            eprintln!("replay: --offline: {e}");
            exit(1)
        }
    }
    if let Some(path) = &args.out {
        let write = || -> std::io::Result<()> {
            let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
            writeln!(w, "t,qw,qx,qy,qz")?;
            for (t, q) in rec.t.iter().zip(&estimates) {
                writeln!(w, "{t},{},{},{},{}", q.w, q.x, q.y, q.z)?;
            }
            w.flush()
        };
        if let Err(e) = write() {
            eprintln!("replay: cannot write {}: {e}", path.display());
            exit(1);
        }
    }
    let tau_mag = kind
        .param_by_name("tau_mag")
        .and_then(|p| config.param(p.id).ok())
        .map_or(String::new(), |v| format!(", tau_mag {v} s"));
    say!(
        "{} offline {}, frame {}{tau_mag}, {} samples from {} smoothed in {:.1} ms of CPU time ({:.0} ns/sample), \
         at most {} bytes allocated",
        kind.name(),
        dims(args),
        args.frame.name(),
        samples.len(),
        args.input.display(),
        elapsed.as_secs_f64() * 1e3,
        elapsed.as_secs_f64() * 1e9 / samples.len().max(1) as f64,
        orient::offline::memory(samples.len()).unwrap_or(usize::MAX),
    );
    let enu = score_and_print(args, rec, &estimates);
    Run { label: format!("{} offline", kind.name()), enu, reports: None }
}
