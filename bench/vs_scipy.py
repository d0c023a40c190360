#!/usr/bin/python3
"""dewall.Delaunay side by side with scipy.spatial.Delaunay (Qhull), for the README.

    PYTHONPATH=build/python /usr/bin/python3 bench/vs_scipy.py [--sizes 1e5 1e6]

Rows: seconds on uniform points in the unit cube (each construction timed with its
`neighbors`, which scipy always builds), then what each does on a 3D integer grid and
on exactly cospherical integer points: every output is judged by dewall.certify
(canonical = the triangulation CGAL's perturbation defines). Prints a Markdown table.
Wall-clock seconds on a shared machine are noisy; the ratios within one run are the
figure.
"""

import argparse
import os
import time

import numpy as np
from scipy.spatial import Delaunay as ScipyDelaunay

import dewall


def timed(build):
    """(seconds, result or the exception it raised)."""
    start = time.perf_counter()
    try:
        result = build()
        result.neighbors  # scipy builds them in its constructor; dewall on first use
    except Exception as error:  # noqa: BLE001 — the table reports what happened
        return time.perf_counter() - start, error
    return time.perf_counter() - start, result


def same_simplices(a, b):
    """Whether two constructions (or errors) gave the same simplices, as vertex sets."""
    if isinstance(a, Exception) or isinstance(b, Exception) or a.nsimplex != b.nsimplex:
        return False
    rows = lambda t: np.unique(np.sort(t.simplices, axis=1), axis=0)  # noqa: E731
    return np.array_equal(rows(a), rows(b))


def verdict(points, outcome):
    """What became of a construction: its certificate, or its error."""
    seconds, result = outcome
    if isinstance(result, Exception):
        first_line = str(result).strip().splitlines()[0] if str(result).strip() else type(result).__name__
        return f"{type(result).__name__}: {first_line[:60]} ({seconds:.2f} s)"
    c = dewall.certify(points, result.simplices, canonical=True)
    if c.canonical:
        what = "canonical"
    elif c.delaunay:
        what = "Delaunay, not canonical"
    else:
        what = f"**not Delaunay** ({c.violation.rule})"
    return f"{what}, {result.nsimplex} simplices ({seconds:.2f} s)"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", nargs="+", type=float, default=[1e5, 1e6])
    parser.add_argument("--grid", type=int, default=20, help="grid side k: k^3 points")
    parser.add_argument("--sphere", type=int, default=5000, help="about this many cospherical points")
    args = parser.parse_args()
    cores = os.cpu_count()
    print(f"| input | scipy.spatial.Delaunay | dewall.Delaunay, 1 thread | dewall.Delaunay, {cores} threads |")
    print("|---|---|---|---|")
    for n in map(int, args.sizes):
        points = dewall.generate("uniform", n, dim=3, seed=1)
        runs = [timed(lambda: ScipyDelaunay(points)), timed(lambda: dewall.Delaunay(points, threads=1)),
                timed(lambda: dewall.Delaunay(points))]
        cells = [f"{s:.2f} s" if not isinstance(r, Exception) else f"{type(r).__name__}" for s, r in runs]
        note = " (same simplices)" if same_simplices(runs[0][1], runs[2][1]) else ""
        print(f"| {n:.0e} uniform points in a cube, time{note} | " + " | ".join(cells) + " |", flush=True)
    k = args.grid
    cases = [(f"3D grid {k}×{k}×{k} ({k**3} points)", dewall.generate("grid", k**3, dim=3)),
             ("cospherical integer points", dewall.generate("lattice-sphere", args.sphere, dim=3))]
    for name, points in cases:
        if name.startswith("cospherical"):
            name = f"{len(points)} {name} (x² + y² + z² constant)"
        row = [verdict(points, timed(lambda: ScipyDelaunay(points))),
               verdict(points, timed(lambda: dewall.Delaunay(points, threads=1))),
               verdict(points, timed(lambda: dewall.Delaunay(points)))]
        print(f"| {name} | " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
