"""What a 3D picture of a result draws, shared by the HTML page and the PNG.

Plain NumPy, no plotting library: the input shell thinned to a face budget
(vertex clustering), the spheres of a simplified result as low-polygon balls,
and axis ranges with one scale on all three axes that never collapse to
zero width (a flat skeleton lies in a plane).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

__all__ = ["Surface", "cluster_decimate", "equal_ranges", "shell_of", "sphere_meshes"]


class Surface(NamedTuple):
    """A triangle surface without a mesh library: the isosurface kept by volume results.

    ``trimesh.Trimesh(*surface)`` turns it into a mesh.
    """

    vertices: np.ndarray
    faces: np.ndarray


def shell_of(ma: Any, surface: Any = None) -> tuple[np.ndarray, np.ndarray] | None:
    """The input surface to draw around ``ma`` as ``(vertices, faces)``, or None."""
    shell = surface if surface is not None else ma.shape
    if shell is None or not (hasattr(shell, "vertices") and hasattr(shell, "faces")):
        return None
    v = np.asarray(shell.vertices, np.float64).reshape(-1, 3)
    f = np.asarray(shell.faces, np.int64).reshape(-1, 3)
    return (v, f) if len(f) else None


def cluster_decimate(vertices: np.ndarray, faces: np.ndarray, max_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """At most ``max_faces`` triangles by merging the vertices of each grid cell.

    Good enough for a translucent context shell (it may change the topology of
    details smaller than a cell); the grid is made coarser until the budget holds.
    """
    if len(faces) <= max_faces:
        return vertices, faces
    tri = vertices[faces]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum()
    cell = max(np.sqrt(2.0 * area / max_faces), 1e-12)
    lo = vertices.min(axis=0)
    while True:
        keys = np.floor((vertices - lo) / cell).astype(np.int64)
        _, cluster, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
        cluster = cluster.reshape(-1)
        merged = np.zeros((len(counts), 3))
        np.add.at(merged, cluster, vertices)
        merged /= counts[:, None]
        out = cluster[faces]
        good = (out[:, 0] != out[:, 1]) & (out[:, 1] != out[:, 2]) & (out[:, 2] != out[:, 0])
        out = out[good]
        _, first = np.unique(np.sort(out, axis=1), axis=0, return_index=True)
        out = out[np.sort(first)]
        if len(out) <= max_faces:
            used = np.unique(out)
            index = np.full(len(merged), -1, np.int64)
            index[used] = np.arange(len(used))
            return merged[used], index[out]
        cell *= 1.25


def _unit_ball() -> tuple[np.ndarray, np.ndarray]:
    """An icosahedron subdivided once and pushed onto the unit sphere (42 vertices, 80 faces)."""
    t = (1.0 + 5.0**0.5) / 2.0
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
         [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
         [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    verts = [np.asarray(p, float) / np.linalg.norm(p) for p in v]
    middle: dict[tuple[int, int], int] = {}

    def mid(a: int, b: int) -> int:
        key = (min(a, b), max(a, b))
        if key not in middle:
            p = verts[a] + verts[b]
            verts.append(p / np.linalg.norm(p))
            middle[key] = len(verts) - 1
        return middle[key]

    faces = []
    for a, b, c in f:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        faces += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
    return np.array(verts), np.array(faces, np.int64)


def sphere_meshes(centres: np.ndarray, radii: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One low-polygon ball per sphere: ``(vertices, faces, radius per vertex)``."""
    ball_v, ball_f = _unit_ball()
    n, k = len(centres), len(ball_v)
    vertices = (centres[:, None, :] + radii[:, None, None] * ball_v[None]).reshape(-1, 3)
    faces = (ball_f[None] + (k * np.arange(n))[:, None, None]).reshape(-1, 3)
    return vertices, faces, np.repeat(radii, k)


def equal_ranges(*point_sets: np.ndarray, floor: float = 0.05, pad: float = 0.04) -> tuple[np.ndarray, np.ndarray]:
    """Axis ranges ``(3, 2)`` and their relative lengths ``(3,)`` with one scale on every axis.

    No axis is shorter than ``floor`` times the longest one, so a planar or
    straight skeleton still gets a visible box.
    """
    pts = np.concatenate([np.asarray(p, float).reshape(-1, 3) for p in point_sets if len(p)] or [np.zeros((1, 3))])
    pts = pts[np.isfinite(pts).all(axis=1)]
    if not len(pts):
        pts = np.zeros((1, 3))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    extent = hi - lo
    longest = float(extent.max()) or 1.0
    extent = np.maximum(extent, floor * longest) * (1.0 + 2.0 * pad)
    centre = 0.5 * (lo + hi)
    ranges = np.stack([centre - extent / 2, centre + extent / 2], axis=1)
    return ranges, extent / extent.max()
