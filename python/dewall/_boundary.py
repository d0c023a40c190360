"""The convex hull's boundary on its extreme points, exactly: what ConvexHull reports and where
the furthest-site construction starts. Every decision is an orientation sign of the library
(_dewall.predicate_signs); the Delaunay triangulation's boundary facets are the input.
"""

import numpy as np

from . import _dewall


def extreme_hull_edges_2d(points, simplices, neighbors):
    """2-D: the convex hull's edges between its extreme points (rows of 2 indices). The
    Delaunay triangulation's hull edges also pass through the points inside hull edges (a grid's
    sides); those are dropped here, exactly (orientation ZERO with their two neighbours on the
    boundary), so the furthest-site construction can start from a proper edge."""
    simplex, opposite = np.nonzero(neighbors == -1)
    after = {}
    for s, j in zip(simplex, opposite):  # counterclockwise along the boundary (positively oriented triangles)
        after[int(simplices[s, (j + 1) % 3])] = int(simplices[s, (j + 2) % 3])
    ring = [next(iter(after))]
    while after[ring[-1]] != ring[0]:
        ring.append(after[ring[-1]])
    return extreme_ring_2d(points, np.array(ring))


def extreme_ring_2d(points, ring, collinear=True):
    """The edges (rows of 2 indices) of the counterclockwise boundary cycle `ring` without the
    points collinear with their two neighbours (exact orientation; skipped when `collinear` is
    False: none can be)."""
    if collinear:
        triples = np.column_stack((np.roll(ring, 1), ring, np.roll(ring, -1)))
        ring = ring[_dewall.predicate_signs(points, triples.astype(np.uint32), 0) != 0]
    return np.column_stack((ring, np.roll(ring, -1)))


def extreme_facets_3d(points, simplices, neighbors, convex_hull):
    """3-D hull facets on the extreme points only, from the Delaunay triangulation's boundary
    triangles: see merge_flat_faces_3d. Returns (facets, a point inside for each, whether each
    facet is a whole face of the hull: a triangle of its own, not part of a fan)."""
    simplex, opposite = np.nonzero(neighbors == -1)
    facets = convex_hull.astype(np.int64)
    inside = simplices[simplex, opposite].astype(np.int64)
    # counterclockwise seen from outside: the inside point on the negative side
    flip = _orientation(points, np.column_stack((facets, inside))) > 0
    facets[flip] = facets[flip][:, [0, 2, 1]]
    return merge_flat_faces_3d(points, facets, inside)


def _orientation(points, rows):
    return _dewall.predicate_signs(points, np.ascontiguousarray(rows, dtype=np.uint32), 0)


def merge_flat_faces_3d(points, facets, inside):
    """3-D hull facets on the extreme points only. `facets`: triangles covering the hull's
    boundary, counterclockwise seen from outside, `inside[i]` a point strictly inside facet i's
    plane. Where several lie in one plane (exact orientation ZERO across their shared edge), they
    are replaced by a fan over the corners of that flat face (its boundary cycle without the
    points inside its edges); points inside a face drop out with its inner triangles. Returns
    (facets, a point inside for each, whether each facet is a whole face of the hull)."""
    facets, inside = facets.astype(np.int64), np.asarray(inside, dtype=np.int64)
    neighbors = ridge_pairs(facets)
    i, j = np.nonzero(neighbors >= 0)
    n = neighbors[i, j]
    # the vertex of facet n not in facet i: the one opposite the shared edge
    other = facets[n, np.argmax(neighbors[n] == i[:, None], axis=1)]
    flat = _orientation(points, np.column_stack((facets[i], other))) == 0
    if not flat.any():
        return facets.astype(np.int32), inside, np.ones(len(facets), dtype=bool)
    parent = np.arange(len(facets))

    def root(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b in zip(i[flat], n[flat]):
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    groups = {}
    for f in range(len(facets)):
        groups.setdefault(root(f), []).append(f)
    out, out_inside, whole = [], [], []
    for members in groups.values():
        if len(members) == 1:
            out.append(facets[members[0]])
            out_inside.append(inside[members[0]])
            whole.append(True)
            continue
        directed = {(int(f[k]), int(f[(k + 1) % 3])) for f in facets[members] for k in range(3)}
        after = {a: b for a, b in directed if (b, a) not in directed}  # the face's boundary, counterclockwise
        ring = [next(iter(after))]
        while after[ring[-1]] != ring[0]:
            ring.append(after[ring[-1]])
        ring = np.array(ring)
        below = inside[members[0]]
        triples = np.column_stack((np.roll(ring, 1), ring, np.roll(ring, -1), np.full(len(ring), below)))
        corners = ring[_orientation(points, triples) != 0]  # collinear with its neighbours: inside an edge
        for k in range(1, len(corners) - 1):
            out.append([corners[0], corners[k], corners[k + 1]])
            out_inside.append(below)
            whole.append(len(corners) == 3)
    return np.array(out, dtype=np.int32), np.array(out_inside, dtype=np.int64), np.array(whole)


def quickhull_facets(points):
    """The convex hull's facets on its extreme points by the compiled exact Quickhull (python/src/
    convex_hull.hpp): (facets, whether each is a whole face of the hull), as the furthest-site
    construction takes them; None when Quickhull declines (non-finite, too few or nearly flat
    points): the caller then takes the Delaunay route."""
    hull = _dewall.convex_hull(points)
    if hull is None:
        return None
    facets, _, below, flat, _ = hull
    d = points.shape[1]
    if d == 2:  # Quickhull's edges run clockwise: their ends, reversed, are the ring counterclockwise
        edges = extreme_ring_2d(points, facets[::-1, 1].astype(np.int64), collinear=flat)
        return edges, np.ones(len(edges), dtype=bool)
    if d == 3 and flat:
        facets, _, whole = merge_flat_faces_3d(points, facets, below)
        return facets, whole
    # 4-D and up with flat facets: a triangulation of the boundary, no facet known to be a whole face
    return facets, np.full(len(facets), not flat)


def ridge_pairs(facets):
    """Each facet's ridges (the facet without its vertex j) matched in pairs: neighbors[i, j]
    is the facet sharing the ridge of facet i opposite its vertex j (-1 when none)."""
    m, k = facets.shape
    ridges = np.sort(np.stack([np.delete(facets, j, axis=1) for j in range(k)], axis=1), axis=2)  # (m, k, k-1)
    flat = ridges.reshape(m * k, k - 1)
    order = np.lexsort(flat.T[::-1])
    same = np.all(flat[order][1:] == flat[order][:-1], axis=1)
    neighbors = np.full(m * k, -1, dtype=np.int32)
    first, second = order[:-1][same], order[1:][same]
    neighbors[first], neighbors[second] = second // k, first // k
    return neighbors.reshape(m, k)
