//! Leave-one-group-out evaluation of the recommended kind against VQF on the shared BROAD
//! trials, at the recording rate and decimated.
//!
//!     cargo run --release --bin robust_cv [-- OPTIONS]
//!
//! Scoring is BROAD's (FORMAT.md, `orient_tools::eval`): 9D total, 6D* total (magnetometer
//! unused, one heading offset removed per trial) and 9D inclination RMSE in degrees,
//! mean over trials. VQF is `vqf-rs` with its defaults, scored the same way (its 6D
//! output for 6D*).
//!
//! Decimation by an integer factor k (285.7 Hz / 3 = 95.2 Hz, / 6 = 47.6 Hz): the
//! gyroscope is averaged over each interval of k samples (the mean rate is what
//! integrates to the interval's rotation), the accelerometer and magnetometer are the
//! readings at the interval's end (a host polling the latest register), dt is k times
//! the recording's, and the truth and movement mask are those of the interval's last
//! row.
//!
//! Options:
//! - `--dir DIR` (default ../shared/data/broad); `--rates 1,3,6` decimation factors.
//! - `--set name=value` (repeatable): a fixed setting for every robust run.
//! - `--grid name=v1,v2,...` (repeatable): candidate settings. Every combination is
//!   scored on every trial; for each held-out group the combination with the lowest
//!   mean (9D total + 6D* total) over the *other* groups is chosen and its score on the
//!   held-out group reported (leave-one-group-out cross-validation), next to the
//!   defaults' (in-sample) score and VQF's.
//! - `--starts`: settling time when started in motion (see `starts_table`) instead;
//!   `--kind NAME` runs another kind there (its defaults and `--set`) in robust's column.

use orient::{Config, Filter, Kind, Quat, Sample};
use orient_tools::eval::{remove_heading_offset, score, Recording, GROUPS};
use std::path::PathBuf;

/// One trial at one rate.
struct Trial {
    number: u32,
    samples: Vec<Sample>,
    truth: Vec<Quat>,
    movement: Vec<bool>,
}

fn decimate(rec: &Recording, k: usize, number: u32) -> Trial {
    let all = rec.samples();
    let mut t = Trial { number, samples: Vec::new(), truth: Vec::new(), movement: Vec::new() };
    for chunk_start in (0..all.len()).step_by(k) {
        let end = (chunk_start + k).min(all.len());
        if end - chunk_start < k {
            break;
        }
        let chunk = &all[chunk_start..end];
        let dt: f64 = chunk.iter().map(|s| s.dt).sum();
        let gyro = chunk.iter().fold(orient::Vec3::ZERO, |a, s| a + s.gyro.unwrap() * s.dt) * (1.0 / dt);
        let last = chunk[k - 1];
        t.samples.push(Sample { dt, gyro: Some(gyro), accel: last.accel, mag: last.mag });
        t.truth.push(rec.truth[end - 1]);
        t.movement.push(rec.movement[end - 1]);
    }
    t
}

/// (9D total, 6D* total, 9D inclination) of one trial.
type Triple = [f64; 3];

fn score_both(trial: &Trial, mut run: impl FnMut(&[Sample], bool) -> Vec<Quat>) -> Triple {
    let s9 = score(&run(&trial.samples, true), &trial.truth, &trial.movement);
    let mut q6 = run(&trial.samples, false);
    remove_heading_offset(&mut q6, &trial.truth, &trial.movement);
    let s6 = score(&q6, &trial.truth, &trial.movement);
    [s9.total, s6.total, s9.inclination]
}

fn robust(config: &Config, trial: &Trial) -> Triple {
    score_both(trial, |samples, mag| {
        let mut f = Filter::new(config).expect("filter");
        samples
            .iter()
            .map(|s| {
                let s = Sample { mag: if mag { s.mag } else { None }, ..*s };
                let _ = f.update(&s);
                f.quaternion()
            })
            .collect()
    })
}

fn vqf(trial: &Trial) -> Triple {
    score_both(trial, |samples, mag| {
        let mut f = vqf_rs::VQF::new(samples[0].dt, None, None, None);
        let v = |v: orient::Vec3| [v.x, v.y, v.z];
        samples
            .iter()
            .map(|s| {
                f.update(v(s.gyro.unwrap()), v(s.accel.unwrap()), if mag { s.mag.map(v) } else { None });
                let q = if mag { f.quat_9d() } else { f.quat_6d() };
                Quat::new(q.0, q.1, q.2, q.3)
            })
            .collect()
    })
}

/// Seconds from the start until the 9D total error is below `SETTLED` degrees and
/// stays there for `HOLD` seconds (the convergence, not the steady level, which spikes
/// past 5 degrees on the fast trials); the window's length when it never is.
fn settle(est: &[Quat], trial: &Trial, from: usize, to: usize) -> f64 {
    const SETTLED: f64 = 5.0;
    const HOLD: f64 = 5.0;
    let dt = trial.samples[0].dt;
    let hold = (HOLD / dt) as usize;
    let mut good_since = None;
    for i in from..to {
        let g = trial.truth[i];
        let bad =
            g.is_finite() && orient_tools::eval::error_angles(est[i - from], g).0.to_degrees() >= SETTLED;
        match (bad, good_since) {
            (true, _) => good_since = None,
            (false, None) => good_since = Some(i),
            (false, Some(s)) if i - s >= hold => return (s - from) as f64 * dt,
            _ => {}
        }
    }
    (to - from) as f64 * dt
}

/// Starts in motion: every trial started (fresh filter, first sample at that row) every
/// 20 s from its first movement sample, and how long robust and VQF take to settle
/// (9D total error below 5 degrees for 5 s, within the next 40 s). A start whose field
/// norm is off the trial's first reading by more than 20 % is inside a disturbance.
fn starts_table(config: &Config, trials: &[Trial]) {
    let hz = 1.0 / trials[0].samples[0].dt;
    let k = config.kind().name();
    println!("\n## Starts in motion, {hz:.1} Hz: settling time (s), mean / max over starts\n");
    println!("| trial | starts | {k} | VQF | starts in a disturbance | {k} | VQF |");
    println!("|---|---|---|---|---|---|---|");
    let window = (40.0 * hz) as usize;
    let (mut all_r, mut all_v, mut dist_r, mut dist_v) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for trial in trials {
        let first = trial.movement.iter().position(|m| *m).unwrap_or(0);
        let norm0 = trial.samples[0].mag.map_or(1.0, |m| m.norm());
        let (mut r, mut v, mut dr, mut dv) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut s = first;
        while s + window < trial.samples.len() {
            let part = &trial.samples[s..s + window];
            let mut f = Filter::new(config).expect("filter");
            let est: Vec<Quat> = part
                .iter()
                .map(|x| {
                    let _ = f.update(x);
                    f.quaternion()
                })
                .collect();
            let mut g = vqf_rs::VQF::new(part[0].dt, None, None, None);
            let w = |v: orient::Vec3| [v.x, v.y, v.z];
            let est_v: Vec<Quat> = part
                .iter()
                .map(|x| {
                    g.update(w(x.gyro.unwrap()), w(x.accel.unwrap()), x.mag.map(w));
                    let q = g.quat_9d();
                    Quat::new(q.0, q.1, q.2, q.3)
                })
                .collect();
            let (a, b) = (settle(&est, trial, s, s + window), settle(&est_v, trial, s, s + window));
            let disturbed = part[0].mag.is_some_and(|m| (m.norm() / norm0 - 1.0).abs() > 0.2);
            if disturbed {
                dr.push(a);
                dv.push(b);
            } else {
                r.push(a);
                v.push(b);
            }
            s += (20.0 * hz) as usize;
        }
        let mm = |x: &[f64]| {
            if x.is_empty() {
                "–".to_string()
            } else {
                format!(
                    "{:.1} / {:.1}",
                    x.iter().sum::<f64>() / x.len() as f64,
                    x.iter().cloned().fold(0.0, f64::max)
                )
            }
        };
        println!(
            "| {:02} | {} | {} | {} | {} | {} | {} |",
            trial.number,
            r.len(),
            mm(&r),
            mm(&v),
            dr.len(),
            mm(&dr),
            mm(&dv)
        );
        all_r.extend(r);
        all_v.extend(v);
        dist_r.extend(dr);
        dist_v.extend(dv);
    }
    let mm = |x: &[f64]| {
        format!(
            "{:.1} / {:.1}",
            x.iter().sum::<f64>() / x.len().max(1) as f64,
            x.iter().cloned().fold(0.0, f64::max)
        )
    };
    println!(
        "| all | {} | {} | {} | {} | {} | {} |",
        all_r.len(),
        mm(&all_r),
        mm(&all_v),
        dist_r.len(),
        mm(&dist_r),
        mm(&dist_v)
    );
}

fn mean(rows: &[&Triple]) -> Triple {
    let n = rows.len() as f64;
    let mut m = [0.0; 3];
    for r in rows {
        for i in 0..3 {
            m[i] += r[i] / n;
        }
    }
    m
}

fn cell(m: &Triple) -> String {
    format!("{:.2} / {:.2} / {:.2}", m[0], m[1], m[2])
}

fn main() {
    let mut dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/broad"));
    let mut rates: Vec<usize> = vec![1, 3, 6];
    let mut sets: Vec<(String, f64)> = Vec::new();
    let mut grid: Vec<(String, Vec<f64>)> = Vec::new();
    let mut starts = false;
    let mut kind = Kind::Robust;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--starts" {
            starts = true;
            continue;
        }
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--dir" => dir = PathBuf::from(value()),
            "--kind" => {
                let name = value();
                kind = Kind::from_name(&name).unwrap_or_else(|| panic!("unknown kind {name}"));
            }
            "--rates" => rates = value().split(',').map(|r| r.parse().expect("a factor")).collect(),
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
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "csv"))
        .collect();
    files.sort();
    let recordings: Vec<(u32, Recording)> = files
        .iter()
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            let n = name.split('_').next().and_then(|n| n.parse().ok()).expect("NN_name.csv");
            (n, Recording::read(p, true).unwrap_or_else(|e| panic!("{}: {e}", p.display())))
        })
        .collect();

    // Every combination of the grid, on top of the fixed settings.
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
    assert!(starts || kind == Kind::Robust, "--kind goes with --starts");
    let config_of = |extra: &[(String, f64)]| {
        let mut c = Config::new(kind).expect("kind");
        for (name, value) in sets.iter().chain(extra) {
            c.set(name, *value).unwrap_or_else(|| panic!("no parameter {name}")).expect("value in range");
        }
        c
    };
    let label = |c: &[(String, f64)]| c.iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join(" ");

    if starts {
        let config = config_of(&[]);
        for &k in &rates {
            let trials: Vec<Trial> = recordings.iter().map(|(n, r)| decimate(r, k, *n)).collect();
            starts_table(&config, &trials);
        }
        return;
    }
    for &k in &rates {
        let trials: Vec<Trial> = recordings.iter().map(|(n, r)| decimate(r, k, *n)).collect();
        let hz = 1.0 / trials[0].samples[0].dt;
        println!("\n## {hz:.1} Hz (decimation {k})\n");
        let base: Vec<Triple> = trials.iter().map(|t| robust(&config_of(&[]), t)).collect();
        let vq: Vec<Triple> = trials.iter().map(vqf).collect();
        let table: Vec<Vec<Triple>> = if grid.is_empty() {
            vec![base.clone()]
        } else {
            combos.iter().map(|c| trials.iter().map(|t| robust(&config_of(c), t)).collect()).collect()
        };
        println!("| trial | robust 9D / 6D* / incl | VQF 9D / 6D* / incl |");
        println!("|---|---|---|");
        for (i, t) in trials.iter().enumerate() {
            println!("| {:02} | {} | {} |", t.number, cell(&base[i]), cell(&vq[i]));
        }
        let all: Vec<usize> = (0..trials.len()).collect();
        let pick = |idx: &[usize], v: &[Triple]| mean(&idx.iter().map(|&i| &v[i]).collect::<Vec<_>>());
        println!("| mean | {} | {} |", cell(&pick(&all, &base)), cell(&pick(&all, &vq)));
        if grid.is_empty() {
            continue;
        }
        println!(
            "\nLeave-one-group-out: held-out group, combination chosen on the others, its held-out score\n"
        );
        println!("| held out | chosen | CV robust | defaults | VQF |");
        println!("|---|---|---|---|---|");
        let mut cv: Vec<Triple> = vec![[0.0; 3]; trials.len()];
        for (gname, members) in GROUPS {
            let held: Vec<usize> =
                all.iter().copied().filter(|&i| members.contains(&trials[i].number)).collect();
            let rest: Vec<usize> = all.iter().copied().filter(|i| !held.contains(i)).collect();
            let objective = |c: usize| {
                let m = pick(&rest, &table[c]);
                m[0] + m[1]
            };
            let best = (0..combos.len()).min_by(|a, b| objective(*a).total_cmp(&objective(*b))).unwrap();
            for &i in &held {
                cv[i] = table[best][i];
            }
            println!(
                "| {gname} | {} | {} | {} | {} |",
                label(&combos[best]),
                cell(&pick(&held, &table[best])),
                cell(&pick(&held, &base)),
                cell(&pick(&held, &vq))
            );
        }
        let best_all = (0..combos.len())
            .min_by(|a, b| {
                let f = |c: usize| {
                    let m = pick(&all, &table[c]);
                    m[0] + m[1]
                };
                f(*a).total_cmp(&f(*b))
            })
            .unwrap();
        println!(
            "| **mean over trials** | | {} | {} | {} |",
            cell(&pick(&all, &cv)),
            cell(&pick(&all, &base)),
            cell(&pick(&all, &vq))
        );
        println!(
            "\nIn-sample best over all 14: {} -> {}",
            label(&combos[best_all]),
            cell(&pick(&all, &table[best_all]))
        );
    }
}
