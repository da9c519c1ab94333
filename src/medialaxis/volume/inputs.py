"""Validation of volume inputs: array or file -> grey values, mask, spacing."""

from __future__ import annotations

import dataclasses
import os
from typing import Any

import numpy as np

from medialaxis.core.validate import check_finite
from medialaxis.core.validate import check_spacing as _check_spacing
from medialaxis.errors import EmptyShapeError, InvalidInputError

__all__ = ["VolumeInput", "load_volume", "check_spacing", "iso50", "iso50_counts", "value_counts", "counted"]


def iso50(grey: np.ndarray) -> float:
    """Default iso value: half-way between the mean grey levels of the two
    classes of Otsu's threshold (the "ISO-50" surface of industrial CT).

    Otsu's threshold alone sits anywhere in the gap between well separated
    peaks (with histogram bins, right at the edge of the background noise);
    the mid-point of the class means puts the surface where a blurred edge
    crosses half its height.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.r_[np.zeros(900), np.full(100, 1000.0)].reshape(10, 10, 10)
    >>> iso50(v)
    500.0
    """
    from skimage.filters import threshold_otsu

    grey = np.asarray(grey)
    t = float(threshold_otsu(grey))
    low, high = grey[grey <= t], grey[grey > t]
    if len(low) == 0 or len(high) == 0:
        return t
    return float(0.5 * (low.mean(dtype=np.float64) + high.mean(dtype=np.float64)))


def counted(dtype: np.dtype) -> bool:
    """True for the dtypes whose ISO-50 comes from exact value counts (bool and integers of 1 or 2 bytes)."""
    dtype = np.dtype(dtype)
    return dtype.kind == "b" or (np.issubdtype(dtype, np.integer) and dtype.itemsize <= 2)


def value_counts(array: np.ndarray, slab: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Distinct values and their counts of a bool or 1-2 byte integer array, a slab at a time.

    Returns
    -------
    values : (k,) float64 ndarray
    counts : (k,) int64 ndarray
    """
    dtype = np.dtype(array.dtype)
    low = 0 if dtype.kind == "b" else int(np.iinfo(dtype).min)
    size = 2 if dtype.kind == "b" else 1 << (8 * dtype.itemsize)
    counts = np.zeros(size, np.int64)
    for z in range(0, array.shape[0], slab):
        part = np.asarray(array[z:z + slab]).ravel()
        counts += np.bincount(part.astype(np.int32) - low if low else part, minlength=size)[:size]
    values = np.flatnonzero(counts)
    return (values + low).astype(np.float64), counts[values]


def iso50_counts(values: np.ndarray, counts: np.ndarray) -> float:
    """:func:`iso50` from a table of values and counts (the same 256-bin Otsu
    threshold, exact class means): a volume counted block by block gets the
    iso value the whole array gets.

    Examples
    --------
    >>> import numpy as np
    >>> iso50_counts(np.array([0.0, 1000.0]), np.array([900, 100]))
    500.0
    """
    from skimage.filters import threshold_otsu

    values = np.asarray(values, np.float64)
    counts = np.asarray(counts, np.float64)
    keep = counts > 0
    values, counts = values[keep], counts[keep]
    if len(values) == 1:
        return float(values[0])
    hist, edges = np.histogram(values, bins=256, range=(values[0], values[-1]), weights=counts)
    t = float(threshold_otsu(hist=(hist, 0.5 * (edges[:-1] + edges[1:]))))
    low = values <= t
    n_low, n_high = counts[low].sum(), counts[~low].sum()
    if n_low == 0 or n_high == 0:
        return t
    return float(0.5 * ((values[low] * counts[low]).sum() / n_low + (values[~low] * counts[~low]).sum() / n_high))


@dataclasses.dataclass(frozen=True)
class VolumeInput:
    """A validated volume.

    Attributes
    ----------
    grey : (Z, Y, X) float32 ndarray
        Grey values (the input's own values; a bool mask becomes 0/1).
    mask : (Z, Y, X) bool ndarray
        Foreground: ``grey > iso``.
    iso : float
        The iso value used.
    spacing : (3,) float64 ndarray
        Voxel size per array axis.
    """

    grey: np.ndarray
    mask: np.ndarray
    iso: float
    spacing: np.ndarray


def check_spacing(spacing: Any, default: Any = None) -> np.ndarray:
    """Spacing as a (3,) positive float array (a scalar applies to every axis)."""
    return _check_spacing(default if spacing is None else spacing, 3)


def load_volume(
    volume: Any,
    *,
    iso: float | None = None,
    spacing: Any = None,
    raw_shape: Any = None,
    raw_dtype: Any = None,
) -> VolumeInput:
    """Validate a volume array or read a volume file, then binarize it.

    Parameters
    ----------
    volume : (Z, Y, X) array_like, str or path
        A bool mask, grey values, or a file/folder read by
        :func:`medialaxis.volume.readers.read_volume`. Never modified.
    iso : float, optional
        Foreground is ``grey > iso``. Default: 0.5 for bool input, otherwise
        :func:`iso50` (half-way between the air and material grey levels).
    spacing : float or 3 floats, optional
        Voxel size per array axis; default the file's, else 1.
    raw_shape, raw_dtype : optional
        Array shape ``(Z, Y, X)`` and dtype, needed for ``.raw`` files.

    Returns
    -------
    VolumeInput

    Raises
    ------
    InvalidInputError
        Not 3D, NaN values, non-numeric dtype, bad ``iso`` or ``spacing``.
    EmptyShapeError
        Empty or full foreground.
    InputFileError
        Unreadable file.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.zeros((8, 8, 8), bool); v[2:6, 2:6, 3:5] = True
    >>> load_volume(v).mask.sum()
    np.int64(32)
    """
    file_spacing = None
    if isinstance(volume, (str, os.PathLike)):
        from medialaxis.volume.readers import read_volume

        array, file_spacing = read_volume(volume, shape=raw_shape, dtype=raw_dtype)
    else:
        array = np.asarray(volume)
    if array.ndim != 3:
        raise InvalidInputError(f"a volume must be a 3D array, got shape {array.shape}")
    if min(array.shape) < 3:
        raise InvalidInputError(f"a volume needs at least 3 voxels per axis, got shape {array.shape}")
    if array.dtype == bool:
        grey = array.astype(np.float32)
        iso = 0.5 if iso is None else iso
    elif np.issubdtype(array.dtype, np.number) and not np.issubdtype(array.dtype, np.complexfloating):
        grey = np.asarray(array, dtype=np.float32)
        if grey is array:
            grey = grey.copy()  # never hand out a view the caller can see changing
        if not np.all(np.isfinite(grey)):
            raise InvalidInputError("the volume contains NaN or infinite values")
    else:
        raise InvalidInputError(f"a volume must be bool or numeric, got dtype {array.dtype}")
    if iso is None:
        lo, hi = float(grey.min()), float(grey.max())
        if lo == hi:
            raise EmptyShapeError(f"the volume is constant ({lo}); nothing to threshold")
        iso = iso50_counts(*value_counts(array)) if counted(array.dtype) else iso50(grey)
    iso = check_finite(iso, "iso")
    mask = grey > iso
    count = int(np.count_nonzero(mask))
    if count == 0:
        raise EmptyShapeError(f"no voxel is above iso={iso:g}: the volume is empty")
    if count == mask.size:
        raise EmptyShapeError(f"every voxel is above iso={iso:g}: the volume is full, the part has no surface")
    return VolumeInput(grey, mask, iso, check_spacing(spacing, file_spacing))
