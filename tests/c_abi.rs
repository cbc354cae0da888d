//! Builds tests/c/abi_test.c against the shared and the static library and runs it.
//! The C program checks ABI behaviour and replays the golden vectors bit for bit.
#![cfg(not(miri))]

mod common;

use common::native::{
    check, compiler, cross, deps_dir, link_shared, link_static, out_dir, root, run_checked,
};
use std::path::{Path, PathBuf};
use std::process::Command;

/// How a test program reaches the library.
#[derive(Clone, Copy)]
enum Link {
    Shared,
    Static,
    /// Not linked: the program loads it with dlopen.
    Dlopen,
}

/// Compiles `tests/c/{program}.c` into its own directory for test `name`.
fn build(program: &str, name: &str, link: Link, extra: &[&str]) -> PathBuf {
    let dir = out_dir(name);
    let exe = dir.join(program);
    let mut cmd = compiler(false);
    cmd.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .args(extra)
        .arg(root().join(format!("tests/c/{program}.c")))
        .arg("-o")
        .arg(&exe);
    match link {
        Link::Shared => link_shared(&mut cmd, &dir),
        Link::Static => link_static(&mut cmd),
        Link::Dlopen => {
            cmd.arg("-ldl");
        }
    }
    check(cmd, &format!("compiling {program}.c ({name})"));
    exe
}

fn build_and_run(name: &str, link: Link) {
    let exe = build("abi_test", name, link, &[]);
    run_checked(&exe, &[common::golden::PATH], &format!("abi_test ({name})"));
}

/// The C test under AddressSanitizer and UndefinedBehaviorSanitizer, its calls with
/// freed and forged handles included.
#[test]
fn c_program_under_address_and_undefined_behavior_sanitizers() {
    if cross() {
        eprintln!("skipped under emulation");
        return;
    }
    let exe = build(
        "abi_test",
        "asan",
        Link::Shared,
        &["-fsanitize=address,undefined", "-fno-sanitize-recover=all"],
    );
    let out = Command::new(&exe)
        .arg(common::golden::PATH)
        // A request no address space holds returns NULL (the library's OUT_OF_MEMORY
        // check), as the system allocator's does, instead of stopping the program.
        .env("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=0:allocator_may_return_null=1")
        .env("UBSAN_OPTIONS", "print_stacktrace=1")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && !stderr.contains("ERROR: "), "sanitizers report:\n{stdout}{stderr}");
    assert!(stdout.lines().last().unwrap_or("").ends_with(" 0 failed"), "{stdout}");
}

/// The C test under valgrind memcheck: no invalid access (its calls with freed and
/// forged handles included: the library does not read them), no leak.
#[test]
fn c_program_under_valgrind_memcheck() {
    if cross() {
        eprintln!("skipped under emulation");
        return;
    }
    let exe = build("abi_test", "valgrind", Link::Shared, &[]);
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

/// Bytes valgrind reports in use at exit after `cycles` dlopen/use/dlclose cycles of
/// the shared library (no invalid access allowed).
fn in_use_after_load_cycles(exe: &Path, so: &Path, cycles: u32) -> u64 {
    let out = Command::new("valgrind")
        .env("ORIENT_ISA", "baseline")
        .args(["--error-exitcode=99", "--leak-check=full"])
        .arg(exe)
        .arg(so)
        .arg(cycles.to_string())
        .output()
        .expect("valgrind (scripts/setup-debian.sh installs it)");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "dlopen_test {cycles} (exit {:?}):\n{stderr}", out.status.code());
    let line = stderr.lines().find(|l| l.contains("in use at exit:")).unwrap_or_else(|| panic!("{stderr}"));
    let bytes = line.split("in use at exit:").nth(1).and_then(|r| r.split_whitespace().next());
    bytes.and_then(|b| b.replace(',', "").parse().ok()).unwrap_or_else(|| panic!("{line}"))
}

/// Loading, using and unloading the library leaves nothing behind: the memory in use at
/// exit is the same after 1 and after 6 cycles (it was 15.4 KB more per cycle while the
/// parameter strings were built on the heap).
#[test]
fn load_and_unload_cycles_leave_no_memory_behind() {
    if cross() {
        eprintln!("skipped under emulation");
        return;
    }
    let exe = build("dlopen_test", "dlopen", Link::Dlopen, &[]);
    let so = exe.with_file_name("liborient.so");
    std::fs::copy(deps_dir().join("liborient.so"), &so).unwrap();
    let once = in_use_after_load_cycles(&exe, &so, 1);
    let six = in_use_after_load_cycles(&exe, &so, 6);
    assert_eq!(six, once, "each load/unload cycle leaves {} bytes behind", (six - once) / 5);
}

/// orient_smooth_arrays with the address space limited below what it needs returns
/// ORIENT_STATUS_OUT_OF_MEMORY and leaves the output unwritten (it aborted the host
/// with SIGABRT before: "memory allocation of ... bytes failed").
#[test]
#[cfg(target_os = "linux")]
fn smoothing_out_of_memory_is_a_status_not_an_abort() {
    if cross() {
        eprintln!("skipped under emulation");
        return;
    }
    let exe = build("smooth_oom", "smooth_oom", Link::Shared, &["-std=gnu99"]);
    let out = common::native::run(&exe, &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && stdout.trim_end().ends_with("smooth_oom: 0 failed"),
        "smooth_oom ({:?}):\n{stdout}{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn c_program_against_the_shared_library() {
    build_and_run("shared", Link::Shared);
}

#[test]
fn c_program_against_the_static_library() {
    build_and_run("static", Link::Static);
}
