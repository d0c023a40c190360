"""dewall.certify: true exactly when the check passes, with the first violation and its
witness otherwise; usable on scipy's output."""

import numpy as np
from scipy.spatial import Delaunay as ScipyDelaunay

import dewall

SQUARE = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=np.float64)


def test_scipy_output_on_random_points(rng):
    points = rng.random((500, 3))
    result = dewall.certify(points, ScipyDelaunay(points).simplices, canonical=True)
    assert result and result.delaunay and result.canonical and result.violation is None
    assert result.counts["simplices"] == ScipyDelaunay(points).nsimplex


def test_cospherical_flip_is_delaunay_not_canonical():
    ours = dewall.Delaunay(SQUARE).simplices
    diagonals = {frozenset(a) & frozenset(b) for a in ours for b in ours if len(set(a) & set(b)) == 2}
    (diagonal,) = diagonals
    other = [{0, 1, 2, 3} - {v} for v in diagonal]  # the two triangles of the other diagonal
    flipped = np.array([sorted(t) for t in other])
    result = dewall.certify(SQUARE, flipped)
    assert result and result.delaunay and not result.canonical
    strict = dewall.certify(SQUARE, flipped, canonical=True)
    assert not strict and strict.violation.rule == "not_canonical" and not strict.violation.fatal
    assert dewall.certify(SQUARE, ours, canonical=True)


def test_not_delaunay_names_the_witness(rng):
    points = np.array([[0, 0], [4, 0], [0, 4], [4, 4], [2, 1]], dtype=np.float64)
    tri = dewall.Delaunay(points)
    # Replace the triangulation by a fan from vertex 0: valid tiling, not Delaunay.
    fan = np.array([[0, 1, 4], [0, 4, 3], [0, 3, 2], [4, 1, 3]])
    result = dewall.certify(points, fan)
    assert not result and not result.delaunay
    assert result.violation.rule == "not_locally_delaunay"
    assert result.violation.point is not None and len(result.violation.face) == 2
    assert "not locally Delaunay" in result.violation.message
    assert dewall.certify(points, tri.simplices)


def test_missing_simplex():
    points = rng_points = np.random.default_rng(3).random((50, 2))
    simplices = dewall.Delaunay(rng_points).simplices[1:]
    result = dewall.certify(points, simplices, all=True)
    assert not result and len(result.violations) >= 1 and result.violation.fatal
