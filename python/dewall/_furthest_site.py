"""The furthest-site Delaunay triangulation, exactly (cospherical ties by the library's perturbation).

Its simplices are the upper hull of the points lifted to the paraboloid: the
simplices whose circumsphere contains every point. Only hull vertices take part
(a sphere containing them contains their convex hull), so the construction
works on those: gift wrapping (as for the Delaunay triangulation, with the
sphere test reversed), every decision an exact predicate of the library
(_dewall.predicate_signs: orientation, unperturbed in-sphere).

1. Start from a hull facet that is a whole face of the hull on extreme points:
   its neighbour inside is the first simplex. Without one (flat facets with 4 or
   more corners: a cube, a tesseract, a grid), walk to the simplex above a fixed
   interior point q (_walk_to_first_simplex).
2. Pivot across a ridge R: among the hull vertices strictly beyond R (opposite
   the simplex's apex), the spheres through R form a pencil, nested on that
   side; take any candidate b, and while some candidate lies outside the sphere
   through R + b, move b to it. The last sphere contains every candidate; it
   contains the points on the apex side because the sphere of the simplex we
   came from contains them and, on that side, the new sphere lies inside it.
3. Repeat for every ridge not yet matched (breadth first); a ridge with no
   candidate is a hull facet.

Cost: O(h) exact tests per pivot step, for h hull vertices; a few steps per
ridge on general input, up to O(h) on cospherical input. Meant for the hull
sizes of ordinary inputs (tens to thousands of hull vertices), not for 10^5
points on one sphere.

Cospherical hull vertices (a square's corners, points on a circle) make the
triangulation ambiguous; the pivot then uses the library's perturbed sphere
test (CGAL's symbolic perturbation of the lifted points, the one the Delaunay
triangulation uses), whose upper hull is unique, so the answer is one
consistent triangulation, each circumsphere still containing every point (checked
with the unperturbed test at the end, and the volumes against the hull's). Points
inside hull edges and faces are never vertices (a point inside a face is a convex
combination of its corners, so its lift lies strictly below theirs): in 2-D and
3-D they are set aside first (_boundary); in 4-D and up they stay among the
candidates, which is harmless (a sphere through such a point cannot contain the
corners around it) and only costs tests.
"""

from collections import deque

import numpy as np

from . import _dewall

_FAILED = "dewall: the furthest-site construction failed its check (a bug: please report)"


def furthest_site_simplices(points, hull_facets, whole=None):
    """The furthest-site Delaunay simplices (int32, each positively oriented) of `points`, whose
    convex hull facets are `hull_facets` (rows of d point indices: a triangulation of the hull's
    boundary). `whole`, when given, marks the facets that are whole faces of the hull on extreme
    points (_boundary): the construction then starts from one of them; without one it walks."""
    d = points.shape[1]
    vertices = np.unique(hull_facets).astype(np.uint32)

    def signs(rows, kind):
        return _dewall.predicate_signs(points, np.ascontiguousarray(rows, dtype=np.uint32), kind)

    def orientation(rows):
        return signs(rows, 0)

    def positive(simplex):
        simplex = list(simplex)
        if orientation([simplex])[0] < 0:
            simplex[0], simplex[1] = simplex[1], simplex[0]
        return simplex

    def pivot(ridge, apex_side):
        """The vertex completing `ridge` beyond it (the side of sign -apex_side), or None."""
        others = vertices[~np.isin(vertices, ridge)]
        sides = orientation(np.column_stack([np.tile(ridge, (others.size, 1)), others]))
        candidates = others[sides == -apex_side]  # those in the ridge's hyperplane cannot complete it
        if candidates.size == 0:
            return None
        best = candidates[0]
        while True:
            simplex = positive(list(ridge) + [best])
            rest = candidates[candidates != best]
            if rest.size == 0:
                return best
            outside = rest[signs(np.column_stack([np.tile(simplex, (rest.size, 1)), rest]), 2) < 0]
            if outside.size == 0:
                return best
            best = outside[0]

    def inward(ridge):
        """The simplex beyond `ridge`, a triangle in a hull facet's hyperplane, on the hull's side."""
        side = orientation(np.column_stack([np.tile(ridge, (vertices.size, 1)), vertices]))
        inner = int(side[side != 0][0])  # every hull vertex is on one side of a hull facet
        return tuple(sorted(list(ridge) + [int(pivot(list(ridge), -inner))]))

    if whole is not None and whole.any():  # a whole hull face is a face of every triangulation of the hull vertices
        first = inward([int(v) for v in hull_facets[int(np.argmax(whole))]])
    else:
        first = _walk_to_first_simplex(points, hull_facets, vertices, positive)
    simplices = {first}
    queue = deque(simplices)
    matched = set()
    while queue:
        simplex = queue.popleft()
        for j in range(d + 1):
            ridge = simplex[:j] + simplex[j + 1:]
            if ridge in matched:
                continue
            matched.add(ridge)
            apex = simplex[j]
            apex_side = int(orientation([list(ridge) + [apex]])[0])
            found = pivot(list(ridge), apex_side)
            if found is None:
                continue
            neighbour = tuple(sorted(ridge + (int(found),)))
            if neighbour not in simplices:
                simplices.add(neighbour)
                queue.append(neighbour)
    result = np.array([positive(s) for s in sorted(simplices)], dtype=np.int32).reshape(-1, d + 1)
    # They tile the hull: their volumes add up to its volume (floating point, a safety net).
    corners = points[result]
    volume = np.abs(np.linalg.det(corners[:, 1:] - corners[:, :1])).sum()
    hull_volume = _hull_volume(points, hull_facets, vertices)
    if not abs(volume - hull_volume) <= 1e-9 * hull_volume:
        raise RuntimeError(_FAILED)
    # The defining property, unperturbed: every circumsphere contains every hull vertex (inside or on).
    for simplex in result:
        others = vertices[~np.isin(vertices, simplex)]
        if (signs(np.column_stack([np.tile(simplex, (others.size, 1)), others]), 1) < 0).any():
            raise RuntimeError(_FAILED)
    return result


def _walk_to_first_simplex(points, hull_facets, vertices, positive):
    """A first furthest-site simplex without a whole hull face to start from: the one above a
    fixed point q inside the hull, found as the simplex method would. Lifted to the paraboloid,
    a simplex S of hull vertices spans a hyperplane h_S; a vertex v outside S's (perturbed)
    sphere lies above it. Replacing the vertex of S for which the new simplex S' still contains
    q raises the height at q by λ'_v (|v|² − h_S(v)) > 0 (λ'_v: q's weight on v in S', positive
    while q is in no hyperplane of d input points), so no simplex repeats, and the walk ends at
    a simplex whose sphere contains every vertex: one of the triangulation (it is unique under
    the perturbation). q: a weighted mean of a first simplex with unequal weights, appended to
    a copy of the points so that the exact orientation can place it."""
    d = points.shape[1]
    facet = [int(v) for v in hull_facets[0]]  # hull facets from Quickhull or the Delaunay boundary: never flat
    lifted = np.vstack([points, np.zeros((1, d))])
    q = len(points)

    def signs(rows, kind):
        return _dewall.predicate_signs(lifted, np.ascontiguousarray(rows, dtype=np.uint32), kind)

    others = vertices[~np.isin(vertices, facet)]
    off = others[signs(np.column_stack([np.tile(facet, (others.size, 1)), others]), 0) != 0]
    simplex = positive(facet + [int(off[0])])
    weights = 1 + np.sqrt(np.arange(2, d + 3)) / 7  # unequal, so that q is unlikely on a hyperplane of d points
    lifted[q] = weights @ points[simplex] / weights.sum()
    for _ in range(100 * vertices.size + 1000):  # a cap, in case q lies in such a hyperplane after all
        rest = vertices[~np.isin(vertices, simplex)]
        outside = rest[signs(np.column_stack([np.tile(simplex, (rest.size, 1)), rest]), 2) < 0]
        if outside.size == 0:
            return tuple(sorted(simplex))
        v = int(outside[0])
        # the vertex to replace: q in the new simplex (closed), every sub-simplex with q non-negative
        for i in range(d + 1):
            new = positive(simplex[:i] + [v] + simplex[i + 1:])
            if signs([new], 0)[0] == 0:
                continue
            inside = signs([new[:j] + [q] + new[j + 1:] for j in range(d + 1)], 0)
            if (inside >= 0).all():
                simplex = new
                break
        else:
            break
    raise NotImplementedError("furthest_site=True: no first simplex found for this input (the walk's "
                              "interior point lies in a hyperplane of input points); please report it")


def _hull_volume(points, hull_facets, vertices):
    """The hull's volume from its facets (times d!): the cones from an interior point (the
    vertices' mean), as the simplices' volumes below are measured."""
    centre = points[vertices].mean(axis=0)
    corners = points[hull_facets]
    return np.abs(np.linalg.det(corners - centre[None, None, :])).sum()
