"""Compiled bookkeeping of the compaction (:mod:`medialaxis.mesh.compact`, :mod:`~medialaxis.mesh.compact_inside`).

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

from medialaxis._jit import njit, prange
from medialaxis.mesh._compact_kernels import lattice_steps

__all__ = ["quadrics", "ties_by_source", "changed_prims", "merge_into", "remap_faces"]


@njit(cache=True, nogil=True, parallel=True)
def quadrics(points, contacts):  # pragma: no cover - compiled
    """Spherical quadrics of each point's contacts (see :func:`~medialaxis.mesh.compact.sphere_quadrics`).

    Summed in NumPy's order (a contact's normal dotted with it as
    ``np.einsum`` does it: x and z first), so the quadrics are those of the
    NumPy version before it to the bit; 0.21 -> 0.05 s CPU for the uv
    ellipsoid's 385k spheres, no temporaries.
    """
    n = points.shape[0]
    qa = np.zeros((n, 4, 4))
    qb = np.zeros((n, 4))
    qc = np.zeros(n)
    for s in prange(n):
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
def ties_by_source(rows, cost, src):  # pragma: no cover - compiled
    """``rows`` sorted by ``cost[rows]`` (in any order among equal costs), those runs sorted by ``(src[row], row)``, in place.

    With ``rows`` ascending before the sort by cost, this is
    ``rows[np.lexsort((src[rows], cost[rows]))]``: 0.15 -> 0.07 s for the
    1.15M merges of the uv ellipsoid's first round (an unstable sort by
    cost and this pass; its costs have 0.3M ties).
    """
    m = rows.shape[0]
    a = 0
    while a < m:
        level = cost[rows[a]]
        b = a + 1
        while b < m and cost[rows[b]] == level:
            b += 1
        for t in range(a + 1, b):  # insertion sort of the run (at most a few hundred long)
            r = rows[t]
            s = src[r]
            u = t - 1
            while u >= a and (src[rows[u]] > s or (src[rows[u]] == s and rows[u] > r)):
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

    Returns those of them that carry samples of :func:`~medialaxis.mesh._compact_kernels.lattice`
    at ``spacing`` (over ``spheres``) after and before the map (q, 3), faces
    first, and which vertices (after the map) all of them have: 2.3M
    primitives changed on the uv ellipsoid, 9,073 with samples.
    """
    total = faces.shape[0] + edges.shape[0]
    touched = np.zeros(to.shape[0], np.bool_)
    sampled = np.zeros(total, np.bool_)
    for p in range(total):
        r0, r1, r2 = _prim(faces, edges, p)
        a, b, c = to[r0], to[r1], to[r2]
        if (a == r0 and b == r1 and c == r2) or a == b or c == a or (b == c and r1 != r2):  # unchanged or squeezed flat
            continue
        touched[a] = True
        touched[b] = True
        touched[c] = True
        sampled[p] = lattice_steps(spheres, a, b, c, spacing) >= 2  # else no sample of the lattice on it
    rows = np.flatnonzero(sampled)
    after = np.empty((rows.shape[0], 3), np.int64)
    before = np.empty((rows.shape[0], 3), np.int64)
    for k in range(rows.shape[0]):
        before[k, 0], before[k, 1], before[k, 2] = _prim(faces, edges, rows[k])
        for s in range(3):
            after[k, s] = to[before[k, s]]
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
