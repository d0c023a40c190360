"""dewall's exceptions, and how code written for scipy.spatial catches them.

    ValueError
    └── InvalidInput            (dewall._dewall, from the library) every input the library refuses
        └── DegenerateInput     too few distinct points, points that do not span E^d
    ValueError
    └── InvalidOption           a qhull_options token dewall refuses
    ValueError, TypeError
    └── InvalidShape            a query array of the wrong shape (find_simplex's xi)

DegenerateInput and InvalidOption also subclass `QhullError`: scipy's
`scipy.spatial.QhullError` when scipy is importable (scipy raises it for the
same two conditions: Qhull's "not enough points", "initial simplex is flat" and
"unknown option"), else a RuntimeError subclass of our own under that name. So
`except scipy.spatial.QhullError`, `except ValueError` and
`except dewall.InvalidInput` all catch what they caught before. A NaN or
infinite coordinate is InvalidInput alone: scipy raises a plain ValueError there.
"""

from ._dewall import InvalidInput

try:
    from scipy.spatial import QhullError  # type: ignore[import]
except ImportError:  # scipy is optional

    class QhullError(RuntimeError):  # type: ignore[no-redef]
        """Stands for scipy.spatial.QhullError when scipy is not installed."""


class DegenerateInput(InvalidInput, QhullError):
    """The points cannot be triangulated: fewer than d + 1 distinct points, or they do not span E^d.
    A ValueError (dewall.InvalidInput) and a QhullError, as scipy raises for the same input."""


class InvalidOption(ValueError, QhullError):
    """A qhull_options token that would change the answer, or that is not a Qhull option."""


class InvalidShape(ValueError, TypeError):
    """A query array of the wrong shape: a ValueError, as scipy raises ("wrong dimensionality in
    xi"), and a TypeError, as dewall raises for the points' shape."""


# Tracebacks and reprs name the classes where users import them (dewall.InvalidInput), not the
# private modules that define them; pickle finds them there too.
for _public in (InvalidInput, DegenerateInput, InvalidOption, InvalidShape):
    _public.__module__ = "dewall"
if QhullError.__module__ == __name__:
    QhullError.__module__ = "dewall"

# The library's messages for the conditions scipy reports as QhullError (dewall/detail/common/input.hpp).
_DEGENERATE_PREFIXES = ("need at least ", "the points do not span ")


def translated(error):
    """The exception to raise for the library's InvalidInput `error`: DegenerateInput for the
    conditions above (keeping the message and `.point`), `error` itself otherwise."""
    if not str(error).startswith(_DEGENERATE_PREFIXES):
        return error
    better = DegenerateInput(str(error))
    better.point = getattr(error, "point", None)
    return better
