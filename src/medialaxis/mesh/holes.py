"""Holes of a slightly open mesh closed by caps, so that the solid its winding number defines has a surface.

A mesh with a few missing faces (scans, CAD exports) still encloses a solid:
the generalized winding number stays close to 1 inside and 0 outside away
from the gaps (Jacobson, Kavan, Sorkine-Hornung, "Robust inside-outside
segmentation using generalized winding numbers", ACM Transactions on
Graphics 32(4), 2013, doi:10.1145/2461912.2461916). Each hole (a loop of
edges with one face) is closed by a fan from its centroid, oriented as the
faces around it; where a cap crosses the surface (a hole that is not flat),
:mod:`medialaxis.mesh.arrangement` then keeps the solid's side of it.
"""

from __future__ import annotations

import numpy as np

__all__ = ["boundary_loops", "cap_holes"]


def boundary_loops(faces: np.ndarray) -> list[np.ndarray] | None:
    """Loops of vertices around the holes of a consistently oriented surface, or ``None`` if they do not chain.

    A boundary edge is a directed face edge ``u -> v`` whose reverse no face
    has; around a hole they chain head to tail. ``None`` where a vertex
    starts two boundary edges (two holes touching at a vertex) or an edge
    is used twice in the same direction.
    """
    f = np.asarray(faces, np.int64)
    directed = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    keys = {(int(u), int(v)) for u, v in directed}
    if len(keys) < len(directed):
        return None
    nxt: dict[int, int] = {}
    for u, v in directed:
        if (int(v), int(u)) not in keys:
            if int(u) in nxt:
                return None
            nxt[int(u)] = int(v)
    loops, seen = [], set()
    for start in nxt:
        if start in seen:
            continue
        loop, v = [], start
        while v not in seen:
            seen.add(v)
            loop.append(v)
            if v not in nxt:
                return None
            v = nxt[v]
        if v != start:
            return None
        loops.append(np.array(loop, np.int64))
    return loops


def cap_holes(vertices: np.ndarray, faces: np.ndarray, loops: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """The surface with each loop closed by a fan from its centroid (a new vertex per hole; triangles only for 3)."""
    v = [np.asarray(vertices, np.float64)]
    new = [np.asarray(faces, np.int64)]
    n = len(vertices)
    for loop in loops:
        nxt = np.roll(loop, -1)
        if len(loop) == 3:
            new.append(loop[::-1][None, :])
            continue
        v.append(v[0][loop].mean(axis=0)[None, :])
        new.append(np.column_stack([nxt, loop, np.full(len(loop), n)]))  # v -> u against the faces' u -> v
        n += 1
    return np.vstack(v), np.vstack(new)
