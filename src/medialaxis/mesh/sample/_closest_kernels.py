"""Compiled kernels of the Voronoi mesh pipeline: closest points on triangles (the inside test).

:func:`closest_on_candidates` finds, for each query point, the closest point
among a per-query list of candidate triangles (a CSR list), with the Voronoi
region of the triangle it falls in (a vertex, an edge or the face), so the
caller can sign the distance with the angle-weighted pseudo-normal
(Baerentzen and Aanaes 2005; :func:`pseudo_normal_sign`). A candidate whose bounding sphere
(:func:`face_spheres`) or plane lies farther than the best distance found is
skipped. :func:`face_tree` and :func:`closest_in_tree` search every face
that may be nearer than a distance found, through a bounding volume
hierarchy: memory bounded by the mesh, whatever the number of nearly
equidistant faces. :func:`closest_point_reference` is a
brute-force NumPy version over every triangle, used by the tests.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange

__all__ = [
    "box_distance2", "closest_on_candidates", "closest_in_tree", "closest_point_reference", "face_data", "face_scale",
    "face_spheres", "face_tree", "pseudo_normal_sign", "REGION_FACE",
]

#: Region codes: 0, 1, 2 = vertex a, b, c; 3, 4, 5 = edge ab, bc, ca; 6 = face.
REGION_FACE = 6
#: Most steps of the local descent from the best face found.
MAX_WALK = 16
#: Most faces in a leaf of :func:`face_tree`.
LEAF_FACES = 8
#: Smallest sine of a triangle's angle at its first corner for its normal to bound distances (:func:`face_data`).
MIN_SINE = 1e-3
#: Margin of the plane bound (:func:`_farther`), relative to the coordinates' scale plus the distance.
PLANE_SLACK = 1e-9


def face_spheres(tri_a: np.ndarray, tri_b: np.ndarray, tri_c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Bounding sphere of each triangle: centroid, and distance to its farthest corner, padded for rounding.

    Returns
    -------
    centre : (f, 3) float64 ndarray
    reach : (f,) float64 ndarray
    """
    centre = (tri_a + tri_b + tri_c) / 3.0
    reach = np.sqrt(np.max([np.einsum("ij,ij->i", v - centre, v - centre) for v in (tri_a, tri_b, tri_c)], axis=0))
    scale = float(np.abs(centre).max()) if len(centre) else 0.0
    return centre, reach * (1.0 + 1e-9) + 1e-12 * scale


def face_data(
    tri_a: np.ndarray, tri_b: np.ndarray, tri_c: np.ndarray, spheres: tuple[np.ndarray, np.ndarray] | None = None
) -> np.ndarray:
    """What the kernels read of each triangle, one row of 16 (two cache lines) per face.

    Columns 0-3: its bounding sphere (``spheres``, else :func:`face_spheres`:
    centre, then radius); 4-6, 7-9, 10-12: corners a, b, c; 13-15: its unit
    normal, or 0 where the triangle is too thin for the normal to be known
    to ``1e-12`` (an angle under ``MIN_SINE``: its plane then bounds nothing).

    Returns
    -------
    (f, 16) float64 ndarray
    """
    centre, reach = face_spheres(tri_a, tri_b, tri_c) if spheres is None else spheres
    out = np.zeros((len(centre), 16))
    out[:, :3], out[:, 3] = centre, reach
    for k, corner in enumerate((tri_a, tri_b, tri_c)):
        out[:, 4 + 3 * k : 7 + 3 * k] = corner
    ab, ac = tri_b - tri_a, tri_c - tri_a
    normal = np.cross(ab, ac)
    size = np.linalg.norm(normal, axis=1)
    known = size > MIN_SINE * np.linalg.norm(ab, axis=1) * np.linalg.norm(ac, axis=1)
    out[known, 13:16] = normal[known] / size[known, None]
    return out


def face_scale(fd: np.ndarray) -> float:
    """Largest coordinate magnitude of the triangles of :func:`face_data`, plus their largest bounding radius."""
    return float(np.abs(fd[:, 4:13]).max() + fd[:, 3].max()) if len(fd) else 0.0


@njit(cache=True, nogil=True, inline="always")
def _farther(px, py, pz, fd, f, best_dist, scale):  # type: ignore[no-untyped-def]
    """True when triangle ``f`` is certainly no nearer ``p`` than ``best_dist``: by its bounding sphere, or its plane.

    With the sphere alone, 72 triangles were tested per circumcentre of the uv
    ellipsoid; with the plane, 12 (0.55 -> 0.30 s of CPU for 385k; the same
    answers). The plane must be farther by ``PLANE_SLACK`` of ``scale +
    best_dist``, far above the rounding of both distances (normals known to
    1e-12, :func:`face_data`): a triangle skipped would not have been taken.
    """
    e0, e1, e2 = px - fd[f, 0], py - fd[f, 1], pz - fd[f, 2]
    bound = best_dist + fd[f, 3]
    if e0 * e0 + e1 * e1 + e2 * e2 >= bound * bound:
        return True
    plane = (px - fd[f, 4]) * fd[f, 13] + (py - fd[f, 5]) * fd[f, 14] + (pz - fd[f, 6]) * fd[f, 15]
    return abs(plane) > best_dist + PLANE_SLACK * (scale + best_dist)


@njit(cache=True, nogil=True, inline="always")
def _closest_on_triangle(px, py, pz, fd, f):  # type: ignore[no-untyped-def]
    """Barycentric weights (v, w) of the closest point to ``p`` on triangle ``f`` (row ``fd[f]`` of :func:`face_data`) and its region.

    Ericson, Real-Time Collision Detection, 5.1.5; scalar code (no
    allocation, and no array views: a view of a corner cost a third of the
    whole query). The closest point is ``a + v (b - a) + w (c - a)``.
    """
    ax, ay, az = fd[f, 4], fd[f, 5], fd[f, 6]
    abx, aby, abz = fd[f, 7] - ax, fd[f, 8] - ay, fd[f, 9] - az
    acx, acy, acz = fd[f, 10] - ax, fd[f, 11] - ay, fd[f, 12] - az
    apx, apy, apz = px - ax, py - ay, pz - az
    d1 = abx * apx + aby * apy + abz * apz
    d2 = acx * apx + acy * apy + acz * apz
    if d1 <= 0.0 and d2 <= 0.0:
        return 0.0, 0.0, 0
    bpx, bpy, bpz = px - fd[f, 7], py - fd[f, 8], pz - fd[f, 9]
    d3 = abx * bpx + aby * bpy + abz * bpz
    d4 = acx * bpx + acy * bpy + acz * bpz
    if d3 >= 0.0 and d4 <= d3:
        return 1.0, 0.0, 1
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        return d1 / (d1 - d3), 0.0, 3
    cpx, cpy, cpz = px - fd[f, 10], py - fd[f, 11], pz - fd[f, 12]
    d5 = abx * cpx + aby * cpy + abz * cpz
    d6 = acx * cpx + acy * cpy + acz * cpz
    if d6 >= 0.0 and d5 <= d6:
        return 0.0, 1.0, 2
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        return 0.0, d2 / (d2 - d6), 5
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return 1.0 - w, w, 4
    denom = 1.0 / (va + vb + vc)
    return vb * denom, vc * denom, 6


@njit(cache=True, nogil=True, inline="always")
def _point_on_face(px, py, pz, fd, f):  # type: ignore[no-untyped-def]
    """Squared distance from ``p`` to triangle ``f`` (row ``fd[f]``), its closest point and region."""
    v, w, r = _closest_on_triangle(px, py, pz, fd, f)
    x0 = fd[f, 4] + v * (fd[f, 7] - fd[f, 4]) + w * (fd[f, 10] - fd[f, 4])
    x1 = fd[f, 5] + v * (fd[f, 8] - fd[f, 5]) + w * (fd[f, 11] - fd[f, 5])
    x2 = fd[f, 6] + v * (fd[f, 9] - fd[f, 6]) + w * (fd[f, 12] - fd[f, 6])
    return (px - x0) ** 2 + (py - x1) ** 2 + (pz - x2) ** 2, x0, x1, x2, r


@njit(cache=True, nogil=True, parallel=True)
def closest_on_candidates(query, fd, near, ring_ptr, ring_idx, scale):  # type: ignore[no-untyped-def]
    """Closest point among the faces around a few given faces, per query.

    Parameters
    ----------
    query : (q, 3) float64 ndarray
    fd : (f, 16) float64 ndarray
        Each triangle's bounding sphere and corners in one row
        (:func:`face_data`): the sphere test reads the row's first cache
        line, the closest point its two. Separate arrays of the corners
        (f, 3, 3) and of the spheres (f, 4) took 2.44 s for the 2M
        tetrahedron centroids of the uv ellipsoid and 0.88 s for its 385k
        circumcentres, one thread; packed, with the plane bound and the
        triangle code inlined, 1.47 and 0.26 s, the same answers bit for bit.
    near : (q, k) int64 ndarray
        Faces near each query; the candidates are their rings, then the
        rings of the best face found, repeatedly (up to ``MAX_WALK`` steps)
        until the best face stays the same.
    ring_ptr : (f + 1,) int64 ndarray
    ring_idx : (c,) int64 ndarray
        Ring of face ``f`` (faces sharing a vertex with it, itself included):
        ``ring_idx[ring_ptr[f]:ring_ptr[f + 1]]``.
    scale : float
        :func:`face_scale` of ``fd`` (the margin of the plane bound, :func:`_farther`).

    Returns
    -------
    dist : (q,) float64 ndarray
        Unsigned distance.
    point : (q, 3) float64 ndarray
    face : (q,) int64 ndarray
    region : (q,) int64 ndarray
        0-2 vertex, 3-5 edge (ab, bc, ca), 6 face.
    """
    nq = query.shape[0]
    dist = np.full(nq, np.inf)
    point = np.zeros((nq, 3))
    face = np.full(nq, -1, np.int64)
    region = np.full(nq, -1, np.int64)
    # the rings of neighbouring faces overlap: each face is tested once per
    # query, marked in a stamp array per block of queries (one block per task)
    n_blocks = min(nq, 64)
    for block in prange(n_blocks):
        stamp = np.full(fd.shape[0], -1, np.int32)  # query numbers (< 2**31): half the cache of int64
        for i in range(block * nq // n_blocks, (block + 1) * nq // n_blocks):
            _closest_one(i, query, fd, near, ring_ptr, ring_idx, scale, stamp, point, face, region, dist)
    return dist, point, face, region


@njit(cache=True, nogil=True)
def _closest_one(i, query, fd, near, ring_ptr, ring_idx, scale, stamp, point, face, region, dist):  # type: ignore[no-untyped-def]
    """One query of :func:`closest_on_candidates` (faces with ``stamp == i`` are skipped, then stamped).

    The best face so far is kept in registers and written once.
    """
    px, py, pz = query[i, 0], query[i, 1], query[i, 2]
    best = np.inf
    best_dist = np.inf
    best_face, best_region, b0, b1, b2 = -1, -1, 0.0, 0.0, 0.0
    # scan the rings of the given faces, then walk: scan the ring of the
    # best face found until it no longer changes (local descent on the mesh)
    n_near = near.shape[1]
    scanned = -1
    for a in range(n_near + MAX_WALK):
        if a < n_near:
            g = near[i, a]
        else:
            g = best_face
            if g == scanned:
                break
            scanned = g
        for k in range(ring_ptr[g], ring_ptr[g + 1]):
            f = ring_idx[k]
            if stamp[f] == i:
                continue
            stamp[f] = i
            # no point of the triangle is nearer than its bounding sphere (1.94 -> 1.43 s for
            # the 2M tetrahedron centroids of the uv ellipsoid; same answers), or its plane
            if _farther(px, py, pz, fd, f, best_dist, scale):
                continue
            d2, x0, x1, x2, r = _point_on_face(px, py, pz, fd, f)
            if d2 < best:
                best = d2
                best_dist = np.sqrt(d2)
                best_face, best_region, b0, b1, b2 = f, r, x0, x1, x2
    if best_face >= 0:
        point[i, 0], point[i, 1], point[i, 2] = b0, b1, b2
        face[i], region[i] = best_face, best_region
    dist[i] = np.sqrt(best)


@njit(cache=True, nogil=True)
def face_tree(centre, tri_a, tri_b, tri_c):  # type: ignore[no-untyped-def]
    """Bounding volume hierarchy of triangles: median splits of their centroids along the widest axis.

    Returns
    -------
    order : (f,) int64 ndarray
        Faces in leaf order: node ``n`` holds ``order[start[n]:stop[n]]``.
    low, high : (m, 3) float64 ndarray
        Box of each node's triangles (padded for rounding, as :func:`face_spheres`).
    child : (m,) int64 ndarray
        First child (the second is ``child + 1``), -1 for a leaf of at most ``LEAF_FACES`` faces.
    start, stop : (m,) int64 ndarray
    """
    nf = centre.shape[0]
    order = np.arange(nf)
    cap = 2 * max(nf, 1)  # a binary tree with at most nf leaves
    low, high = np.empty((cap, 3)), np.empty((cap, 3))
    child = np.full(cap, -1, np.int64)
    start, stop = np.zeros(cap, np.int64), np.zeros(cap, np.int64)
    stop[0] = nf
    scale = 0.0
    for f in range(nf):
        for k in range(3):
            scale = max(scale, abs(tri_a[f, k]), abs(tri_b[f, k]), abs(tri_c[f, k]))
    pending = np.empty(cap, np.int64)
    pending[0] = 0
    top, m = 1, 1
    while top > 0:
        top -= 1
        node = pending[top]
        s, e = start[node], stop[node]
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        c_lo, c_hi = np.full(3, np.inf), np.full(3, -np.inf)
        for r in range(s, e):
            f = order[r]
            for k in range(3):
                lo[k] = min(lo[k], tri_a[f, k], tri_b[f, k], tri_c[f, k])
                hi[k] = max(hi[k], tri_a[f, k], tri_b[f, k], tri_c[f, k])
                c_lo[k] = min(c_lo[k], centre[f, k])
                c_hi[k] = max(c_hi[k], centre[f, k])
        for k in range(3):
            pad = 1e-9 * (hi[k] - lo[k]) + 1e-12 * scale
            low[node, k], high[node, k] = lo[k] - pad, hi[k] + pad
        if e - s <= LEAF_FACES:
            continue
        axis = np.argmax(c_hi - c_lo)
        part = order[s:e].copy()
        order[s:e] = part[np.argsort(centre[part, axis], kind="mergesort")]
        mid = (s + e) // 2
        child[node] = m
        start[m], stop[m], start[m + 1], stop[m + 1] = s, mid, mid, e
        pending[top], pending[top + 1] = m, m + 1
        top += 2
        m += 2
    return order, low[:m], high[:m], child[:m], start[:m], stop[:m]


@njit(cache=True, nogil=True)
def box_distance2(p, low, high, n):  # type: ignore[no-untyped-def]
    """Squared distance from ``p`` to the box ``low[n]``..``high[n]`` (any dimension: the simplification's 4-D tree too)."""
    d = 0.0
    for k in range(p.shape[0]):
        if p[k] < low[n, k]:
            d += (low[n, k] - p[k]) ** 2
        elif p[k] > high[n, k]:
            d += (p[k] - high[n, k]) ** 2
    return d


@njit(cache=True, nogil=True, parallel=True)
def closest_in_tree(query, fd, scale, tree, dist, point, face, region):  # type: ignore[no-untyped-def]
    """Improve, in place, the closest points found for each query to the nearest face of the whole mesh.

    ``fd`` and ``scale`` as :func:`closest_on_candidates` takes them;
    ``dist``, ``point``, ``face``, ``region`` (as it returns them) hold a face found for each query; every node of ``tree``
    (:func:`face_tree`) whose box is nearer is opened, nearer child first,
    and every face in it whose bounding sphere is nearer is tested. Returns
    the number of faces tested per query.
    """
    order, low, high, child, start, stop = tree
    nq = query.shape[0]
    tested = np.zeros(nq, np.int64)
    n_blocks = min(nq, 64)
    for block in prange(n_blocks):
        pending = np.empty(128, np.int64)  # the tree is at most log2(f) deep: two entries a level
        for i in range(block * nq // n_blocks, (block + 1) * nq // n_blocks):
            p = query[i]
            best = dist[i] * dist[i]
            best_dist = dist[i]
            pending[0] = 0
            top = 1
            while top > 0:
                top -= 1
                node = pending[top]
                if box_distance2(p, low, high, node) >= best:
                    continue
                first = child[node]
                if first >= 0:
                    near_first = box_distance2(p, low, high, first) <= box_distance2(p, low, high, first + 1)
                    pending[top], pending[top + 1] = (first + 1, first) if near_first else (first, first + 1)
                    top += 2
                    continue
                for r in range(start[node], stop[node]):
                    f = order[r]
                    if _farther(p[0], p[1], p[2], fd, f, best_dist, scale):
                        continue
                    tested[i] += 1
                    d2, x0, x1, x2, reg = _point_on_face(p[0], p[1], p[2], fd, f)
                    if d2 < best:
                        best = d2
                        best_dist = np.sqrt(d2)
                        point[i, 0], point[i, 1], point[i, 2] = x0, x1, x2
                        face[i] = f
                        region[i] = reg
                        dist[i] = best_dist
    return tested


@njit(cache=True, nogil=True, parallel=True)
def pseudo_normal_sign(points, closest, dist, face, region, faces, face_normal, vertex_normal, edge_normal, face_edges):  # type: ignore[no-untyped-def]
    """``dist`` signed by the pseudo-normal of the closest feature: negative where ``points - closest`` points against it.

    The feature is the face, one of its vertices or one of its edges
    (``region`` as :func:`closest_on_candidates` gives it); one compiled
    pass instead of NumPy gathers of (q, 3) normals (0.25 s over the uv
    ellipsoid's 2.5M queries).
    """
    out = np.empty(points.shape[0])
    for q in prange(points.shape[0]):
        f, r = face[q], region[q]
        if r < 3:
            n = vertex_normal[faces[f, r]]
        elif r < REGION_FACE:
            n = edge_normal[face_edges[f, r - 3]]
        else:
            n = face_normal[f]
        side = (points[q, 0] - closest[q, 0]) * n[0] + (points[q, 1] - closest[q, 1]) * n[1]
        side += (points[q, 2] - closest[q, 2]) * n[2]
        out[q] = -dist[q] if side < 0 else dist[q]
    return out


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.einsum("...k,...k->...", p - a, ab) / np.maximum(np.einsum("...k,...k->...", ab, ab), 1e-300)
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(p - (a + t[..., None] * ab), axis=-1)


def closest_point_reference(query: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Brute-force unsigned distance from each query to a triangle soup.

    Parameters
    ----------
    query : (q, 3) float64 ndarray
    triangles : (f, 3, 3) float64 ndarray

    Returns
    -------
    (q,) float64 ndarray
        Distance to the nearest triangle: the plane distance where the foot
        falls inside, else the nearest of the three edges.
    """
    p = np.asarray(query, np.float64)[:, None, :]
    a, b, c = (np.asarray(triangles, np.float64)[None, :, k, :] for k in range(3))
    n = np.cross(b - a, c - a)
    n = n / np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-300)
    h = np.einsum("qfk,qfk->qf", p - a, n)
    foot = p - h[..., None] * n
    inside = np.ones(h.shape, bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("qfk,qfk->qf", np.cross(v - u, foot - u), n) >= 0
    edge = np.minimum(np.minimum(_segment_distance(p, a, b), _segment_distance(p, b, c)), _segment_distance(p, c, a))
    return np.where(inside, np.abs(h), edge).min(axis=1)
