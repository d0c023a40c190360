"""Bad input raises a Python exception — ValueError with the CLI's message for points
that cannot be triangulated, TypeError for a wrong dtype or shape — and never crashes."""

import numpy as np
import pytest

import dewall


def cube():
    return np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=np.float64)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite(bad):
    points = cube()
    points[3, 1] = bad
    with pytest.raises(ValueError, match=r"^point 3 has a non-finite coordinate \(NaN or infinity\)$") as error:
        dewall.Delaunay(points)
    assert isinstance(error.value, dewall.InvalidInput) and error.value.point == 3


def test_too_few_points():
    with pytest.raises(ValueError, match=r"^need at least 4 distinct points in dimension 3, got 2$"):
        dewall.Delaunay([[0, 0, 0], [1, 1, 1], [0, 0, 0]])
    with pytest.raises(ValueError, match="need at least 3 distinct points in dimension 2, got 0"):
        dewall.Delaunay(np.empty((0, 2)))


def test_not_spanning():
    points = cube()
    points[:, 2] = 0
    with pytest.raises(ValueError, match=r"^the points do not span E\^3: all 4 distinct points are coplanar") as error:
        dewall.Delaunay(points)
    assert error.value.point is None


@pytest.mark.parametrize("points", [
    np.array([[1 + 1j, 0], [0, 1], [1, 1]]),
    np.array([["a", "b"], ["c", "d"], ["e", "f"]]),
    np.array([[None, 1], [1, 1], [2, 2]], dtype=object),
    np.array([[True, False], [False, True], [True, True]]),
    np.ones((4, 2), dtype=np.longdouble),
], ids=["complex", "strings", "object", "bool", "longdouble"])
def test_wrong_dtype(points):
    with pytest.raises(TypeError, match="must be real numbers"):
        dewall.Delaunay(points)


@pytest.mark.parametrize("shape", [(12,), (3, 4, 2), ()])
def test_wrong_shape(shape):
    with pytest.raises(TypeError, match="2-D array"):
        dewall.Delaunay(np.ones(shape))


def test_ragged_list():
    with pytest.raises((TypeError, ValueError)):
        dewall.Delaunay([[0, 0], [1]])


def test_unsupported_dimension():  # 7 and up: CGAL's dD triangulation (test_high_dimension.py)
    with pytest.raises(ValueError, match="^dimension 1 is not supported \\(2 to 6\\)$"):
        dewall.Delaunay(np.random.default_rng(1).random((20, 1)))


def test_integers_that_are_not_doubles():
    points = cube().astype(np.int64)
    points[2, 0] = 2**53 + 1
    with pytest.raises(ValueError, match=r"points\[2, 0\] = 9007199254740993 is not exactly a double"):
        dewall.Delaunay(points)


def test_bad_engine_and_threads():
    with pytest.raises(ValueError, match=r"unknown engine 'qhull' \(auto, dewall, hybrid, incremental or cgal\)"):
        dewall.Delaunay(cube(), engine="qhull")
    with pytest.raises(ValueError, match="threads must be at least 1"):
        dewall.Delaunay(cube(), threads=0)


def test_find_simplex_wrong_shape():
    tri = dewall.Delaunay(cube())
    with pytest.raises(TypeError):
        tri.find_simplex(np.ones((4, 2)))
    with pytest.raises(TypeError):
        tri.find_simplex(np.ones((4, 3), dtype=complex))


def test_certify_bad_arrays():
    with pytest.raises(TypeError, match=r"shape \(m, 4\)"):
        dewall.certify(cube(), np.zeros((2, 3), dtype=int))
    with pytest.raises(TypeError, match="integers"):
        dewall.certify(cube(), np.zeros((2, 4)))
    result = dewall.certify(cube(), [[0, 1, 2, 9], [0, 1, 2, -1]])
    assert not result and result.violation.rule == "index_out_of_range"


def test_generate_errors():
    with pytest.raises(ValueError, match="unknown kind 'cubes'"):
        dewall.generate("cubes", 10)
    with pytest.raises(ValueError):
        dewall.generate("uniform", 10, dim=9)
    with pytest.raises(ValueError):
        dewall.generate("uniform", 10, seed=-1)


def test_direct_module_calls_are_checked():
    from dewall import _dewall

    with pytest.raises(TypeError, match="float64"):
        _dewall.triangulate(np.ones((5, 3), dtype=np.float32))
    with pytest.raises(TypeError, match="C-contiguous"):
        _dewall.triangulate(np.ones((5, 6))[:, ::2])
    with pytest.raises(TypeError):
        _dewall.triangulate([[0.0, 1.0]])


def test_scipy_code_catches_what_it_caught():
    """Where scipy raises QhullError (too few points, flat input), ours is a QhullError and a
    ValueError; where scipy raises ValueError (NaN), ours is a ValueError only."""
    from scipy.spatial import Delaunay as ScipyDelaunay
    from scipy.spatial import QhullError

    assert dewall.QhullError is QhullError
    flat = cube()
    flat[:, 2] = 0
    for points in (flat, cube()[:2], np.zeros((5, 3))):
        with pytest.raises(QhullError):
            ScipyDelaunay(points)
        with pytest.raises(QhullError) as error:
            dewall.Delaunay(points)
        assert isinstance(error.value, ValueError) and isinstance(error.value, dewall.InvalidInput)
        assert isinstance(error.value, dewall.DegenerateInput) and error.value.point is None
    nan = cube()
    nan[1, 1] = np.nan
    with pytest.raises(ValueError) as error:
        dewall.Delaunay(nan)
    assert not isinstance(error.value, QhullError) and error.value.point == 1


def test_importing_from_the_source_tree(tmp_path):
    """PYTHONPATH=python (the source tree) finds the build's compiled module, or says how to build
    it, instead of Python's "partially initialized module ... circular import"."""
    import os
    import subprocess
    import sys

    source = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    code = "import dewall; print(dewall.Delaunay([[0, 0], [1, 0], [0, 1]]).nsimplex)"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path,
                         env={**os.environ, "PYTHONPATH": source})
    built = os.path.isdir(os.path.join(os.path.dirname(source), "build", "python", "dewall"))
    if built:
        assert run.returncode == 0 and run.stdout.strip() == "1", run.stderr
    else:
        assert "circular import" not in run.stderr and "scripts/build.sh dewall_python" in run.stderr
