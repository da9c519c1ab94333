"""Balls interpolated over a medial mesh, for coverage checks (written here, apart from the package's own)."""

from __future__ import annotations

import numpy as np


def interpolated_balls(ma, per_edge: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """Balls at the points and interpolated linearly (centre, radius) along the edges and over the triangles.

    The union of these balls is the shape a medial mesh stands for (Q-MAT's
    reading); a compact complex must cover the solid with it.
    """
    centres, radii = [ma.points], [ma.radii]
    sides = np.concatenate([ma.edges, ma.faces[:, [0, 1]], ma.faces[:, [1, 2]], ma.faces[:, [2, 0]]])
    t = np.linspace(0, 1, per_edge + 1)[1:-1, None, None]
    centres.append((ma.points[sides[:, 0]] + t * (ma.points[sides[:, 1]] - ma.points[sides[:, 0]])).reshape(-1, 3))
    radii.append((ma.radii[sides[:, 0]] + t[..., 0] * (ma.radii[sides[:, 1]] - ma.radii[sides[:, 0]])).ravel())
    i, j = np.meshgrid(np.arange(per_edge + 1), np.arange(per_edge + 1), indexing="ij")
    inner = (i > 0) & (j > 0) & (i + j < per_edge)
    w = np.c_[i[inner], j[inner], per_edge - i[inner] - j[inner]] / per_edge
    centres.append(np.einsum("bk,fkd->fbd", w, ma.points[ma.faces]).reshape(-1, 3))
    radii.append(np.einsum("bk,fk->fb", w, ma.radii[ma.faces]).ravel())
    return np.concatenate(centres), np.concatenate(radii)
