#!/usr/bin/env python3
"""Checks a release made by scripts/release.sh, and the Unity package inside it.

    scripts/check-dist.py dist/orient-VERSION      every check below; exits 1 on a failure
    scripts/check-dist.py --functions HEADER      prints the header's function names
    scripts/check-dist.py --unity PACKAGE_DIR     only the Unity package checks

Release: the shared files are there and SHA256SUMS matches; every platform folder has
its libraries, CMake package and pkg-config files, and an archive; every library
(ELF, PE, Mach-O, static archives, import libraries) exports exactly the header's
functions and is built for its folder's machine; no static archive holds tools code
(orient-tools: the CSV reader and scoring); Linux glibc builds need no symbol
newer than GLIBC_2.17 and carry the SONAME liborient.so.ABI; the DLL needs no MinGW
runtime DLL; the dylib is universal (arm64, x86_64), has the install name
@rpath/liborient.dylib and a code signature on arm64.
Unity: every asset and folder has a .meta and every .meta an asset; GUIDs are unique
and derived from the asset's path (so they stay the same from release to release);
each plugin's import settings enable exactly the platform and CPU of its folder;
package.json is complete and names the recommended kind.
Python (python/): the sdist and the manylinux2014 x86_64 and aarch64, macOS universal2 and
win_amd64 wheels; each holds every file of bindings/python/orient and a library that
passes the checks above (exports, glibc floor, SONAME, architectures).
It prints one line per library with its size and what was checked.
"""
import hashlib
import json
import os
import re
import subprocess
import sys
import tarfile
import zipfile

FAILS = []


def fail(msg):
    FAILS.append(msg)
    print("FAIL " + msg)


def llvm(tool):
    host = re.search(r"^host: (\S+)", run(["rustc", "-vV"]), re.M).group(1)
    sysroot = run(["rustc", "--print", "sysroot"]).strip()
    return os.path.join(sysroot, "lib", "rustlib", host, "bin", tool)


def run(cmd):
    out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if out.returncode != 0:
        raise RuntimeError("%s failed: %s" % (" ".join(cmd), out.stderr.strip()))
    return out.stdout


def header_functions(header):
    """Names of the functions the header declares (cbindgen writes one declaration per
    function, starting at column 0 with its return type)."""
    text = open(header).read()
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    names = set()
    for line in text.splitlines():
        if line[:1].isalpha() and not line.startswith(("typedef", "struct", "enum", "union")):
            m = re.search(r"\b(orient_[a-z0-9_]+)\(", line)
            if m:
                names.add(m.group(1))
    return names


# --- libraries ------------------------------------------------------------------------

NM = OBJDUMP = READOBJ = None

ELF_MACHINE = {"x86_64": "EM_X86_64", "aarch64": "EM_AARCH64", "armv7": "EM_ARM"}


def platform_arch(platform):
    """linux-aarch64-musl -> aarch64; android-armeabi-v7a -> armv7; ..."""
    if "arm64" in platform or "aarch64" in platform:
        return "aarch64"
    if "armv7" in platform or "armeabi" in platform:
        return "armv7"
    return "x86_64"


def compare(what, got, want):
    if got != want:
        missing = sorted(want - got)
        extra = sorted(got - want)
        fail("%s: exports differ from the header: missing %s, extra %s%s" % (
            what, missing, extra[:8], " ..." if len(extra) > 8 else ""))
        return False
    return True


def elf_shared(path, platform, want):
    dyn = run([NM, "-D", "--defined-only", path])
    got = {l.split()[2] for l in dyn.splitlines() if len(l.split()) == 3 and l.split()[1] == "T"}
    ok = compare(path, got, want)
    header = run([READOBJ, "--file-headers", path])
    machine = re.search(r"Machine: (\S+)", header).group(1)
    arch = platform_arch(platform)
    if machine != ELF_MACHINE[arch]:
        fail("%s: machine %s, folder says %s" % (path, machine, arch))
    dynamic = run([READOBJ, "--dynamic-table", path])
    soname = re.search(r"SONAME\s+Library soname: \[([^\]]+)\]", dynamic)
    if not soname or soname.group(1) != "liborient.so.%d" % ABI:
        fail("%s: SONAME %s, want liborient.so.%d" % (path, soname and soname.group(1), ABI))
    versions = set(re.findall(r"GLIBC_([0-9.]+)", run([OBJDUMP, "-T", path])))
    floor = max(versions, key=lambda v: tuple(int(x) for x in v.split("."))) if versions else "none"
    if versions and tuple(int(x) for x in floor.split(".")) > (2, 17):
        fail("%s: needs GLIBC_%s, more than 2.17" % (path, floor))
    return ok, "ELF %s, SONAME %s, highest glibc symbol GLIBC_%s" % (machine, soname and soname.group(1), floor)


def pe_dll(path, want):
    exports = run([READOBJ, "--coff-exports", path])
    got = set(re.findall(r"Name: (\S+)", exports))
    ok = compare(path, got, want)
    private = run([OBJDUMP, "-p", path])
    dlls = sorted(set(d.lower() for d in re.findall(r"DLL Name: (\S+)", private)))
    for bad in ("libgcc_s_seh-1.dll", "libwinpthread-1.dll", "libstdc++-6.dll"):
        if bad in dlls:
            fail("%s: needs %s (a MinGW runtime DLL users do not have)" % (path, bad))
    machine = re.search(r"Machine: (\S+)", run([READOBJ, "--file-headers", path])).group(1)
    if machine != "IMAGE_FILE_MACHINE_AMD64":
        fail("%s: machine %s" % (path, machine))
    return ok, "PE %s, imports %s" % (machine, ", ".join(dlls))


def import_lib(path, want):
    syms = run([NM, "--defined-only", path])
    got = {l.split()[-1][len("__imp_"):] for l in syms.splitlines() if l.split() and l.split()[-1].startswith("__imp_")}
    return compare(path, got, want), "import library for orient.dll"


def macho_dylib(path, want):
    info = run([OBJDUMP, "--macho", "--universal-headers", path])
    archs = sorted(set(re.findall(r"cputype CPU_TYPE_(\S+)", info)))
    if archs != ["ARM64", "X86_64"]:
        fail("%s: architectures %s, want ARM64 and X86_64" % (path, archs))
    ok = True
    notes = []
    for arch in ("arm64", "x86_64"):
        trie = run([OBJDUMP, "--macho", "--exports-trie", "--arch=" + arch, path])
        got = {m.lstrip("_") for m in re.findall(r"^0x[0-9A-Fa-f]+\s+(\S+)", trie, re.M)}
        ok = compare("%s (%s)" % (path, arch), got, want) and ok
        headers = run([OBJDUMP, "--macho", "--private-headers", "--arch=" + arch, path])
        idname = re.search(r"cmd LC_ID_DYLIB.*?name (\S+)", headers, re.S)
        if not idname or idname.group(1) != "@rpath/liborient.dylib":
            fail("%s (%s): install name %s" % (path, arch, idname and idname.group(1)))
        if arch == "arm64" and "LC_CODE_SIGNATURE" not in headers:
            fail("%s: the arm64 slice has no code signature (macOS refuses to load it)" % path)
        minos = re.search(r"minos (\S+)", headers) or re.search(r"LC_VERSION_MIN_MACOSX.*?version (\S+)", headers, re.S)
        notes.append("%s macOS >= %s" % (arch, minos.group(1) if minos else "?"))
    return ok, "Mach-O universal, install name @rpath/liborient.dylib, " + ", ".join(notes)


TOOLS_CODE = re.compile(r"\borient(?:_tools)?::eval::\w+|\borient_tools::\w+")


def static_lib(path, platform, want):
    """An archive defines the whole Rust runtime too; its C-named (unmangled) global
    functions must be exactly the header's, and every header function must be there."""
    syms = run([NM, "--defined-only", "-g", "--no-weak", path])
    names = set()
    for line in syms.splitlines():
        parts = line.split()
        if len(parts) >= 2 and parts[-2] in ("T", "t"):
            names.add(parts[-1].lstrip("_") if "apple" in platform or "ios" in platform else parts[-1])
    got = {n for n in names if n.startswith("orient_")}
    ok = compare(path, got, want)
    # The tools crate (recording CSV reader, scoring) must stay out of the library: an
    # archive keeps every public Rust function, so its code would show up here by name.
    demangled = run([NM, "--defined-only", "-C", path])
    tools = sorted(set(m.group(0) for m in TOOLS_CODE.finditer(demangled)))
    if tools:
        fail("%s: contains tools code (%s)" % (path, ", ".join(tools[:4])))
        ok = False
    header = run([READOBJ, "--file-headers", path])
    arch = platform_arch(platform)
    if "ios" in platform:
        if "CPU_TYPE_ARM64" not in header and "Arm64" not in header and "ARM64" not in header:
            fail("%s: not arm64 objects" % path)
        kind = "Mach-O arm64 archive"
    elif "windows" in platform:
        if "IMAGE_FILE_MACHINE_AMD64" not in header:
            fail("%s: not x86_64 COFF objects" % path)
        kind = "COFF x86_64 archive"
    else:
        machines = set(re.findall(r"Machine: (EM_\S+)", header))
        if machines != {ELF_MACHINE[arch]}:
            fail("%s: machines %s, folder says %s" % (path, machines, arch))
        kind = "ELF %s archive" % ELF_MACHINE[arch]
    return ok, kind + ", %d C-named functions" % len(got)


def check_library(path, platform, want):
    size = os.path.getsize(path)
    name = os.path.basename(path)
    if name.endswith(".dll"):
        ok, note = pe_dll(path, want)
    elif name.endswith(".lib") or name.endswith(".dll.a"):
        ok, note = import_lib(path, want)
    elif name.endswith(".dylib"):
        ok, note = macho_dylib(path, want)
    elif name.endswith(".a"):
        ok, note = static_lib(path, platform, want)
    else:
        ok, note = elf_shared(path, platform, want)
    print("%-58s %9d  %s exports %s; %s" % (path, size, len(want), "ok" if ok else "WRONG", note))


EXPECTED = {
    "linux-x86_64": ["liborient.so.{full}", "liborient.so.{abi}", "liborient.so", "liborient.a",
                     "pkgconfig/orient.pc", "pkgconfig/orient-static.pc"],
    "linux-aarch64": ["liborient.so.{full}", "liborient.a", "pkgconfig/orient.pc", "pkgconfig/orient-static.pc"],
    "linux-armv7": ["liborient.so.{full}", "liborient.a", "pkgconfig/orient.pc", "pkgconfig/orient-static.pc"],
    "linux-x86_64-musl": ["liborient.a", "pkgconfig/orient-static.pc"],
    "linux-aarch64-musl": ["liborient.a", "pkgconfig/orient-static.pc"],
    "windows-x86_64": ["orient.dll", "orient.lib", "liborient.dll.a", "liborient.a", "pkgconfig/orient.pc"],
    "macos-universal": ["liborient.dylib", "pkgconfig/orient.pc"],
    "ios-arm64": ["liborient.a"],
    "android-arm64-v8a": ["liborient.a"],
    "android-armeabi-v7a": ["liborient.a"],
}
OPTIONAL = {"linux-armv7-musl": ["liborient.a", "pkgconfig/orient-static.pc"]}


def check_release(rel):
    version = re.search(r"orient-(\d+\.\d+\.\d+)$", rel.rstrip("/")).group(1)
    full = "%d.%s" % (ABI, version.split(".", 1)[1])
    for f in ["include/orient.h", "bindings/cpp/orient.hpp", "LICENSE-MIT", "LICENSE-APACHE",
              "CHANGELOG.md", "README.md", "SHA256SUMS"]:
        if not os.path.isfile(os.path.join(rel, f)):
            fail("%s missing" % f)
    # SHA256SUMS lists every other file and matches.
    listed = {}
    for line in open(os.path.join(rel, "SHA256SUMS")):
        digest, name = line.rstrip("\n").split("  ", 1)
        listed[name] = digest
    present = set()
    for r, _, files in os.walk(rel):
        for f in files:
            p = os.path.relpath(os.path.join(r, f), rel)
            if p != "SHA256SUMS" and not os.path.islink(os.path.join(r, f)):
                present.add(p)
    for p in sorted(present - set(listed)):
        fail("SHA256SUMS does not list %s" % p)
    for p, digest in sorted(listed.items()):
        full_path = os.path.join(rel, p)
        if not os.path.isfile(full_path):
            fail("SHA256SUMS lists missing %s" % p)
        elif hashlib.sha256(open(full_path, "rb").read()).hexdigest() != digest:
            fail("SHA256SUMS: %s does not match" % p)
    if version not in open(os.path.join(rel, "CHANGELOG.md")).read():
        fail("CHANGELOG.md has no entry for %s" % version)
    want = header_functions(os.path.join(rel, "include/orient.h"))
    platforms = sorted(os.listdir(os.path.join(rel, "lib")))
    for p in sorted(set(EXPECTED) - set(platforms)):
        fail("platform %s missing" % p)
    for p in platforms:
        files = EXPECTED.get(p) or OPTIONAL.get(p)
        if files is None:
            fail("unexpected platform folder %s" % p)
            continue
        d = os.path.join(rel, "lib", p)
        for f in files + ["cmake/orientConfig.cmake", "cmake/orientConfigVersion.cmake"]:
            if not os.path.exists(os.path.join(d, f.format(full=full, abi=ABI))):
                fail("%s/%s missing" % (p, f.format(full=full, abi=ABI)))
        archive = os.path.join(rel, "archives", "orient-%s-%s.%s" % (version, p, "zip" if "windows" in p else "tar.gz"))
        if not os.path.isfile(archive):
            fail("archive for %s missing" % p)
        else:
            if archive.endswith(".zip"):
                names = set(zipfile.ZipFile(archive).namelist())
            else:
                names = set(n.rstrip("/") for n in tarfile.open(archive).getnames())
            top = "orient-%s/" % version
            for f in ["include/orient.h", "bindings/cpp/orient.hpp", "LICENSE-MIT", "LICENSE-APACHE", "CHANGELOG.md", "README.md"]:
                if top + f not in names:
                    fail("%s lacks %s" % (os.path.basename(archive), f))
            for r, _, files in os.walk(d):
                for f in files:
                    member = top + os.path.relpath(os.path.join(r, f), rel)
                    if member not in names:
                        fail("%s lacks %s" % (os.path.basename(archive), member))
        for f in sorted(os.listdir(d)):
            path = os.path.join(d, f)
            if os.path.isfile(path) and not os.path.islink(path) and re.search(r"\.(a|lib|dll|dylib)$|\.so\.\d+\.\d+\.\d+$", f):
                check_library(path, p, want)
    if not os.path.isfile(os.path.join(rel, "archives", "com.orient.filters-%s.tgz" % version)):
        fail("Unity package archive missing")
    check_unity(os.path.join(rel, "unity", "com.orient.filters"), version, want)
    check_python(os.path.join(rel, "python"), version, want)


# --- Python ---------------------------------------------------------------------------

# Wheel platform tag (a pattern) -> (the library it bundles, the platform folder it came from).
PYTHON_WHEELS = {
    r"manylinux2014_x86_64\.manylinux_2_17_x86_64": ("orient/liborient.so", "linux-x86_64"),
    r"manylinux2014_aarch64\.manylinux_2_17_aarch64": ("orient/liborient.so", "linux-aarch64"),
    r"macosx_\d+_\d+_universal2": ("orient/liborient.dylib", "macos-universal"),
    r"win_amd64": ("orient/orient.dll", "windows-x86_64"),
}


def check_python(py, version, want):
    """The sdist and one py3-none wheel per platform; each wheel holds every file of
    bindings/python/orient and a library that exports exactly the header's functions
    (for the wheels no Python here can load: macOS and Windows)."""
    import tempfile
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    package = {"orient/" + f for f in os.listdir(os.path.join(root, "bindings", "python", "orient"))
               if os.path.isfile(os.path.join(root, "bindings", "python", "orient", f)) and not f.endswith(".pyc")}
    files = sorted(os.listdir(py)) if os.path.isdir(py) else []
    if "orient_imu-%s.tar.gz" % version not in files:
        fail("python/orient_imu-%s.tar.gz (sdist) missing" % version)
    for tag, (lib, platform) in PYTHON_WHEELS.items():
        found = [f for f in files if re.fullmatch(r"orient_imu-%s-py3-none-%s\.whl" % (re.escape(version), tag), f)]
        if len(found) != 1:
            fail("python: want one wheel tagged %s, found %s" % (tag, found))
            continue
        z = zipfile.ZipFile(os.path.join(py, found[0]))
        names = set(z.namelist())
        for f in sorted((package | {lib}) - names):
            fail("%s lacks %s" % (found[0], f))
        if lib in names:
            with tempfile.TemporaryDirectory() as tmp:
                path = os.path.join(tmp, found[0][:-4] + "-" + os.path.basename(lib))
                with open(path, "wb") as out:
                    out.write(z.read(lib))
                check_library(path, platform, want)


# --- Unity ----------------------------------------------------------------------------

# Plugin path -> (Editor OS, Editor CPU or None when the Editor must not load it,
#                 {standalone or player platform: CPU}).
UNITY_PLUGINS = {
    "Plugins/Windows/x86_64/orient.dll": ("Windows", "x86_64", {"Standalone: Win64": "x86_64"}),
    "Plugins/macOS/liborient.dylib": ("OSX", "AnyCPU", {"Standalone: OSXUniversal": "AnyCPU"}),
    "Plugins/Linux/x86_64/liborient.so": ("Linux", "x86_64", {"Standalone: Linux64": "x86_64"}),
    "Plugins/Android/arm64-v8a/liborient.a": (None, None, {"Android: Android": "ARM64"}),
    "Plugins/Android/armeabi-v7a/liborient.a": (None, None, {"Android: Android": "ARMv7"}),
    "Plugins/iOS/liborient.a": (None, None, {"iPhone: iOS": "ARM64"}),
}
PLUGIN_PLATFORM = {
    "Plugins/Windows/x86_64/orient.dll": "windows-x86_64",
    "Plugins/macOS/liborient.dylib": "macos-universal",
    "Plugins/Linux/x86_64/liborient.so": "linux-x86_64",
    "Plugins/Android/arm64-v8a/liborient.a": "android-arm64-v8a",
    "Plugins/Android/armeabi-v7a/liborient.a": "android-armeabi-v7a",
    "Plugins/iOS/liborient.a": "ios-arm64",
}


def platform_sections(meta):
    """'Editor: Editor' -> (enabled, {setting: value}) from a PluginImporter .meta."""
    out = {}
    for m in re.finditer(r"  - first:\n      (.*?)\n    second:\n      enabled: (\d)\n      settings:(.*?)(?=\n  - first:|\n  userData:)", meta, re.S):
        settings = dict(re.findall(r"\n        ([^:\n]+): ?([^\n]*)", m.group(3)))
        out[m.group(1).strip()] = (m.group(2) == "1", settings)
    return out


def check_plugin(pkg, rel_path, meta):
    if "PluginImporter:" not in meta:
        fail("%s.meta: not a PluginImporter" % rel_path)
        return
    sections = platform_sections(meta)
    editor_os, editor_cpu, players = UNITY_PLUGINS[rel_path]
    any_platform = sections.get(": Any")
    if any_platform is None or any_platform[0]:
        fail("%s.meta: 'Any Platform' must be off (the plugin names its platforms)" % rel_path)
    editor = sections.get("Editor: Editor")
    if editor_os:
        if not editor or not editor[0] or editor[1].get("OS") != editor_os or editor[1].get("CPU") != editor_cpu:
            fail("%s.meta: Editor must be enabled for %s/%s, is %s" % (rel_path, editor_os, editor_cpu, editor))
    elif editor and editor[0]:
        fail("%s.meta: the Editor must not load a player-only library" % rel_path)
    for key, (enabled, settings) in sections.items():
        if key in (": Any", "Any:", "Editor: Editor"):
            continue
        if key in players:
            if not enabled or settings.get("CPU") != players[key]:
                fail("%s.meta: %s must be enabled with CPU %s, is %s %s" % (rel_path, key, players[key], enabled, settings))
        elif enabled:
            fail("%s.meta: %s is enabled but the folder is not for it" % (rel_path, key))
    for key in players:
        if key not in sections:
            fail("%s.meta: no %s section" % (rel_path, key))


def check_unity(pkg, version, want):
    guids = {}
    for r, dirs, files in os.walk(pkg):
        for name in dirs + files:
            path = os.path.join(r, name)
            rel_path = os.path.relpath(path, pkg)
            if name.endswith(".meta"):
                if not os.path.exists(path[:-5]):
                    fail("%s has no asset" % rel_path)
                meta = open(path).read()
                m = re.search(r"^guid: ([0-9a-f]{32})$", meta, re.M)
                if not m or not meta.startswith("fileFormatVersion: 2\n"):
                    fail("%s: no fileFormatVersion 2 / 32-hex guid" % rel_path)
                    continue
                asset = os.path.relpath(path[:-5], pkg)
                derived = hashlib.md5(("com.orient.filters/" + asset).encode()).hexdigest()
                if m.group(1) != derived:
                    fail("%s: GUID %s is not the one derived from its path (%s): it would change between releases" % (rel_path, m.group(1), derived))
                if m.group(1) in guids:
                    fail("GUID %s used by %s and %s" % (m.group(1), guids[m.group(1)], rel_path))
                guids[m.group(1)] = rel_path
                if os.path.isdir(path[:-5]) and "folderAsset: yes" not in meta:
                    fail("%s: a folder's .meta needs folderAsset: yes" % rel_path)
            elif name.endswith("~") and os.path.isdir(path):
                continue  # Unity does not import folders ending in ~ (Samples~); no .meta
            elif not os.path.exists(path + ".meta"):
                fail("%s has no .meta (Unity ignores it in an immutable package)" % rel_path)
    for rel_path, platform in PLUGIN_PLATFORM.items():
        path = os.path.join(pkg, rel_path)
        if not os.path.isfile(path):
            fail("Unity plugin %s missing" % rel_path)
            continue
        check_plugin(pkg, rel_path, open(path + ".meta").read())
        check_library(path, platform, want)
    plugins = os.path.join(pkg, "Plugins")
    for r, _, files in os.walk(plugins):
        for f in files:
            p = os.path.relpath(os.path.join(r, f), pkg)
            if not f.endswith(".meta") and p not in UNITY_PLUGINS:
                fail("unexpected file in Plugins: %s" % p)
    manifest = json.load(open(os.path.join(pkg, "package.json")))
    for key in ["name", "version", "displayName", "description", "unity", "author", "license",
                "changelogUrl", "documentationUrl", "licensesUrl", "samples"]:
        if not manifest.get(key):
            fail("package.json: %s missing" % key)
    if manifest.get("version") != version:
        fail("package.json: version %s, crate %s" % (manifest.get("version"), version))
    if "robust" not in manifest.get("description", "").lower():
        fail("package.json: the description does not name the recommended kind (robust)")
    if not isinstance(manifest.get("author"), dict) or not manifest["author"].get("name"):
        fail("package.json: author needs a name")
    for key in ["changelogUrl", "documentationUrl", "licensesUrl"]:
        if not str(manifest.get(key, "")).startswith("https://"):
            fail("package.json: %s is not an https URL" % key)
    for s in manifest.get("samples", []):
        if not os.path.isdir(os.path.join(pkg, s["path"])):
            fail("package.json: sample path %s missing" % s["path"])
    print("unity: %d .meta files, GUIDs unique, %d plugins with matching import settings" % (len(guids), len(PLUGIN_PLATFORM)))


def main():
    global NM, OBJDUMP, READOBJ, ABI
    args = sys.argv[1:]
    if len(args) == 2 and args[0] == "--functions":
        print("\n".join(sorted(header_functions(args[1]))))
        return 0
    NM, OBJDUMP, READOBJ = llvm("llvm-nm"), llvm("llvm-objdump"), llvm("llvm-readobj")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    header = open(os.path.join(root, "include/orient.h")).read()
    ABI = int(re.search(r"^#define ORIENT_ABI_VERSION (\d+)$", header, re.M).group(1))
    if len(args) == 2 and args[0] == "--unity":
        version = json.load(open(os.path.join(args[1], "package.json")))["version"]
        check_unity(args[1], version, header_functions(os.path.join(root, "include/orient.h")))
    elif len(args) == 1:
        check_release(args[0])
    else:
        print(__doc__)
        return 2
    if FAILS:
        print("%d check(s) failed" % len(FAILS))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
