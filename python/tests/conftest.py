"""Shared helpers of the Python suite: seeded randomness, simplex sets, the CLI."""

import os
import subprocess

import numpy as np
import pytest

SEED = 20240614  # fixed, and printed in every failure report: a failure can be replayed


def pytest_report_header(config):
    return f"dewall python suite: random seed {SEED}"


@pytest.fixture
def rng():
    return np.random.default_rng(SEED)


def simplex_set(simplices):
    """The simplices as a set of sorted vertex tuples (orientation and order ignored)."""
    return {tuple(sorted(map(int, s))) for s in simplices}


def cli_path():
    return os.environ.get("DEWALL_CLI") or None


def cli_triangulate(points, tmp_path):
    """The `dewall triangulate` output for `points` (written as text, every double kept by repr)."""
    cli = cli_path()
    if not cli:
        pytest.skip("DEWALL_CLI is not set (the dewall executable; ctest sets it)")
    path = tmp_path / "points.txt"
    path.write_text("".join(" ".join(repr(float(c)) for c in p) + "\n" for p in points))
    out = subprocess.run([cli, "triangulate", str(path), "--quiet"], check=True, capture_output=True, text=True).stdout
    return np.array([[int(v) for v in line.split()] for line in out.splitlines()], dtype=np.int64)
