"""Boundary sampling: simplify to the tolerance, then subdivide adaptively.

The region's rings are first simplified (Douglas-Peucker, topology
preserving) to the accuracy ``tolerance``, so the work no longer depends on
the input's vertex count. Each simplified edge is then split into equal
pieces; :func:`refine_arcs` splits the pieces that are too long for the
local medial radius (the adaptive, iterative sampling of "A Qualitative
Approach for Medial Computation"). The result is an epsilon-sample in the
sense of Algorithm 5 of Boissonnat, Wormser and Yvinec ("Curved Voronoi
diagrams", section 2.7): every boundary point is within ``tolerance`` of the
sampled polygon.
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np
import shapely
from scipy.spatial import cKDTree

from medialaxis.planar._inside_kernels import RegionLocator
from medialaxis.planar._kernels import OVER_SPLIT, split_pieces
from medialaxis.planar.boundary._simplify_kernels import flattening_is_safe

__all__ = ["Rings", "BoundarySample", "simplify_rings", "initial_arcs", "sample", "refine_arcs", "refine_arcs_reference"]


@dataclasses.dataclass(frozen=True)
class Rings:
    """Closed rings of a simplified region.

    Attributes
    ----------
    vertices : list of (k, 2) float ndarray
        Ring vertices, not repeated at the end.
    region : shapely geometry
        The polygon the rings bound (used for inside tests).
    """

    vertices: list[np.ndarray]
    region: Any

    @functools.cached_property
    def closed(self) -> list[np.ndarray]:
        """Each ring's vertices with its first repeated at the end."""
        return [np.vstack([v, v[:1]]) for v in self.vertices]

    @functools.cached_property
    def arc_lengths(self) -> list[np.ndarray]:
        """Each closed ring's cumulative arc length at its vertices (0 first, the perimeter last)."""
        return [np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(c, axis=0), axis=1))]) for c in self.closed]

    @functools.cached_property
    def locator(self) -> RegionLocator:
        """The compiled inside test of ``region`` (built once, used every round)."""
        return RegionLocator(self.region)


@dataclasses.dataclass(frozen=True)
class BoundarySample:
    """Sample points on the rings with their order along each ring.

    Attributes
    ----------
    points : (N, 2) float ndarray
    ring : (N,) int ndarray
        Ring index of each sample.
    arc : (N,) float ndarray
        Arc-length position of each sample along its ring.
    ring_length : (R,) float ndarray
        Perimeter of each ring.
    next : (N,) int ndarray
        Index of the following sample on the same ring.
    """

    points: np.ndarray
    ring: np.ndarray
    arc: np.ndarray
    ring_length: np.ndarray
    next: np.ndarray

    @functools.cached_property
    def prev(self) -> np.ndarray:
        """(N,) int ndarray: index of the preceding sample on the same ring."""
        out = np.empty_like(self.next)
        out[self.next] = np.arange(len(self.next))
        return out

    @functools.cached_property
    def tree(self) -> cKDTree:
        """k-d tree of the samples (built once, for the distance queries)."""
        return cKDTree(self.points)

    def arc_between(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Shorter boundary arc length between samples ``a`` and ``b`` (inf across rings)."""
        same = self.ring[a] == self.ring[b]
        d = np.abs(self.arc[a] - self.arc[b])
        length = self.ring_length[self.ring[a]]
        return np.where(same, np.minimum(d, length - d), np.inf)


def _rings_of(geom: Any) -> list[np.ndarray]:
    rings = []
    for ring in shapely.get_rings(shapely.get_parts(geom)):  # each polygon's exterior, then its interiors
        xy = shapely.get_coordinates(ring)[:-1]
        if len(xy) >= 3:
            rings.append(xy)
    return rings


def _ring_arrays(geom: Any) -> tuple[np.ndarray, np.ndarray] | None:
    """All rings' vertices (not closed) one after another, and where each starts; None for no polygon."""
    rings = [shapely.get_coordinates(r)[:-1] for r in shapely.get_rings(shapely.get_parts(geom))]
    if not rings or shapely.get_type_id(geom) not in (3, 6):
        return None
    start = np.concatenate([[0], np.cumsum([len(r) for r in rings])]).astype(np.int64)
    return np.ascontiguousarray(np.concatenate(rings), np.float64), start


def topology_preserving_simplify(region: Any, tolerance: float) -> Any:
    """``shapely.simplify(region, tolerance, preserve_topology=True)``, by plain Douglas-Peucker where that is the same.

    Plain Douglas-Peucker is ten times faster; :func:`medialaxis.planar.boundary._simplify_kernels.flattening_is_safe`
    tells when the topology-preserving simplifier would have refused none of its flattenings.
    """
    plain = shapely.simplify(region, tolerance, preserve_topology=False)
    before, after = _ring_arrays(region), _ring_arrays(plain)
    if (before is not None and after is not None and len(before[1]) == len(after[1])
            and shapely.get_num_geometries(region) == shapely.get_num_geometries(plain)
            and flattening_is_safe(before[0], before[1], after[0], after[1], float(tolerance))):
        return plain
    return shapely.simplify(region, tolerance, preserve_topology=True)


def simplify_rings(region: Any, tolerance: float) -> Rings:
    """Douglas-Peucker simplification of every ring to ``tolerance`` (topology kept)."""
    simple = topology_preserving_simplify(region, tolerance) if tolerance > 0 else region
    if simple is not region and (simple.is_empty or not simple.is_valid):
        simple = region
    simple = shapely.normalize(simple)
    return Rings(_rings_of(simple), simple)


def initial_arcs(rings: Rings, max_length: float) -> list[np.ndarray]:
    """Arc positions of the first sample: every vertex, edges cut to ``max_length``."""
    arcs = []
    for s in rings.arc_lengths:
        seg = np.diff(s)
        count = np.maximum(1, np.ceil(seg / max_length)).astype(np.int64)
        owner = np.repeat(np.arange(len(seg)), count)
        frac = (np.arange(len(owner)) - np.repeat(np.cumsum(count) - count, count)) / count[owner]
        arcs.append(s[owner] + frac * seg[owner])
    return arcs


def _offsets(parts: list[np.ndarray]) -> np.ndarray:
    return np.concatenate([[0], np.cumsum([len(p) for p in parts])]).astype(np.int64)


def refine_arcs(
    arcs: list[np.ndarray],
    smp: BoundarySample,
    piece_radius: np.ndarray,
    conforming: np.ndarray,
    tolerance: float,
    min_length: float,
    ratio: float = 0.5,
    over_split: float = OVER_SPLIT,
) -> list[np.ndarray] | None:
    """Insert samples into the pieces that are too long; ``None`` when none is.

    A piece ``(i, next[i])`` of length ``h`` with inner medial radius ``R``
    (circumradius of its inner Delaunay triangle) is too long when
    ``h > min(ratio * R, sqrt(16 R tolerance))``: the first bound keeps the
    sample dense relative to the local feature size (topology), the second
    bounds the offset of a Voronoi vertex from the medial axis, about
    ``h**2 / (16 R)``, by ``tolerance``. Pieces that are not Delaunay edges are
    split too (conformity). Nothing is split below ``min_length``. Over-split
    (``over_split`` times, :data:`~medialaxis.planar._kernels.OVER_SPLIT` by default) so the radii, which
    shrink as the sample gets denser near corners and tips, rarely need
    another round. Compiled
    (:func:`medialaxis.planar._kernels.split_pieces`);
    :func:`refine_arcs_reference` is the NumPy version.

    References
    ----------
    .. [1] "A Qualitative Approach for Medial Computation" (Voronoi/Delaunay medial axis of a 2D
           image; authors, venue and year unconfirmed: docs/references.md).
    .. [2] J.-D. Boissonnat, C. Wormser, M. Yvinec, "Curved Voronoi diagrams", in J.-D.
           Boissonnat, M. Teillaud (eds.), Effective Computational Geometry for Curves and
           Surfaces, Springer, 67-116, 2006, section 2.7 (medial axis, Algorithm 5).
           https://hal.archives-ouvertes.fr/hal-00488446
    """
    out, offsets = split_pieces(smp.arc, _offsets(arcs), smp.points, smp.next, smp.ring_length,
                                np.asarray(piece_radius, np.float64), np.asarray(conforming, bool),
                                float(tolerance), float(min_length), float(ratio), float(over_split))
    if offsets[0] < 0:
        return None
    return [out[offsets[r] : offsets[r + 1]] for r in range(len(arcs))]


def sample(rings: Rings, arcs: list[np.ndarray]) -> BoundarySample:
    """Points at the given arc positions (sorted, in ``[0, perimeter)``) of each ring."""
    pts, ring_id, arc, nxt, lengths = [], [], [], [], []
    n0 = 0
    for r, (closed, s, a) in enumerate(zip(rings.closed, rings.arc_lengths, arcs)):
        p = np.column_stack((np.interp(a, s, closed[:, 0]), np.interp(a, s, closed[:, 1])))
        pts.append(p)
        arc.append(a)
        lengths.append(s[-1])
        ring_id.append(np.full(len(p), r))
        nxt.append(n0 + (np.arange(len(p)) + 1) % len(p))
        n0 += len(p)
    return BoundarySample(
        np.concatenate(pts), np.concatenate(ring_id), np.concatenate(arc), np.asarray(lengths), np.concatenate(nxt)
    )


def refine_arcs_reference(
    arcs: list[np.ndarray],
    smp: BoundarySample,
    piece_radius: np.ndarray,
    conforming: np.ndarray,
    tolerance: float,
    min_length: float,
    ratio: float = 0.5,
    over_split: float = OVER_SPLIT,
) -> list[np.ndarray] | None:
    """NumPy version of :func:`refine_arcs` (for the tests)."""
    h = np.linalg.norm(smp.points[smp.next] - smp.points, axis=1)
    target = np.maximum(np.minimum(ratio * piece_radius, np.sqrt(16.0 * piece_radius * tolerance)), min_length)
    split = ((h > target) | ~conforming) & (h > 2.0 * min_length)
    if not split.any():
        return None
    pieces = np.clip(np.ceil(over_split * h / target), 2, 64).astype(np.int64)
    out = []
    for r, a in enumerate(arcs):
        idx = np.flatnonzero(split & (smp.ring == r))
        if len(idx) == 0:
            out.append(a)
            continue
        start = smp.arc[idx]
        length = smp.ring_length[r]
        stop = smp.arc[smp.next[idx]]
        stop = np.where(stop <= start, stop + length, stop)
        k = pieces[idx]
        owner = np.repeat(np.arange(len(idx)), k - 1)
        j = np.arange(len(owner)) - np.repeat(np.cumsum(k - 1) - (k - 1), k - 1) + 1
        new = start[owner] + (stop - start)[owner] * j / k[owner]
        out.append(np.sort(np.concatenate([a, np.mod(new, length)])))
    return out
