"""Centerlines of GIS layers: one axis per feature, the layer's index, columns and CRS kept."""

import numpy as np
import pytest
import shapely

import medialaxis as mx

gpd = pytest.importorskip("geopandas")


@pytest.fixture()
def layer():
    # a road-like strip, a lake with an island, and two parcels in one feature (projected metres)
    x0, y0 = 500_000.0, 4_649_000.0
    road = shapely.Polygon([(x0, y0), (x0 + 300, y0), (x0 + 300, y0 + 12), (x0, y0 + 12)])
    lake = shapely.Point(x0 + 600, y0 + 100).buffer(80).difference(shapely.Point(x0 + 600, y0 + 100).buffer(20))
    parcels = shapely.MultiPolygon([shapely.box(x0, y0 + 300, x0 + 40, y0 + 360),
                                    shapely.box(x0 + 100, y0 + 300, x0 + 160, y0 + 330)])
    return gpd.GeoDataFrame({"name": ["road", "lake", "parcels"], "lanes": [2, 0, 0]},
                            geometry=[road, lake, parcels], index=[10, 20, 30], crs="EPSG:32633")


def test_one_axis_per_feature_with_attributes_crs_and_widths(layer):
    out = mx.centerlines(layer)
    assert list(out.index) == [10, 20, 30] and out.crs == layer.crs
    assert list(out["name"]) == ["road", "lake", "parcels"] and list(out["lanes"]) == [2, 0, 0]
    for geom, polygon in zip(out.geometry, layer.geometry):
        assert geom.geom_type == "MultiLineString" and polygon.buffer(1e-6).contains(geom)
    road = out.loc[10]
    assert np.isclose(road["width_mean"], 12.0, rtol=0.05) and road["width_max"] <= 12.0 + 1e-6
    lake = out.loc[20].geometry
    # the axis of an annulus of radii 20 and 80 is the circle of radius 50: one closed loop
    distances = np.hypot(*(np.asarray(shapely.get_coordinates(lake)) - [500_600.0, 4_649_100.0]).T)
    assert np.allclose(distances, 50.0, atol=0.5)
    assert np.isclose(out.loc[20, "width_mean"], 60.0, rtol=0.02)
    assert len(out.loc[30].geometry.geoms) >= 2  # both parcels
    assert layer.geometry.geom_type.tolist() == ["Polygon", "Polygon", "MultiPolygon"]  # input untouched


def test_a_geoseries_and_a_file(layer, tmp_path):
    out = mx.centerlines(layer.geometry)
    assert out.crs == layer.crs and len(out) == 3 and set(out.columns) >= {"width_min", "width_mean", "width_max"}
    path = tmp_path / "layer.gpkg"
    layer.to_file(path)
    again = mx.centerlines(path)
    assert list(again["name"]) == ["road", "lake", "parcels"] and again.crs == layer.crs


def test_empty_and_wrong_geometries(layer):
    holes = layer.copy()
    holes.loc[30, "geometry"] = None
    out = mx.centerlines(holes)
    assert out.loc[30].geometry is None and np.isnan(out.loc[30, "width_mean"])
    lines = layer.copy()
    lines.loc[20, "geometry"] = shapely.LineString([(0, 0), (1, 1)])
    with pytest.raises(mx.InvalidInputError, match="feature 20 is a LineString"):
        mx.centerlines(lines)


def test_cli_writes_a_layer_other_tools_read(layer, tmp_path, capsys):
    from medialaxis.cli import main

    source = tmp_path / "parcels.gpkg"
    layer.to_file(source)
    for ext in (".gpkg", ".shp", ".geojson"):
        target = tmp_path / f"centerlines{ext}"
        assert main(["centerlines", str(source), "-o", str(target)]) == 0
        back = gpd.read_file(target)
        assert len(back) == 3 and back.crs == layer.crs and list(back["name"]) == ["road", "lake", "parcels"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".medialaxis-")]
    (tmp_path / "bad.gpkg").write_bytes(b"not a geopackage")
    capsys.readouterr()
    assert main(["centerlines", str(tmp_path / "bad.gpkg"), "-o", str(tmp_path / "x.gpkg")]) == 1
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "cannot read the layer" in err
    assert main(["centerlines", str(source), "-o", str(tmp_path / "x.txt")]) == 2


# ------------------------------------------------------------------ a real layer
LAKES = __import__("pathlib").Path(__file__).parent / "data" / "osm_lakes.geojson"


@pytest.fixture(scope="module")
def lakes():
    return gpd.read_file(LAKES).to_crs("EPSG:3857")  # 30 OpenStreetMap lakes, WGS84 as distributed


@pytest.fixture(scope="module")
def lake_lines(lakes):
    return mx.centerlines(lakes)


def test_real_lakes_keep_rows_and_lines_stay_inside(lakes, lake_lines):
    assert len(lake_lines) == len(lakes) == 30 and lake_lines.crs == lakes.crs
    assert (lake_lines["islands"] == lakes["islands"]).all()
    for k, (line, lake) in enumerate(zip(lake_lines.geometry, lakes.geometry)):
        outside = shapely.get_coordinates(line.difference(lake))
        depth = shapely.distance(shapely.points(outside), lake.boundary).max() if len(outside) else 0.0
        assert depth <= 1e-6 * np.sqrt(lake.area), k


def test_real_lakes_one_loop_per_island(lakes, lake_lines):
    # truth: the polygon's own count of interior rings (shapely), not our metadata
    for k, (line, lake) in enumerate(zip(lake_lines.geometry, lakes.geometry)):
        merged = shapely.unary_union(line)
        parts = shapely.get_parts(shapely.polygonize(shapely.get_parts(merged)))
        assert len(parts) == shapely.get_num_interior_rings(lake), k


def test_real_lakes_widest_place_matches_the_largest_inscribed_circle(lakes, lake_lines):
    # truth: shapely's maximum inscribed circle (GEOS, an independent algorithm)
    for k, (row, lake) in enumerate(zip(lake_lines.itertuples(), lakes.geometry)):
        radius = shapely.maximum_inscribed_circle(lake, tolerance=1e-4 * np.sqrt(lake.area)).length
        assert row.width_max == pytest.approx(2.0 * radius, rel=0.01), k


def test_centerlines_cli_writes_a_layer_other_tools_read(tmp_path, lakes):
    from medialaxis.cli import main

    source = tmp_path / "lakes.gpkg"
    lakes.to_file(source, driver="GPKG")
    out = tmp_path / "lines.fgb"
    assert main(["centerlines", str(source), "-o", str(out)]) == 0
    back = gpd.read_file(out)
    assert len(back) == 30 and back.crs.to_epsg() == 3857 and {"width_min", "width_mean", "width_max"} <= set(back.columns)


def test_branch_lines_are_the_axis_to_shapely_gives(layer):
    from medialaxis.gis.features import branch_lines

    shapes = [*layer.geometry, shapely.Point(0, 0).buffer(5.0), shapely.box(0, 0, 100, 10)]
    for shape in shapes:
        ma = mx.medial_axis(shape, detour=1.0)
        lines, reference = branch_lines(ma), ma.to_shapely()
        assert lines.geom_type == "MultiLineString" and len(lines.geoms) == len(reference.geoms)
        assert lines.equals_exact(reference, 0.0)
    assert branch_lines(mx.medial_axis(shapes[-2])).is_empty  # a disc: its centre, no branch


def test_branch_chains_walk_as_the_graph_branches_do():
    from medialaxis.core.graph import branches, branches_reference
    from medialaxis.gis._kernels import branch_chains

    rng = np.random.default_rng(34)
    graphs = [np.array([[0, 1], [1, 2], [2, 0]]), np.array([[0, 0], [0, 1]]), np.empty((0, 2), np.int64)]
    graphs += [rng.integers(0, n, size=(m, 2)) for n, m in [(5, 4), (12, 15), (40, 39), (60, 90)] for _ in range(10)]
    for edges in graphs:
        n = int(edges.max()) + 2 if len(edges) else 3
        nodes, part = branch_chains(n, np.ascontiguousarray(edges, np.int64))
        chains = branches(n, edges)
        assert [list(c) for c in chains] == [list(nodes[part == k]) for k in range(len(chains))]
        assert [list(c) for c in chains] == [list(c) for c in branches_reference(n, edges)]  # the Python twin
        assert len(np.unique(part)) == len(chains)


def test_widths_and_lines_of_a_chunk_are_those_of_each_axis(layer):
    from medialaxis.gis.features import axis_widths, branch_lines, chunk_lines
    from tests.gis_reference import axis_widths_reference

    shapes = [*layer.geometry, shapely.Point(0, 0).buffer(5.0), shapely.box(0, 0, 100, 10)]
    axes = [mx.medial_axis(shape, detour=1.0) for shape in shapes]
    for ma in axes:
        assert axis_widths(ma) == axis_widths_reference(ma)
    lines = chunk_lines([None, *axes])
    assert lines[0] is None and lines[4] is None  # no axis; a disc's axis is a point, no branch
    for line, ma in zip(lines[1:], axes):
        if line is not None:
            assert line.wkb == branch_lines(ma).wkb
    assert chunk_lines([]) == [] and chunk_lines([None]) == [None]


def test_widths_sum_as_numpy_sums():
    from types import SimpleNamespace

    from medialaxis.gis._kernels import pairwise_sum
    from medialaxis.gis.features import axis_widths
    from tests.gis_reference import axis_widths_reference

    rng = np.random.default_rng(34)
    for n in [*range(0, 300, 7), 1000, 8191, 8192, 9001, 40000]:
        values = rng.random(n) * 10.0 ** rng.uniform(-6, 6, n)
        assert pairwise_sum(values, 0, n) == np.sum(values)
        m = max(n, 2)
        axis = SimpleNamespace(points=rng.random((m, 2)) * 1e5, radii=rng.random(m),
                               edges=rng.integers(0, m, (n // 2, 2)))
        assert axis_widths(axis) == axis_widths_reference(axis)
    nothing = SimpleNamespace(points=np.empty((0, 2)), radii=np.empty(0), edges=np.empty((0, 2), np.int64))
    assert np.isnan(axis_widths(nothing)).all() and np.isnan(axis_widths_reference(nothing)).all()


def test_a_series_and_a_frame_give_the_same_table(layer):
    from geopandas.testing import assert_geodataframe_equal

    frame = layer.rename_geometry("shape").assign(width_min=-1.0)  # a width column is overwritten where it is
    out = mx.centerlines(frame)
    assert list(out.columns) == ["name", "lanes", "width_min", "width_mean", "width_max", "geometry"]
    assert out.geometry.name == "geometry" and out.crs == layer.crs and (out["width_min"] > 0).all()
    series = mx.centerlines(layer.geometry)
    assert list(series.columns) == ["width_min", "width_mean", "width_max", "geometry"]
    assert_geodataframe_equal(series, out[series.columns])
    empty = mx.centerlines(layer.geometry.iloc[:0])
    assert len(empty) == 0 and list(empty.columns) == list(series.columns) and empty.crs == layer.crs
