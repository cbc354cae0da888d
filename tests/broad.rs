//! Filters on the shared BROAD recordings (../shared/data/broad), scored with BROAD's
//! rule, against bounds taken from ../shared/data/README.md.
//!
//! Needs the shared directory beside the repository, as CI has it. Set
//! ORIENT_SKIP_SHARED_DATA=1 to skip these tests where it is absent.

use orient::{Config, Filter, Frame, Kind, Quat};
use orient_tools::eval::{remove_heading_offset, score, Recording, Scores};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Mutex, OnceLock};

fn broad_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data/broad");
    if dir.is_dir() {
        return Some(dir);
    }
    if std::env::var_os("ORIENT_SKIP_SHARED_DATA").is_some() {
        eprintln!("skipping: {} not found", dir.display());
        return None;
    }
    panic!("{} not found (set ORIENT_SKIP_SHARED_DATA=1 to skip)", dir.display());
}

/// A trial, read once per test process (parsing is most of the cost under emulation);
/// without `with_mag` its magnetometer readings are dropped.
fn trial(dir: &PathBuf, prefix: &str, with_mag: bool) -> Recording {
    static CACHE: OnceLock<Mutex<HashMap<String, Recording>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let mut rec = {
        let mut map = cache.lock().unwrap();
        map.entry(prefix.to_string())
            .or_insert_with(|| {
                let entry = std::fs::read_dir(dir)
                    .unwrap()
                    .map(|e| e.unwrap().path())
                    .find(|p| p.file_name().unwrap().to_string_lossy().starts_with(prefix))
                    .unwrap_or_else(|| panic!("trial {prefix} missing"));
                Recording::read(&entry, true).unwrap()
            })
            .clone()
    };
    if !with_mag {
        rec.mag.clear();
    }
    rec
}

fn run(config: &Config, rec: &Recording) -> Vec<Quat> {
    let mut f = Filter::new(config).unwrap();
    let to_enu = config.frame.rotation_to(Frame::Enu);
    rec.samples()
        .iter()
        .map(|s| {
            f.update(s).unwrap();
            let q = f.quaternion();
            to_enu.map_or(q, |c| c * q)
        })
        .collect()
}

fn scores(config: &Config, rec: &Recording, remove_offset: bool) -> Scores {
    let mut q = run(config, rec);
    if remove_offset {
        remove_heading_offset(&mut q, &rec.truth, &rec.movement);
    }
    score(&q, &rec.truth, &rec.movement)
}

const TRIALS: [&str; 8] = ["01_", "06_", "08_", "15_", "24_", "26_", "28_", "32_"];

/// Madgwick 9D with β = 0.041, column "Madgwick 9D β=0.041 (Python ahrs, paper
/// equations)" of shared/data/README.md: total (inclination) per trial.
const AHRS_041: [(f64, f64); 8] = [
    (2.11, 0.73),
    (3.81, 1.61),
    (5.89, 2.82),
    (19.86, 5.20),
    (1.92, 1.26),
    (6.11, 2.94),
    (4.96, 2.59),
    (13.11, 4.85),
];

#[test]
fn madgwick_9d_defaults_reproduce_the_published_ahrs_scores() {
    let Some(dir) = broad_dir() else { return };
    // The default beta_marg is 0.041, the value behind the published column.
    let config = Config::new(Kind::Madgwick).unwrap();
    for (prefix, (total, incl)) in TRIALS.iter().zip(AHRS_041) {
        let s = scores(&config, &trial(&dir, prefix, true), false);
        println!(
            "{prefix} total {:.2} (published {total}), inclination {:.2} ({incl})",
            s.total, s.inclination
        );
        // The published start differs slightly (BROAD's acc/mag helper); the scores must
        // agree to within a tenth of a degree.
        assert!((s.total - total).abs() < 0.1, "{prefix}: total {:.3} vs {total}", s.total);
        assert!((s.inclination - incl).abs() < 0.1, "{prefix}: inclination {:.3} vs {incl}", s.inclination);
    }
}

#[test]
fn madgwick_defaults_stay_within_bounds_in_9d_and_6d() {
    let Some(dir) = broad_dir() else { return };
    let config = Config::new(Kind::Madgwick).unwrap();
    let (mut sum9, mut sum6, mut incl) = (0.0, 0.0, 0.0);
    for prefix in TRIALS {
        let s9 = scores(&config, &trial(&dir, prefix, true), false);
        let s6 = scores(&config, &trial(&dir, prefix, false), true);
        println!(
            "{prefix} 9D total {:.2} incl {:.2} | 6D* total {:.2} incl {:.2}",
            s9.total, s9.inclination, s6.total, s6.inclination
        );
        sum9 += s9.total;
        sum6 += s6.total;
        incl += s9.inclination;
    }
    let (m9, m6, mi) = (sum9 / 8.0, sum6 / 8.0, incl / 8.0);
    println!("mean 9D {m9:.2}, 6D* {m6:.2}, inclination {mi:.2}");
    // Measured 7.22 / 8.43 / 2.75 (beta 0.041); the published ahrs mean is 7.22 (2.75).
    // The bounds leave room for rounding-level changes, not for a regression.
    assert!(m9 < 7.25, "mean 9D total {m9:.2}");
    assert!(m6 < 8.6, "mean 6D* total {m6:.2} (BROAD's C code, beta 0.1: 8.60)");
    assert!(mi < 2.8, "mean inclination {mi:.2}");
}

#[test]
fn frames_give_the_same_broad_score() {
    let Some(dir) = broad_dir() else { return };
    let rec = trial(&dir, "01_", true);
    let mut totals = Vec::new();
    for frame in Frame::ALL {
        let mut config = Config::new(Kind::Madgwick).unwrap();
        config.frame = frame;
        totals.push(scores(&config, &rec, false).total);
    }
    assert!(totals.iter().all(|t| (t - totals[0]).abs() < 1e-6), "{totals:?}");
}

/// Mean total (inclination) over the 8 trials, with defaults.
fn means(kind: Kind, six_d: bool) -> (f64, f64) {
    means_with(kind, six_d, &[])
}

/// [`means`] with some parameters set by name.
fn means_with(kind: Kind, six_d: bool, set: &[(&str, f64)]) -> (f64, f64) {
    let dir = broad_dir().unwrap();
    let mut config = Config::new(kind).unwrap();
    for (name, value) in set {
        config.set(name, *value).unwrap().unwrap();
    }
    let (mut t, mut i) = (0.0, 0.0);
    for prefix in TRIALS {
        let s = scores(&config, &trial(&dir, prefix, !six_d), six_d);
        t += s.total;
        i += s.inclination;
    }
    (t / 8.0, i / 8.0)
}

#[test]
fn mahony_9d_matches_the_published_baseline() {
    if broad_dir().is_none() {
        return;
    }
    // Published (BROAD's C code, Kp = 0.5, Ki = 0): mean 10.34 (3.48). Per-trial
    // differences of up to 0.8° come from that code's float32 arithmetic and start.
    let (total, incl) = means(Kind::Mahony, false);
    println!("mahony 9D mean {total:.2} ({incl:.2})");
    assert!((total - 10.34).abs() < 0.3 && (incl - 3.48).abs() < 0.2, "{total} {incl}");
}

#[test]
fn every_kind_stays_within_its_measured_bounds() {
    if broad_dir().is_none() {
        return;
    }
    // Measured means with the defaults (see the issue notes and README), plus about 5 %:
    // regression guards, not targets. (kind, 6D*, total bound, inclination bound)
    let bounds = [
        (Kind::Mahony, true, 9.0, 2.3),
        (Kind::Complementary, false, 6.5, 3.55),
        (Kind::Complementary, true, 4.55, 3.55),
        (Kind::Ekf, false, 6.1, 3.2),
        (Kind::Ekf, true, 18.4, 3.8),
        (Kind::Gmvdk, false, 19.3, 6.4),
        (Kind::Gmvdk, true, 8.5, 7.35),
    ];
    for (kind, six_d, max_total, max_incl) in bounds {
        let (total, incl) = means(kind, six_d);
        println!("{kind:?} {}: mean {total:.2} ({incl:.2})", if six_d { "6D*" } else { "9D" });
        assert!(total < max_total && incl < max_incl, "{kind:?} 6D*={six_d}: {total:.2} ({incl:.2})");
    }
}

#[test]
fn robust_beats_vqf_on_every_target() {
    if broad_dir().is_none() {
        return;
    }
    // The recommended kind against VQF, the best published filter on these trials
    // (shared/data/README.md): 9D 3.34 (0.82), 6D* 2.82 (0.82). Measured: 9D 2.28
    // (0.80), 6D* 2.78 (0.80) (before the motion bias filter, issue 42: 2.36 and 2.69).
    let (total, incl) = means(Kind::Robust, false);
    println!("robust 9D mean {total:.2} ({incl:.2})");
    assert!(total < 3.34 && incl < 0.82, "9D {total:.3} ({incl:.3})");
    let (total, incl) = means(Kind::Robust, true);
    println!("robust 6D* mean {total:.2} ({incl:.2})");
    assert!(total < 2.82 && incl < 0.82, "6D* {total:.3} ({incl:.3})");
}

#[test]
fn rest_bias_options_improve_the_seed_filters() {
    if broad_dir().is_none() {
        return;
    }
    // (kind, option, value, 6D*, measured with it, bound) against the defaults above.
    // Measured: Madgwick 4.34 (9D) 3.33 (6D*), Mahony 7.19 / 3.94, EKF 7.26 / 8.40.
    let cases = [
        (Kind::Madgwick, "rest_bias_tau", 2.0, false, 4.5),
        (Kind::Madgwick, "rest_bias_tau", 2.0, true, 3.5),
        (Kind::Mahony, "rest_bias_tau", 2.0, false, 7.5),
        (Kind::Mahony, "rest_bias_tau", 2.0, true, 4.15),
        (Kind::Ekf, "rest_rate_std", 0.01, false, 7.65),
        (Kind::Ekf, "rest_rate_std", 0.01, true, 8.8),
    ];
    for (kind, name, value, six_d, bound) in cases {
        let (total, incl) = means_with(kind, six_d, &[(name, value)]);
        println!("{kind:?} {name}={value} {}: mean {total:.2} ({incl:.2})", if six_d { "6D*" } else { "9D" });
        assert!(total < bound, "{kind:?} {name}={value} 6D*={six_d}: {total:.2}");
    }
}

#[test]
fn seed_kinds_are_no_worse_than_their_published_references() {
    if broad_dir().is_none() {
        return;
    }
    // shared/data/README.md: Madgwick (Python ahrs, beta 0.041) 7.22, Mahony (BROAD's
    // C code) 10.34, EKF (Python ahrs) 6.27; mean total 9D over the 8 trials.
    // Measured with the defaults: 7.22, 10.31, 5.82.
    for (kind, reference) in [(Kind::Madgwick, 7.22), (Kind::Mahony, 10.34), (Kind::Ekf, 6.27)] {
        let (total, incl) = means(kind, false);
        println!("{kind:?} 9D mean {total:.3} ({incl:.2}), reference {reference}");
        assert!(total < reference + 0.005, "{kind:?}: {total:.3} against {reference}");
    }
}

/// All 14 shared trials (shared/data/README.md lists VQF's scores for each).
const ALL_TRIALS: [&str; 14] =
    ["01_", "03_", "06_", "08_", "11_", "15_", "21_", "24_", "25_", "26_", "28_", "30_", "32_", "34_"];

#[test]
fn robust_leads_vqf_over_all_fourteen_trials() {
    let Some(dir) = broad_dir() else { return };
    // VQF over the 14 trials (shared/data/README.md, reproduced by tools/src/bin/robust_cv.rs
    // with vqf-rs): 9D 2.94 (0.81), 6D* 2.80 (0.81). Measured (docs/ACCURACY.md): 9D 2.23,
    // 6D* 2.77, inclination 0.80 (6D* 2.79 with the rest time constant at 2 s); before the
    // motion bias filter (issue 42) 2.32 / 2.69 / 0.80, before issue 19's changes 2.52 /
    // 2.69 / 0.80. The 6D* bound is VQF's own:
    // the motion bias filter trades 0.1° of it for the 9D error and for simulated gloves,
    // whose 6D error it halves (docs/ACCURACY.md).
    let config = Config::new(Kind::Robust).unwrap();
    let (mut t9, mut t6, mut incl) = (0.0, 0.0, 0.0);
    for prefix in ALL_TRIALS {
        let s9 = scores(&config, &trial(&dir, prefix, true), false);
        let s6 = scores(&config, &trial(&dir, prefix, false), true);
        println!("{prefix} 9D {:.2} ({:.2}) 6D* {:.2}", s9.total, s9.inclination, s6.total);
        t9 += s9.total / 14.0;
        t6 += s6.total / 14.0;
        incl += s9.inclination / 14.0;
    }
    println!("robust over 14: 9D {t9:.3}, 6D* {t6:.3}, inclination {incl:.3}");
    // Regression bounds (measured plus a little), each below VQF's figure.
    assert!(t9 < 2.4, "9D {t9:.3} (VQF 2.94)");
    assert!(t6 < 2.80, "6D* {t6:.3} (VQF 2.80)");
    assert!(incl < 0.81, "inclination {incl:.3} (VQF 0.81)");
}
