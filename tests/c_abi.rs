//! Builds tests/c/abi_test.c against the shared and the static library and runs it.
//! The C program checks ABI behaviour and replays the golden vectors bit for bit.
#![cfg(not(miri))]

mod common;

use common::native::{check, compiler, cross, link_shared, link_static, out_dir, root, run_checked};
use std::path::PathBuf;
use std::process::Command;

fn build(name: &str, shared: bool, extra: &[&str]) -> PathBuf {
    let dir = out_dir(name);
    let exe = dir.join("abi_test");
    let mut cmd = compiler(false);
    cmd.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .args(extra)
        .arg(root().join("tests/c/abi_test.c"))
        .arg("-o")
        .arg(&exe);
    if shared {
        link_shared(&mut cmd, &dir);
    } else {
        link_static(&mut cmd);
    }
    check(cmd, &format!("compiling abi_test.c ({name})"));
    exe
}

fn build_and_run(name: &str, shared: bool) {
    let exe = build(name, shared, &[]);
    run_checked(&exe, &[common::golden::PATH], &format!("abi_test ({name})"));
}

/// The C test under AddressSanitizer and UndefinedBehaviorSanitizer (without its
/// deliberate use of a freed handle, which a sanitizer rightly reports).
#[test]
fn c_program_under_address_and_undefined_behavior_sanitizers() {
    if cross() {
        eprintln!("skipped under emulation");
        return;
    }
    let exe = build(
        "asan",
        true,
        &["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-DORIENT_TEST_NO_USE_AFTER_FREE"],
    );
    let out = Command::new(&exe)
        .arg(common::golden::PATH)
        .env("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=0")
        .env("UBSAN_OPTIONS", "print_stacktrace=1")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !stderr.contains("ERROR: "), "sanitizers report:\n{stdout}{stderr}");
    assert!(stdout.lines().last().unwrap_or("").ends_with(" 0 failed"), "{stdout}");
}

/// The C test under valgrind memcheck: no invalid access, no leak.
#[test]
fn c_program_under_valgrind_memcheck() {
    if cross() {
        eprintln!("skipped under emulation");
        return;
    }
    let exe = build("valgrind", true, &["-DORIENT_TEST_NO_USE_AFTER_FREE"]);
    let out = Command::new("valgrind")
        // valgrind 3.19 (Debian 12) cannot decode every AVX instruction of the wide path
        // (src/isa.rs); memory safety does not depend on the encoding.
        .env("ORIENT_ISA", "baseline")
        .args(["--error-exitcode=99", "--leak-check=full", "--errors-for-leak-kinds=definite,indirect", "-q"])
        .arg(&exe)
        .arg(common::golden::PATH)
        .output()
        .expect("valgrind (scripts/setup-debian.sh installs it)");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "valgrind reports (exit {:?}):\n{stderr}", out.status.code());
    assert!(stdout.lines().last().unwrap_or("").ends_with(" 0 failed"), "{stdout}");
}

#[test]
fn c_program_against_the_shared_library() {
    build_and_run("shared", true);
}

#[test]
fn c_program_against_the_static_library() {
    build_and_run("static", false);
}
