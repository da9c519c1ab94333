"""Where the holes of a mask are and which face of an axis graph holds each (test helpers).

The shapes and their independent hole counts (scikit-image) are in
:mod:`medialaxis.datasets` (``holed_shapes``, ``rasterize``, ``raster_counts``).
"""

from __future__ import annotations

import numpy as np
import shapely


def hole_points(mask: np.ndarray) -> np.ndarray:
    """(h, 2) one (row, col) per hole of ``mask``: its pixel farthest from the shape."""
    from scipy.ndimage import distance_transform_edt
    from skimage.measure import label

    background = label(~mask, connectivity=1)
    border = np.unique(np.concatenate([background[0], background[-1], background[:, 0], background[:, -1]]))
    depth = distance_transform_edt(~mask)
    out = []
    for k in range(1, int(background.max()) + 1):
        if k in border:
            continue
        idx = np.flatnonzero(background.ravel() == k)
        out.append(np.unravel_index(idx[np.argmax(depth.ravel()[idx])], mask.shape))
    return np.array(out, np.float64).reshape(-1, 2)


def faces_around(ma, points: np.ndarray) -> np.ndarray:
    """Index of the bounded face of the axis graph that contains each point (-1: none).

    The faces of a plane graph do not overlap (shapely gives a face with an
    island inside it a hole), so a point lies in one face at most.
    """
    lines = [shapely.LineString(ma.points[[i, j]]) for i, j in ma.edges]
    faces = shapely.get_parts(shapely.polygonize(lines))
    out = np.full(len(points), -1)
    for f, face in enumerate(faces):
        inside = shapely.contains_xy(face, points[:, 0], points[:, 1])
        assert not (inside & (out >= 0)).any(), "faces overlap"
        out[inside] = f
    return out
