//! Runs every filter kind, 9D and 6D, with default settings over every recording in a
//! directory and prints BROAD's scores as a Markdown table.
//!
//!     cargo run --release --example broad_table [-- DIR]     (default ../shared/data/broad)
//!
//! 9D: magnetometer used, scored as is (BROAD's rule). 6D*: magnetometer unused, one
//! constant heading offset removed per trial (FORMAT.md). Cells: total (inclination)
//! RMSE in degrees; the last rows are group means (undisturbed trials 01-23, disturbed
//! 24-39, magnetically disturbed 28-36) and the mean over all trials.

use orient::eval::{remove_heading_offset, score, Recording, Scores};
use orient::{Config, Filter, Kind, Quat};
use std::path::PathBuf;
use std::time::Instant;

fn run(kind: Kind, rec: &Recording, six_d: bool) -> Scores {
    let mut f = Filter::new(&Config::new(kind).expect("kind")).expect("filter");
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
    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/broad")));
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
    let columns: Vec<(Kind, bool)> = Kind::ALL.iter().flat_map(|k| [(*k, false), (*k, true)]).collect();
    let mut table: Vec<Vec<Scores>> = Vec::new();
    for (_, rec) in &recordings {
        table.push(columns.iter().map(|(k, six)| run(*k, rec, *six)).collect());
    }
    let elapsed = start.elapsed();

    print!("| trial |");
    for (k, six) in &columns {
        print!(" {} {} |", k.name(), if *six { "6D*" } else { "9D" });
    }
    println!();
    println!("|---|{}", "---|".repeat(columns.len()));
    let cell = |s: &Scores| format!(" {:.2} ({:.2}) |", s.total, s.inclination);
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
            let incl = rows.iter().map(|r| r[c].inclination).sum::<f64>() / n;
            print!(" {total:.2} ({incl:.2}) |");
        }
        println!();
    }
    let samples: usize = recordings.iter().map(|(_, r)| r.len()).sum();
    println!(
        "\n{} trials, {samples} samples, {} runs in {:.1} s (reading included)",
        recordings.len(),
        columns.len() * recordings.len(),
        elapsed.as_secs_f64()
    );
}
