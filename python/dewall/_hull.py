"""dewall.ConvexHull and dewall.Voronoi: scipy.spatial's interfaces, from the exact Delaunay triangulation.

The hull facets are the Delaunay triangulation's boundary facets, the Voronoi
vertices its circumcentres (simplices with exactly one circumsphere, decided by
the exact unperturbed sphere test, give one vertex), the Voronoi ridges the duals
of its edges. Topology is exact; coordinates, normals, volumes are floating
point from the points.
"""

import contextlib
import gc
import re

import numpy as np

from . import _dewall
from ._arrays import as_coordinates
from ._errors import InvalidOption
from ._boundary import extreme_hull_edges_2d, extreme_ring_2d, merge_flat_faces_3d, ridge_pairs
from ._progress import progress_callback
from ._delaunay import (Delaunay, _check_qhull_options, _check_threads, _determinants, _option_in_effect,
                        _refuse_masked, _with_added_points)

__all__ = ["ConvexHull", "Voronoi"]

# The compiled module's kernel covers 2 … 6 dimensions (dewall._delaunay).
_MAX_COMPILED_DIMENSION = 6


class _FromDelaunay:
    """Construction, incremental mode and bounds shared by ConvexHull and Voronoi."""

    def __init__(self, points, incremental=False, qhull_options=None, *, engine="auto", threads=None,
                 furthest_site=False, progress=None):
        self._tri = Delaunay(points, furthest_site, incremental, qhull_options, engine=engine, threads=threads,
                             progress=progress)
        self._update()

    def _update(self):
        tri = self._tri
        self.points, self.ndim, self.npoints = tri.points, tri.ndim, tri.npoints
        self.min_bound, self.max_bound = tri.min_bound, tri.max_bound
        self.furthest_site = tri.furthest_site
        self._compute()

    def add_points(self, points, restart=False):
        """As scipy: needs incremental=True and no close(); dewall recomputes from all the points."""
        self._tri.add_points(points, restart)
        self._update()

    def close(self):
        self._tri.close()


def _good_option(options):
    """qhull_options without a "QGn" / "QG-n" token, and (n, whether good means visible) or None."""
    if options is None:
        return None, None
    if isinstance(options, bytes):
        options = options.decode("ascii")
    if not isinstance(options, str):
        return options, None  # _check_qhull_options says why
    good, rest = None, []
    for token in options.split():
        match = re.fullmatch(r"QG(-?)([0-9]+)", token)
        if match:
            good = (int(match.group(2)), match.group(1) != "-")
        else:
            rest.append(token)
    return " ".join(rest), good


class ConvexHull:
    """The convex hull of points in E^d (d >= 2), with scipy.spatial.ConvexHull's interface.

    ConvexHull(points, incremental=False, qhull_options=None, *, engine="auto", threads=None, progress=None)

    Attributes (as scipy's): points, vertices (2-D: counterclockwise), simplices (the facets,
    triangulated), neighbors, equations (outward unit normal, offset; normal . x + offset <= 0
    inside), coplanar, good, volume, area, min_bound, max_bound, ndim, npoints, nsimplex.

    Built by Quickhull with the library's exact orientation predicate (python/src/convex_hull.hpp):
    only the hull, no triangulation of the inside. Only the extreme points are vertices, as
    Qhull's: points inside a hull edge or flat face (a grid's sides, a cube's faces) are set
    aside exactly, and in 2-D and 3-D a flat face is a fan over its corners. In 4-D and up a
    hull with flat facets is the boundary of the exact Delaunay triangulation instead (points
    inside a flat facet are vertices there, the facet triangulated by CGAL's perturbation), as
    are nearly flat inputs (the exact Delaunay code then raises DegenerateInput or copes) and
    every hull in 7-D and up (Quickhull's exact filter is compiled for 2 … 6 dimensions; the
    triangulation there is CGAL's dD one, see dewall.Delaunay).
    `engine` and `threads` steer only that Delaunay triangulation. `coplanar` is empty: Qhull
    (option Qc) lists points it could not place for rounding, and neither boundary points nor
    duplicates (checked with scipy 1.10). Incremental mode recomputes from all the points.

    qhull_options "QGn" (Qhull's good facets): the hull of all the points but point n, and
    `good[i]` true when point n sees facet i strictly (exact orientation; a point in the
    facet's hyperplane does not see it); "QG-n": true for the others. Without it `good` is None.
    The facets' order is not Qhull's, so compare `good` together with `simplices`.

    progress (keyword only): as dewall.Delaunay's (True: a bar on sys.stderr; a callable of the
    fraction done). Ctrl-C stops the work within a fraction of a second (KeyboardInterrupt).
    """

    def __init__(self, points, incremental=False, qhull_options=None, *, engine="auto", threads=None,
                 progress=None):
        _refuse_masked(points, "Input points")
        progress_callback(progress)  # (checked now: a bar is made for each build)
        self._progress = progress
        qhull_options, self._good_point = _good_option(qhull_options)
        self._qhull_options = _check_qhull_options(qhull_options)
        self._engine, self._threads = str(engine), _check_threads(threads)
        self._incremental, self._closed = bool(incremental), False
        self._build(as_coordinates(points))

    def add_points(self, points, restart=False):
        """As scipy: needs incremental=True and no close(); dewall recomputes from all the points."""
        self._build(_with_added_points(self, points, "the hull"))

    def close(self):
        self._closed = True

    def _build(self, points):
        keep = None
        if self._good_point is not None:  # QGn: the hull of the other points, then `good` from point n
            n = self._good_point[0]
            if not n < points.shape[0]:
                raise InvalidOption(f"qhull option 'QG{n}': there is no point {n} ({points.shape[0]} points)")
            keep = np.delete(np.arange(points.shape[0]), n)
            self._hull(np.ascontiguousarray(points[keep]))
            self.simplices, self.vertices = keep[self.simplices].astype(np.int32), keep[self.vertices].astype(np.int32)
        else:
            self._hull(points)
        self.points, self.npoints = points, points.shape[0]
        self._bounds = None
        self.nsimplex = self.simplices.shape[0]
        self.coplanar = np.empty((0, 3), dtype=np.int32)
        self.good = None if keep is None else self._good()

    def _good(self):
        """QGn: the facets that point n sees strictly (exact orientation: a point in a facet's
        hyperplane does not see it, as in Qhull with scipy's options); QG-n: the others."""
        n, visible = self._good_point
        rows = np.column_stack((self.simplices, np.full(self.nsimplex, n))).astype(np.uint32)
        sign = _dewall.predicate_signs(self.points, rows, 0)
        # the inside's sign: 2-D edges run counterclockwise (inside on their left, positive),
        # facets in 3-D and up are stored with the inside on their negative side
        sees = sign < 0 if self.ndim == 2 else sign > 0
        return sees if visible else ~sees

    def _hull(self, points):
        self.points, self.ndim, self.npoints = points, points.shape[1], points.shape[0]
        d = self.ndim
        if d < 2:  # the Delaunay code's message
            Delaunay(points, engine=self._engine, threads=self._threads)
        hull = _dewall.convex_hull(points, progress_callback(self._progress, "dewall.ConvexHull"))
        if hull is None or (hull[3] and d > 3):
            self._from_delaunay(Delaunay(points, False, False, self._qhull_options, engine=self._engine,
                                         threads=self._threads, progress=self._progress))
        else:
            facets, neighbors, below, flat, normals = hull
            if d == 2:
                self._polygon(facets, flat)
            else:
                if d == 3 and flat:
                    facets, below, _ = merge_flat_faces_3d(points, facets, below)
                    neighbors, normals = ridge_pairs(facets), None
                self._facets(facets, neighbors, below, normals)

    def __repr__(self):
        return (f"<dewall.ConvexHull: {self.npoints} points in E^{self.ndim}, {len(self.vertices)} vertices, "
                f"{self.nsimplex} facets>")

    @property
    def min_bound(self):
        """The smallest coordinate along each axis, over all points (computed on first use)."""
        if self._bounds is None:
            self._bounds = (self.points.min(axis=0), self.points.max(axis=0))
        return self._bounds[0]

    @property
    def max_bound(self):
        """The largest coordinate along each axis, over all points (computed on first use)."""
        self.min_bound
        return self._bounds[1]

    def _from_delaunay(self, tri):
        """The boundary facets of the exact Delaunay triangulation `tri`."""
        simplex, opposite = np.nonzero(tri.neighbors == -1)
        if self.ndim == 2:
            edges = extreme_hull_edges_2d(self.points, tri.simplices, tri.neighbors)
            self._polygon_edges(edges)
            return
        facets, inside = tri.convex_hull.astype(np.int64), tri.simplices[simplex, opposite].astype(np.int64)
        flip = _dewall.predicate_signs(self.points, np.column_stack((facets, inside)).astype(np.uint32), 0) > 0
        facets[flip] = facets[flip][:, [1, 0] + list(range(2, self.ndim))]  # inside on the negative side
        if self.ndim == 3:
            facets, inside, _ = merge_flat_faces_3d(self.points, facets, inside)
        self._facets(facets, ridge_pairs(facets), inside)

    def _polygon(self, facets, flat):
        """2-D from Quickhull's edges (a, b), in clockwise order along the boundary (the inside
        on their right); reversed, counterclockwise."""
        ring = facets[::-1, 1].astype(np.int64)  # each edge's end, counterclockwise: b, then the a before it
        self._polygon_edges(extreme_ring_2d(self.points, ring, collinear=flat))

    def _polygon_edges(self, edges):
        """2-D: the polygon of the extreme points, counterclockwise; facet i runs from vertex i to
        vertex i + 1, its neighbours are facets i + 1 (opposite its first vertex) and i - 1."""
        k = np.arange(len(edges))
        self.simplices = edges.astype(np.int32)
        self.vertices = edges[:, 0].astype(np.int32)
        self.neighbors = np.column_stack(((k + 1) % len(k), (k - 1) % len(k))).astype(np.int32)
        start = self.points[edges[:, 0]]
        delta = self.points[edges[:, 1]] - start
        length = np.hypot(delta[:, 0], delta[:, 1])
        normal = np.column_stack((delta[:, 1], -delta[:, 0])) / length[:, None]  # right of a counterclockwise edge
        self.equations = np.column_stack((normal, -np.einsum("ij,ij->i", normal, start)))
        self.area = float(length.sum())
        x, y = self.points[edges[:, 0], 0], self.points[edges[:, 0], 1]
        xn, yn = self.points[edges[:, 1], 0], self.points[edges[:, 1], 1]
        x0, y0 = x.mean(), y.mean()  # the shoelace formula about the vertices' mean, for accuracy
        self.volume = float(((x - x0) * (yn - y0) - (xn - x0) * (y - y0)).sum() / 2)

    def _facets(self, facets, neighbors, inside, normal=None):
        """3-D and up: facets (each with `inside`, a point strictly on its inner side), their
        neighbours, their normals either way round if known (Quickhull's); equations, area, and
        the volume as a sum of cones from the vertices' mean."""
        d = self.ndim
        factorial = float(np.prod(np.arange(1, d + 1)))
        self.simplices = np.ascontiguousarray(facets, dtype=np.int32)
        self.neighbors = np.ascontiguousarray(neighbors, dtype=np.int32)
        self.vertices = np.flatnonzero(np.bincount(self.simplices.ravel(), minlength=self.npoints)).astype(np.int32)
        origin = self.points[self.simplices[:, 0]]  # each facet's first corner
        if normal is None:  # the generalised cross product of the edges from the first corner
            edges = self.points[self.simplices[:, 1:]] - origin[:, None, :]  # (m, d - 1, d)
            normal = np.stack([(-1) ** k * _determinants(np.delete(edges, k, axis=2)) for k in range(d)], axis=1)
        else:
            normal = np.array(normal)  # scaled in place below
        normal *= np.where(np.einsum("ij,ij->i", normal, self.points[inside] - origin) > 0, -1.0, 1.0)[:, None]
        length = np.sqrt(np.einsum("ij,ij->i", normal, normal))
        # each facet's cone from the vertices' mean: |normal| (d-1)! facet measure times the height, over d!
        centre = self.points[self.vertices].mean(axis=0)
        self.volume = float(np.einsum("ij,ij->i", normal, origin - centre).sum() / factorial)
        normal /= length[:, None]
        self.equations = np.column_stack((normal, -np.einsum("ij,ij->i", normal, origin)))
        self.area = float(length.sum() / (factorial / d))  # |generalised cross product| = (d-1)! facet measure


class Voronoi(_FromDelaunay):
    """The Voronoi diagram of points in E^d (d >= 2), with scipy.spatial.Voronoi's interface.

    Voronoi(points, furthest_site=False, incremental=False, qhull_options=None, *, engine="auto", threads=None,
            progress=None)

    Attributes (as scipy's): points, vertices, ridge_points, ridge_vertices, regions,
    point_region, ridge_dict, furthest_site, min_bound, max_bound, ndim, npoints.

    Vertices are the circumcentres of the Delaunay simplices, one for each set of
    neighbouring simplices with exactly one circumsphere (the exact unperturbed sphere
    test): four cocircular points give one vertex, where Qhull may give several nearly
    equal ones. A ridge is listed for each Delaunay edge whose dual has at least d distinct
    vertices (counting -1, the vertex at infinity, for a hull edge): edges inside a
    cospherical cell, whose dual collapsed, are not ridges. Regions: one per distinct input
    point (the circumcentres around it, -1 when the region is unbounded; in 2-D in
    counterclockwise order, in 3-D ridges in cyclic order), after an empty one first (Qhull's
    point at infinity, option Qz: present when scipy's would be, i.e. with the default options
    or "Qz" in qhull_options, not incremental, not furthest site); a duplicate point shares its
    first occurrence's region. furthest_site=True:
    the furthest-site diagram, from Delaunay(furthest_site=True) (its rules on ties); points
    inside the hull get an empty region, and there is no point at infinity (as Qhull's).
    progress (keyword only): as dewall.Delaunay's, for the triangulation (most of the work).
    Ctrl-C stops the work within a fraction of a second (KeyboardInterrupt).
    """

    def __init__(self, points, furthest_site=False, incremental=False, qhull_options=None, *, engine="auto",
                 threads=None, progress=None):
        super().__init__(points, incremental, qhull_options, engine=engine, threads=threads,
                         furthest_site=furthest_site, progress=progress)

    def _compute(self):
        tri = self._tri
        group = _merge(tri.nsimplex, tri._triangulation.cospherical_neighbours())
        self.vertices = _circumcentres(self.points, tri.simplices, group)
        compiled = getattr(tri._triangulation, "voronoi", None)  # 2 … 6 dimensions (python/src/voronoi.hpp)
        if compiled is not None:
            with _collector_paused():
                self.ridge_points, self.ridge_vertices, around = compiled(np.ascontiguousarray(group, dtype=np.int32))
        else:
            self.ridge_points, self.ridge_vertices = self._ridges(group, tri.simplices.astype(np.int64))
            around = self._regions(group)
        # Regions: the vertices around each distinct point (first occurrences; [] for no vertex).
        first = np.arange(self.npoints)
        dup = tri.duplicates
        first[dup[:, 0]] = dup[:, 1]
        # Qhull's point at infinity (option Qz: scipy's default, not with furthest_site or incremental)
        # has an empty region; Qhull's lands among the others, dewall's first.
        at_infinity = (_option_in_effect(tri._qhull_options, "Qz") and not self.furthest_site
                       and not tri._incremental)
        kept = np.nonzero(first == np.arange(self.npoints))[0]
        self.regions = ([[]] if at_infinity else []) + (around if kept.size == self.npoints
                                                       else [around[i] for i in kept.tolist()])
        self.point_region = np.empty(self.npoints, dtype=np.intp)
        self.point_region[kept] = np.arange(kept.size) + (1 if at_infinity else 0)
        self.point_region[dup[:, 0]] = self.point_region[dup[:, 1]]

    def _ridges(self, group, simplices):
        """Ridges in 7-D and up (below, the compiled module's, by the same rules): each Delaunay
        edge whose dual has at least d distinct vertices (unordered: a ridge there is a polytope
        of dimension 3 or more)."""
        tri, d = self._tri, self.ndim
        a, b = np.triu_indices(d + 1, 1)
        edges = np.sort(np.stack((simplices[:, a], simplices[:, b]), axis=2), axis=2).reshape(-1, 2)
        owner = np.repeat(np.arange(tri.nsimplex), a.size)
        order = np.lexsort((edges[:, 1], edges[:, 0]))
        edges, owner = edges[order], owner[order]
        starts = np.r_[0, np.nonzero(np.any(edges[1:] != edges[:-1], axis=1))[0] + 1]
        hull_edges = _hull_edges(tri)
        ridge_points, ridge_vertices = [], []
        for start, stop in zip(starts, np.r_[starts[1:], len(edges)]):
            p, q = map(int, edges[start])
            around = list(dict.fromkeys(int(g) for g in group[owner[start:stop]]))
            unbounded = (p, q) in hull_edges
            if unbounded:
                around.insert(0, -1)
            if len(around) < d:
                continue
            ridge_points.append((p, q))
            ridge_vertices.append(around)
        return np.array(ridge_points, dtype=np.int32).reshape(-1, 2), ridge_vertices

    def _regions(self, group):
        """Regions in 7-D and up (as the compiled module's from 3-D up): the groups of each point's
        simplices (ascending), -1 first on the hull."""
        tri, d = self._tri, self.ndim
        pairs = np.unique(np.column_stack((tri.simplices.ravel(), np.repeat(group, d + 1))), axis=0)
        on_hull = np.zeros(self.npoints, dtype=bool)
        on_hull[tri.convex_hull] = True
        split = np.split(pairs[:, 1], np.cumsum(np.bincount(pairs[:, 0], minlength=self.npoints))[:-1])
        return [([-1] if on_hull[i] else []) + part.tolist() if part.size else [] for i, part in enumerate(split)]

    def __repr__(self):
        return (f"<dewall.Voronoi: {self.npoints} points in E^{self.ndim}, {len(self.vertices)} vertices, "
                f"{len(self.ridge_points)} ridges, {len(self.regions)} regions>")

    @property
    def ridge_dict(self):
        """{(p, q): ridge vertices} for each ridge, as scipy's."""
        return {tuple(map(int, pq)): v for pq, v in zip(self.ridge_points, self.ridge_vertices)}


@contextlib.contextmanager
def _collector_paused():
    """Python's cycle collector off while the compiled module builds the ridges' and regions' lists:
    lists of ints make no cycles, and the collector would otherwise walk them again and again as
    their number grows."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _merge(count, pairs):
    """Group index (0, 1, … in order of first simplex) of each simplex, joining the pairs (union-find,
    in the compiled module)."""
    return _dewall.merge_groups(count, np.ascontiguousarray(np.reshape(pairs, (-1, 2)), dtype=np.int32))


def _circumcentres(points, simplices, group):
    """Circumcentre of the first simplex of each group: solve 2 (v_j - v_0) . c = |v_j|^2 - |v_0|^2,
    relative to v_0 for accuracy (in the compiled module up to 6 dimensions)."""
    _, first = np.unique(group, return_index=True)
    if points.shape[1] <= _MAX_COMPILED_DIMENSION:
        return _dewall.circumcentres(points, np.ascontiguousarray(simplices[first], dtype=np.uint32))
    v = points[simplices[first]]
    edges = v[:, 1:, :] - v[:, :1, :]
    rhs = 0.5 * np.einsum("ijk,ijk->ij", edges, edges)
    return v[:, 0, :] + np.linalg.solve(edges, rhs[:, :, None])[:, :, 0]


def _hull_edges(tri):
    """The Delaunay edges on the convex hull, as sorted (p, q) tuples."""
    hull = tri.convex_hull
    a, b = np.triu_indices(hull.shape[1], 1)
    pairs = np.sort(np.stack((hull[:, a], hull[:, b]), axis=2), axis=2).reshape(-1, 2)
    return set(map(tuple, np.unique(pairs, axis=0).tolist()))
