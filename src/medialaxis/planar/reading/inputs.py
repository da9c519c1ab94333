"""Turn every planar input into one region: a shapely (Multi)Polygon in output units.

Raster inputs (masks, grey images, image files) go through a sub-pixel
iso-contour (:func:`skimage.measure.find_contours`) in array index order
scaled by ``spacing``; vector inputs (shapely, WKT, GeoJSON, SVG, boundary
loops) keep their own coordinates.
"""

from __future__ import annotations

import dataclasses
import os
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import shapely

from medialaxis.core.formats import reader_suffixes, suffix_of
from medialaxis.core.validate import check_spacing, is_geometry_text
from medialaxis.errors import InputFileError, InvalidInputError, MedialAxisWarning, UnsupportedFormatError
from medialaxis.planar.reading.images import (
    FOREGROUNDS,
    IMAGE_EXTENSIONS,
    check_foreground,
    check_image,
    colour_to_grey,
    contour_region,
    image_region,
    max_pixels,
    read_image,
    shape_side,
)
from medialaxis.planar.reading.labels import is_label_image, label_regions
from medialaxis.planar.reading.vectors import loop_polygon, parse_vector, read_vector, validate_polygonal

__all__ = ["PlanarInput", "load_planar", "max_pixels", "shape_side", "contour_region", "FOREGROUNDS", "DRAWINGS"]

#: Drawing formats: what they paint is read by the library made for the format (:func:`read_drawing`).
DRAWINGS = reader_suffixes("planar", f"{__name__}:read_drawing")
#: Other vector formats: their geometry is the shape.
VECTORS = reader_suffixes("planar", "medialaxis.planar.reading.vectors:read_vector")


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
    drawing : dict or None
        What the reader of a drawing (SVG, DXF) found: its format, units or
        viewport, and the elements it skipped (see :func:`read_drawing`).
    labels : tuple of (int, region) or None
        For label images: each label and its region (``region`` is their
        union); every label is a shape of its own.
    channels : {"rgb", "alpha"} or None
        For colour images: which channels the grey image comes from.
    """

    region: Any
    spacing: np.ndarray
    image: np.ndarray | None = None
    foreground: np.ndarray | None = None
    threshold: float | None = None
    side: str | None = None
    repaired: str | None = None
    drawing: dict[str, Any] | None = None
    labels: tuple[tuple[int, Any], ...] | None = None
    channels: str | None = None

    @property
    def is_raster(self) -> bool:
        return self.image is not None


def read_drawing(
    path: Path, *, tolerance: float | None = None, strokes: bool | None = None, layers: Sequence[str] | None = None
) -> tuple[Any, dict[str, Any]]:
    """The region an SVG or DXF drawing paints, and what its reader found.

    Elements that bound no region (text, raster images, dimensions) are
    skipped with a :class:`~medialaxis.MedialAxisWarning` that counts them;
    the counts are in ``info["skipped"]``.
    """
    ext = path.suffix.lower()
    if ext == ".svg":
        if layers is not None:
            raise InvalidInputError(f"layers= applies to DXF drawings; {str(path)!r} is an SVG")
        from medialaxis.planar.drawings.svg import read_svg

        region, info = read_svg(path, tolerance=tolerance, strokes=True if strokes is None else bool(strokes))
    else:
        if strokes is not None:
            raise InvalidInputError(f"strokes= applies to SVG drawings; {str(path)!r} is a DXF")
        from medialaxis.planar.drawings.dxf import read_dxf

        region, info = read_dxf(path, layers=layers, tolerance=tolerance)
    skipped = {k: v for k, v in info.get("skipped", {}).items() if v}
    if skipped:
        counts = ", ".join(f"{n} {kind}" for kind, n in sorted(skipped.items()))
        warnings.warn(
            f"{str(path)!r}: not read (they bound no region): {counts}", MedialAxisWarning, stacklevel=3
        )
    for error in info.get("errors", []):
        warnings.warn(f"{str(path)!r}: {error}", MedialAxisWarning, stacklevel=3)
    return region, info


# ------------------------------------------------------------------ entry
def load_planar(
    shape: Any,
    *,
    threshold: float | None = None,
    spacing: Any = None,
    foreground: str = "auto",
    tolerance: float | None = None,
    strokes: bool | None = None,
    layers: Sequence[str] | None = None,
    labels: bool | None = None,
    channel_axis: int | None = -1,
) -> PlanarInput:
    """Read and validate any planar input.

    ``foreground`` ("auto", "bright" or "dark", see :func:`shape_side`)
    says which side of the threshold of an image is the shape; vector
    inputs accept only "auto". ``tolerance`` is the chord error of the
    curves of drawings; ``strokes`` (SVG: read strokes as regions, default
    True) and ``layers`` (DXF: the layers to read, default all visible)
    apply to drawings only. ``labels`` says whether an integer image is a
    label image (default: 32 and 64-bit integer arrays are, see
    :func:`~medialaxis.planar.reading.labels.is_label_image`; image files only with
    ``labels=True``); ``channel_axis`` is
    the colour axis of a 3D array (RGB or RGBA, made grey by
    :func:`~medialaxis.planar.reading.images.colour_to_grey`).

    Raises
    ------
    InvalidInputError, EmptyShapeError, InputFileError, ResourceLimitError,
    UnsupportedFeatureError
    """
    foreground = check_foreground(foreground)
    if is_geometry_text(shape):  # WKT or GeoJSON text rather than a file name
        return load_planar(parse_vector(shape, wkt=not shape.lstrip().startswith("{")), threshold=threshold,
                           spacing=spacing, foreground=foreground, strokes=strokes, layers=layers)
    is_drawing = isinstance(shape, (str, os.PathLike)) and suffix_of(shape) in DRAWINGS
    if not is_drawing and (strokes is not None or layers is not None):
        name = "strokes" if strokes is not None else "layers"
        raise InvalidInputError(f"{name}= applies to drawings (SVG, DXF files), not to {_what(shape)}")
    if isinstance(shape, (str, os.PathLike)):
        path = Path(shape)
        if not path.is_file():
            raise InputFileError(f"no such file: {str(path)!r}")
        ext = suffix_of(path)
        if ext in IMAGE_EXTENSIONS:
            # an image file is a picture unless labels=True says it holds labels (a 16-bit scan opens as int32)
            return _image_input(read_image(path), threshold, check_spacing(spacing, 2), foreground, bool(labels))
        if ext in DRAWINGS:
            _vector_only_auto(foreground, str(path))
            region, info = read_drawing(path, tolerance=tolerance, strokes=strokes, layers=layers)
            geom, repaired = validate_polygonal(region, str(path))
            return PlanarInput(geom, np.ones(2), repaired=repaired, drawing=info)
        if ext in VECTORS:
            _vector_only_auto(foreground, str(path))
            geom, repaired = validate_polygonal(read_vector(path), str(path))
            return PlanarInput(geom, np.ones(2), repaired=repaired)
        if ext == ".npy":
            try:
                arr = np.load(path, allow_pickle=False)
            except Exception as exc:  # noqa: BLE001
                raise InputFileError(f"cannot read {str(path)!r}: {exc}") from exc
            return load_planar(
                arr, threshold=threshold, spacing=spacing, foreground=foreground, labels=labels,
                channel_axis=channel_axis,
            )
        raise UnsupportedFormatError(f"unsupported planar file type {ext!r} for {str(path)!r}")
    if hasattr(shape, "geom_type"):
        if spacing is not None:
            raise InvalidInputError("spacing applies to arrays only; vector inputs keep their coordinates")
        _vector_only_auto(foreground, "a polygon")
        geom, repaired = validate_polygonal(shape, "polygon")
        return PlanarInput(geom, np.ones(2), repaired=repaired)
    if isinstance(shape, (list, tuple)) and shape and all(hasattr(s, "geom_type") for s in shape):
        return load_planar(shapely.union_all(list(shape)), threshold=threshold, spacing=spacing, foreground=foreground)
    arr = np.asarray(shape)
    if arr.ndim == 2 and arr.shape[1] == 2 and arr.dtype != bool and arr.dtype.kind in "iuf":
        _vector_only_auto(foreground, "a boundary loop")
        geom, repaired = validate_polygonal(loop_polygon(arr.astype(np.float64)), "boundary loop")
        return PlanarInput(geom, np.ones(2), repaired=repaired)
    channels = None
    # the default colour axis (the last) applies where it has 3 or 4 entries; any other 3D array is refused below
    if arr.ndim == 3 and channel_axis is not None and (channel_axis != -1 or arr.shape[-1] in (3, 4)):
        axis = _channel_axis(channel_axis, arr.shape)
        arr, channels = colour_to_grey(np.moveaxis(arr, axis, -1))
    return _image_input(arr, threshold, check_spacing(spacing, 2), foreground, labels, channels)


def _channel_axis(channel_axis: Any, shape: tuple[int, ...]) -> int:
    if isinstance(channel_axis, bool) or not isinstance(channel_axis, (int, np.integer)):
        raise InvalidInputError(f"channel_axis must be an integer axis or None, got {channel_axis!r}")
    if not -len(shape) <= int(channel_axis) < len(shape) or shape[int(channel_axis)] not in (3, 4):
        raise InvalidInputError(
            f"channel_axis={channel_axis} must name an axis of 3 (RGB) or 4 (RGBA) channels; the array has shape "
            f"{shape} (channel_axis=None: no colour axis)"
        )
    return int(channel_axis)


def _image_input(
    arr: np.ndarray,
    threshold: float | None,
    spacing: np.ndarray,
    foreground: str,
    labels: bool | None = None,
    channels: str | None = None,
) -> PlanarInput:
    if is_label_image(arr, labels):
        if threshold is not None or foreground != "auto":
            raise InvalidInputError("threshold= and foreground= apply to grey images; a label image is not thresholded")
        check_image(arr)
        pieces = tuple(label_regions(arr, spacing))
        n_parts = sum(len(shapely.get_parts(r)) for _, r in pieces)
        if labels is None and len(pieces) > 2 and n_parts > 2 * len(pieces):
            # labels are objects; the values of a grey image fall apart into many pieces each
            warnings.warn(
                f"the {arr.dtype} image was read as {len(pieces)} labels (one shape per value), but they fall "
                f"apart into {n_parts} pieces: if it is a grey image, pass labels=False",
                MedialAxisWarning,
                stacklevel=4,
            )
        region = shapely.union_all([r for _, r in pieces])
        return PlanarInput(region, spacing, image=arr, foreground=arr > 0, labels=pieces)
    region, mask, level, side = image_region(arr, threshold, spacing, foreground)
    return PlanarInput(region, spacing, image=arr, foreground=mask, threshold=level, side=side, channels=channels)


def _what(shape: Any) -> str:
    if isinstance(shape, (str, os.PathLike)):
        return repr(str(shape))
    return f"a {type(shape).__name__}"


def _vector_only_auto(foreground: str, what: str) -> None:
    if foreground != "auto":
        raise InvalidInputError(
            f"foreground={foreground!r} applies to images; {what} has an inside already (use 'auto')"
        )
