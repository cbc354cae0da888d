"""A consumer of the orient package: find_package(orient 1) and both imported targets,
from C and from C++ (orient.hpp), built with CMake and run."""

import os

from conan import ConanFile
from conan.tools.build import can_run
from conan.tools.cmake import CMake, cmake_layout


class OrientTestPackage(ConanFile):
    settings = "os", "arch", "compiler", "build_type"
    generators = "CMakeToolchain", "CMakeDeps", "VirtualRunEnv"

    def requirements(self):
        self.requires(self.tested_reference_str)

    def layout(self):
        cmake_layout(self)

    def build(self):
        cmake = CMake(self)
        cmake.configure()
        cmake.build()

    def test(self):
        if can_run(self):
            for exe in ("consumer_shared", "consumer_static", "consumer_cpp"):
                self.run(os.path.join(self.cpp.build.bindir, exe), env="conanrun")
