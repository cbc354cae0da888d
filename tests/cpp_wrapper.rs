//! Builds tests/cpp/wrapper_test.cpp against bindings/cpp/orient.hpp, with and without
//! exceptions, and runs it (golden vectors bit for bit, RAII, error paths).
#![cfg(not(miri))]

mod common;

use common::native::{check, compiler, link_shared, out_dir, root, run_checked};

fn build_and_run(name: &str, exceptions: bool) {
    let dir = out_dir(name);
    let exe = dir.join("wrapper_test");
    let mut cmd = compiler(true);
    cmd.args(["-std=c++17", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(root().join("bindings/cpp"))
        .arg(root().join("tests/cpp/wrapper_test.cpp"))
        .arg("-o")
        .arg(&exe);
    if !exceptions {
        cmd.arg("-fno-exceptions");
    }
    link_shared(&mut cmd, &dir);
    check(cmd, &format!("compiling wrapper_test.cpp ({name})"));
    let out = run_checked(&exe, &[common::golden::PATH], name);
    assert!(out.contains("golden: "), "{out}");
}

#[test]
fn cpp_wrapper_with_exceptions() {
    build_and_run("cpp_exceptions", true);
}

#[test]
fn cpp_wrapper_without_exceptions() {
    build_and_run("cpp_no_exceptions", false);
}
