"""The package around the module: no copy of the input, generators as the CLI's,
threads passed through, the GIL released while it works."""

import subprocess
import threading
import time

import numpy as np
import pytest

import dewall
from conftest import cli_path


def test_no_copy_of_contiguous_float64(rng):
    points = rng.random((100, 3))
    tri = dewall.Delaunay(points)
    assert tri.points is points
    fortran = np.asfortranarray(points)
    assert not np.shares_memory(dewall.Delaunay(fortran).points, fortran)


@pytest.mark.parametrize("d", [2, 7])
def test_simplices_writeable_without_misleading_find_simplex(rng, d):
    # scipy's simplices are writeable (its test_nd_simplex sorts them in place); find_simplex walks
    # the compiled copy, so it still answers right; neighbors stay read-only
    points = rng.random((50, d))
    tri = dewall.Delaunay(points)
    assert tri.simplices.dtype == np.int32 and tri.neighbors.dtype == np.int32
    centroids = points[tri.simplices].mean(axis=1)
    tri.simplices.sort()
    np.testing.assert_array_equal(tri.find_simplex(centroids), np.arange(tri.nsimplex))
    with pytest.raises(ValueError):
        tri.neighbors[0, 0] = 1


def test_generate_matches_the_cli():
    points = dewall.generate("uniform", 50, dim=4, seed=7)
    assert points.shape == (50, 4) and points.dtype == np.float64
    np.testing.assert_array_equal(points, dewall.generate("uniform", 50, dim=4, seed=7))
    if cli_path():
        text = subprocess.run([cli_path(), "generate", "uniform", "50", "--dim", "4", "--seed", "7", "--quiet"],
                              check=True, capture_output=True, text=True).stdout
        np.testing.assert_array_equal(points, np.loadtxt(text.splitlines()))
    assert dewall.generate("grid", 27).shape == (27, 3)


def test_statistics(rng):
    tri = dewall.Delaunay(rng.random((200, 3)), engine="cgal")
    assert tri.statistics["engine"] == "cgal" and tri.statistics["simplices"] == tri.nsimplex
    assert "200 points in E^3" in repr(tri)
    hybrid = dewall.Delaunay(rng.random((5000, 3)), engine="hybrid").statistics
    assert hybrid["engine"] == "hybrid" and 0 < hybrid["region_simplices"] <= hybrid["simplices"]


def test_gil_released_during_a_large_triangulation():
    points = dewall.generate("uniform", 60_000, dim=3, seed=1)
    done = threading.Event()
    ticks = 0

    def build():
        # Builds for at least 0.3 s whatever the machine's speed (one build of
        # these points took 0.13 s here): a held GIL would let the loop below
        # run only between builds.
        while True:
            dewall.Delaunay(points, threads=1)
            if time.perf_counter() - start > 0.3:
                break
        done.set()

    worker = threading.Thread(target=build)
    start = time.perf_counter()
    worker.start()
    while not done.is_set():  # Python code runs here while the worker triangulates
        ticks += 1
        time.sleep(0.001)
    worker.join()
    elapsed = time.perf_counter() - start
    # A held GIL would leave this loop a handful of ticks (one per switch interval at most).
    assert elapsed > 0.2 and ticks > elapsed * 100, (ticks, elapsed)


def test_concurrent_queries_on_one_triangulation(rng):
    points = rng.random((20_000, 3))
    tri = dewall.Delaunay(points)
    queries = rng.random((2_000, 3)) * 0.5 + 0.25  # well inside the hull
    results = [None] * 4

    def ask(i):  # the first asks build the neighbours, concurrently
        results[i] = tri.find_simplex(queries)

    workers = [threading.Thread(target=ask, args=(i,)) for i in range(4)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    for r in results[1:]:
        np.testing.assert_array_equal(r, results[0])
    assert (results[0] >= 0).all()
