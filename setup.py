# SPDX-License-Identifier: MIT
"""Builds the package meshmorph (python/meshmorph and its compiled core) with CMake.

MESHMORPH_BUILD_DIR names a CMake build folder of this tree (configured with the Python
module) to build the module in, and take it from: a few seconds where it is built already.
Without it the module is configured and built in build/pip (the whole library: minutes).
CMAKE_ARGS are passed to that configuration (-DPython3_EXECUTABLE=... and the like).
"""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def version():
    """The project's version, from the top CMakeLists.txt."""
    return re.search(r"project\(meshmorph VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())[1]


class CMakeBuild(build_ext):
    """The extension meshmorph._meshmorph, built by CMake's target meshmorph_python."""

    def build_extension(self, ext):
        build = os.environ.get("MESHMORPH_BUILD_DIR")
        if build:
            build = pathlib.Path(build).resolve()
            if not (build / "CMakeCache.txt").exists():
                sys.exit(f"setup.py: MESHMORPH_BUILD_DIR={build} is no configured CMake build folder")
        else:
            build = ROOT / "build" / "pip"
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                            f"-DPython3_EXECUTABLE={sys.executable}", "-DMESHMORPH_BUILD_TESTS=OFF",
                            "-DMESHMORPH_BUILD_BENCH=OFF", "-DMESHMORPH_BUILD_PYTHON=ON",
                            *shlex.split(os.environ.get("CMAKE_ARGS", ""))], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "meshmorph_python", "meshmorph_python_package",
                        "-j", str(os.cpu_count() or 1)], check=True)
        built = list((build / "python" / "meshmorph").glob("_meshmorph*.so"))
        if len(built) != 1:
            sys.exit(f"setup.py: expected one _meshmorph module in {build}/python/meshmorph, found {len(built)}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    version=version(),
    packages=["meshmorph"],
    package_dir={"meshmorph": "python/meshmorph"},
    ext_modules=[Extension("meshmorph._meshmorph", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build folders inside CMake's build folder (ignored by git).
    options={"build": {"build_base": "build/setuptools"}, "egg_info": {"egg_base": "build"}},
)
