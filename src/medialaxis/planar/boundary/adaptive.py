"""Adaptive boundary sampling: sample, triangulate, and refine where the Delaunay triangulation misses the boundary.

The samples start evenly spaced along the rings and are refined piece by
piece until every boundary piece is a Delaunay edge (the triangulation
conforms) and each inner circumcentre lies within the tolerance of the
axis of the sampled shape (:func:`medialaxis.planar.boundary.sampling.refine_arcs`).
Convex corners start with mirrored samples and their triangles, whose
circumcentres lie on the corner's bisector, do not drive the refinement
(:mod:`medialaxis.planar.boundary.corners`).

Each round inserts only its new samples into the triangulation of the round
before and tests only the triangles it made (:mod:`medialaxis.planar.boundary._refine_kernels`);
:func:`rounds_from_scratch` is the same refinement triangulating every round
anew, the reference of the tests and the fallback where rounding stops the
incremental kernel.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import shapely

from medialaxis._progress import progress
from medialaxis.planar._inside_kernels import RegionLocator
from medialaxis.planar._kernels import OVER_SPLIT
from medialaxis.planar.axis import inner_triangles
from medialaxis.planar.boundary._corner_kernels import corner_piece_state
from medialaxis.planar.boundary._refine_kernels import CORNERS, assembled, first_sample
from medialaxis.planar.boundary._rounds_kernels import (
    ASK_GEOS,
    DONE,
    FAILED,
    MORE_JITTER,
    first_state,
    incremental_rounds,
    sample_box,
)
from medialaxis.planar.boundary.corners import RingArrays, mirrored_corner_arcs, ring_arrays
from medialaxis.planar.boundary.sampling import BoundarySample, Rings, initial_arcs, refine_arcs, sample
from medialaxis.planar.delaunay import FAR_CORNERS, Triangulation, jitter, triangulate

__all__ = ["sample_and_triangulate", "rounds_from_scratch", "incremental_sample", "MAX_REFINEMENTS"]

#: Most rounds of refinement.
MAX_REFINEMENTS = 12
#: Fewest new samples, as a share of the sample, for another round after the sample conforms.
SETTLED_SHARE = 0.05
#: Past this many vertices the compiled rounds come back to Python after each round (progress bar, Ctrl-C).
ONE_ROUND_ABOVE = 20_000
#: Longest piece, as a share of its inner circumradius (see :func:`medialaxis.planar.boundary.sampling.refine_arcs`).
RATIO = 0.5


def _start_length(region: Any, min_length: float) -> float:
    """The length of the first pieces: about ``sqrt(area) / 8``, never below ``min_length``."""
    return max(min_length, np.sqrt(max(region.area, 1e-300)) / 8.0)


def _start_arcs(
    rings: Rings, closed: RingArrays, region: Any, tolerance: float, min_length: float
) -> list[np.ndarray]:
    """Pieces of :func:`_start_length`, every vertex a sample, corners mirrored."""
    arcs = initial_arcs(rings, _start_length(region, min_length))
    return mirrored_corner_arcs(closed, arcs, tolerance, min_length, RATIO)


def sample_and_triangulate(
    rings: Rings, region: Any, tolerance: float, min_length: float, over_split: float = OVER_SPLIT
) -> tuple[BoundarySample, Triangulation, np.ndarray]:
    """Samples of ``rings``, their Delaunay triangulation and its triangles inside ``region``.

    Pieces start about ``sqrt(area) / 8`` long (never below ``min_length``)
    and are split until they conform and are within ``tolerance``, at most
    :data:`MAX_REFINEMENTS` rounds; a piece too long is cut ``over_split``
    times finer than that asks (:data:`medialaxis.planar._kernels.OVER_SPLIT`).
    """
    if region is rings.region:
        found = incremental_sample(rings.region, rings.locator, ring_arrays(rings), tolerance, min_length,
                                   over_split=over_split)
        if found is not None:
            return found
    return rounds_from_scratch(rings, region, tolerance, min_length, over_split)


def rounds_from_scratch(
    rings: Rings, region: Any, tolerance: float, min_length: float, over_split: float = OVER_SPLIT
) -> tuple[BoundarySample, Triangulation, np.ndarray]:
    """:func:`sample_and_triangulate` with every round's sample triangulated anew."""
    closed = ring_arrays(rings)
    arcs: list[np.ndarray] | None = _start_arcs(rings, closed, region, tolerance, min_length)
    settled = False
    locator = rings.locator if region is rings.region else None
    for _ in progress(range(MAX_REFINEMENTS), desc="adaptive sampling"):
        smp = sample(rings, arcs)
        tri = triangulate(smp.points)
        inside = inner_triangles(tri, region, locator)
        if settled:
            break
        conforming, radius = corner_piece_state(tri.simplices, inside, tri.radii, tri.centers, smp.next, smp.arc,
                                                smp.ring, 0, closed.s, closed.xy, closed.start, closed.convex,
                                                closed.touching, float(tolerance), float(over_split))
        arcs = refine_arcs(arcs, smp, radius, conforming, tolerance, min_length, RATIO, over_split)
        if arcs is None:
            break
        # Only a handful of pieces near tips were split: triangulate once more and stop.
        settled = conforming.all() and sum(map(len, arcs)) - len(smp.points) < SETTLED_SHARE * len(smp.points)
    return smp, tri, inside


def incremental_sample(
    region: Any, locator: RegionLocator, closed: RingArrays, tolerance: float, min_length: float,
    show_progress: bool | None = None, over_split: float = OVER_SPLIT,
) -> tuple[BoundarySample, Triangulation, np.ndarray] | None:
    """:func:`rounds_from_scratch`, each round inserting only its new samples; None where the kernel gives up.

    It reads of the rings ``region`` (their region), its ``locator`` and the rings' arrays ``closed``
    (:func:`medialaxis.planar.boundary.corners.ring_arrays`); ``show_progress`` False: no bar over the rounds (a layer
    has its own over the features)."""
    # sample(rings, _start_arcs(...)) in one compiled call
    first, first_arc, first_ring, first_next = first_sample(
        closed.xy, closed.s, closed.start, _start_length(region, min_length), float(tolerance), float(min_length),
        RATIO)
    ring_length = closed.s[closed.start[1:] - 1]
    n_real = len(first)
    if n_real < 3:
        return None  # the reference raises the error
    lo, extent = sample_box(first)
    if extent <= 0:
        return None
    shaken = jitter(max(4 * n_real, 4096))
    (points, arc, ring, nxt, x, y, near, tv, tn, centre, radius, where, memo, batch, hint) = first_state(
        first, first_arc, first_ring, first_next, lo, extent, FAR_CORNERS, shaken)
    count = 2
    rounds = progress(range(MAX_REFINEMENTS), desc="adaptive sampling", show=show_progress)
    next(rounds, None)
    round_, inserted, settled = 0, False, False
    try:
        while True:
            (status, now, settled, count, x, y, tv, tn, batch, hint, near, points, centre, radius, where, memo, arc,
             ring, nxt, unsure, gx, gy) = incremental_rounds(
                round_, inserted, settled, MAX_REFINEMENTS, ONE_ROUND_ABOVE, count, x, y, tv, tn, batch, hint, near,
                points, centre, radius, where, memo, arc, ring, nxt, 1e-7 * extent, locator.segments, locator.start,
                locator.members, locator.y0, locator.height, closed.s, closed.xy, closed.start, closed.convex,
                closed.touching, ring_length, lo, extent, shaken, float(tolerance), float(min_length), RATIO, SETTLED_SHARE,
                float(over_split))
            for _ in range(now - round_):  # the rounds done, for the progress bar
                next(rounds, None)
            round_, inserted = now, status in (ASK_GEOS, MORE_JITTER)
            if status == FAILED:
                return None
            if status == ASK_GEOS:
                shapely.prepare(region)
                where[unsure] = shapely.contains_xy(region, gx, gy)
            elif status == MORE_JITTER:
                shaken = jitter(2 * len(shaken))
            elif status == DONE:
                break
    finally:
        rounds.close()
    n = len(x)
    return _assembled(points[CORNERS:n], arc[CORNERS:n], ring[CORNERS:n], ring_length, tv, tn, count,
                      centre, radius, where)


def _assembled(
    points: np.ndarray, arc: np.ndarray, ring: np.ndarray, ring_length: np.ndarray, tv: np.ndarray, tn: np.ndarray,
    count: int, centre: np.ndarray, radius: np.ndarray, where: np.ndarray,
) -> tuple[BoundarySample, Triangulation, np.ndarray]:
    """The sample in ring and arc order, its triangulation (no corner) and the inner triangles (compiled: :func:`assembled`)."""
    pts, ring, arc, nxt, simplices, neighbors, centres, radii, inside = assembled(
        points, arc, ring, len(ring_length), tv, tn, count, centre, radius, where)
    smp = BoundarySample(pts, ring, arc, ring_length, nxt)
    return smp, Triangulation(pts, simplices, neighbors, centres, radii), inside
