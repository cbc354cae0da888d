//! Leave-one-group-out cross-validation of the offline mode's heading time constant
//! (`tau_mag` of the recommended kind) over the BROAD trials in a directory: for each
//! group of trials (rotation, translation, breaks, tapping, vibration, stationary magnet,
//! attached magnet), the value is chosen from a grid on the other groups and scored on
//! the held-out group. Prints each held-out trial's 9D total with the chosen value, and
//! the means.
//!
//!     cargo run --release --bin offline_cv [-- DIR]

use orient::{offline, Config, Kind};
use orient_tools::eval::{score, Recording};
use std::path::PathBuf;

const GRID: [f64; 6] = [9.0, 13.5, 18.0, 27.0, 36.0, 54.0];

fn group(trial: u32) -> &'static str {
    match trial {
        1..=7 => "rotation",
        8..=10 => "breaks",
        11..=23 => "translation",
        24 | 25 => "tapping",
        26 | 27 => "vibration",
        28..=31 => "stationary magnet",
        _ => "attached magnet",
    }
}

fn main() {
    let dir = std::env::args().nth(1).map_or_else(
        || PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/broad")),
        PathBuf::from,
    );
    let files = orient_tools::eval::csv_files(&dir).expect("a directory of recordings");
    // scores[trial][grid index]
    let mut trials: Vec<(u32, String, Vec<f64>)> = Vec::new();
    for p in &files {
        let name = p.file_stem().unwrap().to_string_lossy().into_owned();
        let number: u32 = name.split('_').next().and_then(|n| n.parse().ok()).unwrap_or(0);
        let rec = Recording::read(p, true).expect("recording");
        let samples = rec.samples();
        let row = GRID
            .iter()
            .map(|tau| {
                let mut c = Config::new(Kind::Robust).unwrap();
                c.set("tau_mag", *tau).unwrap().unwrap();
                score(&offline::smooth(&c, &samples).unwrap(), &rec.truth, &rec.movement).total
            })
            .collect();
        trials.push((number, name, row));
    }
    let mut held = Vec::new();
    let groups: Vec<&str> = {
        let mut g: Vec<&str> = trials.iter().map(|t| group(t.0)).collect();
        g.dedup();
        g
    };
    for g in groups {
        let train: Vec<&(u32, String, Vec<f64>)> = trials.iter().filter(|t| group(t.0) != g).collect();
        let best = (0..GRID.len())
            .min_by(|a, b| {
                let m = |k: usize| train.iter().map(|t| t.2[k]).sum::<f64>();
                m(*a).total_cmp(&m(*b))
            })
            .unwrap();
        for t in trials.iter().filter(|t| group(t.0) == g) {
            println!("{} ({g}): tau_mag {} chosen, held-out {:.2}", t.1, GRID[best], t.2[best]);
            held.push((t.0, t.2[best]));
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let all: Vec<f64> = held.iter().map(|h| h.1).collect();
    let first: Vec<f64> =
        held.iter().filter(|h| [1, 6, 8, 15, 24, 26, 28, 32].contains(&h.0)).map(|h| h.1).collect();
    println!("cross-validated mean: all {:.3}, first 8 {:.3}", mean(&all), mean(&first));
    for (k, tau) in GRID.iter().enumerate() {
        let v: Vec<f64> = trials.iter().map(|t| t.2[k]).collect();
        println!("in-sample tau_mag {tau}: {:.3}", mean(&v));
    }
}
