//! The C# binding: the committed P/Invoke layer is what scripts/gen-csharp.py generates
//! from include/orient.h (and the generator follows header changes and refuses what
//! IL2CPP cannot pass), its declarations match the header, its wrapper replays the
//! golden vectors bit for bit under Mono, and the Unity scripts compile against a stub
//! of UnityEngine. Needs Mono's mcs and mono (scripts/setup-debian.sh installs them).
#![cfg(not(miri))]

mod common;

use common::native::{check, cross, deps_dir, out_dir, root};
use std::collections::BTreeMap;
use std::process::Command;

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The text without /* */ and // comments or preprocessor lines.
fn code_only(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(start) = rest.find("/*") {
        out.push_str(&rest[..start]);
        rest = rest[start..].find("*/").map_or("", |end| &rest[start + end + 2..]);
    }
    out.push_str(rest);
    out.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .filter(|l| !l.trim_start().starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Function name -> parameter count, from C or C# declarations (joined over lines).
fn functions(text: &str, marker: &str) -> BTreeMap<String, usize> {
    let flat = code_only(text).split_whitespace().collect::<Vec<_>>().join(" ");
    let mut out = BTreeMap::new();
    for piece in flat.split(';') {
        if !piece.contains(marker) {
            continue;
        }
        let Some(open) = piece.find("orient_") else { continue };
        let rest = &piece[open..];
        let Some(paren) = rest.find('(') else { continue };
        let name = rest[..paren].trim().to_string();
        let args = rest[paren + 1..].rsplit_once(')').map(|(a, _)| a.trim()).unwrap_or("");
        let count = if args.is_empty() || args == "void" { 0 } else { args.split(',').count() };
        out.insert(name, count);
    }
    out
}

fn camel(screaming: &str) -> String {
    screaming
        .split('_')
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_ascii_uppercase().to_string() + &c.as_str().to_ascii_lowercase())
                .unwrap_or_default()
        })
        .collect()
}

#[test]
fn csharp_declarations_match_the_header() {
    let header = read("include/orient.h");
    let cs = read("bindings/csharp/Orient.Native.cs");

    let c_fns = functions(&header, "orient_");
    let cs_fns = functions(&cs, "static extern");
    assert!(c_fns.len() >= 31, "the header parse found too few functions: {c_fns:?}");
    assert_eq!(
        c_fns, cs_fns,
        "functions (name -> parameter count) differ between orient.h and Orient.Native.cs"
    );

    // iOS and Android players link the static liborient.a (the only library the Unity
    // package ships for them), which Unity calls through "__Internal"; the Editor and the
    // desktop players load the shared library by name.
    let internal = concat!(
        "#if (UNITY_IOS || UNITY_ANDROID || UNITY_WEBGL) && !UNITY_EDITOR\n",
        "        public const string Library = \"__Internal\";\n",
        "#else\n",
        "        public const string Library = \"orient\";\n",
        "#endif",
    );
    assert!(
        cs.contains(internal),
        "Orient.Native.cs must pick __Internal exactly where the library is static"
    );

    // Every #define ORIENT_X N is `public const uint X = N;` (camel-cased).
    let mut missing = Vec::new();
    for line in header.lines().filter_map(|l| l.strip_prefix("#define ORIENT_")) {
        let mut parts = line.split_whitespace();
        let (Some(name), Some(value)) = (parts.next(), parts.next()) else { continue };
        let decl = format!("public const uint {} = {value};", camel(name));
        if !cs.contains(&decl) {
            missing.push(decl);
        }
    }
    assert!(missing.is_empty(), "constants missing or different in Orient.Native.cs: {missing:?}");
    let cs_consts = cs.matches("public const uint ").count();
    let c_consts =
        header.lines().filter(|l| l.starts_with("#define ORIENT_") && !l.contains("ORIENT_H")).count();
    assert_eq!(cs_consts, c_consts, "Orient.Native.cs has constants the header lacks");

    // Every enumerator ORIENT_<ENUM>_<NAME> = N appears as `<Name> = N,` in the C# enum.
    for (prefix, enum_name) in [
        ("ORIENT_STATUS_", "Status"),
        ("ORIENT_KIND_", "Kind"),
        ("ORIENT_FRAME_", "Frame"),
        ("ORIENT_INIT_", "Init"),
    ] {
        let start =
            cs.find(&format!("public enum {enum_name} : int")).unwrap_or_else(|| panic!("enum {enum_name}"));
        let body = &cs[start..start + cs[start..].find('}').unwrap()];
        let mut n = 0;
        for line in header.lines().map(str::trim).filter(|l| l.starts_with(prefix) && l.contains(" = ")) {
            let (name, value) = line.trim_end_matches(',').split_once(" = ").unwrap();
            let expected = format!("{} = {value},", camel(&name[prefix.len()..]));
            assert!(body.contains(&expected), "enum {enum_name} lacks `{expected}`");
            n += 1;
        }
        assert_eq!(body.matches(" = ").count(), n, "enum {enum_name} has members the header lacks");
    }
}

fn tool(name: &str) -> Command {
    let probe = Command::new(name).arg("--version").output();
    assert!(
        probe.is_ok_and(|o| o.status.success()),
        "{name} not found: install Debian's mono-mcs and mono-runtime (scripts/setup-debian.sh does)"
    );
    Command::new(name)
}

#[test]
fn csharp_wrapper_replays_the_golden_vectors_under_mono() {
    if cross() {
        eprintln!("skipped: Mono on this machine cannot load a library built for another target");
        return;
    }
    let dir = out_dir("csharp");
    std::fs::copy(deps_dir().join("liborient.so"), dir.join("liborient.so")).unwrap();
    let exe = dir.join("OrientTests.exe");
    let mut mcs = tool("mcs");
    mcs.args(["-unsafe", "-warnaserror", "-nologo"])
        .arg(format!("-out:{}", exe.display()))
        .arg(root().join("bindings/csharp/Orient.Native.cs"))
        .arg(root().join("bindings/csharp/Orient.cs"))
        .arg(root().join("tests/csharp/OrientTests.cs"));
    check(mcs, "mcs OrientTests");
    let mut mono = tool("mono");
    mono.arg(&exe).arg(common::golden::PATH).env("LD_LIBRARY_PATH", &dir);
    let out = mono.output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    print!("{stdout}");
    eprint!("{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "mono OrientTests.exe failed");
    let summary = stdout.lines().last().unwrap_or("");
    assert!(summary.ends_with(" 0 failed") && !summary.starts_with("0 passed"), "{summary}");
}

#[test]
fn unity_package_assembles_and_compiles_against_the_unityengine_stub() {
    let dir = out_dir("unity");
    let mut package = Command::new(root().join("scripts/package-unity.sh"));
    package.arg(&dir);
    check(package, "package-unity.sh");
    let pkg = dir.join("com.orient.filters");
    for f in [
        "package.json",
        "Runtime/Orient.Runtime.asmdef",
        "Runtime/Orient.cs",
        "Samples~/HandRig/OrientHandRig.cs",
    ] {
        assert!(pkg.join(f).exists(), "{f} missing from the package");
    }
    let asmdef = std::fs::read_to_string(pkg.join("Runtime/Orient.Runtime.asmdef")).unwrap();
    assert!(asmdef.contains("\"allowUnsafeCode\": true"));
    // Everything the package compiles in Unity, here against the stub.
    let mut mcs = tool("mcs");
    mcs.args(["-unsafe", "-warnaserror", "-nologo", "-target:library"])
        .arg(format!("-out:{}", dir.join("Orient.Unity.dll").display()))
        .arg(pkg.join("Runtime/Orient.Native.cs"))
        .arg(pkg.join("Runtime/Orient.cs"))
        .arg(pkg.join("Runtime/OrientUnity.cs"))
        .arg(pkg.join("Samples~/HandRig/OrientHandRig.cs"))
        .arg(root().join("examples/unity/OrientHand.cs"))
        .arg(root().join("tests/csharp/UnityEngineStub.cs"));
    check(mcs, "mcs Unity scripts");
}

#[test]
fn the_readme_shows_the_unity_hand_example_as_compiled() {
    // README.md's first C# block under "## C# and Unity" is examples/unity/OrientHand.cs, which
    // the test above compiles against the UnityEngine stub.
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let section = &readme[readme.find("\n## C# and Unity").expect("a Unity section")..];
    let start = section.find("```csharp\n").expect("a C# block") + "```csharp\n".len();
    let block = &section[start..start + section[start..].find("```\n").unwrap()];
    let file = std::fs::read_to_string(root().join("examples/unity/OrientHand.cs")).unwrap();
    assert_eq!(block, file, "README's Unity example differs from examples/unity/OrientHand.cs");
}

/// Runs scripts/gen-csharp.py on `header` text; its exit success, output and stderr.
fn generate(name: &str, header: &str) -> (bool, String, String) {
    let dir = out_dir("gen_csharp");
    let (h, cs) = (dir.join(format!("{name}.h")), dir.join(format!("{name}.cs")));
    std::fs::write(&h, header).unwrap();
    let _ = std::fs::remove_file(&cs);
    let out = Command::new("python3")
        .arg(root().join("scripts/gen-csharp.py"))
        .arg(&h)
        .arg(&cs)
        .output()
        .expect("python3 (scripts/setup-debian.sh installs it)");
    let text = std::fs::read_to_string(&cs).unwrap_or_default();
    (out.status.success(), text, String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn committed_csharp_layer_is_what_the_generator_makes_from_the_header() {
    let (ok, generated, err) = generate("orient", &read("include/orient.h"));
    assert!(ok, "gen-csharp.py failed: {err}");
    assert!(
        generated == read("bindings/csharp/Orient.Native.cs"),
        "bindings/csharp/Orient.Native.cs is stale: run scripts/gen-csharp.py and commit the result"
    );
}

#[test]
fn generator_follows_header_additions() {
    let header = read("include/orient.h");
    let added = header
        .replacen(
            "#define ORIENT_MAX_PARAMS",
            "#define ORIENT_TEST_ADDED 77\n\n#define ORIENT_MAX_PARAMS",
            1,
        )
        .replacen(
            "  double z;\n} OrientVec3;",
            "  double z;\n  /**\n   * New & <documented>.\n   */\n  uint8_t extra[4];\n} OrientVec3;",
            1,
        )
        .replacen(
            "#ifdef __cplusplus\n}",
            "/**\n * Added.\n */\nOrientStatus orient_test_added(const OrientFilter *filter,\n                              \
             size_t n,\n                              double *out);\n\n#ifdef __cplusplus\n}",
            1,
        );
    assert_ne!(added, header);
    let (ok, cs, err) = generate("added", &added);
    assert!(ok, "gen-csharp.py failed: {err}");
    for expected in [
        "public const uint TestAdded = 77;",
        "public static extern Status orient_test_added(IntPtr filter, UIntPtr n, double* @out);",
        "/// New &amp; &lt;documented&gt;.",
        "public fixed byte Extra[4];",
        "public unsafe partial struct Vec3",
    ] {
        assert!(cs.contains(expected), "generated file lacks `{expected}`");
    }
}

#[test]
fn generator_refuses_what_il2cpp_cannot_pass_and_what_it_does_not_know() {
    let header = read("include/orient.h");
    for (name, from, to, message) in [
        ("bool", "uint32_t orient_abi_version(void);", "bool orient_abi_version(void);", "bool"),
        (
            "unknown",
            "uint32_t orient_abi_version(void);",
            "wchar_t orient_abi_version(void);",
            "unknown type",
        ),
        ("union", "typedef struct OrientVec3 {", "typedef union OrientVec3 {", "unhandled"),
    ] {
        assert!(header.contains(from));
        let (ok, _, err) = generate(name, &header.replacen(from, to, 1));
        assert!(!ok && err.contains(message), "{name}: expected a refusal naming `{message}`, got: {err}");
    }
}
