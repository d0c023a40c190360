"""Runs scipy's own Qhull tests (scipy/spatial/tests/test_qhull.py, the installed scipy's) against
dewall: scipy.spatial's Delaunay, ConvexHull, Voronoi and tsearch are replaced by dewall's before the
test module is imported. HalfspaceIntersection (no dewall counterpart) is left out.

    PYTHONPATH=build/python /usr/bin/python3 python/tools/run_scipy_qhull_tests.py [pytest options]

The README's Python section lists the cases that fail and why (with scipy 1.10.1: 152 of 173 pass).
Not part of the pytest suite: it takes scipy's test run time, and its failures are known.
"""

import os
import sys

import pytest


class ReplaceQhull:
    """pytest plugin: the replacement happens at configure time, before collection imports the tests."""

    def pytest_configure(self, config):
        import scipy.spatial
        import scipy.spatial._qhull as qhull

        import dewall

        for name in ("Delaunay", "ConvexHull", "Voronoi", "tsearch"):
            setattr(qhull, name, getattr(dewall, name))
            setattr(scipy.spatial, name, getattr(dewall, name))


def main():
    import scipy.spatial.tests

    path = os.path.join(os.path.dirname(scipy.spatial.tests.__file__), "test_qhull.py")
    args = [path, "-q", "-p", "no:cacheprovider", "-k", "not HalfspaceIntersection", "-rf"] + sys.argv[1:]
    return pytest.main(args, plugins=[ReplaceQhull()])


if __name__ == "__main__":
    sys.exit(main())
