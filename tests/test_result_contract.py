"""One result contract for every method (issue 33.1): typed attributes, and save then load gives the same result.

Every method's result is saved as ``.json`` and ``.npz`` and read back:
the arrays, the metadata (as a dict, value for value), the input shape (a
planar geometry; a mesh's or an isosurface's vertices and faces) and the
unpruned axis must come back equal. Timings (wall-clock seconds) are left
out of the file unless asked for.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely

import medialaxis as mx
from medialaxis._dispatch import METHODS
from medialaxis.core.outputs import METHOD_KINDS

trimesh = pytest.importorskip("trimesh")


@pytest.fixture(scope="module")
def results():
    plate = np.zeros((20, 20, 20), bool)
    plate[4:16, 4:16, 7:13] = True
    image = np.zeros((40, 60), bool)
    image[8:32, 6:54] = True
    capsule = trimesh.creation.capsule(height=2.0, radius=0.5, count=[12, 12])
    box = trimesh.creation.box(extents=(2, 1, 0.5))
    return {
        "planar voronoi polygon": mx.medial_axis(shapely.box(0, 0, 4, 1)),
        "planar voronoi image": mx.medial_axis(image, spacing=(0.5, 0.25)),
        "mesh flow": mx.medial_axis(capsule, method="flow"),
        "mesh voronoi": mx.medial_axis(box, method="voronoi", samples=1000),
        "mesh voronoi simplified": mx.medial_axis(box, method="voronoi", samples=1000, simplify=12),
        "volume midsurface": mx.medial_axis(plate, method="midsurface", spacing=(1.0, 1.0, 0.5)),
        "volume voxels": mx.medial_axis(plate, method="voxels"),
    }


def test_every_method_is_covered(results):
    covered = {(ma.domain, ma.method) for ma in results.values()}
    assert covered == {(d, m) for d, methods in METHODS.items() for m in methods}


def test_typed_attributes_follow_what_the_method_made(results):
    for name, ma in results.items():
        assert (ma.domain, ma.method) == tuple(name.split()[:2]), name
        assert ma.kind == METHOD_KINDS[ma.domain, ma.method]
        # array inputs are in index order (an image's rows first), vector inputs in their own coordinates
        assert ma.frame == ("image" if name.endswith("image") or ma.domain == "volume" else "world"), name
    hand_made = mx.MedialAxis(np.zeros((1, 3)), np.ones(1))  # a lone 3D point: a voxel set
    assert (hand_made.domain, hand_made.method, hand_made.frame, hand_made.kind) == (None, None, "world", "voxel sets")


def test_metadata_is_read_only_and_json_like(results):
    for name, ma in results.items():
        with pytest.raises(TypeError):
            ma.metadata["method"] = "other"  # type: ignore[index]
        # what JSON holds: sequences are lists (a tuple would index one axis each in NumPy), numbers Python's
        assert all(not isinstance(v, (tuple, np.generic, np.ndarray)) for v in _values(ma.metadata)), name
        assert json.loads(json.dumps(dict(ma.metadata)))["method"] == ma.method


def _values(mapping):
    for value in mapping.values():
        if isinstance(value, dict):
            yield from _values(value)
        elif isinstance(value, list):
            yield from value
        yield value


def _same_shape(a, b) -> bool:
    if a is None or b is None:
        return a is None and b is None
    if hasattr(a, "wkt"):
        return bool(a.equals_exact(b, 0.0)) and a.geom_type == b.geom_type
    return (type(a) is type(b) and np.array_equal(np.asarray(a.vertices), np.asarray(b.vertices))
            and np.array_equal(np.asarray(a.faces), np.asarray(b.faces)))


def _assert_same(ma, back, timings: bool, where: str) -> None:
    for field in ("points", "radii", "edges", "faces"):
        assert np.array_equal(getattr(ma, field), getattr(back, field)), (where, field)
        assert getattr(ma, field).dtype == getattr(back, field).dtype, (where, field)
    assert set(ma.extras) == set(back.extras), where
    for key, value in ma.extras.items():
        assert np.array_equal(value, back.extras[key], equal_nan=value.dtype.kind == "f") and value.dtype == back.extras[key].dtype, (where, key)
    expected = dict(ma.metadata) if timings else {k: v for k, v in ma.metadata.items() if k != "timings"}
    assert dict(back.metadata) == expected, where
    assert (back.domain, back.method, back.frame, back.kind) == (ma.domain, ma.method, ma.frame, ma.kind), where
    assert _same_shape(ma.shape, back.shape), (where, type(ma.shape), type(back.shape))
    assert (ma.raw is None) == (back.raw is None), where
    if ma.raw is not None:
        _assert_same(ma.raw, back.raw, timings, where + " (raw)")


@pytest.mark.parametrize("ext", [".json", ".npz"])
def test_save_then_load_gives_the_same_result(results, tmp_path, ext):
    for name, ma in results.items():
        path = tmp_path / f"{name.replace(' ', '_')}{ext}"
        ma.save(path)
        _assert_same(ma, mx.load(path), timings=False, where=f"{name} {ext}")
        ma.save(path, timings=True)
        _assert_same(ma, mx.load(path), timings=True, where=f"{name} {ext} with timings")


def test_timings_stay_out_of_saved_files_unless_asked(results, tmp_path):
    timed = [name for name, ma in results.items() if "timings" in ma.metadata]
    assert {"mesh voronoi", "mesh flow", "volume midsurface"} <= set(timed)
    voronoi = results["mesh voronoi"].metadata["timings"]  # stages timed after the full complex was made count too
    assert voronoi["total"] >= voronoi["compact"] > 0 and voronoi["total"] >= voronoi["facets"]
    for name in timed:
        ma = results[name]
        assert all(isinstance(v, float) and v >= 0 for v in ma.metadata["timings"].values()), name
        ma.save(tmp_path / "a.json")
        assert "timings" not in json.loads((tmp_path / "a.json").read_text())["metadata"]
        ma.save(tmp_path / "b.json", timings=True)
        assert json.loads((tmp_path / "b.json").read_text())["metadata"]["timings"] == dict(ma.metadata["timings"])


def test_a_loaded_mesh_result_keeps_what_its_shape_is_used_for(results, tmp_path):
    ma = results["mesh voronoi"]
    ma.save(tmp_path / "m.npz")
    back = mx.load(tmp_path / "m.npz")
    assert isinstance(back.shape, trimesh.Trimesh) and back.shape.is_watertight
    assert back.shape.volume == pytest.approx(2 * 1 * 0.5)
    # the balls touch the loaded surface: its exact distance from each centre is the radius
    depth = back.shape.nearest.signed_distance(back.points)
    assert np.all(depth > 0) and np.abs(depth - back.radii).max() < 0.02 * 2.29


def test_files_of_the_first_format_version_still_load(results, tmp_path):
    ma = results["planar voronoi polygon"]
    ma.save(tmp_path / "v2.json")
    doc = json.loads((tmp_path / "v2.json").read_text())
    doc["version"], doc["shape"] = 1, ma.shape.wkt  # version 1 kept a planar shape as its WKT text
    doc["metadata"]["spacing"] = list(doc["metadata"].get("spacing") or ())
    (tmp_path / "v1.json").write_text(json.dumps(doc))
    back = mx.load(tmp_path / "v1.json")
    assert back.shape.equals(ma.shape) and np.array_equal(back.points, ma.points)


def test_summary_rows_follow_the_kind(results):
    pytest.importorskip("pandas")
    for name, ma in results.items():
        table = ma.summary()
        if ma.kind.endswith("curves"):
            assert table["length"].sum() == pytest.approx(sum(b.length for b in ma.branches()))
        elif ma.kind == "surfaces":
            # sheets, not triangle edges: the areas sum to the surface's, thickness is twice the radius
            tri = ma.points[ma.faces]
            area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum()
            assert table["area"].sum() == pytest.approx(area) and table["faces"].sum() == len(ma.faces), name
            assert len(table) < len(ma.faces) / 4, name
            assert table["thickness_min"].min() == pytest.approx(2 * ma.radii[np.unique(ma.faces)].min()), name
        else:
            assert table["voxels"].sum() == len(ma.points) and set(table["kind"]) <= {"surface", "boundary", "junction"}
            with pytest.raises(mx.InvalidInputError, match="for curve skeletons"):
                ma.summary(style="skan")


def test_the_mid_surface_of_a_plate_is_one_sheet_as_thick_as_the_plate(results):
    pytest.importorskip("pandas")
    table = results["volume midsurface"].summary()  # the plate is 6 voxels of 0.5 thick: 3.0
    assert len(table) == 1 and table["thickness_mean"][0] == pytest.approx(3.0, rel=0.1)
    assert table["area"][0] == pytest.approx(12 * 12, rel=0.15) and table["junction_edge_length"][0] == 0


def test_one_callback_protocol_for_every_method():
    """Every method hands its ``callback`` a ``Progress`` (method, stage, step, total, state); False cancels."""
    from medialaxis._progress import Progress

    plate = np.zeros((20, 20, 20), bool)
    plate[4:16, 4:16, 7:13] = True
    capsule = trimesh.creation.capsule(height=2.0, radius=0.5, count=[12, 12])
    box = trimesh.creation.box(extents=(2, 1, 0.5))
    calls = [
        ("voronoi", lambda cb: mx.medial_axis(shapely.box(0, 0, 4, 2), callback=cb)),
        ("voronoi", lambda cb: mx.medial_axis(box, samples=1000, simplify=12, callback=cb)),
        ("flow", lambda cb: mx.medial_axis(capsule, method="flow", callback=cb)),
        ("midsurface", lambda cb: mx.medial_axis(plate, method="midsurface", callback=cb)),
        ("voxels", lambda cb: mx.medial_axis(plate, method="voxels", callback=cb)),
    ]
    for method, call in calls:
        heard = []
        call(heard.append)
        assert heard and all(isinstance(p, Progress) and p.method == method for p in heard), method
        assert [p.step for p in heard] == list(range(len(heard))), method
        assert all(p.total == len(heard) for p in heard) or method == "flow", method  # the flow stops when done
        last = len(heard) - 1
        with pytest.raises(mx.Cancelled):
            call(lambda progress, last=last: progress.step < last)  # cancelled at the last report
    assert [p.stage for p in heard] == ["binarize", "distance", "medial voxels", "classify"]


def test_edges_mean_one_thing(results):
    """Curve pieces, and on surfaces the sides where a sheet ends or sheets meet: never a side inside a sheet."""
    for name, ma in results.items():
        if not len(ma.faces):
            assert ma.kind != "surfaces", name
            continue
        sides = np.sort(ma.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        uniq, uses = np.unique(sides, axis=0, return_counts=True)
        listed = {tuple(e) for e in np.sort(ma.edges, axis=1).tolist()}
        assert {tuple(e) for e in uniq[uses != 2].tolist()} <= listed, name
        assert not {tuple(e) for e in uniq[uses == 2].tolist()} & listed, name


def test_a_corrupt_saved_shape_is_refused(results, tmp_path):
    ma = results["mesh voronoi"]
    ma.save(tmp_path / "m.json")
    doc = json.loads((tmp_path / "m.json").read_text())
    doc["shape"]["faces"] = {"dtype": "<i8", "shape": [1, 3], "base64": "AAAAAAAAAAABAAAAAAAAAOcDAAAAAAAA"}  # 0, 1, 999
    (tmp_path / "bad.json").write_text(json.dumps(doc))
    with pytest.raises(mx.InputFileError, match="faces name no vertex"):
        mx.load(tmp_path / "bad.json")
