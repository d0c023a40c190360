"""Turning what users pass into the arrays the compiled module takes.

Coordinates: float64, C-contiguous, shape (n, d). Such an array is used as it
is (no copy). Anything else is converted once, and only when the conversion is
exact: other float widths up to 64 bits and integers whose values are doubles
exactly, also held in an object array (as scipy accepts them); a conversion that
would round (int64 beyond 2^53, long double) is refused rather than
triangulating other points than the user's.
"""

import numpy as np

# Kinds NumPy calls signed integer, unsigned integer, floating point.
_NUMBER_KINDS = "iuf"


def as_coordinates(values, what="points"):
    """`values` as a C-contiguous float64 array of shape (n, d), d >= 1.

    TypeError for a wrong dtype (not real numbers; a float wider than 64 bits)
    or shape (not 2-D); ValueError for integers that are not doubles exactly.
    """
    array = np.asarray(values)
    if array.dtype == object:
        array = _from_objects(array, what)
    if array.dtype.kind not in _NUMBER_KINDS or (array.dtype.kind == "f" and array.dtype.itemsize > 8):
        raise TypeError(f"{what} must be real numbers (float64, a narrower float or integers), not dtype {array.dtype}")
    if array.ndim != 2:
        raise TypeError(f"{what} must be a 2-D array of shape (n, d), not of shape {array.shape}")
    if array.dtype == np.float64:
        return np.ascontiguousarray(array)  # the same array when it is already C-contiguous
    converted = np.ascontiguousarray(array, dtype=np.float64)
    if array.dtype.kind in "iu" and array.dtype.itemsize > 4:  # 32-bit integers and floats convert exactly
        with np.errstate(invalid="ignore"):
            back = converted.astype(array.dtype)
        inexact = back != array
        if inexact.any():
            row, column = np.argwhere(inexact)[0]
            raise ValueError(f"{what}[{row}, {column}] = {array[row, column]} is not exactly a double (|x| > 2^53)")
    return converted


def _is_real_type(kind):
    """Whether objects of type `kind` convert to a double without losing their meaning: Python
    and NumPy floats (64 bits at most) and integers, not bools (refused in any array)."""
    if issubclass(kind, (bool, np.bool_)) or not issubclass(kind, (float, int, np.floating, np.integer)):
        return False
    return not issubclass(kind, np.floating) or np.dtype(kind).itemsize <= 8


def _from_objects(array, what):
    """An object array of real numbers as float64, exactly; TypeError for any other element,
    ValueError for an integer that is not a double exactly."""
    flat = array.ravel()
    for kind in set(map(type, flat)):
        if not _is_real_type(kind):
            raise TypeError(f"{what} must be real numbers (float64, a narrower float or integers), not dtype "
                            f"object holding {kind.__name__}")

    def inexact(i, x):
        where = ", ".join(map(str, np.unravel_index(i, array.shape)))
        return ValueError(f"{what}[{where}] = {x} is not exactly a double (|x| > 2^53)")

    try:
        converted = flat.astype(np.float64)
    except OverflowError:  # a Python int beyond the doubles' range: name it
        for i, x in enumerate(flat):
            try:
                float(x)
            except OverflowError:
                raise inexact(i, x) from None
        raise
    # only integers of 2^53 and more can round: compare those with the integer they came from
    for i in np.nonzero(~(np.abs(converted) < 2.0**53))[0]:
        x = flat[i]
        if isinstance(x, (int, np.integer)) and int(converted[i]) != int(x):
            raise inexact(i, x)
    return converted.reshape(array.shape)


def as_simplices(values, vertices, what="simplices"):
    """`values` as a C-contiguous uint32 array of shape (m, vertices), for the certifier.

    Any integer dtype. An index that is not a possible input index (negative,
    2^32 or more) becomes 2^32 - 1, which the certifier reports as out of range.
    """
    array = np.asarray(values)
    if array.dtype.kind not in "iu":
        raise TypeError(f"{what} must be integers, not dtype {array.dtype}")
    if array.ndim != 2 or array.shape[1] != vertices:
        raise TypeError(f"{what} must be a 2-D array of shape (m, {vertices}), not of shape {array.shape}")
    out_of_range = (array < 0) | (array >= 2**32 - 1)
    return np.ascontiguousarray(np.where(out_of_range, 2**32 - 1, array), dtype=np.uint32)
