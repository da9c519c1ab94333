"""Adaptive boundary sampling: sample, triangulate, and refine where the Delaunay triangulation misses the boundary.

The samples start evenly spaced along the rings and are refined piece by
piece until every boundary piece is a Delaunay edge (the triangulation
conforms) and each inner circumcentre lies within the tolerance of the
axis of the sampled shape (:func:`medialaxis.planar.sampling.refine_arcs`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis._progress import progress
from medialaxis.planar._kernels import piece_state
from medialaxis.planar.axis import inner_triangles
from medialaxis.planar.delaunay import Triangulation, triangulate
from medialaxis.planar.sampling import BoundarySample, Rings, initial_arcs, refine_arcs, sample

__all__ = ["sample_and_triangulate", "MAX_REFINEMENTS"]

#: Most rounds of refinement.
MAX_REFINEMENTS = 12


def sample_and_triangulate(
    rings: Rings, region: Any, tolerance: float, min_length: float
) -> tuple[BoundarySample, Triangulation, np.ndarray]:
    """Samples of ``rings``, their Delaunay triangulation and its triangles inside ``region``.

    Pieces start about ``sqrt(area) / 8`` long (never below ``min_length``)
    and are split until they conform and are within ``tolerance``, at most
    :data:`MAX_REFINEMENTS` rounds.
    """
    area = max(region.area, 1e-300)
    start = max(min_length, np.sqrt(area) / 8.0)
    arcs: list[np.ndarray] | None = initial_arcs(rings, start)
    settled = False
    locator = rings.locator if region is rings.region else None
    for _ in progress(range(MAX_REFINEMENTS), desc="adaptive sampling"):
        smp = sample(rings, arcs)
        tri = triangulate(smp.points)
        inside = inner_triangles(tri, region, locator)
        if settled:
            break
        conforming, radius = piece_state(tri.simplices, inside, tri.radii, smp.next)
        arcs = refine_arcs(arcs, smp, radius, conforming, tolerance, min_length)
        if arcs is None:
            break
        # Only a handful of pieces near tips were split: triangulate once more and stop.
        settled = conforming.all() and sum(map(len, arcs)) - len(smp.points) < 0.05 * len(smp.points)
    return smp, tri, inside
