"""Compiled bookkeeping of the compaction (:mod:`medialaxis.mesh.medial.compact`, :mod:`~medialaxis.mesh.medial.compact_inside`).

The spheres' quadrics (:func:`quadrics`), the order in which a round takes
its collapses (:func:`ties_by_source`, after a sort by cost), the edges and
triangles its collapses change (:func:`changed_prims`), and the merges
themselves (:func:`merge_into`, :func:`remap_faces`), each in one pass
instead of a handful of NumPy temporaries the size of the complex. The uv
ellipsoid's compaction (27 rounds, 1.2M edges in the first): 1.4 s CPU of
such temporaries before, 0.4 s after.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.mesh.medial._compact_kernels import lattice_steps

__all__ = ["quadrics", "morton_codes", "ties_by_source", "changed_prims", "merge_into", "remap_faces"]


@njit(cache=True, nogil=True)
def quadrics(points, contacts):  # pragma: no cover - compiled
    """Spherical quadrics of each point's contacts (see :func:`~medialaxis.mesh.medial.compact.sphere_quadrics`).

    Summed in NumPy's order (a contact's normal dotted with it as
    ``np.einsum`` does it: x and z first), so the quadrics are those of the
    NumPy version before it to the bit; 0.21 -> 0.05 s CPU for the uv
    ellipsoid's 385k spheres, no temporaries.
    """
    n = points.shape[0]
    qa = np.zeros((n, 4, 4))
    qb = np.zeros((n, 4))
    qc = np.zeros(n)
    for s in range(n):
        for t in range(contacts.shape[1]):
            x = contacts[s, t, 0] - points[s, 0]
            y = contacts[s, t, 1] - points[s, 1]
            z = contacts[s, t, 2] - points[s, 2]
            norm = max(np.sqrt(x * x + y * y + z * z), 1e-300)
            x, y, z = x / norm, y / norm, z / norm
            d = (x * contacts[s, t, 0] + z * contacts[s, t, 2]) + y * contacts[s, t, 1]
            for k, a in enumerate((x, y, z, 1.0)):
                for m, b in enumerate((x, y, z, 1.0)):
                    qa[s, k, m] += a * b
                qb[s, k] += a * d
            qc[s] += d * d
    return qa, qb, qc


@njit(cache=True, nogil=True)
def _spread(x):  # pragma: no cover - compiled
    """The 21 low bits of ``x`` two zero bits apart (a Morton code's share of one axis)."""
    x &= 0x1FFFFF
    x = (x | x << 32) & 0x1F00000000FFFF
    x = (x | x << 16) & 0x1F0000FF0000FF
    x = (x | x << 8) & 0x100F00F00F00F00F
    x = (x | x << 4) & 0x10C30C30C30C30C3
    return (x | x << 2) & 0x1249249249249249


@njit(cache=True, nogil=True)
def morton_codes(points):  # pragma: no cover - compiled
    """Morton (Z-order) codes of ``points`` (n, 3) on a 2^21 grid over their box (all 0 if it is not finite)."""
    n = points.shape[0]
    codes = np.zeros(n, np.int64)
    low = np.full(3, np.inf)
    high = np.full(3, -np.inf)
    for p in range(n):
        for k in range(3):
            if not np.isfinite(points[p, k]):
                return codes
            low[k] = min(low[k], points[p, k])
            high[k] = max(high[k], points[p, k])
    span = max(high[0] - low[0], max(high[1] - low[1], high[2] - low[2]))
    if not span > 0.0:  # no points, or all in one
        return codes
    for p in range(n):
        for k in range(3):
            codes[p] |= _spread(np.int64((points[p, k] - low[k]) / span * 2097151.0)) << k
    return codes


@njit(cache=True, nogil=True)
def _before(a, b, src, edges, name, n):  # pragma: no cover - compiled
    """Whether edge ``a`` comes before ``b``: by the ``name`` of its source, then by its ends' names."""
    if name[src[a]] != name[src[b]]:
        return name[src[a]] < name[src[b]]
    ua, va = name[edges[a, 0]], name[edges[a, 1]]
    ub, vb = name[edges[b, 0]], name[edges[b, 1]]
    return min(ua, va) * n + max(ua, va) < min(ub, vb) * n + max(ub, vb)


@njit(cache=True, nogil=True)
def ties_by_source(rows, cost, src, edges, name):  # pragma: no cover - compiled
    """``rows`` sorted by ``cost[rows]`` (in any order among equal costs), those runs sorted by source and edge, in place.

    Ties go by ``name[src[row]]``, then by the edge's key ``min * n + max``
    over the names of its ends ``edges[row]``: with ``name`` the identity
    and ``edges`` sorted, this is ``rows[np.lexsort((src[rows], cost[rows]))]``
    for ``rows`` ascending (the complex's own labels, whatever order the
    compaction works in). 0.15 -> 0.07 s for the 1.15M merges of the uv
    ellipsoid's first round (an unstable sort by cost and this pass; its
    costs have 0.3M ties).
    """
    m = rows.shape[0]
    n = name.shape[0]
    a = 0
    while a < m:
        level = cost[rows[a]]
        b = a + 1
        while b < m and cost[rows[b]] == level:
            b += 1
        for t in range(a + 1, b):  # insertion sort of the run (at most a few hundred long)
            r = rows[t]
            u = t - 1
            while u >= a and _before(r, rows[u], src, edges, name, n):
                rows[u + 1] = rows[u]
                u -= 1
            rows[u + 1] = r
        a = b
    return rows


@njit(cache=True, nogil=True)
def _prim(faces, edges, p):  # pragma: no cover - compiled
    """Primitive ``p``: a triangle, or past the triangles an edge ``(a, b, b)``."""
    if p < faces.shape[0]:
        return faces[p, 0], faces[p, 1], faces[p, 2]
    e = p - faces.shape[0]
    return edges[e, 0], edges[e, 1], edges[e, 1]


@njit(cache=True, nogil=True)
def changed_prims(faces, edges, to, spheres, spacing):  # pragma: no cover - compiled
    """Triangles ``faces`` and edges ``edges`` (as triangles ``(a, b, b)``) that the map ``to`` changes without squeezing flat.

    Returns those of them that carry samples of :func:`~medialaxis.mesh.medial._compact_kernels.lattice`
    at ``spacing`` (over ``spheres``) after and before the map (q, 3), faces
    first, and which vertices (after the map) all of them have: 2.3M
    primitives changed on the uv ellipsoid, 9,073 with samples.
    """
    total = faces.shape[0] + edges.shape[0]
    kind = np.zeros(total, np.uint8)  # 1: changed, 2: changed, with samples
    for p in range(total):
        r0, r1, r2 = _prim(faces, edges, p)
        a, b, c = to[r0], to[r1], to[r2]
        if (a == r0 and b == r1 and c == r2) or a == b or c == a or (b == c and r1 != r2):  # unchanged or squeezed flat
            continue
        kind[p] = 2 if lattice_steps(spheres, a, b, c, spacing) >= 2 else 1
    touched = np.zeros(to.shape[0], np.bool_)
    count = 0
    for p in range(total):
        if kind[p]:
            r0, r1, r2 = _prim(faces, edges, p)
            touched[to[r0]] = touched[to[r1]] = touched[to[r2]] = True
            count += kind[p] == 2
    after = np.empty((count, 3), np.int64)
    before = np.empty((count, 3), np.int64)
    count = 0
    for p in range(total):
        if kind[p] == 2:
            before[count, 0], before[count, 1], before[count, 2] = _prim(faces, edges, p)
            for s in range(3):
                after[count, s] = to[before[count, s]]
            count += 1
    return after, before, touched


@njit(cache=True, nogil=True)
def merge_into(j, i, qa, qb, qc, count):  # pragma: no cover - compiled
    """Add the quadrics and contact counts of vertices ``j`` to those of ``i`` (no vertex twice in ``i``), in place."""
    for t in range(j.shape[0]):
        a, b = j[t], i[t]
        for k in range(4):
            for m in range(4):
                qa[b, k, m] += qa[a, k, m]
            qb[b, k] += qb[a, k]
        qc[b] += qc[a]
        count[b] += count[a]


@njit(cache=True, nogil=True)
def remap_faces(faces, origin, to):  # pragma: no cover - compiled
    """Triangles ``to[faces]`` that keep three corners, their ``origin`` and their corners sorted (each row ascending)."""
    keep = 0
    out = np.empty_like(faces)
    where = np.empty_like(origin)
    corners = np.empty_like(faces)
    for f in range(faces.shape[0]):
        a, b, c = to[faces[f, 0]], to[faces[f, 1]], to[faces[f, 2]]
        if a == b or b == c or c == a:
            continue
        out[keep, 0], out[keep, 1], out[keep, 2] = a, b, c
        where[keep] = origin[f]
        corners[keep, 0], corners[keep, 1], corners[keep, 2] = min(a, b, c), max(min(a, b), min(max(a, b), c)), max(a, b, c)
        keep += 1
    return out[:keep], where[:keep], corners[:keep]
