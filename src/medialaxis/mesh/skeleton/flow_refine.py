"""Embedding refinement of a flow skeleton: chain nodes onto the medial axis.

The diffusion flow smooths as it contracts, and smoothing shrinks curved
tubes: the flow stops where the pull towards the inner-ball centres balances
the Laplacian, ``(L + w M) p = w M c``, which is the medial axis moved by
``-(1/w) M^-1 L p`` towards the centre of curvature (a torus of major radius 3
and minor radius 1 came out 0.12 inside its core circle): the "shrinkage" that
Au et al. (2008) correct by an embedding refinement. Tagliasacchi, Alhashim,
Olson, Zhang (Mean Curvature Skeletons. Computer Graphics Forum 31(5) (Proc.
SGP), 1735-1744, 2012) reach centred skeletons with a medial attraction term
in the flow; here the nodes are centred after it, which leaves the flow and
its topology alone (on a 164,000-vertex tripod, 1.5-1.9 s against 1.5 s for
the ring fit alone before).

Each node inside a branch (degree 2) moves within its plane across the branch:

1. to the centre of the circle fitted to the surface vertices in a thin slab
   along that plane, where they form one round ring all around the node (a
   tube: least squares over the whole ring, the most accurate centre);
2. elsewhere, unless it is within ``JUNCTION_CLEARANCE`` junction radii of a
   junction (there the plane meets the hub, and the largest ball leans
   towards it), to the point of the plane farthest from the surface, the
   centre of the largest ball there: the plane meets the medial axis there
   (a tube of radius ``r``: ``r`` minus the distance to the axis, whichever
   way the plane tilts), whatever the shape of the section.

Junctions, tips and fixed nodes stay where the graph put them; the radii are
measured again from the new places.
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.core import graph as _graph
from medialaxis.mesh.skeleton._flow_operators import vertex_normals

__all__ = ["centre_nodes", "node_radii", "surface_samples", "MAX_SHIFT", "MIN_RING", "RING_TOLERANCE",
           "RING_SECTORS", "SLAB", "GRID", "LEVELS", "TIE", "SAMPLE_SPACING", "JUNCTION_CLEARANCE"]

#: Largest move of a node, as a fraction of its radius (a safeguard against
#: stray balls on a coarse or noisy surface).
MAX_SHIFT = 0.5
#: Fewest surface vertices a ring needs (a circle needs three; a handful more
#: keep one stray vertex from deciding).
MIN_RING = 8
#: A ring is round when the spread of its vertices' distances to the fitted
#: centre is at most this fraction of the mean distance ...
RING_TOLERANCE = 0.1
#: ... and its vertices lie in every one of this many equal angular sectors
#: around the centre (an arc on one side fits a circle as well). Sectors, not
#: the mean direction: the slab of a curved tube holds more rings on its inner
#: side than on its outer one.
RING_SECTORS = 8
#: Half-thickness of the slab across a branch whose vertices give a node's
#: ring, as a fraction of its radius.
SLAB = 0.2
#: Points per side of the first square grid searched in a node's plane.
GRID = 7
#: Levels of that search; the second level's grid (3 x 3) spans the first one's step around
#: its best point, each later one half the step before, so the last step is
#: ``MAX_SHIFT / ((GRID - 1) / 2) / 2**(LEVELS - 2)`` radii (0.1% of the radius).
LEVELS = 9
#: Depth differences below this fraction of the node's radius are ties (a plate's
#: ridge, a noisy surface): of the tied points, the one nearest the node wins.
TIE = 0.01
#: Surface samples for the depth are spaced at most this fraction of the median
#: radius apart (the nearest-sample distance then exceeds the distance to the
#: surface by well under 1% of the radius) ...
SAMPLE_SPACING = 0.125
#: ... but there are no more than about this many (the spacing grows instead).
MAX_SAMPLES = 2_000_000
#: The largest-ball search leaves alone the nodes closer to a junction than
#: this many junction radii: there the plane across one branch meets the hub,
#: and the largest ball leans towards it.
JUNCTION_CLEARANCE = 3.0


def centre_nodes(
    points: np.ndarray,
    edges: np.ndarray,
    correspondence: np.ndarray,
    surface: np.ndarray,
    faces: np.ndarray,
    keep: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Move chain nodes, within their plane across the branch, onto the medial axis.

    Parameters
    ----------
    points : (s, 3) float64 ndarray
        Skeleton nodes.
    edges : (e, 2) int64 ndarray
    correspondence : (n,) int64 ndarray
        Node of each surface vertex (-1: none).
    surface : (n, 3) float64 ndarray
        Vertices of the closed surface.
    faces : (k, 3) int64 ndarray
        Its triangles.
    keep : (s,) bool ndarray
        Nodes that must not move (user-fixed points).

    Returns
    -------
    points : (s, 3) float64 ndarray
    radii : (s,) float64 ndarray
        Mean distance from each node to its surface vertices.

    References
    ----------
    .. [1] O. K.-C. Au, C.-L. Tai, H.-K. Chu, D. Cohen-Or, T.-Y. Lee, "Skeleton extraction by
           mesh contraction", ACM Transactions on Graphics 27(3):44, 2008.
           doi:10.1145/1360612.1360643
    .. [2] A. Tagliasacchi, I. Alhashim, M. Olson, H. Zhang, "Mean curvature skeletons",
           Computer Graphics Forum 31(5):1735-1744 (Proc. SGP), 2012.
           doi:10.1111/j.1467-8659.2012.03178.x
    """
    s = len(points)
    out = np.array(points, dtype=np.float64, copy=True)
    radius = node_radii(points, correspondence, surface)
    deg = _graph.degree(s, edges)
    adj = _graph.adjacency(s, edges)
    # two distinct neighbours (a repeated edge or a self-loop also gives degree 2)
    rows = np.flatnonzero((deg == 2) & (np.diff(adj.indptr) == 2) & (radius > 0) & ~np.asarray(keep, bool))
    if len(rows) == 0:
        return out, radius
    # the tangent spans two nodes either side, where the chain goes on
    # (neighbouring nodes can be close and a little off the axis)
    first = adj.indices[adj.indptr[rows]]
    second = adj.indices[adj.indptr[rows] + 1]
    tangent = np.zeros((s, 3))
    tangent[rows] = points[_beyond(adj, deg, first, rows)] - points[_beyond(adj, deg, second, rows)]
    tangent[rows] /= np.maximum(np.linalg.norm(tangent[rows], axis=1, keepdims=True), 1e-300)
    e1, e2 = _plane_basis(tangent)
    offset, round_ring = _ring_offsets(points, tangent, e1, e2, radius, surface, rows)
    length = np.linalg.norm(offset, axis=1)
    scale = np.minimum(1.0, MAX_SHIFT * radius[rows] / np.maximum(length, 1e-300))
    out[rows] += scale[:, None] * offset
    clear = ~round_ring
    for j in np.flatnonzero(deg >= 3):
        clear &= np.linalg.norm(points[rows] - points[j], axis=1) >= JUNCTION_CLEARANCE * radius[j]
    if clear.any():
        rest = rows[clear]
        out[rest] = _largest_balls(points[rest], e1[rest], e2[rest], radius[rest], surface, faces)
    return out, node_radii(out, correspondence, surface)


def _ring_offsets(points: np.ndarray, tangent: np.ndarray, e1: np.ndarray, e2: np.ndarray, radius: np.ndarray,
                  surface: np.ndarray, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Move ``(r, 3)`` of each node of ``rows`` to the centre of its round ring, and which rings are round."""
    s = len(points)
    member, target = _slab(points, tangent, radius, surface, rows)
    rel = surface[member] - points[target]
    x = np.einsum("ij,ij->i", rel, e1[target])
    y = np.einsum("ij,ij->i", rel, e2[target])
    centres = _circle_centres(x, y, target, s)
    dist = np.hypot(x - centres[target, 0], y - centres[target, 1])
    total = np.bincount(target, minlength=s).astype(np.float64)
    ring = np.maximum(total, 1.0)
    mean = np.bincount(target, weights=dist, minlength=s) / ring
    spread = np.sqrt(np.maximum(np.bincount(target, weights=dist * dist, minlength=s) / ring - mean**2, 0.0))
    with np.errstate(invalid="ignore"):
        angle = np.arctan2(y - centres[target, 1], x - centres[target, 0])
        sector = np.floor((angle + np.pi) / (2 * np.pi) * RING_SECTORS).astype(np.int64) % RING_SECTORS
        filled = np.bincount(target * RING_SECTORS + sector, minlength=s * RING_SECTORS).reshape(s, RING_SECTORS) > 0
        round_ring = (total >= MIN_RING) & (spread <= RING_TOLERANCE * mean) & filled.all(axis=1)
    round_ring &= np.isfinite(centres).all(axis=1)
    centre = np.where(round_ring[:, None], centres, 0.0)[rows]
    return centre[:, :1] * e1[rows] + centre[:, 1:] * e2[rows], round_ring[rows]


def _largest_balls(start: np.ndarray, e1: np.ndarray, e2: np.ndarray, radius: np.ndarray, surface: np.ndarray,
                   faces: np.ndarray) -> np.ndarray:
    """Point ``(r, 3)`` of each plane (through ``start``, spanned by ``e1, e2``) farthest from the surface, near ``start``.

    A coarse-to-fine grid search; the grid stays in the ball already empty
    around its centre (so inside the solid) and within ``MAX_SHIFT`` radii of
    the start; ties along a ridge (a plate's mid-surface) keep the point
    nearest the start.
    """
    tri = surface[faces]
    area = 0.5 * float(np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum())
    spacing = max(SAMPLE_SPACING * float(np.median(radius)), float(np.sqrt(area / MAX_SAMPLES)))
    samples, normals = surface_samples(surface, faces, spacing)
    tree = cKDTree(samples)
    centre = start.copy()
    depth, nearest = tree.query(centre, workers=-1)
    # only nodes inside the solid move (then the grids, in the empty ball, stay inside)
    inside = np.einsum("ij,ij->i", centre - samples[nearest], normals[nearest]) < 0
    half = np.where(inside, np.minimum(MAX_SHIFT * radius, 0.7 * depth), 0.0)
    tie = TIE * radius
    rows = np.arange(len(start))
    for level in range(LEVELS):
        # a fine grid first, then 3 x 3 grids each spanning the last one's step
        side = np.linspace(-1, 1, GRID if level == 0 else 3)
        a, b = (g.ravel() for g in np.meshgrid(side, side, indexing="ij"))
        cand = centre[:, None, :] + half[:, None, None] * (a[None, :, None] * e1[:, None, :] + b[None, :, None] * e2[:, None, :])
        d = tree.query(cand.reshape(-1, 3), workers=-1)[0].reshape(len(start), -1)
        gap = np.linalg.norm(cand - start[:, None, :], axis=2)
        gap[gap > MAX_SHIFT * radius[:, None]] = np.inf
        pick = np.argmin(np.where(d >= d.max(axis=1, keepdims=True) - tie[:, None], gap, np.inf), axis=1)
        better = (d[rows, pick] > depth) & np.isfinite(gap[rows, pick])
        centre[better] = cand[better, pick[better]]
        depth[better] = d[better, pick[better]]
        # the next grid spans this one's step (7 x 7), or half of it (3 x 3); its corners stay in the empty ball
        half = np.minimum(half / ((GRID - 1) / 2 if level == 0 else 2.0), 0.7 * depth)
    return centre


def surface_samples(points: np.ndarray, faces: np.ndarray, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """The vertices and, on faces with an edge longer than ``spacing``, a barycentric grid of about that step.

    Returns
    -------
    samples : (m, 3) float64 ndarray
        The vertices first, at their indices.
    normals : (m, 3) float64 ndarray
        Outward unit normals: area-weighted at the vertices, the face's inside it.
    """
    tri = points[faces]
    longest = np.max(np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2), axis=1)
    steps = np.ceil(longest / spacing).astype(np.int64)
    face_normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    face_normal /= np.maximum(np.linalg.norm(face_normal, axis=1, keepdims=True), 1e-300)
    out, normals = [points], [vertex_normals(points, faces)]
    for k in np.unique(steps[steps >= 2]):
        i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
        inner = (i + j <= k) & (i + j > 0) & (i < k) & (j < k)  # not the corners: they are vertices
        u, v = i[inner] / k, j[inner] / k
        t = tri[steps == k]
        grid = t[:, :1] + u[None, :, None] * (t[:, 1:2] - t[:, :1]) + v[None, :, None] * (t[:, 2:3] - t[:, :1])
        out.append(grid.reshape(-1, 3))
        normals.append(np.repeat(face_normal[steps == k], len(u), axis=0))
    return np.concatenate(out), np.concatenate(normals)


def node_radii(points: np.ndarray, correspondence: np.ndarray, surface: np.ndarray) -> np.ndarray:
    """Mean distance ``(s,)`` from each node to the surface vertices mapped to it (0 where none)."""
    own = np.flatnonzero(correspondence >= 0)
    node = correspondence[own]
    d = np.linalg.norm(surface[own] - points[node], axis=1)
    count = np.bincount(node, minlength=len(points))
    return np.bincount(node, weights=d, minlength=len(points)) / np.maximum(count, 1)


def _beyond(adj: Any, deg: np.ndarray, nxt: np.ndarray, prev: np.ndarray) -> np.ndarray:
    """The node after ``nxt`` going away from ``prev`` along a chain (``nxt`` itself where the chain ends)."""
    out = nxt.copy()
    chain = (deg[nxt] == 2) & (np.diff(adj.indptr)[nxt] == 2)
    a = adj.indices[adj.indptr[nxt[chain]]]
    b = adj.indices[adj.indptr[nxt[chain]] + 1]
    out[chain] = np.where(a == prev[chain], b, a)
    return out


def _plane_basis(tangent: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors orthogonal to each (unit or zero) tangent and to each other."""
    helper = np.where(np.abs(tangent[:, :1]) < 0.9, np.array([[1.0, 0.0, 0.0]]), np.array([[0.0, 1.0, 0.0]]))
    e1 = np.cross(tangent, helper)
    e1 /= np.maximum(np.linalg.norm(e1, axis=1, keepdims=True), 1e-300)
    return e1, np.cross(tangent, e1)


def _slab(points: np.ndarray, tangent: np.ndarray, radius: np.ndarray, surface: np.ndarray,
          rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (surface vertex, node): the vertices within ``2 * radius`` of each
    node of ``rows`` and within ``SLAB * radius`` of its plane across the branch."""
    near = cKDTree(surface).query_ball_point(points[rows], 2.0 * radius[rows])
    length = np.fromiter((len(v) for v in near), np.int64, len(rows))
    member = np.fromiter(itertools.chain.from_iterable(near), np.int64, int(length.sum()))
    target = np.repeat(rows, length)
    along = np.abs(np.einsum("ij,ij->i", surface[member] - points[target], tangent[target]))
    keep = along <= SLAB * radius[target]
    return member[keep], target[keep]


def _circle_centres(x: np.ndarray, y: np.ndarray, group: np.ndarray, s: int) -> np.ndarray:
    """(s, 2) least-squares circle centre of each group's points (Kasa fit; NaN where singular)."""
    z = x * x + y * y
    cols = (x, y, np.ones_like(x))

    def total(w: np.ndarray) -> np.ndarray:
        return np.bincount(group, weights=w, minlength=s)

    a = np.empty((s, 3, 3))
    b = np.empty((s, 3))
    for i in range(3):
        b[:, i] = total(cols[i] * z)
        for j in range(i, 3):
            a[:, i, j] = a[:, j, i] = total(cols[i] * cols[j])
    out = np.full((s, 2), np.nan)
    good = np.abs(np.linalg.det(a)) > 1e-12 * np.maximum(np.einsum("kii->k", a), 1e-300) ** 3
    if good.any():
        sol = np.linalg.solve(a[good], b[good][:, :, None])[:, :, 0]
        out[good] = 0.5 * sol[:, :2]
    return out
