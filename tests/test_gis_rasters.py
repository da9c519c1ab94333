"""Raster water masks: a GeoTIFF in, the river network out in its CRS, against an analytic river.

The river is the union of discs of radius r(s) centred on a sine curve c(s)
(slowly varying radius, curvature radius above the largest r): its medial
axis is the curve itself and its width 2 r(s), exactly. It is rasterized by
rasterio (GDAL) in UTM 33N (EPSG:32633) on square, non-square and rotated
pixel grids and written as a GeoTIFF; the axis must come back within one
pixel of the curve and the widths within one pixel of 2 r.
"""

import numpy as np
import pytest
import shapely

import medialaxis as mx

rasterio = pytest.importorskip("rasterio")
gpd = pytest.importorskip("geopandas")
from affine import Affine  # noqa: E402  (rasterio's dependency)
from rasterio.features import rasterize, shapes  # noqa: E402

from medialaxis.gis import stations  # noqa: E402

X0, Y0 = 500_000.0, 4_649_000.0  # metres, UTM zone 33N
LENGTH = 800.0


def curve(t):
    return np.column_stack([X0 + t, Y0 + 60.0 * np.sin(2 * np.pi * t / 400.0)])


def radius(t):
    return 12.0 + 6.0 * np.sin(2 * np.pi * t / 300.0)


T = np.linspace(0.0, LENGTH, 4001)
CURVE = curve(T)
RIVER = shapely.union_all(shapely.buffer(shapely.points(CURVE[::4]), radius(T[::4]), quad_segs=32))


def nearest(xy):
    """For each point: its distance to the analytic curve and the curve parameter there."""
    d = np.linalg.norm(xy[:, None, :] - CURVE[None, ::2, :], axis=2)
    k = d.argmin(axis=1)
    return d[np.arange(len(xy)), k], T[::2][k]


def geotiff(path, polygon, pixel=(2.0, 2.0), angle=0.0, margin=6, crs="EPSG:32633"):
    """``polygon`` rasterized by rasterio on a grid of ``pixel`` (width, height) turned by ``angle`` degrees."""
    turn = Affine.rotation(angle) @ Affine.scale(pixel[0], -pixel[1])
    col_row = np.asarray([~turn @ xy for xy in shapely.get_coordinates(polygon)])
    low = np.floor(col_row.min(axis=0)) - margin
    shape = tuple(int(s) for s in (np.ceil(col_row.max(axis=0)) - low + margin)[::-1])
    transform = turn @ Affine.translation(*low)
    mask = rasterize([(polygon, 1)], out_shape=shape, transform=transform, dtype="uint8")
    with rasterio.open(path, "w", driver="GTiff", height=shape[0], width=shape[1], count=1, dtype="uint8",
                       crs=crs, transform=transform) as out:
        out.write(mask, 1)
    return path, mask, transform


GRIDS = {"square": ((2.0, 2.0), 0.0), "non-square": ((2.0, 3.0), 0.0), "rotated": ((2.5, 1.5), 30.0)}


@pytest.mark.parametrize("grid", GRIDS)
def test_the_river_comes_back_on_its_curve_with_its_widths_in_its_crs(tmp_path, grid):
    pixel, angle = GRIDS[grid]
    path, mask, transform = geotiff(tmp_path / "water.tif", RIVER, pixel, angle)
    assert abs(mask.sum() * pixel[0] * pixel[1] / RIVER.area - 1) < 0.02  # rasterio drew the river
    lines = mx.centerlines(path)
    one_pixel = max(pixel)
    assert lines.crs.to_epsg() == 32633
    # the analytic axis is the curve, ending at the centres of the round caps; the computed one
    # ends within a pixel of them or reaches past them into the caps by under two pixels (a sampled
    # arc is not a circle)
    off, t = nearest(shapely.get_coordinates(lines.geometry.values))
    inner = (t > 0) & (t < LENGTH)
    assert t.min() <= one_pixel and t.max() >= LENGTH - one_pixel, (t.min(), t.max())
    assert off[inner].max() <= one_pixel and off[~inner].max(initial=0.0) <= 2 * one_pixel, (off[inner].max(),
                                                                                           off.max())
    # the whole river, end to end: the longest branch spans the curve
    assert lines["length"].max() > 0.95 * shapely.length(shapely.LineString(CURVE))
    points = stations(path, step=5.0)
    assert points.crs.to_epsg() == 32633 and set(points["branch"]) <= set(lines["branch"])
    off, t = nearest(shapely.get_coordinates(points.geometry.values))
    inner = (t > 0) & (t < LENGTH)
    assert inner.mean() > 0.95 and off[inner].max() <= one_pixel
    # widths: 2 r(s) along the curve; past its ends, where the curve has no width, twice the
    # distance to the shore rasterio drew (its pixels' outline), and to the analytic shore within
    # 1.5 pixels: at the tip of a round cap the staircase lies up to 0.6 pixel inside the circle
    width = points["width"].to_numpy()
    assert np.abs(width - 2 * radius(t))[inner].max() <= one_pixel
    drawn = shapely.union_all([shapely.geometry.shape(g) for g, v in shapes(
        mask.astype(np.uint8), transform=transform) if v == 1])
    past = points.geometry.values[~inner]
    assert np.abs(width[~inner] - 2 * shapely.distance(past, drawn.boundary)).max(initial=0.0) <= one_pixel
    assert np.abs(width[~inner] - 2 * shapely.distance(past, RIVER.boundary)).max(initial=0.0) <= 1.5 * one_pixel
    for _, row in lines.iterrows():  # the table's widths are the stations' extremes along the branch
        on = points[points["branch"] == row["branch"]]
        assert row["width_min"] <= on["width"].min() + 1e-9 and row["width_max"] >= on["width"].max() - 1e-9
    # distance along the branch is the analytic arc length between the stations' places on the curve
    main = points[points["branch"] == lines.loc[lines["length"].idxmax(), "branch"]]
    s = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(CURVE, axis=0), axis=1))])
    arc = np.interp(nearest(shapely.get_coordinates(main.geometry.values))[1], T, s)
    along = main["distance"].to_numpy()
    assert np.abs(np.abs(arc - arc[0]) - (along - along[0])).max() <= 0.01 * LENGTH + one_pixel


def test_a_y_shaped_river_has_one_junction_and_three_ends(tmp_path):
    t = np.linspace(0.0, 1.0, 200)
    arms = [np.column_stack([X0 + 0 * t, Y0 - 300 * t]), np.column_stack([X0 - 220 * t, Y0 + 260 * t]),
            np.column_stack([X0 + 200 * t, Y0 + 280 * t])]
    widths = (16.0, 10.0, 11.0)
    river = shapely.union_all([shapely.buffer(shapely.LineString(a), w, quad_segs=32) for a, w in zip(arms, widths)])
    path, _, _ = geotiff(tmp_path / "y.tif", river, (2.0, 2.0), 0.0)
    lines = mx.centerlines(path)
    kinds = {}
    for row in lines.itertuples():
        kinds[row.start_node], kinds[row.end_node] = row.start_kind, row.end_kind
    assert sorted(kinds.values()) == ["end", "end", "end", "junction"]
    with rasterio.open(path) as dataset:  # an open dataset is the same raster
        again = mx.centerlines(dataset)
    assert all(a.equals_exact(b, 0.0) for a, b in zip(again.geometry, lines.geometry))
    tips = np.asarray([a[-1] for a in arms])
    ends = np.asarray([row.geometry.coords[0 if row.start_kind == "end" else -1] for row in lines.itertuples()])
    tip = np.linalg.norm(ends[:, None] - tips[None], axis=2).argmin(axis=1)
    assert sorted(tip) == [0, 1, 2]  # one branch to each arm's tip
    # each end lies at the centre of its arm's round tip (the medial axis of a disc cap ends there),
    # up to the two pixels the axis reaches into a sampled cap
    assert np.linalg.norm(ends - tips[tip], axis=1).max() <= 2 * 2.0
    points = stations(path)
    for row, k in zip(lines.itertuples(), tip):  # along each arm, its width (the median: the junction apart)
        assert np.median(points.loc[points["branch"] == row.branch, "width"]) == pytest.approx(2 * widths[k], abs=2.0)


def test_sheared_missing_and_non_raster_inputs_say_what_is_wrong(tmp_path):
    sheared = tmp_path / "sheared.tif"
    with rasterio.open(sheared, "w", driver="GTiff", height=20, width=20, count=1, dtype="uint8",
                       transform=Affine(1.0, 0.5, 0.0, 0.0, -1.0, 0.0)) as out:
        data = np.zeros((20, 20), np.uint8)
        data[5:15, 5:15] = 1
        out.write(data, 1)
    with pytest.raises(mx.InvalidInputError, match="sheared"):
        mx.centerlines(sheared)
    with pytest.raises(mx.InputFileError, match="no such file"):
        mx.centerlines(tmp_path / "missing.tif")
    (tmp_path / "bad.tif").write_bytes(b"not a tiff")
    with pytest.raises(mx.InputFileError, match="cannot read the raster"):
        mx.centerlines(tmp_path / "bad.tif")
    with pytest.raises(mx.InvalidInputError, match="band"):
        mx.centerlines(sheared, band=2)


def test_cli_writes_the_network_in_the_rasters_crs(tmp_path):
    from medialaxis.cli import main

    path, _, _ = geotiff(tmp_path / "water.tif", RIVER, (2.0, 3.0), 0.0)
    out, points = tmp_path / "lines.gpkg", tmp_path / "stations.fgb"
    assert main(["centerlines", str(path), "-o", str(out), "--stations", str(points), "--step", "10"]) == 0
    back = gpd.read_file(out)
    assert back.crs.to_epsg() == 32633 and {"start_kind", "end_kind", "width_mean"} <= set(back.columns)
    assert nearest(shapely.get_coordinates(back.geometry.values))[0].max() <= 2 * 3.0  # caps included
    stations_back = gpd.read_file(points)
    assert stations_back.crs.to_epsg() == 32633 and stations_back.geom_type.eq("Point").all()
    off, t = nearest(shapely.get_coordinates(stations_back.geometry.values))
    inner = (t > 0) & (t < LENGTH)
    assert np.abs(stations_back["width"] - 2 * radius(t))[inner].max() <= 3.0
    assert main(["centerlines", str(path), "-o", str(out), "--step", "-1"]) == 2
