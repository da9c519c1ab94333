"""Bai and Latecki's skeleton paths and the "previous default" distance, moved out of the package (issue 17).

The shape distance once had three terms: the axis tour (the package's
distance today), the skeleton paths between every two endpoints (Bai and
Latecki, TPAMI 2008; :mod:`research.path_kernels`) and an unordered axis
context (:mod:`research.axis_context`). Before the tour, the default was
``paths + 0.6 context`` (Kimia-99 912). The last two did not raise the tour,
on Kimia-99 nor on MPEG-7 (35 dev classes, not the set they were tuned on):

    tour alone 87.59%; + 0.1 paths 87.64%, + 0.3 paths 87.65%;
    + 0.1 context 87.42%, + 0.3 context 86.79%; DCE 0.01 87.54%, DCE 0.02 87.61%

(bull's-eye, one signature set; the paths' +0.06 points is below the spread
between class folds, and the term is most of the pair time when on). Here
they are computed from the package's compared axis (largest component,
spurious branches removed) exactly as they were, so ``bench_compare.py`` can
print the previous default beside the tour and the rows of ``--variants``.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Sequence

import numpy as np
from scipy.sparse import csgraph

from medialaxis.compare.compared_axis import drop_spurious, edge_lengths, main_component
from medialaxis.compare.endpoints import endpoint_order, endpoint_weights, weighted_graph
from medialaxis.compare.matrix import _blocks
from medialaxis.core.parallel import run_tasks
from medialaxis.core.result import MedialAxis

from . import path_kernels
from .axis_context import N_ANGULAR, axis_context, context_distances, pack_context
from .dce import convex_dce_vertices, dce_prune, outline

__all__ = [
    "PathSignature", "path_signature", "endpoint_paths", "term_matrices", "previous_default", "match_endpoints",
    "PATH_PARAMS", "DEFAULT_SAMPLES",
]

#: Radius samples per skeleton path (Bai and Latecki use 50; 24 gave the same Kimia-99 row, faster).
DEFAULT_SAMPLES = 24
#: Interior samples of each path's bend profile.
N_BEND = 7
#: Weights of the path-length, chord and bend parts of the path cost, cost of skipping a path in an
#: alignment and of an unmatched endpoint (both times the endpoint's weight); chosen on Kimia-99
#: when the path term was the main term.
PATH_PARAMS = {"alpha": 0.1333, "beta": 0.0625, "gamma": 0.175, "skip": 0.2, "unmatched": 0.4}
#: Weight of the axis context in the previous default (``paths + 0.6 context``).
PREVIOUS_CONTEXT = 0.6
#: Spurious-branch pruning of the previous default (the package's default was 0.03 then).
PREVIOUS_PRUNE = 0.03


@dataclasses.dataclass(frozen=True, eq=False)
class PathSignature:
    """Skeleton paths and axis context of one axis, all divided by its scale.

    ``radii (e, e, s)``: radius function along the geodesic path from
    endpoint ``i`` to ``j`` at ``s`` points equally spaced in arc length
    (``radii[j, i]`` is its reverse); ``lengths``, ``chords (e, e)``: path
    lengths and straight-line distances; ``bends (e, e, b)``: distance of
    the path points at arc-length fractions ``1/(b+1) ... b/(b+1)`` from the
    chord's midpoint; ``weights (e,)``: how far each endpoint's terminal
    branch protrudes past its junction's disc; ``context (k, h)`` and
    ``context_radii (k,)``: axis-context histograms and radii of samples
    along the branches. Endpoints in boundary order.
    """

    radii: np.ndarray
    lengths: np.ndarray
    chords: np.ndarray
    bends: np.ndarray
    weights: np.ndarray
    context: np.ndarray
    context_radii: np.ndarray

    def features(self) -> tuple[np.ndarray, ...]:
        return self.radii, self.lengths, self.chords, self.bends, self.weights


def endpoint_paths(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, ends: np.ndarray, n_samples: int, n_bend: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Radius functions, lengths and bend profiles of the geodesic paths between endpoints.

    Returns ``(radii (e, e, n_samples), lengths (e, e), bends (e, e, n_bend))``;
    the bend profile is the distance from the chord's midpoint of the path
    points at ``n_bend`` interior arc-length fractions ``k / (n_bend + 1)``.
    """
    e = len(ends)
    out_r = np.zeros((e, e, n_samples))
    out_l = np.zeros((e, e))
    out_b = np.zeros((e, e, n_bend))
    if not len(edges):
        out_r[:] = radii[ends[0]]
        return out_r, out_l, out_b
    n = len(points)
    weights = edge_lengths(points, edges)
    dist, pred = csgraph.dijkstra(weighted_graph(n, edges, weights), directed=False, indices=ends, return_predecessors=True)
    t = np.linspace(0.0, 1.0, n_samples)
    tb = np.arange(1, n_bend + 1) / (n_bend + 1)
    for i in range(e):
        for j in range(e):
            if i == j:
                out_r[i, j] = radii[ends[i]]
                continue
            if j < i:
                out_r[i, j] = out_r[j, i][::-1]
                out_l[i, j] = out_l[j, i]
                out_b[i, j] = out_b[j, i][::-1]
                continue
            path = [int(ends[j])]
            while path[-1] != ends[i]:
                path.append(int(pred[i, path[-1]]))
            path.reverse()
            p = points[path]
            arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
            total = arc[-1]
            out_l[i, j] = total
            if total > 0:
                out_r[i, j] = np.interp(t * total, arc, radii[path])
                along = np.column_stack([np.interp(tb * total, arc, p[:, 0]), np.interp(tb * total, arc, p[:, 1])])
                out_b[i, j] = np.linalg.norm(along - (p[0] + p[-1]) / 2, axis=1)
            else:
                out_r[i, j] = radii[path[0]]
    return out_r, out_l, out_b


def path_signature(
    ma: MedialAxis,
    *,
    n_samples: int = DEFAULT_SAMPLES,
    prune: float = PREVIOUS_PRUNE,
    max_endpoints: int = 24,
    dce: float = 0.0,
    dce_vertices: int = 3,
    unpruned: bool = False,
) -> PathSignature:
    """The paths and context of ``ma``'s compared axis.

    ``dce > 0``: first prune the axis by Discrete Curve Evolution of the
    shape's outline (:mod:`research.dce`); ``unpruned``: use the axis before
    the method's own pruning (``ma.raw``) when there is one.
    """
    if unpruned and ma.raw is not None and len(ma.raw.points):
        ma = ma.raw
    points, radii, edges, scale = main_component(ma)
    if dce > 0:
        contour = outline(ma.shape)
        if contour is not None:
            edges = dce_prune(points, radii, edges, convex_dce_vertices(contour, dce, min_vertices=dce_vertices))
    points, radii, edges = drop_spurious(points, radii, edges, scale, prune, max_endpoints)
    order = endpoint_order(points, edges)
    path_r, path_l, bends = endpoint_paths(points, radii, edges, order, int(n_samples), N_BEND)
    weights = endpoint_weights(points, radii, edges, order, path_l)
    ends = points[order]
    chords = np.linalg.norm(ends[:, None, :] - ends[None, :, :], axis=2)
    context, context_radii = axis_context(points, radii, edges, scale)
    return PathSignature(path_r / scale, path_l / scale, chords / scale, bends / scale, weights / scale, context,
                         context_radii)


def _score(blk: slice, packed: tuple, rows: np.ndarray, cols: np.ndarray, params: tuple[float, ...]
           ) -> tuple[np.ndarray, np.ndarray]:
    paths, context = packed
    r, c = rows[blk], cols[blk]
    forward = path_kernels.pair_distances(*paths, r, c, *params)
    backward = path_kernels.pair_distances(*paths, c, r, *params)
    # equal up to rounding; the minimum makes the matrix exactly symmetric
    return np.minimum(forward, backward), context_distances(*context, r, c)


def term_matrices(
    sigs: Sequence[PathSignature], n_jobs: int | None = None, params: dict[str, float] | None = None
) -> dict[str, np.ndarray]:
    """``{"paths": (n, n), "context": (n, n)}``: the two terms for every pair, on ``n_jobs`` threads.

    ``params``: the path term's weights and costs (default :data:`PATH_PARAMS`).
    """
    n = len(sigs)
    if len({s.radii.shape[2] for s in sigs}) > 1:
        raise ValueError("path signatures with different n_samples")
    packed = (path_kernels.pack(*(list(column) for column in zip(*(s.features() for s in sigs)))),
              pack_context([s.context for s in sigs], [s.context_radii for s in sigs], N_ANGULAR))
    rows, cols = np.triu_indices(n, 1)
    workers = n_jobs or os.cpu_count() or 1
    blocks = _blocks(len(rows), max(1, min(len(rows) // 500 + 1, 64 * workers)))
    values = tuple((params or PATH_PARAMS)[k] for k in PATH_PARAMS)
    scored = run_tasks(_score, blocks, packed, rows, cols, values, n_jobs=workers, desc="path pairs")
    out = {"paths": np.zeros((n, n)), "context": np.zeros((n, n))}
    for blk, values in zip(blocks, scored):
        for name, value in zip(("paths", "context"), values):
            out[name][rows[blk], cols[blk]] = value
            out[name][cols[blk], rows[blk]] = value
    return out


def previous_default(terms: dict[str, np.ndarray]) -> np.ndarray:
    """The default distance before the tour: ``paths + 0.6 context``."""
    return terms["paths"] + PREVIOUS_CONTEXT * terms["context"]


def match_endpoints(a: PathSignature, b: PathSignature) -> tuple[float, list[tuple[int, int]]]:
    """The path term of one pair (NumPy/SciPy reference) and the endpoints it matched (indices in boundary order)."""
    return path_kernels.reference_match(a.features(), b.features(), *PATH_PARAMS.values())
