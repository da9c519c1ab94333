"""Saved results (.json, .npz) are accepted wherever a shape is; outputs get ordinary permissions."""

from __future__ import annotations

import contextlib
import json
import os
import stat
from pathlib import Path

import numpy as np
import pytest
import shapely

import medialaxis as mx
from medialaxis.cli import main
from medialaxis.core.io import WRITERS

DATA = Path(mx.__file__).parent / "data"
SHAPE = DATA / "kimia_class3_05.png"
OTHER = DATA / "kimia_class5_03.png"


@contextlib.contextmanager
def umask(mask: int):
    old = os.umask(mask)
    try:
        yield
    finally:
        os.umask(old)


def _mode(path: Path) -> int:
    return stat.S_IMODE(path.stat().st_mode)


@pytest.fixture(scope="module")
def axis():
    return mx.medial_axis(SHAPE)


@pytest.mark.parametrize("ext", [".json", ".npz"])
def test_medial_axis_returns_a_saved_result_as_loaded(axis, tmp_path, ext):
    path = tmp_path / f"a{ext}"
    axis.save(path)
    back = mx.medial_axis(path)
    np.testing.assert_array_equal(back.points, axis.points)
    np.testing.assert_array_equal(back.edges, axis.edges)
    assert dict(back.metadata) == dict(axis.metadata)
    np.testing.assert_array_equal(mx.medial_axis(path, lam=4.0).points, axis.prune(lam=4.0).points)
    with pytest.raises(mx.InvalidInputError, match="threshold"):
        mx.medial_axis(path, threshold=3)
    with pytest.raises(mx.InvalidInputError, match="tolerance"):
        mx.medial_axis(path, tolerance=0.1)
    with pytest.raises(mx.InvalidInputError, match="flow"):
        mx.medial_axis(path, method="flow")


@pytest.mark.parametrize("ext", [".json", ".npz"])
def test_distance_from_a_saved_axis_equals_the_distance_from_its_shape(axis, tmp_path, ext):
    path = tmp_path / f"a{ext}"
    axis.save(path)
    assert mx.shape_distance(path, SHAPE) == 0.0
    assert mx.shape_distance(str(path), OTHER) == mx.shape_distance(SHAPE, OTHER) > 0
    assert mx.shape_distance(OTHER, path) == mx.shape_distance(OTHER, SHAPE)
    mixed = mx.distance_matrix([path, OTHER, SHAPE])
    direct = mx.distance_matrix([SHAPE, OTHER, SHAPE])
    np.testing.assert_array_equal(mixed, direct)


def test_cli_compare_and_search_take_saved_results(axis, tmp_path, capsys):
    saved = tmp_path / "a.json"
    axis.save(saved)
    assert main(["compare", str(saved), str(OTHER)]) == 0
    from_saved = float(capsys.readouterr().out)
    assert main(["compare", str(SHAPE), str(OTHER)]) == 0
    assert from_saved == float(capsys.readouterr().out) > 0
    folder = tmp_path / "library"
    folder.mkdir()
    axis.save(folder / "same.npz")
    mx.medial_axis(OTHER).save(folder / "other.json")
    assert main(["search", str(saved), str(folder), "--jobs", "1"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert [Path(line.split("\t")[2]).name for line in lines] == ["same.npz", "other.json"]
    assert float(lines[0].split("\t")[1]) == 0.0


def test_cli_compute_converts_a_saved_result(axis, tmp_path, capsys):
    saved = tmp_path / "a.npz"
    axis.save(saved)
    svg = tmp_path / "a.svg"
    assert main(["compute", str(saved), "-o", str(svg), "-o", str(tmp_path / "b.json")]) == 0
    assert svg.stat().st_size > 0
    np.testing.assert_array_equal(mx.load(tmp_path / "b.json").points, axis.points)
    assert main(["compute", str(saved), "--steps", str(tmp_path / "s.png")]) == 2
    assert "saved result" in capsys.readouterr().err


def test_geojson_named_json_is_still_a_polygon(tmp_path):
    doc = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"format": "medialaxis"}, "geometry": shapely.geometry.mapping(shapely.box(0, 0, 40, 20))}]}
    path = tmp_path / "parcel.json"
    path.write_text(json.dumps(doc))
    ma = mx.medial_axis(path)
    assert len(ma.endpoints) == 4 and ma.metadata["method"] == "voronoi"


def test_corrupt_saved_results_fail_cleanly(tmp_path):
    (tmp_path / "bad.npz").write_bytes(b"PK\x03\x04 truncated")
    (tmp_path / "cut.json").write_text('{"format": "medialaxis", "points": [[0, 0], [1')
    with pytest.raises(mx.InputFileError, match="bad.npz"):
        mx.medial_axis(tmp_path / "bad.npz")
    with pytest.raises(mx.InputFileError, match="cut.json"):
        mx.medial_axis(tmp_path / "cut.json")
    with pytest.raises(mx.InputFileError):
        mx.shape_distance(tmp_path / "bad.npz", SHAPE)


@pytest.mark.parametrize("ext", sorted(WRITERS))
@pytest.mark.parametrize("mask", [0o022, 0o002, 0o077])
def test_every_format_is_written_with_the_umask_permissions(axis, tmp_path, ext, mask):
    path = tmp_path / f"a{ext}"
    if ext == ".html":  # a 3D page here (2D results have their page too: tests/test_output_frames.py)
        axis = mx.MedialAxis(np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 1]]), np.ones(3), np.array([[0, 1], [1, 2]]))
    with umask(mask):
        axis.save(path)
    assert _mode(path) == 0o666 & ~mask


def test_a_replaced_file_keeps_its_permissions(axis, tmp_path):
    path = tmp_path / "a.json"
    path.write_text("old")
    path.chmod(0o640)
    with umask(0o022):
        axis.save(path)
    assert _mode(path) == 0o640 and mx.load(path).points.shape == axis.points.shape


def test_cli_outputs_are_readable_by_others(tmp_path):
    outs = [tmp_path / "a.json", tmp_path / "a.svg", tmp_path / "a.png"]
    steps = tmp_path / "steps.png"
    with umask(0o022):
        args = ["compute", str(SHAPE), "--steps", str(steps)]
        for out in outs:
            args += ["-o", str(out)]
        assert main(args) == 0
        assert main(["compare", str(SHAPE), str(OTHER), "-o", str(tmp_path / "m.png")]) == 0
    for path in [*outs, steps, tmp_path / "m.png"]:
        assert _mode(path) == 0o644, path
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "a.png", "a.svg", "m.png", "steps.png"]


def test_unwritable_folder_is_one_clear_error(axis, tmp_path, monkeypatch):
    import tempfile

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "mkstemp", refuse)  # as a read-only folder does, even for root
    with pytest.raises(mx.InputFileError, match="cannot write in .*Permission denied"):
        axis.save(tmp_path / "a.json")
    assert main(["compute", str(SHAPE), "-o", str(tmp_path / "b.json")]) == 1
    assert list(tmp_path.iterdir()) == []
