"""Distances between a shape and its reconstruction."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

__all__ = ["ReconstructionError", "compare_regions", "boundary_samples"]


@dataclasses.dataclass(frozen=True)
class ReconstructionError:
    """How well the union of medial balls rebuilds the shape.

    Attributes
    ----------
    iou : float
        Area of intersection over area of union (1 is perfect).
    hausdorff : float
        Two-sided Hausdorff distance between the two boundaries.
    mean_distance : float
        Mean distance from each boundary to the other (symmetrised).
    """

    iou: float
    hausdorff: float
    mean_distance: float


def boundary_samples(geom: Any, step: float) -> np.ndarray:
    """Points every ``step`` along the boundary of ``geom`` (vertices included)."""
    import shapely

    dense = shapely.segmentize(geom.boundary, step)
    return shapely.get_coordinates(dense)


def compare_regions(rebuilt: Any, original: Any, step: float | None = None) -> ReconstructionError:
    """IoU, Hausdorff and mean boundary distance between two planar regions."""
    import shapely

    inter = shapely.intersection(rebuilt, original).area
    union = shapely.union(rebuilt, original).area
    iou = float(inter / union) if union > 0 else 0.0
    if step is None:
        minx, miny, maxx, maxy = original.bounds
        step = float(np.hypot(maxx - minx, maxy - miny)) / 2000.0
    a = boundary_samples(rebuilt, step)
    b = boundary_samples(original, step)
    shapely.prepare(original.boundary)
    shapely.prepare(rebuilt.boundary)
    da = shapely.distance(shapely.points(a), original.boundary) if len(a) else np.array([np.inf])
    db = shapely.distance(shapely.points(b), rebuilt.boundary) if len(b) else np.array([np.inf])
    hausdorff = float(max(da.max(), db.max()))
    mean = float(0.5 * (da.mean() + db.mean()))
    return ReconstructionError(iou, hausdorff, mean)
