"""Finds the compiled module dewall._dewall.

Installed (pip) or run from the build tree (PYTHONPATH=build/python), it sits
next to this file. Imported from the source tree (PYTHONPATH=python, or a
session started in python/), it does not: Python then used to fail with
"cannot import name '_dewall' from partially initialized module 'dewall' (most
likely due to a circular import)", which was misleading. Here we look for a
build of this checkout (build/python/dewall/, as scripts/build.sh makes it)
and add it to the package's search path; failing that, say how to build it.
"""

import importlib
import os

import dewall as _package

try:
    _dewall = importlib.import_module("dewall._dewall")
except ImportError as missing:
    _source = os.path.dirname(os.path.abspath(__file__))
    _build = os.path.join(os.path.dirname(os.path.dirname(_source)), "build", "python", "dewall")
    if not os.path.isdir(_build) or any(os.path.samefile(_build, p) for p in _package.__path__ if os.path.isdir(p)):
        raise ImportError(
            f"dewall's compiled module _dewall is not in {_source}: this is the source tree. Build it "
            "(scripts/build.sh dewall_python) and use PYTHONPATH=build/python, or pip install the "
            "package (see the README's Python section)") from missing
    _package.__path__.append(_build)
    _dewall = importlib.import_module("dewall._dewall")
