"""scipy.spatial.Delaunay's interface on dewall.Delaunay, compared with scipy on the same points:
transform, equations, plane_distance, lift_points, paraboloid_*, adjacency, coplanar, bounds,
find_simplex's tol, the signature, incremental mode, pickling, threads."""

import copy
import pickle

import numpy as np
import pytest
from scipy.spatial import Delaunay as ScipyDelaunay

import dewall
from conftest import simplex_set
from dewall._delaunay import barycentric_transforms

CASES = [(2, 200), (3, 120), (4, 60), (5, 30)]


@pytest.fixture(params=CASES, ids=[f"{d}D" for d, _ in CASES])
def both(request, rng):
    d, n = request.param
    points = rng.random((n, d)) * 4 - 1  # off the origin: the paraboloid's shift matters
    return points, dewall.Delaunay(points), ScipyDelaunay(points)


def scipy_rows(ours, theirs):
    """For each of our simplices, the row of scipy's with the same vertex set."""
    row = {tuple(sorted(s)): i for i, s in enumerate(theirs.simplices)}
    return np.array([row[tuple(sorted(s))] for s in ours.simplices])


def test_transform_is_scipys(both):
    points, ours, theirs = both
    t = ours.transform
    assert t.shape == (ours.nsimplex, ours.ndim + 1, ours.ndim) and t.dtype == np.float64
    # Same vertex order, same numbers: our formula on scipy's simplices gives scipy's transform.
    np.testing.assert_allclose(barycentric_transforms(points, theirs.simplices), theirs.transform, rtol=1e-9,
                               atol=1e-9 * np.abs(theirs.transform).max())
    # And on ours: the last row is the last vertex; the centroid has coordinates 1/(d + 1).
    np.testing.assert_array_equal(t[:, -1, :], points[ours.simplices[:, -1]])
    centroids = points[ours.simplices].mean(axis=1)
    c = np.einsum("ijk,ik->ij", t[:, :-1, :], centroids - t[:, -1, :])
    np.testing.assert_allclose(c, 1 / (ours.ndim + 1), rtol=1e-6)


def test_lifting_and_equations_are_scipys(both, rng):
    points, ours, theirs = both
    assert ours.paraboloid_scale == pytest.approx(theirs.paraboloid_scale, rel=1e-14)
    assert ours.paraboloid_shift == pytest.approx(theirs.paraboloid_shift, rel=1e-14, abs=1e-14)
    queries = rng.random((20, ours.ndim))
    np.testing.assert_allclose(ours.lift_points(queries), theirs.lift_points(queries), rtol=1e-14, atol=1e-15)
    rows = scipy_rows(ours, theirs)
    assert ours.equations.shape == (ours.nsimplex, ours.ndim + 2)
    np.testing.assert_allclose(ours.equations, theirs.equations[rows], atol=1e-11)
    np.testing.assert_allclose(ours.plane_distance(queries), theirs.plane_distance(queries)[:, rows], atol=1e-11)
    assert (ours.plane_distance(points) <= 1e-12).all()  # every lifted point on or above every plane


def test_adjacency_is_scipys(both):
    points, ours, theirs = both
    indptr, indices = ours.vertex_neighbor_vertices
    their_ptr, their_indices = theirs.vertex_neighbor_vertices
    assert indptr.dtype == indices.dtype == np.int32 and indptr.shape == (len(points) + 1,)
    for k in range(len(points)):
        assert set(indices[indptr[k]:indptr[k + 1]]) == set(their_indices[their_ptr[k]:their_ptr[k + 1]])
    v = ours.vertex_to_simplex
    assert v.dtype == np.int32 and all(k in ours.simplices[v[k]] for k in range(len(points)))
    np.testing.assert_array_equal(ours.min_bound, theirs.min_bound)
    np.testing.assert_array_equal(ours.max_bound, theirs.max_bound)
    assert ours.coplanar.shape == theirs.coplanar.shape == (0, 3)


def test_tolerance_of_find_simplex_is_scipys(both):
    points, ours, theirs = both
    # Just outside a hull facet: scipy's tol decides, ours too (exact first, then tol).
    simplex, opposite = map(int, np.argwhere(ours.neighbors == -1)[0])
    facet = np.delete(points[ours.simplices[simplex]], opposite, axis=0)
    centre = facet.mean(axis=0)
    outward = centre - points[ours.simplices[simplex, opposite]]
    outward /= np.linalg.norm(outward)
    for gap, tol, found in [(1e-9, 1e-6, True), (1e-9, None, False), (1e-9, 0, False), (1e-3, 1e-6, False)]:
        q = centre + gap * outward
        # the facet's plane, not the direction to the opposite vertex, decides: check with the transform
        mine, scipys = ours.find_simplex(q, tol=tol), theirs.find_simplex(q, tol=tol)
        if found:
            assert mine == simplex and scipys != -1
        else:
            assert mine == -1 and scipys == -1
        assert ours.find_simplex(q, tol=0, bruteforce=True) == -1  # exact: outside


# ---- cases ported from scipy 1.10's scipy/spatial/tests/test_qhull.py --------------------------

SQUARE = np.array([(0, 0), (0, 1), (1, 1), (1, 0)], dtype=np.double)


def test_find_simplex_square():  # TestUtilities.test_find_simplex, as vertex sets
    tri = dewall.Delaunay(SQUARE)
    assert simplex_set(tri.simplices) == {(1, 2, 3), (0, 1, 3)}  # scipy pins [[1, 3, 2], [3, 1, 0]]
    for x, y, vertices in [(0.25, 0.25, {0, 1, 3}), (0.75, 0.75, {1, 2, 3}), (0.3, 0.2, {0, 1, 3})]:
        assert set(tri.simplices[tri.find_simplex((x, y))]) == vertices
        assert dewall.tsearch(tri, (x, y)) == tri.find_simplex((x, y))


def test_plane_distance_by_hand():  # TestUtilities.test_plane_distance
    x = np.array([(0, 0), (1, 1), (1, 0), (0.99189033, 0.37674127), (0.99440079, 0.45182168)])
    p = np.array([0.99966555, 0.15685619])
    tri = dewall.Delaunay(x)
    z, pz = tri.lift_points(x), tri.lift_points(p)
    dist = tri.plane_distance(p)
    for j, v in enumerate(tri.simplices):
        n = np.cross(z[v[0]] - z[v[2]], z[v[1]] - z[v[2]])
        n /= np.sqrt(np.dot(n, n))
        n *= -np.sign(n[2])
        assert dist[j] == pytest.approx(np.dot(n, pz - z[v[2]]), abs=1e-7)


def test_convex_hull_square():  # TestUtilities.test_convex_hull, as sets
    assert simplex_set(dewall.Delaunay(SQUARE).convex_hull) == {(2, 3), (1, 2), (0, 1), (0, 3)}


@pytest.mark.parametrize("points", [
    [(0, 0), (0, 1), (1, 0)],
    SQUARE,
    [(0, 0), (0, 1), (1, 1), (1, 0), (0.5, 0.5), (0.9, 0.5)],
], ids=["triangle", "rectangle", "complicated"])
def test_vertex_neighbor_vertices(points):  # TestVertexNeighborVertices
    tri = dewall.Delaunay(np.asarray(points, dtype=np.double))
    expected = [set() for _ in range(tri.npoints)]
    for s in tri.simplices:
        for a in s:
            expected[a] |= set(map(int, s)) - {a}
    indptr, indices = tri.vertex_neighbor_vertices
    assert [set(map(int, indices[indptr[k]:indptr[k + 1]])) for k in range(tri.npoints)] == expected


def test_masked_arrays_fail():  # TestDelaunay.test_masked_array_fails
    with pytest.raises(ValueError, match="masked array"):
        dewall.Delaunay(np.ma.masked_all((4, 2)))
    with pytest.raises(ValueError, match="masked array"):
        dewall.Delaunay(SQUARE).find_simplex(np.ma.array([[0.5, 0.5]]))


def test_array_with_nans_fails():  # TestDelaunay.test_array_with_nans_fails
    with pytest.raises(ValueError):
        dewall.Delaunay(np.array([(0, 0), (0, 1), (1, 1), (1, np.nan)]))


@pytest.mark.parametrize("nd", range(2, 9))
def test_nd_simplex(nd):  # TestDelaunay.test_nd_simplex (scipy: 2..7; 7 and 8: CGAL's dD triangulation)
    points = np.zeros((nd + 1, nd))
    points[np.arange(nd), np.arange(nd)] = 1.0
    points[-1, :] = 1.0
    tri = dewall.Delaunay(points)
    np.testing.assert_array_equal(np.sort(tri.simplices), [np.arange(nd + 1)])
    np.testing.assert_array_equal(tri.neighbors, [[-1] * (nd + 1)])


def test_duplicate_points_and_coplanar(rng):  # TestDelaunay.test_duplicate_points, test_coplanar
    points = rng.random((10, 2))
    points = np.r_[points, points]
    tri, theirs = dewall.Delaunay(points), ScipyDelaunay(points)
    assert len(np.unique(tri.simplices)) == len(tri.coplanar) == len(np.unique(tri.coplanar[:, 2])) == 10
    assert (tri.vertex_to_simplex >= 0).all()
    assert tri.coplanar.dtype == np.int32
    for point, simplex, vertex in tri.coplanar:  # (point, a simplex of its vertex, the vertex)
        assert (points[point] == points[vertex]).all() and vertex in tri.simplices[simplex]
    # The same points left out, up to which copy: dewall keeps the first, Qhull any one.
    assert {tuple(points[i]) for i in tri.coplanar[:, 0]} == {tuple(points[i]) for i in theirs.coplanar[:, 0]}


@pytest.mark.parametrize("name", ["pathological-1", "pathological-2"])
def test_pathological(name):  # TestDelaunay.test_pathological
    x = np.array([-3.14, -2.36, -1.57, -0.79, 0.0, 0.79, 1.57, 2.36, 3.14])
    points = (np.array(np.meshgrid(x, x)).reshape(2, -1).T if name == "pathological-1" else
              np.array([[-1, -1], [-1, 0], [-1, 1], [0, -1], [0, 0], [0, 1], [1, -1 - np.finfo(float).eps], [1, 0],
                        [1, 1]]))
    tri = dewall.Delaunay(points)
    assert tri.points[tri.simplices].max() == points.max() and tri.points[tri.simplices].min() == points.min()
    assert dewall.certify(points, tri.simplices, canonical=True)


def test_incremental_bug_2850(rng):  # TestDelaunay.test_incremental, datasets bug-2850(-2)
    chunks = [rng.random((10, 2)), np.array([[0, 0], [0, 1], [1, 0], [1, 1]]), rng.random((10, 2)),
              0.25 + np.array([[0, 0], [0, 1], [1, 0], [1, 1]])]
    points = np.concatenate(chunks)
    grown = dewall.Delaunay(chunks[0], incremental=True)
    for chunk in chunks[1:]:
        grown.add_points(chunk)
    restarted = dewall.Delaunay(chunks[0], incremental=True)
    restarted.add_points(np.concatenate(chunks[1:]), restart=True)
    expected = simplex_set(ScipyDelaunay(points).simplices)
    assert simplex_set(grown.simplices) == simplex_set(restarted.simplices) == expected
    np.testing.assert_array_equal(grown.points, points)
    scipys = ScipyDelaunay(chunks[0], incremental=True)
    scipys.add_points(np.concatenate(chunks[1:]))
    assert (grown.paraboloid_scale, grown.paraboloid_shift) == (scipys.paraboloid_scale, scipys.paraboloid_shift)
    rows = scipy_rows(grown, scipys)
    np.testing.assert_allclose(grown.equations, scipys.equations[rows], atol=1e-11)
    np.testing.assert_array_equal(grown.max_bound, points.max(axis=0))
    assert grown.find_simplex([0.9, 0.95]) >= 0
    grown.close()
    with pytest.raises(RuntimeError, match="closed"):
        grown.add_points(chunks[0])
    with pytest.raises(RuntimeError, match="not enabled"):
        dewall.Delaunay(points).add_points(chunks[0])


# ---- the signature, options, pickling, threads -------------------------------------------------


def test_scipys_positional_signature(rng):
    points = rng.random((30, 2))
    assert simplex_set(dewall.Delaunay(points, False, False, "Qbb Qc Qz Q12").simplices) == \
        simplex_set(dewall.Delaunay(points).simplices)
    assert dewall.Delaunay(points).furthest_site is False
    assert simplex_set(dewall.Delaunay(points, True).simplices) == \
        simplex_set(ScipyDelaunay(points, True).simplices)  # furthest_site, positionally
    with pytest.raises(TypeError):
        dewall.Delaunay(points, False, False, None, "cgal")  # engine and threads are keyword-only


@pytest.mark.parametrize("options", ["QJ", "Qt Qbb Qc Qz", "QJ Pp", "Qx Q12", b"Qbb", "Qc", "Qz", "Qbb Qz", None])
def test_qhull_options_ignored(options, rng):
    points = rng.random((40, 2)) * 3 + 1
    text = options.decode() if isinstance(options, bytes) else options  # scipy takes str only
    ours, theirs = dewall.Delaunay(points, qhull_options=options), ScipyDelaunay(points, qhull_options=text)
    assert simplex_set(ours.simplices) == simplex_set(dewall.Delaunay(points).simplices)
    # but the lifting follows the options, as scipy's (its defaults apply only without options)
    assert ours.paraboloid_scale == pytest.approx(theirs.paraboloid_scale, rel=1e-9)
    assert ours.paraboloid_shift == pytest.approx(theirs.paraboloid_shift, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("options", ["Qu", "QG4", "Qfoo", "QbB", "Pdk:0"])
def test_qhull_options_refused(options):
    from scipy.spatial import QhullError

    with pytest.raises(dewall.InvalidOption, match="not supported") as error:
        dewall.Delaunay(SQUARE, qhull_options=options)
    assert isinstance(error.value, ValueError) and isinstance(error.value, QhullError)
    with pytest.raises(TypeError):
        dewall.Delaunay(SQUARE, qhull_options=5)


def test_pickle_and_deepcopy(rng):
    points = rng.random((300, 3))
    tri = dewall.Delaunay(points, engine="cgal", threads=1, incremental=True)
    queries = rng.random((100, 3))
    for other in (pickle.loads(pickle.dumps(tri)), copy.deepcopy(tri)):
        assert other.points is not tri.points
        np.testing.assert_array_equal(other.points, points)
        np.testing.assert_array_equal(other.simplices, tri.simplices)
        np.testing.assert_array_equal(other.neighbors, tri.neighbors)
        np.testing.assert_array_equal(other.find_simplex(queries), tri.find_simplex(queries))
        np.testing.assert_array_equal(other.transform, tri.transform)
        assert other.statistics["engine"] == "cgal"
        other.add_points(rng.random((5, 3)))  # incremental mode survives
        assert other.npoints == 305 and tri.npoints == 300


@pytest.mark.parametrize("bad, error", [(2.7, TypeError), ("2", TypeError), (True, TypeError), (0, ValueError),
                                        (-1, ValueError), (2.0, TypeError)])
def test_threads_are_strict(bad, error):
    with pytest.raises(error, match="threads"):
        dewall.Delaunay(SQUARE, threads=bad)
    dewall.Delaunay(SQUARE, threads=np.int64(1))


def test_no_tbb_warning_under_one_cpu():
    import os
    import subprocess
    import sys

    if not hasattr(os, "sched_setaffinity"):
        pytest.skip("no CPU affinity on this platform")
    code = ("import os, numpy as np, dewall; os.sched_setaffinity(0, {min(os.sched_getaffinity(0))}); "
            "dewall.Delaunay(np.random.default_rng(1).random((5000, 3)), threads=2)")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env=dict(os.environ))
    assert "TBB" not in run.stderr + run.stdout


# ---- TestUtilities' barycentric-transform checks, on Qhull's hard cases ------------------------


def check_barycentric_transforms(tri, unit_cube=False, unit_cube_tol=0.0):
    """scipy's _check_barycentric_transforms: each transform is NaN or maps the centroid to
    coordinates 1/(d + 1); NaN only for (nearly) zero volume; centroids located; in the unit
    cube no interior centroid outside. Returns the number of NaN transforms."""
    vertices = tri.points[tri.simplices]
    share = 1 / (tri.ndim + 1.0)
    centroids = vertices.mean(axis=1)
    t = tri.transform
    c = np.einsum("ijk,ik->ij", t[:, :-1, :], centroids - t[:, -1, :])
    nan = np.isnan(t[:, 0, 0])
    with np.errstate(invalid="ignore"):
        assert (nan | (np.abs(c - share) / share < 0.1).all(axis=1)).all()
    edges = vertices[:, :-1, :] - vertices[:, -1:, :]
    assert (~nan | (np.abs(np.linalg.det(edges)) < np.sqrt(np.finfo(float).eps))).all()
    found = tri.find_simplex(centroids)
    assert ((found != -1) | nan).all()
    if unit_cube:
        boundary = ((centroids <= unit_cube_tol) | (centroids >= 1 - unit_cube_tol)).any(axis=1)
        assert ((found != -1) | boundary).all()
    return int(nan.sum())


def test_degenerate_barycentric_transforms():  # TestUtilities.test_degenerate_barycentric_transforms
    import os

    import scipy.spatial.tests as scipy_tests

    path = os.path.join(os.path.dirname(scipy_tests.__file__), "data", "degenerate_pointset.npz")
    if not os.path.exists(path):
        pytest.skip("scipy's test data is not installed")
    with np.load(path) as data:
        points = data["c"]
    tri = dewall.Delaunay(points)
    assert dewall.certify(points, tri.simplices, canonical=True)
    # scipy asserts fewer than 23 NaN transforms (Qhull's triangulation has 22). The exact
    # Delaunay triangulation of this set has 31 slivers under scipy's rcond rule (on Qhull's
    # simplices the same rule gives Qhull's 22): thin, never flat, so interpolation solves them.
    nan = check_barycentric_transforms(tri)
    assert 0 < nan < 0.005 * tri.nsimplex
    slivers = np.isnan(tri.transform[:, 0, 0])
    from dewall.interpolate import LinearNDInterpolator

    centroids = points[tri.simplices[slivers]].mean(axis=1)
    inside = tri.find_simplex(centroids, tol=0) >= 0
    assert np.isfinite(LinearNDInterpolator(tri, points[:, 0])(centroids[inside])).all()


@pytest.mark.parametrize("ndim, k", [(2, 70), (3, 11), (4, 5)])  # scipy's 5-D 3^5 case: 4 s here, left out
def test_more_barycentric_transforms(ndim, k):  # TestUtilities.test_more_barycentric_transforms
    eps = np.finfo(float).eps
    x = np.linspace(0, 1, k)
    grid = np.stack([a.ravel() for a in np.meshgrid(*[x] * ndim, indexing="ij")], axis=1)
    tri = dewall.Delaunay(grid)
    assert check_barycentric_transforms(tri, unit_cube=True) == 0  # a grid: no flat simplex, no NaN
    rng = np.random.RandomState(1234)
    moved = rng.rand(grid.shape[0]) < 0.2
    grid[moved, :] += 2 * eps * (rng.rand(*grid[moved, :].shape) - 0.5)
    check_barycentric_transforms(dewall.Delaunay(grid), unit_cube=True, unit_cube_tol=2 * eps)
    doubled = dewall.Delaunay(np.r_[grid, grid])
    check_barycentric_transforms(doubled, unit_cube=True, unit_cube_tol=2 * eps)
    assert len(doubled.coplanar) == len(grid)


# ---- furthest site -------------------------------------------------------------------------------


def test_furthest_site_scipys_case():  # TestDelaunay.test_furthest_site, as sets
    tri = dewall.Delaunay([(0, 0), (0, 1), (1, 0), (0.5, 0.5), (1.1, 1.1)], furthest_site=True)
    assert tri.furthest_site is True
    assert simplex_set(tri.simplices) == {(0, 1, 4), (0, 2, 4)}  # scipy (Qhull): [(1, 4, 0), (4, 2, 0)]
    assert tri.vertex_to_simplex[3] == -1 and tri.find_simplex((0.5, 0.5)) >= 0


@pytest.mark.parametrize("d, n", [(2, 200), (3, 100), (4, 40)])
def test_furthest_site_equals_scipy(d, n, rng):
    points = rng.random((n, d))
    ours, theirs = dewall.Delaunay(points, True), ScipyDelaunay(points, True)
    assert simplex_set(ours.simplices) == simplex_set(theirs.simplices)
    assert (ours.paraboloid_scale, ours.paraboloid_shift) == pytest.approx(
        (theirs.paraboloid_scale, theirs.paraboloid_shift), rel=1e-14, abs=1e-15)
    np.testing.assert_allclose(ours.equations, theirs.equations[scipy_rows(ours, theirs)], atol=1e-11)
    assert (ours.equations[:, d] > 0).all()  # the upper hull
    queries = rng.random((300, d))
    mine, scipys = ours.find_simplex(queries), theirs.find_simplex(queries)
    assert ((mine == -1) == (scipys == -1)).all()
    assert all(set(ours.simplices[a]) == set(theirs.simplices[b]) for a, b in zip(mine, scipys) if a >= 0)
    # every circumsphere contains every point: no lifted point above a simplex's plane
    assert (ours.plane_distance(points) <= 1e-12).all()
    again = pickle.loads(pickle.dumps(ours))
    assert again.furthest_site and simplex_set(again.simplices) == simplex_set(ours.simplices)


def test_furthest_site_ties():
    # cocircular hull vertices: one of the two triangulations, by the perturbation, each circle holding every point
    square_and_inside = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [0.5, 0.4]])
    tri = dewall.Delaunay(square_and_inside, furthest_site=True)
    assert tri.nsimplex == 2 and set(np.unique(tri.simplices)) == {0, 1, 2, 3}
    assert (tri.plane_distance(square_and_inside) <= 1e-12).all()
    angles = np.arange(12) * np.pi / 6  # a regular 12-gon (floating point: not exactly cocircular)
    ring = np.column_stack((np.cos(angles), np.sin(angles)))
    integer_ring = np.array([[5, 0], [4, 3], [3, 4], [0, 5], [-3, 4], [-4, 3], [-5, 0], [-4, -3], [-3, -4], [0, -5],
                             [3, -4], [4, -3], [0, 1]], dtype=float)  # 12 exactly cocircular, one inside
    for points in (ring, integer_ring):
        tri = dewall.Delaunay(points, furthest_site=True)
        area = np.abs(np.linalg.det(points[tri.simplices[:, 1:]] - points[tri.simplices[:, :1]])).sum() / 2
        assert tri.nsimplex == 10 and area == pytest.approx(dewall.ConvexHull(points).volume, rel=1e-12)
        assert (tri.find_simplex(points[:12] * 0.5) >= 0).all()
    # 2-D: points inside hull edges are set aside (a grid: its 4 corners, one diagonal)
    x = np.linspace(0, 1, 5)
    grid = np.array(np.meshgrid(x, x)).reshape(2, -1).T
    tri = dewall.Delaunay(grid, furthest_site=True)
    assert tri.nsimplex == 2 and set(np.unique(tri.simplices)) == {0, 4, 20, 24}
    assert (tri.find_simplex(grid) >= 0).all()
    # 3-D: a square pyramid (a flat square base, points inside the base, its edges, the pyramid)
    pyramid = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0.5, 0.5, 1], [0.5, 0, 0], [0.3, 0.4, 0],
                        [0.5, 0.5, 0.3]])
    tri = dewall.Delaunay(pyramid, furthest_site=True)
    assert set(np.unique(tri.simplices)) == {0, 1, 2, 3, 4} and tri.nsimplex == 2
    assert (tri.plane_distance(pyramid) <= 1e-12).all()
    # 3-D without a triangular face (a cube, a 3 x 3 x 3 grid: started from a hull edge)
    import itertools

    for side in ([0, 1], [0, 1, 2]):
        cube = np.array(list(itertools.product(side, repeat=3)), dtype=float)
        tri = dewall.Delaunay(cube, furthest_site=True)
        volume = np.abs(np.linalg.det(cube[tri.simplices[:, 1:]] - cube[tri.simplices[:, :1]])).sum() / 6
        assert tri.nsimplex == 6 and volume == pytest.approx(side[-1] ** 3, rel=1e-12)
        assert np.unique(tri.simplices).size == 8 and (tri.plane_distance(cube) <= 1e-12).all()


def _furthest_site_by_definition(points, simplices):
    """Brute force in exact rational arithmetic: each simplex is proper, its closed circumsphere
    holds every point, and the simplices' volumes add up to the hull's (`hull_volume`, exact)."""
    from fractions import Fraction

    p = [[Fraction(float(x)) for x in row] for row in points]
    d = len(p[0])
    total = Fraction(0)
    for simplex in simplices:
        corners = [p[i] for i in simplex]
        # the centre c: 2 (v_i - v_0) . c = |v_i|^2 - |v_0|^2, solved by exact Gaussian elimination
        rows = [[2 * (v[k] - corners[0][k]) for k in range(d)] + [sum(x * x for x in v) - sum(x * x for x in corners[0])]
                for v in corners[1:]]
        det = Fraction(1)
        for c in range(d):
            pivot = next(r for r in range(c, d) if rows[r][c] != 0)  # StopIteration: a flat simplex
            rows[c], rows[pivot] = rows[pivot], rows[c]
            det *= rows[c][c] / 2
            for r in range(d):
                if r != c and rows[r][c] != 0:
                    f = rows[r][c] / rows[c][c]
                    rows[r] = [x - f * y for x, y in zip(rows[r], rows[c])]
        centre = [rows[c][d] / rows[c][c] for c in range(d)]
        radius = sum((x - y) ** 2 for x, y in zip(corners[0], centre))
        assert all(sum((x - y) ** 2 for x, y in zip(q, centre)) <= radius for q in p)
        total += abs(det)
    return total  # d! times the volume covered


@pytest.mark.parametrize("d, side", [(3, 2), (3, 3), (4, 2), (4, 3), (5, 2)])
def test_furthest_site_flat_facets(d, side):
    """Hulls whose every facet is flat with 2^(d-1) corners (a cube, a grid in a box): no facet to
    start from; the walk finds the first simplex. Checked against the definition, exactly."""
    import itertools
    import math

    grid = np.array(list(itertools.product(range(side), repeat=d)), dtype=float)
    tri = dewall.Delaunay(grid, furthest_site=True)
    assert tri.nsimplex == math.factorial(d) and np.unique(tri.simplices).size == 2 ** d  # only the corners
    assert _furthest_site_by_definition(grid, tri.simplices) == math.factorial(d) * (side - 1) ** d
    assert (tri.find_simplex(grid) >= 0).all()


@pytest.mark.parametrize("d", [4, 5])
def test_furthest_site_flat_facets_random_lattice(d, rng):
    """Lattice points (flat facets, cospherical corners, points inside facets) in 4-D and 5-D:
    the definition holds exactly, and the Quickhull and Delaunay-boundary routes agree (the
    perturbed triangulation is unique)."""
    import math

    from dewall._delaunay import _hull_facets
    from dewall._furthest_site import furthest_site_simplices

    for _ in range(3):
        points = rng.integers(0, 3, (int(rng.integers(20, 40)), d)).astype(float)
        points = np.unique(points, axis=0)
        ours = dewall.Delaunay(points, furthest_site=True)
        hull = dewall.ConvexHull(points)
        covered = _furthest_site_by_definition(points, ours.simplices)
        assert float(covered) == pytest.approx(math.factorial(d) * hull.volume, rel=1e-12)
        tri = dewall.Delaunay(points)
        assert simplex_set(furthest_site_simplices(points, _hull_facets(tri.simplices, tri.neighbors))) == \
            simplex_set(ours.simplices)


@pytest.mark.parametrize("d", [2, 3])
def test_furthest_site_routes_agree(d, rng):
    """furthest_site from the Quickhull hull equals it from the Delaunay triangulation's boundary
    (the perturbed furthest-site triangulation is unique) on lattices and rounded sphere points."""
    from dewall._boundary import extreme_facets_3d, extreme_hull_edges_2d, quickhull_facets
    from dewall._delaunay import _hull_facets
    from dewall._furthest_site import furthest_site_simplices

    for trial in range(8):
        if trial % 2:
            points = rng.integers(0, 3, (int(rng.integers(8, 30)), d)).astype(float)
        else:
            q = rng.normal(size=(30, d))
            points = np.round(5 * q / np.linalg.norm(q, axis=1)[:, None])
        tri = dewall.Delaunay(points)
        if d == 2:
            hull = extreme_hull_edges_2d(points, tri.simplices, tri.neighbors)
            whole = np.ones(len(hull), dtype=bool)
        else:
            hull, _, whole = extreme_facets_3d(points, tri.simplices, tri.neighbors,
                                               _hull_facets(tri.simplices, tri.neighbors))
        assert simplex_set(furthest_site_simplices(points, hull, whole)) == simplex_set(
            furthest_site_simplices(points, *quickhull_facets(points)))
