"""Centerlines and stations of GIS layers: one medial axis per feature, attributes and CRS kept.

The GIS "centerline" tools (PostGIS ``ST_ApproximateMedialAxis``,
pygeoops.centerline, centerline) work per feature and keep the attributes;
:func:`centerlines` does the same and adds the widths the radius function
gives. Layers need geopandas (``pip install geopandas``); plain shapely
polygons need only pandas; a ``dask_geopandas.GeoDataFrame`` needs
dask-geopandas; a raster mask rasterio. All are loaded on first use.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from medialaxis import _optional
from medialaxis.errors import InputFileError, InvalidInputError
from medialaxis.gis.features import WIDTH_COLUMNS
from medialaxis.gis.network import STATION_COLUMNS
from medialaxis.gis.parallel import check_parallel, map_features
from medialaxis.gis.rasters import is_raster, raster_network, raster_stations

__all__ = ["centerlines", "stations"]


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


def _is_dask_frame(layer: Any) -> bool:
    return type(layer).__module__.startswith("dask_geopandas") or (
        type(layer).__module__.startswith("dask") and hasattr(layer, "map_partitions"))


def _frame(gpd: Any, layer: Any) -> Any:
    """A GeoDataFrame of a GeoDataFrame, a GeoSeries or a vector file."""
    if isinstance(layer, (str, os.PathLike)):
        if not os.path.exists(layer):
            raise InputFileError(f"no such file: {str(layer)!r}")
        try:
            layer = gpd.read_file(layer)
        except (OSError, ValueError, RuntimeError) as exc:  # GDAL's errors (pyogrio, fiona)
            raise InputFileError(f"cannot read the layer {str(layer)!r}: {exc}") from exc
    if isinstance(layer, gpd.GeoSeries):
        return gpd.GeoDataFrame(geometry=layer, crs=layer.crs)
    if isinstance(layer, gpd.GeoDataFrame):
        return layer
    raise InvalidInputError(
        "centerlines needs a GeoDataFrame, a GeoSeries, a file path or shapely polygons, "
        f"got {type(layer).__name__}"
    )


def _on_partitions(function: Any, layer: Any, n_jobs: Any, scheduler: Any, **kwargs: Any) -> Any:
    """``function`` on each partition of a dask GeoDataFrame: a lazy dask GeoDataFrame."""
    if n_jobs is not None or scheduler is not None:
        raise InvalidInputError("a dask GeoDataFrame runs on the scheduler active when it is computed; "
                                "n_jobs and scheduler are not taken with it")
    _optional.require("dask_geopandas", "dask-geopandas")
    meta = function(layer._meta, show_progress=False, **kwargs)
    return layer.map_partitions(function, show_progress=False, meta=meta, **kwargs)


def centerlines(layer: Any, *, n_jobs: int | None = None, scheduler: Any = None, band: int = 1,
                show_progress: bool | None = None, **options: Any) -> Any:
    """The medial axis of every polygon feature of a layer, with its widths; or the network of a raster mask.

    Parameters
    ----------
    layer : GeoDataFrame, GeoSeries, dask_geopandas.GeoDataFrame, str, path, rasterio dataset, shapely geometry \
or sequence of them
        Polygon or MultiPolygon features (a vector file is read with
        ``geopandas.read_file``); a single shapely Polygon or MultiPolygon,
        or a list, tuple or object array of them (``None`` allowed), is a
        layer without attributes or CRS. A ``.tif``, ``.tiff`` or ``.vrt``
        file (or an open rasterio dataset) is a raster mask: its band
        ``band``'s non-zero valid pixels (see :mod:`medialaxis.gis.rasters`).
        Never modified.
    n_jobs : int, optional
        Features computed at once: None or 1 in this process, one after the
        other; more on that many threads (measured faster than worker
        processes, see :mod:`medialaxis.gis.parallel`).
    scheduler : {None, "threads", "processes", "synchronous"}, dask Client or address, optional
        Where the features run: threads, worker processes (``n_jobs``, or
        all CPUs), in order in this process, or a Dask cluster in chunks.
        A dask GeoDataFrame takes neither: it runs on the scheduler active
        when it is computed. A raster mask is one axis: neither applies.
    band : int
        The band of a raster mask (1-based).
    show_progress : bool, optional
        Progress bar over the features (default: when stderr is a terminal).
        Ctrl-C stops the run and raises :class:`~medialaxis.errors.Cancelled`.
    **options
        Passed to :func:`medialaxis.medial_axis` for each feature (``lam``,
        ``tolerance``, ``detour``, ...), in the layer's units. ``detour``
        defaults to :data:`~medialaxis.gis.DETOUR` (1.0, not the 0.028 of
        single polygons), so a lake or a road gets its centre line and its
        real arms, not a branch to every bend of the shore. A raster mask
        takes the image defaults.

    Returns
    -------
    geopandas.GeoDataFrame, pandas.DataFrame or dask_geopandas.GeoDataFrame
        For polygons, one row per input feature. For a GeoDataFrame,
        GeoSeries or file: a GeoDataFrame with the input's index, columns
        and CRS; the geometry is the axis (a MultiLineString of its
        branches, as :meth:`MedialAxis.to_shapely`; ``None`` for an empty or
        missing input geometry) and ``width_min``, ``width_mean``,
        ``width_max`` are twice the radius (``NaN`` where no axis). A dask
        GeoDataFrame gives the same, lazily, partition by partition. For
        shapely geometries: a pandas DataFrame (geopandas not needed) with
        the index 0, 1, ... and the columns ``geometry`` (shapely objects),
        ``width_min``, ``width_mean``, ``width_max``.
        For a raster mask, the network: one row per branch in the raster's
        CRS, a LineString in map coordinates, and the columns of
        :data:`~medialaxis.gis.network.BRANCH_COLUMNS` (``start_node``,
        ``end_node`` and their kind ``"end"`` or ``"junction"``, ``length``
        and the widths, in map units).

    Raises
    ------
    MissingDependencyError
        geopandas (layers, files), pandas (shapely inputs), dask-geopandas
        or rasterio is not installed.
    InvalidInputError
        A feature that is not a polygon (named by its index), an input of
        another type, a sheared raster, or a bad option.
    InputFileError
        A file that is missing or cannot be read.
    Cancelled
        Ctrl-C during the run.

    Examples
    --------
    >>> import geopandas as gpd, shapely, medialaxis as mx
    >>> strips = gpd.GeoDataFrame({"name": ["strip"]}, geometry=[shapely.box(0, 0, 100, 10)], crs="EPSG:3857")
    >>> out = mx.centerlines(strips)  # or mx.centerlines("roads.gpkg", n_jobs=2), mx.centerlines("water.tif")
    >>> out.loc[0, "name"], round(float(out.loc[0, "width_max"]), 1), out.crs.to_epsg(), out.geometry[0].geom_type
    ('strip', 10.0, 3857, 'MultiLineString')
    >>> table = mx.centerlines(shapely.box(0, 0, 100, 10))  # a plain polygon: a pandas table, one row
    >>> type(table).__name__, list(table.columns), round(float(table.loc[0, "width_max"]), 1)
    ('DataFrame', ['geometry', 'width_min', 'width_mean', 'width_max'], 10.0)
    """
    if _is_dask_frame(layer):
        return _on_partitions(centerlines, layer, n_jobs, scheduler, **options)
    check_parallel(n_jobs, scheduler)
    if is_raster(layer):
        return raster_network(layer, options, band)
    shapely = _optional.require("shapely", "shapely")
    plain = _plain_geometries(shapely, layer)
    run = {"n_jobs": n_jobs, "scheduler": scheduler, "show_progress": show_progress}
    if plain is not None:
        pd = _optional.require("pandas", "pandas")
        rows = map_features("lines", list(enumerate(plain)), options, **run)
        table = pd.DataFrame({"geometry": pd.Series([row[0] for row in rows], dtype=object)})
        for k, name in enumerate(WIDTH_COLUMNS):
            table[name] = np.asarray([row[1][k] for row in rows], np.float64)
        return table
    gpd = _optional.require("geopandas", "geopandas")
    if isinstance(layer, gpd.GeoSeries):  # no frame of the input: its rows' attributes are none
        index, geoms, crs, out = layer.index, layer.array, layer.crs, None
    else:
        frame = _frame(gpd, layer)
        index, geoms, crs = frame.index, frame.geometry.array, frame.crs
        out = frame.drop(columns=frame.geometry.name)
    rows = map_features("lines", list(zip(index, geoms)), options, **run)
    widths = np.asarray([row[1] for row in rows], np.float64).reshape(-1, len(WIDTH_COLUMNS))
    columns = {name: widths[:, k] for k, name in enumerate(WIDTH_COLUMNS)}
    out = _optional.require("pandas", "pandas").DataFrame(columns, index=index) if out is None else out.assign(**columns)
    lines = np.empty(len(rows), dtype=object)
    lines[:] = [row[0] for row in rows]
    return gpd.GeoDataFrame(out, geometry=gpd.GeoSeries(lines, index=index, crs=crs), crs=crs)


def stations(layer: Any, *, step: float | None = None, n_jobs: int | None = None, scheduler: Any = None,
             band: int = 1, show_progress: bool | None = None, **options: Any) -> Any:
    """Points along the centerlines with the width there and the distance along their branch.

    The same axes as :func:`centerlines` (same inputs and options), given as
    stations, as GRWL gives a river's width along its centre line.

    Parameters
    ----------
    layer, n_jobs, scheduler, band, show_progress, **options
        As for :func:`centerlines`; plain shapely geometries need geopandas here.
    step : float, optional
        Distance between stations along each branch, in map units (and one
        at the branch's end), positions and widths interpolated linearly
        between the axis's vertices; None: one station per vertex.

    Returns
    -------
    geopandas.GeoDataFrame or dask_geopandas.GeoDataFrame
        One Point per station, in the input's CRS, with the columns
        ``branch`` (the branch's row of the raster network, or its position
        in the feature's MultiLineString of :func:`centerlines`),
        ``distance`` (along the branch from its first vertex) and ``width``
        (twice the radius), and for polygon layers ``feature``, the input
        row's index label.

    Examples
    --------
    >>> import shapely
    >>> from medialaxis.gis import stations
    >>> points = stations(shapely.box(0, 0, 100, 10), step=20.0)  # a strip 10 wide: its mid-line
    >>> points["distance"].round(1).tolist(), points["width"].round(1).tolist()
    ([0.0, 20.0, 40.0, 60.0, 80.0, 90.0], [10.0, 10.0, 10.0, 10.0, 10.0, 10.0])
    """
    if step is not None and not (isinstance(step, (int, float, np.number)) and np.isfinite(step) and step > 0):
        raise InvalidInputError(f"step must be a positive distance or None, got {step!r}")
    if _is_dask_frame(layer):
        return _on_partitions(stations, layer, n_jobs, scheduler, step=step, **options)
    check_parallel(n_jobs, scheduler)
    if is_raster(layer):
        return raster_stations(layer, options, step, band)
    gpd = _optional.require("geopandas", "geopandas")
    shapely = _optional.require("shapely", "shapely")
    plain = _plain_geometries(shapely, layer)
    frame = gpd.GeoDataFrame(geometry=plain) if plain is not None else _frame(gpd, layer)
    rows = map_features("stations", list(zip(frame.index, frame.geometry)), options, step=step, n_jobs=n_jobs,
                        scheduler=scheduler, show_progress=show_progress)
    counts = [len(row["branch"]) for row in rows]
    columns: dict[str, Any] = {"feature": frame.index[np.repeat(np.arange(len(frame)), counts)].to_numpy()}
    for name in STATION_COLUMNS:
        columns[name] = np.concatenate([row[name] for row in rows]) if rows else np.empty(0)
    columns["branch"] = np.asarray(columns["branch"], np.int64)
    xy = (columns.pop("x"), columns.pop("y"))
    return gpd.GeoDataFrame(columns, geometry=gpd.points_from_xy(*xy), crs=frame.crs)
