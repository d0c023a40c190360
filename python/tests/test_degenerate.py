"""Degenerate input, where Qhull fails or answers wrongly: grids, cospherical integer
points, duplicates, large offsets. dewall's output is the canonical triangulation
(dewall.certify says so) and is the CLI's output, row for row."""

import numpy as np
import pytest

import dewall
from conftest import cli_triangulate, simplex_set


def grid(k, d):
    axes = np.meshgrid(*[np.arange(k, dtype=np.float64)] * d, indexing="ij")
    return np.column_stack([a.ravel() for a in axes])


def cospherical(radius_squared):
    """Every integer point of E^3 with |p|^2 = radius_squared: exactly on one sphere."""
    r = int(np.ceil(np.sqrt(radius_squared)))
    g = grid(2 * r + 1, 3) - r
    return g[(g**2).sum(axis=1) == radius_squared]


def with_duplicates(rng):
    points = rng.integers(0, 4, size=(60, 3)).astype(np.float64)  # many repeats, many ties
    return np.vstack([points, points[::7]])


CASES = {
    "grid 2D": lambda rng: grid(9, 2),
    "grid 3D": lambda rng: grid(5, 3),
    "grid 4D": lambda rng: grid(3, 4),
    "cospherical 3D": lambda rng: cospherical(50),
    "lattice-sphere generator": lambda rng: dewall.generate("lattice-sphere", 200, dim=3),
    "duplicates": with_duplicates,
    "offset 2^30": lambda rng: grid(4, 3) + 2.0**30,
    "offset 1e15, unit-scale noise": lambda rng: rng.random((100, 3)) + 1e15,
    "tiny scale": lambda rng: grid(4, 3) * 2.0**-500,
}


@pytest.fixture(params=list(CASES), ids=list(CASES))
def points(request, rng):
    return CASES[request.param](rng)


def test_canonical_and_equal_to_cli(points, tmp_path):
    tri = dewall.Delaunay(points)
    certificate = dewall.certify(points, tri.simplices, canonical=True)
    assert certificate, certificate
    assert certificate.canonical and certificate.delaunay
    np.testing.assert_array_equal(tri.simplices, cli_triangulate(points, tmp_path))


def test_engines_agree(points):
    sets = {engine: simplex_set(dewall.Delaunay(points, engine=engine).simplices) for engine in ("dewall", "cgal", "incremental")}
    assert sets["dewall"] == sets["cgal"] == sets["incremental"]


def test_threads_do_not_change_the_output(points):
    one = dewall.Delaunay(points, threads=1).simplices
    np.testing.assert_array_equal(one, dewall.Delaunay(points, threads=2).simplices)


def test_find_simplex_on_a_grid_is_exact():
    points = grid(4, 3)
    tri = dewall.Delaunay(points)
    # Points on shared faces and edges of the lattice: inside some closed simplex.
    inside = np.array([[1.5, 1.5, 1.5], [1, 1, 1.5], [0, 0, 0], [3, 3, 3], [1.5, 0, 0]])
    assert (tri.find_simplex(inside) >= 0).all()
    # Outside by the smallest margin a double allows: outside for the exact test (tol=0);
    # with scipy's default tolerance (100 eps) each gets a hull simplex, as scipy's does.
    outside = np.array([[np.nextafter(3.0, 4.0), 1, 1], [1, np.nextafter(0.0, -1.0), 1], [-1e-300, 2, 2]])
    assert (tri.find_simplex(outside, tol=0) == -1).all()
    found = tri.find_simplex(outside)
    assert (found >= 0).all()
    assert (tri.find_simplex(outside + [[1e-9, 0, 0], [0, -1e-9, 0], [-1e-9, 0, 0]]) == -1).all()


def test_duplicates_map_to_first_occurrence():
    points = np.array([[0, 0], [1, 0], [0, 1], [1, 0], [0, 0], [1, 1], [0.0, -0.0]])
    tri = dewall.Delaunay(points)
    np.testing.assert_array_equal(tri.duplicates, [[3, 1], [4, 0], [6, 0]])
    assert set(np.unique(tri.simplices)) == {0, 1, 2, 5}
    assert dewall.Delaunay(np.eye(3)[:, :2].copy()).duplicates.shape == (0, 2)


def test_integer_input_is_taken_exactly():
    points = grid(3, 3).astype(np.int64) + 2**52
    tri = dewall.Delaunay(points)
    assert dewall.certify(points, tri.simplices, canonical=True)
