"""The shape a medial mesh stands for: the union of its spheres interpolated over edges and triangles.

Q-MAT and the sphere-mesh papers read a medial mesh with radii as a
continuous family of spheres: along an edge ``(c, r)`` runs linearly from one
end to the other (a *medial cone*), over a triangle barycentrically (a
*medial slab*). For a point ``x`` the function ``f(c, r) = |x - c| - r`` is
convex in ``(c, r)``, so its minimum over a cone or a slab has a closed form
(Thiery, Guy and Boubekeur, "Sphere-Meshes", 2013): the stationary point
where the direction ``n`` from the sphere's centre to ``x`` satisfies
``n . dc = -dr`` along every edge of the primitive, or else the minimum on
its edges and ends. The *gap* ``g(x) = min f`` over all primitives is the
distance from ``x`` to the union when ``x`` is outside it and minus the depth
in the deepest sphere when inside.

The boundary of the union lies on the primitives' own envelopes: sphere
surfaces, the tangent circles of cones (``n . u = -dr / |dc|``) and the two
offset planes of slabs. :func:`two_sided_distance` samples those evenly,
keeps the samples no other primitive holds, refines around the farthest of
them (the largest distances sit at creases where spheres meet, between
samples) and measures their distance to the input surface; the other side is
``|g|`` over samples of the surface.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis._jit import njit, prange

__all__ = ["primitives", "envelope_gap", "envelope_samples", "surface_sample", "two_sided_distance"]

#: Farthest envelope samples refined, and jittered points around each (:func:`two_sided_distance`).
REFINE_TOP = 32
REFINE_JITTER = 16


def primitives(n: int, edges: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """``(p, 4)`` int64 rows ``(kind, a, b, c)``: every sphere (0), every edge of ``edges`` and ``faces`` (1), every face (2)."""
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    pairs = np.concatenate([np.asarray(edges, np.int64).reshape(-1, 2), faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    pairs = np.unique(np.sort(pairs, axis=1), axis=0)
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    rows = [np.c_[np.zeros(n, np.int64), np.arange(n), np.arange(n), np.arange(n)]]
    rows.append(np.c_[np.ones(len(pairs), np.int64), pairs, pairs[:, 1]])
    rows.append(np.c_[np.full(len(faces), 2, np.int64), faces])
    return np.concatenate(rows).astype(np.int64)


def _bounds(spheres: np.ndarray, prims: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A ball ``(centre, B)`` per primitive with ``f(x) >= |x - centre| - B`` on it (``|c - centre| + r`` is convex)."""
    c = spheres[prims[:, 1:], :3]
    centre = c.mean(axis=1)
    reach = (np.linalg.norm(c - centre[:, None], axis=2) + spheres[prims[:, 1:], 3]).max(axis=1)
    return centre, reach


@njit(cache=True, nogil=True)
def _cone(x0, x1, x2, s, a, b):  # pragma: no cover - compiled
    """``min_t |x - c(t)| - r(t)`` over the spheres interpolated between spheres ``a`` and ``b``."""
    ax, ay, az = x0 - s[a, 0], x1 - s[a, 1], x2 - s[a, 2]
    bx, by, bz = x0 - s[b, 0], x1 - s[b, 1], x2 - s[b, 2]
    aa = ax * ax + ay * ay + az * az
    best = min(np.sqrt(aa) - s[a, 3], np.sqrt(bx * bx + by * by + bz * bz) - s[b, 3])
    dx, dy, dz = s[b, 0] - s[a, 0], s[b, 1] - s[a, 1], s[b, 2] - s[a, 2]
    dr = s[b, 3] - s[a, 3]
    l2 = dx * dx + dy * dy + dz * dz
    if dr * dr >= l2:  # one sphere holds the other: the minimum is at an end
        return best
    length = np.sqrt(l2)
    k = dr / length
    t0 = (ax * dx + ay * dy + az * dz) / l2
    h2 = aa - t0 * t0 * l2
    t = t0 + k * np.sqrt(max(h2, 0.0)) / (length * np.sqrt(1.0 - k * k))
    if t <= 0.0 or t >= 1.0:  # convex: the constrained minimum is at the nearer end
        return best
    qx, qy, qz = ax - t * dx, ay - t * dy, az - t * dz
    return min(best, np.sqrt(qx * qx + qy * qy + qz * qz) - (s[a, 3] + t * dr))


@njit(cache=True, nogil=True)
def _slab(x0, x1, x2, s, a, b, c):  # pragma: no cover - compiled
    """``min |x - c(u, v)| - r(u, v)`` over the spheres interpolated over the triangle ``a, b, c``."""
    e1x, e1y, e1z, d1 = s[b, 0] - s[a, 0], s[b, 1] - s[a, 1], s[b, 2] - s[a, 2], s[b, 3] - s[a, 3]
    e2x, e2y, e2z, d2 = s[c, 0] - s[a, 0], s[c, 1] - s[a, 1], s[c, 2] - s[a, 2], s[c, 3] - s[a, 3]
    g11 = e1x * e1x + e1y * e1y + e1z * e1z
    g12 = e1x * e2x + e1y * e2y + e1z * e2z
    g22 = e2x * e2x + e2y * e2y + e2z * e2z
    det = g11 * g22 - g12 * g12
    if det > 1e-14 * g11 * g22:
        # in-plane part of the unit direction n with n.e1 = -d1, n.e2 = -d2
        al = (-d1 * g22 + d2 * g12) / det
        be = (-d2 * g11 + d1 * g12) / det
        px, py, pz = al * e1x + be * e2x, al * e1y + be * e2y, al * e1z + be * e2z
        p2 = px * px + py * py + pz * pz
        if p2 < 1.0:
            root = np.sqrt(det)
            mx, my, mz = (e1y * e2z - e1z * e2y) / root, (e1z * e2x - e1x * e2z) / root, (e1x * e2y - e1y * e2x) / root
            ax, ay, az = x0 - s[a, 0], x1 - s[a, 1], x2 - s[a, 2]
            hh = ax * mx + ay * my + az * mz
            gam = np.sqrt(1.0 - p2)
            sg = gam if hh >= 0.0 else -gam
            lam = abs(hh) / gam
            wx, wy, wz = ax - lam * (px + sg * mx), ay - lam * (py + sg * my), az - lam * (pz + sg * mz)
            b1 = wx * e1x + wy * e1y + wz * e1z
            b2 = wx * e2x + wy * e2y + wz * e2z
            u = (b1 * g22 - b2 * g12) / det
            v = (b2 * g11 - b1 * g12) / det
            if u >= 0.0 and v >= 0.0 and u + v <= 1.0:
                return lam - (s[a, 3] + u * d1 + v * d2)
    return min(_cone(x0, x1, x2, s, a, b), min(_cone(x0, x1, x2, s, b, c), _cone(x0, x1, x2, s, a, c)))


@njit(cache=True, nogil=True)
def _gap(x0, x1, x2, s, kind, a, b, c):  # pragma: no cover - compiled
    if kind == 0:
        return np.sqrt((x0 - s[a, 0]) ** 2 + (x1 - s[a, 1]) ** 2 + (x2 - s[a, 2]) ** 2) - s[a, 3]
    if kind == 1:
        return _cone(x0, x1, x2, s, a, b)
    return _slab(x0, x1, x2, s, a, b, c)


@njit(cache=True, nogil=True, parallel=True)
def _gaps(points, s, prims, centre, reach, stop):  # pragma: no cover - compiled
    """Per point the least ``f`` over all primitives; once below ``stop`` the search ends (held inside)."""
    out = np.empty(len(points))
    for p in prange(len(points)):
        x0, x1, x2 = points[p, 0], points[p, 1], points[p, 2]
        best = np.inf
        for q in range(len(prims)):
            thr = best + reach[q]  # f >= |x - centre| - reach: skip unless that can beat best
            if thr <= 0.0:
                continue
            d2 = (x0 - centre[q, 0]) ** 2 + (x1 - centre[q, 1]) ** 2 + (x2 - centre[q, 2]) ** 2
            if d2 >= thr * thr:
                continue
            g = _gap(x0, x1, x2, s, prims[q, 0], prims[q, 1], prims[q, 2], prims[q, 3])
            if g < best:
                best = g
                if best < stop:
                    break
        out[p] = best
    return out


def envelope_gap(
    points: np.ndarray, centres: np.ndarray, radii: np.ndarray, edges: np.ndarray, faces: np.ndarray
) -> np.ndarray:
    """Exact ``g(x) = min |x - c| - r`` over the spheres interpolated over a medial mesh.

    Parameters
    ----------
    points : (q, 3) array_like
    centres, radii : (n, 3), (n,) array_like
        The medial mesh's spheres.
    edges, faces : (m, 2), (k, 3) array_like of int
        Its curve edges and triangles (the triangles' edges are cones too).

    Returns
    -------
    (q,) float64 ndarray
        Distance to the union of the spheres outside it, minus the depth in
        the deepest sphere inside it.

    References
    ----------
    .. [1] J.-M. Thiery, E. Guy, T. Boubekeur, "Sphere-Meshes: Shape approximation using
           spherical quadric error metrics", ACM Transactions on Graphics (Proc. SIGGRAPH Asia),
           2013. doi:10.1145/2508363.2508384
    .. [2] P. Li, B. Wang, F. Sun, X. Guo, C. Zhang, W. Wang, "Q-MAT: Computing medial axis
           transform by quadratic error minimization", ACM Transactions on Graphics
           35(1):8:1-8:16, 2015. doi:10.1145/2753755
    """
    spheres = np.ascontiguousarray(np.c_[centres, radii], np.float64)
    prims = primitives(len(spheres), edges, faces)
    centre, reach = _bounds(spheres, prims)
    return _gaps(np.ascontiguousarray(points, np.float64), spheres, prims, centre, reach, -np.inf)


def _fibonacci(j: np.ndarray, k: np.ndarray) -> np.ndarray:
    """Point ``j`` of ``k`` spread evenly over the unit sphere (Fibonacci lattice)."""
    i = j + 0.5
    phi, theta = np.arccos(1.0 - 2.0 * i / k), np.pi * (1.0 + 5.0**0.5) * i
    return np.c_[np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)]


def _local(counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For ``counts[i]`` points per item: each point's item and its index within the item."""
    owner = np.repeat(np.arange(len(counts)), counts)
    start = np.cumsum(counts) - counts
    return owner, np.arange(int(counts.sum())) - start[owner]


def envelope_samples(spheres: np.ndarray, prims: np.ndarray, budget: int = 100_000) -> np.ndarray:
    """About ``budget`` points spread evenly over the envelopes of the primitives (the union's boundary lies on them)."""
    kind = prims[:, 0]
    sph = prims[kind == 0, 1]
    cone = prims[kind == 1, 1:3]
    slab = prims[kind == 2, 1:]
    c, r = spheres[:, :3], spheres[:, 3]
    d = c[cone[:, 1]] - c[cone[:, 0]]
    length = np.linalg.norm(d, axis=1)
    dr = r[cone[:, 1]] - r[cone[:, 0]]
    open_cone = np.abs(dr) < length
    cone, d, length, dr = cone[open_cone], d[open_cone], length[open_cone], dr[open_cone]
    k = dr / length
    ring = np.sqrt(1.0 - k * k)
    e1, e2 = c[slab[:, 1]] - c[slab[:, 0]], c[slab[:, 2]] - c[slab[:, 0]]
    slab_area = 0.5 * np.linalg.norm(np.cross(e1, e2), axis=1)
    areas = [4 * np.pi * r[sph] ** 2, 2 * np.pi * length * ring * 0.5 * (r[cone[:, 0]] + r[cone[:, 1]]), 2 * slab_area]
    h2 = max(sum(float(a.sum()) for a in areas) / max(budget, 1), 1e-300)
    out = []
    # spheres: a Fibonacci lattice each
    counts = np.clip(np.ceil(areas[0] / h2), 16, 4096).astype(np.int64)
    owner, j = _local(counts)
    out.append(c[sph[owner]] + r[sph[owner], None] * _fibonacci(j, counts[owner]))
    # cones: rings of the tangent circle at steps along the edge
    along = np.clip(np.ceil(length / np.sqrt(h2)), 1, 256).astype(np.int64)
    around = np.clip(np.ceil(2 * np.pi * ring * np.maximum(r[cone[:, 0]], r[cone[:, 1]]) / np.sqrt(h2)), 6, 256)
    around = around.astype(np.int64)
    owner, j = _local(along * around)
    t = ((j // around[owner]) + 0.5) / along[owner]
    angle = 2 * np.pi * ((j % around[owner]) + 0.5 * (j // around[owner] % 2)) / around[owner]
    u = d / length[:, None]
    w1 = np.cross(u, np.where(np.abs(u[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]]))
    w1 /= np.linalg.norm(w1, axis=1, keepdims=True)
    w2 = np.cross(u, w1)
    n = -k[owner, None] * u[owner] + ring[owner, None] * (
        np.cos(angle)[:, None] * w1[owner] + np.sin(angle)[:, None] * w2[owner]
    )
    a = cone[owner, 0]
    out.append(c[a] + t[:, None] * d[owner] + (r[a] + t * dr[owner])[:, None] * n)
    # slabs: random points on the two offset planes (none where the plane does not exist)
    dr1, dr2 = r[slab[:, 1]] - r[slab[:, 0]], r[slab[:, 2]] - r[slab[:, 0]]
    g11, g12, g22 = (e1 * e1).sum(1), (e1 * e2).sum(1), (e2 * e2).sum(1)
    det = g11 * g22 - g12 * g12
    ok = det > 1e-14 * g11 * g22
    det = np.where(ok, det, 1.0)
    plane = ((-dr1 * g22 + dr2 * g12) / det)[:, None] * e1 + ((-dr2 * g11 + dr1 * g12) / det)[:, None] * e2
    p2 = (plane * plane).sum(1)
    ok &= p2 < 1.0
    m = np.cross(e1, e2) / np.sqrt(det)[:, None]
    counts = np.where(ok, np.clip(np.ceil(slab_area / h2), 1, 4096), 0).astype(np.int64)
    owner, _ = _local(counts)
    uv = np.random.default_rng(0).random((len(owner), 2))
    flip = uv.sum(axis=1) > 1
    uv[flip] = 1 - uv[flip]
    gam = np.sqrt(np.maximum(1.0 - p2[owner], 0.0))
    base = c[slab[owner, 0]] + uv[:, :1] * e1[owner] + uv[:, 1:] * e2[owner]
    rad = r[slab[owner, 0]] + uv[:, 0] * dr1[owner] + uv[:, 1] * dr2[owner]
    for side in (1.0, -1.0):
        out.append(base + rad[:, None] * (plane[owner] + side * gam[:, None] * m[owner]))
    return np.concatenate(out)


def surface_sample(surface: Any, count: int = 20_000) -> Any:
    """About ``count`` points spread evenly over ``surface``, its vertices among them (a ``SurfaceSample``)."""
    from medialaxis.mesh.sample.sampling import sample_surface

    area = np.asarray(surface.area_faces, np.float64)
    return sample_surface(surface, np.full(len(area), np.sqrt(area.sum() / count)))


def two_sided_distance(
    centres: np.ndarray,
    radii: np.ndarray,
    edges: np.ndarray,
    faces: np.ndarray,
    surface: Any,
    sample: Any = None,
    budget: int = 100_000,
    signed: Any = None,
    gaps: np.ndarray | None = None,
) -> tuple[float, float]:
    """Hausdorff distance both ways between ``surface`` and the boundary of the interpolated spheres.

    Parameters
    ----------
    centres, radii, edges, faces
        The medial mesh.
    surface : trimesh.Trimesh
        The input surface (closed, consistently oriented).
    sample : SurfaceSample, optional
        An even sample of the surface (:func:`surface_sample`; made here when
        not given): its points for the first figure, its faces to start the
        closest-point search of the second.
    budget : int
        About how many points are spread over the primitives' envelopes.
    signed : SignedDistance, optional
        Of ``surface`` (made here when not given; pass one to measure many
        medial meshes against the same surface).
    gaps : ndarray, optional
        :func:`envelope_gap` of the medial mesh at ``sample``'s points, when
        the caller has it (the cover repair keeps it up to date).

    Returns
    -------
    surface_to_mat : float
        ``max |g(x)|`` over the surface points: exact at each point.
    mat_to_surface : float
        Largest distance to the surface from a point of the union's
        boundary: envelope samples that no primitive holds, refined around
        the farthest ones (jittered at the spacing and at a quarter of it,
        then moved onto the boundary by Newton steps on ``g``). A lower
        bound; the maxima sit at creases where spheres meet.
    """
    from medialaxis.mesh.sample.signed_distance import SignedDistance

    smp = surface_sample(surface) if sample is None else sample
    x = smp.points
    spheres = np.ascontiguousarray(np.c_[centres, radii], np.float64)
    prims = primitives(len(spheres), edges, faces)
    centre, reach = _bounds(spheres, prims)
    if gaps is None:
        gaps = _gaps(x, spheres, prims, centre, reach, -np.inf) if len(x) else np.zeros(0)
    surface_to_mat = float(np.abs(gaps).max()) if len(x) else 0.0
    y = np.ascontiguousarray(envelope_samples(spheres, prims, budget))
    diag = float(np.linalg.norm(np.ptp(np.asarray(surface.vertices), axis=0)))
    # the samples' own spacing: median distance to the nearest other sample
    spacing = float(np.median(cKDTree(y).query(y[:: max(1, len(y) // 2000)], k=2)[0][:, 1])) if len(y) > 1 else 0.0
    y = y[_gaps(y, spheres, prims, centre, reach, -1e-7 * diag) >= -1e-7 * diag]
    if len(y) == 0:
        return surface_to_mat, 0.0
    tree, sd = cKDTree(smp.points), SignedDistance(surface) if signed is None else signed

    def distance(z: np.ndarray) -> np.ndarray:
        _, nearest = tree.query(z, k=4, workers=-1)
        return np.abs(sd.query(z, smp.face[nearest])[0])

    far = distance(y)
    # the largest distances sit at creases where spheres meet, between samples: jitter around the
    # farthest samples at the spacing, then a quarter of it, and move back onto the union's boundary
    rng = np.random.default_rng(0)
    for step in (spacing, 0.25 * spacing) if REFINE_TOP > 0 else ():
        top = y[np.argsort(far)[-REFINE_TOP:]]
        z = np.repeat(top, REFINE_JITTER, axis=0) + step * rng.normal(size=(len(top) * REFINE_JITTER, 3))
        z = _onto_boundary(z, spheres, prims, centre, reach, diag)
        if len(z):
            y, far = np.concatenate([y, z]), np.concatenate([far, distance(z)])
    # the local search may overstate (it misses faces farther off), never understate: the largest are searched
    # exhaustively, in batches doubling from 64, until the largest exact distance is at least the next local one.
    # (A batch of 64 and a sort of every distance per round took over 40 minutes on a triangle soup whose local
    # distances all overstate.)
    order = np.argsort(far)[::-1]
    best, start, size = 0.0, 0, 64
    while start < len(order) and far[order[start]] > best:
        batch = order[start : start + size]
        best = max(best, float(np.abs(sd.exact(y[batch])[0]).max()))
        start, size = start + len(batch), 2 * size
    return surface_to_mat, best


def _onto_boundary(z: np.ndarray, spheres: np.ndarray, prims: np.ndarray, centre: np.ndarray, reach: np.ndarray, diag: float) -> np.ndarray:
    """Points moved onto the union's boundary by Newton steps on ``g``; those not within ``1e-6 diag`` of it are dropped."""
    h = 1e-6 * diag  # finite-difference step of the gradient (|grad g| = 1 away from creases)
    for _ in range(2):
        z = np.ascontiguousarray(z)
        g = _gaps(z, spheres, prims, centre, reach, -np.inf)
        grad = np.stack([(_gaps(z + h * e, spheres, prims, centre, reach, -np.inf) - g) / h for e in np.eye(3)], axis=1)
        z = z - (g / np.maximum((grad * grad).sum(axis=1), 1e-12))[:, None] * grad
    g = _gaps(np.ascontiguousarray(z), spheres, prims, centre, reach, -np.inf)
    return z[np.abs(g) <= 1e-6 * diag]
