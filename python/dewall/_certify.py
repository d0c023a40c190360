"""dewall.certify: is a list of simplices the Delaunay triangulation of a point set?"""

from dataclasses import dataclass

from . import _dewall
from ._arrays import as_coordinates, as_simplices


@dataclass(frozen=True)
class Violation:
    """One broken rule and its witness. `rule` is a stable name (e.g. "not_locally_delaunay");
    `simplex`, `other_simplex` are rows of the simplex list, `face` the facet or ridge
    (sorted input indices), `point` the witness point's input index (None where unused)."""

    rule: str
    message: str
    fatal: bool
    simplex: object = None
    other_simplex: object = None
    face: tuple = ()
    point: object = None


class Certificate:
    """The certifier's verdict. True in a boolean context exactly when the check passed:
    a Delaunay triangulation, or with canonical=True the canonical one.

    delaunay:  every closed circumsphere empty (a Delaunay triangulation).
    canonical: and the one CGAL's perturbation picks (dewall's, CGAL's output).
    violation: the first violation that makes the check fail (None when it passes);
               its `point`, `face`, `simplex` are the witness.
    violations: all found (with all=True, every one; else the first fatal one and the
               first non-canonical facet).
    counts: points, distinct_points, simplices, interior_facets, boundary_facets,
            cospherical_facets.
    """

    def __init__(self, report, canonical):
        self.delaunay = report["delaunay"]
        self.canonical = report["canonical"]
        self.required = "canonical" if canonical else "delaunay"
        self.violations = [Violation(**v) for v in report["violations"]]
        self.counts = {key: report[key] for key in ("points", "distinct_points", "simplices", "interior_facets",
                                                    "boundary_facets", "cospherical_facets")}
        failing = [v for v in self.violations if v.fatal or canonical]
        self.violation = None if self else failing[0]

    def __bool__(self):
        return self.canonical if self.required == "canonical" else self.delaunay

    def __repr__(self):
        verdict = ("canonical Delaunay" if self.canonical else "Delaunay, not canonical" if self.delaunay
                   else "not Delaunay")
        detail = f": {self.violation.message}" if self.violation else ""
        return f"<dewall.Certificate {verdict} ({self.counts['simplices']} simplices){detail}>"


def certify(points, simplices, canonical=False, all=False):
    """Checks that `simplices` is a Delaunay triangulation of `points`, exactly.

    points: (n, d) array; simplices: (m, d + 1) integer array of input indices, any vertex
    and row order (dewall's, scipy.spatial.Delaunay(points).simplices, anybody's).
    canonical: require the canonical triangulation (CGAL's perturbation), not just any
    Delaunay one — on cospherical input there are many.
    all: list every violation instead of stopping at the first.

    Duplicate points: the first occurrence must be the vertex and later copies unused
    (CGAL's and dewall's convention; scipy may pick another copy). Returns a Certificate.
    """
    points = as_coordinates(points)
    rows = as_simplices(simplices, points.shape[1] + 1)
    return Certificate(_dewall.certify(points, rows, bool(all)), canonical)
