"""Convex corners of the rings, sampled in mirrored pairs so that the refinement leaves them alone.

A convex vertex's medial axis is the bisector of its two edges; samples at
equal distances from the vertex along both edges give Voronoi vertices on it
however sparse they are (:mod:`medialaxis.planar.boundary._corner_kernels`). Left to
the split rule of :func:`medialaxis.planar.boundary.sampling.refine_arcs`, the triangle
of a corner and its two neighbouring samples has a radius that shrinks with
every split, and the pieces at the corner are split down to ``min_length``:
on the median (17-vertex) lake of ``benchmarks/bench_centerlines.py``, 63%
of some 1,160 samples lay within 1% of the perimeter of a vertex. :func:`mirrored_corner_arcs` adds, at each convex
vertex the rule would split, the mirror images of the samples of its shorter
edge on its longer edge (up to the shorter edge's length), so the corner
starts mirrored, with a few pairs closing in on the vertex (three times
closer each); the kernel keeps it mirrored.

The samples and their refinement are those of the adaptive sampling of
:mod:`medialaxis.planar.boundary.adaptive`; the corner rule is elementary geometry
(the medial axis of two edges meeting at a convex vertex is their bisector,
and an isosceles trapezoid is cyclic with its centre on its axis).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from medialaxis.planar.boundary._corner_kernels import closed_rings, corner_twins
from medialaxis.planar.boundary._pinch_kernels import touching_vertices
from medialaxis.planar.boundary.sampling import Rings

__all__ = ["RingArrays", "closed_ring_arrays", "ring_arrays", "ring_arrays_reference", "mirrored_corner_arcs"]


@dataclasses.dataclass(frozen=True)
class RingArrays:
    """Every ring closed, one after another, as the compiled kernels take them.

    Attributes
    ----------
    xy : (V, 2) float ndarray
        Vertices, each ring's first repeated at its end.
    s : (V,) float ndarray
        Cumulative arc length along each ring (0 at its first vertex).
    start : (R + 1,) int ndarray
        Ring ``r`` is ``start[r]:start[r + 1]``.
    convex : (V,) bool ndarray
        Convex vertices (the region turns right there: rings are normalized,
        the region on their right).
    touching : (V,) int ndarray
        The vertices at the same point as another (rings touching at a
        vertex): the next of them, in a cycle; -1 for the others and the
        repeats (:func:`medialaxis.planar.boundary._pinch_kernels.touching_vertices`).
    """

    xy: np.ndarray
    s: np.ndarray
    start: np.ndarray
    convex: np.ndarray
    touching: np.ndarray


def closed_ring_arrays(vertices: np.ndarray, open_start: np.ndarray) -> RingArrays:
    """The :class:`RingArrays` of rings given one after another, not closed, ring ``r`` at
    ``open_start[r]:open_start[r + 1]`` (compiled: :func:`medialaxis.planar.boundary._corner_kernels.closed_rings`)."""
    xy, s, start, convex = closed_rings(np.ascontiguousarray(vertices, np.float64), np.asarray(open_start, np.int64))
    return RingArrays(xy, s, start, convex, touching_vertices(xy, start))


def ring_arrays(rings: Rings) -> RingArrays:
    """The closed rings of ``rings`` with their arc lengths (:attr:`~medialaxis.planar.boundary.sampling.Rings.arc_lengths`, as
    :func:`medialaxis.planar.boundary.sampling.sample` reads them) and convex vertices, as the compiled kernels take them
    (:func:`medialaxis.planar.boundary._corner_kernels.closed_rings`; :func:`ring_arrays_reference` is the NumPy version)."""
    sizes = [len(v) for v in rings.vertices]
    vertices = np.ascontiguousarray(np.concatenate(rings.vertices), np.float64) if sizes else np.empty((0, 2))
    return closed_ring_arrays(vertices, np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64))


def ring_arrays_reference(rings: Rings) -> RingArrays:
    """NumPy version of :func:`ring_arrays` (for the tests)."""
    closed, s = rings.closed, rings.arc_lengths
    start = np.concatenate([[0], np.cumsum([len(c) for c in closed])]).astype(np.int64)
    xy = np.ascontiguousarray(np.concatenate(closed))
    row = np.arange(len(xy))
    first = np.repeat(start[:-1], np.diff(start))  # each row's ring's first row
    before = np.where(row == first, start[1:].repeat(np.diff(start)) - 2, row - 1)  # the vertex before, not the repeat
    after = np.where(row == start[1:].repeat(np.diff(start)) - 1, first + 1, row + 1)
    into, out = xy - xy[before], xy[after] - xy
    touching = np.full(len(xy), -1, np.int64)
    real = np.flatnonzero(row != start[1:].repeat(np.diff(start)) - 1)  # not the repeats
    for same in _groups(xy[real]):
        touching[real[same]] = real[np.roll(same, -1)]
    return RingArrays(xy, np.concatenate(s), start, into[:, 0] * out[:, 1] - into[:, 1] * out[:, 0] < 0, touching)


def _groups(xy: np.ndarray) -> list[np.ndarray]:
    """The rows of ``xy`` at one point, two or more, each group in ascending rows."""
    _, inverse, counts = np.unique(xy, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    return [np.flatnonzero(inverse == g) for g in np.flatnonzero(counts > 1)]


def mirrored_corner_arcs(
    closed: RingArrays, arcs: list[np.ndarray], tolerance: float, min_length: float, ratio: float = 0.5
) -> list[np.ndarray]:
    """``arcs`` with mirrored samples at every convex vertex whose corner the split rule would split.

    The corner's triangle (the vertex and the nearest sample on each edge,
    at the shorter distance ``h``) has circumradius ``R = h / (2 cos(a / 2))``
    for the inner angle ``a``; the rule splits it when ``h`` exceeds
    ``max(min(ratio * R, sqrt(16 R tolerance)), min_length)`` and
    ``2 * min_length``. There (:func:`medialaxis.planar.boundary._corner_kernels.corner_twins`):

    * pairs of samples at ``h / 3, h / 9, ...`` from the vertex on both edges,
      down to the pair ``8 * min_length`` apart (``lam`` by default; the
      pruned axis reaches into the corner as far as that pair, as it did when
      the rule split the corner down to ``min_length``) and one more;
    * every sample of the shorter edge (its far vertex included) at distance
      ``d`` from the vertex gets a twin at ``d`` on the longer edge, unless a
      sample is already within ``min_length`` of it.
    """
    out = []
    for r, a in enumerate(arcs):
        rows = slice(closed.start[r], closed.start[r + 1])
        twins = corner_twins(np.ascontiguousarray(a, np.float64), closed.s[rows], closed.xy[rows], float(tolerance),
                             float(min_length), float(ratio))
        out.append(np.unique(np.concatenate([a, twins])) if len(twins) else a)
    return out
