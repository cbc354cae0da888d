//! Builds tests/c/abi_test.c against the shared and the static library and runs it.
//! The C program checks ABI behaviour and replays the golden vectors bit for bit.
#![cfg(not(miri))]

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// target/<profile>/deps, where cargo test leaves liborient.so and liborient.a.
fn deps_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    exe.parent().expect("deps dir").to_path_buf()
}

fn compiler() -> cc::Tool {
    cc::Build::new()
        .target(env!("ORIENT_BUILD_TARGET"))
        .host(env!("ORIENT_BUILD_HOST"))
        .opt_level(0)
        .cargo_metadata(false)
        .cargo_warnings(false)
        .try_get_compiler()
        .expect("a C compiler")
}

/// Runs a program the tests built, through ORIENT_TEST_RUNNER when set (for example
/// "qemu-aarch64 -L /usr/aarch64-linux-gnu" for a cross build: binfmt_misc may be absent).
fn run(program: &Path, args: &[&str]) -> std::process::Output {
    let runner = std::env::var("ORIENT_TEST_RUNNER").unwrap_or_default();
    let mut words = runner.split_whitespace();
    let mut cmd = match words.next() {
        Some(first) => {
            let mut c = Command::new(first);
            c.args(words).arg(program);
            c
        }
        None => Command::new(program),
    };
    cmd.args(args).output().unwrap_or_else(|e| panic!("cannot run {}: {e}", program.display()))
}

fn build_and_run(name: &str, link: &dyn Fn(&mut Command, &Path)) {
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&out_dir).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let exe = out_dir.join("abi_test");
    let tool = compiler();
    let mut cmd = tool.to_command();
    cmd.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-ffp-contract=off", "-g"])
        .arg("-I")
        .arg(root.join("include"))
        .arg(root.join("tests/c/abi_test.c"))
        .arg("-o")
        .arg(&exe);
    link(&mut cmd, &out_dir);
    let status = cmd.status().expect("run the C compiler");
    assert!(status.success(), "compiling abi_test.c ({name}) failed: {cmd:?}");
    let output = run(&exe, &[common::golden::PATH]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    print!("{stdout}");
    eprint!("{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success(), "abi_test ({name}) failed");
    let summary = stdout.lines().last().unwrap_or("");
    assert!(summary.ends_with(" 0 failed") && !summary.starts_with("0 passed"), "{summary}");
}

#[test]
fn c_program_against_the_shared_library() {
    let so = deps_dir().join("liborient.so");
    assert!(so.exists(), "{} missing", so.display());
    build_and_run("shared", &|cmd, dir| {
        // The SONAME is liborient.so.1: give the loader that name beside the program.
        std::fs::copy(&so, dir.join("liborient.so.1")).unwrap();
        std::fs::copy(&so, dir.join("liborient.so")).unwrap();
        cmd.arg("-L").arg(dir).arg("-lorient").arg(format!("-Wl,-rpath,{}", dir.display())).arg("-lm");
    });
}

#[test]
fn c_program_against_the_static_library() {
    let a = deps_dir().join("liborient.a");
    assert!(a.exists(), "{} missing", a.display());
    build_and_run("static", &|cmd, _| {
        // What `cargo rustc -- --print native-static-libs` lists for linux-gnu targets.
        cmd.arg(&a).args(["-lgcc_s", "-lutil", "-lrt", "-lpthread", "-lm", "-ldl", "-lc"]);
    });
}
