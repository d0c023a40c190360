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
    again = pickle.loads(pickle.dumps(nearest))  # as scipy's own: picklable
    assert repr(again) == repr(nearest)
    np.testing.assert_array_equal(again(points[:5]), nearest(points[:5]))


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


def test_mypy_stubtest_agrees_with_the_module(tmp_path):
    pytest.importorskip("mypy")  # Debian's python3-mypy (scripts/setup.sh)
    where = os.path.dirname(os.path.dirname(dewall.__file__))
    allowlist = os.path.join(os.path.dirname(os.path.abspath(__file__)), "stubtest_allowlist.txt")
    env = dict(os.environ)
    if os.path.basename(where) not in ("site-packages", "dist-packages"):  # installed: found as PEP 561 says
        env["MYPYPATH"] = where
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "dewall._dewall", "--allowlist", allowlist],
                         capture_output=True, text=True, env=env, cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr


# ---- Voronoi's ridges and regions, ConvexHull's equations: compiled, not a Python loop ----------


def _python_calls(function):
    """How many Python functions and builtins `function()` calls (sys.setprofile's events)."""
    count = 0

    def profile(frame, event, arg):
        nonlocal count
        count += event in ("call", "c_call")

    sys.setprofile(profile)
    try:
        function()
    finally:
        sys.setprofile(None)
    return count


@pytest.mark.parametrize("d", [2, 3, 4])
@pytest.mark.parametrize("kind", ["uniform", "grid"])  # a grid: cospherical simplices, merged
def test_voronoi_python_work_does_not_grow_with_the_points(d, kind):
    small, large = (dewall.generate(kind, n, dim=d, seed=3) for n in (300, 3000))
    calls = [_python_calls(lambda: dewall.Voronoi(points)) for points in (small, large)]
    assert calls[1] < calls[0] + 100, calls


def _reference_ridges(vor, tri, group):
    """Each Delaunay edge's Voronoi vertices as a set (-1 for a hull edge), from the definition."""
    d = tri.ndim
    around = {}
    for s, simplex in enumerate(tri.simplices.tolist()):
        for i in range(d + 1):
            for j in range(i + 1, d + 1):
                around.setdefault(tuple(sorted((simplex[i], simplex[j]))), set()).add(int(group[s]))
    for facet in tri.convex_hull.tolist():
        for i in range(d):
            for j in range(i + 1, d):
                around[tuple(sorted((facet[i], facet[j])))].add(-1)
    return {edge: vertices for edge, vertices in around.items() if len(vertices) >= d}


@pytest.mark.parametrize("d, kind", [(2, "uniform"), (2, "grid"), (3, "uniform"), (3, "grid"), (4, "uniform"),
                                     (4, "grid")])
def test_voronoi_ridges_and_regions_from_the_definition(d, kind):
    n = {2: 400, 3: 343, 4: 81}[d]
    points = dewall.generate(kind, n, dim=d, seed=5)
    vor = dewall.Voronoi(points)
    tri = dewall.Delaunay(points)
    # the Voronoi vertex of each simplex: its circumcentre, shared by cospherical neighbours
    centres = np.array([np.linalg.solve(2 * (v[1:] - v[0]), (v[1:] ** 2).sum(1) - (v[0] ** 2).sum())
                        for v in points[tri.simplices]])
    group = np.argmin(np.linalg.norm(centres[:, None, :] - vor.vertices[None, :, :], axis=2), axis=1)
    np.testing.assert_allclose(vor.vertices[group], centres, atol=1e-9)
    expected = _reference_ridges(vor, tri, group)
    ours = {tuple(map(int, pq)): v for pq, v in zip(vor.ridge_points, vor.ridge_vertices)}
    assert set(ours) == set(expected)
    # Voronoi edges: the circumcentres of simplices across a facet, when they differ
    simplex, _ = np.nonzero(tri.neighbors >= 0)
    across = tri.neighbors[tri.neighbors >= 0]
    adjacent = {frozenset(pair) for pair in zip(group[simplex].tolist(), group[across].tolist()) if pair[0] != pair[1]}

    def in_order(cycle, closed):  # consecutive vertices joined by a Voronoi edge
        pairs = list(zip(cycle, cycle[1:] + cycle[:1] if closed else cycle[1:]))
        return len(cycle) < 2 or all(frozenset(pair) in adjacent for pair in pairs)

    for edge, vertices in ours.items():
        assert set(vertices) == expected[edge] and len(vertices) == len(set(vertices)), edge
        if d == 3:  # a polygon around the edge, -1 first when unbounded
            assert in_order(vertices[1:], False) if vertices[0] == -1 else in_order(vertices, True), edge
    hull_points = set(tri.convex_hull.ravel().tolist())
    for point, region in enumerate(vor.point_region):
        vertices = vor.regions[region]
        expected_region = set(group[np.nonzero((tri.simplices == point).any(axis=1))[0]].tolist())
        assert set(vertices) == expected_region | ({-1} if point in hull_points else set()), point
        if d == 2:  # a polygon around the point, -1 last when unbounded
            assert in_order(vertices[:-1], False) if vertices[-1] == -1 else in_order(vertices, True), point


def test_hull_equations_from_quickhull_without_lapack(monkeypatch):
    """5-D: the facets' normals come with Quickhull's facets (no batched LAPACK determinant per
    facet), and Voronoi's circumcentres from the module; the equations equal scipy's."""
    scipy_spatial = pytest.importorskip("scipy.spatial")
    points = np.random.default_rng(8).random((1500, 5))
    theirs = scipy_spatial.ConvexHull(points)

    def refuse(*args, **kwargs):
        raise AssertionError("np.linalg called per facet")

    monkeypatch.setattr(np.linalg, "det", refuse)
    monkeypatch.setattr(np.linalg, "solve", refuse)
    hull = dewall.ConvexHull(points)
    voronoi = dewall.Voronoi(points[:300, :3])  # circumcentres: the compiled module's too
    monkeypatch.undo()
    assert len(voronoi.vertices) > 0
    mine = {tuple(sorted(f)): e for f, e in zip(hull.simplices.tolist(), hull.equations)}
    other = {tuple(sorted(f)): e for f, e in zip(theirs.simplices.tolist(), theirs.equations)}
    assert set(mine) == set(other)
    for facet, equation in mine.items():
        np.testing.assert_allclose(equation, other[facet], atol=1e-12)
    assert hull.volume == pytest.approx(theirs.volume, rel=1e-12) and hull.area == pytest.approx(theirs.area, rel=1e-12)
