"""Builds dewall._dewall with the project's CMake build, for `pip install .`.

setuptools is the build backend because Debian 12 packages it (python3-setuptools);
it has no scikit-build-core or meson-python, and pip cannot fetch them offline.
The extension is the CMake target dewall_python (python/CMakeLists.txt), built
with only the libraries it links (no tests, CLI, benchmarks or examples) in
setuptools' build_temp, with ccache when present, then copied where setuptools
expects it. DEWALL_BUILD_JOBS sets the parallel build jobs (default: 1).
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(self.build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython_EXECUTABLE={sys.executable}", "-DDEWALL_BUILD_PYTHON=ON",
                     "-DDEWALL_BUILD_TESTS=OFF", "-DDEWALL_BUILD_CLI=OFF", "-DDEWALL_BUILD_BENCH=OFF",
                     "-DDEWALL_BUILD_EXAMPLES=OFF"]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        subprocess.run(configure, check=True)
        jobs = os.environ.get("DEWALL_BUILD_JOBS", "1")
        subprocess.run(["cmake", "--build", str(build), "--target", "dewall_python", "-j", jobs], check=True)
        built = next((build / "python" / "dewall").glob("_dewall*.so"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


# build/ is also the CMake build of ./test: keep setuptools' files in a folder of their own.
setup(ext_modules=[CMakeExtension("dewall._dewall")], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": "build/python-package"}})
