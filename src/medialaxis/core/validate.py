"""Checks of scalar and spacing arguments shared by every domain.

Each raises :class:`~medialaxis.errors.InvalidInputError` naming the
argument and the bad value, before any kernel runs.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["MAX_COORDINATE", "check_coordinates", "check_number", "check_spacing", "memory_budget", "is_geometry_text"]

#: A string that is a geometry rather than a file name: WKT, or GeoJSON text.
GEOMETRY_TEXT = re.compile(r"\s*(\{|(MULTI)?(POINT|LINESTRING|POLYGON)\s*[(EZM]|GEOMETRYCOLLECTION\b)", re.IGNORECASE)


def is_geometry_text(shape: Any) -> bool:
    """Whether ``shape`` is WKT or GeoJSON text rather than a file name.

    Examples
    --------
    >>> is_geometry_text("POLYGON ((0 0, 4 0, 4 1, 0 0))"), is_geometry_text("polygon.wkt")
    (True, False)
    """
    return isinstance(shape, str) and GEOMETRY_TEXT.match(shape) is not None

#: Largest coordinate magnitude accepted: squared distances and areas must
#: stay finite in float64 (about 1.8e308).
MAX_COORDINATE = 1e150


def check_finite(value: Any, name: str) -> float:
    """``float(value)``, required finite (any sign: a grey level, an iso value).

    Examples
    --------
    >>> check_finite("-1000", "iso")
    -1000.0
    """
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise InvalidInputError(f"{name} must be a number, got {value!r}") from None
    if not np.isfinite(out):
        raise InvalidInputError(f"{name} must be finite, got {value!r}")
    return out


def check_number(value: Any, name: str, *, positive: bool = False) -> float:
    """``float(value)``, required finite and ``>= 0`` (``> 0`` when ``positive``).

    Examples
    --------
    >>> check_number("2.5", "lam")
    2.5
    >>> check_number(-1, "lam")
    Traceback (most recent call last):
    ...
    medialaxis.errors.InvalidInputError: lam must be finite and >= 0, got -1
    """
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise InvalidInputError(f"{name} must be a number, got {value!r}") from None
    if not np.isfinite(out) or out < 0 or (positive and out == 0):
        raise InvalidInputError(f"{name} must be finite and {'> 0' if positive else '>= 0'}, got {value!r}")
    return out


def check_spacing(spacing: Any, ndim: int) -> np.ndarray:
    """Spacing as a ``(ndim,)`` positive float array; one number applies to every axis (``None``: ones)."""
    if spacing is None:
        return np.ones(ndim)
    try:
        out = np.asarray(spacing, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        out = np.empty(0)
    if out.size == 1:
        out = np.repeat(out, ndim)
    if out.size != ndim or not np.all(np.isfinite(out)) or np.any(out <= 0):
        raise InvalidInputError(f"spacing must be one or {ndim} positive finite numbers, got {spacing!r}")
    if np.any(out > MAX_COORDINATE / 1e10):
        raise InvalidInputError(f"spacing {spacing!r} is too large: coordinates would overflow; use another unit")
    return out


def check_coordinates(coords: np.ndarray, where: str) -> None:
    """Refuse NaN, infinite, or overflowing (beyond :data:`MAX_COORDINATE`) coordinates, naming them.

    Examples
    --------
    >>> check_coordinates(np.array([[0.0, 1e300]]), "polygon")
    Traceback (most recent call last):
    ...
    medialaxis.errors.InvalidInputError: polygon: coordinates up to 1e+300 are too large (squared distances overflow beyond 1e+150); rescale the shape
    """
    if not np.all(np.isfinite(coords)):
        bad = np.argwhere(~np.isfinite(coords))[0]
        raise InvalidInputError(f"{where}: coordinates contain NaN or infinity (at {tuple(int(i) for i in bad)})")
    largest = float(np.abs(coords).max()) if coords.size else 0.0
    if largest > MAX_COORDINATE:
        raise InvalidInputError(
            f"{where}: coordinates up to {largest:.3g} are too large (squared distances overflow beyond "
            f"{MAX_COORDINATE:.3g}); rescale the shape"
        )


def memory_budget() -> int:
    """Bytes an input may use while it is processed: half the physical memory."""
    import os

    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):  # pragma: no cover - non-POSIX
        total = 8 << 30
    return int(total // 2)
