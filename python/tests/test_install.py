"""`pip install .` (setup.py, issue 57): a parallel build of the module's target only, CMake's
output logged and shown while pip holds it, and a clear message when the interpreter lacks `wheel`.
The install itself takes minutes (bench/README.md has its time); these check its parts."""

import importlib.util
import io
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SETUP = ROOT / "setup.py"

pytestmark = pytest.mark.skipif(not SETUP.is_file(), reason="not run from a source tree")


@pytest.fixture
def setup_py():
    spec = importlib.util.spec_from_file_location("dewall_setup", SETUP)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # defines the helpers; setup() runs only as a script
    return module


def test_parallel_by_default_and_only_the_module(setup_py, monkeypatch, tmp_path):
    monkeypatch.delenv("DEWALL_BUILD_JOBS", raising=False)
    monkeypatch.delenv("CMAKE_BUILD_PARALLEL_LEVEL", raising=False)
    assert setup_py._jobs() == str(len(os.sched_getaffinity(0)))
    monkeypatch.setenv("CMAKE_BUILD_PARALLEL_LEVEL", "5")
    assert setup_py._jobs() == "5"
    monkeypatch.setenv("DEWALL_BUILD_JOBS", "3")
    assert setup_py._jobs() == "3"
    configure, build = setup_py.cmake_commands(tmp_path, "3")
    for part in ("TESTS", "CLI", "BENCH", "EXAMPLES", "MPI"):
        assert f"-DDEWALL_BUILD_{part}=OFF" in configure
    assert f"-DPython_EXECUTABLE={sys.executable}" in configure
    assert build[-4:] == ["--target", "dewall_python", "--parallel", "3"]
    assert ("Ninja" in configure) == bool(shutil.which("ninja"))


def test_build_output_goes_to_the_log_and_the_terminal(setup_py, tmp_path):
    log, terminal = io.StringIO(), io.StringIO()
    setup_py._run([sys.executable, "-c", "print('[ 50%] Building CXX object x.o')"], log, terminal)
    assert "[ 50%] Building CXX object x.o" in log.getvalue()
    assert "[ 50%] Building CXX object x.o" in terminal.getvalue()
    with pytest.raises(subprocess.CalledProcessError):
        setup_py._run([sys.executable, "-c", "raise SystemExit(2)"], io.StringIO(), None)


def test_missing_wheel_is_explained(tmp_path):
    """pip's metadata step (setup.py dist_info) with an interpreter that has no `wheel`: what is
    missing and how to get it, not setuptools' "invalid command 'bdist_wheel'"."""
    code = (
        "import runpy, sys\n"
        "class NoWheel:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name == 'wheel' or name.startswith('wheel.') or name == 'setuptools.command.bdist_wheel':\n"
        "            raise ImportError(name)\n"
        "sys.meta_path.insert(0, NoWheel())\n"
        "sys.argv = ['setup.py', 'dist_info', '--output-dir', sys.argv[1]]\n"
        "runpy.run_path('setup.py', run_name='__main__')\n"
    )
    run = subprocess.run([sys.executable, "-c", code, str(tmp_path)], cwd=ROOT, capture_output=True, text=True)
    assert run.returncode != 0
    assert "invalid command" not in run.stderr
    assert "needs the Python package 'wheel'" in run.stderr and "apt-get install python3-wheel" in run.stderr
    assert "/usr/bin/python3 -m pip install --no-build-isolation ." in run.stderr
