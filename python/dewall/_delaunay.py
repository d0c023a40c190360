"""dewall.Delaunay: scipy.spatial.Delaunay's interface over the exact triangulator.

Combinatorics (simplices, neighbours, hull, point location, adjacency) come from
the exact triangulation; floating point is used only for what is a number in
scipy too (transform, equations, plane distances, the tolerance of
find_simplex), computed from the points as scipy computes them.
"""

import os
import re
import time

import numpy as np

from . import _dewall
from ._arrays import as_coordinates
from ._errors import InvalidInput, InvalidOption, InvalidShape, translated
from ._boundary import extreme_facets_3d, extreme_hull_edges_2d, quickhull_facets
from ._furthest_site import furthest_site_simplices
from ._high_dimension import DimensionFreeTriangulation
from ._progress import progress_callback

# scipy's default tolerance of find_simplex (barycentric), and its limit on the
# reciprocal condition number under which a barycentric transform is NaN.
_EPS = np.finfo(np.float64).eps
_DEFAULT_TOL = 100 * _EPS
_RCOND_LIMIT = 1000 * _EPS

# qhull_options tokens accepted and ignored: they steer how Qhull copes with
# rounding (scaling, merging, joggling, triangulated output) or what it prints,
# and an exact triangulation needs none of them. Anything else is refused
# (InvalidOption): "Qu" (use furthest_site=True), "QG"/"Qg" (good facets),
# "QbB"/"Qbk"/"QBk" (rescaling the input), "Pd"/"PD" (dropping facets) would change the answer.
_IGNORED_OPTION = re.compile(r"^(Qbb|Qc|Qz|Qx|Qt|Qs|Qv|Qw|QJ[0-9.eE+-]*|Q[0-9]{1,2}|Pp|Po|T[cvsIO]?[0-9]*"
                             r"|[CAERUW]-?[0-9.eE+-]+|d|v)$")


def _check_qhull_options(options):
    if options is None:
        return None
    if isinstance(options, bytes):
        options = options.decode("ascii")
    if not isinstance(options, str):
        raise TypeError(f"qhull_options must be a string, not {type(options).__name__}")
    for token in options.split():
        if not _IGNORED_OPTION.match(token):
            hint = " (use furthest_site=True)" if token == "Qu" else ""
            raise InvalidOption(f"qhull option '{token}' is not supported: it would change the answer, or is not "
                                f"a Qhull option{hint}; dewall ignores only Qhull's precision and output options")
    return options


def _option_in_effect(options, name):
    """Whether Qhull option `name` (Qbb or Qz) would be in effect for scipy: its defaults
    ("Qbb Qc Qz ...") when no options are given, else the tokens given (QJ implies Qbb)."""
    if options is None:
        return True
    tokens = options.split()
    return name in tokens or (name == "Qbb" and any(t.startswith("QJ") for t in tokens))


def _check_threads(threads):
    """`threads` as an int >= 1 (None: all cores), capped at the CPUs this process may run on.

    The cap (os.sched_getaffinity) is silent: a TBB arena asked for more threads than the
    affinity allows only warns ("The number of workers is currently limited ...") and runs
    on fewer; the answer never depends on the number of threads."""
    if threads is None:
        return None
    if isinstance(threads, (bool, np.bool_)) or not isinstance(threads, (int, np.integer)):
        raise TypeError(f"threads must be a positive int or None, not {threads!r}")
    threads = int(threads)
    if threads < 1:
        raise ValueError(f"threads must be at least 1, not {threads}")
    try:
        available = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # not Linux
        available = os.cpu_count() or threads
    return min(threads, max(available, 1))


def _with_added_points(obj, points, what):
    """add_points' checks (scipy's: incremental mode, not closed; masked arrays refused; the
    object's dimension), then obj.points followed by the new points."""
    if not obj._incremental or obj._closed:
        raise RuntimeError("incremental mode not enabled or already closed")
    _refuse_masked(points, "Input points")
    new = as_coordinates(points)
    if new.shape[1] != obj.ndim:
        raise ValueError(f"the new points have dimension {new.shape[1]}, {what} {obj.ndim}")
    return np.concatenate((obj.points, new))


def _refuse_masked(values, what):
    if isinstance(values, np.ma.MaskedArray):
        raise ValueError(f"{what} cannot be a masked array")


# The library's kernel and engines cover 2 … 6 dimensions; above, CGAL's dD triangulation (_high_dimension.py).
_MAX_LIBRARY_DIMENSION = 6


def _triangulate(points, engine, threads, progress=None):
    if points.shape[1] > _MAX_LIBRARY_DIMENSION:
        if str(engine) not in ("auto", "cgal"):
            raise ValueError(f"engine {engine!r}: above {_MAX_LIBRARY_DIMENSION} dimensions the triangulation is "
                             "CGAL's dD Delaunay_triangulation (engine 'auto' or 'cgal')")
        return DimensionFreeTriangulation.triangulate(points, progress)
    try:
        return _dewall.triangulate(points, str(engine), threads, progress)
    except InvalidInput as error:
        raise translated(error) from None


def _from_simplices(points, simplices):
    """A triangulation object over given simplices (no triangulation run), in any dimension."""
    if points.shape[1] > _MAX_LIBRARY_DIMENSION:
        return DimensionFreeTriangulation(points, simplices)
    return _dewall.from_simplices(points, np.ascontiguousarray(simplices, dtype=np.uint32))


class Delaunay:
    """The Delaunay triangulation of points in E^d (d >= 2), exact, with scipy.spatial.Delaunay's interface.

    Delaunay(points, furthest_site=False, incremental=False, qhull_options=None, *, engine="auto", threads=None,
             progress=None)

    points: array of shape (n, d). A C-contiguous float64 array is used in
        place, not copied (so do not change it while this object is in use);
        other real arrays are converted exactly (dewall._arrays); masked
        arrays are refused (ValueError), as scipy does.
    furthest_site: scipy's: the furthest-site Delaunay triangulation (the
        upper hull of the lifted points: each simplex's circumsphere contains
        every point), exact, by gift wrapping over the hull vertices with the
        library's predicates (dewall/_furthest_site.py); cospherical hull
        vertices resolved by the library's symbolic perturbation. Points
        inside hull edges and faces are never vertices; hulls with flat
        facets (a cube, a tesseract, a grid in a box) in every dimension.
    incremental: allow add_points() until close(). Each add re-triangulates
        all the points (exact answer first; scipy's Qhull inserts instead), so
        the simplices are always those of Delaunay(all points).
    qhull_options: accepted when every token is one of Qhull's precision or
        output options (Qbb, Qc, Qz, Qx, Qt, QJ, Q12, Pp, …: an exact
        triangulation needs none, the simplices never depend on them); any
        other token raises dewall.InvalidOption (a ValueError and a
        QhullError), e.g. "Qu" or "QG4". As in scipy, options given replace
        the defaults "Qbb Qc Qz Q12": Qbb (or QJ) and Qz decide the lifting's
        scale (paraboloid_scale, equations) and Voronoi's empty region.
    engine (keyword only): "auto" (in 2D and 3D the hybrid, handing over to
        CGAL's incremental construction when DeWall's searches prove too
        costly, e.g. points on one sphere; in 4D and up dewall's own
        incremental construction), "hybrid", "dewall", "incremental" or
        "cgal". The simplices are the same with each. In 7 dimensions and up
        the library's kernel and engines (compiled for 2 … 6) are not there:
        CGAL's dD Delaunay_triangulation (Epick_d, its filtered exact
        predicates and symbolic perturbation, one thread) builds the
        triangulation, so "auto" and "cgal" are the choices; its simplices
        are CGAL's, as the library's are below (dewall/_high_dimension.py).
    threads (keyword only): the most threads to use, an int >= 1 (None: all
        cores); capped silently at the CPUs the process may run on
        (os.sched_getaffinity). The result does not depend on it.
    progress (keyword only): True draws a bar on sys.stderr while the
        triangulation is built; a callable is called as progress(fraction),
        fraction a float in [0, 1] (at most every few hundredths of a second,
        in the calling thread, and with 1.0 at the end); None or False (the
        default): nothing. An exception the callable raises stops the work
        and is raised here (dewall._progress).

    The work runs without the GIL, and Ctrl-C stops it within a fraction of
    a second (KeyboardInterrupt; what was built is freed), as it stops the
    other long calls (neighbors, find_simplex, ConvexHull, Voronoi, the
    interpolators). Degenerate input (grids, cospherical
    points) is resolved by CGAL's symbolic perturbation, so the simplices are
    CGAL's; duplicate points are one vertex, the first occurrence (see
    `duplicates`, and `coplanar` in scipy's layout).

    Raises dewall.DegenerateInput (a ValueError and a QhullError) for fewer
    than d + 1 distinct points or points that do not span E^d;
    dewall.InvalidInput (a ValueError) for a NaN or infinite coordinate, with
    `.point` naming the input point; TypeError for an array of the wrong dtype
    or shape.

    Attributes (as scipy's): points, simplices, neighbors, equations,
    transform, vertex_to_simplex, vertex_neighbor_vertices, convex_hull,
    coplanar, paraboloid_scale, paraboloid_shift, min_bound, max_bound, ndim,
    npoints, nsimplex, furthest_site; find_simplex, plane_distance,
    lift_points, add_points, close. Also: duplicates, statistics. Pickling and
    copy.deepcopy keep the points, the options and the simplices; the rest is
    recomputed on first use.
    """

    # Attributes computed on first use, forgotten when add_points changes the points.
    _LAZY = ("neighbors", "transform", "equations", "vertex_to_simplex", "vertex_neighbor_vertices",
             "convex_hull", "duplicates", "coplanar", "_lift", "_hull_simplices")

    def __init__(self, points, furthest_site=False, incremental=False, qhull_options=None, *, engine="auto",
                 threads=None, progress=None):
        _refuse_masked(points, "Input points")
        progress_callback(progress)  # (checked now: a bar is made for each build)
        self._progress = progress
        self.furthest_site = bool(furthest_site)
        self._qhull_options = _check_qhull_options(qhull_options)
        self._engine = str(engine)
        self._threads = _check_threads(threads)
        self._incremental = bool(incremental)
        self._closed = False
        self._build(as_coordinates(points))

    def _build(self, points):
        self._forget()
        self._statistics = None
        self.points = points
        start = time.perf_counter()
        hull = quickhull_facets(points) if self.furthest_site else None
        if hull is not None:  # the furthest-site triangulation needs only the hull (None: the Delaunay route)
            simplices = furthest_site_simplices(points, *hull)
            self._triangulation = _from_simplices(points, simplices)
            self._statistics = dict(self._triangulation.statistics, engine="furthest-site (Quickhull, gift wrapping)",
                                    input_points=points.shape[0], simplices=len(simplices),
                                    build_seconds=time.perf_counter() - start)
            self._set_bounds()
            return
        self._triangulation = _triangulate(points, self._engine, self._threads,
                                           progress_callback(self._progress, "dewall.Delaunay"))
        if self.furthest_site:
            self._statistics = self._triangulation.statistics
            simplices, neighbors = self._triangulation.simplices(), self._triangulation.neighbors()
            hull, whole = _hull_facets(simplices, neighbors), None
            if points.shape[1] == 2:
                hull = extreme_hull_edges_2d(points, simplices, neighbors)
                whole = np.ones(len(hull), dtype=bool)
            elif points.shape[1] == 3:
                hull, _, whole = extreme_facets_3d(points, simplices, neighbors, hull)
            self._triangulation = _from_simplices(points, furthest_site_simplices(points, hull, whole))
        self._set_bounds()

    def _set_bounds(self):
        self.min_bound = self.points.min(axis=0)
        self.max_bound = self.points.max(axis=0)

    def _forget(self):
        for name in self._LAZY + ("simplices",):
            self.__dict__.pop(name, None)

    def _lazy(self, name, compute):
        value = self.__dict__.get(name)
        if value is None:
            value = self.__dict__[name] = compute()
        return value

    # ---- scipy's attributes ------------------------------------------------------------------

    @property
    def ndim(self):
        return self.points.shape[1]

    @property
    def npoints(self):
        return self.points.shape[0]

    @property
    def nsimplex(self):
        return self.simplices.shape[0]

    @property
    def simplices(self):
        """int32 array (nsimplex, ndim + 1): input indices, each simplex positively oriented
        (det[p1 - p0, …, pd - p0] > 0). Writeable, as scipy's (`tri.simplices.sort()` is common,
        scipy's own tests do it): a copy of the compiled triangulation's rows, which find_simplex
        walks, so changing it cannot mislead point location; the attributes computed from it
        afterwards (transform, convex_hull, …) follow the change, as in scipy."""
        return self._lazy("simplices", lambda: np.array(self._triangulation.simplices()))

    @property
    def neighbors(self):
        """int32 array (nsimplex, ndim + 1): neighbors[i, j] is the simplex across the facet of
        simplex i opposite its vertex j, -1 when that facet is on the convex hull (scipy's
        convention). Computed on first use."""
        return self._lazy("neighbors", lambda: self._triangulation.neighbors())

    @property
    def convex_hull(self):
        """int32 array (nfacets, ndim): the facets of the convex hull, each as the simplex
        facet it is (simplices[i] without its vertex j where neighbors[i, j] == -1)."""

        return self._lazy("convex_hull", lambda: _hull_facets(self.simplices, self.neighbors))

    @property
    def duplicates(self):
        """int32 array (k, 2): one row (i, j) for each input point i that repeats an earlier
        point; j is the first occurrence, the vertex that stands for it. Empty when all
        points are distinct. (scipy lists such points in `coplanar`.)"""

        def compute():
            first = self._triangulation.first_occurrences()
            repeated = np.nonzero(first != np.arange(first.size))[0]
            return np.column_stack((repeated, first[repeated])).astype(np.int32)

        return self._lazy("duplicates", compute)

    @property
    def coplanar(self):
        """int32 array (k, 3), scipy's layout: (point, nearest simplex, nearest vertex) for each
        input point that is not a vertex. For dewall these are exactly the duplicates: the
        nearest vertex is the first occurrence, the simplex one that has it. (Qhull may also
        leave out distinct points it cannot resolve in floating point; dewall never does.)"""

        def compute():
            dup = self.duplicates
            rows = np.column_stack((dup[:, 0], self.vertex_to_simplex[dup[:, 1]], dup[:, 1])).astype(np.int32)
            return rows[rows[:, 1] >= 0]  # furthest site: copies of points inside the hull are no vertices

        return self._lazy("coplanar", compute)

    @property
    def vertex_to_simplex(self):
        """int32 array (npoints,): a simplex having each point as a vertex; a duplicate point
        gets a simplex of the vertex that stands for it (so every entry is >= 0, except with
        furthest_site=True, where points inside the hull are no vertices: -1)."""

        def compute():
            out = np.full(self.npoints, -1, dtype=np.int32)
            out[self.simplices.ravel()] = np.repeat(np.arange(self.nsimplex, dtype=np.int32), self.ndim + 1)
            dup = self.duplicates
            out[dup[:, 0]] = out[dup[:, 1]]
            return out

        return self._lazy("vertex_to_simplex", compute)

    @property
    def vertex_neighbor_vertices(self):
        """(indptr, indices), int32: the vertices joined to vertex k by an edge are
        indices[indptr[k]:indptr[k + 1]] (ascending). Duplicate points have none."""

        def compute():
            s = self.simplices.astype(np.int64)
            a, b = np.nonzero(~np.eye(self.ndim + 1, dtype=bool))  # ordered vertex pairs of one simplex
            keys = np.unique((s[:, a] * self.npoints + s[:, b]).ravel())
            source, target = np.divmod(keys, self.npoints)
            indptr = np.zeros(self.npoints + 1, dtype=np.int32)
            np.cumsum(np.bincount(source, minlength=self.npoints), out=indptr[1:])
            return indptr, target.astype(np.int32)

        return self._lazy("vertex_neighbor_vertices", compute)

    @property
    def transform(self):
        """float64 array (nsimplex, ndim + 1, ndim): scipy's barycentric transforms.

        With r the last vertex of simplex i and T the matrix whose column j is vertex j minus r,
        transform[i, :ndim] is T^-1 and transform[i, ndim] is r: the barycentric coordinates of
        x are c = T^-1 (x - r) and c_ndim = 1 - sum(c). Computed in floating point from the
        points, as scipy does, with scipy's rule: NaN for a simplex whose T has a reciprocal
        condition number (1-norm) under 1000 eps. No dewall simplex is flat, so NaN rows are
        only for nearly flat slivers (rare; not on grids, whose simplices are proper)."""
        return self._lazy("transform", lambda: barycentric_transforms(self.points, self.simplices))

    @property
    def paraboloid_scale(self):
        """Qhull's scale of the lifted coordinate (as scipy's, option Qbb): the largest |coordinate|
        divided by the range of the lifted values (sum of squares, up to 1.1 times their maximum
        for Qhull's point at infinity, option Qz, which scipy leaves out for furthest_site). 1
        (and shift 0) in incremental mode, where scipy's Qhull does not scale, and when
        qhull_options is given without Qbb (or QJ, which implies it): scipy's defaults
        "Qbb Qc Qz Q12" apply only when qhull_options is None, as in scipy."""
        return self._paraboloid[0]

    @property
    def paraboloid_shift(self):
        """Qhull's shift of the lifted coordinate: the lifted value of x is
        paraboloid_scale * |x|^2 + paraboloid_shift (>= 0 for every input point)."""
        return self._paraboloid[1]

    @property
    def _paraboloid(self):
        def compute():
            if self._incremental or not _option_in_effect(self._qhull_options, "Qbb"):
                return 1.0, 0.0
            squares = np.einsum("ij,ij->i", self.points, self.points)
            at_infinity = _option_in_effect(self._qhull_options, "Qz") and not self.furthest_site
            low, high = squares.min(), squares.max() * (1.1 if at_infinity else 1.0)
            largest = np.abs(self.points).max()
            if not high > low or not largest > 0:
                return 1.0, 0.0
            scale = largest / (high - low)
            return float(scale), float(-low * scale)

        return self._lazy("_lift", compute)

    def lift_points(self, x):
        """The points x (shape (..., ndim)) lifted to Qhull's paraboloid: shape (..., ndim + 1),
        the last coordinate paraboloid_scale * |x|^2 + paraboloid_shift."""
        x = np.asarray(x, dtype=np.float64)
        scale, shift = self._paraboloid
        z = scale * np.einsum("...i,...i->...", x, x) + shift
        return np.concatenate((x, z[..., None]), axis=-1)

    @property
    def equations(self):
        """float64 array (nsimplex, ndim + 2): the hyperplane [normal, offset] of each simplex
        lifted to the paraboloid (lift_points), unit normal pointing away from the lifted points
        (normal[ndim] < 0: the triangulation is the lower hull), normal . y + offset = 0 on it."""

        def compute():
            lifted = self.lift_points(self.points)[self.simplices]  # (m, d + 1, d + 1)
            edges = lifted[:, 1:, :] - lifted[:, :1, :]  # (m, d, d + 1)
            d = self.ndim
            normal = np.empty((self.nsimplex, d + 1))
            for k in range(d + 1):  # cofactor expansion: the normal orthogonal to every edge
                normal[:, k] = (-1) ** k * _determinants(np.delete(edges, k, axis=2))
            # lower hull: last component negative; furthest site (upper hull): positive
            normal *= (1 if self.furthest_site else -1) * np.sign(normal[:, d:])
            normal /= np.linalg.norm(normal, axis=1, keepdims=True)
            offset = -np.einsum("ij,ij->i", normal, lifted[:, 0, :])
            return np.column_stack((normal, offset))

        return self._lazy("equations", compute)

    def plane_distance(self, xi):
        """Signed distances of the lifted xi (shape (..., ndim)) to the planes of all simplices:
        shape (..., nsimplex), <= 0 for every input point (they lie on or above every plane)."""
        xi = np.asarray(xi, dtype=np.float64)
        if xi.shape[-1:] != (self.ndim,):
            raise ValueError(f"xi must have shape (..., {self.ndim}), not {xi.shape}")
        eq = self.equations
        return self.lift_points(xi) @ eq[:, :-1].T + eq[:, -1]

    @property
    def statistics(self):
        """Counters of the run: the engine that built the simplices ("dewall", "hybrid", "incremental" or "cgal"),
        distinct points, simplices, build_seconds, … (as `dewall triangulate --stats`). With furthest_site,
        those of the Delaunay triangulation it started from, or (engine "furthest-site (Quickhull, gift
        wrapping)") only input_points, simplices and build_seconds when it needed the hull alone."""
        return self._statistics if self._statistics is not None else self._triangulation.statistics

    # ---- point location ----------------------------------------------------------------------

    def find_simplex(self, xi, bruteforce=False, tol=None):
        """The simplex containing each point of xi (shape (..., ndim)), -1 outside: int32, shape xi.shape[:-1].

        Exact first: each point is located by the exact orientation predicate (a walk from the
        previous answer, with a full scan as fallback; `bruteforce` is accepted and changes
        nothing). A point inside the convex hull always gets a simplex that contains it
        (closed); on a face shared by several simplices, one of them.

        Then tol, as scipy documents it ("tolerance allowed in the inside-triangle check",
        default 100 eps): a point outside the hull gets the hull simplex in which its smallest
        barycentric coordinate is largest when that coordinate is >= -tol (and the point lies
        within tol of the bounding box, scipy's first test). tol=0 gives the exact answer
        alone. NaN or infinite coordinates get -1.
        """
        _refuse_masked(xi, "xi")
        xi = np.asarray(xi)
        if xi.ndim == 0 or xi.shape[-1] != self.ndim:
            raise InvalidShape(f"wrong dimensionality in xi: shape (..., {self.ndim}) expected, not {xi.shape}")
        eps = _DEFAULT_TOL if tol is None else float(tol)
        if not eps >= 0:
            raise ValueError(f"tol must be a non-negative number, not {tol!r}")
        flat = as_coordinates(xi.reshape(-1, self.ndim), "xi")
        found = self._in_walk_order(self._triangulation.locate, flat)
        if eps > 0:
            self._within_tolerance(flat, found, eps)
        return found.reshape(xi.shape[:-1])

    def _in_walk_order(self, locate, flat, *args):
        """locate(queries, *args) (arrays with a row per query) on `flat` sorted along a space-filling
        curve, so that each walk starts near its answer; the rows back in the order of `flat`."""
        if flat.shape[0] <= 64:
            return locate(flat, *args)
        order = _morton_order(flat, self.min_bound, self.max_bound)
        answer = locate(np.ascontiguousarray(flat[order]), *args)
        if isinstance(answer, tuple):
            out = tuple(np.empty_like(a) for a in answer)
            for o, a in zip(out, answer):
                o[order] = a
            return out
        out = np.empty_like(answer)
        out[order] = answer
        return out

    def _simplices_and_weights(self, flat):
        """For queries `flat` (q, ndim), float64 C-contiguous: find_simplex's answer (default tol)
        and the barycentric coordinates in that simplex, from its row of `transform` (NaN where
        that row is NaN, and for -1). In 2-D and 3-D computed during the walk, for the simplices
        found only (LinearNDInterpolator on 10^6 points: no transform of all the simplices)."""
        if self.ndim > 3 or "transform" in self.__dict__:
            found = self.find_simplex(flat)
            weights = np.full((flat.shape[0], self.ndim + 1), np.nan)
            inside = found >= 0
            weights[inside] = barycentric(self.transform[found[inside]], flat[inside])
            return found, weights
        found, weights = self._in_walk_order(self._triangulation.locate_weights, flat, _RCOND_LIMIT)
        exact = found.copy()
        self._within_tolerance(flat, found, _DEFAULT_TOL)
        near = np.nonzero((exact == -1) & (found >= 0))[0]
        if near.size:
            weights[near] = barycentric(barycentric_transforms(self.points, self.simplices[found[near]]), flat[near])
        return found, weights

    @property
    def _hull_simplices(self):
        return self._lazy("_hull_simplices", lambda: np.nonzero((self.neighbors == -1).any(axis=1))[0])

    def _within_tolerance(self, flat, found, eps, chunk=1 << 20):
        """Gives each point outside (found == -1) within eps of a hull simplex that simplex (in place)."""
        with np.errstate(invalid="ignore"):
            near = (found == -1) & np.all((flat >= self.min_bound - eps) & (flat <= self.max_bound + eps), axis=1)
        candidates = np.nonzero(near)[0]
        if candidates.size == 0:
            return
        hull = self._hull_simplices
        cached = self.__dict__.get("transform")  # else only the hull's: a few of the simplices
        transform = cached[hull] if cached is not None else barycentric_transforms(self.points, self.simplices[hull])
        valid = np.isfinite(transform[:, 0, 0])
        hull, transform = hull[valid], transform[valid]
        if hull.size == 0:
            return
        step = max(1, chunk // max(1, hull.size * (self.ndim + 1)))
        for start in range(0, candidates.size, step):
            rows = candidates[start:start + step]
            c = barycentric(transform[None, :, :, :], flat[rows, None, :])  # (q, h, d + 1)
            worst = c.min(axis=2)
            worst[c.max(axis=2) > 1 + eps] = -np.inf
            best = worst.argmax(axis=1)
            ok = worst[np.arange(rows.size), best] >= -eps
            found[rows[ok]] = hull[best[ok]]

    # ---- incremental mode --------------------------------------------------------------------

    def add_points(self, points, restart=False):
        """Adds points (shape (k, ndim)); needs incremental=True and no close() yet (else
        RuntimeError, as scipy). dewall re-triangulates all the points (restart changes nothing):
        the simplices are those of Delaunay(all points), exactly."""
        self._build(_with_added_points(self, points, "the triangulation"))

    def close(self):
        """Ends incremental mode (scipy frees Qhull's memory here); add_points then raises."""
        self._closed = True

    # ---- pickling ------------------------------------------------------------------------------

    def __getstate__(self):
        return {"points": self.points, "simplices": np.array(self.simplices), "furthest_site": self.furthest_site,
                "engine": self._engine,
                "threads": self._threads, "incremental": self._incremental, "closed": self._closed,
                "qhull_options": self._qhull_options, "statistics": self.statistics}

    def __setstate__(self, state):
        self.furthest_site = state["furthest_site"]
        self._engine, self._threads = state["engine"], state["threads"]
        self._incremental, self._closed = state["incremental"], state["closed"]
        self._qhull_options, self._statistics = state["qhull_options"], state["statistics"]
        self._progress = None
        self.points = state["points"]
        self._triangulation = _from_simplices(self.points, state["simplices"])
        self._set_bounds()

    def __repr__(self):
        return f"<dewall.Delaunay: {self.npoints} points in E^{self.ndim}, {self.nsimplex} simplices>"


def _hull_facets(simplices, neighbors):
    """The facets simplices[i] without vertex j where neighbors[i, j] == -1, (k, d) int32."""
    simplex, opposite = np.nonzero(neighbors == -1)
    keep = np.ones((simplex.size, simplices.shape[1]), dtype=bool)
    keep[np.arange(simplex.size), opposite] = False
    return simplices[simplex][keep].reshape(simplex.size, simplices.shape[1] - 1)


def tsearch(tri, xi):
    """scipy.spatial.tsearch: the simplex of `tri` containing each point of xi (tri.find_simplex(xi))."""
    return tri.find_simplex(xi)


def _morton_order(x, low, high, bits=10):
    """The permutation sorting the rows of x along a Z-order curve over the box [low, high]
    (2^bits cells per axis; rows outside the box or non-finite go to its faces). Only the
    speed of the walks depends on it, never which simplex contains a point."""
    with np.errstate(all="ignore"):
        unit = np.nan_to_num((x - low) / np.where(high > low, high - low, 1.0), nan=0.0, posinf=1.0, neginf=0.0)
    cells = np.clip(unit * (1 << bits), 0, (1 << bits) - 1).astype(np.uint64)
    code = np.zeros(x.shape[0], dtype=np.uint64)
    d = x.shape[1]
    for bit in range(bits):
        for axis in range(d):
            code |= ((cells[:, axis] >> np.uint64(bit)) & np.uint64(1)) << np.uint64(bit * d + axis)
    return np.argsort(code, kind="stable")


def barycentric(transform, x):
    """Barycentric coordinates (..., ndim + 1) of x (..., ndim) under scipy-layout transforms (..., ndim + 1, ndim)."""
    c = np.einsum("...ij,...j->...i", transform[..., :-1, :], x - transform[..., -1, :])
    return np.concatenate((c, 1 - c.sum(axis=-1, keepdims=True)), axis=-1)


def _determinants(a):
    """Determinants of a stack of small matrices (m, d, d): written out in 2-D and 3-D (where
    batched LAPACK costs a call per matrix), by LU beyond."""
    d = a.shape[1]
    if d == 2:
        return a[:, 0, 0] * a[:, 1, 1] - a[:, 0, 1] * a[:, 1, 0]
    if d == 3:
        return (a[:, 0, 0] * (a[:, 1, 1] * a[:, 2, 2] - a[:, 1, 2] * a[:, 2, 1])
                - a[:, 0, 1] * (a[:, 1, 0] * a[:, 2, 2] - a[:, 1, 2] * a[:, 2, 0])
                + a[:, 0, 2] * (a[:, 1, 0] * a[:, 2, 1] - a[:, 1, 1] * a[:, 2, 0]))
    return np.linalg.det(a)


def _inverse_and_determinant(e):
    """T^-1 and det T for a stack of small matrices T given by their columns, e[:, j] = column j
    (m, d, d): by the adjugate in 2-D and 3-D (a few vector operations, where batched LAPACK
    costs a call per matrix), by LU beyond. Singular matrices get NaN inverses."""
    m, d, _ = e.shape
    if d == 2:  # T = [[a, b], [c, f]]
        a, c, b, f = e[:, 0, 0], e[:, 0, 1], e[:, 1, 0], e[:, 1, 1]
        det = a * f - b * c
        adjugate = np.empty((m, 2, 2))
        adjugate[:, 0, 0], adjugate[:, 0, 1], adjugate[:, 1, 0], adjugate[:, 1, 1] = f, -b, -c, a
    elif d == 3:  # row i of the adjugate: the cross product of the other two columns
        adjugate = np.empty((m, 3, 3))
        for i, (j, k) in enumerate(((1, 2), (2, 0), (0, 1))):
            u, v = e[:, j], e[:, k]
            adjugate[:, i, 0] = u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1]
            adjugate[:, i, 1] = u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2]
            adjugate[:, i, 2] = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
        det = np.einsum("ij,ij->i", e[:, 0], adjugate[:, 0])
    else:
        t = np.swapaxes(e, 1, 2)
        det = np.linalg.det(t)
        singular = ~(np.abs(det) > 0)
        safe = np.array(t)
        safe[singular] = np.eye(d)
        inverse = np.linalg.inv(safe)
        inverse[singular] = np.nan
        return inverse, det
    with np.errstate(all="ignore"):
        adjugate /= det[:, None, None]
    return adjugate, det


def barycentric_transforms(points, simplices):
    """scipy's transform array for `simplices` of `points` (see Delaunay.transform). In 2-D and
    3-D the same formulas run in the compiled module (one pass, no temporaries)."""
    if points.shape[1] in (2, 3):
        return _dewall.barycentric_transforms(np.ascontiguousarray(points, dtype=np.float64),
                                              np.ascontiguousarray(simplices, dtype=np.uint32), _RCOND_LIMIT)
    vertices = points[simplices]  # (m, d + 1, d)
    r = vertices[:, -1, :]
    columns = vertices[:, :-1, :] - r[:, None, :]  # columns[:, j]: vertex j - r, column j of T
    d = points.shape[1]
    inverse, det = _inverse_and_determinant(columns)
    with np.errstate(all="ignore"):  # reciprocal condition number in the 1-norm (largest column sum)
        rcond = 1 / (np.abs(columns).sum(axis=2).max(axis=1) * np.abs(inverse).sum(axis=1).max(axis=1))
    bad = ~(np.abs(det) > 0) | ~(rcond >= _RCOND_LIMIT)
    out = np.empty((simplices.shape[0], d + 1, d))
    out[:, :d, :] = inverse
    out[:, d, :] = r
    out[bad] = np.nan
    return out
