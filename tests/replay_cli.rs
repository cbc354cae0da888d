//! The replay tool's interface: other scripts depend on it.
#![cfg(not(miri))]

mod common;

use std::path::PathBuf;
use std::process::{Command, Output};

/// target/[<target>/]debug/replay, from the tools crate (orient-tools). `cargo test` does
/// not build another package's binaries for this package's tests, so build it here, once
/// per test process, with cargo test's own profile: a no-op when `cargo test` at the root
/// built the tools (their tests need the binary), and never a second, unoptimised build
/// of every dependency.
fn replay() -> PathBuf {
    static BUILT: std::sync::Once = std::sync::Once::new();
    let exe = std::env::current_exe().unwrap();
    let bin = exe.parent().unwrap().parent().unwrap().join("replay");
    BUILT.call_once(|| {
        let mut cargo = Command::new(env!("CARGO"));
        cargo.args(["build", "--quiet", "--profile", "test", "-p", "orient-tools", "--bin", "replay"]);
        cargo.arg("--manifest-path");
        cargo.arg(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"));
        if common::native::cross() {
            cargo.args(["--target", env!("ORIENT_BUILD_TARGET")]);
        }
        assert!(cargo.status().unwrap().success(), "cargo build -p orient-tools --bin replay failed");
    });
    assert!(bin.exists(), "{} not built", bin.display());
    bin
}

fn run(args: &[&str]) -> Output {
    common::native::command(&replay()).args(args).output().unwrap()
}

fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("replay_cli");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

const EXCERPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/data/broad_01_excerpt.csv");

#[test]
fn replays_the_excerpt_writes_one_row_per_input_row_and_scores_it() {
    let out = tmp("excerpt.csv");
    let o = run(&["--filter", "madgwick", "--out", out.to_str().unwrap(), EXCERPT]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("BROAD RMSE [deg]:") && stdout.contains("inclination"), "{stdout}");
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,qw,qx,qy,qz"));
    assert_eq!(lines.count(), 13500);
}

#[test]
fn no_mag_prints_the_offset_removed_score_and_frames_are_accepted() {
    let o = run(&["--filter", "madgwick", "--no-mag", "--frame", "ned", "--set", "beta_imu=0.1", EXCERPT]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}");
    assert!(stdout.contains("6D, frame ned") && stdout.contains("heading offset"), "{stdout}");
}

fn expect_exit_2(csv: &str, needle: &str) {
    let path = tmp(&format!("bad_{}.csv", needle.len()));
    std::fs::write(&path, csv).unwrap();
    let o = run(&["--filter", "madgwick", path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(needle), "expected '{needle}' in: {stderr}");
}

#[test]
fn malformed_input_names_line_and_column_and_exits_2() {
    let header = "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n";
    expect_exit_2(
        "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,9.8\n",
        "line 1, column 'mag_x': missing column",
    );
    expect_exit_2(
        &format!("{header}0,0,0,0,0,0,9.8,1,2,3\n0.01,0,x1,0,0,0,9.8,1,2,3\n"),
        "line 3, column 'gyr_y'",
    );
    expect_exit_2(
        &format!("{header}0,0,0,0,0,0,9.8,1,2,3\n0,0,0,0,0,0,9.8,1,2,3\n"),
        "line 3, column 't': time must increase",
    );
}

#[test]
fn bad_arguments_exit_2() {
    for args in [
        &["--filter", "kalman", EXCERPT][..],
        &["--filter", "madgwick", "--set", "nope=1", EXCERPT],
        &[EXCERPT],
    ] {
        assert_eq!(run(args).status.code(), Some(2), "{args:?}");
    }
    let o = run(&["--filter", "gmvdk", "--set", "slope_muk=-1", EXCERPT]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("out of range"));
}

#[test]
fn every_kind_replays_and_writes_its_diagnostics_as_extra_columns() {
    let expected = [
        ("madgwick", "t,qw,qx,qy,qz"),
        ("mahony", "t,qw,qx,qy,qz,bias_x,bias_y,bias_z"),
        ("complementary", "t,qw,qx,qy,qz,bias_x,bias_y,bias_z,rest"),
        ("ekf", "t,qw,qx,qy,qz,bias_x,bias_y,bias_z,rate_x,rate_y,rate_z,p0,p1,p2,p3,p4,p5,p6,p7,p8,p9"),
        ("gmvdk", "t,qw,qx,qy,qz,bias_x,bias_y,bias_z,alpha,mu_ka,mu_km,mu_k"),
    ];
    for (kind, header) in expected {
        let out = tmp(&format!("{kind}.csv"));
        let o = run(&["--filter", kind, "--out", out.to_str().unwrap(), EXCERPT]);
        assert!(o.status.success(), "{kind}: {}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(&out).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some(header), "{kind}");
        let last: Vec<f64> = lines.last().unwrap().split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(last.len(), header.split(',').count());
        assert!(last.iter().all(|v| v.is_finite()), "{kind}: {last:?}");
    }
}

#[test]
fn a_closed_standard_output_ends_the_tool_quietly() {
    // The reading end closed before the tool writes anything, as `| head -0` would.
    let mut child = common::native::command(&replay())
        .args(["--filter", "robust,madgwick", EXCERPT])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{stderr}");
    assert!(stderr.is_empty(), "expected no message, got: {stderr}");
}

#[test]
fn several_filters_replay_in_turn_and_draw_one_svg() {
    let svg = tmp("several.svg");
    let o = run(&["--filter", "robust,madgwick", "--filter", "ekf", "--svg", svg.to_str().unwrap(), EXCERPT]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    for kind in ["robust 9D", "madgwick 9D", "ekf 9D"] {
        assert!(stdout.contains(kind), "{kind}: {stdout}");
    }
    assert_eq!(stdout.matches("BROAD RMSE [deg]:").count(), 3, "{stdout}");
    assert!(stdout.contains(&format!("svg: {}", svg.display())), "{stdout}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
    for kind in ["robust", "madgwick", "ekf"] {
        for series in ["total", "heading", "inclination", "rest", "mag unused", "accel unused", "gap"] {
            assert!(text.contains(&format!("\n{kind} {series}\n")), "no label '{kind} {series}'");
        }
    }
    // --out takes one filter; --svg needs ground truth.
    let out = tmp("two.csv");
    assert_eq!(
        run(&["--filter", "robust,madgwick", "--out", out.to_str().unwrap(), EXCERPT]).status.code(),
        Some(2)
    );
    let no_truth = tmp("no_truth.csv");
    std::fs::write(&no_truth, "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,9.8\n0.01,0,0,0,0,0,9.8\n")
        .unwrap();
    let o = run(&[
        "--filter",
        "madgwick",
        "--no-mag",
        "--svg",
        svg.to_str().unwrap(),
        no_truth.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no ground truth"));
}

#[test]
fn offline_smooths_with_the_offline_defaults_and_writes_what_the_smoother_gives() {
    let out = tmp("offline.csv");
    let svg = tmp("offline.svg");
    let o = run(&["--offline", "--out", out.to_str().unwrap(), "--svg", svg.to_str().unwrap(), EXCERPT]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("robust offline 9D, frame enu, tau_mag 27 s, 13500 samples"), "{stdout}");
    // orient_smooth_memory(13500) = 8 * 13500 + 32768.
    assert!(stdout.contains("at most 140768 bytes allocated"), "{stdout}");
    assert_eq!(stdout.matches("BROAD RMSE [deg]:").count(), 1, "{stdout}");

    // Every row is the library's smoothed orientation for that sample, bit for bit.
    let rec = orient_tools::eval::Recording::read(std::path::Path::new(EXCERPT), true).unwrap();
    let expected = orient::offline::smooth(&orient::offline::config(), &rec.samples()).unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,qw,qx,qy,qz"));
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), expected.len());
    for (i, (row, q)) in rows.iter().zip(&expected).enumerate() {
        assert_eq!(row[0], rec.t[i]);
        assert_eq!(row[1..], [q.w, q.x, q.y, q.z], "row {i}");
    }

    // One series, no lanes: the smoother reports no flags or rest.
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("\nrobust offline total\n"), "no total line for the smoothed run");
    assert!(!text.contains("offline rest") && !text.contains("mag unused"), "a smoothed run has no lanes");
}

#[test]
fn offline_takes_any_kind_and_its_settings_and_lowers_the_inclination_error() {
    let causal = run(&["--filter", "robust", EXCERPT]);
    let o = run(&["--offline", "--filter", "robust,madgwick", "--set", "tau_mag=9", EXCERPT]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("robust offline 9D, frame enu, tau_mag 9 s"), "{stdout}");
    assert!(stdout.contains("madgwick offline 9D, frame enu, 13500 samples"), "{stdout}");
    let inclination = |text: &str| -> f64 {
        let line = text.lines().find(|l| l.starts_with("BROAD RMSE")).unwrap();
        let words: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(words[7], "inclination", "{line}");
        words[8].parse().unwrap()
    };
    let (c, s) = (inclination(&String::from_utf8_lossy(&causal.stdout)), inclination(&stdout));
    // The same kind and settings: the smoother brings every sample's future gravity
    // direction to it (measured 0.34 against 0.42). The heading is another matter on this
    // trial (docs/ACCURACY.md, "Offline mode").
    assert!(s < c, "offline inclination {s} against causal {c}");
}

#[test]
fn offline_names_the_sample_it_refuses_and_exits_2() {
    let path = tmp("offline_refused.csv");
    std::fs::write(
        &path,
        "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n\
         0,0,0,0,0,0,9.8,0,20,-40\n0.01,20000,0,0,0,0,9.8,0,20,-40\n0.02,0,0,0,0,0,9.8,0,20,-40\n",
    )
    .unwrap();
    let o = run(&["--offline", path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("row 1 (line 3) is refused"), "{stderr}");
}
