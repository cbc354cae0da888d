//! Runs every filter kind, 9D and 6D, with default settings over every recording in a
//! directory and prints BROAD's scores as a Markdown table.
//!
//!     cargo run --release --bin broad_table [-- DIR]     (default ../shared/data/broad)
//!
//! 9D: magnetometer used, scored as is (BROAD's rule). 6D*: magnetometer unused, one
//! constant heading offset removed per trial (FORMAT.md). Cells: total / heading /
//! inclination RMSE in degrees; the last rows are group means (undisturbed trials 01-23,
//! disturbed 24-39, magnetically disturbed 28-36), the mean over all trials, and each
//! column's run time per sample.
//!
//! Options: `--kinds robust,madgwick` limits the columns; `--set name=value` (repeatable)
//! sets a parameter on every kind that has it.

use orient::{Config, Filter, Kind, Quat};
use orient_tools::clock;
use orient_tools::eval::{remove_heading_offset, score, Recording, Scores};
use std::path::PathBuf;
use std::time::Instant;

fn run(config: &Config, rec: &Recording, six_d: bool) -> Scores {
    let mut f = Filter::new(config).expect("filter");
    let mut est: Vec<Quat> = Vec::with_capacity(rec.len());
    for mut s in rec.samples() {
        if six_d {
            s.mag = None;
        }
        let _ = f.update(&s);
        // Config::new defaults to ENU, the frame BROAD scores.
        est.push(f.quaternion());
    }
    if six_d {
        remove_heading_offset(&mut est, &rec.truth, &rec.movement);
    }
    score(&est, &rec.truth, &rec.movement)
}

fn trial_number(name: &str) -> u32 {
    name.split('_').next().and_then(|n| n.parse().ok()).unwrap_or(0)
}

fn main() {
    let mut dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/broad"));
    let mut kinds: Vec<Kind> = Kind::ALL.to_vec();
    let mut sets: Vec<(String, f64)> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--kinds" => {
                let list = args.next().expect("--kinds needs a list");
                kinds = list
                    .split(',')
                    .map(|n| Kind::from_name(n).unwrap_or_else(|| panic!("no kind {n}")))
                    .collect();
            }
            "--set" => {
                let kv = args.next().expect("--set needs name=value");
                let (k, v) = kv.split_once('=').expect("--set needs name=value");
                sets.push((k.to_string(), v.parse().expect("a number")));
            }
            _ => dir = PathBuf::from(a),
        }
    }
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "csv"))
        .collect();
    files.sort();
    let start = Instant::now();
    let recordings: Vec<(String, Recording)> = files
        .iter()
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            let rec = Recording::read(p, true).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            (name, rec)
        })
        .collect();
    let columns: Vec<(Kind, bool)> = kinds.iter().flat_map(|k| [(*k, false), (*k, true)]).collect();
    let configs: Vec<Config> = kinds
        .iter()
        .map(|k| {
            let mut c = Config::new(*k).expect("kind");
            for (name, value) in &sets {
                if let Some(r) = c.set(name, *value) {
                    r.unwrap_or_else(|e| panic!("{}: {name}: {e}", k.name()));
                }
            }
            c
        })
        .collect();
    let mut table: Vec<Vec<Scores>> = Vec::new();
    let mut seconds = vec![0.0; columns.len()];
    for (_, rec) in &recordings {
        let mut row = Vec::new();
        for (c, (_, six)) in columns.iter().enumerate() {
            let (scores, t) = clock::time(|| run(&configs[c / 2], rec, *six));
            row.push(scores);
            seconds[c] += t.as_secs_f64();
        }
        table.push(row);
    }
    let elapsed = start.elapsed();

    print!("| trial |");
    for (k, six) in &columns {
        print!(" {} {} |", k.name(), if *six { "6D*" } else { "9D" });
    }
    println!();
    println!("|---|{}", "---|".repeat(columns.len()));
    let cell = |s: &Scores| format!(" {:.2} / {:.2} / {:.2} |", s.total, s.heading, s.inclination);
    for ((name, _), row) in recordings.iter().zip(&table) {
        print!("| {} |", name.split('_').next().unwrap_or(name));
        for s in row {
            print!("{}", cell(s));
        }
        println!();
    }
    type Group = (&'static str, fn(u32) -> bool);
    let groups: [Group; 4] = [
        ("undisturbed", |n| n <= 23),
        ("disturbed", |n| n >= 24),
        ("magnetic", |n| (28..=36).contains(&n)),
        ("mean", |_| true),
    ];
    for (label, keep) in groups {
        let rows: Vec<&Vec<Scores>> = recordings
            .iter()
            .zip(&table)
            .filter(|((name, _), _)| keep(trial_number(name)))
            .map(|(_, r)| r)
            .collect();
        if rows.is_empty() {
            continue;
        }
        print!("| {label} |");
        for c in 0..columns.len() {
            let n = rows.len() as f64;
            let total = rows.iter().map(|r| r[c].total).sum::<f64>() / n;
            let heading = rows.iter().map(|r| r[c].heading).sum::<f64>() / n;
            let incl = rows.iter().map(|r| r[c].inclination).sum::<f64>() / n;
            print!(" {total:.2} / {heading:.2} / {incl:.2} |");
        }
        println!();
    }
    let samples: usize = recordings.iter().map(|(_, r)| r.len()).sum();
    print!("| ns/sample |");
    for t in &seconds {
        print!(" {:.0} |", t * 1e9 / samples as f64);
    }
    println!();
    println!(
        "\nCells: total / heading / inclination RMSE (deg). ns/sample: thread CPU time on {}, \
         filter, scoring and copying included.\n{} trials, {samples} samples, {} runs in {:.1} s (reading included)",
        clock::cpu_model(),
        recordings.len(),
        columns.len() * recordings.len(),
        elapsed.as_secs_f64()
    );
}
