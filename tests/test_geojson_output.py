"""GeoJSON outputs land where GIS tools put their inputs."""

import json

import numpy as np
import shapely
from shapely.geometry import box, shape

import medialaxis as mx


def test_image_axis_is_written_with_x_column_and_y_row(tmp_path):
    image = np.zeros((60, 90), bool)
    image[15:45, 10:80] = True  # rows 15-44, columns 10-79: wider than tall
    path = tmp_path / "axis.geojson"
    mx.medial_axis(image).save(path)
    doc = json.loads(path.read_text())
    assert doc["properties"]["coordinates"].startswith("x = column, y = row")
    lines = [shape(f["geometry"]) for f in doc["features"] if f["properties"]["kind"] == "branch"]
    footprint = box(9.5, 14.5, 79.5, 44.5)  # the pixels' extent, x = column, y = row
    assert all(footprint.buffer(1e-9).contains(line) for line in lines)
    longest = max(lines, key=lambda line: line.length)
    xs, ys = np.asarray(longest.coords).T
    assert np.ptp(xs) > 30 and np.ptp(ys) < 1  # the long axis runs along x
    assert np.allclose(ys, 29.5, atol=0.5)


def test_polygon_axis_keeps_its_coordinates(tmp_path):
    polygon = shapely.Polygon([(100, 200), (170, 200), (170, 230), (100, 230)])
    path = tmp_path / "axis.geojson"
    mx.medial_axis(polygon).save(path)
    doc = json.loads(path.read_text())
    assert doc["properties"]["coordinates"] == "the result's own coordinates"
    lines = [shape(f["geometry"]) for f in doc["features"] if f["properties"]["kind"] == "branch"]
    assert all(polygon.buffer(1e-9).contains(line) for line in lines)
