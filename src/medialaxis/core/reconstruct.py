"""Rebuild a shape as the union of its medial balls.

The validation step of "A Qualitative Approach for Medial Computation"
(docs/references.md).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["reconstruct", "union_of_discs", "rasterize"]


def union_of_discs(points: np.ndarray, radii: np.ndarray, edges: np.ndarray, resolution: int = 16) -> Any:
    """Union of the discs at ``points`` and of the tapered capsules along ``edges``.

    A capsule (convex hull of the two end discs) is the union of the discs
    centred along the edge with linearly varying radius, so the result is the
    union of balls of the continuous axis, not only of its sampled points.
    """
    import shapely

    pts = shapely.points(points)
    discs = shapely.buffer(pts, np.maximum(radii, 0.0), quad_segs=resolution)
    parts = [discs]
    if len(edges):
        pair = shapely.union(discs[edges[:, 0]], discs[edges[:, 1]])
        parts.append(shapely.convex_hull(pair))
    return shapely.union_all(np.concatenate(parts))


def rasterize(geom: Any, image_shape: tuple[int, int], spacing: Any) -> np.ndarray:
    """Boolean image: pixels whose centre (index * spacing) lies in ``geom``."""
    import shapely

    sp = np.broadcast_to(np.asarray(spacing, np.float64), (2,))
    rows, cols = np.indices(image_shape)
    shapely.prepare(geom)
    inside = shapely.contains_xy(geom, (rows * sp[0]).ravel(), (cols * sp[1]).ravel())
    return inside.reshape(image_shape)


def reconstruct(ma: Any, *, raster: bool = False, resolution: int = 16) -> Any:
    """See :meth:`medialaxis.MedialAxis.reconstruct`.

    References
    ----------
    .. [1] "A Qualitative Approach for Medial Computation" (Voronoi/Delaunay medial axis of a 2D
           image; authors, venue and year unconfirmed: docs/references.md).
    """
    if ma.dim != 2:
        raise InvalidInputError("reconstruct() rebuilds planar shapes; this axis is 3D")
    if int(resolution) < 1:
        raise InvalidInputError(f"resolution must be >= 1, got {resolution!r}")
    geom = union_of_discs(ma.points, ma.radii, ma.edges, int(resolution))
    if not raster:
        return geom
    if ma.frame != "image":
        raise InvalidInputError("raster=True needs an axis computed from an image")
    return rasterize(geom, tuple(ma.metadata["image_shape"]), ma.metadata.get("spacing", (1.0, 1.0)))
