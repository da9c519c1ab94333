"""Validation of volume inputs: array or file -> grey values, mask, spacing.

The default iso value is ISO-50: half-way between the grey levels of the
background and of the material, each read as the mode of its peak in the
grey-value histogram (:func:`iso50`).
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from typing import Any

import numpy as np

from medialaxis.core.validate import check_finite
from medialaxis.core.validate import check_spacing as _check_spacing
from medialaxis.errors import EmptyShapeError, InvalidInputError

__all__ = ["VolumeInput", "Iso50", "load_volume", "check_spacing", "iso50", "iso50_counts", "iso50_histogram",
           "value_counts", "counted"]

HISTOGRAM_BINS = 256
#: Gaussian smoothing of the histogram (bins) before its modes are read.
SMOOTHING_BINS = 2.0
#: A peak is one where the histogram between the two modes falls below this
#: fraction of the lower mode's height; otherwise ISO-50 falls back to Otsu.
VALLEY_RATIO = 0.5


@dataclasses.dataclass(frozen=True)
class Iso50:
    """An automatic iso value and the two grey levels it lies half-way between.

    Attributes
    ----------
    value : float
        ``(background + material) / 2``.
    method : str
        ``"peaks"``: the levels are the modes of the background and material
        peaks of the histogram (ISO-50 as industrial CT software takes it);
        ``"otsu"``: the histogram has not two peaks, and the levels are the
        mean grey values of the two classes of Otsu's threshold.
    background, material : float
        The two grey levels.
    """

    value: float
    method: str
    background: float
    material: float


def _mode(smooth: np.ndarray, edges: np.ndarray, i: int) -> float:
    """Bin ``i``'s centre moved to the top of the parabola through the log
    heights of bins ``i - 1 .. i + 1``; the end of the range for an end bin."""
    if i == 0 or i == len(smooth) - 1:
        return float(edges[0] if i == 0 else edges[-1])
    centres = 0.5 * (edges[i - 1 : i + 2] + edges[i : i + 3])
    if np.all(smooth[i - 1 : i + 2] > 0):
        a, b, c = np.log(smooth[i - 1 : i + 2])
        curvature = a - 2.0 * b + c
        if curvature < 0:
            return float(centres[1] + np.clip(0.5 * (a - c) / curvature, -0.5, 0.5) * (centres[2] - centres[1]))
    return float(centres[1])


def _peaks(hist: np.ndarray, edges: np.ndarray, split: float) -> tuple[float, float] | None:
    """The background and material modes: the highest local maxima of the
    smoothed histogram on either side of ``split``; None where a side has none
    or the histogram between them does not fall below ``VALLEY_RATIO`` of the
    lower one (a tail, not a peak)."""
    from scipy.ndimage import gaussian_filter1d

    smooth = gaussian_filter1d(np.asarray(hist, np.float64), SMOOTHING_BINS, mode="constant")
    padded = np.r_[-1.0, smooth, -1.0]
    peak = (smooth > 0) & (smooth >= padded[:-2]) & (smooth > padded[2:])
    side = 0.5 * (edges[:-1] + edges[1:]) > split
    low, high = np.flatnonzero(peak & ~side), np.flatnonzero(peak & side)
    if len(low) == 0 or len(high) == 0:
        return None
    i, j = int(low[np.argmax(smooth[low])]), int(high[np.argmax(smooth[high])])
    if smooth[i : j + 1].min() > VALLEY_RATIO * min(smooth[i], smooth[j]):
        return None
    return _mode(smooth, edges, i), _mode(smooth, edges, j)


def iso50_histogram(hist: np.ndarray, lo: float, hi: float,
                    class_means: Callable[[float], tuple[float, float] | None]) -> Iso50:
    """ISO-50 of a grey-value histogram: half-way between the background and
    material peaks.

    The histogram is split at Otsu's threshold; on each side the mode of the
    histogram smoothed by a Gaussian of ``SMOOTHING_BINS`` bins (refined
    between bins by a parabola through the log counts) is that class's grey
    level. Unlike the class means, the modes are not pulled towards each other
    by the partial-volume voxels of the surface, which thin plates have many
    of (issue 35: Otsu's class means put a 6-voxel plate with levels 1000 and
    3000 at 1807, and it read 6.5 voxels thick; ``benchmarks/bench_iso50.py``).
    Where a side has no peak of its own (a plate so thin or blurred that no
    voxel reaches the material level, or no valley between the modes), the
    levels are Otsu's class means.

    Parameters
    ----------
    hist : (HISTOGRAM_BINS,) array_like
        Counts of equal bins spanning ``[lo, hi]``.
    lo, hi : float
        The smallest and largest grey value.
    class_means : callable
        ``class_means(t)``: the mean grey values at or below ``t`` and above
        it, or None when a class is empty (for the fallback).

    Returns
    -------
    Iso50

    References
    ----------
    .. [1] J.-P. Kruth, M. Bartscher, S. Carmignato, R. Schmitt, L. De Chiffre, A. Weckenmann,
           "Computed tomography for dimensional metrology", CIRP Annals - Manufacturing
           Technology 60(2):821-842, 2011. doi:10.1016/j.cirp.2011.05.006 (surface determination
           by a global threshold, the ISO-50 grey value half-way between the background and
           material peaks of the histogram).

    Examples
    --------
    >>> import numpy as np
    >>> grey = np.random.default_rng(0).normal(np.repeat([1000.0, 3000.0], [9000, 1000]), 50.0)
    >>> hist, _ = np.histogram(grey, 256, (grey.min(), grey.max()))
    >>> found = iso50_histogram(hist, grey.min(), grey.max(), lambda t: None)
    >>> found.method, bool(abs(found.value - 2000.0) < 20.0)
    ('peaks', True)
    """
    from skimage.filters import threshold_otsu

    hist = np.asarray(hist, np.float64)
    edges = np.linspace(lo, hi, len(hist) + 1)
    centres = 0.5 * (edges[:-1] + edges[1:])
    t = float(threshold_otsu(hist=(hist, centres)))
    peaks = _peaks(hist, edges, t)
    if peaks is not None:
        return Iso50(0.5 * (peaks[0] + peaks[1]), "peaks", *peaks)
    means = class_means(t)
    if means is None:
        return Iso50(t, "otsu", t, t)
    return Iso50(float(0.5 * (means[0] + means[1])), "otsu", float(means[0]), float(means[1]))


def iso50(grey: np.ndarray) -> Iso50:
    """Default iso value of grey values: :func:`iso50_histogram` of their
    ``HISTOGRAM_BINS``-bin histogram, the fallback with the exact class means.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.r_[np.zeros(900), np.full(100, 1000.0)].reshape(10, 10, 10)
    >>> iso50(v)
    Iso50(value=500.0, method='peaks', background=0.0, material=1000.0)
    """
    grey = np.asarray(grey)
    lo, hi = float(grey.min()), float(grey.max())
    hist = np.histogram(grey, bins=HISTOGRAM_BINS, range=(lo, hi))[0]

    def class_means(t: float) -> tuple[float, float] | None:
        low = grey <= t
        n_low = int(np.count_nonzero(low))
        if n_low == 0 or n_low == grey.size:
            return None
        return grey[low].mean(dtype=np.float64), grey[~low].mean(dtype=np.float64)

    return iso50_histogram(hist, lo, hi, class_means)


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


def iso50_counts(values: np.ndarray, counts: np.ndarray) -> Iso50:
    """:func:`iso50` from a table of values and counts (the same histogram,
    exact class means): a volume counted block by block gets the iso value
    the whole array gets.

    Examples
    --------
    >>> import numpy as np
    >>> iso50_counts(np.array([0.0, 1000.0]), np.array([900, 100])).value
    500.0
    """
    values = np.asarray(values, np.float64)
    counts = np.asarray(counts, np.float64)
    keep = counts > 0
    values, counts = values[keep], counts[keep]
    if len(values) == 1:
        return Iso50(float(values[0]), "otsu", float(values[0]), float(values[0]))
    hist = np.histogram(values, bins=HISTOGRAM_BINS, range=(values[0], values[-1]), weights=counts)[0]

    def class_means(t: float) -> tuple[float, float] | None:
        low = values <= t
        n_low, n_high = counts[low].sum(), counts[~low].sum()
        if n_low == 0 or n_high == 0:
            return None
        return (values[low] * counts[low]).sum() / n_low, (values[~low] * counts[~low]).sum() / n_high

    return iso50_histogram(hist, float(values[0]), float(values[-1]), class_means)


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
    threshold_method : str
        Where ``iso`` comes from: ``"given"`` by the caller, ``"mask"`` (0.5
        for a bool mask), or ISO-50's ``"peaks"`` or ``"otsu"`` fallback
        (:class:`Iso50`).
    """

    grey: np.ndarray
    mask: np.ndarray
    iso: float
    spacing: np.ndarray
    threshold_method: str = "given"


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
        :func:`medialaxis.volume.files.readers.read_volume`. Never modified.
    iso : float, optional
        Foreground is ``grey > iso``. Default: 0.5 for bool input, otherwise
        :func:`iso50`: half-way between the modes of the background and
        material peaks of the histogram (Otsu's class means where it has not
        two peaks).
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
        from medialaxis.volume.files.readers import read_volume

        array, file_spacing = read_volume(volume, shape=raw_shape, dtype=raw_dtype)
    else:
        array = np.asarray(volume)
    if array.ndim != 3:
        raise InvalidInputError(f"a volume must be a 3D array, got shape {array.shape}")
    if min(array.shape) < 3:
        raise InvalidInputError(f"a volume needs at least 3 voxels per axis, got shape {array.shape}")
    method = "given" if iso is not None else "mask"
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
        found = iso50_counts(*value_counts(array)) if counted(array.dtype) else iso50(grey)
        iso, method = found.value, found.method
    iso = check_finite(iso, "iso")
    mask = grey > iso
    count = int(np.count_nonzero(mask))
    if count == 0:
        raise EmptyShapeError(f"no voxel is above iso={iso:g}: the volume is empty")
    if count == mask.size:
        raise EmptyShapeError(f"every voxel is above iso={iso:g}: the volume is full, the part has no surface")
    return VolumeInput(grey, mask, iso, check_spacing(spacing, file_spacing), method)
