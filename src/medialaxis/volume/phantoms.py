"""CT-like phantoms of thin-plate parts with their exact mid-surfaces.

Each phantom is a union of axis-aligned plates, blurred (Gaussian, like a CT
point-spread function) and noisy, with foreground near 1 and background near
0, so that ``iso=0.5`` recovers the voxel faces of the plates. The true
mid-surface is a list of rectangles (:class:`Rect`) in voxel index
coordinates, used by :mod:`medialaxis.volume.validation` to score results.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from medialaxis.errors import InvalidInputError

__all__ = ["Rect", "Phantom", "t_phantom", "x_phantom", "member_phantom"]


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
