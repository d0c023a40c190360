#!/usr/bin/python3
"""dewall.Delaunay (with neighbors and transform), ConvexHull, Voronoi and interpolate.LinearNDInterpolator against
scipy's, for the README and bench/README.md.

    PYTHONPATH=build/python nice -n 15 taskset -c 0 /usr/bin/python3 bench/vs_scipy_hull_interpolate.py build --sizes 1e6
    PYTHONPATH=build/python nice -n 15 taskset -c 0 /usr/bin/python3 bench/vs_scipy_hull_interpolate.py hull
    PYTHONPATH=build/python nice -n 15 taskset -c 0 /usr/bin/python3 bench/vs_scipy_hull_interpolate.py \
        voronoi --dims 3 --sizes 2e4 --repeat 5
    PYTHONPATH=build/python nice -n 15 taskset -c 0 /usr/bin/python3 bench/vs_scipy_hull_interpolate.py \
        interpolate --dims 2 --sizes 1e6

build: Delaunay of n uniform points in the unit square / cube (seed 1) with `neighbors` and
`transform`, scipy's then dewall's (threads=1), each timed around all three.
hull: ConvexHull of n uniform points in the unit square / cube (seed 1), scipy's then
dewall's, each timed around the constructor; the facets compared as sets.
voronoi: Voronoi of n uniform points in the unit box (seed 11, as issue 57's example), scipy's
then dewall's, each timed around the constructor (which builds every attribute, the ridges'
and regions' lists included, in both); the ridges compared as sets of point pairs. --grid:
the points of an integer grid instead (every cell cospherical).
interpolate: LinearNDInterpolator(points, values) built and then evaluated on a regular
grid of about n queries over the unit box (row-major, the usual griddata layout; random
queries make scipy's walk far slower: --random-queries); values compared where both are finite.
Seconds are CPU seconds (time.process_time), best of --repeat; the ratio within one run is the figure.
"""

import argparse
import time

import numpy as np
import scipy.interpolate
import scipy.spatial

import dewall
import dewall.interpolate


def timed(function, repeat=1):
    """The best of `repeat` runs in CPU seconds of this process (under `taskset -c N` one CPU, so
    dewall runs one thread; on a shared machine wall time would count the other jobs), and the result."""
    best = float("inf")
    for _ in range(repeat):
        start = time.process_time()
        result = function()
        best = min(best, time.process_time() - start)
    return best, result


def facet_set(simplices):
    return {tuple(sorted(row)) for row in simplices.tolist()}


def hull(dims, sizes, repeat):
    for d in dims:
        for n in sizes:
            points = np.random.default_rng(1).random((n, d))
            theirs_seconds, theirs = timed(lambda: scipy.spatial.ConvexHull(points), repeat)
            ours_seconds, ours = timed(lambda: dewall.ConvexHull(points), repeat)
            same = facet_set(ours.simplices) == facet_set(theirs.simplices)
            print(f"ConvexHull {d}-D n={n:.0e}: dewall {ours_seconds:.3f} s, scipy {theirs_seconds:.3f} s, "
                  f"ratio {ours_seconds / theirs_seconds:.2f}, same facets: {same}", flush=True)


def voronoi(dims, sizes, repeat, grid=False):
    for d in dims:
        for n in sizes:
            points = dewall.generate("grid", n, dim=d) if grid else np.random.default_rng(11).random((n, d))
            n = len(points)
            theirs_seconds, theirs = timed(lambda: scipy.spatial.Voronoi(points), repeat)
            ours_seconds, ours = timed(lambda: dewall.Voronoi(points), repeat)
            same = facet_set(ours.ridge_points) == facet_set(theirs.ridge_points)
            print(f"Voronoi {d}-D {'grid' if grid else 'uniform'} n={n}: dewall {ours_seconds:.3f} s, scipy {theirs_seconds:.3f} s, "
                  f"ratio {ours_seconds / theirs_seconds:.2f}, same ridges: {same}", flush=True)


def build(dims, sizes, repeat):
    """Delaunay construction, then `neighbors` and `transform` (what interpolation and barycentric
    code read first): scipy's, then dewall's on the same points, one thread under taskset."""
    for d in dims:
        for n in sizes:
            points = np.random.default_rng(1).random((n, d))
            seconds = {}
            for name, make in (("scipy", lambda: scipy.spatial.Delaunay(points)),
                               ("dewall", lambda: dewall.Delaunay(points, threads=1))):
                def run():
                    tri = make()
                    tri.neighbors, tri.transform
                    return tri
                seconds[name], tri = timed(run, repeat)
                simplices = tri.nsimplex
                del tri
                print(f"Delaunay + neighbors + transform {d}-D n={n:.0e}, {name}: {seconds[name]:.2f} s "
                      f"({simplices} simplices)", flush=True)
            print(f"  ratio {seconds['dewall'] / seconds['scipy']:.2f}", flush=True)


def interpolate(dims, sizes, random_queries=False):
    for d in dims:
        for n in sizes:
            rng = np.random.default_rng(1)
            points = rng.random((n, d))
            values = np.sin(6 * points[:, 0]) * points[:, 1] + points[:, -1]
            if random_queries:
                queries = rng.random((n, d))
            else:
                k = round(n ** (1 / d))
                axes = np.meshgrid(*[np.linspace(0, 1, k)] * d, indexing="ij")
                queries = np.stack([a.ravel() for a in axes], axis=1)
            results, seconds = {}, {}
            for name, module in (("dewall", dewall.interpolate), ("scipy", scipy.interpolate)):
                build, f = timed(lambda: module.LinearNDInterpolator(points, values))
                evaluate, results[name] = timed(lambda: f(queries))
                seconds[name] = build + evaluate
                print(f"LinearNDInterpolator {d}-D n={n:.0e}, {len(queries)} queries, {name}: build {build:.2f} s, "
                      f"evaluate {evaluate:.2f} s, total {seconds[name]:.2f} s", flush=True)
            ours, theirs = results["dewall"], results["scipy"]
            both = np.isfinite(ours) & np.isfinite(theirs)
            print(f"  ratio {seconds['dewall'] / seconds['scipy']:.2f}; NaN: dewall {np.isnan(ours).sum()}, "
                  f"scipy {np.isnan(theirs).sum()}; largest difference {np.abs(ours[both] - theirs[both]).max():.1e}",
                  flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=("build", "hull", "voronoi", "interpolate"))
    parser.add_argument("--dims", type=int, nargs="+", default=[2, 3])
    parser.add_argument("--sizes", type=float, nargs="+", default=[1e5, 1e6])
    parser.add_argument("--repeat", type=int, default=1,
                        help="build, hull, voronoi: the best of this many runs of each")
    parser.add_argument("--grid", action="store_true",
                        help="voronoi: points of an integer grid (dewall.generate('grid'): cospherical cells)")
    parser.add_argument("--random-queries", action="store_true",
                        help="interpolate: n uniform random queries instead of the grid (scipy's walk is slow on them)")
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes]
    if args.what == "build":
        build(args.dims, sizes, args.repeat)
    elif args.what == "hull":
        hull(args.dims, sizes, args.repeat)
    elif args.what == "voronoi":
        voronoi(args.dims, sizes, args.repeat, args.grid)
    else:
        interpolate(args.dims, sizes, args.random_queries)


if __name__ == "__main__":
    main()
