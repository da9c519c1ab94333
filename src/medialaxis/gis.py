"""Centerlines of GIS layers: one medial axis per feature, attributes and CRS kept.

The GIS "centerline" tools (PostGIS ``ST_ApproximateMedialAxis``,
pygeoops.centerline, centerline) work per feature and keep the attributes;
:func:`centerlines` does the same and adds the widths the radius function
gives. Layers need geopandas (``pip install geopandas``); plain shapely
polygons need only pandas. Both are loaded on first use.
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


def _feature_axis(index: Any, geom: Any, options: dict[str, Any]) -> tuple[Any, tuple[float, ...]]:
    """The axis of one feature as a MultiLineString (None when empty) and its widths."""
    if geom is None or geom.is_empty:
        return None, (np.nan,) * 3
    if geom.geom_type not in ("Polygon", "MultiPolygon"):
        raise InvalidInputError(f"feature {index!r} is a {geom.geom_type}; centerlines needs polygons")
    ma = medial_axis(geom, **{"detour": DETOUR, **options})
    lines = ma.to_shapely()
    return (lines if len(lines.geoms) else None), _widths(ma)


def _plain_geometries(shapely: Any, layer: Any) -> list[Any] | None:
    """The geometries of a shapely geometry or a sequence of them (None allowed), else None."""
    if isinstance(layer, shapely.Geometry):
        return [layer]
    if isinstance(layer, (list, tuple)) or (isinstance(layer, np.ndarray) and layer.dtype == object):
        items = list(np.asarray(layer, dtype=object).ravel()) if isinstance(layer, np.ndarray) else list(layer)
        for k, item in enumerate(items):
            if item is not None and not isinstance(item, shapely.Geometry):
                raise InvalidInputError(f"centerlines: item {k} is a {type(item).__name__}, not a shapely geometry")
        return items
    return None


def centerlines(layer: Any, *, show_progress: bool | None = None, **options: Any) -> Any:
    """The medial axis of every polygon feature of a layer, with its widths.

    Parameters
    ----------
    layer : geopandas.GeoDataFrame, geopandas.GeoSeries, str, path, shapely geometry or sequence of them
        Polygon or MultiPolygon features (a path is read with
        ``geopandas.read_file``); a single shapely Polygon or MultiPolygon,
        or a list, tuple or object array of them (``None`` allowed), is a
        layer without attributes or CRS. Never modified.
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
    geopandas.GeoDataFrame or pandas.DataFrame
        One row per input feature. For a GeoDataFrame, GeoSeries or file: a
        GeoDataFrame with the input's index, columns and CRS; the geometry
        is the axis (a MultiLineString of its branches, as
        :meth:`MedialAxis.to_shapely`; ``None`` for an empty or missing
        input geometry) and ``width_min``, ``width_mean``, ``width_max`` are
        twice the radius (``NaN`` where no axis). For shapely geometries: a
        pandas DataFrame (geopandas not needed) with the index 0, 1, ... and
        the same columns ``geometry`` (shapely objects), ``width_min``,
        ``width_mean``, ``width_max``; ``geopandas.GeoDataFrame(table,
        crs=...)`` makes it a layer. A single geometry gives one row.

    Raises
    ------
    MissingDependencyError
        geopandas (layers, files) or pandas (shapely inputs) is not installed.
    InvalidInputError
        A feature that is not a polygon (named by its index), an input of
        another type, or a bad option.

    Examples
    --------
    >>> import geopandas as gpd, shapely, medialaxis as mx
    >>> strips = gpd.GeoDataFrame({"name": ["strip"]}, geometry=[shapely.box(0, 0, 100, 10)], crs="EPSG:3857")
    >>> out = mx.centerlines(strips)  # or mx.centerlines("roads.gpkg", tolerance=0.1)
    >>> out.loc[0, "name"], round(float(out.loc[0, "width_max"]), 1), out.crs.to_epsg(), out.geometry[0].geom_type
    ('strip', 10.0, 3857, 'MultiLineString')
    >>> table = mx.centerlines(shapely.box(0, 0, 100, 10))  # a plain polygon: a pandas table, one row
    >>> type(table).__name__, list(table.columns), round(float(table.loc[0, "width_max"]), 1)
    ('DataFrame', ['geometry', 'width_min', 'width_mean', 'width_max'], 10.0)
    """
    shapely = _optional.require("shapely", "shapely")
    plain = _plain_geometries(shapely, layer)
    if plain is not None:
        pd = _optional.require("pandas", "pandas")
        rows = [_feature_axis(k, geom, options)
                for k, geom in progress(list(enumerate(plain)), desc="features", show=show_progress)]
        table = pd.DataFrame({"geometry": pd.Series([row[0] for row in rows], dtype=object)})
        for k, name in enumerate(WIDTH_COLUMNS):
            table[name] = np.asarray([row[1][k] for row in rows], np.float64)
        return table
    gpd = _optional.require("geopandas", "geopandas")
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
        raise InvalidInputError(
            "centerlines needs a GeoDataFrame, a GeoSeries, a file path or shapely polygons, "
            f"got {type(layer).__name__}"
        )
    geometries, widths = [], []
    for index, geom in progress(list(zip(frame.index, frame.geometry)), desc="features", show=show_progress):
        lines, width = _feature_axis(index, geom, options)
        geometries.append(lines)
        widths.append(width)
    out = frame.drop(columns=frame.geometry.name).copy()
    for k, name in enumerate(WIDTH_COLUMNS):
        out[name] = [w[k] for w in widths]
    return gpd.GeoDataFrame(out, geometry=gpd.GeoSeries(geometries, index=frame.index, crs=frame.crs), crs=frame.crs)
