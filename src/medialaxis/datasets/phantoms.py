"""CT-like phantoms of thin-plate parts with their exact mid-surfaces and thicknesses.

Each phantom is a union of axis-aligned plates, blurred (Gaussian, like a CT
point-spread function) and noisy, with foreground near 1 and background near
0, so that ``iso=0.5`` recovers the voxel faces of the plates. The true
mid-surface is a list of rectangles (:class:`Rect`) in voxel index
coordinates, used by :mod:`medialaxis.volume.validation` to score results;
each plate's thickness is :attr:`Phantom.plate_thickness` (twice the radius
a mid-surface should carry there).

>>> import numpy as np
>>> import medialaxis as mx
>>> from medialaxis.datasets import t_phantom
>>> ph = t_phantom((40, 64, 64), thickness=6, margin=8)
>>> ma = mx.medial_axis(ph.volume, method="midsurface")
>>> bool(abs(np.median(2 * ma.radii) - ph.thickness) < 1.0)
True
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["Rect", "Phantom", "t_phantom", "x_phantom", "member_phantom", "ribbed_panel", "ribbed_panel_slab",
           "ribbed_panel_truth"]


@dataclasses.dataclass(frozen=True)
class Rect:
    """A planar rectangle ``origin + s * u + t * v`` for ``s, t`` in ``[0, 1]``.

    Attributes
    ----------
    origin, u, v : (3,) float64 ndarray
        Corner and the two (orthogonal) edge vectors, in voxel index units.
    """

    origin: np.ndarray
    u: np.ndarray
    v: np.ndarray

    def sample(self, step: float = 0.5) -> np.ndarray:
        """(n, 3) grid of points on the rectangle, ``step`` apart (edges included)."""
        nu = max(int(np.ceil(np.linalg.norm(self.u) / step)), 1)
        nv = max(int(np.ceil(np.linalg.norm(self.v) / step)), 1)
        s, t = np.meshgrid(np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1), indexing="ij")
        return self.origin + s.reshape(-1, 1) * self.u + t.reshape(-1, 1) * self.v


@dataclasses.dataclass(frozen=True)
class Phantom:
    """A grey volume with its ground truth.

    Attributes
    ----------
    volume : (Z, Y, X) float32 ndarray
        Grey values (foreground ~1, background ~0).
    mask : (Z, Y, X) bool ndarray
        The plates before blurring.
    midsurface : list of Rect
        The true mid-surface, in voxel index coordinates.
    thickness : float
        Nominal plate thickness in voxels (of the first plate where they differ).
    plate_thickness : tuple of float
        Thickness of each rectangle's plate, in the order of ``midsurface``.
    """

    volume: np.ndarray
    mask: np.ndarray
    midsurface: list[Rect]
    thickness: float
    plate_thickness: tuple[float, ...] = ()


def _box(mask: np.ndarray, lo: tuple[int, int, int], hi: tuple[int, int, int]) -> None:
    mask[lo[0] : hi[0], lo[1] : hi[1], lo[2] : hi[2]] = True


def _render(mask: np.ndarray, blur: float, noise: float, rng: object) -> np.ndarray:
    from scipy import ndimage

    grey = mask.astype(np.float32)
    if blur > 0:
        grey = ndimage.gaussian_filter(grey, blur)
    if noise > 0:
        gen = np.random.default_rng(rng)  # type: ignore[arg-type]
        grey += gen.normal(0.0, noise, grey.shape).astype(np.float32)
    return grey


def _check(shape: tuple[int, int, int], thickness: int, minimum: int) -> tuple[int, int, int]:
    shape = tuple(int(s) for s in shape)  # type: ignore[assignment]
    if len(shape) != 3 or min(shape) < minimum:
        raise InvalidInputError(f"phantom shape must be 3 sizes >= {minimum}, got {shape}")
    if thickness < 2 or 4 * thickness > min(shape):
        raise InvalidInputError(f"thickness must be in [2, {min(shape) // 4}] voxels for shape {shape}, got {thickness}")
    return shape


def _rect(origin: list[float], u: list[float], v: list[float]) -> Rect:
    return Rect(np.asarray(origin, float), np.asarray(u, float), np.asarray(v, float))


def t_phantom(
    shape: tuple[int, int, int] = (140, 240, 240),
    *,
    thickness: int = 6,
    margin: int = 20,
    blur: float = 1.0,
    noise: float = 0.05,
    rng: object = 0,
    stem_thickness: int | None = None,
) -> Phantom:
    """A T of two plates: a flange normal to axis 0 and a stem normal to axis 1.

    Parameters
    ----------
    shape : tuple of 3 int
        Volume size ``(Z, Y, X)``; the default is the issue's benchmark size.
    thickness : int
        Plate thickness in voxels (the flange's, when ``stem_thickness`` is given).
    margin : int
        Empty voxels between the part and the volume border.
    blur, noise : float
        Gaussian blur sigma (voxels) and noise standard deviation.
    rng : seed or numpy Generator
        Noise generator seed.
    stem_thickness : int, optional
        Thickness of the stem when it differs from the flange's (a rib
        thinner than its wall), at least 2 voxels.

    Returns
    -------
    Phantom

    Examples
    --------
    >>> ph = t_phantom((40, 60, 60), margin=6)
    >>> ph.volume.shape, len(ph.midsurface)
    ((40, 60, 60), 2)
    >>> t_phantom((60, 80, 80), thickness=8, stem_thickness=4, margin=8).plate_thickness
    (8.0, 4.0)
    """
    Z, Y, X = _check(shape, thickness, 24)
    m, e = margin, thickness
    w = e if stem_thickness is None else int(stem_thickness)
    if not 2 <= w <= e * 4:
        raise InvalidInputError(f"stem_thickness must be in [2, {4 * e}] voxels, got {stem_thickness}")
    mask = np.zeros((Z, Y, X), bool)
    z0 = m  # flange voxels z0 .. z0+e-1
    yc = Y // 2 - w // 2  # stem voxels yc .. yc+w-1
    _box(mask, (z0, m, m), (z0 + e, Y - m, X - m))
    _box(mask, (z0 + e, yc, m), (Z - m, yc + w, X - m))
    zmid, ymid = z0 + (e - 1) / 2, yc + (w - 1) / 2
    lo, hiy, hix, hiz = m - 0.5, Y - m - 0.5, X - m - 0.5, Z - m - 0.5
    rects = [
        _rect([zmid, lo, lo], [0, hiy - lo, 0], [0, 0, hix - lo]),
        _rect([zmid, ymid, lo], [hiz - zmid, 0, 0], [0, 0, hix - lo]),
    ]
    return Phantom(_render(mask, blur, noise, rng), mask, rects, float(e), (float(e), float(w)))


def x_phantom(
    shape: tuple[int, int, int] = (100, 100, 80),
    *,
    thickness: int = 6,
    margin: int = 12,
    blur: float = 1.0,
    noise: float = 0.05,
    rng: object = 0,
) -> Phantom:
    """Two plates crossing in an X junction (normals along axes 0 and 1).

    Parameters and returns as :func:`t_phantom`.

    Examples
    --------
    >>> x_phantom((40, 40, 30), margin=5).midsurface[0].u.tolist()
    [0.0, 30.0, 0.0]
    """
    Z, Y, X = _check(shape, thickness, 24)
    m, e = margin, thickness
    mask = np.zeros((Z, Y, X), bool)
    zc, yc = Z // 2 - e // 2, Y // 2 - e // 2
    _box(mask, (zc, m, m), (zc + e, Y - m, X - m))
    _box(mask, (m, yc, m), (Z - m, yc + e, X - m))
    zmid, ymid = zc + (e - 1) / 2, yc + (e - 1) / 2
    lo = m - 0.5
    rects = [
        _rect([zmid, lo, lo], [0, Y - 2 * m, 0], [0, 0, X - 2 * m]),
        _rect([lo, ymid, lo], [Z - 2 * m, 0, 0], [0, 0, X - 2 * m]),
    ]
    return Phantom(_render(mask, blur, noise, rng), mask, rects, float(e), (float(e),) * 2)


def member_phantom(
    shape: tuple[int, int, int] = (90, 110, 120),
    *,
    thickness: int = 6,
    margin: int = 12,
    blur: float = 1.0,
    noise: float = 0.05,
    rng: object = 0,
) -> Phantom:
    """A closed box section (a rectangular tube along axis 2) with a flange.

    The tube's walls are ``thickness`` thick; the flange continues the top wall
    (normal to axis 0) beyond the tube along axis 1, like a car body member.

    Parameters and returns as :func:`t_phantom`.

    Examples
    --------
    >>> len(member_phantom((60, 80, 40), margin=6).midsurface)
    5
    """
    Z, Y, X = _check(shape, thickness, 40)
    m, e = margin, thickness
    mask = np.zeros((Z, Y, X), bool)
    z0, z1 = m, Z - m  # tube spans z0 .. z1-1
    y0 = m
    y1 = m + (Y - 2 * m) * 3 // 5  # tube spans y0 .. y1-1; the flange goes on to Y - m
    _box(mask, (z0, y0, m), (z0 + e, Y - m, X - m))  # top wall + flange
    _box(mask, (z1 - e, y0, m), (z1, y1, X - m))  # bottom wall
    _box(mask, (z0, y0, m), (z1, y0 + e, X - m))  # left wall
    _box(mask, (z0, y1 - e, m), (z1, y1, X - m))  # right wall
    h = (e - 1) / 2
    zt, zb, yl, yr = z0 + h, z1 - e + h, y0 + h, y1 - e + h
    xl, xw = m - 0.5, X - 2 * m
    rects = [
        _rect([zt, yl, xl], [0, yr - yl, 0], [0, 0, xw]),  # top
        _rect([zb, yl, xl], [0, yr - yl, 0], [0, 0, xw]),  # bottom
        _rect([zt, yl, xl], [zb - zt, 0, 0], [0, 0, xw]),  # left
        _rect([zt, yr, xl], [zb - zt, 0, 0], [0, 0, xw]),  # right
        _rect([zt, yr, xl], [0, Y - m - 0.5 - yr, 0], [0, 0, xw]),  # flange
    ]
    return Phantom(_render(mask, blur, noise, rng), mask, rects, float(e), (float(e),) * 5)


def _panel_layout(shape: tuple[int, int, int], thickness: int, margin: int) -> tuple[list[Any], list[Rect]]:
    """Boxes ``(lo, hi)`` of the ribbed panel and its true mid-surface."""
    Z, Y, X = _check(shape, thickness, 32)
    m, e = margin, thickness
    if Z - 2 * m < 3 * e or Y - 2 * m < 8 * e or X - 2 * m < 4 * e:
        raise InvalidInputError(f"shape {shape} is too small for a ribbed panel of {e}-voxel plates with margin {m}")
    base = ((m, m, m), (m + e, Y - m, X - m))
    webs = [m + k * (Y - 2 * m) // 4 - e // 2 for k in (1, 2, 3)]
    xc = X // 2 - e // 2
    rib_top = m + e + (Z - 2 * m - e) // 2
    boxes = [base] + [((m + e, y, m), (Z - m, y + e, X - m)) for y in webs] + [((m + e, m, xc), (rib_top, Y - m, xc + e))]
    h = (e - 1) / 2
    lo = m - 0.5
    zb = m + h
    rects = [_rect([zb, lo, lo], [0, Y - 2 * m, 0], [0, 0, X - 2 * m])]
    rects += [_rect([zb, y + h, lo], [Z - m - 0.5 - zb, 0, 0], [0, 0, X - 2 * m]) for y in webs]
    rects += [_rect([zb, lo, xc + h], [rib_top - 0.5 - zb, 0, 0], [0, Y - 2 * m, 0])]
    return boxes, rects


def ribbed_panel_truth(shape: tuple[int, int, int], *, thickness: int = 8, margin: int = 8) -> list[Rect]:
    """The exact mid-surface of :func:`ribbed_panel` (voxel index coordinates), without rendering it.

    Examples
    --------
    >>> [r.origin.tolist() for r in ribbed_panel_truth((48, 96, 64), margin=4)][:2]
    [[7.5, 3.5, 3.5], [7.5, 25.5, 3.5]]
    """
    return _panel_layout(tuple(shape), int(thickness), int(margin))[1]  # type: ignore[arg-type]


def ribbed_panel_slab(
    shape: tuple[int, int, int],
    start: int,
    stop: int,
    *,
    thickness: int = 8,
    margin: int = 8,
    blur: float = 1.0,
    noise: float = 0.05,
    rng: int = 0,
    levels: tuple[float, float] = (0.0, 1.0),
    dtype: Any = np.float32,
) -> np.ndarray:
    """Rows ``start:stop`` (along axis 0) of the grey values of :func:`ribbed_panel`.

    Every slab is rendered on its own (the blur sees ``4 * blur`` rows past
    each end, the noise of row ``z`` is drawn from ``(rng, z)``), so a volume
    written slab by slab equals the one rendered whole, at any slab size.
    ``levels`` are the background and material grey values (e.g. ``(1000,
    3000)`` for a 16-bit scan; the noise is a fraction of their difference).

    Examples
    --------
    >>> shape = (48, 96, 64)
    >>> bool(np.array_equal(ribbed_panel_slab(shape, 10, 20, margin=4), ribbed_panel(shape, margin=4).volume[10:20]))
    True
    """
    from scipy import ndimage

    shape = tuple(int(s) for s in shape)  # type: ignore[assignment]
    boxes, _ = _panel_layout(shape, int(thickness), int(margin))
    Z, Y, X = shape
    if not 0 <= start < stop <= Z:
        raise InvalidInputError(f"slab {start}:{stop} is outside 0:{Z}")
    pad = int(4.0 * blur + 0.5) if blur > 0 else 0
    lo, hi = max(start - pad, 0), min(stop + pad, Z)
    mask = np.zeros((hi - lo, Y, X), np.float32)
    for (z0, y0, x0), (z1, y1, x1) in boxes:
        a, b = max(z0, lo), min(z1, hi)
        if a < b:
            mask[a - lo : b - lo, y0:y1, x0:x1] = 1.0
    grey = ndimage.gaussian_filter(mask, blur, mode="constant") if blur > 0 else mask
    grey = grey[start - lo : stop - lo]
    if noise > 0:
        for k in range(stop - start):
            gen = np.random.default_rng([int(rng), start + k])
            grey[k] += gen.normal(0.0, noise, (Y, X)).astype(np.float32)
    low, high = (float(v) for v in levels)
    grey = low + (high - low) * grey
    if np.issubdtype(np.dtype(dtype), np.integer):
        info = np.iinfo(np.dtype(dtype))
        grey = np.clip(np.rint(grey), info.min, info.max)
    return grey.astype(dtype)


def ribbed_panel(
    shape: tuple[int, int, int] = (96, 128, 128),
    *,
    thickness: int = 8,
    margin: int = 8,
    blur: float = 1.0,
    noise: float = 0.05,
    rng: int = 0,
) -> Phantom:
    """A stiffened panel: a base plate (normal to axis 0), three webs (normal
    to axis 1) standing on it, and a half-height cross rib (normal to axis 2)
    through the webs: T junctions along the base, X junctions where the rib
    crosses a web, free edges at the tops and plate ends.

    The plates are ``thickness`` voxels thick at every size (a larger shape is
    a larger part at the same resolution), as for the large-scan benchmark.
    The same volume is produced slab by slab by :func:`ribbed_panel_slab`.

    Parameters and returns as :func:`t_phantom`.

    Examples
    --------
    >>> ph = ribbed_panel((48, 96, 64), margin=4)
    >>> ph.volume.shape, len(ph.midsurface)
    ((48, 96, 64), 5)
    """
    shape = tuple(int(s) for s in shape)  # type: ignore[assignment]
    boxes, rects = _panel_layout(shape, int(thickness), int(margin))
    mask = np.zeros(shape, bool)
    for lo, hi in boxes:
        _box(mask, lo, hi)  # type: ignore[arg-type]
    grey = ribbed_panel_slab(shape, 0, shape[0], thickness=thickness, margin=margin, blur=blur, noise=noise, rng=rng)
    return Phantom(grey, mask, rects, float(thickness), (float(thickness),) * len(rects))
