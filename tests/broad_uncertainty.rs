//! Issue 20: is the heading uncertainty (`Filter::uncertainty`) honest on real data? On
//! the shared BROAD recordings (9D, optical truth), the fraction of scored rows whose
//! heading error is within 2σ and 3σ of the reported uncertainty, per trial and over all.
//! A consistent σ covers about 95 % and 99.7 % of a Gaussian error; a σ that covers
//! everything by being huge is no use either, so its median is printed beside the RMS
//! error. The robust kind's defaults come from datasheets and VQF (src/filters/robust.rs),
//! none fitted to these recordings.
//!
//! Needs ../shared/data/broad beside the repository; ORIENT_SKIP_SHARED_DATA=1 skips.

use orient::{Config, Filter, Kind};
use orient_tools::eval::{csv_files, error_angles, Recording};
use std::path::PathBuf;

struct Coverage {
    rows: usize,
    within2: usize,
    within3: usize,
    sq_error: f64,
    sigmas: Vec<f64>,
}

fn coverage(kind: Kind, rec: &Recording) -> Coverage {
    let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
    let mut c = Coverage { rows: 0, within2: 0, within3: 0, sq_error: 0.0, sigmas: Vec::new() };
    for (i, s) in rec.samples().iter().enumerate() {
        f.update(s).unwrap();
        if !rec.movement[i] {
            continue;
        }
        let sigma = f.uncertainty().heading.expect("a heading uncertainty");
        let (_, heading, _) = error_angles(f.quaternion(), rec.truth[i]);
        if !heading.is_finite() {
            continue; // a row without optical truth
        }
        c.rows += 1;
        c.within2 += usize::from(heading <= 2.0 * sigma);
        c.within3 += usize::from(heading <= 3.0 * sigma);
        c.sq_error += heading * heading;
        c.sigmas.push(sigma);
    }
    c
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

#[test]
fn the_heading_uncertainty_covers_the_heading_error_on_broad() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data/broad");
    if !dir.is_dir() {
        if std::env::var_os("ORIENT_SKIP_SHARED_DATA").is_some() {
            return;
        }
        panic!("{} not found (set ORIENT_SKIP_SHARED_DATA=1 to skip)", dir.display());
    }
    for kind in [Kind::Robust, Kind::Ekf] {
        let (mut rows, mut w2, mut w3, mut sigmas, mut ratios) = (0, 0, 0, Vec::new(), Vec::new());
        println!("{kind:?}: trial, rows, RMS heading error (deg), median sigma (deg), ratio, within 2 sigma, within 3 sigma");
        for path in csv_files(&dir).unwrap() {
            let rec = Recording::read(&path, true).unwrap();
            let mut c = coverage(kind, &rec);
            let name = path.file_name().unwrap().to_string_lossy().chars().take(3).collect::<String>();
            let (rms, med) = ((c.sq_error / c.rows as f64).sqrt(), median(&mut c.sigmas));
            ratios.push((name.clone(), rms / med));
            println!(
                "  {name} {:6} {:6.2} {:6.2} {:5.2} {:6.1}% {:6.1}%",
                c.rows,
                rms.to_degrees(),
                med.to_degrees(),
                rms / med,
                100.0 * c.within2 as f64 / c.rows as f64,
                100.0 * c.within3 as f64 / c.rows as f64
            );
            sigmas.extend_from_slice(&c.sigmas);
            rows += c.rows;
            w2 += c.within2;
            w3 += c.within3;
        }
        let (f2, f3) = (w2 as f64 / rows as f64, w3 as f64 / rows as f64);
        println!("  all {rows} {:.1}% {:.1}%", 100.0 * f2, 100.0 * f3);
        if kind == Kind::Robust {
            // Issue 40 class 11: sigma must follow the error, trial by trial: the RMS error
            // within 0.5-2 times the median sigma on every trial (measured 0.59-1.69; before
            // the deviation and turning terms, 0.41-1.98 with a median of 2.0-2.1 deg on
            // every trial), and 2 sigma covering near its Gaussian 95 % over all (measured
            // 95.4 %, 3 sigma 99.7 %; 94.3 % before the innovation evidence, eq. H5).
            for (name, r) in &ratios {
                assert!((0.5..=2.0).contains(r), "trial {name}: RMS error / median sigma = {r}");
            }
            assert!(
                (0.90..=0.98).contains(&f2) && f3 > 0.97,
                "robust's sigma covers {f2} (2 sigma), {f3} (3 sigma)"
            );
            let mut all = sigmas;
            let m = median(&mut all).to_degrees();
            assert!(m < 3.0, "robust's median sigma {m} deg is too large to be of use");
        } else {
            // The EKF's covariance is the paper's model: measured 87.2 % and 91.1 %, over-
            // confident in fast combined motion (21) and near a stationary magnet (28).
            assert!(f2 > 0.82 && f3 > 0.87, "the EKF's sigma covers {f2} (2 sigma), {f3} (3 sigma)");
        }
    }
}
