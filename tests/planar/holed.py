"""Plates with round and square holes, their rasterizations, and independent hole counts.

The truth of every test here comes from scikit-image (``label`` and
``euler_number`` of the rasterized mask), never from medialaxis.
"""

from __future__ import annotations

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import Point, box

from tests.planar.shapes import render


def _disc(x: float, y: float, r: float):
    return Point(x, y).buffer(r, quad_segs=64)


def _square(x: float, y: float, side: float):
    return box(x - side / 2, y - side / 2, x + side / 2, y + side / 2)


def holed_shapes() -> dict[str, shapely.Geometry]:
    """Shapes about the origin (pixels) with 1, 2 and 3 holes, round and square."""
    washer = _disc(0, 0, 90).difference(_disc(0, 0, 35))
    eight = shapely.union_all([_disc(0, -50, 58), _disc(0, 50, 58)]).difference(
        shapely.union_all([_disc(0, -50, 24), _disc(0, 50, 24)])
    )
    plate3 = box(-100, -60, 100, 60).difference(shapely.union_all([_disc(x, 0, 18) for x in (-60, 0, 60)]))
    square_ring = _square(0, 0, 180).difference(_square(0, 0, 90))
    bracket2 = box(-100, -55, 100, 55).difference(shapely.union_all([_square(-50, 0, 40), _square(50, 0, 40)]))
    mixed3 = _disc(0, 0, 105).difference(
        shapely.union_all([_square(-45, -25, 36), _square(45, -25, 36), _disc(0, 45, 20)])
    )
    return {
        "washer": washer,
        "figure8": eight,
        "plate3": plate3,
        "square_ring": square_ring,
        "bracket2": bracket2,
        "mixed3": mixed3,
    }


def rasterize(geom, size: int, angle: float, kind: str, supersample: int = 4) -> np.ndarray:
    """``geom`` rotated by ``angle`` degrees, centred in a ``size`` x ``size`` image of ``kind``.

    Kinds: ``"bool"`` (pixel centre coverage above one half), ``"float"``
    (anti-aliased coverage in [0, 1]), ``"uint8"`` (coverage * 255).
    """
    g = affinity.translate(affinity.rotate(geom, angle, origin=(0, 0)), size / 2, size / 2)
    cover = render(g, (size, size), supersample)
    if kind == "bool":
        return cover > 0.5
    if kind == "float":
        return cover
    if kind == "uint8":
        return np.round(cover * 255).astype(np.uint8)
    raise ValueError(kind)


def truth_counts(mask: np.ndarray) -> tuple[int, int]:
    """(pieces, holes) of a bool mask, counted by scikit-image.

    Foreground pixels are 4-connected (``connectivity=1``), so pixels that
    touch only at a corner are separate pieces and the background around
    them is one: the convention of the sub-pixel contour
    (``skimage.measure.find_contours``), documented for raster inputs.
    """
    from skimage.measure import euler_number, label

    pieces = int(label(mask, connectivity=1).max())
    return pieces, pieces - int(euler_number(mask, connectivity=1))


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
