"""Planar shapes with known medial axes or known hole counts, as polygons and images.

Analytic shapes (:func:`ellipse`, :func:`annulus`, :func:`capsule`, a
rectangle) come with their exact medial axes as segments
(:func:`rectangle_axis`, :func:`ellipse_axis`; the annulus's is the circle of
the mean radius, the capsule's its core segment), which
:func:`~medialaxis.datasets.segment_distance` measures a result against.
:func:`holed_shapes` are plates with 1 to 3 round and square holes
(:data:`HOLES`); :func:`render` and :func:`rasterize` turn any of them into
an anti-aliased image, and :func:`raster_counts` counts the pieces and holes
of a mask with scikit-image, independently of medialaxis.

>>> import numpy as np
>>> import shapely
>>> import medialaxis as mx
>>> from medialaxis.datasets import rectangle_axis, segment_distance
>>> ma = mx.medial_axis(shapely.box(-2, -1, 2, 1))
>>> bool(segment_distance(ma.points, rectangle_axis(4, 2)).max() < 0.01)
True
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["rotation", "rectangle_axis", "ellipse", "ellipse_axis", "annulus", "capsule", "render", "in_image",
           "holed_shapes", "HOLES", "rasterize", "raster_counts"]

Segments = list[tuple[tuple[float, float], tuple[float, float]]]

#: Holes of each shape of :func:`holed_shapes`.
HOLES = {"washer": 1, "figure8": 2, "plate3": 3, "square_ring": 1, "bracket2": 2, "mixed3": 3}


def rotation(deg: float) -> np.ndarray:
    """The (2, 2) matrix of a rotation by ``deg`` degrees (counter-clockwise).

    Examples
    --------
    >>> (rotation(90) @ [1.0, 0.0]).round(12).tolist()
    [0.0, 1.0]
    """
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[c, -s], [s, c]])


def rectangle_axis(w: float, h: float) -> Segments:
    """Segments of the medial axis of the rectangle [-w/2, w/2] x [-h/2, h/2] (w >= h).

    Examples
    --------
    >>> rectangle_axis(4, 2)[0]
    ((-1.0, 0), (1.0, 0))
    """
    a, b = w / 2, h / 2
    j = a - b
    return [((-j, 0), (j, 0)), ((-j, 0), (-a, -b)), ((-j, 0), (-a, b)), ((j, 0), (a, b)), ((j, 0), (a, -b))]


def ellipse(a: float = 2.0, b: float = 1.0, n: int = 2000) -> Any:
    """The ellipse of semi-axes ``a`` (along x) and ``b`` as a shapely polygon of ``n`` vertices.

    Its medial axis is :func:`ellipse_axis`.

    Examples
    --------
    >>> import medialaxis as mx
    >>> from medialaxis.datasets import segment_distance
    >>> ma = mx.medial_axis(ellipse())
    >>> bool(segment_distance(ma.points, ellipse_axis()).max() < 1e-3)
    True
    """
    from shapely.geometry import Polygon

    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return Polygon(np.c_[a * np.cos(t), b * np.sin(t)])


def ellipse_axis(a: float = 2.0, b: float = 1.0) -> Segments:
    """The medial axis of :func:`ellipse` (a >= b): the segment between the centres of curvature of its ends.

    Examples
    --------
    >>> ellipse_axis(2.0, 1.0)
    [((-1.5, 0.0), (1.5, 0.0))]
    """
    c = (a * a - b * b) / a
    return [((-c, 0.0), (c, 0.0))]


def annulus(r_out: float = 2.0, r_in: float = 1.0) -> Any:
    """The ring between two circles about the origin; its medial axis is the circle of radius ``(r_out + r_in) / 2``.

    Examples
    --------
    >>> import numpy as np
    >>> import medialaxis as mx
    >>> ma = mx.medial_axis(annulus())
    >>> ma.n_cycles, bool(np.abs(np.linalg.norm(ma.points, axis=1) - 1.5).max() < 0.01)
    (1, True)
    """
    from shapely.geometry import Point

    return Point(0, 0).buffer(r_out, quad_segs=256).difference(Point(0, 0).buffer(r_in, quad_segs=256))


def capsule(length: float = 4.0, radius: float = 0.5) -> Any:
    """A stadium: the points within ``radius`` of the segment of ``length`` along x; that segment is its axis.

    Examples
    --------
    >>> import numpy as np
    >>> import medialaxis as mx
    >>> ma = mx.medial_axis(capsule(4.0, 0.5))
    >>> len(ma.endpoints), bool(np.allclose(np.median(ma.radii), 0.5, atol=1e-3))
    (2, True)
    """
    import shapely

    return shapely.LineString([(-length / 2, 0), (length / 2, 0)]).buffer(radius, quad_segs=128)


def render(geom: Any, shape: tuple[int, int] = (512, 512), supersample: int = 4) -> np.ndarray:
    """Anti-aliased rendering of a geometry: the fraction of each pixel it covers (row, col = y, x).

    Examples
    --------
    >>> import shapely
    >>> render(shapely.box(0.5, 0.5, 2.5, 1.5), (3, 4)).tolist()
    [[0.0, 0.0, 0.0, 0.0], [0.0, 1.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0]]
    """
    import shapely

    rows, cols = shape
    s = supersample
    yy, xx = np.mgrid[0:rows * s, 0:cols * s]
    y = (yy + 0.5) / s - 0.5
    x = (xx + 0.5) / s - 0.5
    inside = shapely.contains_xy(geom, x.ravel(), y.ravel()).reshape(rows * s, cols * s)
    return inside.reshape(rows, s, cols, s).mean(axis=(1, 3))


def in_image(geom: Any, deg: float, center: tuple[float, float] = (256.0, 256.0)) -> Any:
    """``geom`` (given in (x, y) about 0) rotated by ``deg`` degrees and moved to ``center`` (row, col).

    Examples
    --------
    >>> import shapely
    >>> in_image(shapely.Point(1, 0), 90, center=(10.0, 20.0)).wkt
    'POINT (20 11)'
    """
    from shapely import affinity

    g = affinity.rotate(geom, deg, origin=(0, 0))
    return affinity.translate(g, center[1], center[0])


def _disc(x: float, y: float, r: float) -> Any:
    from shapely.geometry import Point

    return Point(x, y).buffer(r, quad_segs=64)


def _square(x: float, y: float, side: float) -> Any:
    from shapely.geometry import box

    return box(x - side / 2, y - side / 2, x + side / 2, y + side / 2)


def holed_shapes() -> dict[str, Any]:
    """Plates about the origin (in pixels, about 200 across) with 1, 2 and 3 holes, round and square.

    Returns
    -------
    dict of str to shapely.Polygon
        The shapes by name; :data:`HOLES` gives each one's number of holes
        (the cycles of its medial axis).

    Examples
    --------
    >>> import medialaxis as mx
    >>> shapes = holed_shapes()
    >>> all(len(shape.interiors) == HOLES[name] for name, shape in shapes.items())
    True
    >>> mx.medial_axis(shapes["plate3"]).n_cycles
    3
    """
    import shapely
    from shapely.geometry import box

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


def rasterize(geom: Any, size: int, angle: float, kind: str, supersample: int = 4) -> np.ndarray:
    """``geom`` rotated by ``angle`` degrees, centred in a ``size`` x ``size`` image of ``kind``.

    Kinds: ``"bool"`` (pixel centre coverage above one half), ``"float"``
    (anti-aliased coverage in [0, 1]), ``"uint8"`` (coverage * 255).

    Examples
    --------
    >>> image = rasterize(holed_shapes()["washer"], 320, 30, "uint8")
    >>> image.shape, image.dtype.name, raster_counts(image > 127)
    ((320, 320), 'uint8', (1, 1))
    """
    from shapely import affinity

    if kind not in ("bool", "float", "uint8"):
        raise InvalidInputError(f"kind must be 'bool', 'float' or 'uint8', got {kind!r}")
    g = affinity.translate(affinity.rotate(geom, angle, origin=(0, 0)), size / 2, size / 2)
    cover = render(g, (size, size), supersample)
    if kind == "bool":
        return cover > 0.5
    if kind == "float":
        return cover
    return np.round(cover * 255).astype(np.uint8)


def raster_counts(mask: np.ndarray) -> tuple[int, int]:
    """(pieces, holes) of a bool mask, counted by scikit-image (``label`` and ``euler_number``).

    Foreground pixels are 4-connected (``connectivity=1``), so pixels that
    touch only at a corner are separate pieces and the background around
    them is one: the convention of the sub-pixel contour
    (``skimage.measure.find_contours``), documented for raster inputs.

    Examples
    --------
    >>> import numpy as np
    >>> ring = np.ones((5, 5), bool)
    >>> ring[2, 2] = False
    >>> raster_counts(ring)
    (1, 1)
    """
    from skimage.measure import euler_number, label

    pieces = int(label(mask, connectivity=1).max())
    return pieces, pieces - int(euler_number(mask, connectivity=1))
