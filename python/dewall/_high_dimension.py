"""7 dimensions and up: the triangulation behind Delaunay, ConvexHull and Voronoi when the points
have more coordinates than the library's kernel and engines are compiled for (D = 2 … 6).

The compiled module's `triangulate_dd` runs CGAL's `Delaunay_triangulation` over
`Epick_d<Dynamic_dimension_tag>` (python/src/high_dimension.cpp): filtered exact predicates and
CGAL's symbolic perturbation, so the simplices are CGAL's by definition — the same answer the
library gives below 7 dimensions, where it equals CGAL's on every input. Each simplex is
positively oriented, duplicates are one vertex (the first occurrence), `neighbors` and -1 as in
2 … 6 dimensions. `DimensionFreeTriangulation` has the methods of the compiled
`_dewall.Triangulation` that the Python classes call, so nothing above it changes with the
dimension. What is missing above 6 dimensions: `dewall.certify` (the certifier is compiled for
2 … 6 dimensions) and the `engine`/`threads` choices (CGAL's construction, one thread).
"""

import time

import numpy as np

from . import _dewall
from ._errors import translated
from ._dewall import InvalidInput


def _read_only(array):
    array.flags.writeable = False
    return array


class DimensionFreeTriangulation:
    """Simplices (and neighbours) of points in any dimension, with _dewall.Triangulation's methods."""

    def __init__(self, points, simplices, neighbors=None, statistics=None):
        self._points = points
        self._simplices = _read_only(np.ascontiguousarray(simplices, dtype=np.int32))
        self._neighbors = None if neighbors is None else _read_only(np.ascontiguousarray(neighbors, dtype=np.int32))
        self.statistics = statistics if statistics is not None else {
            "engine": "given simplices", "input_points": points.shape[0], "simplices": len(self._simplices)}

    @classmethod
    def triangulate(cls, points, progress=None):
        """CGAL's dD Delaunay triangulation of `points` (float64, C-contiguous, (n, d))."""
        start = time.perf_counter()
        try:
            simplices, neighbors = _dewall.triangulate_dd(points, progress)
        except InvalidInput as error:
            raise translated(error) from None
        seconds = time.perf_counter() - start
        distinct = int(np.count_nonzero(_first_occurrences(points) == np.arange(points.shape[0])))
        statistics = {"engine": "cgal-dd (CGAL's dD Delaunay_triangulation, Epick_d; 7 dimensions and up)",
                      "input_points": points.shape[0], "distinct_points": distinct,
                      "simplices": len(simplices), "build_seconds": seconds}
        return cls(points, simplices, neighbors, statistics)

    def simplices(self):
        return self._simplices

    def neighbors(self):
        if self._neighbors is None:
            from ._boundary import ridge_pairs  # the simplex across each facet: facets matched in pairs

            self._neighbors = _read_only(ridge_pairs(self._simplices) if len(self._simplices) else
                                         np.empty_like(self._simplices))
        return self._neighbors

    def locate(self, xi):
        """The simplex containing each row of xi (exact orientation walk), -1 outside the hull."""
        return _dewall.locate_dd(self._points, self._simplices, self.neighbors(), xi)

    def locate_weights(self, xi, rcond_limit):
        raise ValueError("locate_weights: points of 2 or 3 dimensions")

    def first_occurrences(self):
        return _first_occurrences(self._points)

    def cospherical_neighbours(self):
        """Pairs (i, n), i < n, of neighbouring simplices with one circumsphere (exact, unperturbed)."""
        simplices, neighbors = self._simplices, self.neighbors()
        i, j = np.nonzero(neighbors > np.arange(len(simplices))[:, None])
        n = neighbors[i, j]
        # the vertex of n opposite the shared facet: where n's neighbour is i
        opposite = simplices[n, np.argmax(neighbors[n] == i[:, None], axis=1)]
        rows = np.column_stack((simplices[i], opposite)).astype(np.uint32)
        on = _dewall.predicate_signs(self._points, rows, 1) == 0 if len(rows) else np.zeros(0, dtype=bool)
        return np.column_stack((i[on], n[on])).astype(np.int32).reshape(-1, 2)


def _first_occurrences(points):
    """For each row, the index of the first row equal to it (itself unless a duplicate)."""
    n = points.shape[0]
    order = np.lexsort(points.T[::-1])  # lexicographic and stable: equal rows keep input order
    rows = points[order]
    new_run = np.r_[True, np.any(rows[1:] != rows[:-1], axis=1)]
    heads = order[np.nonzero(new_run)[0]]
    first = np.empty(n, dtype=np.int32)
    first[order] = heads[np.cumsum(new_run) - 1]
    return first
