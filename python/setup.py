# Builds the extension ellipsect._ellipsect with the project's CMake (target _ellipsect,
# which links the library target), so no source file is listed twice.
#
# Environment: ELLIPSECT_BUILD_DIR (relative to the repository; default build/python, kept
# between installs so rebuilds are incremental; a tree already configured keeps its own
# choice of tests, benchmarks and tools, so the test script builds the module in its Release
# tree, whose library is built already); CMake itself reads CMAKE_CXX_COMPILER_LAUNCHER (e.g.
# ccache) and CMAKE_BUILD_PARALLEL_LEVEL.
import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent.parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        out = Path(self.get_ext_fullpath(ext.name)).resolve().parent
        build = ROOT / os.environ.get("ELLIPSECT_BUILD_DIR", "build/python")
        args = [
            "-G", "Ninja",
            "-DCMAKE_BUILD_TYPE=Release",
            "-DELLIPSECT_BUILD_PYTHON=ON",
            f"-DPython3_EXECUTABLE={sys.executable}",
            f"-DCMAKE_LIBRARY_OUTPUT_DIRECTORY={out}",
        ]
        if not (build / "CMakeCache.txt").exists():
            args += ["-DELLIPSECT_BUILD_TESTS=OFF", "-DELLIPSECT_BUILD_BENCH=OFF", "-DELLIPSECT_BUILD_TOOLS=OFF"]
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *args], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "_ellipsect"], check=True)


setup(ext_modules=[Extension("ellipsect._ellipsect", sources=[])], cmdclass={"build_ext": CMakeBuild})
