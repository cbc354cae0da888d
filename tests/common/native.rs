//! Building and running programs in other languages against the library, for the
//! tests: where cargo test left liborient.so/.a, the C/C++ compiler for the target, and
//! a runner that starts foreign binaries through qemu (or ORIENT_TEST_RUNNER).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// target/<profile>/deps, where cargo test leaves liborient.so and liborient.a.
pub fn deps_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    exe.parent().expect("deps dir").to_path_buf()
}

pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh directory for one test's build products.
pub fn out_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The C (or, with `cpp`, C++) compiler for the target, no optimisation.
pub fn compiler(cpp: bool) -> Command {
    let tool = cc::Build::new()
        .target(env!("ORIENT_BUILD_TARGET"))
        .host(env!("ORIENT_BUILD_HOST"))
        .cpp(cpp)
        .opt_level(0)
        .cargo_metadata(false)
        .cargo_warnings(false)
        .try_get_compiler()
        .expect("a C/C++ compiler");
    let mut cmd = tool.to_command();
    cmd.arg("-I").arg(root().join("include")).arg("-ffp-contract=off").arg("-g");
    cmd
}

/// Copies liborient.so into `dir` (also as liborient.so.1, its SONAME) and links
/// against it with an rpath.
pub fn link_shared(cmd: &mut Command, dir: &Path) {
    let so = deps_dir().join("liborient.so");
    assert!(so.exists(), "{} missing", so.display());
    std::fs::copy(&so, dir.join("liborient.so.1")).unwrap();
    std::fs::copy(&so, dir.join("liborient.so")).unwrap();
    cmd.arg("-L").arg(dir).arg("-lorient").arg(format!("-Wl,-rpath,{}", dir.display())).arg("-lm");
}

/// Links liborient.a and what `cargo rustc -- --print native-static-libs` lists for
/// linux-gnu targets.
pub fn link_static(cmd: &mut Command) {
    let a = deps_dir().join("liborient.a");
    assert!(a.exists(), "{} missing", a.display());
    cmd.arg(&a).args(["-lgcc_s", "-lutil", "-lrt", "-lpthread", "-lm", "-ldl", "-lc"]);
}

/// Runs `cmd`, failing the test with its output when it fails.
pub fn check(mut cmd: Command, what: &str) {
    let out = cmd.output().unwrap_or_else(|e| panic!("{what}: cannot start: {e}"));
    assert!(
        out.status.success(),
        "{what} failed: {cmd:?}\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// True when the tests run for another target than the machine's (under qemu).
pub fn cross() -> bool {
    let (target, host) = (env!("ORIENT_BUILD_TARGET"), env!("ORIENT_BUILD_HOST"));
    target != host
}

/// The emulator command for a foreign target: ORIENT_TEST_RUNNER when set, else qemu
/// for the Linux board targets of .cargo/config.toml.
fn runner() -> Option<String> {
    if let Ok(r) = std::env::var("ORIENT_TEST_RUNNER") {
        return (!r.trim().is_empty()).then_some(r);
    }
    if !cross() {
        return None;
    }
    match env!("ORIENT_BUILD_TARGET") {
        "aarch64-unknown-linux-gnu" => Some("qemu-aarch64 -L /usr/aarch64-linux-gnu".into()),
        "armv7-unknown-linux-gnueabihf" => Some("qemu-arm -L /usr/arm-linux-gnueabihf".into()),
        t => panic!("no emulator known for {t}: set ORIENT_TEST_RUNNER"),
    }
}

/// A command that starts a program built for the target (through the emulator when
/// cross-testing: binfmt_misc may be absent).
pub fn command(program: &Path) -> Command {
    match runner() {
        Some(r) => {
            let mut words = r.split_whitespace();
            let mut c = Command::new(words.next().unwrap());
            c.args(words).arg(program);
            c
        }
        None => Command::new(program),
    }
}

/// Runs a program the tests built, through the emulator when cross-testing.
pub fn run(program: &Path, args: &[&str]) -> Output {
    command(program).args(args).output().unwrap_or_else(|e| panic!("cannot run {}: {e}", program.display()))
}

/// Runs a test program and requires a zero exit and a closing "N passed, 0 failed" line.
pub fn run_checked(program: &Path, args: &[&str], what: &str) -> String {
    let output = run(program, args);
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    print!("{stdout}");
    eprint!("{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success(), "{what} failed");
    let summary = stdout.lines().last().unwrap_or("");
    assert!(summary.ends_with(" 0 failed") && !summary.starts_with("0 passed"), "{what}: {summary}");
    stdout
}
