//! The examples in every language build and run on the demo recording.
#![cfg(not(miri))]

mod common;

use common::native::{check, command, compiler, cross, deps_dir, link_shared, out_dir, root, run};
use orient::Kind;
use std::process::Command;

const EXCERPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/data/broad_01_excerpt.csv");

fn stdout_of(output: std::process::Output, what: &str) -> String {
    let text = String::from_utf8_lossy(&output.stdout).into_owned();
    print!("{text}");
    eprint!("{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success(), "{what} failed");
    text
}

#[test]
fn c_example_prints_the_orientation() {
    let dir = out_dir("example_c");
    let exe = dir.join("print_orientation");
    let mut cmd = compiler(false);
    cmd.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg(root().join("examples/c/print_orientation.c"))
        .arg("-o")
        .arg(&exe);
    link_shared(&mut cmd, &dir);
    check(cmd, "compiling print_orientation.c");
    let out = stdout_of(run(&exe, &[EXCERPT]), "print_orientation");
    assert!(out.contains("13500 samples; final q = ("), "{out}");
}

#[test]
fn cpp_example_runs_every_filter_side_by_side() {
    let dir = out_dir("example_cpp");
    let exe = dir.join("side_by_side");
    let mut cmd = compiler(true);
    cmd.args(["-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(root().join("bindings/cpp"))
        .arg(root().join("examples/cpp/side_by_side.cpp"))
        .arg("-o")
        .arg(&exe);
    link_shared(&mut cmd, &dir);
    check(cmd, "compiling side_by_side.cpp");
    let out = stdout_of(run(&exe, &[EXCERPT]), "side_by_side");
    assert!(out.contains(&format!("13500 samples, {} filters", orient::Kind::ALL.len())), "{out}");
    for kind in orient::Kind::ALL.map(orient::Kind::name) {
        assert!(out.lines().any(|l| l.starts_with(kind) && l.contains("RMS error")), "{kind}: {out}");
    }
}

/// Issue 20: four sensors at different mountings on one segment, calibrated from a
/// posture, agree on the segment afterwards.
#[test]
fn cpp_rig_calibration_example_finds_the_mountings() {
    let dir = out_dir("example_cpp_rig");
    let exe = dir.join("rig_calibration");
    let mut cmd = compiler(true);
    cmd.args(["-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(root().join("bindings/cpp"))
        .arg(root().join("examples/cpp/rig_calibration.cpp"))
        .arg("-o")
        .arg(&exe);
    link_shared(&mut cmd, &dir);
    check(cmd, "compiling rig_calibration.cpp");
    let out = stdout_of(run(&exe, &[EXCERPT]), "rig_calibration");
    println!("{out}");
    assert!(out.contains("calibrated at t = 2.0"), "{out}");
    let worst: f64 = out
        .lines()
        .find_map(|l| {
            l.strip_prefix("13500 samples; after calibration the sensors disagree on the segment by at most ")
        })
        .and_then(|l| l.trim_end_matches(" deg").parse().ok())
        .unwrap_or_else(|| panic!("{out}"));
    assert!(worst < 1.0, "{out}");
    for k in 0..4 {
        let line =
            out.lines().find(|l| l.starts_with(&format!("sensor {k}: "))).unwrap_or_else(|| panic!("{out}"));
        let err: f64 = line.rsplit("error ").next().unwrap().trim_end_matches(" deg").parse().unwrap();
        assert!(err < 0.5, "{line}");
    }
}

#[test]
fn csharp_console_example_runs_under_mono() {
    if cross() {
        eprintln!("skipped: Mono on this machine cannot load a library built for another target");
        return;
    }
    let dir = out_dir("example_csharp");
    std::fs::copy(deps_dir().join("liborient.so"), dir.join("liborient.so")).unwrap();
    let exe = dir.join("ConsoleExample.exe");
    let mut mcs = Command::new("mcs");
    mcs.args(["-unsafe", "-warnaserror", "-nologo"])
        .arg(format!("-out:{}", exe.display()))
        .arg(root().join("bindings/csharp/Orient.Native.cs"))
        .arg(root().join("bindings/csharp/Orient.cs"))
        .arg(root().join("examples/csharp/ConsoleExample.cs"));
    check(mcs, "mcs ConsoleExample");
    let out = Command::new("mono").arg(&exe).arg(EXCERPT).env("LD_LIBRARY_PATH", &dir).output().unwrap();
    let out = stdout_of(out, "ConsoleExample.exe");
    assert!(out.contains("13500 samples; ENU q = (") && out.contains("alpha "), "{out}");
}

#[test]
fn rust_quickstart_example_runs() {
    let bin = deps_dir().parent().unwrap().join("examples/quickstart");
    if !bin.exists() {
        let status = Command::new(env!("CARGO"))
            .args(["build", "--quiet", "--example", "quickstart", "--manifest-path"])
            .arg(root().join("Cargo.toml"))
            .status()
            .unwrap();
        assert!(status.success());
    }
    let out = stdout_of(command(&bin).output().unwrap(), "quickstart");
    assert_eq!(out.lines().filter(|l| l.contains("error vs truth")).count(), Kind::ALL.len(), "{out}");
}
