"""Compiled: the pieces at a pinch, where two rings (or one ring twice) meet at one vertex, get their triangles' radii.

A valid polygon may have an island touching the shore, or two islands
touching each other, at one point. Each ring then has its own sample there,
two samples at the same point; the triangulation, which jitters its points,
joins the pair by slivers, and the inner triangle on one side of the pinch
takes one of the two samples and the pieces of the other ring's sample do
not see it. :func:`medialaxis.planar._kernels.piece_state` gives such a
piece the radius of no inner triangle, so the split rule of
:func:`medialaxis.planar.boundary.sampling.refine_arcs` never splits it: a sparse
piece at the pinch lets a wide triangle of one side of an island's spike
have its circumcentre in the water on the other side, and the Voronoi edge
to it crosses the spike (a lake of ``benchmarks/bench_centerlines.py`` had
an axis edge 35 m out of its water through a 23 degree spike tip touching
the shore). :func:`pinched_radius` gives every piece of a sample the radius
of the inner triangles that hold a sample at the same point and the
piece's other end, as if both samples were one.

The shore then runs through the pinch from one ring to the other, and so
does the arc between two contacts on the two rings that the pruning weighs
(:func:`medialaxis.planar.pruning.prune_graph`): :func:`pinch_arcs` gives
them the arc through the pinch, not the infinite one of contacts on rings
that never meet. Without it the branch into the wedge between the rings at
the pinch, now sampled as any corner, stayed however wide the wedge (the
detour test of a branch into a corner of one ring removes it above 60
degrees at a detour of 1).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["touching_vertices", "pinched_radius", "pinch_arcs"]


@njit(cache=True, nogil=True)
def touching_vertices(xy, start):  # type: ignore[no-untyped-def]
    """The vertices at the same point as another: each one's next in a cycle over them, -1 for the others.

    ``xy`` holds the closed rings one after another, ring ``r`` at
    ``start[r]:start[r + 1]`` with its first vertex repeated at its end (the
    repeat is left out: -1).
    """
    n = len(xy)
    out = np.full(n, -1, np.int64)
    rows = np.empty(n, np.int64)
    m = 0
    for r in range(len(start) - 1):
        for i in range(start[r], start[r + 1] - 1):
            rows[m] = i
            m += 1
    rows = rows[:m]
    order = rows[np.argsort(xy[rows, 0], kind="mergesort")]
    i = 0
    while i < m:
        j = i + 1
        while j < m and xy[order[j], 0] == xy[order[i], 0]:
            j += 1
        for a in range(i, j):  # a run of equal x: link the rows of equal y into cycles
            first = order[a]
            if out[first] >= 0:
                continue
            last = first
            for b in range(a + 1, j):
                if out[order[b]] < 0 and xy[order[b], 1] == xy[first, 1]:
                    out[last] = order[b]
                    last = order[b]
            if last != first:
                out[last] = first
        i = j
    return out


@njit(cache=True, nogil=True, inline="always")
def pinched_radius(simplices, counted, radii, nxt, radius, ring, edge, at_vertex, rings_start, touching):  # type: ignore[no-untyped-def]
    """Lower ``radius`` (each piece ``(i, nxt[i])``'s, in place) by the triangles at a pinch (see the module docstring).

    ``counted`` are the inner triangles whose radius counts; ``edge`` and
    ``at_vertex`` say which samples are ring vertices
    (:func:`medialaxis.planar.boundary._corner_kernels.sample_edges`), ``touching``
    which vertices share their point (:func:`touching_vertices`).
    """
    n = len(nxt)
    twin = np.full(n, -1, np.int64)
    if not (touching >= 0).any():
        return
    sample_at = np.full(len(touching), -1, np.int64)
    for i in range(n):
        if at_vertex[i]:
            sample_at[rings_start[ring[i]] + edge[i]] = i
    pinched = False
    for i in range(n):
        if at_vertex[i]:
            other = touching[rings_start[ring[i]] + edge[i]]
            if other >= 0:
                twin[i] = sample_at[other]
                pinched = pinched or twin[i] >= 0
    if not pinched:
        return
    for t in range(len(simplices)):
        if not counted[t]:
            continue
        for k in range(3):
            for side in range(2):
                u = simplices[t, (k + 1 + side) % 3]
                v = simplices[t, (k + 2 - side) % 3]
                w = twin[u]
                while w >= 0 and w != u:  # the other samples at u's point
                    if nxt[w] == v:
                        radius[w] = min(radius[w], radii[t])
                    elif nxt[v] == w:
                        radius[v] = min(radius[v], radii[t])
                    w = twin[w]


@njit(cache=True, nogil=True)
def pinch_arcs(contact_arc, contact, arc, ring, ring_length, rings_s, rings_start, touching):  # type: ignore[no-untyped-def]
    """Lower ``contact_arc`` (in place) of each contact pair on two rings by the shorter arc through a pinch of them.

    ``contact`` (m, 2) are sample pairs, ``arc`` and ``ring`` each sample's
    arc position and ring, ``rings_s``, ``rings_start`` the closed rings'
    cumulative arc lengths (:class:`medialaxis.planar.boundary.corners.RingArrays`),
    ``touching`` their vertices at one point (:func:`touching_vertices`).
    The arc from a contact to the pinch on its ring and from the pinch to
    the other contact on the other ring, each the shorter way round.
    """
    pinch = np.flatnonzero(touching >= 0)  # loop over these only: a feature has thousands of vertices, a few pinches
    if len(pinch) == 0:
        return
    ring_of = np.empty(len(touching), np.int64)
    for r in range(len(rings_start) - 1):
        for g in range(rings_start[r], rings_start[r + 1]):
            ring_of[g] = r
    for e in range(len(contact)):
        a, b = contact[e, 0], contact[e, 1]
        ra, rb = ring[a], ring[b]
        if ra == rb:
            continue
        best = contact_arc[e]
        for g in pinch:  # a vertex of a's ring at a pinch, and its twins on b's ring
            if ring_of[g] != ra:
                continue
            h = touching[g]
            while h != g:
                if ring_of[h] == rb:
                    da = abs(arc[a] - rings_s[g])  # each ring's arc starts at 0 at its first vertex
                    db = abs(arc[b] - rings_s[h])
                    best = min(best, min(da, ring_length[ra] - da) + min(db, ring_length[rb] - db))
                h = touching[h]
        contact_arc[e] = best
