"""Repairs of the sub-sampled mid-surface mesh: folds, double quads, notches and small holes."""

from __future__ import annotations

import itertools

import numpy as np

__all__ = ["repair_faces", "edge_counts", "SMALL_HOLE_EDGES"]


def edge_counts(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(f, 3) number of faces on each face's edges, and the edge keys."""
    e = np.sort(np.stack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]], axis=1), axis=2)  # (f, 3, 2)
    flat = e.reshape(-1, 2)
    _, inverse, count = np.unique(flat, axis=0, return_inverse=True, return_counts=True)
    return count[inverse.ravel()].reshape(-1, 3), e


#: Holes bounded by at most this many edges are closed (where a sheet bends
#: sharply, its Voronoi regions can miss a few triangles); free edges of a
#: part are far longer loops at the sampling density.
SMALL_HOLE_EDGES = 8


def _close_small_holes(faces: np.ndarray, points: np.ndarray, max_edges: int = SMALL_HOLE_EDGES) -> np.ndarray:
    """Close holes bounded by at most ``max_edges`` edges (shortest diagonals first).

    A hole is a cycle of boundary edges, or a path of boundary edges whose
    ends are joined by an edge of the mesh (a notch beside a junction edge).
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    count, e = edge_counts(faces)
    single = e[count == 1]
    if len(single) == 0:
        return faces
    n = int(faces.max()) + 1
    graph = coo_matrix((np.ones(len(single)), (single[:, 0], single[:, 1])), shape=(n, n))
    _, comp = connected_components(graph, directed=False)
    size = np.bincount(comp[single[:, 0]], minlength=n)
    existing = {tuple(x) for x in np.sort(e.reshape(-1, 2), axis=1).tolist()}
    new: list[list[int]] = []
    for c in np.flatnonzero((size >= 2) & (size <= max_edges)):
        edges = single[comp[single[:, 0]] == c]
        verts, deg = np.unique(edges, return_counts=True)
        if np.all(deg == 2):  # a cycle
            cycle = _walk(edges, int(verts[0]))
        elif np.all(deg % 2 == 0):  # cycles touching at a vertex (a pinched hole): each closed
            for loop in _loops(edges):
                new += _ear_triangles(loop, points)
            continue
        elif (deg == 1).sum() == 2 and np.all(deg <= 2):  # a path
            a, b = verts[deg == 1]
            if (min(a, b), max(a, b)) not in existing:
                continue
            cycle = _walk(edges, int(a))
        else:
            continue
        new += _ear_triangles(cycle, points)
    if not new:
        return faces
    return np.unique(np.concatenate([faces, np.sort(np.array(new, np.int64), axis=1)]), axis=0)


def _loops(edges: np.ndarray) -> list[list[int]]:
    """Simple cycles of an edge set whose vertices all have even degree (cut where a walk comes back)."""
    nbrs: dict[int, list[int]] = {}
    for a, b in edges.tolist():
        nbrs.setdefault(a, []).append(b)
        nbrs.setdefault(b, []).append(a)
    out: list[list[int]] = []
    for start in sorted(nbrs):
        path = [start]
        while nbrs[path[-1]]:
            cur = path[-1]
            nxt = nbrs[cur].pop(0)
            nbrs[nxt].remove(cur)
            if nxt in path:  # a cycle closes: cut it off the path
                k = path.index(nxt)
                out.append(path[k:])
                del path[k + 1:]
            else:
                path.append(nxt)
    return [loop for loop in out if len(loop) >= 3]


def _walk(edges: np.ndarray, start: int) -> list[int]:
    """Vertices of a path or cycle of edges in order, from ``start``."""
    nbrs: dict[int, list[int]] = {}
    for a, b in edges.tolist():
        nbrs.setdefault(a, []).append(b)
        nbrs.setdefault(b, []).append(a)
    order, prev, cur = [start], -1, start
    while True:
        nxt = [v for v in nbrs[cur] if v != prev]
        if not nxt or nxt[0] == start:
            return order
        prev, cur = cur, nxt[0]
        order.append(cur)


def _line_path(line_nbrs: dict[int, list[int]], a: int, b: int, max_hops: int) -> list[int] | None:
    """Vertices from ``a`` to ``b`` along junction edges (at most ``max_hops``), or None."""
    previous = {a: a}
    frontier = [a]
    for _ in range(max_hops):
        nxt = []
        for v in frontier:
            for w in line_nbrs.get(v, []):
                if w not in previous:
                    previous[w] = v
                    nxt.append(w)
        frontier = nxt
        if b in previous:
            path = [b]
            while path[-1] != a:
                path.append(previous[path[-1]])
            return path[::-1]
    return None


def _close_junction_notches(faces: np.ndarray, junction: np.ndarray, points: np.ndarray,
                            max_edges: int = 8, max_hops: int = 3, free: np.ndarray | None = None) -> np.ndarray:
    """Close the notches of a sheet beside its junction edges.

    Where a sheet misses the triangles along a junction line, a path of
    boundary edges runs from one junction vertex ``a`` through sheet vertices
    to another ``b`` at most ``max_hops`` junction edges along the line. Each
    such path of at most ``max_edges`` edges, with the line from ``b`` back
    to ``a``, bounds a hole: it is triangulated by cutting off the ear with
    the shortest diagonal first. Paths through ``free`` vertices (the part's
    free edges, at a line's end) are left to :func:`_close_line_ends`.
    """
    count, e = edge_counts(faces)
    single = e[count == 1]
    if len(single) == 0:
        return faces
    if free is None:
        free = np.zeros(len(junction), bool)
    nbrs: dict[int, list[int]] = {}
    for a, b in single.tolist():
        nbrs.setdefault(a, []).append(b)
        nbrs.setdefault(b, []).append(a)
    edges = np.unique(e.reshape(-1, 2), axis=0)
    line_nbrs: dict[int, list[int]] = {}
    for a, b in edges[junction[edges[:, 0]] & junction[edges[:, 1]]].tolist():
        line_nbrs.setdefault(a, []).append(b)
        line_nbrs.setdefault(b, []).append(a)
    seen: set[frozenset[int]] = set()
    new: list[list[int]] = []
    for start in line_nbrs:
        for first in nbrs.get(start, []):
            path, prev, cur = [start], start, first
            while len(path) <= max_edges and not junction[cur]:
                path.append(cur)
                ahead = [v for v in nbrs.get(cur, []) if v != prev]
                if len(ahead) != 1:
                    break
                prev, cur = cur, ahead[0]
            if not junction[cur] or cur == start or len(path) < 2 or frozenset(path[1:]) in seen \
                    or free[path[1:]].any():
                continue
            back = _line_path(line_nbrs, cur, start, max_hops)
            if back is None:
                continue
            seen.add(frozenset(path[1:]))
            new += _ear_triangles(path + back[:-1], points)
    if not new:
        return faces
    return np.unique(np.concatenate([faces, np.sort(np.array(new, np.int64), axis=1)]), axis=0)


def _drop_double_quads(faces: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Where a quad is covered by both of its splits (four faces on four
    vertices, a flat tetrahedron), keep the split across the shorter diagonal."""
    count, e = edge_counts(faces)
    if not (count >= 3).any():
        return faces
    present = {tuple(f) for f in faces.tolist()}
    index = {f: i for i, f in enumerate(map(tuple, faces.tolist()))}
    # faces on each edge: the edge keys sorted once, each edge's faces a run in that order
    n = int(faces.max()) + 1
    keys = (e[..., 0].astype(np.int64) * n + e[..., 1]).ravel()
    order = np.argsort(keys, kind="stable")
    sorted_keys = keys[order]
    owner = order // 3
    drop: set[int] = set()
    for i in np.flatnonzero((count >= 3).any(axis=1)):
        for a, b in itertools.combinations(faces[i].tolist(), 2):
            key = min(a, b) * n + max(a, b)
            lo, hi = np.searchsorted(sorted_keys, key, side="left"), np.searchsorted(sorted_keys, key, side="right")
            for other in np.sort(owner[lo:hi]).tolist():
                quad = sorted(set(faces[i].tolist()) | set(faces[other].tolist()))
                if len(quad) != 4:
                    continue
                tris = [tuple(t) for t in itertools.combinations(quad, 3)]
                if not all(t in present for t in tris):
                    continue
                # any two opposite edges of the flat tetrahedron are the
                # diagonals of one split: drop the faces on the longest edge
                longest = max(itertools.combinations(quad, 2),
                              key=lambda pq: float(np.linalg.norm(points[pq[0]] - points[pq[1]])))
                drop.update(index[t] for t in tris if longest[0] in t and longest[1] in t)
    if not drop:
        return faces
    keep = np.ones(len(faces), bool)
    keep[list(drop)] = False
    return faces[keep]


def _ear_triangles(polygon: list[int], points: np.ndarray) -> list[list[int]]:
    """Triangles of a small closed polygon, shortest diagonals first."""
    poly = list(polygon)
    out = []
    while len(poly) > 3:
        k = len(poly)
        diag = [float(np.linalg.norm(points[poly[i - 1]] - points[poly[(i + 1) % k]])) for i in range(k)]
        i = int(np.argmin(diag))
        out.append([poly[i - 1], poly[i], poly[(i + 1) % k]])
        del poly[i]
    out.append(poly)
    return out


def _close_line_ends(faces: np.ndarray, junction: np.ndarray, free: np.ndarray, points: np.ndarray,
                     max_edges: int = 6) -> np.ndarray:
    """Join the last junction vertex of a line to a sheet that stops short of it.

    At the end of a junction line ``(..., n, e)`` a sheet may hold triangles
    up to ``n`` only: its boundary runs from ``n`` through sheet vertices to
    its free edge, and leaves a notch beside the line's last edge. When that
    path (at most ``max_edges`` edges, ending at the first free-edge vertex)
    shares no face with ``e``, it is fanned to ``e``.
    """
    count, e = edge_counts(faces)
    single = e[count == 1]
    if len(single) == 0:
        return faces
    nbrs: dict[int, list[int]] = {}
    for a, b in single.tolist():
        nbrs.setdefault(a, []).append(b)
        nbrs.setdefault(b, []).append(a)
    edges = np.unique(e.reshape(-1, 2), axis=0)
    line = edges[junction[edges[:, 0]] & junction[edges[:, 1]]]
    ends = np.concatenate([line, line[:, ::-1]])
    degree = np.bincount(ends[:, 0], minlength=len(points))
    touching: dict[int, set[int]] = {}
    for f in faces.tolist():
        for v in f:
            touching.setdefault(v, set()).update(f)
    new: list[list[int]] = []
    for end, inner in ends[degree[ends[:, 0]] == 1].tolist():
        for first in nbrs.get(inner, []):
            path, prev, cur = [inner], inner, first
            while len(path) <= max_edges and not junction[cur]:
                path.append(cur)
                if free[cur]:
                    break
                ahead = [v for v in nbrs.get(cur, []) if v != prev]
                if len(ahead) != 1:
                    break
                prev, cur = cur, ahead[0]
            if len(path) < 2 or not free[path[-1]] or touching.get(end, set()) & set(path[1:]):
                continue
            new += [[end, path[i], path[i + 1]] for i in range(len(path) - 1)]
    if not new:
        return faces
    return np.unique(np.concatenate([faces, np.sort(np.array(new, np.int64), axis=1)]), axis=0)


def _close_boundary_triangles(faces: np.ndarray) -> np.ndarray:
    """Add the missing face of every three boundary edges that form a triangle
    (a three-edge hole, also where it touches others at a pinched vertex)."""
    count, e = edge_counts(faces)
    single = e[count == 1]
    nbrs: dict[int, set[int]] = {}
    for a, b in single.tolist():
        nbrs.setdefault(a, set()).add(b)
        nbrs.setdefault(b, set()).add(a)
    present = {tuple(f) for f in faces.tolist()}
    new = set()
    for a, b in single.tolist():
        for c in nbrs[a] & nbrs[b]:
            tri = tuple(sorted((a, b, c)))
            if tri not in present:
                new.add(tri)
    if not new:
        return faces
    return np.unique(np.concatenate([faces, np.array(sorted(new), np.int64)]), axis=0)


def repair_faces(faces: np.ndarray, junction: np.ndarray, points: np.ndarray | None = None,
                 rounds: int = 4, free: np.ndarray | None = None) -> np.ndarray:
    """Remove folded and surplus triangles and close small holes.

    1. Where neighbouring blocks split the same degenerate quad across both
       diagonals, one extra triangle lies over the others: it has an edge with
       three faces that is not a junction edge (both ends junction vertices)
       and an edge with only one. Such triangles are dropped.
    2. Quads covered by both splits lose the two faces on their longest
       edge; notches beside junction lines (a path of at most eight boundary
       edges between two junction vertices up to three junction edges apart)
       are closed, so every sheet at a junction line has triangles on each
       of its edges.
    3. With ``free`` (free-edge vertices): a sheet that stops one edge short
       of a junction line's end is fanned to that end (:func:`_close_line_ends`).
    4. Holes bounded by at most ``SMALL_HOLE_EDGES`` edges (or a notch of
       boundary edges against an edge), and any three boundary edges forming
       a triangle, are closed.

    Parameters
    ----------
    faces : (f, 3) int64 ndarray
    junction : (v,) bool ndarray
        Junction vertices (their shared edges may carry three or more faces).
    points : (v, 3) float64 ndarray, optional
    free : (v,) bool ndarray, optional

    Returns
    -------
    (g, 3) int64 ndarray
        Sorted, unique faces.
    """
    faces = np.unique(np.sort(np.asarray(faces, np.int64), axis=1), axis=0)
    for _ in range(rounds):
        if len(faces) == 0:
            break
        count, e = edge_counts(faces)
        junction_edge = junction[e[..., 0]] & junction[e[..., 1]]
        folded = ((count >= 3) & ~junction_edge).any(axis=1) & (count == 1).any(axis=1)
        if not folded.any():
            break
        faces = faces[~folded]
    if len(faces):
        where = points if points is not None else np.zeros((int(faces.max()) + 1, 3))
        faces = _drop_double_quads(faces, where)
        faces = _close_junction_notches(faces, junction, where, free=free)
        if free is not None:
            faces = _close_line_ends(faces, junction, np.asarray(free, bool), where)
        faces = _close_small_holes(faces, where)
        faces = _close_boundary_triangles(faces)
    return faces
