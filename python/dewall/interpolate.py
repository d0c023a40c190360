"""dewall.interpolate: scipy.interpolate's triangulation-based interpolators over the exact triangulation.

    LinearNDInterpolator(points_or_tri, values, fill_value=nan, rescale=False)
    CloughTocher2DInterpolator(points_or_tri, values, fill_value=nan, tol=1e-6, maxiter=400, rescale=False)
    NearestNDInterpolator(x, y, rescale=False, tree_options=None)
    griddata(points, values, xi, method="linear", fill_value=nan, rescale=False)

Signatures and results as scipy.interpolate's. Linear: dewall's own — the
simplex of each query from find_simplex (exact, then scipy's 100 eps tolerance
outside the hull), the weights from `transform` as scipy computes them, so the
values equal scipy's to rounding on the same triangulation; and every query
inside the hull gets a value, from a proper simplex, also on grids and ties
where Qhull's triangulation has flat simplices.

Cubic (CloughTocher2DInterpolator, griddata(method="cubic")) and nearest are
scipy's own code, so they need scipy: Clough-Tocher gets dewall's triangulation
handed over as a scipy.spatial.Delaunay (as_scipy_delaunay), so its gradients
and patches are built on the exact triangulation, while scipy's code locates
the queries in it (its tolerant walk). Nearest does not triangulate (a k-d
tree): scipy's NearestNDInterpolator as it is. griddata on 1-D data is scipy's.
"""

import numpy as np

from ._delaunay import Delaunay, barycentric

__all__ = ["LinearNDInterpolator", "CloughTocher2DInterpolator", "NearestNDInterpolator", "griddata",
           "as_scipy_delaunay"]


def _coordinates(args, ndim):
    """Query points as scipy's interpolators take them: one array (..., ndim), or ndim arrays
    broadcast together (x, y, …), or a tuple of them; a 1-D array is one row per ndim values."""
    if isinstance(args, tuple) and len(args) == 1:
        args = args[0]
    if isinstance(args, tuple):
        arrays = np.broadcast_arrays(*args)
        xi = np.empty(arrays[0].shape + (len(arrays),), dtype=np.float64)
        for j, a in enumerate(arrays):
            xi[..., j] = a
        return xi
    xi = np.asanyarray(args)
    if xi.ndim == 1:
        xi = xi.reshape(-1, 1) if ndim is None else xi.reshape(-1, ndim)
    return xi


def _rescaling(points):
    """scipy's rescale=True: the offset (mean) and scale (peak to peak after the offset, 1 where 0)."""
    offset = np.mean(points, axis=0)
    scale = np.ptp(points - offset, axis=0)
    scale[~(scale > 0)] = 1.0
    return offset, scale


def _repr(self):
    """Like dewall.Delaunay's: the points, the simplices when there are any, the values' shape."""
    n, d = self.points.shape
    parts = [f"{n} points in E^{d}"]
    nsimplex = getattr(getattr(self, "tri", None), "nsimplex", None)
    if nsimplex is not None:
        parts.append(f"{nsimplex} simplices")
    shape = (n,) + tuple(self.values_shape) if hasattr(self, "values_shape") else np.shape(self.values)
    parts.append(f"values of shape {shape}")
    return f"<dewall.interpolate.{type(self).__name__}: {', '.join(parts)}>"


class _Interpolator:
    """What the interpolators share: the triangulation (built or given), values, rescaling, calling."""

    def __init__(self, points, values, fill_value=np.nan, rescale=False, *, progress=None):
        if isinstance(points, Delaunay):
            if rescale:
                raise ValueError("Rescaling is not supported when passing a Delaunay triangulation as ``points``.")
            self.tri = points
            points = points.points
        else:
            self.tri = None
            points = _coordinates(points, None)
            if isinstance(points, np.ma.MaskedArray):
                raise ValueError("Input points cannot be a masked array")
            points = np.ascontiguousarray(points, dtype=np.float64)
            if points.ndim != 2:
                raise ValueError("invalid shape for input data points")
        if rescale:
            self.offset, self.scale = _rescaling(points)
            points = (points - self.offset) / self.scale
        else:
            self.offset = self.scale = None
        self.points = points
        values = np.asarray(values)
        if values.shape[:1] != (points.shape[0],):
            raise ValueError("different number of values and points")
        self.values_shape = values.shape[1:]
        dtype = np.complex128 if np.iscomplexobj(values) else np.float64
        self.values = np.ascontiguousarray(values.reshape(values.shape[0], -1), dtype=dtype)
        self.fill_value = fill_value
        if self.tri is None:
            self.tri = Delaunay(self.points, progress=progress)

    __repr__ = _repr

    def __call__(self, *args):
        ndim = self.points.shape[1]
        xi = _coordinates(args, ndim)
        if xi.shape[-1] != ndim:
            raise ValueError("number of dimensions in xi does not match x")
        shape = xi.shape
        flat = np.ascontiguousarray(xi.reshape(-1, ndim), dtype=np.float64)
        if self.offset is not None:
            flat = (flat - self.offset) / self.scale
        out = self._evaluate(flat)
        return out.reshape(shape[:-1] + self.values_shape)


_WITH_REPR = {}


def _with_repr(base):
    """scipy's interpolator class `base`, subclassed once for dewall's repr: what this module
    returns stays an instance of scipy's class, for code that checks. Pickle finds the subclass
    as this module's _<name> (__getattr__ below), whose own name is taken by a function."""
    if base not in _WITH_REPR:
        _WITH_REPR[base] = type(base.__name__, (base,), {"__repr__": _repr, "__module__": __name__,
                                                         "__qualname__": "_" + base.__name__, "__doc__": base.__doc__})
    return _WITH_REPR[base]


def __getattr__(name):
    """_NearestNDInterpolator and _CloughTocher2DInterpolator, made on first use (they need scipy)."""
    if name in ("_NearestNDInterpolator", "_CloughTocher2DInterpolator"):
        import scipy.interpolate  # type: ignore[import]

        return _with_repr(getattr(scipy.interpolate, name[1:]))
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class LinearNDInterpolator(_Interpolator):
    """Piecewise linear interpolation on the exact Delaunay triangulation, scipy.interpolate's interface.

    LinearNDInterpolator(points, values, fill_value=np.nan, rescale=False, *, progress=None)

    points: (npoints, ndim) coordinates, or a dewall.Delaunay (then rescale must be False).
    values: (npoints, ...) real or complex values. fill_value: for queries outside the hull.
    rescale: as scipy, triangulate the points shifted to their mean and scaled to unit extent.
    progress (keyword only, dewall's): as dewall.Delaunay's, for the triangulation.
    Calling: interp(xi) with xi of shape (..., ndim), or interp(x, y, …) broadcast together;
    the result has shape xi.shape[:-1] + values.shape[1:].

    Each query's simplex comes from Delaunay.find_simplex (exact, then scipy's default
    tolerance, 100 eps in barycentric coordinates, for queries just outside the hull), its
    weights from Delaunay.transform. Where that transform is NaN (a sliver too thin for
    floating point, never flat) the weights are solved directly, so inside the hull every
    query gets a finite value.
    """

    def _evaluate(self, xi):
        tri = self.tri
        simplex, weights = tri._simplices_and_weights(xi)
        inside = np.nonzero(simplex >= 0)[0]
        out = np.empty((xi.shape[0], self.values.shape[1]), dtype=self.values.dtype)
        out[...] = self.fill_value
        if inside.size == 0:
            return out
        rows = simplex[inside]
        weights = weights[inside]
        flat = np.nonzero(np.isnan(weights[:, 0]))[0]
        if flat.size:
            weights[flat] = _weights_directly(tri.points[tri.simplices[rows[flat]]], xi[inside[flat]])
        # sum over the vertices, one at a time: the order of scipy's loop, and no (q, d + 1, k) temporary
        vertices = tri.simplices[rows]
        total = weights[:, :1] * self.values[vertices[:, 0]]
        for j in range(1, vertices.shape[1]):
            total += weights[:, j:j + 1] * self.values[vertices[:, j]]
        out[inside] = total
        return out


def _weights_directly(vertices, x):
    """Barycentric coordinates of x (q, d) in simplices (q, d + 1, d) by solving [v^T; 1] c = [x; 1]."""
    q, n, d = vertices.shape
    system = np.ones((q, n, n))
    system[:, :d, :] = np.swapaxes(vertices, 1, 2)
    rhs = np.concatenate((x, np.ones((q, 1))), axis=1)
    return np.linalg.solve(system, rhs[:, :, None])[:, :, 0]


def as_scipy_delaunay(tri):
    """dewall's triangulation `tri` as a scipy.spatial.Delaunay instance, for code that accepts
    only that type (scipy.interpolate's interpolators check isinstance):

        scipy.interpolate.LinearNDInterpolator(as_scipy_delaunay(tri), values)

    Every attribute scipy's code reads (simplices, neighbors, equations, transform,
    paraboloid_*, bounds, vertex_to_simplex, vertex_neighbor_vertices, …) is dewall's, copied
    writable (scipy's Cython code takes writable buffers); no Qhull run. Its methods
    (find_simplex, …) are scipy's, running on dewall's simplices. Needs scipy."""
    from scipy.spatial import Delaunay as ScipyDelaunay  # type: ignore[import]

    class DewallAsScipy(ScipyDelaunay):
        points = property(lambda self: self._points)
        transform = property(lambda self: self._transform)
        vertex_to_simplex = property(lambda self: self._vertex_to_simplex)
        vertex_neighbor_vertices = property(lambda self: self._vertex_neighbor_vertices)
        convex_hull = property(lambda self: self._convex_hull)

        def __init__(self):  # never called: instances come from object.__new__ below
            raise TypeError("use dewall.interpolate.as_scipy_delaunay")

    view = object.__new__(DewallAsScipy)
    view._qhull = None
    view._points = np.array(tri.points)
    view._transform = np.array(tri.transform)
    view._vertex_to_simplex = np.array(tri.vertex_to_simplex)
    view._vertex_neighbor_vertices = tuple(np.array(a) for a in tri.vertex_neighbor_vertices)
    view._convex_hull = np.array(tri.convex_hull)
    for name in ("simplices", "neighbors", "equations", "coplanar", "min_bound", "max_bound"):
        setattr(view, name, np.array(getattr(tri, name)))
    view.ndim, view.npoints, view.nsimplex = tri.ndim, tri.npoints, tri.nsimplex
    view.paraboloid_scale, view.paraboloid_shift = tri.paraboloid_scale, tri.paraboloid_shift
    view.furthest_site, view.good = False, None
    return view


def CloughTocher2DInterpolator(points, values, fill_value=np.nan, tol=1e-6, maxiter=400, rescale=False, *,
                               progress=None):
    """scipy.interpolate.CloughTocher2DInterpolator on dewall's exact triangulation (2-D only).

    Same signature and result type as scipy's (it is scipy's object): the triangulation is
    dewall's, handed to scipy as a scipy.spatial.Delaunay; gradients, patches and the
    location of queries (scipy's walk, with its tolerance) are scipy's code. Needs scipy.
    progress (keyword only, dewall's): as dewall.Delaunay's, for the triangulation.
    """
    from scipy.interpolate import CloughTocher2DInterpolator  # type: ignore[import]

    ScipyCloughTocher = _with_repr(CloughTocher2DInterpolator)

    if isinstance(points, Delaunay):
        if rescale:
            raise ValueError("Rescaling is not supported when passing a Delaunay triangulation as ``points``.")
        tri = points
    else:
        points = np.ascontiguousarray(_coordinates(points, None), dtype=np.float64)
        if rescale:  # scipy rescales before triangulating: triangulate the same rescaled points
            offset, scale = _rescaling(points)
            tri = Delaunay((points - offset) / scale, progress=progress)
            interpolator = ScipyCloughTocher(as_scipy_delaunay(tri), values, fill_value=fill_value, tol=tol,
                                             maxiter=maxiter)
            interpolator.offset, interpolator.scale = offset, scale
            interpolator.rescale = True
            return interpolator
        tri = Delaunay(points, progress=progress)
    if tri.ndim != 2:
        raise ValueError(f"CloughTocher2DInterpolator is 2-D only, not {tri.ndim}-D")
    return ScipyCloughTocher(as_scipy_delaunay(tri), values, fill_value=fill_value, tol=tol, maxiter=maxiter)


def NearestNDInterpolator(x, y, rescale=False, tree_options=None):
    """scipy.interpolate.NearestNDInterpolator itself (a k-d tree, no triangulation). Needs scipy."""
    from scipy.interpolate import NearestNDInterpolator as ScipyNearest

    return _with_repr(ScipyNearest)(x, y, rescale=rescale, tree_options=tree_options)


def griddata(points, values, xi, method="linear", fill_value=np.nan, rescale=False):
    """scipy.interpolate.griddata with dewall's triangulation: method "linear" (dewall's
    LinearNDInterpolator), "cubic" (2-D: CloughTocher2DInterpolator above) or "nearest"
    (scipy's). 1-D data is handed to scipy.interpolate.griddata."""
    points = _coordinates(points, None)
    ndim = points.ndim if points.ndim < 2 else points.shape[-1]
    if ndim == 1:
        from scipy.interpolate import griddata as scipy_griddata

        return scipy_griddata(points, values, xi, method=method, fill_value=fill_value, rescale=rescale)
    # xi goes to the interpolator as given: a tuple (x, y) keeps the shape of its arrays, as scipy's
    if method == "nearest":
        return NearestNDInterpolator(points, values, rescale=rescale)(xi)
    if method == "linear":
        return LinearNDInterpolator(points, values, fill_value=fill_value, rescale=rescale)(xi)
    if method == "cubic" and ndim == 2:
        return CloughTocher2DInterpolator(points, values, fill_value=fill_value, rescale=rescale)(xi)
    raise ValueError(f"Unknown interpolation method {method!r} for {ndim} dimensional data")
