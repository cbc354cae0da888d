//! Gives the shared library its SONAME on Linux, links it for 16 KB pages on Android,
//! and tells the tests which C compiler target to use.
fn main() {
    let target = std::env::var("TARGET").unwrap_or_default();
    let host = std::env::var("HOST").unwrap_or_default();
    if target.contains("android") {
        // An APK carries only lib*.so files and apps load liborient.so by that name, so no
        // version suffix. Android 15 devices may use 16 KB pages, and stores require apps
        // targeting them to align every LOAD segment to 16 KB (the linker's default for
        // 32-bit ARM and older NDKs is 4 KB). scripts/check-page-size.py checks the result.
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,liborient.so");
        println!("cargo:rustc-cdylib-link-arg=-Wl,-z,max-page-size=16384");
    } else if target.contains("linux") {
        // The C ABI version (ORIENT_ABI_VERSION), not the crate's 0.x version, names the
        // SONAME: a binary linked against liborient.so.1 keeps working across 0.x releases.
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,liborient.so.1");
    }
    println!("cargo:rustc-env=ORIENT_BUILD_TARGET={target}");
    println!("cargo:rustc-env=ORIENT_BUILD_HOST={host}");
    println!("cargo:rerun-if-changed=build.rs");
}
