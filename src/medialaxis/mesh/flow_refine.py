"""Embedding refinement of a flow skeleton: chain nodes onto the medial axis.

The diffusion flow smooths as it contracts, and smoothing shrinks curved
tubes: a torus's skeleton comes out inside its core circle by a fraction of
the tube radius (about 0.12 for major radius 3, minor 1), the "shrinkage"
that Au et al. (2008) correct by an embedding refinement. Here each node
inside a branch (degree 2) moves, across its branch only, to the mean of the
inner medial-ball centres of the surface vertices it stands for: those
centres lie on the medial axis, and their mean, taken across the branch,
is the axis point the node represents. Junctions, tips and fixed nodes stay
where the graph put them; the radii are measured again from the new places.
"""

from __future__ import annotations

import itertools
from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.core import graph as _graph

__all__ = ["centre_on_rings", "MAX_SHIFT", "MIN_RING", "RING_TOLERANCE", "RING_BALANCE"]

#: Largest move of a node, as a fraction of its radius (a safeguard against
#: stray balls on a coarse or noisy surface).
MAX_SHIFT = 0.5
#: Fewest surface vertices a node needs to be moved (a circle needs three;
#: a handful more keep one stray vertex from deciding).
MIN_RING = 8
#: A node moves only if its vertices lie on a circle across the branch: the
#: spread of their distances to the fitted centre is at most this fraction
#: of the mean distance.
RING_TOLERANCE = 0.1
#: ... and they surround it: the mean of the unit vectors from the centre to
#: them is at most this long (0 for a full, evenly sampled ring).
RING_BALANCE = 0.25
#: Half-thickness of the slab across a branch whose vertices give a node's
#: cross-section, as a fraction of its radius.
SLAB = 0.2


def centre_on_rings(
    points: np.ndarray,
    edges: np.ndarray,
    correspondence: np.ndarray,
    original: np.ndarray,
    keep: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Move chain nodes, across their branch, to the centre of their ring of surface vertices.

    Parameters
    ----------
    points : (s, 3) float64 ndarray
        Skeleton nodes.
    edges : (e, 2) int64 ndarray
    correspondence : (n,) int64 ndarray
        Node of each surface vertex (-1: none).
    original : (n, 3) float64 ndarray
        Surface vertices.
    keep : (s,) bool ndarray
        Nodes that must not move (user-fixed points).

    Returns
    -------
    points : (s, 3) float64 ndarray
    radii : (s,) float64 ndarray
        Mean distance from each node to its surface vertices.
    """
    s = len(points)
    own = np.flatnonzero(correspondence >= 0)
    node = correspondence[own]
    count = np.bincount(node, minlength=s).astype(np.float64)
    out = np.array(points, dtype=np.float64, copy=True)
    deg = _graph.degree(s, edges)
    adj = _graph.adjacency(s, edges)
    # two distinct neighbours (a repeated edge or a self-loop also gives degree 2)
    move = (deg == 2) & (np.diff(adj.indptr) == 2) & (count > 0) & ~np.asarray(keep, bool)
    rows = np.flatnonzero(move)
    if len(rows):
        first = adj.indices[adj.indptr[rows]]
        second = adj.indices[adj.indptr[rows] + 1]
        # the tangent spans two nodes either side, where the chain goes on
        # (neighbouring nodes can be close and a little off the axis)
        tangent = np.zeros((s, 3))
        tangent[rows] = points[_beyond(adj, deg, first, rows)] - points[_beyond(adj, deg, second, rows)]
        tangent[rows] /= np.maximum(np.linalg.norm(tangent[rows], axis=1, keepdims=True), 1e-300)
        e1, e2 = _plane_basis(tangent)
        # each node fits the cross-section of the surface through it: the
        # vertices in a thin slab across the branch, near the node
        radius = _radii(points, node, original[own], count)
        member, target = _slab(points, tangent, radius, original, rows)
        rel = original[member] - points[target]
        x = np.einsum("ij,ij->i", rel, e1[target])
        y = np.einsum("ij,ij->i", rel, e2[target])
        centres = _circle_centres(x, y, target, s)
        # only round rings: a cross-section through a cap or a junction is
        # not one circle, and its node stays where it is
        dist = np.hypot(x - centres[target, 0], y - centres[target, 1])
        total = np.bincount(target, minlength=s).astype(np.float64)
        ring = np.maximum(total, 1.0)
        mean = np.bincount(target, weights=dist, minlength=s) / ring
        spread = np.sqrt(np.maximum(np.bincount(target, weights=dist * dist, minlength=s) / ring - mean**2, 0.0))
        # ... and all round the centre: an arc on one side fits a circle as well
        with np.errstate(invalid="ignore", divide="ignore"):
            ux = np.nan_to_num((x - centres[target, 0]) / dist)
            uy = np.nan_to_num((y - centres[target, 1]) / dist)
        lop = np.hypot(np.bincount(target, weights=ux, minlength=s), np.bincount(target, weights=uy, minlength=s)) / ring
        with np.errstate(invalid="ignore"):
            round_ring = (total >= MIN_RING) & (spread <= RING_TOLERANCE * mean) & (lop <= RING_BALANCE)
        centre = np.where(round_ring[:, None], centres, np.nan)[rows]
        offset = centre[:, :1] * e1[rows] + centre[:, 1:] * e2[rows]
        length = np.linalg.norm(offset, axis=1)
        scale = np.where(np.isfinite(length),
                         np.minimum(1.0, MAX_SHIFT * radius[rows] / np.maximum(length, 1e-300)), 0.0)
        out[rows] += scale[:, None] * np.nan_to_num(offset)
    return out, _radii(out, node, original[own], count)


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


def _radii(points: np.ndarray, node: np.ndarray, surface: np.ndarray, count: np.ndarray) -> np.ndarray:
    d = np.linalg.norm(surface - points[node], axis=1)
    return np.bincount(node, weights=d, minlength=len(points)) / np.maximum(count, 1.0)
