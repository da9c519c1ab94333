"""Raster water masks with their georeference: the axis on the pixels, written in map units.

The GeoTIFF is read by rasterio (BSD; ``pip install rasterio`` or
``medialaxis[gis]``), loaded on first use. Its first band's non-zero valid
pixels are the shape (nodata and GDAL-masked pixels are not).

Pixel size and rotation come from the affine transform: its column step
``u = (a, d)`` and row step ``v = (b, e)`` are the pixel's two sides in map
units. When they are perpendicular (north-up, rotated, mirrored; square or
not), the map frame is the pixel grid scaled by ``(|v|, |u|)`` along (row,
column) and then turned or mirrored, which keeps distances. So the axis is
computed with ``spacing=(|v|, |u|)`` (sub-pixel boundary, as for any image)
and mapped to the map by that isometry: every radius, and the width twice
it, is a true distance in map units to the mask's boundary, also for
non-square pixels (a disc in the map, not a disc in pixel counts). A sheared
grid (sides not perpendicular) has no such frame and is refused.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from medialaxis import _optional
from medialaxis.api import medial_axis
from medialaxis.core import formats
from medialaxis.errors import InputFileError, InvalidInputError
from medialaxis.gis.network import branch_stations, branch_table

__all__ = ["RASTER_SUFFIXES", "is_raster", "read_mask", "pixel_frame", "raster_axis", "raster_network",
           "raster_stations"]

#: Files read as raster masks (GeoTIFF and GDAL's virtual rasters): the ``"raster"`` readers of
#: :data:`medialaxis.core.formats.FORMATS`.
RASTER_SUFFIXES = formats.suffixes("raster")


def is_raster(source: Any) -> bool:
    """A path with a raster suffix, or an open rasterio dataset."""
    if isinstance(source, (str, os.PathLike)):
        return formats.suffix_of(source) in RASTER_SUFFIXES
    return type(source).__module__.startswith("rasterio") and hasattr(source, "transform")


def read_mask(source: Any, band: int = 1) -> tuple[np.ndarray, Any, Any]:
    """``(mask, transform, crs)`` of a GeoTIFF path or open rasterio dataset: the non-zero valid pixels of ``band``."""
    rasterio = _optional.require("rasterio", "rasterio")
    if not isinstance(source, (str, os.PathLike)):
        return _band_mask(source, band), source.transform, source.crs
    if not os.path.exists(source):
        raise InputFileError(f"no such file: {str(source)!r}")
    try:
        with rasterio.open(source) as dataset:
            return _band_mask(dataset, band), dataset.transform, dataset.crs
    except rasterio.errors.RasterioError as exc:
        raise InputFileError(f"cannot read the raster {str(source)!r}: {exc}") from exc


def _band_mask(dataset: Any, band: int) -> np.ndarray:
    if not 1 <= band <= dataset.count:
        raise InvalidInputError(f"band must be 1..{dataset.count} for this raster, got {band!r}")
    data = dataset.read(band, masked=True)
    return np.asarray(data.filled(0) != 0, bool)


def pixel_frame(transform: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(spacing, rotation, origin)``: map ``xy = (row, col) * spacing @ rotation.T + origin``, pixel centres.

    ``spacing`` is the pixel's (height, width) in map units; ``rotation`` an
    orthogonal 2 x 2 matrix (a turn, or a turn and a mirror), so distances
    computed in ``(row, col) * spacing`` are distances on the map.

    Raises
    ------
    InvalidInputError
        A degenerate (zero-area) or sheared pixel grid.
    """
    u = np.array([transform.a, transform.d], np.float64)  # one column to the right
    v = np.array([transform.b, transform.e], np.float64)  # one row down
    width, height = float(np.hypot(*u)), float(np.hypot(*v))
    if not (np.isfinite([width, height]).all() and width > 0 and height > 0):
        raise InvalidInputError(f"the raster's transform has a zero or non-finite pixel size: {tuple(transform)[:6]}")
    if abs(float(u @ v)) > 1e-9 * width * height:
        raise InvalidInputError(
            f"the raster's pixels are sheared (transform {tuple(transform)[:6]}): distances on the pixels are not "
            "distances on the map; warp it to a grid with perpendicular sides first (rasterio.warp.reproject, gdalwarp)"
        )
    rotation = np.column_stack([v / height, u / width])
    origin = np.array([transform.c, transform.f]) + 0.5 * (u + v)  # pixel (0, 0)'s centre
    return np.array([height, width]), rotation, origin


def raster_axis(mask: np.ndarray, transform: Any, options: dict[str, Any]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(points, radii, edges)`` of the mask's axis, points in map coordinates, radii in map units."""
    spacing, rotation, origin = pixel_frame(transform)
    ma = medial_axis(mask, spacing=spacing, **{"foreground": "bright", **options})
    return np.asarray(ma.points) @ rotation.T + origin, np.asarray(ma.radii), np.asarray(ma.edges)


def _crs(crs: Any) -> Any:
    return None if crs is None else crs.to_wkt()


def raster_network(source: Any, options: dict[str, Any], band: int = 1) -> Any:
    """One row per branch of a raster mask's axis, in the raster's CRS (a GeoDataFrame)."""
    gpd = _optional.require("geopandas", "geopandas")
    shapely = _optional.require("shapely", "shapely")
    mask, transform, crs = read_mask(source, band)
    points, radii, edges = raster_axis(mask, transform, options)
    columns, lines = branch_table(points, radii, edges)
    return gpd.GeoDataFrame(columns, geometry=[shapely.LineString(xy) for xy in lines], crs=_crs(crs))


def raster_stations(source: Any, options: dict[str, Any], step: float | None, band: int = 1) -> Any:
    """Stations along the branches of a raster mask's axis, in the raster's CRS (a GeoDataFrame of points)."""
    gpd = _optional.require("geopandas", "geopandas")
    mask, transform, crs = read_mask(source, band)
    table = branch_stations(*raster_axis(mask, transform, options), step)
    frame = {k: v for k, v in table.items() if k not in ("x", "y")}
    frame["branch"] = frame["branch"].astype(np.int64)
    return gpd.GeoDataFrame(frame, geometry=gpd.points_from_xy(table["x"], table["y"]), crs=_crs(crs))
