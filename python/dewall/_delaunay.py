"""dewall.Delaunay: scipy.spatial.Delaunay's interface over the exact triangulator."""

from functools import cached_property

import numpy as np

from . import _dewall
from ._arrays import as_coordinates


class Delaunay:
    """The Delaunay triangulation of points in E^d (d = 2 … 6), exact.

    Delaunay(points, engine="auto", threads=None)

    points: array of shape (n, d). A C-contiguous float64 array is used in
        place, not copied (so do not change it while this object is in use);
        other real arrays are converted exactly (dewall._arrays).
    engine: "auto" (in 2D and 3D the hybrid, handing over to CGAL's
        incremental construction when DeWall's searches prove too costly, e.g.
        points on one sphere; in 4D and up dewall's own incremental
        construction), "hybrid" (DeWall's walls down to regions of n/4 points,
        each triangulated incrementally), "dewall" (walls all the way down),
        "incremental" (dewall's own Bowyer-Watson) or "cgal". The simplices
        are the same with each.
    threads: the most threads to use (None: all cores). The result does not
        depend on it.

    The work runs without the GIL. Degenerate input (grids, cospherical
    points) is resolved by CGAL's symbolic perturbation, so the simplices are
    CGAL's; duplicate points are one vertex, the first occurrence (see
    `duplicates`).

    Raises ValueError (dewall.InvalidInput, with `.point` naming the input
    point when there is one) for a NaN or infinite coordinate, fewer than d + 1
    distinct points, or points that do not span E^d, with the messages of the
    `dewall triangulate` command; TypeError for an array of the wrong dtype or
    shape.

    Attributes (as scipy's): points, simplices, neighbors, convex_hull, ndim,
    npoints, nsimplex; find_simplex(xi). Also: duplicates, statistics.
    """

    def __init__(self, points, engine="auto", threads=None):
        self.points = as_coordinates(points)
        if threads is not None:
            threads = int(threads)
        self._triangulation = _dewall.triangulate(self.points, str(engine), threads)

    @property
    def ndim(self):
        return self.points.shape[1]

    @property
    def npoints(self):
        return self.points.shape[0]

    @property
    def nsimplex(self):
        return self.simplices.shape[0]

    @cached_property
    def simplices(self):
        """int32 array (nsimplex, ndim + 1): input indices, each simplex positively oriented
        (det[p1 - p0, …, pd - p0] > 0). Read-only: find_simplex relies on it."""
        return self._triangulation.simplices()

    @cached_property
    def neighbors(self):
        """int32 array (nsimplex, ndim + 1): neighbors[i, j] is the simplex across the facet of
        simplex i opposite its vertex j, -1 when that facet is on the convex hull (scipy's
        convention). Computed on first use."""
        return self._triangulation.neighbors()

    @cached_property
    def convex_hull(self):
        """int32 array (nfacets, ndim): the facets of the convex hull, each as the simplex
        facet it is (simplices[i] without its vertex j where neighbors[i, j] == -1)."""
        simplex, opposite = np.nonzero(self.neighbors == -1)
        keep = np.ones((simplex.size, self.ndim + 1), dtype=bool)
        keep[np.arange(simplex.size), opposite] = False
        return self.simplices[simplex][keep].reshape(simplex.size, self.ndim)

    @cached_property
    def duplicates(self):
        """int array (k, 2): one row (i, j) for each input point i that repeats an earlier
        point; j is the first occurrence, the vertex that stands for it. Empty when all
        points are distinct. (scipy lists such points in `coplanar`.)"""
        first = self._triangulation.first_occurrences()
        repeated = np.nonzero(first != np.arange(first.size))[0]
        return np.column_stack((repeated, first[repeated])).astype(np.int32)

    @property
    def statistics(self):
        """Counters of the run: the engine that built the simplices ("dewall", "hybrid", "incremental" or "cgal"),
        distinct points, simplices, build_seconds, … (as `dewall triangulate --stats`)."""
        return self._triangulation.statistics

    def find_simplex(self, xi, bruteforce=False, tol=None):
        """The simplex containing each point of xi (shape (..., ndim)), -1 outside the hull.

        bruteforce and tol are scipy's; they are accepted and ignored: the test is exact.

        Exact: decided by the exact orientation predicate, with no tolerance. A point on a
        face shared by several simplices gets one of them; a point outside the hull by
        any margin, or with a NaN or infinite coordinate, gets -1. Walks from the
        previous answer: sorted or clustered queries are fastest.
        """
        xi = np.asarray(xi)
        if xi.ndim == 0 or xi.shape[-1] != self.ndim:
            raise TypeError(f"xi must have shape (..., {self.ndim}), not {xi.shape}")
        flat = as_coordinates(xi.reshape(-1, self.ndim), "xi")
        return self._triangulation.locate(flat).reshape(xi.shape[:-1])

    def __repr__(self):
        return f"<dewall.Delaunay: {self.npoints} points in E^{self.ndim}, {self.nsimplex} simplices>"
