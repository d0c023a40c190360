"""7 and 8 dimensions: Delaunay, ConvexHull, Voronoi from CGAL's dD triangulation (dewall/_high_dimension.py).

Random points against scipy (as sets); a degenerate set (the 7-cube's corners, every point on
one sphere) certified here with the exact predicates, since dewall.certify is compiled for 2 … 6
dimensions: positive orientation, a proper covering of the hull (volumes), neighbours across
shared facets, and at each interior facet the opposite vertex outside the sphere under the
perturbation, whose sign is computed by this module's own code, checked first against the
library's kernel in 2 … 6 dimensions.
"""

import itertools
import math
import pickle

import numpy as np
import pytest
from conftest import simplex_set

import dewall
from dewall import _dewall

scipy_spatial = pytest.importorskip("scipy.spatial")


def signs(points, rows, kind, cgal_dd=False):
    return _dewall.predicate_signs(points, np.ascontiguousarray(rows, dtype=np.uint32), kind, cgal_dd)


def opposite_vertices(tri):
    """(simplex i, facet j, the vertex of the neighbour across that facet) for each interior facet."""
    i, j = np.nonzero(tri.neighbors >= 0)
    n = tri.neighbors[i, j]
    k = np.argmax(tri.neighbors[n] == i[:, None], axis=1)
    return i, j, tri.simplices[n, k]


def check_triangulation(points, tri, volume):
    """Exactly what makes `tri` the perturbed Delaunay triangulation of `points` (distinct points)."""
    d = points.shape[1]
    s = tri.simplices
    assert (signs(points, s, 0) == 1).all()  # positively oriented
    edges = points[s[:, :-1]] - points[s[:, -1:]]
    assert np.sum(np.abs(np.linalg.det(edges))) / math.factorial(d) == pytest.approx(volume, rel=1e-12)
    i, j, opposite = opposite_vertices(tri)
    n = tri.neighbors[i, j]
    assert (tri.neighbors[n] == i[:, None]).any(axis=1).all()  # symmetric
    shared = np.sort(np.where(np.arange(d + 1) == j[:, None], -1, s[i]), axis=1)[:, 1:]
    across = np.sort(np.where(s[n] == opposite[:, None], -1, s[n]), axis=1)[:, 1:]
    assert (shared == across).all()
    rows = np.column_stack((s[i], opposite))
    assert (signs(points, rows, 1) <= 0).all()  # locally Delaunay, unperturbed
    assert (signs(points, rows, 2) == -1).all()  # and under the perturbation: the canonical one


def test_perturbed_sign_equals_the_library_kernel(rng):
    # CGAL's dD predicates and this module's perturbed sphere test against the library's kernel,
    # on grids (every sphere test near a tie) in 2 … 6 dimensions
    for d, k in [(2, 6), (3, 4), (4, 3), (5, 3), (6, 2)]:
        grid = np.array(list(itertools.product(range(k), repeat=d)), dtype=np.float64)
        tri = dewall.Delaunay(grid)
        pick = rng.integers(0, tri.nsimplex, 300)
        query = rng.integers(0, len(grid), 300)
        keep = ~(tri.simplices[pick] == query[:, None]).any(axis=1)
        rows = np.column_stack((tri.simplices[pick][keep], query[keep]))
        for kind, width in [(0, d + 1), (1, d + 2), (2, d + 2)]:
            np.testing.assert_array_equal(signs(grid, rows[:, :width], kind, True), signs(grid, rows[:, :width], kind),
                                          err_msg=f"d={d} kind={kind}")
        assert (signs(grid, rows, 1) == 0).any()  # ties were tested


@pytest.mark.parametrize("d, n", [(7, 30), (8, 20), (9, 14)])  # 9: the dynamic-dimension kernel
def test_random_points_equal_scipy(rng, d, n):
    points = rng.random((n, d))
    tri, theirs = dewall.Delaunay(points), scipy_spatial.Delaunay(points)
    assert simplex_set(tri.simplices) == simplex_set(theirs.simplices)
    assert tri.simplices.dtype == tri.neighbors.dtype == np.int32
    check_triangulation(points, tri, scipy_spatial.ConvexHull(points).volume)
    assert simplex_set(tri.convex_hull) == simplex_set(theirs.convex_hull)
    # point location: each simplex's centroid in that simplex, far points outside
    centroids = points[tri.simplices].mean(axis=1)
    np.testing.assert_array_equal(tri.find_simplex(centroids), np.arange(tri.nsimplex))
    assert (tri.find_simplex(points.mean(axis=0) + 10 * np.eye(d)) == -1).all()
    c = np.einsum("ijk,ik->ij", tri.transform[:, :d], centroids - tri.transform[:, d])  # barycentric, as scipy's
    np.testing.assert_allclose(c, 1 / (d + 1), atol=1e-8)


def test_hull_and_voronoi_equal_scipy(rng):
    points = rng.random((25, 7))
    hull, theirs = dewall.ConvexHull(points), scipy_spatial.ConvexHull(points)
    assert simplex_set(hull.simplices) == simplex_set(theirs.simplices)
    np.testing.assert_array_equal(hull.vertices, theirs.vertices)
    assert hull.volume == pytest.approx(theirs.volume, rel=1e-10)
    assert hull.area == pytest.approx(theirs.area, rel=1e-10)
    vor, their_vor = dewall.Voronoi(points), scipy_spatial.Voronoi(points)
    assert {tuple(sorted(p)) for p in vor.ridge_points} == {tuple(sorted(p)) for p in their_vor.ridge_points}
    np.testing.assert_allclose(np.sort(vor.vertices, axis=0), np.sort(their_vor.vertices, axis=0), rtol=1e-8)


def test_cube_corners_are_certified_and_independent_of_order(rng):
    # the 7-cube's 128 corners lie on one sphere: every Delaunay triangulation of the cube is a
    # triangulation of it, and the perturbation picks one; Qhull's here is another
    cube = np.array(list(itertools.product((0.0, 1.0), repeat=7)))
    tri = dewall.Delaunay(cube)
    check_triangulation(cube, tri, 1.0)
    assert (signs(cube, np.column_stack((tri.simplices, np.full(tri.nsimplex, 5))), 1)[
        ~(tri.simplices == 5).any(axis=1)] == 0).all()  # cospherical indeed
    order = rng.permutation(len(cube))
    shuffled = dewall.Delaunay(np.ascontiguousarray(cube[order]))
    assert simplex_set(order[shuffled.simplices]) == simplex_set(tri.simplices)
    assert tri.nsimplex == 5040  # 7!: the perturbation's triangulation of the cube is Kuhn's


def test_duplicates_and_pickling(rng):
    points = rng.random((20, 7))
    tri = dewall.Delaunay(points)
    with_copies = dewall.Delaunay(np.r_[points, points[[4, 0]]])  # the first occurrence is the vertex
    assert simplex_set(with_copies.simplices) == simplex_set(tri.simplices)
    np.testing.assert_array_equal(with_copies.duplicates, [[20, 4], [21, 0]])
    np.testing.assert_array_equal(with_copies.coplanar[:, [0, 2]], [[20, 4], [21, 0]])
    again = pickle.loads(pickle.dumps(with_copies))
    np.testing.assert_array_equal(again.simplices, with_copies.simplices)
    np.testing.assert_array_equal(again.neighbors, with_copies.neighbors)
    np.testing.assert_array_equal(again.find_simplex(points[:5] * 0.9 + 0.05), with_copies.find_simplex(points[:5] * 0.9 + 0.05))


@pytest.mark.parametrize("d, k", [(2, 7), (3, 4), (4, 3), (5, 2), (6, 2)])
def test_cgal_dd_route_equals_the_library_below_seven_dimensions(d, k):
    # the route taken from 7 dimensions on, run where the library answers too: the same simplices
    # (CGAL's, on a grid with duplicates, every sphere test a tie), orientation and neighbours
    grid = np.array(list(itertools.product(range(k), repeat=d)), dtype=np.float64)
    points = np.r_[grid[::-1], grid[:5]]
    simplices, neighbors = _dewall.triangulate_dd(points)
    tri = dewall.Delaunay(points)
    assert simplex_set(simplices) == simplex_set(tri.simplices)
    assert (signs(points, simplices, 0) == 1).all()
    order = {tuple(sorted(s)): r for r, s in enumerate(tri.simplices.tolist())}
    mine = np.array([order[tuple(sorted(s))] for s in simplices.tolist()])
    theirs = tri.neighbors[mine]  # the library's neighbours, for the same rows
    for r, s in enumerate(simplices):
        for j in range(d + 1):
            n = neighbors[r, j]
            other = theirs[r, list(tri.simplices[mine[r]]).index(s[j])]
            assert (n == -1 and other == -1) or mine[n] == other


def test_errors_above_six_dimensions():
    with pytest.raises(dewall.DegenerateInput, match="need at least 8 distinct points"):
        dewall.Delaunay(np.eye(7))
    flat = np.random.default_rng(1).random((20, 7))
    flat[:, 3] = 0.5
    with pytest.raises(dewall.DegenerateInput, match="do not span E\\^7"):
        dewall.Delaunay(flat)
    nan = np.random.default_rng(1).random((20, 7))
    nan[4, 2] = np.nan
    with pytest.raises(ValueError, match="point 4 has a non-finite coordinate"):
        dewall.Delaunay(nan)
    with pytest.raises(ValueError, match="engine 'dewall'"):
        dewall.Delaunay(np.random.default_rng(1).random((20, 7)), engine="dewall")
    with pytest.raises(ValueError, match="dimension 7 is not supported"):  # the certifier: 2 … 6
        dewall.certify(np.random.default_rng(1).random((20, 7)), np.zeros((1, 8), dtype=int))
