//! Gives the shared library its SONAME on Linux and tells the tests which C compiler
//! target to use.
fn main() {
    let target = std::env::var("TARGET").unwrap_or_default();
    let host = std::env::var("HOST").unwrap_or_default();
    if target.contains("linux") {
        // The C ABI version (ORIENT_ABI_VERSION), not the crate's 0.x version, names the
        // SONAME: a binary linked against liborient.so.1 keeps working across 0.x releases.
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,liborient.so.1");
    }
    println!("cargo:rustc-env=ORIENT_BUILD_TARGET={target}");
    println!("cargo:rustc-env=ORIENT_BUILD_HOST={host}");
    println!("cargo:rerun-if-changed=build.rs");
}
