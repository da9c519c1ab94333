"""Checks of scalar and spacing arguments shared by every domain.

Each raises :class:`~medialaxis.errors.InvalidInputError` naming the
argument and the bad value, before any kernel runs.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["check_number", "check_spacing"]


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
    return out
