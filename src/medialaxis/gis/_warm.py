"""Imported once by the worker-process server of :mod:`medialaxis.gis.parallel`: one small feature computed.

The server forks every worker from itself, so workers start with the modules
imported and the compiled kernels loaded (about 1.6 s per process otherwise).
"""

import shapely

from medialaxis.gis.features import run_chunk

run_chunk("lines", [(0, shapely.Point(0, 0).buffer(10).union(shapely.box(0, 0, 30, 3)))], {})
