//! Builds tests/c/abi_test.c against the shared and the static library and runs it.
//! The C program checks ABI behaviour and replays the golden vectors bit for bit.
#![cfg(not(miri))]

mod common;

use common::native::{check, compiler, link_shared, link_static, out_dir, root, run_checked};

fn build_and_run(name: &str, shared: bool) {
    let dir = out_dir(name);
    let exe = dir.join("abi_test");
    let mut cmd = compiler(false);
    cmd.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg(root().join("tests/c/abi_test.c"))
        .arg("-o")
        .arg(&exe);
    if shared {
        link_shared(&mut cmd, &dir);
    } else {
        link_static(&mut cmd);
    }
    check(cmd, &format!("compiling abi_test.c ({name})"));
    run_checked(&exe, &[common::golden::PATH], &format!("abi_test ({name})"));
}

#[test]
fn c_program_against_the_shared_library() {
    build_and_run("shared", true);
}

#[test]
fn c_program_against_the_static_library() {
    build_and_run("static", false);
}
