"""dewall's exceptions, and how code written for scipy.spatial catches them.

    ValueError
    └── InvalidInput            (dewall._dewall, from the library) every input the library refuses
        └── DegenerateInput     too few distinct points, points that do not span E^d
    ValueError
    └── InvalidOption           a qhull_options token dewall refuses

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
    from scipy.spatial import QhullError
except ImportError:  # scipy is optional

    class QhullError(RuntimeError):
        """Stands for scipy.spatial.QhullError when scipy is not installed."""


class DegenerateInput(InvalidInput, QhullError):
    """The points cannot be triangulated: fewer than d + 1 distinct points, or they do not span E^d.
    A ValueError (dewall.InvalidInput) and a QhullError, as scipy raises for the same input."""


class InvalidOption(ValueError, QhullError):
    """A qhull_options token that would change the answer, or that is not a Qhull option."""


# The library's messages for the conditions scipy reports as QhullError (dewall/detail/input.hpp).
_DEGENERATE_PREFIXES = ("need at least ", "the points do not span ")


def translated(error):
    """The exception to raise for the library's InvalidInput `error`: DegenerateInput for the
    conditions above (keeping the message and `.point`), `error` itself otherwise."""
    if not str(error).startswith(_DEGENERATE_PREFIXES):
        return error
    better = DegenerateInput(str(error))
    better.point = getattr(error, "point", None)
    return better
