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
on extreme points: the triangulation must have it), or, in a 3-D hull without one
(a cube, a box-shaped grid: all faces flat with 4 or more corners), from a hull
edge (_start_on_flat_face). 4-D+ hulls with a hull vertex in a facet's hyperplane
raise NotImplementedError rather than return a guess: their facets come from the
Delaunay triangulation's boundary, points inside flat facets included, and no
start is known there yet.
"""

from collections import deque

import numpy as np

from . import _dewall
from ._boundary import ridge_pairs

_COPLANAR = ("furthest_site=True: the convex hull has flat facets (in 4-D and up: a hull vertex in a hull "
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

    def furthest_site(simplex):
        """Whether the perturbed sphere of `simplex` contains every other hull vertex."""
        others = vertices[~np.isin(vertices, simplex)]
        return bool((signs(np.column_stack([np.tile(positive(simplex), (others.size, 1)), others]), 2) > 0).all())

    if whole.any():  # a whole hull face is a face of every triangulation of the hull vertices
        first = inward([int(v) for v in hull_facets[int(np.argmax(whole))]])
    else:
        first = _start_on_flat_face(hull_facets, vertices, orientation, inward, furthest_site)
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
        raise NotImplementedError(_COPLANAR)
    # The defining property, unperturbed: every circumsphere contains every hull vertex (inside or on).
    for simplex in result:
        others = vertices[~np.isin(vertices, simplex)]
        if (signs(np.column_stack([np.tile(simplex, (others.size, 1)), others]), 1) < 0).any():
            raise RuntimeError("dewall: the furthest-site construction failed its check (a bug: please report)")
    return result


def _start_on_flat_face(hull_facets, vertices, orientation, inward, furthest_site):
    """3-D, every hull face flat with 4 or more corners (a cube): a first simplex. An edge (a, b)
    of the hull polytope is an edge of every triangulation of the hull vertices, so exactly one
    triangle (a, b, c) of the furthest-site triangulation lies in a face F through it, c a corner
    of F; pivoting inward from the right one gives a simplex whose perturbed sphere contains
    every hull vertex, from any other one a simplex whose sphere does not (the perturbed
    furthest-site triangulation is unique). So: try each corner c of F."""
    facets = np.asarray(hull_facets, dtype=np.int64)
    neighbors = ridge_pairs(facets)
    for f, facet in enumerate(facets):
        for j in range(3):
            g = neighbors[f, j]
            across = [v for v in facets[g] if v not in facet][0]
            if orientation([list(facet) + [across]])[0] == 0:
                continue  # inside a flat face: not an edge of the polytope
            a, b = (int(v) for k, v in enumerate(facet) if k != j)
            in_plane = orientation(np.column_stack([np.tile(facet, (vertices.size, 1)), vertices])) == 0
            for c in vertices[in_plane]:
                if c in (a, b):
                    continue
                simplex = inward([a, b, int(c)])
                if furthest_site(simplex):
                    return simplex
    raise NotImplementedError(_COPLANAR)


def _hull_volume(points, hull_facets, vertices):
    """The hull's volume from its facets (times d!): the cones from an interior point (the
    vertices' mean), as the simplices' volumes below are measured."""
    centre = points[vertices].mean(axis=0)
    corners = points[hull_facets]
    return np.abs(np.linalg.det(corners - centre[None, None, :])).sum()
