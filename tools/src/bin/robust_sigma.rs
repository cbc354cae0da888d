//! How well the recommended kind's heading uncertainty follows its heading error on the
//! shared BROAD trials, and leave-one-group-out cross-validation of its uncertainty
//! settings.
//!
//!     cargo run --release --bin robust_sigma [-- OPTIONS]
//!
//! Per trial, over BROAD's scored rows (movement == 1, optical truth present), with the
//! heading error of `orient_tools::eval::error_angles` (no offset removed, as BROAD
//! scores a 9D filter): the RMS heading error, the median reported sigma, their ratio,
//! and the fraction of rows whose error is within 2 and 3 sigma.
//!
//! Options:
//! - `--dir DIR` (default ../shared/data/broad beside the repository).
//! - `--set name=value` (repeatable): a fixed setting for every run.
//! - `--grid name=v1,v2,...` (repeatable): candidate settings. For each held-out group
//!   (the groups of `robust_cv`) the combination with the lowest loss over the *other*
//!   groups is chosen and its figures on the held-out group reported. The loss is the
//!   mean over trials of ln(ratio)² plus 10 (c − 0.95)², c the 2-sigma coverage pooled
//!   over the rows: the ratio near 1 on every trial and the coverage at its stated rate.
//!
//! The sigma is a side model: no setting here changes the orientation.

use orient::{Config, Filter, Kind, Quat, Sample};
use orient_tools::eval::{csv_files, error_angles, Recording, GROUPS};
use std::path::PathBuf;

struct Trial {
    number: u32,
    samples: Vec<Sample>,
    truth: Vec<Quat>,
    movement: Vec<bool>,
}

/// Per-trial figures: rows, sum of squared error, sigmas, within 2 and 3 sigma.
#[derive(Clone, Default)]
struct Fig {
    rows: usize,
    sq: f64,
    median: f64,
    w2: usize,
    w3: usize,
}

impl Fig {
    fn rmse(&self) -> f64 {
        (self.sq / self.rows as f64).sqrt()
    }
    fn ratio(&self) -> f64 {
        self.rmse() / self.median
    }
}

fn run(config: &Config, t: &Trial) -> Fig {
    let mut f = Filter::new(config).expect("filter");
    let mut fig = Fig::default();
    let mut sigmas = Vec::new();
    for (i, s) in t.samples.iter().enumerate() {
        f.update(s).expect("sample");
        if !t.movement[i] || !t.truth[i].is_finite() {
            continue;
        }
        let sigma = f.uncertainty().heading.expect("a heading sigma");
        let (_, e, _) = error_angles(f.quaternion(), t.truth[i]);
        fig.rows += 1;
        fig.sq += e * e;
        fig.w2 += usize::from(e <= 2.0 * sigma);
        fig.w3 += usize::from(e <= 3.0 * sigma);
        sigmas.push(sigma);
    }
    sigmas.sort_by(f64::total_cmp);
    fig.median = sigmas[sigmas.len() / 2];
    fig
}

fn coverage(figs: &[&Fig]) -> (f64, f64) {
    let rows: usize = figs.iter().map(|f| f.rows).sum();
    let w2: usize = figs.iter().map(|f| f.w2).sum();
    let w3: usize = figs.iter().map(|f| f.w3).sum();
    (w2 as f64 / rows as f64, w3 as f64 / rows as f64)
}

fn loss(figs: &[&Fig]) -> f64 {
    let r: f64 = figs.iter().map(|f| f.ratio().ln().powi(2)).sum::<f64>() / figs.len() as f64;
    r + 10.0 * (coverage(figs).0 - 0.95).powi(2)
}

fn table(trials: &[Trial], figs: &[Fig]) {
    println!("| trial | RMSE (deg) | median sigma (deg) | ratio | within 2 sigma | within 3 sigma |");
    println!("|---|---|---|---|---|---|");
    for (t, f) in trials.iter().zip(figs) {
        println!(
            "| {:02} | {:.2} | {:.2} | {:.2} | {:.1} % | {:.1} % |",
            t.number,
            f.rmse().to_degrees(),
            f.median.to_degrees(),
            f.ratio(),
            100.0 * f.w2 as f64 / f.rows as f64,
            100.0 * f.w3 as f64 / f.rows as f64
        );
    }
    let all: Vec<&Fig> = figs.iter().collect();
    let (c2, c3) = coverage(&all);
    let (lo, hi) = figs.iter().fold((f64::MAX, 0.0f64), |(a, b), f| (a.min(f.ratio()), b.max(f.ratio())));
    println!("| all | | | {lo:.2}-{hi:.2} | {:.1} % | {:.1} % |", 100.0 * c2, 100.0 * c3);
}

fn main() {
    let mut dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/broad"));
    let mut sets: Vec<(String, f64)> = Vec::new();
    let mut grid: Vec<(String, Vec<f64>)> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--dir" => dir = PathBuf::from(value()),
            "--set" => {
                let kv = value();
                let (k, v) = kv.split_once('=').expect("--set name=value");
                sets.push((k.into(), v.parse().expect("a number")));
            }
            "--grid" => {
                let kv = value();
                let (k, v) = kv.split_once('=').expect("--grid name=v1,v2");
                grid.push((k.into(), v.split(',').map(|x| x.parse().expect("a number")).collect()));
            }
            other => panic!("unknown option {other}"),
        }
    }
    let trials: Vec<Trial> = csv_files(&dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .iter()
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            let number = name.split('_').next().and_then(|n| n.parse().ok()).expect("NN_name.csv");
            let rec = Recording::read(p, true).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            Trial { number, samples: rec.samples(), truth: rec.truth, movement: rec.movement }
        })
        .collect();
    let config_of = |extra: &[(String, f64)]| {
        let mut c = Config::new(Kind::Robust).expect("kind");
        for (name, value) in sets.iter().chain(extra) {
            c.set(name, *value).unwrap_or_else(|| panic!("no parameter {name}")).expect("value in range");
        }
        c
    };
    let base: Vec<Fig> = trials.iter().map(|t| run(&config_of(&[]), t)).collect();
    println!("\n## Defaults{}\n", if sets.is_empty() { String::new() } else { format!(" with {sets:?}") });
    table(&trials, &base);
    if grid.is_empty() {
        return;
    }
    let mut combos: Vec<Vec<(String, f64)>> = vec![Vec::new()];
    for (name, values) in &grid {
        combos = combos
            .iter()
            .flat_map(|c| {
                values.iter().map(move |v| {
                    let mut c = c.clone();
                    c.push((name.clone(), *v));
                    c
                })
            })
            .collect();
    }
    let label = |c: &[(String, f64)]| c.iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join(" ");
    let figs: Vec<Vec<Fig>> = combos
        .iter()
        .map(|c| {
            let f: Vec<Fig> = trials.iter().map(|t| run(&config_of(c), t)).collect();
            eprintln!("{} -> loss {:.4}", label(c), loss(&f.iter().collect::<Vec<_>>()));
            f
        })
        .collect();
    println!("\n## Leave-one-group-out: held-out group, combination chosen on the others\n");
    println!("| held out | chosen | trial | ratio | within 2 sigma |");
    println!("|---|---|---|---|---|");
    let mut cv: Vec<Fig> = base.clone();
    for (gname, members) in GROUPS {
        let held: Vec<usize> = (0..trials.len()).filter(|&i| members.contains(&trials[i].number)).collect();
        let rest: Vec<usize> = (0..trials.len()).filter(|i| !held.contains(i)).collect();
        let objective = |c: usize| loss(&rest.iter().map(|&i| &figs[c][i]).collect::<Vec<_>>());
        let best = (0..combos.len()).min_by(|a, b| objective(*a).total_cmp(&objective(*b))).unwrap();
        for &i in &held {
            cv[i] = figs[best][i].clone();
            let f = &cv[i];
            println!(
                "| {gname} | {} | {:02} | {:.2} | {:.1} % |",
                label(&combos[best]),
                trials[i].number,
                f.ratio(),
                100.0 * f.w2 as f64 / f.rows as f64
            );
        }
    }
    println!("\n## Held-out figures (each trial with the combination chosen without its group)\n");
    table(&trials, &cv);
    let all: Vec<usize> = (0..trials.len()).collect();
    let best = (0..combos.len())
        .min_by(|a, b| {
            let l = |c: usize| loss(&all.iter().map(|&i| &figs[c][i]).collect::<Vec<_>>());
            l(*a).total_cmp(&l(*b))
        })
        .unwrap();
    println!("\nIn-sample best over all 14: {}", label(&combos[best]));
}
