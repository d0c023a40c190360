"""Builds dewall._dewall with the project's CMake build, for `pip install .`.

setuptools is the build backend because Debian 12 packages it (python3-setuptools);
it has no scikit-build-core or meson-python, and pip cannot fetch them offline.
The extension is the CMake target dewall_python (python/CMakeLists.txt), built
with only the libraries it links (no tests, CLI, benchmarks, examples or MPI) in
setuptools' build_temp, with Ninja and ccache when present, then copied where
setuptools expects it.

Jobs: DEWALL_BUILD_JOBS, else CMAKE_BUILD_PARALLEL_LEVEL, else every CPU this
process may use. Progress: pip keeps a build's output to itself unless run with
-v, so CMake's lines ("[ 42%] Building CXX object ...") also go to the terminal
(/dev/tty) when there is one, and always to build/python-package/cmake-build.log;
DEWALL_BUILD_PROGRESS=0 keeps them off the terminal.
"""

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD_BASE = "build/python-package"  # build/ is also the CMake build of ./test: a folder of its own

# setuptools commands that pip runs and that need `wheel` (setuptools before 70.1 has no bdist_wheel of its own).
_WHEEL_COMMANDS = {"bdist_wheel", "dist_info", "editable_wheel"}


def _check_wheel():
    """Stops with what is missing and how to get it, instead of setuptools' "invalid command
    'bdist_wheel'", when pip runs an interpreter without the `wheel` package."""
    if not _WHEEL_COMMANDS.intersection(sys.argv[1:]):
        return
    try:
        import wheel  # noqa: F401
        return
    except ImportError:
        pass
    try:
        from setuptools.command import bdist_wheel  # noqa: F401
        return
    except ImportError:
        pass
    sys.exit(f"dewall: building the package needs the Python package 'wheel', which {sys.executable} "
             "does not have. Install it for that interpreter (Debian: apt-get install python3-wheel, "
             "for /usr/bin/python3), or run pip with an interpreter that has it, e.g. Debian's: "
             "/usr/bin/python3 -m pip install --no-build-isolation . (scripts/setup.sh installs "
             "everything else it needs).")


def _jobs():
    for name in ("DEWALL_BUILD_JOBS", "CMAKE_BUILD_PARALLEL_LEVEL"):
        if os.environ.get(name, "").strip():
            return os.environ[name].strip()
    try:
        return str(len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # not Linux
        return str(os.cpu_count() or 1)


def _terminal():
    """The terminal to show progress on when pip holds standard output, or None."""
    if os.environ.get("DEWALL_BUILD_PROGRESS", "1") == "0" or sys.stdout.isatty():
        return None  # off, or standard output is the terminal already
    try:
        return open("/dev/tty", "w")
    except OSError:  # no controlling terminal (CI, a service)
        return None


def _run(command, log, terminal):
    """Runs `command`, copying each line of its output to standard output, the log and the terminal."""
    log.write("$ " + " ".join(command) + "\n")
    log.flush()
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1,
                          errors="replace") as process:
        for line in process.stdout:
            sys.stdout.write(line)
            sys.stdout.flush()
            log.write(line)
            log.flush()
            if terminal is not None:
                terminal.write("  " + line)
                terminal.flush()
    if process.returncode != 0:
        raise subprocess.CalledProcessError(process.returncode, command)


def cmake_commands(build, jobs):
    """The configure and build commands: only the module's target and the libraries it links."""
    configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                 f"-DPython_EXECUTABLE={sys.executable}", "-DDEWALL_BUILD_PYTHON=ON",
                 "-DDEWALL_BUILD_TESTS=OFF", "-DDEWALL_BUILD_CLI=OFF", "-DDEWALL_BUILD_BENCH=OFF",
                 "-DDEWALL_BUILD_EXAMPLES=OFF", "-DDEWALL_BUILD_MPI=OFF"]
    # Ninja compiles the module's sources alongside the libraries' (Make waits for the libraries
    # first); a build folder keeps the generator it was made with.
    if shutil.which("ninja") and not (Path(build) / "CMakeCache.txt").exists():
        configure += ["-G", "Ninja"]
    if shutil.which("ccache"):
        configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    return configure, ["cmake", "--build", str(build), "--target", "dewall_python", "--parallel", jobs]


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        jobs = _jobs()
        configure, compile_ = cmake_commands(build, jobs)
        log_path = ROOT / BUILD_BASE / "cmake-build.log"
        log_path.parent.mkdir(parents=True, exist_ok=True)
        terminal = _terminal()
        start = time.monotonic()
        with open(log_path, "w") as log:
            note = (f"dewall: building the compiled module with CMake, {jobs} parallel jobs (DEWALL_BUILD_JOBS "
                    f"sets them); a few minutes from scratch; log: {log_path}\n")
            for stream in (sys.stdout, log) + ((terminal,) if terminal else ()):
                stream.write(note)
                stream.flush()
            outcome = "failed, see the log"
            try:
                _run(configure, log, terminal)
                _run(compile_, log, terminal)
                outcome = "done"
            finally:
                if terminal is not None:
                    terminal.write(f"dewall: CMake {outcome} after {time.monotonic() - start:.0f} s\n")
                    terminal.close()
        built = next((build / "python" / "dewall").glob("_dewall*.so"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


if __name__ == "__main__":  # pip's backend runs this file as a script; the tests import it
    _check_wheel()
    setup(ext_modules=[CMakeExtension("dewall._dewall")], cmdclass={"build_ext": CMakeBuild},
          options={"build": {"build_base": BUILD_BASE}})
