"""``mx.centerlines`` on plain shapely polygons: a pandas table, no geopandas needed."""

import sys

import numpy as np
import pytest
import shapely

import medialaxis as mx

pd = pytest.importorskip("pandas")

ROAD = shapely.box(0, 0, 300, 12)
LAKE = shapely.Point(600, 100).buffer(80).difference(shapely.Point(600, 100).buffer(20))
PARCELS = shapely.MultiPolygon([shapely.box(0, 300, 40, 360), shapely.box(100, 300, 160, 330)])


def test_a_list_gives_one_row_per_geometry_with_the_layers_columns():
    table = mx.centerlines([ROAD, LAKE, None, PARCELS, shapely.Polygon()])
    assert isinstance(table, pd.DataFrame) and list(table.index) == [0, 1, 2, 3, 4]
    assert list(table.columns) == ["geometry", "width_min", "width_mean", "width_max"]
    assert table.loc[2, "geometry"] is None and table.loc[4, "geometry"] is None
    assert np.isnan(table.loc[2, "width_mean"]) and np.isnan(table.loc[4, "width_max"])
    # truth: shapely's largest inscribed circle (GEOS) for the widest place of each feature
    for k, polygon in ((0, ROAD), (1, LAKE), (3, PARCELS)):
        line = table.loc[k, "geometry"]
        assert line.geom_type == "MultiLineString" and polygon.buffer(1e-6).contains(line)
        widest = max(shapely.maximum_inscribed_circle(part, 1e-3).length for part in shapely.get_parts(polygon))
        assert table.loc[k, "width_max"] == pytest.approx(2 * widest, rel=0.01), k
    assert table.loc[0, "width_mean"] == pytest.approx(12.0, rel=0.05)
    # the annulus of radii 20 and 80: its line is the circle of radius 50, width 60
    assert np.allclose(np.hypot(*(shapely.get_coordinates(table.loc[1, "geometry"]) - [600, 100]).T), 50, atol=0.5)
    assert table.loc[1, "width_mean"] == pytest.approx(60.0, rel=0.02)
    assert len(table.loc[3, "geometry"].geoms) >= 2  # both parcels


def test_one_geometry_is_one_row_the_layers_axis():
    table = mx.centerlines(ROAD, lam=2.0)
    ma = mx.medial_axis(ROAD, detour=mx.gis.DETOUR, lam=2.0)
    assert len(table) == 1 and table.loc[0, "geometry"].equals(ma.to_shapely())
    assert table.loc[0, "width_max"] == pytest.approx(2 * ma.radii.max())
    array = mx.centerlines(np.array([ROAD, LAKE], dtype=object))
    assert len(array) == 2 and array.loc[1, "geometry"].geom_type == "MultiLineString"


def test_the_same_answer_as_for_a_layer():
    gpd = pytest.importorskip("geopandas")
    plain = mx.centerlines((ROAD, LAKE, PARCELS))
    layer = mx.centerlines(gpd.GeoDataFrame(geometry=[ROAD, LAKE, PARCELS]))
    for name in ("width_min", "width_mean", "width_max"):
        np.testing.assert_allclose(plain[name], layer[name])
    assert all(a.equals(b) for a, b in zip(plain["geometry"], layer.geometry))
    again = gpd.GeoDataFrame(plain, crs="EPSG:32633")  # the table becomes a layer as it is
    assert again.geometry.name == "geometry" and again.crs.to_epsg() == 32633


def test_works_without_geopandas(monkeypatch):
    monkeypatch.setitem(sys.modules, "geopandas", None)
    table = mx.centerlines(ROAD)
    assert table.loc[0, "geometry"].geom_type == "MultiLineString"


def test_wrong_items_are_named():
    with pytest.raises(mx.InvalidInputError, match="feature 1 is a LineString"):
        mx.centerlines([ROAD, shapely.LineString([(0, 0), (1, 1)])])
    with pytest.raises(mx.InvalidInputError, match="item 1 is a str"):
        mx.centerlines([ROAD, "road"])
    pytest.importorskip("geopandas")  # other objects are checked against geopandas' types
    with pytest.raises(mx.InvalidInputError, match="shapely polygons, got int"):
        mx.centerlines(3)
