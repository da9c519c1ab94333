"""Outputs are checked against the kind of result before any work: the method tells its kind up front."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import medialaxis as mx
from medialaxis._dispatch import METHODS
from medialaxis.cli import main
from medialaxis.core.io import HOLDS, WRITERS, kind_refusal
from medialaxis.core.outputs import KINDS, METHOD_KINDS, result_kind

trimesh = pytest.importorskip("trimesh")


def _stripped(ma):
    """The same geometry without the metadata that names the method."""
    return mx.MedialAxis(ma.points, ma.radii, ma.edges, ma.faces)


@pytest.fixture(scope="module")
def results():
    plate = np.zeros((20, 20, 20), bool)
    plate[4:16, 4:16, 7:13] = True
    capsule = trimesh.creation.capsule(height=2.0, radius=0.5, count=[12, 12])
    return {
        ("planar", "voronoi"): mx.medial_axis(shapely.box(0, 0, 4, 1)),
        ("mesh", "flow"): mx.medial_axis(capsule, method="flow"),
        ("mesh", "voronoi"): mx.medial_axis(trimesh.creation.box(extents=(2, 1, 0.5)), method="voronoi", samples=1000),
        ("volume", "midsurface"): mx.medial_axis(plate, method="midsurface"),
        ("volume", "voxels"): mx.medial_axis(plate, method="voxels"),
    }


def test_every_method_and_every_format_has_a_kind():
    assert {(d, m) for d, methods in METHODS.items() for m in methods} == set(METHOD_KINDS)
    assert set(METHOD_KINDS.values()) == set(KINDS)
    assert set(HOLDS) == set(WRITERS)


def test_each_method_gives_the_kind_it_announces(results):
    for (domain, method), ma in results.items():
        assert ma.metadata["domain"] == domain and ma.metadata["method"] == method
        assert result_kind(ma) == METHOD_KINDS[domain, method]
        assert result_kind(_stripped(ma)) == METHOD_KINDS[domain, method], (domain, method)  # what it holds


def test_save_refuses_before_writing_anything(results, tmp_path):
    refused = {("volume", "midsurface"): [".svg", ".swc", ".geojson"], ("mesh", "voronoi"): [".swc", ".svg"],
               ("mesh", "flow"): [".svg"], ("volume", "voxels"): [".svg", ".swc"]}
    for key, suffixes in refused.items():
        for suffix in suffixes:
            with pytest.raises(mx.UnsupportedFormatError, match=METHOD_KINDS[key]):
                results[key].save(tmp_path / f"out{suffix}")
    assert not list(tmp_path.iterdir())
    results["mesh", "flow"].save(tmp_path / "flow.swc")  # curves: fine
    results["planar", "voronoi"].save(tmp_path / "plane.swc")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["flow.swc", "plane.swc"]


def test_the_refusal_names_the_format_the_kind_and_what_fits():
    text = kind_refusal("t.swc", "surfaces")
    assert text.startswith("SWC holds curve skeletons, not surfaces") and ".ply" in text and ".swc" not in text
    assert kind_refusal("t.ply", "surfaces") is None and kind_refusal("t.swc", None) is None


@pytest.fixture
def torus(tmp_path):
    path = tmp_path / "torus.ply"
    trimesh.creation.torus(1.0, 0.3, major_sections=24, minor_sections=12).export(path)
    return path


def _not_called(*args, **kwargs):
    raise AssertionError("the outputs must be refused before computing")


def test_cli_refuses_an_output_that_cannot_hold_the_methods_kind_before_computing(torus, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(mx, "medial_axis", _not_called)
    assert main(["compute", str(torus), "-o", str(tmp_path / "t.png"), "-o", str(tmp_path / "t.swc")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "t.swc" in err and "surfaces" in err and "SWC" in err, err
    assert main(["compute", str(torus), "--method", "flow", "-o", str(tmp_path / "t.svg")]) == 2
    err = capsys.readouterr().err
    assert "t.svg" in err and "space curves" in err and "SVG" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["torus.ply"]


def test_batch_formats_are_checked_for_every_input_before_any_work(torus, tmp_path, capsys, monkeypatch):
    (tmp_path / "bar.wkt").write_text("POLYGON ((0 0, 4 0, 4 1, 0 1, 0 0))")
    monkeypatch.setattr(mx, "medial_axis", _not_called)
    out = tmp_path / "out"
    assert main(["compute", str(tmp_path), "--out-dir", str(out), "--format", "json,swc"]) == 2
    err = capsys.readouterr().err
    assert "--format swc" in err and "torus.ply" in err and "surfaces" in err
    assert not out.exists() or not list(out.iterdir())


def test_a_saved_results_kind_is_checked_when_it_is_read(results, tmp_path, capsys):
    saved = tmp_path / "mid.json"
    results["volume", "midsurface"].save(saved)
    assert main(["compute", str(saved), "-o", str(tmp_path / "a.ply"), "-o", str(tmp_path / "a.swc")]) == 2  # invalid input
    assert "SWC holds curve skeletons, not surfaces" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mid.json"]  # all or none
