"""The furthest-site Delaunay triangulation, exactly (cospherical ties by the library's perturbation).

Its simplices are the upper hull of the points lifted to the paraboloid: the
simplices whose circumsphere contains every point. Only hull vertices take part
(a sphere containing them contains their convex hull), so the construction
works on those: gift wrapping (as for the Delaunay triangulation, with the
sphere test reversed), every decision an exact predicate of the library
(_dewall.predicate_signs: orientation, unperturbed in-sphere).

1. Start from a hull facet (the Delaunay triangulation's): its neighbour inside
   is the first simplex.
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
inside hull edges and faces are never vertices; in 2-D and 3-D they are set aside
first (_boundary), and the construction starts from a whole hull face (a triangle
on extreme points: the triangulation must have it). A 3-D hull without one (a
cube, a box-shaped grid: all faces flat with 4 or more corners), and 4-D+ hulls
with a hull vertex in a facet's hyperplane, raise NotImplementedError rather than
return a guess.
"""

from collections import deque

import numpy as np

from . import _dewall

_COPLANAR = ("furthest_site=True: the convex hull has flat faces with 4 or more corners and no triangular face "
             "to start from (a cube, a box-shaped grid), or such faces in 4-D and up (a hull vertex in a hull "
             "facet's hyperplane); dewall does not construct that furthest-site triangulation yet")


def furthest_site_simplices(points, hull_facets, whole=None):
    """The furthest-site Delaunay simplices (int32, each positively oriented) of `points`, whose
    convex hull facets are `hull_facets` (rows of d point indices). `whole`, when given, marks the
    facets that are whole faces of the hull on extreme points (_boundary): the construction then
    starts from one of them and allows other hull points in facet hyperplanes (the corners of
    flat faces); without it such points raise NotImplementedError."""
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

    if whole is None:  # refuse hull vertices in a hull facet's hyperplane (see above)
        for facet in hull_facets:
            others = vertices[~np.isin(vertices, facet)]
            if (orientation(np.column_stack([np.tile(facet, (others.size, 1)), others])) == 0).any():
                raise NotImplementedError(_COPLANAR)
        whole = np.ones(len(hull_facets), dtype=bool)
    elif not whole.any():
        raise NotImplementedError(_COPLANAR)

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

    start = [int(v) for v in hull_facets[int(np.argmax(whole))]]
    side = orientation(np.column_stack([np.tile(start, (vertices.size, 1)), vertices]))
    inner = int(side[side != 0][0])  # every hull vertex is on one side of a hull facet
    first = pivot(start, -inner)
    simplices = {tuple(sorted(start + [int(first)]))}
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
        raise NotImplementedError(_COPLANAR)
    # The defining property, unperturbed: every circumsphere contains every hull vertex (inside or on).
    for simplex in result:
        others = vertices[~np.isin(vertices, simplex)]
        if (signs(np.column_stack([np.tile(simplex, (others.size, 1)), others]), 1) < 0).any():
            raise RuntimeError("dewall: the furthest-site construction failed its check (a bug: please report)")
    return result


def _hull_volume(points, hull_facets, vertices):
    """The hull's volume from its facets (times d!): the cones from an interior point (the
    vertices' mean), as the simplices' volumes below are measured."""
    centre = points[vertices].mean(axis=0)
    corners = points[hull_facets]
    return np.abs(np.linalg.det(corners - centre[None, None, :])).sum()
