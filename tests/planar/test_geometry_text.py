"""WKT and GeoJSON text is a shape, as shapely.from_wkt / from_geojson read it, not a file name."""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely

import medialaxis as mx
from medialaxis.datasets import data_path


def test_wkt_text_gives_the_axis_of_its_file_and_of_its_geometry():
    path = data_path("bracket_two_holes.wkt")
    text = path.read_text()
    from_text, from_file = mx.medial_axis(text), mx.medial_axis(path)
    from_geometry = mx.medial_axis(shapely.from_wkt(text))
    assert np.array_equal(from_text.points, from_file.points) and np.array_equal(from_text.radii, from_geometry.radii)


def test_geojson_text_is_read_as_geojson():
    bar = shapely.box(0, 0, 10, 2)
    ma = mx.medial_axis(json.dumps(shapely.geometry.mapping(bar)))
    assert ma.radii.max() == pytest.approx(1.0)  # half the width
    assert np.array_equal(ma.points, mx.medial_axis(bar).points)


def test_a_long_string_that_is_no_file_says_so():
    with pytest.raises(mx.InputFileError, match="not a file name"):
        mx.medial_axis("x" * 5000)
    with pytest.raises(mx.InputFileError, match="cannot parse WKT"):
        mx.medial_axis("POLYGON ((0 0, 1 0, 1")
