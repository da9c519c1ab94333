"""The widths of an axis in NumPy (test helper): :func:`medialaxis.gis.features.axis_widths`, compiled,
sums as NumPy does and must equal this to the last bit."""

from __future__ import annotations

from typing import Any

import numpy as np


def axis_widths_reference(ma: Any) -> tuple[float, float, float]:
    """Twice the smallest, the length-weighted mean and the largest radius of ``ma``'s axis, in NumPy."""
    edges = np.asarray(ma.edges).reshape(-1, 2)
    r = np.asarray(ma.radii, np.float64)
    if len(edges) == 0:
        return (float(2 * r.min()), float(2 * r.mean()), float(2 * r.max())) if len(r) else (np.nan,) * 3
    length = np.linalg.norm(ma.points[edges[:, 0]] - ma.points[edges[:, 1]], axis=1)
    mean = float(np.sum(length * (r[edges[:, 0]] + r[edges[:, 1]])) / max(float(length.sum()), 1e-300))
    return float(2 * r.min()), mean, float(2 * r.max())


