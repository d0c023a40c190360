"""Ctrl-C and progress during long calls (issue 57): SIGINT sent from another process while a
construction, neighbors, find_simplex, ConvexHull or Voronoi runs raises KeyboardInterrupt
within a second, what was built is freed, and the module works afterwards; progress=True draws
a bar on stderr and progress=callable gets fractions that never go back and end at 1.0.

Each interrupted call runs in a child interpreter (a signal to pytest's own process would
interrupt the test run). The child announces the call, the test sends SIGINT, and the child
reports when KeyboardInterrupt arrived (time.monotonic is system-wide on Linux) and its memory."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import dewall

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/self/status")

# The child: builds what the call needs, prints "go" as the call starts (from the progress
# callback when the call takes one: the work is then surely running), waits for SIGINT.
CHILD = textwrap.dedent("""
    import gc, json, sys, time
    import numpy as np
    import dewall

    def rss_mb():
        with open("/proc/self/status") as f:
            return next(int(l.split()[1]) for l in f if l.startswith("VmRSS")) / 1024

    call, n, d = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    points = np.random.default_rng(57).random((n, d))
    queries = np.random.default_rng(58).random((4 * n, d))
    tri = None if call in ("delaunay", "hull", "voronoi") else dewall.Delaunay(points)
    gc.collect()
    before = rss_mb()
    announced = []

    def announce(fraction=None):
        if not announced:
            announced.append(True)
            print("go", flush=True)

    def run():
        if call == "delaunay":
            dewall.Delaunay(points, progress=announce)
        elif call == "hull":
            dewall.ConvexHull(points, progress=announce)
        elif call == "voronoi":
            dewall.Voronoi(points, progress=announce)
        elif call == "neighbors":
            announce()
            tri._triangulation.neighbors()
        elif call == "find_simplex":
            tri.neighbors
            announce()
            tri.find_simplex(queries)

    result = {"call": call}
    try:
        run()
        result["completed"] = True
    except KeyboardInterrupt:
        result["interrupted_at"] = time.monotonic()
    gc.collect()
    result["grew_mb"] = rss_mb() - before
    start = time.monotonic()  # the whole call, uninterrupted (neighbors: none kept from before)
    run()
    result["whole_call"] = time.monotonic() - start
    small = dewall.Delaunay(np.random.default_rng(1).random((100, d)))
    result["still_works"] = bool(small.nsimplex > 0 and (small.find_simplex(small.points[:5]) >= 0).all())
    print(json.dumps(result), flush=True)
""")

# Sizes whose call takes a few seconds in a Release build on one loaded core, at most.
CALLS = [("delaunay", 400_000, 3), ("hull", 200_000, 5), ("voronoi", 100_000, 3),
         ("neighbors", 400_000, 3), ("find_simplex", 200_000, 3)]


@pytest.mark.parametrize("call, n, d", CALLS, ids=[c[0] for c in CALLS])
def test_ctrl_c_stops_a_long_call_within_a_second(call, n, d):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    child = subprocess.Popen([sys.executable, "-c", CHILD, call, str(n), str(d)], stdout=subprocess.PIPE,
                             text=True, env=env)
    try:
        assert child.stdout.readline().strip() == "go"
        time.sleep(0.2)  # into the work
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        result = json.loads(child.stdout.readline())
        assert child.wait(timeout=60) == 0
    finally:
        if child.poll() is None:
            child.kill()
    if result.get("completed"):
        pytest.skip(f"{call} on {n} points ended before the signal (a fast machine): nothing to interrupt")
    latency = result["interrupted_at"] - sent
    assert latency < 1.0, result
    assert latency < result["whole_call"] / 2, result  # stopped, not finished: Ctrl-C did not wait for the end
    assert result["still_works"], result
    # What the interrupted call built is gone: the whole build holds hundreds of MB here.
    assert result["grew_mb"] < 64, result


def test_progress_callable_gets_fractions_up_to_one(rng):
    seen = []
    points = rng.random((100_000, 3))
    tri = dewall.Delaunay(points, progress=seen.append)
    assert tri.nsimplex > 0
    assert seen and seen[-1] == 1.0
    assert all(0.0 <= f <= 1.0 for f in seen)
    assert all(a <= b for a, b in zip(seen, seen[1:]))
    hull_seen = []
    dewall.ConvexHull(points, progress=hull_seen.append)
    assert hull_seen[-1] == 1.0
    voronoi_seen = []
    dewall.Voronoi(points[:50_000], progress=voronoi_seen.append)
    assert voronoi_seen[-1] == 1.0
    interpolated = []
    dewall.interpolate.LinearNDInterpolator(points, points[:, 0], progress=interpolated.append)
    assert interpolated[-1] == 1.0


def test_progress_true_draws_a_bar_on_stderr(capsys, rng):
    dewall.Delaunay(rng.random((2_000, 2)), progress=True)
    err = capsys.readouterr().err
    assert "dewall.Delaunay [" in err and "100%" in err and err.endswith("\n")
    dewall.Delaunay(rng.random((2_000, 2)), progress=False)
    assert capsys.readouterr().err == ""


def test_an_exception_from_the_progress_callable_stops_the_work(rng):
    class Enough(Exception):
        pass

    def stop(fraction):
        if fraction > 0:
            raise Enough

    with pytest.raises(Enough):
        dewall.Delaunay(rng.random((400_000, 3)), progress=stop)
    with pytest.raises(TypeError, match="progress must be"):
        dewall.Delaunay(rng.random((10, 2)), progress="yes")
