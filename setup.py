# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Builds the `ebgeom._ebgeom` extension with CMake (python/CMakeLists.txt) for `pip install .`.

Environment: EBGEOM_NATIVE=0 builds without -march=native (for a wheel that runs on other x86-64
machines); CMAKE_BUILD_PARALLEL_LEVEL sets the build jobs (default 2); EBGEOM_CMAKE_ARGS adds
CMake arguments (e.g. -DEBGEOM_WITH_OPENVDB=ON for .vdb output).
"""

import os
import re
import shlex
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    text = open(os.path.join(ROOT, "include", "ebgeom", "version.hpp")).read()
    return re.search(r'#define EBGEOM_VERSION_STRING "([0-9.]+)"', text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        out_dir = os.path.dirname(os.path.abspath(self.get_ext_fullpath(ext.name)))
        build_dir = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        os.makedirs(build_dir, exist_ok=True)
        native = os.environ.get("EBGEOM_NATIVE", "1") not in ("0", "OFF", "off", "")
        args = [
            "cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
            "-DEBGEOM_BUILD_PYTHON=ON", "-DEBGEOM_BUILD_TESTS=OFF", "-DEBGEOM_BUILD_CLI=OFF",
            "-DEBGEOM_BUILD_EXAMPLES=OFF", "-DEBGEOM_NATIVE=" + ("ON" if native else "OFF"),
            # no OpenVDB unless asked (EBGEOM_CMAKE_ARGS=-DEBGEOM_WITH_OPENVDB=ON): the extension
            # then links no system library beyond zlib
            "-DEBGEOM_WITH_OPENVDB=OFF",
            "-DPython_EXECUTABLE=" + sys.executable, "-DEBGEOM_PYTHON_OUTPUT_DIR=" + out_dir,
        ]
        args += shlex.split(os.environ.get("EBGEOM_CMAKE_ARGS", ""))
        subprocess.check_call(args)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call(["cmake", "--build", build_dir, "--target", "ebgeom_python",
                               "-j", jobs])


setup(version=version(), ext_modules=[Extension("ebgeom._ebgeom", sources=[])],
      cmdclass={"build_ext": CMakeBuild}, zip_safe=False)
