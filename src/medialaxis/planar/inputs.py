"""Turn every planar input into one region: a shapely (Multi)Polygon in output units.

Raster inputs (masks, grey images, image files) go through a sub-pixel
iso-contour (:func:`skimage.measure.find_contours`) in array index order
scaled by ``spacing``; vector inputs (shapely, WKT, GeoJSON, SVG, boundary
loops) keep their own coordinates.
"""

from __future__ import annotations

import dataclasses
import json
import os
import re
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from medialaxis.core.images import open_image
from medialaxis.core.validate import check_coordinates, check_spacing, memory_budget
from medialaxis.errors import (
    EmptyShapeError,
    InputFileError,
    InvalidInputError,
    ResourceLimitError,
    UnsupportedFormatError,
)

__all__ = ["PlanarInput", "load_planar", "max_pixels", "FOREGROUNDS"]

#: Bytes of working memory per pixel of a raster input (float64 copy, padded
#: copy, contour bookkeeping), used to refuse images too large before reading.
BYTES_PER_PIXEL = 48

#: Gaussian sigma (pixels of arc length) smoothing the contours of binary masks.
BINARY_SMOOTHING = 1.0

IMAGE_EXTENSIONS = (".png", ".jpg", ".jpeg", ".bmp", ".gif", ".tif", ".tiff")

#: Accepted values of ``foreground``: which side of the threshold is the shape.
FOREGROUNDS = ("auto", "bright", "dark")


@dataclasses.dataclass(frozen=True)
class PlanarInput:
    """A planar shape ready for sampling.

    Attributes
    ----------
    region : shapely Polygon or MultiPolygon
        Valid, non-empty, in output units.
    spacing : (2,) float ndarray
        Pixel size per array axis (ones for vector inputs).
    image : (rows, cols) ndarray or None
        The grey or bool image for raster inputs.
    foreground : (rows, cols) bool ndarray or None
        The shape's pixels for raster inputs (the side of the threshold
        that was taken as the shape).
    threshold : float or None
        Grey level used for raster inputs.
    side : {"bright", "dark"} or None
        Which side of the threshold is the shape, for raster inputs.
    repaired : str or None
        How an invalid polygon was repaired, if it was.
    """

    region: Any
    spacing: np.ndarray
    image: np.ndarray | None = None
    foreground: np.ndarray | None = None
    threshold: float | None = None
    side: str | None = None
    repaired: str | None = None

    @property
    def is_raster(self) -> bool:
        return self.image is not None


def max_pixels() -> int:
    """Largest image (in pixels) processed: half the physical memory / BYTES_PER_PIXEL."""
    return memory_budget() // BYTES_PER_PIXEL


# ----------------------------------------------------------------- rasters
def _check_pixels(n_pixels: int, what: str) -> None:
    limit = max_pixels()
    if n_pixels > limit:
        raise ResourceLimitError(
            f"{what} has {n_pixels:,} pixels; at most {limit:,} fit in memory here "
            f"(about {BYTES_PER_PIXEL} bytes per pixel are needed)"
        )


def _read_image(path: Path) -> np.ndarray:
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
            else:
                arr = np.asarray(im.convert("L"))
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


def _threshold(image: np.ndarray, threshold: float | None) -> tuple[np.ndarray, float]:
    """The bright side (``image > level``) and the level; bool images are their own bright side.

    The default level is Otsu's threshold, or the mid-grey of an image
    with two grey levels.
    """
    if threshold is not None:
        try:
            threshold = float(threshold)
        except (TypeError, ValueError):
            raise InvalidInputError(f"threshold must be a number, got {threshold!r}") from None
        if not np.isfinite(threshold):
            raise InvalidInputError(f"threshold must be finite, got {threshold!r}")
    if image.dtype == bool:
        return image, 0.5
    if threshold is None:
        lo, hi = float(image.min()), float(image.max())
        if lo == hi:
            raise EmptyShapeError(f"the image is constant ({lo}): no foreground/background contrast")
        from skimage.filters import threshold_otsu

        threshold = float(threshold_otsu(image))
        if not lo < threshold < hi:
            # Otsu lands on a level for two-level images; an iso-line at a
            # level runs through pixel centres and leaves one side empty.
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

    if image.dtype == bool:
        foreground = ~image if dark else image
    else:
        foreground = image < level if dark else image > level
    rows = np.flatnonzero(foreground.any(axis=1))
    cols = np.flatnonzero(foreground.any(axis=0))
    r0, c0 = max(int(rows[0]) - 1, 0), max(int(cols[0]) - 1, 0)
    box = (slice(r0, int(rows[-1]) + 2), slice(c0, int(cols[-1]) + 2))
    if image.dtype == bool:
        padded = np.pad(foreground[box].view(np.uint8), 1)  # 0 is below the 0.5 level
        level = 0.5
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


def _from_array(
    arr: np.ndarray, threshold: float | None, spacing: np.ndarray, foreground: str = "auto"
) -> PlanarInput:
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
    return PlanarInput(region, spacing, image=arr, foreground=mask, threshold=level, side=side)


# ----------------------------------------------------------------- vectors
def _validate_polygonal(geom: Any, where: str) -> tuple[Any, str | None]:
    if geom.geom_type not in ("Polygon", "MultiPolygon", "GeometryCollection"):
        raise InvalidInputError(f"{where}: expected a Polygon or MultiPolygon, got a {geom.geom_type}")
    coords = shapely.get_coordinates(geom)
    if len(coords) == 0 or geom.is_empty:
        raise EmptyShapeError(f"{where}: the geometry is empty")
    check_coordinates(coords, where)
    repaired = None
    if not geom.is_valid:
        reason = shapely.is_valid_reason(geom)
        fixed = shapely.make_valid(geom)
        parts = [g for g in shapely.get_parts(fixed) if g.geom_type in ("Polygon", "MultiPolygon")]
        fixed = shapely.union_all(parts) if parts else Polygon()
        repaired = f"invalid input ({reason}) repaired with shapely.make_valid"
        geom = fixed
    if geom.geom_type == "GeometryCollection":
        parts = [g for g in shapely.get_parts(geom) if g.area > 0]
        geom = shapely.union_all(parts) if parts else Polygon()
    if geom.is_empty or geom.area <= 0:
        raise EmptyShapeError(f"{where}: the polygon has zero area")
    return shapely.normalize(geom), repaired


def _from_loop(loop: np.ndarray) -> Any:
    if loop.ndim != 2 or loop.shape[1] != 2:
        raise InvalidInputError(f"a boundary loop must have shape (n, 2), got {loop.shape}")
    if not np.all(np.isfinite(loop)):
        bad = np.argwhere(~np.isfinite(loop))[0]
        raise InvalidInputError(f"boundary loop has a non-finite coordinate at row {bad[0]}")
    if len(np.unique(loop, axis=0)) < 3:
        raise EmptyShapeError(f"a boundary loop needs at least 3 distinct points, got {len(loop)}")
    return Polygon(loop)


_SVG_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def _read_svg(path: Path) -> Any:
    """Filled shapes of an SVG (polygon, rect, circle, ellipse, path with straight or curved segments)."""
    import xml.etree.ElementTree as ET

    try:
        root = ET.parse(path).getroot()
    except Exception as exc:  # noqa: BLE001 - ParseError, OSError, LookupError (bad encoding), ValueError...
        raise InputFileError(f"cannot parse SVG {str(path)!r}: {exc}") from exc
    rings: list[np.ndarray] = []
    for el in root.iter():
        tag = el.tag.rsplit("}", 1)[-1]
        a = el.attrib
        try:
            if tag in ("polygon", "polyline"):
                nums = [float(v) for v in re.findall(_SVG_NUM, a.get("points", ""))]
                rings.append(np.array(nums).reshape(-1, 2))
            elif tag == "rect":
                x, y = float(a.get("x", 0)), float(a.get("y", 0))
                w, h = float(a["width"]), float(a["height"])
                rings.append(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]]))
            elif tag in ("circle", "ellipse"):
                cx, cy = float(a.get("cx", 0)), float(a.get("cy", 0))
                rx = float(a.get("r", a.get("rx", 0)))
                ry = float(a.get("r", a.get("ry", 0)))
                t = np.linspace(0, 2 * np.pi, 720, endpoint=False)
                rings.append(np.c_[cx + rx * np.cos(t), cy + ry * np.sin(t)])
            elif tag == "path":
                rings.extend(_svg_path_rings(a.get("d", "")))
        except (KeyError, ValueError) as exc:
            raise InputFileError(f"malformed <{tag}> in SVG {str(path)!r}: {exc}") from exc
    rings = [r for r in rings if len(r) >= 3]
    if not rings:
        raise EmptyShapeError(f"SVG {str(path)!r} contains no closed shape")
    check_coordinates(np.vstack(rings), f"SVG {str(path)!r}")
    # Even-odd fill: symmetric difference of all rings.
    geom = Polygon()
    try:
        for r in rings:
            geom = geom.symmetric_difference(shapely.make_valid(Polygon(r)))
    except shapely.errors.GEOSException as exc:
        raise InputFileError(f"malformed shape in SVG {str(path)!r}: {exc}") from exc
    return geom


def _svg_path_rings(d: str) -> list[np.ndarray]:
    """Rings of an SVG path: M/L/H/V/C/Q/Z, absolute and relative; curves are sampled."""
    tokens = re.findall(r"[MmLlHhVvCcQqZz]|" + _SVG_NUM, d)
    rings, cur, pos, start = [], [], np.zeros(2), np.zeros(2)
    i, cmd = 0, None
    while i < len(tokens):
        if re.fullmatch(r"[A-Za-z]", tokens[i]):
            cmd = tokens[i]
            i += 1
            if cmd in "Zz":
                if len(cur) >= 3:
                    rings.append(np.array(cur))
                cur, pos = [], start.copy()
                continue
        if cmd is None:
            raise ValueError(f"path data starts with a number: {d[:30]!r}")

        def take(k: int) -> np.ndarray:
            nonlocal i
            vals = np.array([float(t) for t in tokens[i : i + k]])
            if len(vals) != k:
                raise ValueError("truncated path data")
            i += k
            return vals

        rel = cmd.islower()
        c = cmd.upper()
        if c == "M":
            pos = take(2) + (pos if rel else 0)
            if len(cur) >= 3:
                rings.append(np.array(cur))
            cur, start = [pos.copy()], pos.copy()
            cmd = "l" if rel else "L"
        elif c == "L":
            pos = take(2) + (pos if rel else 0)
            cur.append(pos.copy())
        elif c == "H":
            x = take(1)[0]
            pos = np.array([x + (pos[0] if rel else 0), pos[1]])
            cur.append(pos.copy())
        elif c == "V":
            y = take(1)[0]
            pos = np.array([pos[0], y + (pos[1] if rel else 0)])
            cur.append(pos.copy())
        elif c in "CQ":
            k = 3 if c == "C" else 2
            ctrl = take(2 * k).reshape(k, 2) + (pos if rel else 0)
            pts = np.vstack([pos, ctrl])
            t = np.linspace(0, 1, 17)[1:, None]
            if c == "C":
                curve = ((1 - t) ** 3 * pts[0] + 3 * (1 - t) ** 2 * t * pts[1]
                         + 3 * (1 - t) * t**2 * pts[2] + t**3 * pts[3])
            else:
                curve = (1 - t) ** 2 * pts[0] + 2 * (1 - t) * t * pts[1] + t**2 * pts[2]
            cur.extend(curve)
            pos = pts[-1].copy()
        else:  # pragma: no cover - regex admits only the commands above
            raise ValueError(f"unsupported path command {cmd!r}")
    if len(cur) >= 3:
        rings.append(np.array(cur))
    return rings


def _read_vector(path: Path) -> Any:
    ext = path.suffix.lower()
    if ext == ".svg":
        return _read_svg(path)
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputFileError(f"cannot read {str(path)!r}: {exc}") from exc
    if ext == ".wkt":
        try:
            return shapely.from_wkt(text.strip())
        except shapely.errors.GEOSException as exc:
            raise InputFileError(f"cannot parse WKT in {str(path)!r}: {exc}") from exc
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputFileError(f"cannot parse JSON in {str(path)!r}: {exc}") from exc
    geoms = []
    feats = doc.get("features") if isinstance(doc, dict) else None
    if feats is not None and not isinstance(feats, list):
        raise InputFileError(f"bad GeoJSON in {str(path)!r}: 'features' must be a list, got {type(feats).__name__}")
    items = feats if feats is not None else [doc]
    for item in items:
        g = item.get("geometry", item) if isinstance(item, dict) else None
        if g is None:
            continue
        try:
            geoms.append(shapely.geometry.shape(g))
        except Exception as exc:  # noqa: BLE001 - shapely raises several types
            raise InputFileError(f"bad GeoJSON geometry in {str(path)!r}: {exc}") from exc
    polys = [g for g in geoms if g.geom_type in ("Polygon", "MultiPolygon")]
    if not polys:
        raise EmptyShapeError(f"{str(path)!r} holds no Polygon or MultiPolygon")
    return shapely.union_all(polys)


# ------------------------------------------------------------------ entry
def load_planar(
    shape: Any, *, threshold: float | None = None, spacing: Any = None, foreground: str = "auto"
) -> PlanarInput:
    """Read and validate any planar input.

    ``foreground`` ("auto", "bright" or "dark", see :func:`shape_side`)
    says which side of the threshold of an image is the shape; vector
    inputs accept only "auto".

    Raises
    ------
    InvalidInputError, EmptyShapeError, InputFileError, ResourceLimitError
    """
    foreground = check_foreground(foreground)
    if isinstance(shape, (str, os.PathLike)):
        path = Path(shape)
        if not path.is_file():
            raise InputFileError(f"no such file: {str(path)!r}")
        ext = path.suffix.lower()
        if ext in IMAGE_EXTENSIONS:
            return _from_array(_read_image(path), threshold, check_spacing(spacing, 2), foreground)
        if ext in (".svg", ".wkt", ".geojson", ".json"):
            _vector_only_auto(foreground, str(path))
            geom, repaired = _validate_polygonal(_read_vector(path), str(path))
            return PlanarInput(geom, np.ones(2), repaired=repaired)
        if ext == ".npy":
            try:
                arr = np.load(path, allow_pickle=False)
            except Exception as exc:  # noqa: BLE001
                raise InputFileError(f"cannot read {str(path)!r}: {exc}") from exc
            return load_planar(arr, threshold=threshold, spacing=spacing, foreground=foreground)
        raise UnsupportedFormatError(f"unsupported planar file type {ext!r} for {str(path)!r}")
    if hasattr(shape, "geom_type"):
        if spacing is not None:
            raise InvalidInputError("spacing applies to arrays only; vector inputs keep their coordinates")
        _vector_only_auto(foreground, "a polygon")
        geom, repaired = _validate_polygonal(shape, "polygon")
        return PlanarInput(geom, np.ones(2), repaired=repaired)
    if isinstance(shape, (list, tuple)) and shape and all(hasattr(s, "geom_type") for s in shape):
        return load_planar(shapely.union_all(list(shape)), threshold=threshold, spacing=spacing, foreground=foreground)
    arr = np.asarray(shape)
    if arr.ndim == 2 and arr.shape[1] == 2 and arr.dtype != bool and arr.dtype.kind in "iuf":
        _vector_only_auto(foreground, "a boundary loop")
        geom, repaired = _validate_polygonal(_from_loop(arr.astype(np.float64)), "boundary loop")
        return PlanarInput(geom, np.ones(2), repaired=repaired)
    return _from_array(arr, threshold, check_spacing(spacing, 2), foreground)


def _vector_only_auto(foreground: str, what: str) -> None:
    if foreground != "auto":
        raise InvalidInputError(
            f"foreground={foreground!r} applies to images; {what} has an inside already (use 'auto')"
        )
