"""Images as planar shapes: read, threshold, choose the shape's side, trace the boundary (sub-pixel contours)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from medialaxis.core.formats import reader_suffixes
from medialaxis.core.images import open_image
from medialaxis.core.validate import check_finite, memory_budget
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError, ResourceLimitError

__all__ = ["image_region", "read_image", "contour_region", "shape_side", "check_foreground", "max_pixels",
           "colour_to_grey", "check_image", "FOREGROUNDS", "IMAGE_EXTENSIONS"]


#: Bytes of working memory per pixel of a raster input (float64 copy, padded
#: copy, contour bookkeeping), used to refuse images too large before reading.
BYTES_PER_PIXEL = 48


#: Gaussian sigma (pixels of arc length) smoothing the contours of binary masks.
BINARY_SMOOTHING = 1.0


#: Image files, read by :func:`read_image` (:data:`medialaxis.core.formats.FORMATS`).
IMAGE_EXTENSIONS = reader_suffixes("planar", f"{__name__}:read_image")


#: Accepted values of ``foreground``: which side of the threshold is the shape.
FOREGROUNDS = ("auto", "bright", "dark")


def max_pixels() -> int:
    """Largest image (in pixels) processed: half the physical memory / BYTES_PER_PIXEL."""
    return memory_budget() // BYTES_PER_PIXEL


def _check_pixels(n_pixels: int, what: str) -> None:
    limit = max_pixels()
    if n_pixels > limit:
        raise ResourceLimitError(
            f"{what} has {n_pixels:,} pixels; at most {limit:,} fit in memory here "
            f"(about {BYTES_PER_PIXEL} bytes per pixel are needed)"
        )


def read_image(path: Path) -> np.ndarray:
    try:
        # Our own size check, below, runs before anything is decoded.
        with open_image(path, None) as im:
            _check_pixels(im.width * im.height, f"image {str(path)!r}")
            if getattr(im, "n_frames", 1) > 1:
                raise InvalidInputError(
                    f"{str(path)!r} has {im.n_frames} pages: a 3D stack; use a volume method"
                )
            if im.mode in ("1", "L", "I", "I;16", "F"):
                arr = np.asarray(im)
            elif "A" in im.getbands() or "transparency" in im.info:
                arr, _ = colour_to_grey(np.asarray(im.convert("RGBA")))
            else:
                arr, _ = colour_to_grey(np.asarray(im.convert("RGB")))
    except (ResourceLimitError, InvalidInputError):
        raise
    except Exception as exc:  # noqa: BLE001 - PIL raises many types for bad files
        from PIL import Image

        if isinstance(exc, Image.DecompressionBombError):
            raise ResourceLimitError(
                f"image {str(path)!r} has more than {max_pixels():,} pixels, the most that fit in memory here "
                f"(refused before decoding: {exc})"
            ) from exc
        raise InputFileError(f"cannot read image {str(path)!r}: {exc}") from exc
    return arr


def colour_to_grey(image: np.ndarray) -> tuple[np.ndarray, str]:
    """A colour image (channels last: RGB or RGBA) as the grey image whose threshold gives the shape.

    RGB is made grey as :func:`skimage.color.rgb2gray` does (luminance,
    floats in [0, 1]). An alpha channel that is not constant is the shape
    itself: what is painted is opaque, so the alpha (in [0, 1]) is the grey
    image; a constant alpha is ignored.

    Returns
    -------
    grey : (rows, cols) float ndarray
    source : {"rgb", "alpha"}
        Which channels the grey image comes from.

    Examples
    --------
    >>> rgba = np.zeros((2, 2, 4), np.uint8); rgba[0, 0] = (255, 0, 0, 255)
    >>> grey, source = colour_to_grey(rgba)
    >>> source, grey.tolist()
    ('alpha', [[1.0, 0.0], [0.0, 0.0]])
    """
    from skimage.color import rgb2gray
    from skimage.util import img_as_float

    if image.ndim != 3 or image.shape[-1] not in (3, 4):
        raise InvalidInputError(f"a colour image has 3 or 4 channels on its last axis, got shape {image.shape}")
    if image.dtype.kind not in "biuf":
        raise InvalidInputError(f"colour image dtype must be bool, integer or float, got {image.dtype}")
    if image.shape[-1] == 4:
        alpha = image[..., 3]
        if alpha.min() != alpha.max():
            return img_as_float(alpha), "alpha"
    return rgb2gray(image[..., :3]), "rgb"


def _threshold(image: np.ndarray, threshold: float | None) -> tuple[np.ndarray, float]:
    """The bright side (``image > level``) and the level; bool images are their own bright side.

    The default level is Otsu's threshold, or the mid-grey of an image
    with two grey levels.
    """
    if threshold is not None:
        threshold = check_finite(threshold, "threshold")
    if image.dtype == bool:
        return image, 0.5
    if threshold is None:
        lo, hi = float(image.min()), float(image.max())
        if lo == hi:
            raise EmptyShapeError(f"the image is constant ({lo}): no foreground/background contrast")
        from skimage.filters import threshold_otsu

        threshold = float(threshold_otsu(image))
        if not lo < threshold < hi or ((image == lo) | (image == hi)).all():
            # Otsu lands on a level, or a histogram bin next to one (a float
            # 0/1 image: a GIF's palette), for two-level images; the
            # iso-line belongs half-way between the two levels.
            threshold = 0.5 * (lo + hi)
    return image > threshold, threshold


def check_foreground(foreground: Any) -> str:
    """Validate ``foreground`` (one of :data:`FOREGROUNDS`)."""
    if not isinstance(foreground, str) or foreground not in FOREGROUNDS:
        raise InvalidInputError(f"foreground must be one of {', '.join(map(repr, FOREGROUNDS))}, got {foreground!r}")
    return foreground


def shape_side(bright: np.ndarray, foreground: str = "auto") -> str:
    """Which side of the threshold is the shape: ``"bright"`` or ``"dark"``.

    ``"auto"`` takes the side that does not own most of the image border
    (the outermost rows and columns): a shape lies on its background, so
    the background is what the frame mostly sees. Ties (exactly half of
    the border pixels on each side) go to the side with fewer pixels in
    the whole image, and if that ties too, to the bright side.
    """
    if foreground != "auto":
        return foreground
    border = np.concatenate([bright[0], bright[-1], bright[1:-1, 0], bright[1:-1, -1]])
    n_bright = int(np.count_nonzero(border))
    n_dark = border.size - n_bright
    if n_bright != n_dark:
        return "dark" if n_bright > n_dark else "bright"
    total = int(np.count_nonzero(bright))
    return "dark" if total > bright.size - total else "bright"


def _rings_to_region(rings: list[np.ndarray]) -> Any:
    """Assemble closed rings (shells counter-clockwise, holes clockwise) into polygons.

    A hole belongs to the smallest shell that contains one of its
    vertices: a point on a hole's ring lies inside its own shell, and
    outside the islands the hole may contain (they lie within the hole).
    """
    shells, holes = [], []
    for ring in rings:
        if len(ring) < 4:
            continue
        x, y = ring[:, 0], ring[:, 1]
        area = 0.5 * np.sum(x[:-1] * y[1:] - x[1:] * y[:-1])
        if area > 0:
            shells.append(Polygon(ring))
        elif area < 0:
            holes.append(ring)
    if not shells:
        raise EmptyShapeError("the foreground has no area")
    shell_tree = shapely.STRtree(shells)
    shell_holes: list[list[np.ndarray]] = [[] for _ in shells]
    areas = np.array([s.area for s in shells])
    if holes:
        probes = shapely.points([ring[0] for ring in holes])
        hole_index, shell_index = shell_tree.query(probes, predicate="covered_by")
        best = np.full(len(holes), -1)
        best_area = np.full(len(holes), np.inf)
        for h, s in zip(hole_index, shell_index):
            if areas[s] < best_area[h]:
                best[h], best_area[h] = s, areas[s]
        for h, s in enumerate(best):
            if s >= 0:  # a hole outside every shell cannot come from one contour set
                shell_holes[s].append(holes[h])
    polys = [Polygon(s.exterior.coords, h) for s, h in zip(shells, shell_holes)]
    region = polys[0] if len(polys) == 1 else MultiPolygon(polys)
    if not region.is_valid:
        region = shapely.make_valid(region)
        region = shapely.union_all([g for g in getattr(region, "geoms", [region]) if g.area > 0])
    return region


def _smooth_ring(ring: np.ndarray, sigma: float) -> np.ndarray:
    """Gaussian smoothing (``sigma`` in pixels of arc length) of a closed ring."""
    from scipy.ndimage import gaussian_filter1d

    pts = ring[:-1]
    if len(pts) < 8:
        return ring
    step = np.linalg.norm(np.diff(ring, axis=0), axis=1)
    perimeter = float(step.sum())
    n = max(8, int(np.ceil(perimeter / 0.5)))
    s = np.concatenate([[0.0], np.cumsum(step)])
    t = np.linspace(0.0, perimeter, n, endpoint=False)
    uniform = np.c_[np.interp(t, s, ring[:, 0]), np.interp(t, s, ring[:, 1])]
    smooth = gaussian_filter1d(uniform, sigma / (perimeter / n), axis=0, mode="wrap")
    return np.vstack([smooth, smooth[:1]])


def contour_region(
    image: np.ndarray, level: float, spacing: np.ndarray, smoothing: float = 0.0, *, dark: bool = False
) -> Any:
    """Sub-pixel iso-contour of ``image`` at ``level`` as polygons in index order * spacing.

    The shape is ``image > level`` (``dark=True``: ``image < level``; for a
    bool image, the True or the False pixels). Only its bounding box plus
    one pixel is contoured. A bool image is contoured at 0.5 without a
    float copy. ``smoothing`` > 0 smooths each contour ring with a Gaussian
    of that many pixels of arc length (for binary masks, whose contour is
    a staircase).
    """
    from skimage.measure import find_contours

    from medialaxis.planar.reading._contour_kernels import contour_rings

    if image.dtype == bool:
        foreground = ~image if dark else image
    else:
        foreground = image < level if dark else image > level
    rows = np.flatnonzero(foreground.any(axis=1))
    cols = np.flatnonzero(foreground.any(axis=0))
    r0, c0 = max(int(rows[0]) - 1, 0), max(int(cols[0]) - 1, 0)
    box = (slice(r0, int(rows[-1]) + 2), slice(c0, int(cols[-1]) + 2))
    if image.dtype == bool:
        # compiled: the rings find_contours gives at 0.5, point for point
        rings = contour_rings(np.pad(foreground[box].view(np.uint8), 1))
    else:
        # The same iso-line either way; the sign makes the shape the high side.
        crop = -image[box].astype(np.float64) if dark else image[box].astype(np.float64)
        level = -level if dark else level
        padded = np.pad(crop, 1, constant_values=min(float(crop.min()), level) - 1.0)
        rings = find_contours(padded, level, positive_orientation="high")
    if smoothing > 0:
        rings = [_smooth_ring(r, smoothing) for r in rings]
    origin = np.array([r0 - 1.0, c0 - 1.0])
    rings = [(r + origin) * spacing for r in rings]
    return _rings_to_region(rings)


def check_image(arr: np.ndarray) -> None:
    """Refuse what is not a 2D image of bool, integer or finite float pixels that fits in memory."""
    if arr.ndim != 2:
        raise InvalidInputError(
            f"the planar method needs a 2D image, got an array of shape {arr.shape}"
            + (" (a 3D volume: use method='midsurface' or 'voxels')" if arr.ndim == 3 else "")
        )
    if 0 in arr.shape:
        raise EmptyShapeError(f"the image is empty (shape {arr.shape})")
    _check_pixels(arr.size, f"image of shape {arr.shape}")
    if arr.dtype.kind not in "biuf":
        raise InvalidInputError(f"image dtype must be bool, integer or float, got {arr.dtype}")
    if arr.dtype.kind == "f" and not np.all(np.isfinite(arr)):
        raise InvalidInputError("the image contains NaN or infinite values")


def image_region(
    arr: np.ndarray, threshold: float | None, spacing: np.ndarray, foreground: str = "auto"
) -> tuple[Any, np.ndarray, float, str]:
    """The region of an image, its mask, the threshold used and the side that is the shape."""
    check_image(arr)
    bright, level = _threshold(arr, threshold)
    n_bright = int(np.count_nonzero(bright))
    if foreground == "auto" and n_bright in (0, bright.size):  # one side only: nothing to choose
        if n_bright == 0:
            raise EmptyShapeError("the mask is empty: no foreground pixels")
        raise EmptyShapeError("the mask is all foreground: the shape has no boundary inside the image")
    side = shape_side(bright, foreground)
    dark = side == "dark"
    if dark:
        mask = ~bright if arr.dtype == bool else arr < level
    else:
        mask = bright
    count = int(np.count_nonzero(mask))
    if count == 0:
        raise EmptyShapeError(f"the mask is empty: no {side} foreground pixels (foreground={foreground!r})")
    if count == mask.size:
        raise EmptyShapeError(
            f"the mask is all foreground ({side} side, foreground={foreground!r}): "
            "the shape has no boundary inside the image"
        )
    if arr.dtype == bool:
        # A binary mask is a sampled smooth shape: its staircase is noise.
        # Its 0.5 contour is smoothed along its length by a Gaussian of one
        # pixel, which costs O(perimeter) rather than a blur of every pixel
        # (corners round off by about one pixel).
        region = contour_region(arr, 0.5, spacing, smoothing=BINARY_SMOOTHING, dark=dark)
    else:
        region = contour_region(arr, level, spacing, dark=dark)
    return region, mask, level, side
