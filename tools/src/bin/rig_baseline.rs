//! The baseline of issue 42: every sensor alone (one filter per sensor, headings aligned
//! once at the reference pose), on the issue's five simulated glove cases, over several
//! seeds. Prints the table in the issue's form (RMSE over all joints, degrees, mean over
//! seeds) and beside it the worst joint and the last minute (RIG-FORMAT.md's scores).
//!
//! ```text
//! cargo run --release -p orient-tools --bin rig_baseline [-- --seeds N|A-B] [--minutes M] [--rest S] [--6d]
//!     [--set KEY=VALUE].. [--own-case NAME] [--bias-drift F]
//! ```
//!
//! - `--seeds N` (default 3): seeds 1..=N per case, or `--seeds A-B` seeds A..=B;
//!   `--minutes M` (default 10); `--rest S` the mean still time of the rests (the
//!   simulator's default unless given); `--bias-drift F` the share of each case's bias
//!   bound that the biases drift (the simulator's 0.2 unless given; 0 for constant biases).
//! - `--6d`: only the 6D rows (robust and VQF without magnetometer); otherwise the 9D
//!   rows too (with the simulator's magnet under the desk).
//! - `--set KEY=VALUE`: a robust parameter (by its name, `bias_sigma_motion` say) for the
//!   robust rows.
//!
//! Below the tables, issue 42's item 7: each glove sensor's own 6D estimate on the 60 Hz
//! vigorous glove (`--own-case NAME`: another of the cases), one heading offset removed
//! as FORMAT.md scores BROAD, robust against VQF, with the mean over sensors and how many
//! sensors each kind leads.
//!
//! Runs in memory (`orient_tools::rigsim`, `orient_tools::rig::run_rig`); nothing is
//! written. A benchmark, not a test: it asserts nothing.

use orient::{Config, Filter, Kind};
use orient_tools::clock;
use orient_tools::eval::{self, remove_heading_offset};
use orient_tools::rig::{joint_errors, run_rig, score_rig, Alone, RigRecording, RigScores, SensorFilter};
use orient_tools::rigsim::{bias_drift_arg, seed_range, vertical_hinge_fraction, SimConfig, Simulation};

const CASES: [(&str, &str); 5] = [
    ("100hz", "100 Hz"),
    ("60hz-vigorous", "60 Hz, vigorous"),
    ("palm-sideways", "palm sideways"),
    ("bias-3dps", "bias to 3 deg/s"),
    ("axes-5deg-off", "axes 5 deg off"),
];

#[derive(Clone, Copy)]
enum Row {
    Robust6,
    Vqf6,
    Robust9,
    Vqf9,
}

impl Row {
    fn label(self) -> &'static str {
        match self {
            Row::Robust6 => "robust 6D",
            Row::Vqf6 => "VQF 6D",
            Row::Robust9 => "robust 9D (a magnet under the desk)",
            Row::Vqf9 => "VQF 9D",
        }
    }
    fn mag(self) -> bool {
        matches!(self, Row::Robust9 | Row::Vqf9)
    }
    fn filters(self, n: usize, dt: f64, robust: &Config) -> Vec<SensorFilter> {
        (0..n)
            .map(|_| match self {
                Row::Robust6 | Row::Robust9 => SensorFilter::Orient(Box::new(Filter::new(robust).unwrap())),
                Row::Vqf6 | Row::Vqf9 => SensorFilter::vqf(dt, self.mag()),
            })
            .collect()
    }
}

/// The rig scores, and per sensor BROAD's total and inclination RMSE (deg) after removing
/// one heading offset (FORMAT.md "6D with heading removed"), rows t >= 10 s.
fn score(rec: &RigRecording, row: Row, robust: &Config) -> (RigScores, Vec<(f64, f64)>) {
    let mut rec6;
    let rec = if row.mag() {
        rec
    } else {
        rec6 = rec.clone();
        for s in &mut rec6.sensors {
            s.mag.clear();
        }
        &rec6
    };
    let mut filters = row.filters(rec.spec.sensors.len(), 1.0 / rec.spec.rate_hz, robust);
    let run = run_rig(rec, &mut filters, &mut Alone, true);
    let truth: Vec<&[orient::Quat]> = rec.sensors.iter().map(|r| r.truth.as_slice()).collect();
    let own = run
        .sensors
        .iter()
        .zip(&rec.sensors)
        .map(|(est, r)| {
            let mut est = est.clone();
            remove_heading_offset(&mut est, &r.truth, &r.movement);
            let s = eval::score(&est, &r.truth, &r.movement);
            (s.total, s.inclination)
        })
        .collect();
    (score_rig(&rec.spec, rec.t(), &joint_errors(&rec.spec, &run.sensors, &truth)), own)
}

fn main() {
    let (mut first, mut seeds) = (1u64, 3u64);
    let mut minutes = 10.0;
    let mut only6 = false;
    let mut own_case = "60hz-vigorous";
    let mut rest = None;
    let mut drift = None;
    let mut robust = Config::new(Kind::Robust).unwrap();
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--seeds" => {
                let v = it.next().expect("--seeds N or A-B");
                (first, seeds) =
                    if v.contains('-') { seed_range(&v) } else { (1, v.parse().expect("--seeds N")) };
                assert!(seeds >= 1, "--seeds N: at least one seed");
                assert!(first <= seeds, "--seeds A-B with A <= B");
            }
            "--minutes" => minutes = it.next().and_then(|v| v.parse().ok()).expect("--minutes M"),
            "--rest" => rest = Some(it.next().and_then(|v| v.parse().ok()).expect("--rest S")),
            "--bias-drift" => {
                let v = it.next().expect("--bias-drift F");
                drift = Some(bias_drift_arg(&v).unwrap_or_else(|e| panic!("{e}")));
            }
            "--6d" => only6 = true,
            "--own-case" => {
                let v = it.next().expect("--own-case NAME");
                own_case = CASES.iter().map(|c| c.0).find(|c| *c == v).expect("--own-case: one of the cases");
            }
            "--set" => {
                let kv = it.next().expect("--set KEY=VALUE");
                let (k, v) = kv.split_once('=').expect("--set KEY=VALUE");
                let v: f64 = v.parse().expect("--set KEY=VALUE: a number");
                robust.set(k, v).expect("a robust parameter").expect("a valid value");
            }
            _ => {
                eprintln!(
                    "usage: rig_baseline [--seeds N|A-B] [--minutes M] [--rest S] [--6d] [--set KEY=VALUE].. \
                     [--own-case NAME] [--bias-drift F]"
                );
                std::process::exit(2);
            }
        }
    }
    let rows: Vec<Row> = if only6 {
        vec![Row::Robust6, Row::Vqf6]
    } else {
        vec![Row::Robust6, Row::Vqf6, Row::Robust9, Row::Vqf9]
    };
    // [row][case] -> per-seed scores.
    let mut results: Vec<Vec<Vec<RigScores>>> = vec![vec![Vec::new(); CASES.len()]; rows.len()];
    let mut vertical = vec![0.0; CASES.len()];
    let n_seeds = (seeds - first + 1) as f64;
    // Issue 42 item 7: per sensor, heading offset removed, on `own_case`'s glove.
    let mut own_names: Vec<String> = Vec::new();
    let mut own: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    let (mut sim_time, mut filter_time) = (0.0, 0.0);
    for (c, (preset, _)) in CASES.iter().enumerate() {
        for seed in first..=seeds {
            let mut config = SimConfig::preset(preset, seed).unwrap();
            config.duration_s = minutes * 60.0;
            config.rest_s = rest.unwrap_or(config.rest_s);
            config.bias_drift = drift.unwrap_or(config.bias_drift);
            let (sim, t) = clock::time(|| Simulation::new(config).run());
            sim_time += t.as_secs_f64();
            vertical[c] += vertical_hinge_fraction(&sim, 60.0) / n_seeds;
            let t0 = clock::thread_cpu();
            for (r, row) in rows.iter().enumerate() {
                let (s, per_sensor) = score(&sim.recording, *row, &robust);
                if *preset == own_case && r < 2 {
                    own_names = sim.recording.spec.sensors.iter().map(|s| s.name.clone()).collect();
                    own[r].resize(per_sensor.len(), (0.0, 0.0));
                    for (sum, (t, i)) in own[r].iter_mut().zip(&per_sensor) {
                        sum.0 += t / n_seeds;
                        sum.1 += i / n_seeds;
                    }
                }
                eprintln!(
                    "{preset:<14} seed {seed}  {:<36} all {:6.2}  worst {:6.2} ({})  last minute {:6.2}",
                    row.label(),
                    s.all,
                    s.worst.1,
                    s.worst.0,
                    s.last_minute
                );
                results[r][c].push(s);
            }
            filter_time += clock::thread_cpu().saturating_sub(t0).as_secs_f64();
        }
    }
    let mean = |v: &[RigScores], f: fn(&RigScores) -> f64| v.iter().map(f).sum::<f64>() / v.len() as f64;
    let spread = |v: &[RigScores]| {
        let (lo, hi) = v.iter().fold((f64::MAX, f64::MIN), |(a, b), s| (a.min(s.all), b.max(s.all)));
        format!("{lo:.1}-{hi:.1}")
    };
    println!(
        "\nEvery sensor alone, headings aligned once at the reference pose; RMSE of each child \
         segment relative to its parent over all joints, deg; mean of seeds {first}..={seeds}, {minutes} min each, rests of {} s, biases drifting by {} of their bound.\n",
        rest.unwrap_or(SimConfig::glove(0).rest_s),
        drift.unwrap_or(SimConfig::glove(0).bias_drift)
    );
    let head: Vec<String> = CASES
        .iter()
        .enumerate()
        .map(|(c, (_, name))| {
            if c == 2 {
                format!("{name} (PIP axes > 60 deg from horizontal {:.0} % of the time)", 100.0 * vertical[c])
            } else {
                name.to_string()
            }
        })
        .collect();
    println!("| every sensor alone | {} |", head.join(" | "));
    println!("|---|{}", "---|".repeat(CASES.len()));
    for (r, row) in rows.iter().enumerate() {
        let cells: Vec<String> = results[r].iter().map(|v| format!("{:.1}", mean(v, |s| s.all))).collect();
        println!("| {} | {} |", row.label(), cells.join(" | "));
    }
    println!(
        "\nSpread over seeds (min-max of the RMSE over all joints), worst joint and last minute (means):\n"
    );
    println!("| | {} |", CASES.map(|c| c.1).join(" | "));
    println!("|---|{}", "---|".repeat(CASES.len()));
    for (r, row) in rows.iter().enumerate() {
        let cells: Vec<String> = results[r]
            .iter()
            .map(|v| {
                format!("{} / {:.1} / {:.1}", spread(v), mean(v, |s| s.worst.1), mean(v, |s| s.last_minute))
            })
            .collect();
        println!("| {} | {} |", row.label(), cells.join(" | "));
    }
    println!(
        "\nPer sensor, 6D, one heading offset removed (FORMAT.md), {own_case}, total / inclination RMSE \
         [deg], mean of seeds (issue, 60 Hz vigorous: hand 4.66 vs VQF 3.34, index proximal 4.02 vs 2.28, \
         index middle 1.38 vs 0.82; inclination 0.4 against 0.33-0.36):\n"
    );
    println!("| sensor | {} | {} |", rows[0].label(), rows[1].label());
    println!("|---|---|---|");
    for (k, name) in own_names.iter().enumerate() {
        let ((tr, ir), (tv, iv)) = (own[0][k], own[1][k]);
        println!("| {name} | {tr:.2} / {ir:.2} | {tv:.2} / {iv:.2} |");
    }
    let n = own_names.len().max(1) as f64;
    let mean_of = |r: usize| own[r].iter().map(|v| v.0).sum::<f64>() / n;
    let leads = |r: usize| own[r].iter().zip(&own[1 - r]).filter(|(a, b)| a.0 < b.0).count();
    println!(
        "| mean (robust leads on {}, VQF on {} of {}) | {:.2} | {:.2} |",
        leads(0),
        leads(1),
        own_names.len(),
        mean_of(0),
        mean_of(1)
    );
    println!(
        "\nhinge axes > 60 deg from horizontal: {} % of the time (per case); thread CPU time on {}: \
         simulation {sim_time:.1} s, filters and scoring {filter_time:.1} s",
        vertical.iter().map(|v| format!("{:.0}", 100.0 * v)).collect::<Vec<_>>().join(" / "),
        clock::cpu_model()
    );
}
