"""Sub-sampling polygonization of medial voxels (Michikawa and Suzuki, 2013).

1. Classify medial voxels as junction, boundary or surface by counting the
   background components around them (Malandain).
2. Pick representatives in the order junction, crease, boundary, surface,
   each pick removing the medial voxels within its sampling radius.
3. Split the medial voxels into sheets that meet at the junction voxels
   (:func:`sheet_ids`). Split the junction voxels between the junction
   picks along the lines, then grow the picks' discrete Voronoi regions
   over each sheet from its own picks and from all junction voxels
   (:func:`~medialaxis.volume._kernels.sheet_labels`): regions never cross
   from one sheet to another, and every sheet at a junction line sees the
   same chain of junction regions.
4. A triangle joins three picks whose regions meet in one 2x2x2 block of
   voxels of one sheet (plus junction voxels) and touch pairwise; four
   regions meeting without diagonals (a degenerate Voronoi vertex) give two
   triangles across the shorter diagonal. Junction edges are shared by the
   triangles of all sheets at the line (three at a T, four at an X).
5. Repairs (:func:`repair_faces`): folded and doubly split quads go; the
   notches a sheet leaves beside a junction line, at a line's end, and
   small holes are closed.
"""

from __future__ import annotations

import dataclasses
import itertools
from typing import Any

import numpy as np

from medialaxis.volume import _kernels
from medialaxis.volume.distance import Features, Grid
from medialaxis.volume.medial import MedialVoxels
from medialaxis.volume.voxel_table import VoxelTable, table_lookup, voxel_table

__all__ = ["SURFACE", "BOUNDARY", "JUNCTION", "EXTENSION", "Polygonization", "classify_voxels", "polygonize"]

#: Junction picks are this many local radii apart (sparser than the sheets:
#: larger junction regions keep the regions of different sheets apart).
JUNCTION_SPACING = 1.5

#: Vertex / voxel classes.
SURFACE, BOUNDARY, JUNCTION, EXTENSION = 0, 1, 2, 3


@dataclasses.dataclass(frozen=True)
class Polygonization:
    """A triangle mesh over picked medial voxels.

    Attributes
    ----------
    picks : (v,) int64 ndarray
        Rows of the medial voxels used as vertices.
    points : (v, 3) float64 ndarray
    radii : (v,) float64 ndarray
    kind : (v,) int8 ndarray
        ``SURFACE``, ``BOUNDARY`` or ``JUNCTION``.
    faces : (f, 3) int64 ndarray
    voxel_kind : (n,) int8 ndarray
        Class of every medial voxel.
    voxel_label : (n,) int64 ndarray
        Voronoi region (vertex index) of every medial voxel.
    """

    picks: np.ndarray
    points: np.ndarray
    radii: np.ndarray
    kind: np.ndarray
    faces: np.ndarray
    voxel_kind: np.ndarray
    voxel_label: np.ndarray


def classify_voxels(table: VoxelTable, voxels: np.ndarray) -> np.ndarray:
    """Junction / boundary / surface class of each voxel of a thin sheet.

    Parameters
    ----------
    table : VoxelTable
        The sheet (:func:`~medialaxis.volume.voxel_table.voxel_table`).
    voxels : (n, 3) int64 ndarray
        Indices of the sheet voxels.

    Returns
    -------
    (n,) int8 ndarray
        ``JUNCTION`` (three or more background components around the voxel),
        ``BOUNDARY`` (at most one) or ``SURFACE`` (two).
    """
    count = _kernels.topology_class(*table, np.ascontiguousarray(voxels, np.int64), _kernels.N26_OFFSETS,
                                    _kernels.N26_ADJ, _kernels.N26_FACE)
    kind = np.full(len(voxels), SURFACE, np.int8)
    kind[count <= 1] = BOUNDARY
    kind[count >= 3] = JUNCTION
    return kind


#: Surface voxels whose pair directions disagree this much (mean direction
#: shorter than this) lie on a crease and are sampled before the others.
CREASE_COHERENCE = 0.9


def _pair_keys(a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    return lo.astype(np.int64) * n + hi


def _region_edges(table: VoxelTable, voxels: np.ndarray, label: np.ndarray, n: int,
                  sheet: np.ndarray | None = None) -> np.ndarray:
    """Sorted unique keys of label pairs that are 6-adjacent (share a voxel face) somewhere.

    With ``sheet`` (sheet of each voxel, -1 junction), only pairs in one
    sheet, or with a junction voxel, count.
    """
    keys = []
    for axis in range(3):
        step = np.zeros(3, np.int64)
        step[axis] = 1
        j = table_lookup(table, voxels + step)
        i = np.flatnonzero(j >= 0)
        j = j[i]
        a, b = label[i], label[j]
        touch = (a >= 0) & (b >= 0) & (a != b)
        if sheet is not None:
            sa, sb = sheet[i], sheet[j]
            touch &= (sa == sb) | (sa == -1) | (sb == -1)
        keys.append(_pair_keys(a[touch], b[touch], n))
    return np.unique(np.concatenate(keys))


def _has(keys: np.ndarray, query: np.ndarray) -> np.ndarray:
    pos = np.searchsorted(keys, query)
    pos = np.minimum(pos, len(keys) - 1)
    return keys[pos] == query if len(keys) else np.zeros(len(query), bool)


#: Medial voxels whose 2x2x2 blocks are labelled at a time (bounds the memory of a large sheet).
BLOCK_BATCH = 250_000


def _block_labels(table: VoxelTable, voxels: np.ndarray, label: np.ndarray,
                  sheet: np.ndarray | None = None) -> np.ndarray:
    """Sorted labels (-1 padded) of the 2x2x2 blocks that hold three or more regions (Voronoi vertices).

    With ``sheet`` (sheet of each voxel, -1 junction), a block gives one row
    per sheet in it, with the labels of that sheet's voxels and of the
    junction voxels; blocks of junction voxels only give none. Regions of
    two sheets thus never form a triangle. The voxels are taken
    ``BLOCK_BATCH`` at a time: a block may come once per batch (the
    triangles are made unique afterwards).
    """
    out = [np.zeros((0, 8), np.int64)]
    for start in range(0, len(voxels), BLOCK_BATCH):
        labels = _batch_labels(table, voxels[start:start + BLOCK_BATCH], label, sheet)
        out.append(labels[(labels >= 0).sum(axis=1) >= 3])
    return np.concatenate(out)


def _batch_labels(table: VoxelTable, voxels: np.ndarray, label: np.ndarray, sheet: np.ndarray | None) -> np.ndarray:
    corners = np.array(list(itertools.product((0, 1), repeat=3)), np.int64)
    origins = (voxels[:, None, :] - corners[None, :, :]).reshape(-1, 3)
    shape = table.shape
    origins = origins[np.all((origins >= 0) & (origins < shape - 1), axis=1)]
    flat = np.unique(np.ravel_multi_index(origins.T, tuple(shape)))
    origins = np.stack(np.unravel_index(flat, tuple(shape)), axis=1)
    cells = origins[:, None, :] + corners[None, :, :]
    rows = table_lookup(table, cells.reshape(-1, 3)).reshape(-1, 8)
    present = rows >= 0
    labels = np.where(present, label[rows], -1)
    if sheet is not None:
        sheets = np.where(present, sheet[rows], -2)
        real = sheets >= 0
        top = np.where(real, sheets, -1).max(axis=1)
        bottom = np.where(real, sheets, np.iinfo(sheets.dtype).max).min(axis=1)
        mixed = np.flatnonzero((top >= 0) & (top != bottom))
        # one row per (block, sheet) of the blocks that hold several sheets,
        # in block then sheet order
        block, slot = np.nonzero(real[mixed])
        pairs = np.unique(np.stack([mixed[block], sheets[mixed[block], slot]], axis=1), axis=0)
        b, one = pairs[:, 0], pairs[:, 1]
        keep = (sheets[b] == one[:, None]) | (sheets[b] == -1)
        labels = np.concatenate([labels[(top >= 0) & (top == bottom)], np.where(keep, labels[b], -1)])
    labels.sort(axis=1)
    # blank repeated labels so each row lists its distinct labels
    labels[:, 1:][labels[:, 1:] == labels[:, :-1]] = -1
    labels.sort(axis=1)
    return labels


def _split_quad(labs: np.ndarray, points: np.ndarray, edges: np.ndarray, n: int) -> list[tuple[int, int, int]]:
    """Two triangles for four regions meeting at one degenerate Voronoi vertex.

    Regions that share a voxel face are sides of the quad; the diagonals are
    the two pairs that only touch at the vertex. A diagonal that is a region
    edge elsewhere is used; otherwise the shorter diagonal.
    """
    pairings = [((0, 1), (2, 3)), ((0, 2), (1, 3)), ((0, 3), (1, 2))]

    def side(i: int, j: int) -> bool:
        return bool(_has(edges, _pair_keys(np.array([labs[i]]), np.array([labs[j]]), n))[0])

    def length(i: int, j: int) -> float:
        return float(np.linalg.norm(points[labs[i]] - points[labs[j]]))

    sides = [sum(side(*e) for e in pairing) for pairing in pairings]
    candidates = [k for k in range(3) if sides[k] < 2] or [int(np.argmax([length(*a) + length(*b) for a, b in pairings]))]
    k = min(candidates, key=lambda c: (sides[c] == 0 and len(candidates) > 1, sum(length(*e) for e in pairings[c])))
    (a, b), (c, d) = pairings[k]
    if side(c, d) and not side(a, b):
        (a, b), (c, d) = (c, d), (a, b)
    elif side(a, b) == side(c, d) and length(c, d) < length(a, b):
        (a, b), (c, d) = (c, d), (a, b)
    la, lb, lc, ld = (int(labs[i]) for i in (a, b, c, d))
    return [(la, lb, lc), (la, lb, ld)]


def _triangles(table: VoxelTable, voxels: np.ndarray, label: np.ndarray, points: np.ndarray,
               sheet: np.ndarray | None = None) -> np.ndarray:
    n = len(points)
    edges = _region_edges(table, voxels, label, n, sheet)
    blocks = _block_labels(table, voxels, label, sheet)
    distinct = (blocks >= 0).sum(axis=1)
    faces = [blocks[distinct == 3][:, -3:].astype(np.int64)]
    extra: list[tuple[int, int, int]] = []
    for row in np.unique(blocks[distinct >= 4], axis=0):
        labs = row[row >= 0]
        if len(labs) == 4:
            extra.extend(_split_quad(labs, points, edges, n))
        else:  # five or more regions at one vertex: triangles of face-adjacent triples
            for c in itertools.combinations(labs.tolist(), 3):
                ks = _pair_keys(np.array([c[0], c[0], c[1]]), np.array([c[1], c[2], c[2]]), n)
                if _has(edges, ks).all():
                    extra.append(c)
    if extra:
        faces.append(np.array(extra, np.int64).reshape(-1, 3))
    out = np.sort(np.concatenate(faces), axis=1)
    return np.unique(out, axis=0) if len(out) else out.reshape(0, 3)


def _edge_counts(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(f, 3) number of faces on each face's edges, and the edge keys."""
    e = np.sort(np.stack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]], axis=1), axis=2)  # (f, 3, 2)
    flat = e.reshape(-1, 2)
    _, inverse, count = np.unique(flat, axis=0, return_inverse=True, return_counts=True)
    return count[inverse.ravel()].reshape(-1, 3), e


def _drop_surplus(faces: np.ndarray, junction: np.ndarray, points: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """On edges from a junction vertex to a sheet vertex with three or more
    faces, keep the two faces closest to the sheet's plane (the others bridge
    to another sheet across the junction's corner)."""
    from medialaxis.volume.dents import face_normals

    count, e = _edge_counts(faces)
    end_j = junction[e[..., 0]] ^ junction[e[..., 1]]  # exactly one end is a junction vertex
    over = (count >= 3) & end_j
    if not over.any():
        return faces
    fid, slot = np.nonzero(over)
    edge = e[fid, slot]
    sheet_vertex = np.where(junction[edge[:, 0]], edge[:, 1], edge[:, 0])
    fit = np.abs(np.einsum("ij,ij->i", face_normals(points, faces)[fid], normal[sheet_vertex]))
    key = edge[:, 0].astype(np.int64) * (int(faces.max()) + 1) + edge[:, 1]
    order = np.lexsort((-fit, key))  # per edge, best-fitting faces first
    key, fid = key[order], fid[order]
    rank = np.arange(len(key)) - np.searchsorted(key, key)
    drop = np.zeros(len(faces), bool)
    drop[fid[rank >= 2]] = True
    return faces[~drop]


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

    count, e = _edge_counts(faces)
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
    count, e = _edge_counts(faces)
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
    count, e = _edge_counts(faces)
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
    count, e = _edge_counts(faces)
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
    count, e = _edge_counts(faces)
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
                 normal: np.ndarray | None = None, rounds: int = 4, free: np.ndarray | None = None) -> np.ndarray:
    """Remove folded and surplus triangles and close small holes.

    1. Where neighbouring blocks split the same degenerate quad across both
       diagonals, one extra triangle lies over the others: it has an edge with
       three faces that is not a junction edge (both ends junction vertices)
       and an edge with only one. Such triangles are dropped.
    2. With ``points`` and ``normal`` (vertex sheet normals): on edges from a
       junction vertex to a sheet vertex with three or more faces, only the
       two faces closest to that sheet's plane stay.
    3. Quads covered by both splits lose the two faces on their longest
       edge; notches beside junction lines (a path of at most eight boundary
       edges between two junction vertices up to three junction edges apart)
       are closed, so every sheet at a junction line has triangles on each
       of its edges.
    4. With ``free`` (free-edge vertices): a sheet that stops one edge short
       of a junction line's end is fanned to that end (:func:`_close_line_ends`).
    5. Holes bounded by at most ``SMALL_HOLE_EDGES`` edges (or a notch of
       boundary edges against an edge), and any three boundary edges forming
       a triangle, are closed.

    Parameters
    ----------
    faces : (f, 3) int64 ndarray
    junction : (v,) bool ndarray
        Junction vertices (their shared edges may carry three or more faces).
    points : (v, 3) float64 ndarray, optional
    normal : (v, 3) float64 ndarray, optional

    Returns
    -------
    (g, 3) int64 ndarray
        Sorted, unique faces.
    """
    faces = np.unique(np.sort(np.asarray(faces, np.int64), axis=1), axis=0)
    for _ in range(rounds):
        if len(faces) == 0:
            break
        count, e = _edge_counts(faces)
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


#: Medial voxels closer than this (voxels) to a junction voxel do not join
#: sheets: near a junction the sheets touch one another diagonally.
SHEET_SEPARATION = 3.0

#: Sheets of fewer voxels are noise: their voxels join the nearest sheet.
MIN_SHEET_VOXELS = 20


def sheet_ids(table: VoxelTable, voxels: np.ndarray, junction: np.ndarray, spacing: np.ndarray) -> np.ndarray:
    """Split the medial voxels into sheets that meet at junction voxels.

    Voxels farther than ``SHEET_SEPARATION`` voxels from every junction voxel
    form sheets by 26-connectivity; the voxels near the junctions then join
    the sheet they are geodesically nearest to (never through a junction
    voxel).

    Parameters
    ----------
    table : VoxelTable
        Row of each medial voxel.
    voxels : (n, 3) int64 ndarray
    junction : (n,) bool ndarray
    spacing : (3,) float64 ndarray

    Returns
    -------
    (n,) int64 ndarray
        Sheet number, -1 for junction voxels.
    """
    from scipy.spatial import cKDTree

    n = len(voxels)
    if not junction.any():
        free = np.ones(n, bool)
    else:
        near, _ = cKDTree(voxels[junction]).query(voxels, k=1, distance_upper_bound=SHEET_SEPARATION + 1e-9)
        free = ~np.isfinite(near) | (near > SHEET_SEPARATION)
    # components numbered by their smallest row (the order of scipy's connected_components)
    comp = _kernels.neighbour_components(*table, voxels, free, _kernels.OFFSETS_26[:13])
    size = np.bincount(comp[free], minlength=n)
    core = free & (size[comp] >= MIN_SHEET_VOXELS)
    if not core.any():
        return np.where(junction, -1, 0).astype(np.int64)
    _, sheet = np.unique(comp[core], return_inverse=True)
    seeds = np.flatnonzero(core)
    grow = np.where(junction, -1, 0).astype(np.int64)
    out = _kernels.sheet_labels(*table, voxels, seeds, sheet.astype(np.int64), grow, _kernels.OFFSETS_26, spacing)
    out[junction] = -1
    out[(out < 0) & ~junction] = 0 if len(seeds) else -1  # cut off from every sheet: rare specks
    return out


def _labels(table: VoxelTable, voxels: np.ndarray, picks: np.ndarray, junction: np.ndarray, sheet: np.ndarray,
            spacing: np.ndarray) -> np.ndarray:
    """Vertex (pick number) of every medial voxel: Voronoi regions kept inside sheets.

    The junction voxels are first split between the junction picks along
    the junction lines; then they, with the other picks, grow regions into
    the sheets. Every sheet at a junction line thus sees the same chain of
    junction regions, and their triangles share the junction edges.
    """
    from scipy.spatial import cKDTree

    on_line = np.where(junction, 0, -1).astype(np.int64)
    vertex = np.arange(len(picks), dtype=np.int64)
    at_junction = junction[picks]
    jlabel = _kernels.sheet_labels(*table, voxels, picks[at_junction], vertex[at_junction], on_line,
                                   _kernels.OFFSETS_26, spacing)
    lost = junction & (jlabel < 0)
    if lost.any() and at_junction.any():  # junction voxels cut off from every junction pick
        _, nearest = cKDTree(voxels[picks[at_junction]] * spacing).query(voxels[lost] * spacing, k=1)
        jlabel[lost] = vertex[at_junction][nearest]
    rows = np.flatnonzero(junction & (jlabel >= 0))
    seeds = np.concatenate([rows, picks[~at_junction]]).astype(np.int64)
    seed_label = np.concatenate([jlabel[rows], vertex[~at_junction]]).astype(np.int64)
    return _kernels.sheet_labels(*table, voxels, seeds, seed_label, sheet, _kernels.OFFSETS_26, spacing)


def polygonize(features: Features | Grid, medial: MedialVoxels, *, density: float = 1.0, rng: Any = 0) -> Polygonization:
    """Triangle mesh of the medial voxels by sub-sampling.

    Parameters
    ----------
    features : Features or Grid
        Gives the crop grid of the medial voxels (``shape``, ``spacing``).
    medial : MedialVoxels
    density : float
        Sampling radius in units of the local radius (half thickness); smaller
        gives more vertices. The radius is at least 1.5 voxels.
    rng : seed or numpy Generator
        Order of the picks within a class (results are reproducible for a seed).

    Returns
    -------
    Polygonization
    """
    voxels = np.ascontiguousarray(medial.voxels, np.int64)
    n = len(voxels)
    table = voxel_table(voxels, features.shape)
    kind = classify_voxels(table, voxels)
    # creases (a sheet bending sharply, pairs in two directions) come right
    # after junctions so that vertices sit on the crease line
    crease = (kind == SURFACE) & (medial.coherence < CREASE_COHERENCE)
    priority = np.select([kind == JUNCTION, crease, kind == BOUNDARY], [0, 1, 2], 3)
    # a random order within each class avoids grid-aligned picks, whose Voronoi
    # regions meet four at a time (degenerate vertices)
    order = np.lexsort((np.random.default_rng(rng).permutation(n), priority))
    radius = np.maximum(density * medial.radius, 1.5 * float(features.spacing.max()))
    radius[kind == JUNCTION] *= JUNCTION_SPACING
    picks = _kernels.greedy_subsample(*table, voxels, order, radius, features.spacing)
    junction = kind == JUNCTION
    sheet = sheet_ids(table, voxels, junction, features.spacing)
    label = _labels(table, voxels, picks, junction, sheet, features.spacing)
    points = medial.position[picks]
    vertex_junction = kind[picks] == JUNCTION
    faces = _triangles(table, voxels, label, points, sheet)
    faces = faces[~vertex_junction[faces].all(axis=1)]  # junction lines carry no faces of their own
    faces = repair_faces(faces, vertex_junction, points, medial.normal[picks], free=kind[picks] == BOUNDARY)
    return Polygonization(picks, points, medial.radius[picks], kind[picks], faces, kind, label)
