"""The boundary route of "A Qualitative Approach for Medial Computation": Canny edge pixels as the point set.

The edge pixels of the image (:func:`skimage.feature.canny`) choose the
samples: each edge pixel is moved to its nearest point on the sub-pixel
iso-contour (at most about half a pixel away), which gives it a ring and an
arc position. In arc order the samples of each ring form a polygon that
never crosses itself, so the triangles are classified against the filled
region exactly as on the contour route and the detour test of the pruning
applies unchanged. Unlike the contour route, the sample density is fixed by
the pixels (about one sample per pixel of boundary) rather than adaptive.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.errors import EmptyShapeError
from medialaxis.planar.axis import inner_triangles
from medialaxis.planar.boundary.sampling import BoundarySample, Rings, initial_arcs, sample, simplify_rings
from medialaxis.planar.delaunay import Triangulation, triangulate
from medialaxis.planar.reading.inputs import PlanarInput

__all__ = ["canny_stages", "edge_pixels"]


def edge_pixels(src: PlanarInput, sigma: float = 1.0) -> np.ndarray:
    """(N, 2) Canny edge pixel coordinates (index order times spacing)."""
    from skimage.feature import canny

    if src.image.dtype == bool:
        image, background = src.foreground.astype(np.float64), 0.0
    else:
        image = src.image.astype(np.float64)
        # The frame is padded with background, so the border makes no edge.
        background = float(image.max() if src.side == "dark" else image.min())
    padded = np.pad(image, 2, mode="constant", constant_values=background)
    edges = canny(padded, sigma=sigma)[2:-2, 2:-2]
    pts = np.argwhere(edges).astype(np.float64) * src.spacing
    if len(pts) < 3:
        raise EmptyShapeError("Canny found fewer than 3 edge pixels")
    return pts


def canny_stages(src: PlanarInput, tolerance: float) -> tuple[BoundarySample, Rings, Triangulation, np.ndarray]:
    """Sample, rings, triangulation and inner-triangle mask of the Canny route.

    References
    ----------
    .. [1] "A Qualitative Approach for Medial Computation" (Voronoi/Delaunay medial axis of a 2D
           image; authors, venue and year unconfirmed: docs/references.md).
    .. [2] J. Canny, "A computational approach to edge detection", IEEE Transactions on Pattern
           Analysis and Machine Intelligence 8(6):679-698, 1986. doi:10.1109/TPAMI.1986.4767851
    """
    pixels = edge_pixels(src)
    rings = simplify_rings(src.region, tolerance)
    step = 0.1 * float(src.spacing.min())
    dense = sample(rings, initial_arcs(rings, step))
    _, nearest = cKDTree(dense.points).query(pixels)
    # One sample per distinct contour position, in ring order.
    nearest = np.unique(nearest)
    arcs = [np.sort(dense.arc[nearest[dense.ring[nearest] == r]]) for r in range(len(rings.vertices))]
    # A ring without edge pixels (a tiny hole Canny smoothed away) keeps its vertices.
    arcs = [a if len(a) >= 3 else initial_arcs(Rings([v], rings.region), np.inf)[0] for a, v in zip(arcs, rings.vertices)]
    smp = sample(rings, arcs)
    tri = triangulate(smp.points)
    inside = inner_triangles(tri, rings.region)
    return smp, rings, tri, inside
