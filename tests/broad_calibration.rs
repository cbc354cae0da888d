//! Issue 20 on the shared BROAD recordings: a magnetometer calibration fitted once (from
//! trial 01, an undisturbed slow rotation; every trial was recorded with the same IMU).
//!
//! BROAD's magnetometer readings come calibrated already, so the fit is near the
//! identity; its residual (2.7 %: indoor field gradients, noise) is above the trust
//! rule's 2 %, and applied all the same it makes 9 of the 16 scores below worse (up to
//! 1.5 degrees) and 7 better. The check is that the trust rule turns that fit down, and
//! that it is right to (applying it does make scores worse); the table is printed.
//!
//! Needs ../shared/data/broad beside the repository; ORIENT_SKIP_SHARED_DATA=1 skips.

use orient::filters::calibration::{MagCalibrator, Model, Sensor};
use orient::{Config, Filter, Kind};
use orient_tools::eval::{score, Recording};
use std::path::PathBuf;

fn trial(prefix: &str) -> Option<Recording> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data/broad");
    if !dir.is_dir() {
        if std::env::var_os("ORIENT_SKIP_SHARED_DATA").is_some() {
            return None;
        }
        panic!("{} not found (set ORIENT_SKIP_SHARED_DATA=1 to skip)", dir.display());
    }
    let path = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.file_name().unwrap().to_string_lossy().starts_with(prefix))
        .unwrap_or_else(|| panic!("trial {prefix} missing"));
    Some(Recording::read(&path, true).unwrap())
}

fn total(kind: Kind, rec: &Recording, model: Option<Model>) -> f64 {
    let mut f = Filter::new(&Config::new(kind).unwrap()).unwrap();
    f.set_sensor_model(Sensor::Mag, model).unwrap();
    let q: Vec<_> = rec
        .samples()
        .iter()
        .map(|s| {
            f.update(s).unwrap();
            f.quaternion()
        })
        .collect();
    score(&q, &rec.truth, &rec.movement).total
}

#[test]
fn the_trust_rule_turns_down_a_fit_that_would_make_broad_scores_worse() {
    let Some(source) = trial("01_") else { return };
    let mut cal = MagCalibrator::new();
    for s in source.samples() {
        cal.add(s.mag.unwrap()).unwrap();
    }
    let fit = cal.solve().expect("trial 01 determines an ellipsoid");
    println!(
        "fit from trial 01: field {:.4}, hard iron {:?}, residual {:.4}, coverage {:.2}, trustworthy {}",
        fit.field,
        fit.model.offset,
        fit.residual,
        fit.coverage,
        fit.trustworthy()
    );
    println!("soft iron {:?}", fit.model.matrix);
    let hard_only = Model { offset: fit.model.offset, ..Model::IDENTITY };
    // Near the identity: a hard iron under 1 µT of a 44 µT field.
    assert!(fit.model.offset.norm() < 0.05 * fit.field, "{fit:?}");
    assert!(!fit.trustworthy(), "{fit:?}");
    let mut worse = 0;
    for prefix in ["01_", "06_", "08_", "15_", "24_", "26_", "28_", "32_"] {
        let rec = trial(prefix).unwrap();
        for kind in [Kind::Madgwick, Kind::Robust] {
            let (raw, calibrated) = (total(kind, &rec, None), total(kind, &rec, Some(fit.model)));
            let hard = total(kind, &rec, Some(hard_only));
            println!("{prefix} {kind:?}: total {raw:.3} -> {calibrated:.3} deg, hard iron only {hard:.3}");
            worse += usize::from(calibrated > raw + 0.01);
        }
    }
    assert!(worse > 0, "the untrusted fit made nothing worse: the trust rule is too strict");
}
