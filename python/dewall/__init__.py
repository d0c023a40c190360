"""Exact Delaunay triangulations in E^2 … E^6, with scipy.spatial.Delaunay's interface.

    >>> import dewall
    >>> tri = dewall.Delaunay(points)            # as scipy.spatial.Delaunay(points)
    >>> tri.simplices, tri.neighbors, tri.transform, tri.find_simplex(xi)
    >>> dewall.interpolate.griddata(points, values, xi)   # as scipy.interpolate.griddata
    >>> dewall.certify(points, tri.simplices)    # also on scipy's own output

Every geometric decision is the sign of an exact determinant, and degenerate
input (grids, cospherical points, duplicates) is resolved by CGAL's symbolic
perturbation: the simplices are CGAL's, on every input. See the README's
Python section.
"""

from ._compiled import _dewall  # noqa: F401  (first: it finds the compiled module, or says how to build it)
from ._certify import Certificate, Violation, certify
from ._delaunay import Delaunay, tsearch
from ._errors import DegenerateInput, InvalidInput, InvalidOption, InvalidShape, QhullError
from ._generate import KINDS, generate
from ._hull import ConvexHull, Voronoi
from . import interpolate

__all__ = ["Delaunay", "ConvexHull", "Voronoi", "tsearch", "interpolate", "certify", "Certificate", "Violation",
           "generate", "KINDS", "InvalidInput", "DegenerateInput", "InvalidOption", "InvalidShape",
           "QhullError"]
__version__ = "0.1.0"
