"""On random non-degenerate points dewall and scipy.spatial.Delaunay (Qhull) agree:
the same simplices, the same neighbours, the same containing simplex."""

import numpy as np
import pytest
from scipy.spatial import Delaunay as ScipyDelaunay

import dewall
from conftest import simplex_set

CASES = [(2, 400), (3, 300), (4, 150)]


@pytest.fixture(params=CASES, ids=[f"{d}D" for d, _ in CASES])
def both(request, rng):
    d, n = request.param
    points = rng.random((n, d))
    return points, dewall.Delaunay(points), ScipyDelaunay(points)


def test_same_simplices(both):
    points, ours, theirs = both
    assert simplex_set(ours.simplices) == simplex_set(theirs.simplices)


def test_positively_oriented(both):
    points, ours, _ = both
    p = points[ours.simplices]
    edges = p[:, 1:, :] - p[:, :1, :]
    assert (np.linalg.det(edges) > 0).all()  # random points: far from zero, floats are fine here


def neighbour_map(simplices, neighbors):
    """(simplex as a vertex set, opposite vertex) -> the neighbour's vertex set (None on the hull)."""
    out = {}
    for s, row in zip(simplices, neighbors):
        for vertex, n in zip(s, row):
            out[(frozenset(map(int, s)), int(vertex))] = None if n == -1 else frozenset(map(int, simplices[n]))
    return out


def test_same_neighbors(both):
    _, ours, theirs = both
    assert neighbour_map(ours.simplices, ours.neighbors) == neighbour_map(theirs.simplices, theirs.neighbors)


def test_convex_hull(both):
    _, ours, theirs = both
    assert simplex_set(ours.convex_hull) == simplex_set(theirs.convex_hull)


def test_find_simplex(both, rng):
    points, ours, theirs = both
    d = points.shape[1]
    queries = rng.random((500, d)) * 1.2 - 0.1  # some outside the hull
    mine, scipys = ours.find_simplex(queries), theirs.find_simplex(queries)
    for q, a, b in zip(queries, mine, scipys):
        assert (a == -1) == (b == -1), q
        if a != -1:
            assert set(ours.simplices[a]) == set(theirs.simplices[b]), q


def test_find_simplex_vertices_and_shape(both):
    points, ours, _ = both
    found = ours.find_simplex(points[:7])  # on vertices: a simplex having that vertex
    for i, s in enumerate(found):
        assert i in ours.simplices[s]
    assert ours.find_simplex(points[:6].reshape(2, 3, -1)).shape == (2, 3)
    assert ours.find_simplex(np.full(points.shape[1], np.nan)) == -1
