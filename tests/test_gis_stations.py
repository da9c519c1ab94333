"""Stations along the centerlines of polygon layers: position, width and distance against exact answers."""

import numpy as np
import pytest
import shapely

import medialaxis as mx

gpd = pytest.importorskip("geopandas")
from medialaxis.gis import stations  # noqa: E402

X0, Y0 = 500_000.0, 4_649_000.0
ROAD = shapely.box(X0, Y0, X0 + 300, Y0 + 12)
LAKE = shapely.Point(X0 + 600, Y0 + 100).buffer(80, quad_segs=64).difference(
    shapely.Point(X0 + 600, Y0 + 100).buffer(20, quad_segs=64))


@pytest.fixture(scope="module")
def layer():
    return gpd.GeoDataFrame({"name": ["road", "lake"]}, geometry=[ROAD, LAKE], index=[10, 20], crs="EPSG:32633")


def test_the_annulus_circle_and_the_road_mid_line(layer):
    points = stations(layer, step=10.0)
    assert points.crs == layer.crs and set(points["feature"]) == {10, 20}
    lake = points[points["feature"] == 20]
    # truth: the axis of an annulus of radii 20 and 80 is the circle of radius 50, width 60, length 2 pi 50
    xy = shapely.get_coordinates(lake.geometry.values)
    np.testing.assert_allclose(np.hypot(*(xy - [X0 + 600, Y0 + 100]).T), 50.0, atol=0.5)
    np.testing.assert_allclose(lake["width"], 60.0, atol=0.5)
    assert lake["distance"].max() == pytest.approx(2 * np.pi * 50, rel=0.01)
    assert np.allclose(np.diff(lake["distance"])[:-1], 10.0)
    road = points[points["feature"] == 10]
    # truth: the mid-line y = Y0 + 6 of the 12 m strip, 12 wide (the ends, within 6 of the short sides, apart)
    mid = road[road.geometry.x.between(X0 + 6, X0 + 294)]
    np.testing.assert_allclose(mid.geometry.y, Y0 + 6, atol=1e-6)
    np.testing.assert_allclose(mid["width"], 12.0, atol=1e-6)
    # every station's width is twice its distance to the shore (shapely, GEOS)
    for geom, part in zip((ROAD, LAKE), (road, lake)):
        shore = 2 * shapely.distance(part.geometry.values, geom.boundary)
        np.testing.assert_allclose(part["width"], shore, atol=0.02 * part["width"].max())


def test_stations_follow_the_lines_of_centerlines(layer):
    lines = mx.centerlines(layer)
    points = stations(layer)  # one per vertex
    for index, line in lines.geometry.items():
        on = points[points["feature"] == index]
        for k, branch in enumerate(line.geoms):
            xy = shapely.get_coordinates(on[on["branch"] == k].geometry.values)
            np.testing.assert_allclose(xy, shapely.get_coordinates(branch))
            along = on.loc[on["branch"] == k, "distance"].to_numpy()
            assert along[-1] == pytest.approx(branch.length)
    assert lines.loc[20, "width_max"] == pytest.approx(points.loc[points["feature"] == 20, "width"].max())


def test_plain_geometries_dask_and_bad_steps(layer):
    points = stations([ROAD, None])
    assert set(points["feature"]) == {0} and points.crs is None
    dask_geopandas = pytest.importorskip("dask_geopandas")
    lazy = stations(dask_geopandas.from_geopandas(layer, npartitions=2), step=10.0)
    assert len(lazy.compute()) == len(stations(layer, step=10.0))
    for bad in (0.0, -1.0, float("nan"), "5"):
        with pytest.raises(mx.InvalidInputError, match="step must be a positive distance"):
            stations(layer, step=bad)
