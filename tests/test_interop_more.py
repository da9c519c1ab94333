"""Results as shapely, trimesh and skimage/skan objects, checked with those libraries' own answers."""

import sys

import numpy as np
import pytest
import shapely
import trimesh
from scipy import ndimage
from skimage.draw import disk

import medialaxis as mx
from medialaxis.datasets import t_phantom


def _rectangle():
    image = np.zeros((61, 91), bool)
    image[15:46, 10:81] = True  # 31 rows: the long axis on row 30, pixel centres
    return image


def _cross():
    image = np.zeros((101, 101), bool)
    image[40:61, 5:96] = True
    image[5:96, 40:61] = True
    return image


def _ell():
    image = np.zeros((80, 80), bool)
    image[10:70, 10:25] = True
    image[55:70, 10:70] = True
    return image


def _annulus():
    image = np.zeros((101, 101), bool)
    image[disk((50, 50), 40)] = True
    image[disk((50, 50), 15)] = False
    return image


@pytest.fixture(scope="module")
def surface():
    phantom = t_phantom((40, 60, 60), margin=6)
    return phantom, mx.medial_axis(phantom.volume, method="midsurface", iso=0.5)


@pytest.fixture(scope="module")
def torus_curve():
    return mx.medial_axis(trimesh.creation.torus(2.0, 0.5), method="flow")


# ------------------------------------------------------------------ shapely
def test_to_shapely_is_the_branches_and_shapely_measures_them_as_we_do():
    ring = shapely.Point(0, 0).buffer(10, 64).difference(shapely.Point(0, 0).buffer(4, 64))
    slot = shapely.box(30, -3, 70, 3)
    ma = mx.medial_axis(shapely.MultiPolygon([ring, slot]))
    lines = ma.to_shapely()
    branches = ma.branches()
    assert lines.geom_type == "MultiLineString" and len(lines.geoms) == len(branches)
    for line, branch in zip(lines.geoms, branches):
        np.testing.assert_array_equal(np.asarray(line.coords), branch.points)  # the result's own coordinates
    assert lines.length == pytest.approx(ma.summary()["length"].sum(), rel=1e-12)
    assert shapely.MultiPolygon([ring, slot]).buffer(1e-9).contains(lines)
    # shapely closes the ring's axis around the hole: one face, on the circle of radius 7
    faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(shapely.unary_union(lines))))
    assert len(faces) == 1 and faces[0].contains(shapely.Point(0, 0))
    assert np.allclose(np.hypot(*np.asarray(faces[0].exterior.coords).T), 7.0, atol=0.05)


def test_to_shapely_of_an_image_result_is_in_row_col_order():
    ma = mx.medial_axis(_rectangle())
    lines = ma.to_shapely()
    middle = max(lines.geoms, key=lambda g: g.length)  # the junction-junction branch, 40 long
    assert middle.length == pytest.approx(40.0, rel=0.03)
    assert np.allclose(np.asarray(middle.coords)[:, 0], 30.0, atol=0.6)  # x is the row here


def test_to_shapely_refuses_3d_and_surfaces(surface, torus_curve):
    with pytest.raises(mx.InvalidInputError, match="to_trimesh"):
        surface[1].to_shapely()
    with pytest.raises(mx.InvalidInputError, match="3D"):
        torus_curve.to_shapely()


# ------------------------------------------------------------------ trimesh
def test_to_trimesh_of_a_surface_has_the_faces_area_and_radius(surface):
    _, ma = surface
    mesh = ma.to_trimesh()
    assert isinstance(mesh, trimesh.Trimesh)
    np.testing.assert_array_equal(mesh.vertices, ma.points)
    np.testing.assert_array_equal(mesh.faces, ma.faces)
    np.testing.assert_array_equal(mesh.vertex_attributes["radius"], ma.radii)
    tri = ma.points[ma.faces]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum()
    assert mesh.area == pytest.approx(area, rel=1e-12)
    # trimesh's edges of the triangles are the result's face edges
    ours = np.unique(np.sort(ma.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0)
    np.testing.assert_array_equal(np.unique(mesh.edges_unique, axis=0), ours)
    mesh.vertices[0] += 1.0  # the mesh is the caller's: the result is not touched
    assert not np.array_equal(mesh.vertices[0], ma.points[0])


def test_to_trimesh_of_a_curve_is_a_path_as_long_as_the_branches(torus_curve):
    path = torus_curve.to_trimesh()
    assert isinstance(path, trimesh.path.Path3D)
    assert len(path.entities) == len(torus_curve.branches()) == 1 and path.entities[0].closed
    assert path.length == pytest.approx(torus_curve.summary()["length"].sum(), rel=1e-9)
    assert path.length == pytest.approx(2 * np.pi * 2.0, rel=0.02)  # the core circle of the torus
    np.testing.assert_array_equal(path.vertex_attributes["radius"], torus_curve.radii)


def test_to_trimesh_of_a_planar_curve_and_of_points():
    ma = mx.medial_axis(_cross())
    path = ma.to_trimesh()
    assert isinstance(path, trimesh.path.Path2D) and len(path.entities) == len(ma.branches())
    assert path.length == pytest.approx(ma.to_shapely().length, rel=1e-9)  # trimesh and shapely agree
    balls = mx.MedialAxis(np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]]), [0.5, 0.25])
    cloud = balls.to_trimesh()
    assert isinstance(cloud, trimesh.PointCloud) and np.allclose(cloud.vertices, balls.points)
    np.testing.assert_array_equal(cloud.metadata["radius"], [0.5, 0.25])


def test_without_trimesh_the_error_says_what_to_install(torus_curve, monkeypatch):
    monkeypatch.setitem(sys.modules, "trimesh", None)
    with pytest.raises(mx.MissingDependencyError, match="pip install trimesh"):
        torus_curve.to_trimesh()


# ------------------------------------------------------------------ images
def test_to_image_refuses_inputs_without_a_grid(torus_curve):
    with pytest.raises(mx.InvalidInputError, match="pixel grid"):
        mx.medial_axis(shapely.box(0, 0, 10, 4)).to_image()
    with pytest.raises(mx.InvalidInputError, match="pixel grid"):
        torus_curve.to_image()


def test_to_image_against_skimage_distance():
    image = _rectangle()
    ma = mx.medial_axis(image)
    skeleton, distance = ma.to_image()
    assert skeleton.shape == distance.shape == image.shape and skeleton.dtype == bool
    assert not (skeleton & ~image).any() and np.all(distance[~skeleton] == 0) and np.all(distance[skeleton] > 0)
    assert skeleton[30, 25:66].all()  # the long branch on row 30, one pixel wide
    assert skeleton[29, 30:60].sum() == skeleton[31, 30:60].sum() == 0
    # the radius against scipy's Euclidean distance transform at the same pixels (to the
    # nearest background pixel centre, half a pixel beyond the boundary we measure to)
    edt = ndimage.distance_transform_edt(image)
    assert np.abs(edt[skeleton] - distance[skeleton]).max() <= 1.0
    # one pixel per point's pixel, and every drawn pixel near an axis edge
    drawn = np.argwhere(skeleton).astype(float)
    nearest = shapely.distance(shapely.points(drawn), ma.to_shapely())
    assert nearest.max() <= 1.0


def test_to_image_uses_the_spacing():
    ma = mx.medial_axis(_rectangle(), spacing=(2.0, 1.0))
    skeleton, distance = ma.to_image()
    assert skeleton.shape == (61, 91) and skeleton[30, 40:50].all()
    assert distance[30, 45] == pytest.approx(31.0, abs=1.0)  # 31 rows of 2 units: half-height 31, physical


def test_to_image_of_a_volume_midsurface(surface):
    phantom, ma = surface
    skeleton, distance = ma.to_image()
    solid = phantom.volume > 0.5
    assert skeleton.shape == solid.shape and skeleton.sum() > 1000
    assert (skeleton & solid).sum() >= 0.95 * skeleton.sum()
    edt = ndimage.distance_transform_edt(solid)
    inside = skeleton & (edt > 2)
    assert np.median(np.abs(edt[inside] - distance[inside])) <= 0.75


def test_to_image_of_medial_voxels_is_those_voxels(surface):
    phantom, _ = surface
    ma = mx.medial_axis(phantom.volume, method="voxels", iso=0.5)
    skeleton, distance = ma.to_image()
    voxels = tuple(np.rint(ma.points / np.asarray(ma.metadata["spacing"])).astype(int).T)
    assert skeleton.sum() == len(ma.points) and skeleton[voxels].all()
    np.testing.assert_array_equal(distance[voxels], ma.radii)
    cloud = ma.to_trimesh()
    assert isinstance(cloud, trimesh.PointCloud) and len(cloud.vertices) == len(ma.points)


# ------------------------------------------------------------------ skan
def _match(ours, theirs):
    """Pairs (our row, skan row): each of our branches to the skan branch whose ends are nearest."""
    ends = ["coord_src_0", "coord_src_1", "coord_dst_0", "coord_dst_1"]
    a = ours[ends].to_numpy().reshape(-1, 2, 2)
    b = theirs[ends].to_numpy().reshape(-1, 2, 2)
    cost = np.minimum(
        np.linalg.norm(a[:, None, 0] - b[None, :, 0], axis=2) + np.linalg.norm(a[:, None, 1] - b[None, :, 1], axis=2),
        np.linalg.norm(a[:, None, 0] - b[None, :, 1], axis=2) + np.linalg.norm(a[:, None, 1] - b[None, :, 0], axis=2),
    )
    from scipy.optimize import linear_sum_assignment

    rows, cols = linear_sum_assignment(cost)
    return list(zip(rows, cols)), cost[rows, cols]


SKAN_PANDAS = "ignore:The inplace keyword"  # skan 0.13's own call of pandas' rename


@pytest.mark.filterwarnings(SKAN_PANDAS)
@pytest.mark.parametrize("make", [_rectangle, _cross, _ell], ids=["rectangle", "cross", "ell"])
def test_skan_on_our_pixel_skeleton_finds_our_branches(make):
    skan = pytest.importorskip("skan")
    ma = mx.medial_axis(make())
    ours = ma.summary(style="skan")
    skeleton, distance = ma.to_image()
    theirs = skan.summarize(skan.Skeleton(distance), separator="_")
    assert list(ours.columns) == list(theirs.columns)  # skan's names, in skan's order
    assert len(ours) == len(theirs)
    assert sorted(ours["branch_type"]) == sorted(theirs["branch_type"])
    pairs, end_gaps = _match(ours, theirs)
    assert end_gaps.max() <= 4.0  # both ends within about a pixel and a half
    for i, j in pairs:
        mine, skans = ours.iloc[i], theirs.iloc[j]
        assert mine["branch_type"] == skans["branch_type"]
        assert abs(mine["branch_distance"] - skans["branch_distance"]) <= 2.0
        assert abs(mine["euclidean_distance"] - skans["euclidean_distance"]) <= 2.0
        assert abs(mine["mean_pixel_value"] - skans["mean_pixel_value"]) <= 0.5  # mean radius
    assert ours["skeleton_id"].tolist() == [0] * len(ours) and theirs["skeleton_id"].nunique() == 1


@pytest.mark.filterwarnings(SKAN_PANDAS)
def test_skan_sees_the_annulus_axis_as_one_cycle():
    skan = pytest.importorskip("skan")
    ma = mx.medial_axis(_annulus())
    ours = ma.summary(style="skan")
    theirs = skan.summarize(skan.Skeleton(ma.to_image().distance), separator="_")
    assert ours["branch_type"].tolist() == theirs["branch_type"].tolist() == [3]
    assert ours["branch_distance"].iloc[0] == pytest.approx(2 * np.pi * 27.5, rel=0.01)
    # a digital circle's 8-connected steps are longer than the circle: skan's length is a few % over
    assert 1.0 <= theirs["branch_distance"].iloc[0] / ours["branch_distance"].iloc[0] <= 1.08
    assert ours["mean_pixel_value"].iloc[0] == pytest.approx(theirs["mean_pixel_value"].iloc[0], abs=0.3)


# ------------------------------------------------------------------ summary(style=...)
def test_skan_style_is_the_same_rows_under_skans_names():
    ma = mx.medial_axis(_cross())
    ours, skan_style = ma.summary(), ma.summary(style="skan")
    assert list(ours.columns)[:3] == ["start", "end", "kind"]  # the default table is unchanged
    assert len(ours) == len(skan_style)
    np.testing.assert_array_equal(skan_style["node_id_src"], ours["start"])
    np.testing.assert_array_equal(skan_style["node_id_dst"], ours["end"])
    np.testing.assert_allclose(skan_style["branch_distance"], ours["length"])
    np.testing.assert_allclose(skan_style["euclidean_distance"], ours["euclidean"])
    np.testing.assert_allclose(skan_style["mean_pixel_value"], ours["radius_mean"])
    codes = {"endpoint-endpoint": 0, "endpoint-junction": 1, "junction-junction": 2, "cycle": 3}
    assert skan_style["branch_type"].tolist() == [codes[k] for k in ours["kind"]]
    np.testing.assert_allclose(skan_style["coord_src_1"], ours["start_1"])
    np.testing.assert_allclose(skan_style["image_coord_dst_0"], ours["end_0"])  # spacing 1
    with pytest.raises(mx.InvalidInputError, match="style must be one of 'medialaxis', 'skan', got 'skimage'"):
        ma.summary(style="skimage")


def test_skan_style_numbers_components_and_has_no_pixel_coordinates_without_a_grid():
    two = shapely.MultiPolygon([shapely.box(0, 0, 40, 10), shapely.box(0, 50, 10, 90)])
    table = mx.medial_axis(two).summary(style="skan")
    assert set(table["skeleton_id"]) == {0, 1}
    assert not [c for c in table.columns if c.startswith("image_coord")]
    assert list(table.columns) == ["skeleton_id", "node_id_src", "node_id_dst", "branch_distance", "branch_type",
                                   "mean_pixel_value", "stdev_pixel_value", "coord_src_0", "coord_src_1",
                                   "coord_dst_0", "coord_dst_1", "euclidean_distance"]
    assert (table["stdev_pixel_value"] >= 0).all()
