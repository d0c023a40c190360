"""dewall.ConvexHull and dewall.Voronoi against scipy.spatial's on the same points (compared as
sets), plus cases ported from scipy 1.10's test_qhull.py (TestConvexHull, TestVoronoi)."""

import numpy as np
import pytest
import scipy.spatial as ss

import dewall
from conftest import simplex_set


def nearest_rows(reference, coordinates):
    """For each row of coordinates, the index of the equal (to 1e-9) row of reference."""
    distance = np.linalg.norm(coordinates[:, None, :] - reference[None, :, :], axis=2)
    rows = distance.argmin(axis=1)
    assert (distance[np.arange(len(rows)), rows] < 1e-9).all()
    return rows


@pytest.mark.parametrize("d, n", [(2, 150), (3, 80), (4, 40)])
def test_convex_hull_equals_scipy(d, n, rng):
    points = rng.random((n, d))
    ours, theirs = dewall.ConvexHull(points), ss.ConvexHull(points)
    assert simplex_set(ours.simplices) == simplex_set(theirs.simplices)
    assert ours.volume == pytest.approx(theirs.volume, rel=1e-12)
    assert ours.area == pytest.approx(theirs.area, rel=1e-12)
    np.testing.assert_array_equal(np.sort(ours.vertices), np.sort(theirs.vertices))
    row = {tuple(sorted(f)): i for i, f in enumerate(theirs.simplices)}
    match = [row[tuple(sorted(f))] for f in ours.simplices]
    np.testing.assert_allclose(ours.equations, theirs.equations[match], atol=1e-12)
    for i, facet in enumerate(ours.simplices):  # neighbour opposite vertex j: same vertex set as scipy's
        for j, v in enumerate(facet):
            k = list(theirs.simplices[match[i]]).index(v)
            assert set(ours.simplices[ours.neighbors[i, j]]) == set(theirs.simplices[theirs.neighbors[match[i], k]])
    assert (points @ ours.equations[:, :-1].T + ours.equations[:, -1] <= 1e-12).all()


@pytest.mark.parametrize("d, n, furthest", [(2, 150, False), (3, 60, False), (4, 30, False), (2, 100, True),
                                             (3, 50, True)])
def test_voronoi_equals_scipy(d, n, furthest, rng):
    points = rng.random((n, d))
    ours, theirs = dewall.Voronoi(points, furthest), ss.Voronoi(points, furthest)
    assert ours.vertices.shape == theirs.vertices.shape
    to_theirs = nearest_rows(theirs.vertices, ours.vertices)

    def mapped(vertices):
        return frozenset(-1 if v == -1 else int(to_theirs[v]) for v in vertices)

    assert ({tuple(sorted(p)): mapped(v) for p, v in zip(ours.ridge_points, ours.ridge_vertices)} ==
            {tuple(sorted(p)): frozenset(v) for p, v in zip(theirs.ridge_points, theirs.ridge_vertices)})
    assert len(ours.regions) == len(theirs.regions) == n + (not furthest) and ours.point_region.shape == (n,)
    for i in range(n):
        assert mapped(ours.regions[ours.point_region[i]]) == frozenset(theirs.regions[theirs.point_region[i]])
    if d == 3:  # each ridge polygon in Qhull's cyclic order, up to rotation and direction
        theirs_by_pair = {tuple(sorted(p)): v for p, v in zip(theirs.ridge_points.tolist(), theirs.ridge_vertices)}
        for p, v in zip(ours.ridge_points.tolist(), ours.ridge_vertices):
            mine, reference = [int(to_theirs[x]) if x >= 0 else -1 for x in v], theirs_by_pair[tuple(sorted(p))]
            turns = [reference[i:] + reference[:i] for i in range(len(reference))]
            assert mine in turns or mine[::-1] in turns
    if d == 2:  # Qhull's cyclic order (in either direction: Qhull's turn either way), ours counterclockwise
        for i in range(n):
            region = [int(to_theirs[v]) if v >= 0 else -1 for v in ours.regions[ours.point_region[i]]]
            reference = theirs.regions[theirs.point_region[i]]
            if not region:
                continue  # furthest site: a point inside the hull
            k = reference.index(region[0])
            backwards = reference[::-1]
            m = backwards.index(region[0])
            assert region in (reference[k:] + reference[:k], backwards[m:] + backwards[:m])
            finite = [v for v in ours.regions[ours.point_region[i]] if v >= 0]
            if len(finite) < len(region):
                continue  # unbounded: the chain from one hull triangle to the other
            angle = np.unwrap(np.arctan2(*(ours.vertices[finite] - points[i]).T[::-1]))
            assert (np.diff(angle) > 0).all()


# ---- ported from scipy's test_qhull.py ---------------------------------------------------------


def _hull_via_delaunay(points):
    """ConvexHull's other route: the exact Delaunay triangulation's boundary (4-D+ flat hulls,
    nearly flat input), used here as the reference for Quickhull."""
    hull = dewall.ConvexHull.__new__(dewall.ConvexHull)
    hull.points, hull.ndim, hull.npoints = points, points.shape[1], points.shape[0]
    hull._from_delaunay(dewall.Delaunay(points))
    return hull


@pytest.mark.parametrize("d", [2, 3, 4])
def test_quickhull_equals_the_delaunay_boundary_on_degenerate_input(d, rng):
    """Lattices with duplicates, rounded sphere points, a grid in random order: the same extreme
    vertices, volume and area as the Delaunay route (in 4-D: its extreme points, a subset), a
    closed facet graph, every point inside every facet's plane."""
    for trial in range(12):
        n = int(rng.integers(d + 2, 50))
        kind = trial % 3
        if kind == 0:
            points = rng.integers(0, 3, (n, d)).astype(float)
        elif kind == 1:
            q = rng.normal(size=(n, d))
            points = np.round(8 * q / np.linalg.norm(q, axis=1)[:, None])
        else:
            points = np.array(np.meshgrid(*[range(3)] * d)).reshape(d, -1).T.astype(float)
            points = points[rng.permutation(len(points))]
        ours, reference = dewall.ConvexHull(points), _hull_via_delaunay(points)
        if d <= 3:
            assert set(ours.vertices) == set(reference.vertices)
        else:
            assert set(ours.vertices) <= set(reference.vertices)
        assert ours.volume == pytest.approx(reference.volume, rel=1e-9)
        assert ours.area == pytest.approx(reference.area, rel=1e-9)
        assert (ours.neighbors >= 0).all()
        assert all(i in ours.neighbors[j] for i in range(ours.nsimplex) for j in ours.neighbors[i])
        assert (ours.equations[:, :-1] @ points.T + ours.equations[:, -1:] <= 1e-12).all()


@pytest.mark.parametrize("d", [3, 4, 5, 6])
def test_quickhull_filter_on_nearly_flat_facets(d, rng):
    """The corners of a cube moved by a few units in the last place (at the origin, and at 1000):
    facets nearly in one hyperplane, where the static filter cannot decide and the exact test
    must. The facets are the exact Delaunay triangulation's boundary facets, an independent
    construction."""
    for trial in [1] if d == 6 else range(4):  # 6-D at the origin: the reference's Delaunay takes 5 s
        corners = np.array(np.meshgrid(*[range(2)] * d)).reshape(d, -1).T.astype(float)
        offset = 1e3 if trial % 2 else 0.0
        points = corners + offset + rng.uniform(-1, 1, corners.shape) * (2.0 ** -33 if offset else 2.0 ** -45)
        compiled = dewall._dewall.convex_hull(points)
        assert compiled is not None and not compiled[3]  # moved off the planes: no two facets in one
        reference = dewall.Delaunay(points).convex_hull
        assert simplex_set(compiled[0]) == simplex_set(reference)


@pytest.mark.parametrize("d", [3, 4, 5, 6])
def test_quickhull_filter_on_rounded_facet_points(d, rng):
    """A random simplex and points on one of its facets, rounded off its hyperplane by a few ulps
    to either side: the floating-point orientation gets many of them wrong (a filter with its
    bound 10^6 times too small failed most trials). The facets are the exact Delaunay
    triangulation's boundary facets, an independent construction."""
    tried = 0
    for _ in range(6):
        simplex = rng.random((d + 1, d)) * 10 - 5
        weights = rng.random((25, d))
        points = np.vstack([simplex, (weights / weights.sum(axis=1)[:, None]) @ simplex[:d]])
        compiled = dewall._dewall.convex_hull(points)
        if compiled is None or compiled[3]:
            continue  # some points exactly in one hyperplane: the Delaunay boundary triangulates that facet differently
        tried += 1
        assert simplex_set(compiled[0]) == simplex_set(dewall.Delaunay(points).convex_hull)
    assert tried >= 3


def test_masked_and_nan_fail():  # TestConvexHull/TestVoronoi.test_masked_array_fails, ..._with_nans_fails
    for cls in (dewall.ConvexHull, dewall.Voronoi):
        with pytest.raises(ValueError):
            cls(np.ma.masked_all((4, 2)))
    with pytest.raises(ValueError):
        dewall.ConvexHull(np.array([(0, 0), (1, 1), (2, np.nan)]))


def test_vertices_2d_counterclockwise(rng):  # TestConvexHull.test_vertices_2d
    hull = dewall.ConvexHull(rng.random((30, 2)))
    np.testing.assert_array_equal(np.unique(hull.simplices), np.sort(hull.vertices))
    x, y = hull.points[hull.vertices].T
    assert (np.diff(np.unwrap(np.arctan2(y - y.mean(), x - x.mean()))) > 0).all()


def test_volume_area_cube():  # TestConvexHull.test_volume_area
    points = np.array([(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0), (0, 0, 1), (0, 1, 1), (1, 0, 1), (1, 1, 1)])
    hull = dewall.ConvexHull(points)
    assert hull.volume == pytest.approx(1.0, rel=1e-14) and hull.area == pytest.approx(6.0, rel=1e-14)


def test_2d_hull_of_a_grid_has_its_corners_only():
    x = np.arange(4.0)
    grid = np.array(np.meshgrid(x, x)).reshape(2, -1).T
    grid = np.vstack((grid, grid[:2]))  # and duplicates
    ours, theirs = dewall.ConvexHull(grid), ss.ConvexHull(grid)
    assert simplex_set(ours.simplices) == simplex_set(theirs.simplices) == {(0, 3), (0, 12), (3, 15), (12, 15)}
    assert set(ours.vertices) == set(theirs.vertices) and ours.coplanar.shape == theirs.coplanar.shape == (0, 3)
    assert (ours.volume, ours.area) == (9.0, 12.0)
    for i, facet in enumerate(ours.simplices):  # neighbours: the facet through the other vertex
        for j in range(2):
            assert facet[1 - j] in ours.simplices[ours.neighbors[i, j]]


def test_3d_hull_of_a_cube_and_a_grid_has_their_corners_only():
    import itertools

    cube = np.array(list(itertools.product([0, 1], repeat=3)), dtype=float)
    on_faces = np.array([[0.5, 0.5, 0.5], [0.5, 0.5, 0], [0.5, 0, 0], [0.3, 0.6, 1]])  # inside, face, edge, face
    grid = np.stack([a.ravel() for a in np.meshgrid(*[np.arange(4.0)] * 3)], axis=1)
    for points in (cube, np.vstack((cube, on_faces)), grid):
        ours, theirs = dewall.ConvexHull(points), ss.ConvexHull(points)
        assert ours.nsimplex == theirs.nsimplex == 12  # two triangles per square face
        np.testing.assert_array_equal(np.sort(ours.vertices), np.sort(theirs.vertices))
        assert ours.volume == pytest.approx(theirs.volume, rel=1e-14) and ours.area == pytest.approx(theirs.area)
        assert (points @ ours.equations[:, :-1].T + ours.equations[:, -1] <= 1e-12).all()
        for i, facet in enumerate(ours.simplices):  # each neighbour shares the facet's other two vertices
            for j in range(3):
                assert set(np.delete(facet, j)) <= set(ours.simplices[ours.neighbors[i, j]])


def test_hull_incremental(rng):  # TestConvexHull.test_incremental (bug-2850)
    chunks = [rng.random((10, 2)), np.array([[0, 0], [0, 1], [1, 0], [1, 1]])]
    hull = dewall.ConvexHull(chunks[0], incremental=True)
    hull.add_points(chunks[1])
    assert simplex_set(hull.simplices) == {(10, 11), (10, 12), (11, 13), (12, 13)}


def test_voronoi_simple_grid():  # TestVoronoi.test_simple, as sets (scipy pins Qhull's numbering)
    points = np.array([(x, y) for x in range(3) for y in range(3)], dtype=float)
    vor = dewall.Voronoi(points)
    expected = np.array([(0.5, 0.5), (0.5, 1.5), (1.5, 0.5), (1.5, 1.5)])
    assert vor.vertices.shape == (4, 2)  # cocircular squares: one vertex each, exactly
    to_expected = nearest_rows(expected, vor.vertices)
    regions = {frozenset(-1 if v == -1 else int(to_expected[v]) for v in r) for r in vor.regions}
    assert regions == {frozenset(r) for r in [[-1, 0], [-1, 0, 1], [1, -1], [-1, 2, 0], [0, 1, 3, 2], [-1, 3, 1],
                                              [2, -1], [-1, 3, 2], [-1, 3], []]}
    assert len(vor.ridge_points) == 12
    assert vor.furthest_site is False


def test_voronoi_furthest_site():  # TestVoronoi.test_furthest_site, as sets; test_furthest_site_flag
    points = [(0, 0), (0, 1), (1, 0), (0.5, 0.5), (1.1, 1.1)]
    vor = dewall.Voronoi(points, furthest_site=True)
    assert vor.furthest_site is True and dewall.Voronoi(points).furthest_site is False
    expected = np.array([(0.6000000000000001, 0.5), (0.5, 0.6000000000000001)])  # qvoronoi Qu's output
    to_expected = nearest_rows(expected, vor.vertices)

    def mapped(vertices):
        return tuple(sorted(-1 if v == -1 else int(to_expected[v]) for v in vertices))

    assert [mapped(vor.regions[vor.point_region[i]]) for i in range(5)] == [(-1, 0, 1), (-1, 0), (-1, 1), (),
                                                                            (-1, 0, 1)]
    assert sorted((tuple(sorted(p)), mapped(v)) for p, v in zip(vor.ridge_points, vor.ridge_vertices)) == [
        ((0, 1), (-1, 0)), ((0, 2), (-1, 1)), ((0, 4), (0, 1)), ((1, 4), (-1, 0)), ((2, 4), (-1, 1))]


@pytest.mark.parametrize("d", [2, 3, 4])
def test_ridges_separate_nearest_neighbours(d, rng):  # TestVoronoi.test_ridges
    points = rng.random((30, d))
    tree = ss.cKDTree(points)
    vor = dewall.Voronoi(points)
    for (p, q), v in vor.ridge_dict.items():
        if min(v) < 0:
            continue
        middle = vor.vertices[v].mean(axis=0)
        step = 1e-6 * (points[p] - middle)
        assert tree.query(middle + step)[1] == p and tree.query(middle - step)[1] == q


def test_cospherical_points_give_one_vertex():
    import itertools

    corners = np.array(list(itertools.product([0, 1], repeat=3)), dtype=float)
    for points in (corners, np.vstack((corners, [[0.5, 0.5, 0.5]]))):
        ours, theirs = dewall.Voronoi(points), ss.Voronoi(points)
        assert ours.vertices.shape == theirs.vertices.shape  # 1, then 6: one per cospherical cell
        np.testing.assert_allclose(np.sort(ours.vertices, axis=0), np.sort(theirs.vertices, axis=0), atol=1e-12)
        assert simplex_set(ours.ridge_points) == simplex_set(theirs.ridge_points)  # none, then 20
    assert dewall.Voronoi(corners).regions == [[]] + [[-1, 0]] * 8


@pytest.mark.parametrize("options, extra", [("Qbb Qc Qz", 1), ("Qbb Qc", 0)])
@pytest.mark.parametrize("n, ndim", [(50, 2), (100, 3)])
def test_point_region_structure(n, ndim, options, extra):  # TestVoronoi.test_point_region_structure (gh-16773)
    points = np.random.default_rng(7790).random((n, ndim))
    vor = dewall.Voronoi(points, qhull_options=options)
    assert vor.point_region.max() == n - 1 + extra and vor.point_region.size == len(vor.regions) - extra == n
    sizes = [len(r) for r in vor.regions]
    assert sizes.count(0) == extra
    if extra:
        assert sizes.index(0) not in vor.point_region
    assert len(dewall.Voronoi(points, incremental=True).regions) == n  # no Qz in incremental mode, as scipy's


@pytest.mark.parametrize("d, n", [(2, 30), (3, 30), (4, 30), (5, 30), (6, 10)])
def test_hull_consistency_tri(d, n, rng):  # TestConvexHull.test_hull_consistency_tri (random datasets)
    points = rng.random((n, d))
    hull = dewall.ConvexHull(points)
    assert simplex_set(dewall.Delaunay(points).convex_hull) == simplex_set(hull.simplices)
    assert simplex_set(hull.simplices) == simplex_set(ss.ConvexHull(points).simplices)
    np.testing.assert_array_equal(np.unique(hull.simplices), np.sort(hull.vertices))


def test_3d_ridges_in_cyclic_order(rng):
    points = rng.random((60, 3))
    vor = dewall.Voronoi(points)
    for (p, q), ridge in vor.ridge_dict.items():
        finite = vor.vertices[[v for v in ridge if v >= 0]]
        if len(finite) < 3:
            continue
        # consecutive edges turn the same way around the edge pq: a convex polygon, in order
        axis = points[q] - points[p]
        m = len(finite)
        turns = [np.dot(np.cross(finite[(k + 1) % m] - finite[k], finite[(k + 2) % m] - finite[(k + 1) % m]), axis)
                 for k in range(m - (2 if -1 in ridge else 0))]
        assert (np.array(turns) > 0).all() or (np.array(turns) < 0).all()


def _good_facets(hull):
    return {tuple(sorted(f)) for f, good in zip(hull.simplices.tolist(), hull.good) if good}


@pytest.mark.parametrize("option", ["QG4", "QG-4"])
def test_good_facets_as_scipy(option, rng):  # TestConvexHull.test_good2d*, test_good3d, compared as sets
    square = np.array([[0.2, 0.2], [0.2, 0.4], [0.4, 0.4], [0.4, 0.2], [0.3, 0.6]])
    for extra in ([[0.3, 0.7]], [[0.3, -0.7]], [[0.3, 0.41]], [[0.5, 0.6], [0.6, 0.6]], [[0.3, 0.6 + 1e-16]]):
        ours = dewall.ConvexHull(square, incremental=True, qhull_options=option)
        theirs = ss.ConvexHull(square, incremental=True, qhull_options=option)
        ours.add_points(np.array(extra))
        theirs.add_points(np.array(extra))
        assert _good_facets(ours) == _good_facets(theirs)
        assert ours.good.dtype == bool and ours.nsimplex == theirs.nsimplex
    for d in (2, 3):
        points = rng.random((25, d))
        options = option.replace("4", "7")
        ours, theirs = dewall.ConvexHull(points, qhull_options=options), ss.ConvexHull(points, qhull_options=options)
        assert _good_facets(ours) == _good_facets(theirs) and 7 not in ours.vertices
    assert dewall.ConvexHull(square).good is None
    with pytest.raises(dewall.InvalidOption):
        dewall.ConvexHull(square, qhull_options="QG5")
