"""dewall.generate: the library's seeded point generators (as `dewall generate`)."""

import secrets

from . import _dewall

KINDS = _dewall.point_kinds  # the library's names: ("uniform", "ball", …)


def generate(kind, n, dim=3, seed=None):
    """A point set of `kind` in E^dim as a float64 array of shape (about n, dim).

    kind: one of KINDS (see `dewall generate --help`): uniform (unit cube),
    ball, sphere, bubbles (the DeWall paper's clusters), grid (integer lattice,
    about n points), lattice-sphere (integer points on one sphere, about n,
    exactly cospherical), planes, torus, scan (a simulated range scan), depth
    (a depth-camera frame), lidar (an airborne laser scan in UTM coordinates),
    indoor (a scan with every point 2-4 times); the last four 3D only.
    The same seed gives the same points as
    `dewall generate KIND N --dim DIM --seed SEED`. seed=None draws one at
    random; pass a seed to reproduce a set.
    """
    if seed is None:
        seed = secrets.randbits(64)
    if not 0 <= seed < 2**64:
        raise ValueError(f"seed must be an integer from 0 to 2^64 - 1, not {seed}")
    if n < 0:
        raise ValueError(f"n must be a non-negative count, not {n}")
    return _dewall.generate(str(kind), int(n), int(dim), int(seed))
