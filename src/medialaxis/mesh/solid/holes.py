"""Holes of a slightly open mesh closed by caps, so that the solid its winding number defines has a surface.

A mesh with a few missing faces (scans, CAD exports) still encloses a solid:
the generalized winding number stays close to 1 inside and 0 outside away
from the gaps (Jacobson, Kavan, Sorkine-Hornung, "Robust inside-outside
segmentation using generalized winding numbers", ACM Transactions on
Graphics 32(4), 2013, doi:10.1145/2461912.2461916). Each hole (a loop of
edges with one face) is closed by a fan from its centroid, oriented as the
faces around it; where a cap crosses the surface (a hole that is not flat),
:mod:`medialaxis.mesh.solid.arrangement` then keeps the solid's side of it.
"""

from __future__ import annotations

import numpy as np

#: Winding numbers of the open surface within this of 1/2 are undecided (neither inside nor outside).
UNDECIDED = 0.2

__all__ = ["boundary_loops", "cap_holes", "undecided_share"]


def boundary_loops(faces: np.ndarray) -> list[np.ndarray] | None:
    """Loops of vertices around the holes of a consistently oriented surface, or ``None`` if they do not chain.

    A boundary edge is a directed face edge ``u -> v`` whose reverse no face
    has; around a hole they chain head to tail. Where two holes touch at a
    vertex (it starts two boundary edges), ``u -> v`` is followed by the
    boundary edge that is not on its own fan of faces about ``v`` (that one
    borders the other hole), so each hole gets its own loop and cap and the
    vertex becomes a manifold one. ``None`` where an edge is used twice in
    the same direction or three holes or more meet at a vertex.
    """
    f = np.asarray(faces, np.int64)
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    third = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])  # the corner opposite each directed edge
    n = int(f.max(initial=-1)) + 1
    keys = directed[:, 0] * n + directed[:, 1]
    order = np.argsort(keys, kind="stable")
    keys = keys[order]  # sorted: an edge's corner by binary search, no dict of them all
    if len(keys) and (keys[1:] == keys[:-1]).any():
        return None

    def corner(u: int, v: int) -> int | None:
        """The corner opposite the directed edge ``u -> v``, if a face has it."""
        at = int(np.searchsorted(keys, u * n + v))
        return int(third[order[at]]) if at < len(keys) and keys[at] == u * n + v else None

    reverse = directed[:, 1] * n + directed[:, 0]
    at = np.minimum(np.searchsorted(keys, reverse), max(len(keys) - 1, 0))
    open_edge = np.flatnonzero(keys[at] != reverse) if len(keys) else np.empty(0, np.int64)
    boundary = [(int(u), int(v)) for u, v in directed[open_edge]]
    leaving: dict[int, list[int]] = {}
    for u, v in boundary:
        leaving.setdefault(u, []).append(v)
    nxt: dict[tuple[int, int], tuple[int, int]] = {}
    for u, v in boundary:
        heads = leaving.get(v, [])
        if len(heads) == 1:
            nxt[(u, v)] = (v, heads[0])
            continue
        if len(heads) != 2:
            return None  # three holes or more at a vertex: their order about it is not known
        # two holes at v: turning about v through the faces from the one of u -> v (v -> w, across it the
        # next face, ...) reaches the boundary edge on the same fan, of the other hole; u -> v's hole goes on
        # along the other fan's edge
        w, guard = corner(u, v), 0
        while (nw := corner(w, v)) is not None and guard < len(keys):  # type: ignore[arg-type]
            w, guard = nw, guard + 1
        if w not in heads:
            return None
        nxt[(u, v)] = (v, heads[1 - heads.index(w)])
    if len(set(nxt.values())) < len(nxt):
        return None
    loops, seen = [], set()
    for edge in boundary:
        if edge in seen:
            continue
        loop = []
        while edge not in seen:
            seen.add(edge)
            loop.append(edge[0])
            edge = nxt[edge]
        loops.append(np.array(loop, np.int64))
    return loops


def cap_holes(vertices: np.ndarray, faces: np.ndarray, loops: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """The surface with each loop closed by a fan from its centroid (a new vertex per hole; triangles only for 3).

    Coplanar holes nested in one another and running opposite ways (a lid
    set in a pot's opening, as the Utah teapot's) are closed together by
    the ring between them (:func:`_rings`): their two fans would overlap
    with opposite orientations in a plane, where no cut is exact.
    """
    v = [np.asarray(vertices, np.float64)]
    new = [np.asarray(faces, np.int64)]
    rings, inside = _rings(v[0], loops)
    new.extend(rings)
    n = len(vertices)
    for k, loop in enumerate(loops):
        if k in inside:
            continue
        nxt = np.roll(loop, -1)
        if len(loop) == 3:
            new.append(loop[::-1][None, :])
            continue
        v.append(v[0][loop].mean(axis=0)[None, :])
        new.append(np.column_stack([nxt, loop, np.full(len(loop), n)]))  # v -> u against the faces' u -> v
        n += 1
    return np.vstack(v), np.vstack(new)


def _rings(vertices: np.ndarray, loops: list[np.ndarray]) -> tuple[list[np.ndarray], set[int]]:
    """Triangles of the rings between coplanar loops nested the opposite way, and the loops they close.

    Each ring is the outer loop's polygon less the loops within it, in the
    loops' common plane (to the coordinates' accuracy, at least ``1e-9`` of
    the mesh's size), triangulated by shapely's constrained Delaunay
    triangulation (no new vertices) and oriented as the outer loop's cap.
    """
    import shapely

    from medialaxis.mesh.solid.degenerate import coordinate_accuracy

    size = float(np.linalg.norm(np.ptp(vertices, axis=0))) or 1.0
    tol = max(1e-9 * size, coordinate_accuracy(vertices))
    planes = []
    for loop in loops:
        points = vertices[loop]
        centre = points.mean(axis=0)
        _, spread, axes = np.linalg.svd(points - centre, full_matrices=False)
        flat = len(loop) > 3 and spread[2] / np.sqrt(len(loop)) <= tol
        planes.append((centre, axes, flat, points.min(axis=0) - tol, points.max(axis=0) + tol))
    out: list[np.ndarray] = []
    closed: set[int] = set()
    for k, (centre, axes, flat, low, high) in enumerate(planes):
        if not flat or k in closed:
            continue
        normal, frame = axes[2], axes[:2].T
        outer = shapely.Polygon((vertices[loops[k]] - centre) @ frame)
        coplanar = [j for j, (c, a, f, lo, hi) in enumerate(planes)
                    if j != k and f and j not in closed and np.all(lo >= low) and np.all(hi <= high)
                    and np.linalg.norm(np.cross(a[2], normal)) <= 10 * tol / size and abs((c - centre) @ normal) <= tol]
        inner = {j: shapely.Polygon((vertices[loops[j]] - centre) @ frame) for j in coplanar}
        within = [j for j, p in inner.items() if outer.is_valid and p.is_valid and p.within(outer)
                  and shapely.is_ccw(p.exterior) != shapely.is_ccw(outer.exterior)]
        if not within:
            continue
        ring = shapely.Polygon(outer.exterior, [inner[j].exterior for j in within])
        corners = np.concatenate([loops[j] for j in [k, *within]])
        index = {tuple(xy): int(i) for xy, i in zip((vertices[corners] - centre) @ frame, corners)}
        try:
            triangles = np.array([[index[tuple(xy)] for xy in np.asarray(t.exterior.coords)[:3]]
                                  for t in shapely.constrained_delaunay_triangles(ring).geoms], np.int64)
        except KeyError:  # a point the triangulation moved: fans instead
            continue
        u, w, x = (vertices[triangles[:, i]] for i in range(3))
        along = np.cross(w - u, x - u) @ normal
        flip = (along > 0) == shapely.is_ccw(outer.exterior)  # the cap runs against its loop
        triangles[flip] = triangles[flip][:, ::-1]
        out.append(triangles)
        closed.update([k, *within])
    return out, closed


def undecided_share(vertices: np.ndarray, faces: np.ndarray, capped_vertices: np.ndarray, capped_faces: np.ndarray,
                    points: int = 1024, seed: int = 0) -> float:
    """Share of the capped solid where the open surface's winding number is undecided (within ``UNDECIDED`` of 1/2).

    The generalized winding number of an open surface is close to 1 inside
    and 0 outside away from its holes, so the solid ``w >= 1/2`` is defined
    and the caps only close it; where the holes are most of the boundary (an
    open sheet, a shell without its bottom) ``w`` stays near 1/2 throughout
    and no solid is defined (Jacobson, Kavan, Sorkine-Hornung 2013, above).
    Measured at quasi-random points of the bounding box inside the capped
    surface (Sobol, scrambled with ``seed``): ``w_open = w_capped - w_caps``.
    """
    from scipy.stats import qmc

    from medialaxis.mesh.solid.crossings import winding_numbers

    v = np.asarray(capped_vertices, np.float64)
    pad = 0.01 * float(np.linalg.norm(np.ptp(v, axis=0)))  # a flat mesh's box has a side of zero
    sample = qmc.scale(qmc.Sobol(3, seed=seed).random(points), v.min(axis=0) - pad, v.max(axis=0) + pad)
    opened = winding_numbers(sample, np.asarray(vertices, np.float64)[np.asarray(faces)])
    caps = winding_numbers(sample, v[np.asarray(capped_faces)[len(faces):]])
    whole = opened + caps
    decided = whole[np.abs(whole) >= 0.5]
    if not decided.size:
        return 1.0
    sign = 1.0 if np.median(decided) > 0 else -1.0  # an inward-wound surface: -1 inside
    inside = sign * whole >= 0.5
    return float(np.mean(np.abs(sign * opened[inside] - 0.5) < UNDECIDED))
