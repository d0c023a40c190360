"""Issue 57, the Python package: object arrays accepted, only public exceptions reach users,
reprs for every object the package returns, type information shipped with the package."""

import ast
import inspect
import os
import pickle
import re
import subprocess
import sys
from fractions import Fraction

import numpy as np
import pytest

import dewall
from dewall import _dewall

# ---- object arrays of floats, as scipy accepts them ------------------------------------------


def test_object_arrays_of_floats_and_integers(rng):
    points = rng.random((300, 3))
    expected = dewall.Delaunay(points).simplices
    as_objects = points.astype(object)
    np.testing.assert_array_equal(dewall.Delaunay(as_objects).simplices, expected)
    mixed = np.array([[0, 0.0], [1, np.float32(0)], [np.int64(0), 1.0], [1, 1]], dtype=object)
    assert dewall.Delaunay(mixed).nsimplex == 2
    assert dewall.ConvexHull(as_objects).volume == pytest.approx(dewall.ConvexHull(points).volume)
    assert len(dewall.Voronoi(as_objects).vertices) == len(dewall.Voronoi(points).vertices)
    tri = dewall.Delaunay(points)
    np.testing.assert_array_equal(tri.find_simplex(points[:20].astype(object)), tri.find_simplex(points[:20]))


def test_object_arrays_convert_exactly_or_not_at_all():
    exact = np.array([[2**53, 0], [0, 1], [1, 1]], dtype=object)  # Python ints that are doubles
    assert dewall.Delaunay(exact).nsimplex == 1
    for big in (2**53 + 1, 10**400):  # rounds; beyond the doubles' range
        rounded = np.array([[0, 0], [big, 0], [0, 1]], dtype=object)
        with pytest.raises(ValueError, match=r"points\[1, 0\] = \d+ is not exactly a double"):
            dewall.Delaunay(rounded)
    for other in (Fraction(1, 3), True, "1.0", np.longdouble(1), None, [1.0]):
        with pytest.raises(TypeError, match="must be real numbers.*object holding"):
            dewall.Delaunay(np.array([[0.0, 0.0], [other, 0.0], [0.0, 1.0]], dtype=object))


# ---- no private exception reaches a user -----------------------------------------------------


def _public(error_type):
    """Whether users can name `error_type` where its traceback says it lives."""
    if error_type.__module__ == "builtins":
        return True
    module = sys.modules.get(error_type.__module__)
    return (not any(part.startswith("_") for part in error_type.__module__.split("."))
            and getattr(module, error_type.__qualname__, None) is error_type)


def _raised(call):
    with pytest.raises(Exception) as caught:
        call()
    return caught.value


def test_every_error_is_a_public_class(rng):
    points = rng.random((30, 3))
    tri = dewall.Delaunay(points)
    calls = [
        lambda: tri.find_simplex(np.ones((4, 2))),  # wrong dimensionality in xi
        lambda: tri.find_simplex(np.float64(1)),
        lambda: dewall.Delaunay(np.zeros((5, 3))),  # degenerate
        lambda: dewall.Delaunay([[0.0, np.nan], [1, 0], [0, 1]]),  # non-finite
        lambda: dewall.Delaunay(points, qhull_options="QG4"),
        lambda: dewall.Delaunay(points[:, :1]),
        lambda: dewall.ConvexHull(np.zeros((5, 3))),
        lambda: dewall.Voronoi(np.zeros((5, 2))),
        lambda: dewall.Delaunay(np.ones((4, 2), dtype=complex)),
    ]
    for call in calls:
        error = _raised(call)
        assert _public(type(error)), f"{type(error).__module__}.{type(error).__qualname__}: {error}"
    shape = _raised(calls[0])
    assert isinstance(shape, ValueError) and isinstance(shape, TypeError)  # scipy's type, and dewall's before
    assert type(shape) is dewall.InvalidShape
    # picklable by their public names (multiprocessing sends them between processes)
    degenerate = _raised(calls[2])
    again = pickle.loads(pickle.dumps(degenerate))
    assert type(again) is dewall.DegenerateInput and str(again) == str(degenerate)


def test_traceback_names_public_classes():
    code = "import dewall, numpy as np; dewall.Delaunay(np.zeros((3, 3))).find_simplex(np.ones(2))"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    last = run.stderr.strip().splitlines()[-1]
    assert last.startswith("dewall.DegenerateInput: "), run.stderr
    code = "import dewall, numpy as np; dewall.Delaunay(np.eye(3, 2)).find_simplex(np.ones(3))"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.stderr.strip().splitlines()[-1].startswith("dewall.InvalidShape: wrong dimensionality"), run.stderr


# ---- reprs ------------------------------------------------------------------------------------


def test_reprs(rng):
    points = rng.random((60, 2))
    assert re.fullmatch(r"<dewall\.ConvexHull: 60 points in E\^2, \d+ vertices, \d+ facets>",
                        repr(dewall.ConvexHull(points)))
    assert re.fullmatch(r"<dewall\.Voronoi: 60 points in E\^2, \d+ vertices, \d+ ridges, 61 regions>",
                        repr(dewall.Voronoi(points)))
    values = points[:, 0]
    nsimplex = dewall.Delaunay(points).nsimplex
    for interpolator in (dewall.interpolate.LinearNDInterpolator(points, values),
                         dewall.interpolate.CloughTocher2DInterpolator(points, values)):
        name = type(interpolator).__name__
        assert repr(interpolator) == (f"<dewall.interpolate.{name}: 60 points in E^2, {nsimplex} simplices, "
                                      "values of shape (60,)>")
    nearest = dewall.interpolate.NearestNDInterpolator(points, np.column_stack((values, values)))
    assert repr(nearest) == "<dewall.interpolate.NearestNDInterpolator: 60 points in E^2, values of shape (60, 2)>"
    scipy_interpolate = pytest.importorskip("scipy.interpolate")
    assert isinstance(nearest, scipy_interpolate.NearestNDInterpolator)
    np.testing.assert_array_equal(nearest(points[:5]), np.column_stack((values, values))[:5])


# ---- type information -------------------------------------------------------------------------


def _stub():
    path = os.path.join(os.path.dirname(dewall.__file__), "_dewall.pyi")
    assert os.path.isfile(path), "the compiled module's stub is not installed next to it"
    return ast.parse(open(path).read())


def _parameters(node):
    arguments = node.args.args[1:] if node.args.args and node.args.args[0].arg == "self" else node.args.args
    defaults = [None] * (len(arguments) - len(node.args.defaults)) + [ast.literal_eval(d) for d in node.args.defaults]
    return [(a.arg, d) for a, d in zip(arguments, defaults)]


def _bound_parameters(function):
    """Parameter names and defaults from pybind11's signature line, e.g.
    "triangulate(points: object, engine: str = 'auto', threads: Optional[int] = None) -> ..."."""
    line = function.__doc__.splitlines()[0]
    inside = line[line.index("(") + 1:line.rindex(") ->")]
    out = []
    for part in filter(None, (p.strip() for p in re.split(r",\s*(?![^\[]*\])", inside))):
        name, _, default = part.partition("=")
        name = name.split(":")[0].strip()
        if name != "self":
            out.append((name, ast.literal_eval(default.strip()) if default else None))
    return out


def test_py_typed_and_stubs_match_the_module():
    assert os.path.isfile(os.path.join(os.path.dirname(dewall.__file__), "py.typed"))
    stub = _stub()
    functions = {n.name: n for n in stub.body if isinstance(n, ast.FunctionDef)}
    classes = {n.name: n for n in stub.body if isinstance(n, ast.ClassDef)}
    compiled = {name for name in dir(_dewall) if not name.startswith("_")}
    declared = set(functions) | set(classes) | {n.target.id for n in stub.body if isinstance(n, ast.AnnAssign)}
    assert {name for name in declared if not name.startswith("_")} == compiled
    for name, node in functions.items():
        assert _parameters(node) == _bound_parameters(getattr(_dewall, name)), name
    for node in classes["Triangulation"].body:
        if isinstance(node, ast.FunctionDef):
            member = inspect.getattr_static(_dewall.Triangulation, node.name)
            if not isinstance(member, property):
                assert _parameters(node) == _bound_parameters(getattr(_dewall.Triangulation, node.name)), node.name


def test_mypy_accepts_the_package_and_its_stubs(tmp_path):
    pytest.importorskip("mypy")  # Debian's python3-mypy (scripts/setup.sh)
    where = os.path.dirname(os.path.dirname(dewall.__file__))
    allowlist = os.path.join(os.path.dirname(os.path.abspath(__file__)), "stubtest_allowlist.txt")
    env = {**os.environ, "MYPYPATH": where}
    cache = ["--cache-dir", str(tmp_path / "cache")]  # not next to an installed package
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "dewall._dewall", "--allowlist", allowlist],
                         capture_output=True, text=True, env=env, cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    run = subprocess.run([sys.executable, "-m", "mypy", *cache, "-p", "dewall"], capture_output=True, text=True,
                         env=env, cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
