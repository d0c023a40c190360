#!/usr/bin/env python3
"""Checks ARCHITECTURE.md's include rules over the #include lines of the tree.

Usage: check_include_rules.py [ROOT]   (ROOT: the repository, default: this script's parent's parent)
Prints every include that breaks a rule and exits 1; exits 0 when there is none.
The rules are ARCHITECTURE.md's ("Layers"); a rule changed there is changed here.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]')

# Where CGAL may be included (outside tests/, fuzz/, bench/, examples/, which may include anything).
CGAL_ALLOWED = (
    "kernel/include/dewall/kernel/cgal_kernel_adapter.hpp",
    "certify/include/dewall/certify/cgal.hpp",  # dewall::cgal::certify, header-only
    "dewall/include/dewall/cgal/",
    "dewall/src/cgal_engine.cpp",
    "python/src/high_dimension.cpp",  # the dimension known at run time, CGAL's dD code
)
FREE = ("tests/", "fuzz/", "bench/", "examples/")


def ours(header):
    """The layer an include of ours names, or None for a third-party or standard header."""
    for layer in ("kernel", "certify", "io", "mpi", "cgal", "detail/walls", "detail/incremental", "detail/common"):
        if header.startswith(f"dewall/{layer}/"):
            return layer
    if header.startswith("dewall/detail/"):
        return "detail"
    if header.startswith("dewall/"):
        return "dewall"
    return None


def rules(path, header):
    """The rules `path` including `header` breaks (a list of strings)."""
    broken = []
    layer = ours(header)
    if header.startswith("CGAL/") and not path.startswith(CGAL_ALLOWED + FREE):
        broken.append("CGAL is included only where ARCHITECTURE.md allows it")
    if path.startswith("kernel/") and layer not in (None, "kernel"):
        broken.append("kernel/ includes only kernel/")
    if path.startswith("certify/") and layer not in (None, "kernel", "certify"):
        broken.append("certify/ includes only kernel/ and certify/")
    if path.startswith("io/") and layer not in (None, "io"):
        broken.append("io/ includes nothing else of ours")
    if path.startswith(("dewall/", "kernel/")) and (layer in ("io", "certify") or header.startswith("cli/")):
        broken.append("the algorithm knows nothing of I/O, the certifier or the CLI")
    detail = "dewall/include/dewall/detail/"
    if path.startswith(detail + "common/") and layer in ("detail/walls", "detail/incremental"):
        broken.append("detail/common/ includes neither engine")
    if path.startswith(detail + "walls/") and layer == "detail/incremental":
        broken.append("detail/walls/ does not include detail/incremental/")
    if path.startswith(detail + "incremental/") and layer == "detail/walls":
        broken.append("detail/incremental/ does not include detail/walls/")
    topology = ("walls/face.hpp", "walls/active_face_list.hpp", "walls/region.hpp", "incremental/cell_store.hpp",
                "incremental/star_gluing.hpp")
    if path.startswith(tuple(detail + t for t in topology)) and layer == "kernel":
        broken.append("topology knows no geometry: no kernel header")
    return broken


def main():
    failures = 0
    files = sorted(p for p in ROOT.rglob("*") if p.suffix in (".hpp", ".cpp", ".h") and p.is_file())
    checked = 0
    for p in files:
        rel = p.relative_to(ROOT).as_posix()
        if rel.startswith(("build", ".")) or "/build" in rel.split("/", 1)[0]:
            continue
        checked += 1
        for number, line in enumerate(p.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            for rule in rules(rel, m.group(1)):
                print(f"{rel}:{number}: #include <{m.group(1)}>: {rule}")
                failures += 1
    if checked < 50:
        print(f"only {checked} files under {ROOT}: is that the repository?")
        return 1
    print(f"{checked} files, {failures} includes against ARCHITECTURE.md's rules")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
