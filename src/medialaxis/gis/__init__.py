"""GIS layers and raster masks: centerlines with widths, networks of branches, stations along them.

* :mod:`~medialaxis.gis.layers`: :func:`centerlines` and :func:`stations`, the public calls;
* :mod:`~medialaxis.gis.features`: the work for one feature (its axis, widths, stations);
* :mod:`~medialaxis.gis.parallel`: features in chunks on worker processes, threads or Dask;
* :mod:`~medialaxis.gis.rasters`: GeoTIFF masks read by rasterio, the axis in map units;
* :mod:`~medialaxis.gis.network`: an axis as branches between end and junction nodes, and stations.
"""

from medialaxis.gis.features import DETOUR, WIDTH_COLUMNS
from medialaxis.gis.layers import centerlines, stations
from medialaxis.gis.network import BRANCH_COLUMNS, STATION_COLUMNS

__all__ = ["centerlines", "stations", "DETOUR", "WIDTH_COLUMNS", "BRANCH_COLUMNS", "STATION_COLUMNS"]
