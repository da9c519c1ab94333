"""Analytic shapes with known medial axes, as polygons and anti-aliased images."""

from __future__ import annotations

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import Point, Polygon


def rotation(deg: float) -> np.ndarray:
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[c, -s], [s, c]])


def segment_distance(p: np.ndarray, a, b) -> np.ndarray:
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    ab = b - a
    t = np.clip(((p - a) @ ab) / (ab @ ab), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def rectangle_axis(w: float, h: float) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """Segments of the medial axis of the rectangle [-w/2, w/2] x [-h/2, h/2] (w >= h)."""
    a, b = w / 2, h / 2
    j = a - b
    return [((-j, 0), (j, 0)), ((-j, 0), (-a, -b)), ((-j, 0), (-a, b)), ((j, 0), (a, b)), ((j, 0), (a, -b))]


def distance_to_segments(p: np.ndarray, segments) -> np.ndarray:
    return np.min([segment_distance(p, a, b) for a, b in segments], axis=0)


def ellipse(a: float = 2.0, b: float = 1.0, n: int = 2000) -> Polygon:
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return Polygon(np.c_[a * np.cos(t), b * np.sin(t)])


def ellipse_axis(a: float = 2.0, b: float = 1.0):
    c = (a * a - b * b) / a
    return [((-c, 0.0), (c, 0.0))]


def annulus(r_out: float = 2.0, r_in: float = 1.0) -> Polygon:
    return Point(0, 0).buffer(r_out, quad_segs=256).difference(Point(0, 0).buffer(r_in, quad_segs=256))


def capsule(length: float = 4.0, radius: float = 0.5) -> Polygon:
    return shapely.LineString([(-length / 2, 0), (length / 2, 0)]).buffer(radius, quad_segs=128)


def render(geom, shape=(512, 512), supersample: int = 4) -> np.ndarray:
    """Anti-aliased rendering: fraction of each pixel covered (row, col = y, x)."""
    rows, cols = shape
    s = supersample
    yy, xx = np.mgrid[0:rows * s, 0:cols * s]
    y = (yy + 0.5) / s - 0.5
    x = (xx + 0.5) / s - 0.5
    inside = shapely.contains_xy(geom, x.ravel(), y.ravel()).reshape(rows * s, cols * s)
    return inside.reshape(rows, s, cols, s).mean(axis=(1, 3))


def in_image(geom, deg: float, center=(256.0, 256.0)):
    """Rotate ``geom`` (given in (x, y) about 0) and move it to the image centre."""
    g = affinity.rotate(geom, deg, origin=(0, 0))
    return affinity.translate(g, center[1], center[0])
