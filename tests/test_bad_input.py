"""Bad input gets a clear MedialAxisError naming the problem, never a deep traceback."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import medialaxis as mx
from medialaxis.planar import voronoi_medial_axis
from medialaxis.planar.reading import images


def test_empty_mask():
    with pytest.raises(mx.EmptyShapeError, match="empty"):
        mx.medial_axis(np.zeros((20, 20), bool))


def test_all_foreground_mask():
    with pytest.raises(mx.EmptyShapeError, match="all foreground"):
        mx.medial_axis(np.ones((20, 20), bool))


def test_constant_grey_image():
    with pytest.raises(mx.EmptyShapeError, match="constant"):
        mx.medial_axis(np.full((20, 20), 7.0))


def test_zero_size_image():
    with pytest.raises(mx.EmptyShapeError, match="empty"):
        mx.medial_axis(np.zeros((0, 5)))


def test_nan_in_image():
    img = np.zeros((20, 20))
    img[5:15, 5:15] = 1
    img[0, 0] = np.nan
    with pytest.raises(mx.InvalidInputError, match="NaN"):
        mx.medial_axis(img)


def test_nan_in_boundary_loop():
    loop = np.array([[0, 0], [1, 0], [np.nan, 1], [0, 1]], float)
    with pytest.raises(mx.InvalidInputError, match="row 2"):
        mx.medial_axis(loop)


def test_nan_in_polygon():
    with pytest.raises(mx.InvalidInputError, match="NaN"):
        mx.medial_axis(shapely.Polygon([(0, 0), (1, 0), (1, np.nan), (0, 1)]))


def test_degenerate_loop():
    with pytest.raises(mx.EmptyShapeError, match="3 distinct"):
        mx.medial_axis(np.array([[0.0, 0.0], [1.0, 1.0], [0.0, 0.0]]))


def test_self_intersecting_polygon_is_repaired_and_says_so():
    bowtie = shapely.Polygon([(0, 0), (4, 4), (4, 0), (0, 4)])
    assert not bowtie.is_valid
    ma = mx.medial_axis(bowtie)
    assert len(ma.metadata["repairs"]) == 1 and "Self-intersection" in ma.metadata["repairs"][0]
    assert mx.medial_axis(shapely.box(0, 0, 4, 1)).metadata["repairs"] == []
    assert ma.n_components == 2  # two triangles touching at a point


def test_zero_area_polygon():
    with pytest.raises(mx.EmptyShapeError):
        mx.medial_axis(shapely.Polygon([(0, 0), (1, 1), (2, 2)]))


def test_line_is_not_a_shape():
    with pytest.raises(mx.InvalidInputError, match="LineString"):
        mx.medial_axis(shapely.LineString([(0, 0), (1, 1)]))


def test_3d_array_to_the_planar_route():
    with pytest.raises(mx.InvalidInputError, match=r"2D image.*\(4, 5, 6\)"):
        voronoi_medial_axis(np.zeros((4, 5, 6), bool))


def test_4d_array():
    with pytest.raises(mx.InvalidInputError, match="shape"):
        mx.medial_axis(np.zeros((2, 3, 4, 5)))


def test_object_input():
    with pytest.raises(mx.InvalidInputError, match="dict"):
        mx.medial_axis({"a": 1})


def test_unknown_method_and_option():
    mask = np.zeros((20, 20), bool)
    mask[5:15, 5:15] = True
    with pytest.raises(mx.InvalidInputError, match="'nope'"):
        mx.medial_axis(mask, method="nope")
    with pytest.raises(mx.InvalidInputError, match="'colour'"):
        mx.medial_axis(mask, colour="red")


@pytest.mark.parametrize("kw", [{"lam": -1}, {"lam": np.nan}, {"tolerance": "x"}, {"detour": -0.5}, {"spacing": (1, 0)}, {"spacing": (1, 2, 3)}, {"boundary": "sobel"}, {"threshold": np.inf}])
def test_bad_parameters_name_the_value(kw):
    mask = np.zeros((20, 20), bool)
    mask[5:15, 5:15] = True
    with pytest.raises(mx.InvalidInputError) as info:
        mx.medial_axis(mask, **kw)
    assert list(kw)[0] in str(info.value)


def test_missing_file(tmp_path):
    with pytest.raises(mx.InputFileError, match="no such file"):
        mx.medial_axis(tmp_path / "nothing.png")


def test_corrupt_png(tmp_path):
    path = tmp_path / "bad.png"
    path.write_bytes(b"\x89PNG\r\n\x1a\nthis is not a png")
    with pytest.raises(mx.InputFileError, match="bad.png"):
        mx.medial_axis(path)


def test_truncated_png(tmp_path):
    from PIL import Image

    img = np.zeros((64, 64), np.uint8)
    img[10:50, 10:50] = 255
    path = tmp_path / "cut.png"
    Image.fromarray(img).save(path)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    with pytest.raises(mx.InputFileError, match="cut.png"):
        mx.medial_axis(path)


def test_corrupt_vector_files(tmp_path):
    (tmp_path / "a.svg").write_text("<svg><polygon points='0,0 1")
    (tmp_path / "b.geojson").write_text("{not json")
    (tmp_path / "c.wkt").write_text("POLYGON ((0 0, 1")
    (tmp_path / "d.geojson").write_text('{"type": "Point", "coordinates": [0, 0]}')
    for name in ("a.svg", "b.geojson", "c.wkt"):
        with pytest.raises(mx.InputFileError):
            mx.medial_axis(tmp_path / name)
    with pytest.raises(mx.EmptyShapeError):
        mx.medial_axis(tmp_path / "d.geojson")


def test_unsupported_extension(tmp_path):
    path = tmp_path / "shape.xyz"
    path.write_text("1 2 3")
    with pytest.raises(mx.UnsupportedFormatError, match="xyz"):
        mx.medial_axis(path)


def test_image_too_large_is_refused_before_decoding(tmp_path, monkeypatch):
    from PIL import Image

    path = tmp_path / "big.png"
    Image.fromarray(np.zeros((300, 400), np.uint8)).save(path)
    decoded = []
    monkeypatch.setattr(images, "max_pixels", lambda: 1000)
    original = Image.Image.load
    monkeypatch.setattr(Image.Image, "load", lambda self: decoded.append(1) or original(self))
    with pytest.raises(mx.ResourceLimitError, match="120,000 pixels"):
        mx.medial_axis(path)
    assert not decoded


def test_array_too_large_is_refused(monkeypatch):
    monkeypatch.setattr(images, "max_pixels", lambda: 100)
    with pytest.raises(mx.ResourceLimitError):
        mx.medial_axis(np.zeros((20, 20), bool))


def test_errors_share_one_hierarchy():
    for cls in (mx.InvalidInputError, mx.EmptyShapeError, mx.InputFileError, mx.UnsupportedFormatError,
                mx.ResourceLimitError, mx.MissingDependencyError, mx.ComputationError, mx.Cancelled):
        assert issubclass(cls, mx.MedialAxisError)


# ------------------------------------------------- issue 16: named failures
@pytest.mark.parametrize("make", ["box", "tetrahedron", "thin box"])
def test_flow_handles_the_smallest_closed_meshes(make):
    trimesh = pytest.importorskip("trimesh")
    mesh = {
        "box": lambda: trimesh.creation.box(),
        "tetrahedron": lambda: trimesh.creation.icosphere(0),
        "thin box": lambda: trimesh.creation.box(extents=(4, 1, 1)),
    }[make]()
    sk = mx.medial_axis(mesh, method="flow")
    assert sk.n_components == 1 and len(sk.points) >= 1
    # inside the (convex) solid, about its middle
    assert np.all(np.abs(sk.points - mesh.centroid) < 0.5 * mesh.extents)


def test_both_mesh_methods_take_the_solid_of_overlapping_shells_and_accept_disjoint_ones():
    trimesh = pytest.importorskip("trimesh")
    a, b = trimesh.creation.box(), trimesh.creation.box()
    b.apply_translation([0.5, 0.3, 0.2])
    overlapping = trimesh.util.concatenate([a, b])
    for method in ("flow", "voronoi"):
        with pytest.warns(mx.MedialAxisWarning, match="winding number is at least 1/2"):
            assert mx.medial_axis(overlapping, method=method).betti == (1, 0, 0)  # the union: one solid
    c = trimesh.creation.box()
    c.apply_translation([3.0, 0, 0])
    apart = trimesh.util.concatenate([a, c])
    assert mx.medial_axis(apart, method="flow").n_components == 2
    assert mx.medial_axis(apart, method="voronoi", samples=20_000).n_components == 2


def test_corrupt_mesh_files_name_the_defect(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box()
    box.export(tmp_path / "box.stl")
    data = (tmp_path / "box.stl").read_bytes()
    (tmp_path / "cut.stl").write_bytes(data[:300])
    (tmp_path / "tiny.stl").write_bytes(b"\x00\x01")
    box.export(tmp_path / "box.obj")
    text = (tmp_path / "box.obj").read_text()
    (tmp_path / "bad.obj").write_text(text.replace("\nf 1 ", "\nf 99 ", 1))
    with pytest.raises(mx.InputFileError, match=r"truncated or corrupt binary STL: its header announces 12 triangles \(684 bytes\) but the file has 300"):
        mx.medial_axis(tmp_path / "cut.stl")
    with pytest.raises(mx.InputFileError, match="not an STL file"):
        mx.medial_axis(tmp_path / "tiny.stl")
    with pytest.raises(mx.InputFileError, match="a face refers to a vertex that does not exist"):
        mx.medial_axis(tmp_path / "bad.obj")
    ascii_stl = tmp_path / "ascii.stl"
    box.export(ascii_stl, file_type="stl_ascii")
    assert mx.medial_axis(ascii_stl, method="flow").n_components == 1


def test_overflowing_coordinates_are_named():
    with pytest.raises(mx.InvalidInputError, match=r"coordinates up to 1e\+300 are too large"):
        mx.medial_axis(shapely.box(0, 0, 1e300, 1e300))
    trimesh = pytest.importorskip("trimesh")
    big = trimesh.creation.box()
    big.vertices *= 1e299
    with pytest.raises(mx.InvalidInputError, match="mesh vertices: coordinates up to"):
        mx.medial_axis(big, method="flow")
    with pytest.raises(mx.InvalidInputError, match="spacing"):
        mx.medial_axis(np.eye(8, dtype=bool), spacing=1e300)


def test_crossing_kernel_matches_its_reference():
    from medialaxis.mesh.solid._intersect_kernels import first_crossing, first_crossing_reference

    rng = np.random.default_rng(5)
    triangles = rng.normal(size=(400, 3, 3))
    faces = rng.integers(0, 300, size=(400, 3))  # some pairs share a vertex index: only folds count then
    pairs = rng.integers(0, 400, size=(3000, 2))
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    hits_fast = [first_crossing(triangles, faces, pairs[k : k + 1], 1e-12) for k in range(len(pairs))]
    hits_ref = [first_crossing_reference(triangles, faces, pairs[k : k + 1], 1e-12) for k in range(len(pairs))]
    assert hits_fast == hits_ref and 0 < hits_fast.count(0) < len(pairs)
    # two triangles that only touch along an edge or at a vertex do not cross
    a = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    edge_touch = np.array([[1.0, 0, 0], [0, 1, 0], [1, 1, 1]])
    vertex_touch = np.array([[0.0, 0, 0], [-1, 0, 1], [0, -1, 1]])
    through = np.array([[0.2, 0.2, -1], [0.2, 0.2, 1], [3, 3, 0]])
    tris = np.stack([a, edge_touch, vertex_touch, through])
    distinct = np.arange(12).reshape(4, 3)
    assert first_crossing(tris, distinct, np.array([[0, 1]]), 1e-12) == -1
    assert first_crossing(tris, distinct, np.array([[0, 2]]), 1e-12) == -1
    assert first_crossing(tris, distinct, np.array([[0, 3]]), 1e-12) == 0
