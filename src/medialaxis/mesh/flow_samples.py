"""Generated test shapes for the diffusion-flow skeleton: capsules, a tripod, a torus.

The shapes are built as watertight triangle meshes by marching cubes over a
signed distance function (scikit-image), so their exact medial axes are known:
a capsule of radius ``r`` around a segment has that segment as its curve
skeleton and ``r`` as its radius.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from medialaxis._optional import require
from medialaxis.errors import InvalidInputError

__all__ = ["tripod_segments", "capsules_mesh", "tripod_mesh", "segment_distance"]


def tripod_segments(arm: float = 3.0, *, tilt_degrees: float = 30.0) -> np.ndarray:
    """The three axis segments ``(3, 2, 3)`` of a tripod: from the origin, 120 degrees apart, tilted down."""
    tilt = np.radians(tilt_degrees)
    segments = np.zeros((3, 2, 3))
    for k in range(3):
        phi = 2.0 * np.pi * k / 3.0
        segments[k, 1] = arm * np.array([np.cos(tilt) * np.cos(phi), np.cos(tilt) * np.sin(phi), -np.sin(tilt)])
    return segments


def segment_distance(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Distance ``(n,)`` from each point to the nearest of ``segments`` ``(s, 2, 3)``."""
    points = np.asarray(points, dtype=np.float64)
    best = np.full(len(points), np.inf)
    for a, b in np.asarray(segments, dtype=np.float64):
        ab = b - a
        t = np.clip(((points - a) @ ab) / max(float(ab @ ab), 1e-300), 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(points - (a + t[:, None] * ab), axis=1))
    return best


def capsules_mesh(segments: Sequence[Sequence[Sequence[float]]], radius: float, *, pitch: float) -> object:
    """Watertight mesh of the union of capsules (marching cubes, grid step ``pitch``).

    Parameters
    ----------
    segments : (s, 2, 3) array_like
        Capsule axes.
    radius : float
        Capsule radius (> 0).
    pitch : float
        Grid step; the vertex count grows as ``pitch ** -2``.

    Returns
    -------
    trimesh.Trimesh

    Raises
    ------
    InvalidInputError
        Non-positive radius or pitch, or segments of the wrong shape.

    Examples
    --------
    >>> from medialaxis.mesh.flow_samples import capsules_mesh
    >>> m = capsules_mesh([[[0, 0, 0], [2, 0, 0]]], 0.5, pitch=0.1)
    >>> bool(m.is_watertight)
    True
    """
    trimesh = require("trimesh", "medialaxis[mesh]")
    from skimage.measure import marching_cubes

    segs = np.asarray(segments, dtype=np.float64)
    if segs.ndim != 3 or segs.shape[1:] != (2, 3):
        raise InvalidInputError(f"segments must have shape (s, 2, 3), got {segs.shape}")
    if not (radius > 0 and pitch > 0):
        raise InvalidInputError(f"radius and pitch must be positive, got {radius} and {pitch}")
    lo = segs.reshape(-1, 3).min(axis=0) - radius - 2 * pitch
    hi = segs.reshape(-1, 3).max(axis=0) + radius + 2 * pitch
    axes = [np.arange(lo[d], hi[d] + pitch, pitch) for d in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    sdf = (segment_distance(grid, segs) - radius).reshape(len(axes[0]), len(axes[1]), len(axes[2]))
    verts, faces, _n, _v = marching_cubes(sdf, level=0.0, spacing=(pitch, pitch, pitch))
    mesh = trimesh.Trimesh(verts + lo, faces[:, ::-1], process=True, validate=True)
    if mesh.volume < 0:
        mesh.invert()
    return mesh


def tripod_mesh(*, radius: float = 0.5, arm: float = 3.0, pitch: float = 0.08) -> object:
    """A tripod of three capsules (see :func:`tripod_segments`) as a watertight mesh."""
    return capsules_mesh(tripod_segments(arm), radius, pitch=pitch)
