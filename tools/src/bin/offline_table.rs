//! Scores the offline mode (forward-backward smoothing, `orient::offline`) against the
//! causal filter on every recording in a directory, 9D, BROAD's rule.
//!
//!     cargo run --release --bin offline_table [-- DIR] [--kinds robust,gmvdk]
//!
//! Cells: total (inclination) RMSE in degrees, causal then offline; the last row is the
//! mean over all trials and the mean over the first eight shared trials. The recommended
//! kind's offline column uses the offline defaults (`orient::offline::config()`).
//! `PASSES=1` also prints each pass's total / heading / inclination; `SETS=name=value,...`
//! sets parameters on both columns; `DECIMATE=k` keeps every k-th row (gyroscope averaged
//! over each interval, `orient_tools::eval::decimate`); `SIXD=1` drops the magnetometer and
//! removes one heading offset per trial (6D*).

use orient::{offline, Config, Filter, Kind, Quat};
use orient_tools::eval::{remove_heading_offset, score, Recording};
use std::path::PathBuf;

const FIRST_EIGHT: [u32; 8] = [1, 6, 8, 15, 24, 26, 28, 32];

fn main() {
    let mut dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/broad"));
    let mut kinds = vec![Kind::Robust];
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--kinds" => {
                let list = args.next().expect("--kinds needs a list");
                kinds = list.split(',').map(|n| Kind::from_name(n).expect("a kind")).collect();
            }
            _ => dir = PathBuf::from(a),
        }
    }
    let files = orient_tools::eval::csv_files(&dir).expect("a directory of recordings");
    for kind in kinds {
        let mut config = Config::new(kind).expect("config");
        if let Ok(v) = std::env::var("SETS") {
            for kv in v.split(',') {
                let (k, x) = kv.split_once('=').unwrap();
                config.set(k, x.parse().unwrap()).unwrap().unwrap();
            }
        }
        let mut offline_config = if kind == Kind::Robust { offline::config() } else { config.clone() };
        if let Ok(v) = std::env::var("SETS") {
            for kv in v.split(',') {
                let (k, x) = kv.split_once('=').unwrap();
                offline_config.set(k, x.parse().unwrap()).unwrap().unwrap();
            }
        }
        println!("\n{} | causal 9D | offline 9D", kind.name());
        let (mut sums, mut first) = ([0.0; 4], [0.0; 4]);
        for p in &files {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            let mut rec = Recording::read(p, true).expect("recording");
            let mut samples = rec.samples();
            if std::env::var_os("SIXD").is_some() {
                for s in samples.iter_mut() {
                    s.mag = None;
                }
            }
            if let Some(k) = std::env::var("DECIMATE").ok().and_then(|v| v.parse::<usize>().ok()) {
                (rec, samples) = orient_tools::eval::decimate(&rec, &samples, k);
            }
            let mut f = Filter::new(&config).expect("filter");
            let causal: Vec<Quat> = samples
                .iter()
                .map(|s| {
                    let _ = f.update(s);
                    f.quaternion()
                })
                .collect();
            let (fore, back) = offline::passes(&offline_config, &samples).expect("smooth");
            let smoothed = offline::fuse(&fore, &back);
            if std::env::var_os("PASSES").is_some() {
                let f = score(&fore.q, &rec.truth, &rec.movement);
                let b = score(&back.q, &rec.truth, &rec.movement);
                println!(
                    "  fore {:.2}/{:.2}/{:.2} back {:.2}/{:.2}/{:.2}",
                    f.total, f.heading, f.inclination, b.total, b.heading, b.inclination
                );
            }
            let (mut causal, mut smoothed) = (causal, smoothed);
            if std::env::var_os("SIXD").is_some() {
                remove_heading_offset(&mut causal, &rec.truth, &rec.movement);
                remove_heading_offset(&mut smoothed, &rec.truth, &rec.movement);
            }
            let c = score(&causal, &rec.truth, &rec.movement);
            let o = score(&smoothed, &rec.truth, &rec.movement);
            println!(
                "{name} | {:.2} ({:.2}) | {:.2} ({:.2})",
                c.total, c.inclination, o.total, o.inclination
            );
            let v = [c.total, c.inclination, o.total, o.inclination];
            let number: u32 = name.split('_').next().and_then(|n| n.parse().ok()).unwrap_or(0);
            for k in 0..4 {
                sums[k] += v[k] / files.len() as f64;
                if FIRST_EIGHT.contains(&number) {
                    first[k] += v[k] / 8.0;
                }
            }
        }
        println!("mean of all | {:.2} ({:.2}) | {:.2} ({:.2})", sums[0], sums[1], sums[2], sums[3]);
        println!("mean of first 8 | {:.2} ({:.2}) | {:.2} ({:.2})", first[0], first[1], first[2], first[3]);
    }
}
