"""Meshes with known medial axes: unions of capsules (a tripod among them) and a torus.

The capsule shapes are built as watertight triangle meshes by marching cubes
over a signed distance function (scikit-image), so their exact medial axes
are known: a capsule of radius ``r`` around a segment has that segment as its
curve skeleton and ``r`` as its radius (:func:`segment_distance` measures a
result against it). The torus's medial axis is its core circle.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.errors import InvalidInputError

__all__ = ["tripod_segments", "capsules_mesh", "tripod_mesh", "segment_distance", "torus_mesh"]


def tripod_segments(arm: float = 3.0, *, tilt_degrees: float = 30.0) -> np.ndarray:
    """The three axis segments ``(3, 2, 3)`` of a tripod: from the origin, 120 degrees apart, tilted down.

    Examples
    --------
    >>> import numpy as np
    >>> from medialaxis.datasets import tripod_segments
    >>> segments = tripod_segments(3.0)
    >>> segments.shape, np.linalg.norm(segments[:, 1] - segments[:, 0], axis=1).round(6).tolist()
    ((3, 2, 3), [3.0, 3.0, 3.0])
    """
    tilt = np.radians(tilt_degrees)
    segments = np.zeros((3, 2, 3))
    for k in range(3):
        phi = 2.0 * np.pi * k / 3.0
        segments[k, 1] = arm * np.array([np.cos(tilt) * np.cos(phi), np.cos(tilt) * np.sin(phi), -np.sin(tilt)])
    return segments


def segment_distance(points: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """Distance ``(n,)`` from each point to the nearest of ``segments`` ``(s, 2, d)``, in any dimension ``d``.

    Examples
    --------
    >>> from medialaxis.datasets import segment_distance
    >>> segment_distance([[0.5, 2.0], [3.0, 0.0]], [[[0, 0], [1, 0]]]).tolist()
    [2.0, 2.0]
    """
    points = np.asarray(points, dtype=np.float64)
    best = np.full(len(points), np.inf)
    for a, b in np.asarray(segments, dtype=np.float64):
        ab = b - a
        t = np.clip(((points - a) @ ab) / max(float(ab @ ab), 1e-300), 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(points - (a + t[:, None] * ab), axis=1))
    return best


def capsules_mesh(segments: Any, radius: float, *, pitch: float) -> Any:
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
    >>> from medialaxis.datasets import capsules_mesh
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


def tripod_mesh(*, radius: float = 0.5, arm: float = 3.0, pitch: float = 0.08) -> Any:
    """A tripod of three capsules (see :func:`tripod_segments`) as a watertight mesh.

    Its curve skeleton is the three segments of :func:`tripod_segments`, its radius ``radius``.

    Examples
    --------
    >>> from medialaxis.datasets import tripod_mesh
    >>> bool(tripod_mesh(pitch=0.2).is_watertight)
    True
    """
    return capsules_mesh(tripod_segments(arm), radius, pitch=pitch)


def torus_mesh(major_radius: float = 1.0, minor_radius: float = 0.35, *, sections: tuple[int, int] = (64, 24)) -> Any:
    """A solid torus as a watertight mesh (trimesh's ``creation.torus``).

    Its medial axis is the core circle of radius ``major_radius`` in the plane z = 0, with radius
    ``minor_radius`` (for the smooth torus; the mesh is a polyhedron of ``sections`` faces around
    the core and around the tube).

    Examples
    --------
    >>> from medialaxis.datasets import torus_mesh
    >>> mesh = torus_mesh()
    >>> bool(mesh.is_watertight), int(mesh.euler_number)
    (True, 0)
    """
    trimesh = require("trimesh", "medialaxis[mesh]")
    return trimesh.creation.torus(major_radius=major_radius, minor_radius=minor_radius, major_sections=sections[0],
                                  minor_sections=sections[1])
