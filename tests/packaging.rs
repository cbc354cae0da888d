//! Packaging: scripts/install.sh lays out the libraries, header, pkg-config files and
//! CMake package; the prefix is relocatable; a CMake project finds it with
//! find_package(orient 1 CONFIG REQUIRED) and links both imported targets, while a request
//! for another ABI major is refused; a Makefile-style build finds it with pkg-config, and
//! orient-static.pc links the archive. (scripts/test-release.sh checks the release's
//! per-platform packages the same way.)
#![cfg(not(miri))]

mod common;

use common::native::{check, cross, deps_dir, out_dir, root};
use std::path::Path;
use std::process::Command;

fn run_ok(cmd: &mut Command, what: &str) -> String {
    let out = cmd.output().unwrap_or_else(|e| panic!("{what}: {e}"));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{what} failed:\n{text}{}", String::from_utf8_lossy(&out.stderr));
    text
}

fn install(prefix: &Path) {
    let _ = std::fs::remove_dir_all(prefix);
    let mut cmd = Command::new(root().join("scripts/install.sh"));
    cmd.arg("--prefix").arg(prefix).arg("--lib-dir").arg(deps_dir());
    run_ok(&mut cmd, "install.sh");
}

#[test]
fn installed_prefix_is_complete_relocatable_and_usable_from_cmake_and_pkg_config() {
    if cross() {
        eprintln!("skipped: the CMake and pkg-config consumers are built for this machine");
        return;
    }
    let dir = out_dir("packaging");
    let first = dir.join("staging");
    install(&first);
    let lib = first.join("lib");
    for (link, target) in [("liborient.so", "liborient.so.1"), ("liborient.so.1", "liborient.so.1.1.0")] {
        let t = std::fs::read_link(lib.join(link)).unwrap_or_else(|e| panic!("{link}: {e}"));
        assert_eq!(t, Path::new(target), "{link}");
    }
    for f in [
        "lib/liborient.so.1.1.0",
        "lib/liborient.a",
        "include/orient.h",
        "include/orient.hpp",
        "lib/pkgconfig/orient.pc",
        "lib/pkgconfig/orient-static.pc",
        "lib/cmake/orient/orientConfig.cmake",
        "lib/cmake/orient/orientConfigVersion.cmake",
    ] {
        assert!(first.join(f).exists(), "{f} missing");
    }
    let soname = run_ok(Command::new("readelf").arg("-d").arg(lib.join("liborient.so.1.1.0")), "readelf");
    assert!(soname.contains("Library soname: [liborient.so.1]"), "{soname}");

    // Relocate: move the whole prefix; nothing inside may name the old path.
    let prefix = dir.join("moved");
    let _ = std::fs::remove_dir_all(&prefix);
    std::fs::rename(&first, &prefix).unwrap();

    // CMake consumer: ABI 1 is found; another major, or the crate's 0.x numbering, is not.
    let configure = |build: &Path, request: &str| {
        let _ = std::fs::remove_dir_all(build);
        let mut configure = Command::new("cmake");
        configure
            .arg("-S")
            .arg(root().join("tests/cmake_consumer"))
            .arg("-B")
            .arg(build)
            .arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()))
            .arg(format!("-DORIENT_REQUEST={request}"));
        configure
    };
    for request in ["2", "0.1", "1.99"] {
        let out = configure(&dir.join(format!("cmake-{request}")), request).output().unwrap();
        assert!(!out.status.success(), "find_package(orient {request}) accepted ABI 1");
    }
    let build = dir.join("cmake-build");
    run_ok(&mut configure(&build, "1"), "cmake configure");
    run_ok(Command::new("cmake").arg("--build").arg(&build), "cmake build");
    for exe in ["consumer_shared", "consumer_static", "consumer_cpp"] {
        let out = run_ok(&mut Command::new(build.join(exe)), exe);
        assert!(out.contains("q = ("), "{exe}: {out}");
    }

    // pkg-config consumer.
    let pc = prefix.join("lib/pkgconfig");
    let flags = run_ok(
        Command::new("pkg-config").args(["--cflags", "--libs", "orient"]).env("PKG_CONFIG_PATH", &pc),
        "pkg-config",
    );
    let version = run_ok(
        Command::new("pkg-config").args(["--modversion", "orient"]).env("PKG_CONFIG_PATH", &pc),
        "pkg-config",
    );
    let abi_keyed = format!("1.{}", env!("CARGO_PKG_VERSION").split_once('.').unwrap().1);
    assert_eq!(version.trim(), abi_keyed, "pkg-config version is ABI.MINOR.PATCH");
    let exe = dir.join("consumer_pkgconfig");
    let mut cc = Command::new("cc");
    cc.arg(root().join("tests/cmake_consumer/consumer.c")).arg("-o").arg(&exe).args(flags.split_whitespace());
    check(cc, "cc with pkg-config flags");
    let out = run_ok(Command::new(&exe).env("LD_LIBRARY_PATH", prefix.join("lib")), "pkg-config consumer");
    assert!(out.contains("abi 1"), "{out}");
    let needed = run_ok(Command::new("readelf").arg("-d").arg(&exe), "readelf");
    assert!(needed.contains("liborient.so.1"), "the shared pkg-config build links liborient.so.1");

    // orient-static.pc names the archive, so the program needs no liborient.so.
    let flags = run_ok(
        Command::new("pkg-config").args(["--cflags", "--libs", "orient-static"]).env("PKG_CONFIG_PATH", &pc),
        "pkg-config orient-static",
    );
    assert!(flags.contains("liborient.a"), "{flags}");
    let exe = dir.join("consumer_pkgconfig_static");
    let mut cc = Command::new("cc");
    cc.arg(root().join("tests/cmake_consumer/consumer.c")).arg("-o").arg(&exe).args(flags.split_whitespace());
    check(cc, "cc with orient-static flags");
    let out = run_ok(&mut Command::new(&exe), "static pkg-config consumer");
    assert!(out.contains("abi 1"), "{out}");
    let needed = run_ok(Command::new("readelf").arg("-d").arg(&exe), "readelf");
    assert!(!needed.contains("liborient"), "the static pkg-config build needs no liborient.so:\n{needed}");
}
