"""Centerlines of GIS layers: one medial axis per feature, attributes and CRS kept.

The GIS "centerline" tools (PostGIS ``ST_ApproximateMedialAxis``,
pygeoops.centerline, centerline) work per feature and keep the attributes;
:func:`centerlines` does the same and adds the widths the radius function
gives. Needs geopandas (``pip install geopandas``), loaded on first use.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from medialaxis import _optional
from medialaxis._progress import progress
from medialaxis.api import medial_axis
from medialaxis.errors import InputFileError, InvalidInputError

__all__ = ["centerlines", "DETOUR", "WIDTH_COLUMNS"]

#: Columns added to the layer: twice the smallest, mean (over the axis
#: length) and largest radius along each feature's axis.
WIDTH_COLUMNS = ("width_min", "width_mean", "width_max")

#: Default ``detour`` of the pruning for layers: a branch stays when the shore
#: between its contacts is at least twice as long as the gap between them (an
#: arm, a bay), not for every bend of a digitized shore line. Measured on 200
#: OSM lakes (``benchmarks/bench_centerlines.py``): the polygon default 0.028
#: keeps 31 terminal branches per lake, 0.5 keeps 17, 1.0 keeps 12 with 1.2
#: spurious ones and 95% of each lake covered by the discs of its line, where
#: pruning by ``lam`` at the mean width instead (1.3 spurious) cuts whole narrow
#: arms (83% covered, as pygeoops.centerline's defaults).
DETOUR = 1.0


def _widths(ma: Any) -> tuple[float, float, float]:
    edges = np.asarray(ma.edges).reshape(-1, 2)
    r = np.asarray(ma.radii, np.float64)
    if len(edges) == 0:
        return (float(2 * r.min()), float(2 * r.mean()), float(2 * r.max())) if len(r) else (np.nan,) * 3
    length = np.linalg.norm(ma.points[edges[:, 0]] - ma.points[edges[:, 1]], axis=1)
    mean = float(np.sum(length * (r[edges[:, 0]] + r[edges[:, 1]])) / max(float(length.sum()), 1e-300))
    return float(2 * r.min()), mean, float(2 * r.max())


def centerlines(layer: Any, *, show_progress: bool | None = None, **options: Any) -> Any:
    """The medial axis of every polygon feature of a layer, with its widths.

    Parameters
    ----------
    layer : geopandas.GeoDataFrame, geopandas.GeoSeries, str or path
        Polygon or MultiPolygon features (a path is read with
        ``geopandas.read_file``). Never modified.
    show_progress : bool, optional
        Progress bar over the features (default: when stderr is a terminal).
    **options
        Passed to :func:`medialaxis.medial_axis` for each feature (``lam``,
        ``tolerance``, ``detour``, ...), in the layer's units. ``detour``
        defaults to :data:`DETOUR` (1.0, not the 0.028 of single polygons), so
        a lake or a road gets its centre line and its real arms, not a branch
        to every bend of the shore.

    Returns
    -------
    geopandas.GeoDataFrame
        One row per input feature, with the input's index, columns and CRS;
        the geometry is the axis (a MultiLineString of its branches; ``None``
        for an empty or missing input geometry) and ``width_min``,
        ``width_mean``, ``width_max`` are twice the radius (``NaN`` where no
        axis).

    Raises
    ------
    MissingDependencyError
        geopandas is not installed.
    InvalidInputError
        A feature that is not a polygon (named by its index), or a bad option.

    Examples
    --------
    >>> import geopandas as gpd, shapely, medialaxis as mx
    >>> strips = gpd.GeoDataFrame({"name": ["strip"]}, geometry=[shapely.box(0, 0, 100, 10)], crs="EPSG:3857")
    >>> out = mx.centerlines(strips)  # or mx.centerlines("roads.gpkg", tolerance=0.1)
    >>> out.loc[0, "name"], round(float(out.loc[0, "width_max"]), 1), out.crs.to_epsg(), out.geometry[0].geom_type
    ('strip', 10.0, 3857, 'MultiLineString')
    """
    gpd = _optional.require("geopandas", "geopandas")
    shapely = _optional.require("shapely", "shapely")
    if isinstance(layer, (str, os.PathLike)):
        if not os.path.exists(layer):
            raise InputFileError(f"no such file: {str(layer)!r}")
        try:
            layer = gpd.read_file(layer)
        except (OSError, ValueError, RuntimeError) as exc:  # GDAL's errors (pyogrio, fiona)
            raise InputFileError(f"cannot read the layer {str(layer)!r}: {exc}") from exc
    if isinstance(layer, gpd.GeoSeries):
        frame = gpd.GeoDataFrame(geometry=layer, crs=layer.crs)
    elif isinstance(layer, gpd.GeoDataFrame):
        frame = layer
    else:
        raise InvalidInputError(f"centerlines needs a GeoDataFrame, a GeoSeries or a file path, got {type(layer).__name__}")
    geometries, widths = [], []
    for index, geom in progress(list(zip(frame.index, frame.geometry)), desc="features", show=show_progress):
        if geom is None or geom.is_empty:
            geometries.append(None)
            widths.append((np.nan,) * 3)
            continue
        if geom.geom_type not in ("Polygon", "MultiPolygon"):
            raise InvalidInputError(f"feature {index!r} is a {geom.geom_type}; centerlines needs polygons")
        ma = medial_axis(geom, **{"detour": DETOUR, **options})
        lines = [shapely.LineString(branch.points) for branch in ma.branches() if len(branch.points) >= 2]
        geometries.append(shapely.MultiLineString(lines) if lines else None)
        widths.append(_widths(ma))
    out = frame.drop(columns=frame.geometry.name).copy()
    for k, name in enumerate(WIDTH_COLUMNS):
        out[name] = [w[k] for w in widths]
    return gpd.GeoDataFrame(out, geometry=gpd.GeoSeries(geometries, index=frame.index, crs=frame.crs), crs=frame.crs)
