"""dewall.interpolate against scipy.interpolate on the same data: equal values on random points,
and a value for every query inside the hull of a grid."""

import numpy as np
import pytest
import scipy.interpolate as si

import dewall
import dewall.interpolate as di


@pytest.mark.parametrize("d, n", [(2, 300), (3, 200), (4, 80)])
def test_linear_equals_scipy(d, n, rng):
    points = rng.random((n, d))
    values = np.column_stack((np.sin(3 * points.sum(axis=1)), points[:, 0] ** 2))
    queries = rng.random((1500, d)) * 1.2 - 0.1  # some outside the hull: fill_value
    ours = di.griddata(points, values, queries)
    theirs = si.griddata(points, values, queries)
    assert ours.shape == theirs.shape == (1500, 2)
    np.testing.assert_array_equal(np.isnan(ours), np.isnan(theirs))
    assert 0 < np.isnan(ours[:, 0]).sum() < 1500
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-12)
    rescaled = di.LinearNDInterpolator(points * [1, 100] + [0, 5] if d == 2 else points, values[:, 0], rescale=True)
    reference = si.LinearNDInterpolator(points * [1, 100] + [0, 5] if d == 2 else points, values[:, 0], rescale=True)
    q = queries * [1, 100] + [0, 5] if d == 2 else queries
    np.testing.assert_allclose(rescaled(q), reference(q), rtol=0, atol=1e-12)


def test_call_conventions_and_options(rng):
    points = rng.random((100, 2))
    values = points[:, 0] + 1j * points[:, 1]  # complex, as scipy
    tri = dewall.Delaunay(points)
    ours, theirs = di.LinearNDInterpolator(tri, values, fill_value=-5), si.LinearNDInterpolator(points, values, -5)
    x, y = np.meshgrid(np.linspace(-0.2, 1.2, 7), np.linspace(-0.2, 1.2, 5))
    np.testing.assert_allclose(ours(x, y), theirs(x, y), atol=1e-12)  # broadcast coordinate arrays
    assert ours(x, y).shape == (5, 7) and ours(x, y).dtype == np.complex128
    np.testing.assert_allclose(ours((x, y)), theirs((x, y)), atol=1e-12)
    np.testing.assert_allclose(ours(np.stack((x, y), axis=-1)), theirs(np.stack((x, y), axis=-1)), atol=1e-12)
    assert (ours(x, y) == -5).any()
    with pytest.raises(ValueError, match="Rescaling is not supported"):
        di.LinearNDInterpolator(tri, values, rescale=True)
    with pytest.raises(ValueError, match="different number of values and points"):
        di.LinearNDInterpolator(points, values[:-1])
    with pytest.raises(ValueError, match="number of dimensions in xi"):
        ours(np.ones((3, 3)))
    for xi in ((0.5, 0.5), np.array([0.5, 0.5]), [0.5, 0.5], (x, y), np.stack((x, y), axis=-1)):  # shapes as scipy's
        for method in ("linear", "nearest", "cubic"):
            assert di.griddata(points, values, xi, method=method).shape == \
                si.griddata(points, values, xi, method=method).shape
            assert ours(xi).shape == theirs(xi).shape
    with pytest.raises(ValueError, match="Unknown interpolation method"):
        di.griddata(points, values, points, method="cubic2")


def test_cubic_and_nearest_equal_scipy(rng):
    points = rng.random((200, 2))
    values = np.cos(4 * points[:, 0]) * points[:, 1]
    queries = rng.random((500, 2)) * 1.1 - 0.05
    for method in ("cubic", "nearest"):
        ours, theirs = (di.griddata(points, values, queries, method=method),
                        si.griddata(points, values, queries, method=method))
        np.testing.assert_array_equal(np.isnan(ours), np.isnan(theirs))
        np.testing.assert_allclose(ours, theirs, atol=1e-12)
    ct = di.CloughTocher2DInterpolator(points, values, rescale=True)
    np.testing.assert_allclose(ct(queries), si.CloughTocher2DInterpolator(points, values, rescale=True)(queries),
                               atol=1e-12)
    assert isinstance(ct, si.CloughTocher2DInterpolator)


def grid(k, d):
    axes = np.meshgrid(*[np.linspace(0, 1, k)] * d, indexing="ij")
    return np.stack([a.ravel() for a in axes], axis=1)


@pytest.mark.parametrize("k, d", [(21, 2), (9, 3)])
def test_every_query_inside_a_grid_gets_a_value(k, d, rng):
    points = grid(k, d)
    values = points @ np.arange(1, d + 1) + 1  # linear: interpolation is exact
    queries = np.vstack((rng.random((3000, d)), points, grid(2 * k - 1, d)))  # inside, on vertices, edges, faces
    ours = di.griddata(points, values, queries)
    assert np.isfinite(ours).all()
    np.testing.assert_allclose(ours, queries @ np.arange(1, d + 1) + 1, atol=1e-12)
    if d == 2:
        cubic = di.griddata(points, values, queries, method="cubic")
        assert np.isfinite(cubic).all()


def test_a_dewall_triangulation_handed_to_scipy(rng):
    points = rng.random((200, 3))
    values = np.sin(points).sum(axis=1)
    tri = dewall.Delaunay(points)
    view = di.as_scipy_delaunay(tri)
    queries = rng.random((300, 3))
    np.testing.assert_allclose(si.LinearNDInterpolator(view, values)(queries),
                               di.LinearNDInterpolator(tri, values)(queries), atol=1e-12)
    found = view.find_simplex(queries)  # scipy's walk on dewall's simplices
    assert (found == tri.find_simplex(queries)).mean() > 0.99


def test_large_offset_keeps_the_interpolation_right(rng):
    """2,000 points in a unit square offset by 10^7: Qhull's triangulation has a few dozen triangles at most
    (max error 0.96 on these queries, measured with scipy 1.10), dewall's is the Delaunay one of
    the (rounded) points: the error stays that of the unshifted data."""
    points = rng.random((2000, 2))
    queries = rng.random((5000, 2)) * 0.8 + 0.1
    exact = np.sin(6 * queries[:, 0]) * queries[:, 1]
    values = np.sin(6 * points[:, 0]) * points[:, 1]
    error_at_origin = np.abs(di.griddata(points, values, queries) - exact).max()
    shifted = points + 1e7
    assert dewall.Delaunay(shifted).nsimplex > 3900
    error = np.abs(di.griddata(shifted, values, queries + 1e7) - exact).max()
    assert error < 2 * error_at_origin
