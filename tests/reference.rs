//! Agreement with an independent implementation of Madgwick's paper: reference outputs
//! from the Python `ahrs` package (tests/reference/ahrs_madgwick.py) on a recorded
//! BROAD sequence, within 1e-9 rad per sample.

use orient::{Config, Filter, Frame, Init, Kind, Quat};
use orient_tools::eval::Recording;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The initial quaternion from the header and the reference quaternions.
fn reference(name: &str) -> (Quat, Vec<Quat>) {
    let text = std::fs::read_to_string(root().join("tests/reference").join(name)).unwrap();
    let mut q0 = None;
    let mut out = Vec::new();
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("# q0 ") {
            let v: Vec<f64> = rest.split(' ').map(|s| s.parse().unwrap()).collect();
            q0 = Some(Quat::new(v[0], v[1], v[2], v[3]));
        } else if line.starts_with('#') || line.starts_with("qw") {
            continue;
        } else {
            let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
            out.push(Quat::new(v[0], v[1], v[2], v[3]));
        }
    }
    (q0.expect("q0 header line"), out)
}

fn compare(name: &str, use_mag: bool) -> f64 {
    let (q0, expected) = reference(name);
    let rec = Recording::read(&root().join("examples/data/broad_01_excerpt.csv"), use_mag).unwrap();
    let mut config = Config::new(Kind::Madgwick).unwrap();
    config.frame = Frame::Nwu;
    config.init = Init::Given(q0);
    // The reference files were made with the paper's β (0.033 MARG, 0.041 IMU).
    config.set_param(orient::filters::params::id::MADGWICK_BETA_MARG, 0.033).unwrap();
    let mut f = Filter::new(&config).unwrap();
    let mut worst: f64 = 0.0;
    for (i, (s, want)) in rec.samples().iter().zip(&expected).enumerate() {
        f.update(s).unwrap();
        let err = f.quaternion().angle_to(*want);
        assert!(err <= 1e-9, "{name}: sample {i} differs by {err} rad");
        worst = worst.max(err);
    }
    assert_eq!(expected.len(), 6000);
    worst
}

#[test]
fn madgwick_marg_matches_ahrs_within_1e9_rad() {
    let worst = compare("ahrs_madgwick_marg.csv", true);
    println!("MARG: largest difference {worst:e} rad");
}

#[test]
fn madgwick_imu_matches_ahrs_within_1e9_rad() {
    let worst = compare("ahrs_madgwick_imu.csv", false);
    println!("IMU: largest difference {worst:e} rad");
}
