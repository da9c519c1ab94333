"""Generalized winding numbers of a triangle surface (numba) with their NumPy reference.

The winding number of a closed, outward surface at a point is the sum of the
signed solid angles of its triangles over 4 pi: 1 inside, 0 outside, 1/2 on
the surface; for a surface that crosses itself or has overlapping shells it
counts how many times the point is enclosed, and for a slightly open one it
stays close to those values away from the gaps. Each solid angle is Van
Oosterom and Strackee's formula.

References
----------
.. [1] Van Oosterom, Strackee, "The solid angle of a plane triangle", IEEE Transactions on
       Biomedical Engineering 30(2):125-126, 1983. doi:10.1109/TBME.1983.325207
.. [2] Jacobson, Kavan, Sorkine-Hornung, "Robust inside-outside segmentation using
       generalized winding numbers", ACM Transactions on Graphics 32(4):33:1-33:12 (Proc.
       SIGGRAPH), 2013. doi:10.1145/2461912.2461916
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange

__all__ = ["own_terms", "solid_angle", "winding_numbers", "winding_numbers_reference", "winding_numbers_without"]


@njit(cache=True, nogil=True)
def solid_angle(x, y, z, triangles, t):  # type: ignore[no-untyped-def]
    """Signed solid angle of triangle ``t`` of ``triangles`` at ``(x, y, z)`` (Van Oosterom and Strackee)."""
    ax, ay, az = triangles[t, 0, 0] - x, triangles[t, 0, 1] - y, triangles[t, 0, 2] - z
    bx, by, bz = triangles[t, 1, 0] - x, triangles[t, 1, 1] - y, triangles[t, 1, 2] - z
    cx, cy, cz = triangles[t, 2, 0] - x, triangles[t, 2, 1] - y, triangles[t, 2, 2] - z
    la = np.sqrt(ax * ax + ay * ay + az * az)
    lb = np.sqrt(bx * bx + by * by + bz * bz)
    lc = np.sqrt(cx * cx + cy * cy + cz * cz)
    det = ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    den = (la * lb * lc + (ax * bx + ay * by + az * bz) * lc + (ax * cx + ay * cy + az * cz) * lb
           + (bx * cx + by * cy + bz * cz) * la)
    return 2.0 * np.arctan2(det, den)


@njit(cache=True, nogil=True)
def _at(x, y, z, triangles, skip):  # type: ignore[no-untyped-def]
    """Sum of the solid angles of the triangles but ``skip`` at ``(x, y, z)``, over 4 pi."""
    total = 0.0
    for t in range(triangles.shape[0]):
        if t != skip:
            total += solid_angle(x, y, z, triangles, t)
    return total / (4.0 * np.pi)


@njit(cache=True, nogil=True, parallel=True)
def winding_numbers(points, triangles):  # type: ignore[no-untyped-def]
    """Winding number of the triangles ``(T, 3, 3)`` at each of ``points`` ``(P, 3)``."""
    out = np.empty(points.shape[0])
    for p in prange(points.shape[0]):
        out[p] = _at(points[p, 0], points[p, 1], points[p, 2], triangles, -1)
    return out


@njit(cache=True, nogil=True, parallel=True)
def winding_numbers_without(points, triangles, skip):  # type: ignore[no-untyped-def]
    """Winding number at each point of all the triangles but the point's own (``skip[p]``): on a face, its mean over both sides."""
    out = np.empty(points.shape[0])
    for p in prange(points.shape[0]):
        out[p] = _at(points[p, 0], points[p, 1], points[p, 2], triangles, skip[p])
    return out


@njit(cache=True, nogil=True, parallel=True)
def own_terms(points, triangles, which):  # type: ignore[no-untyped-def]
    """Each point's term of its own triangle (``which[p]``) in a winding number, the solid angle over 4 pi."""
    out = np.empty(points.shape[0])
    for p in prange(points.shape[0]):
        out[p] = solid_angle(points[p, 0], points[p, 1], points[p, 2], triangles, which[p]) / (4.0 * np.pi)
    return out


def winding_numbers_reference(points: np.ndarray, triangles: np.ndarray, chunk: int = 2_000_000) -> np.ndarray:
    """NumPy twin of :func:`winding_numbers` (chunks of at most ``chunk`` point-triangle terms)."""
    points, triangles = np.asarray(points, np.float64), np.asarray(triangles, np.float64)
    out = np.zeros(len(points))
    step = max(1, chunk // max(len(triangles), 1))
    for start in range(0, len(points), step):
        rel = triangles[None, :, :, :] - points[start : start + step, None, None, :]
        a, b, c = rel[:, :, 0], rel[:, :, 1], rel[:, :, 2]
        la, lb, lc = (np.linalg.norm(v, axis=2) for v in (a, b, c))
        det = np.einsum("ptk,ptk->pt", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ptk,ptk->pt", a, b) * lc + np.einsum("ptk,ptk->pt", a, c) * lb
               + np.einsum("ptk,ptk->pt", b, c) * la)
        out[start : start + step] = 2.0 * np.arctan2(det, den).sum(axis=1) / (4.0 * np.pi)
    return out
