"""Conan 2 recipe for orient: builds the C library with cargo and packages the same
layout and CMake package as scripts/install.sh.

    conan create .                     # builds, packages, runs test_package
    # a consumer's conanfile: requires = "orient/0.1.0"; generators = "CMakeToolchain", "CMakeDeps"
    find_package(orient 1 CONFIG REQUIRED)
    target_link_libraries(app PRIVATE orient::orient)   # or orient::orient_static

The package holds both libraries, as an install does: the shared one (orient::orient) and
the static one with the system libraries it needs (orient::orient_static), orient.h and
orient.hpp, pkg-config files, and lib/cmake/orient/orientConfig.cmake filled from the
same templates (packaging/) as an install and a release, so the targets, the
ABI-keyed version check (find_package(orient 1) matches ABI 1 only) and the include
directories are the ones every other way of getting orient gives. CMakeDeps therefore
writes nothing for orient (cmake_find_mode "none"); the package folder is on
CMAKE_PREFIX_PATH instead.

Needs cargo (rustup) on PATH or in ~/.cargo/bin. cargo builds one release library
whatever the C compiler and build type, so those settings are not part of the package
id. Conf user.orient:cargo_target_dir shares a cargo target directory with other builds
(scripts/test-conan.sh passes the checkout's, so CI reuses its release build).
"""

import os
import re
import shutil

from conan import ConanFile
from conan.errors import ConanInvalidConfiguration
from conan.tools.files import copy, load, save

# (os, arch) -> Rust target triple, for the builds this recipe knows how to name.
RUST_TARGETS = {
    ("Linux", "x86_64"): "x86_64-unknown-linux-gnu",
    ("Linux", "armv8"): "aarch64-unknown-linux-gnu",
    ("Linux", "armv7hf"): "armv7-unknown-linux-gnueabihf",
    ("Macos", "x86_64"): "x86_64-apple-darwin",
    ("Macos", "armv8"): "aarch64-apple-darwin",
    ("Windows", "x86_64"): "x86_64-pc-windows-msvc",
}
# The system libraries a static link needs besides the archive (cargo's
# --print native-static-libs; the same lists as CMakeLists.txt and scripts/install.sh).
SYSTEM_LIBS = {
    "Linux": ["gcc_s", "util", "rt", "pthread", "m", "dl"],
    "Macos": ["System", "m"],
    "Windows": ["kernel32", "advapi32", "ntdll", "userenv", "ws2_32", "dbghelp"],
}


class OrientConan(ConanFile):
    name = "orient"
    description = "IMU/MARG orientation filters (Madgwick, Mahony, complementary, EKF, GMVDK, robust) behind a C ABI"
    license = "MIT OR Apache-2.0"
    topics = ("imu", "marg", "ahrs", "orientation", "sensor-fusion", "kalman-filter")
    settings = "os", "arch", "compiler", "build_type"
    exports_sources = (
        "Cargo.toml", "Cargo.lock", "build.rs", "src/*", "tools/Cargo.toml", "tools/src/*",
        "include/orient.h", "bindings/cpp/orient.hpp", "packaging/*", "LICENSE-MIT", "LICENSE-APACHE",
    )

    def set_version(self):
        manifest = load(self, os.path.join(self.recipe_folder, "Cargo.toml"))
        self.version = re.search(r'^version = "([^"]+)"', manifest, re.M).group(1)

    def package_id(self):
        del self.info.settings.compiler
        del self.info.settings.build_type

    def validate(self):
        if (str(self.settings.os), str(self.settings.arch)) not in RUST_TARGETS:
            raise ConanInvalidConfiguration(
                f"no Rust target known for os={self.settings.os} arch={self.settings.arch}; "
                f"known: {sorted(RUST_TARGETS)}")

    def _abi(self):
        header = load(self, os.path.join(self.source_folder, "include", "orient.h"))
        return int(re.search(r"^#define ORIENT_ABI_VERSION (\d+)$", header, re.M).group(1))

    def _target(self):
        return RUST_TARGETS[(str(self.settings.os), str(self.settings.arch))]

    def _cross(self):
        build = getattr(self, "settings_build", None)
        return build is not None and (build.os, build.arch) != (self.settings.os, self.settings.arch)

    def _out_dir(self):
        target_dir = self.conf.get("user.orient:cargo_target_dir") or os.path.join(self.build_folder, "cargo")
        if self._cross():
            return target_dir, os.path.join(target_dir, self._target(), "release")
        return target_dir, os.path.join(target_dir, "release")

    def build(self):
        cargo = shutil.which("cargo") or os.path.expanduser(os.path.join("~", ".cargo", "bin", "cargo"))
        target_dir, _ = self._out_dir()
        cmd = [cargo, "build", "--release", "--locked", "-p", "orient", "--lib",
               "--manifest-path", os.path.join(self.source_folder, "Cargo.toml"), "--target-dir", target_dir]
        if self._cross():
            cmd += ["--target", self._target()]
        self.run(" ".join(f'"{c}"' for c in cmd))

    def package(self):
        _, out = self._out_dir()
        abi = self._abi()
        full = f"{abi}.{self.version.split('.', 1)[1]}"
        lib = os.path.join(self.package_folder, "lib")
        os.makedirs(lib, exist_ok=True)
        copy(self, "orient.h", os.path.join(self.source_folder, "include"), os.path.join(self.package_folder, "include"))
        copy(self, "orient.hpp", os.path.join(self.source_folder, "bindings", "cpp"), os.path.join(self.package_folder, "include"))
        copy(self, "LICENSE-*", self.source_folder, os.path.join(self.package_folder, "licenses"))
        system = str(self.settings.os)
        implib = soname = ""
        if system == "Linux":
            shared, soname, static = f"liborient.so.{full}", f"liborient.so.{abi}", "liborient.a"
            shutil.copy2(os.path.join(out, "liborient.so"), os.path.join(lib, shared))
            for link, to in ((soname, shared), ("liborient.so", soname)):
                if os.path.lexists(os.path.join(lib, link)):
                    os.remove(os.path.join(lib, link))
                os.symlink(to, os.path.join(lib, link))
            shutil.copy2(os.path.join(out, "liborient.a"), os.path.join(lib, static))
        elif system == "Macos":
            shared, soname, static = "liborient.dylib", "@rpath/liborient.dylib", "liborient.a"
            for f in (shared, static):
                shutil.copy2(os.path.join(out, f), os.path.join(lib, f))
        else:  # Windows, MSVC: the DLL, its import library orient.lib, the static orient_static.lib
            shared, implib, static = "orient.dll", "orient.lib", "orient_static.lib"
            shutil.copy2(os.path.join(out, "orient.dll"), os.path.join(lib, shared))
            shutil.copy2(os.path.join(out, "orient.dll.lib"), os.path.join(lib, implib))
            shutil.copy2(os.path.join(out, "orient.lib"), os.path.join(lib, static))
        self._configure(lib, abi, shared, soname, implib, static, SYSTEM_LIBS[system])

    def _configure(self, lib, abi, shared, soname, implib, static, system_libs):
        """What scripts/configure-package.sh does for an installed prefix (--prefix-up 1,
        --headers include, --cmake-dir cmake/orient): the templates in packaging/ filled."""
        version = self.version
        values = {
            "VERSION": version, "PACKAGE_VERSION": f"{abi}.{version.split('.', 1)[1]}", "ABI": str(abi),
            "PC_PREFIX": "${pcfiledir}/../..", "PC_CFLAGS": "-I${prefix}/include",
            "LIBS_PRIVATE": " ".join("-l" + l for l in system_libs), "CMAKE_PREFIX_UP": "/..",
            "CMAKE_TO_LIBDIR": "/../..", "CMAKE_HEADERS": "include", "CMAKE_LIBS": ";".join(system_libs),
            "SHARED": shared, "SONAME": soname, "IMPLIB": implib, "STATIC": static,
        }

        def fill(template, dest):
            text = load(self, os.path.join(self.source_folder, "packaging", template))
            save(self, dest, re.sub(r"@([A-Z_]+)@", lambda m: values[m.group(1)], text))

        fill("orient.pc.in", os.path.join(lib, "pkgconfig", "orient.pc"))
        fill("orient-static.pc.in", os.path.join(lib, "pkgconfig", "orient-static.pc"))
        fill("orientConfig.cmake.in", os.path.join(lib, "cmake", "orient", "orientConfig.cmake"))
        fill("orientConfigVersion.cmake.in", os.path.join(lib, "cmake", "orient", "orientConfigVersion.cmake"))

    def package_info(self):
        # find_package(orient) loads the package's own lib/cmake/orient/orientConfig.cmake.
        self.cpp_info.set_property("cmake_find_mode", "none")
        self.cpp_info.builddirs = [""]
        self.cpp_info.set_property("pkg_config_name", "orient")
        # For generators other than CMake's (the shared library by name).
        self.cpp_info.libs = ["orient"]
        self.cpp_info.bindirs = ["lib"] if self.settings.os == "Windows" else []
