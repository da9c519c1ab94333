"""Drawings (SVG, DXF) on the command line: single files, batch folders, compare and search."""

from __future__ import annotations

import json

import numpy as np
import pytest

import medialaxis as mx
from medialaxis.cli import main

ezdxf = pytest.importorskip("ezdxf")

SVG_HEAD = '<svg xmlns="http://www.w3.org/2000/svg" width="300" height="200">'


def _dxf_plate(path, layer_of_hole="0"):
    """A 100 x 40 plate (LWPOLYLINE) on layer CUT with a round hole of radius 8 (CIRCLE) on ``layer_of_hole``."""
    doc = ezdxf.new()
    doc.layers.add("CUT")
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (100, 0), (100, 40), (0, 40)], close=True, dxfattribs={"layer": "CUT"})
    msp.add_circle((30, 20), 8, dxfattribs={"layer": layer_of_hole})
    doc.saveas(path)
    return path


def test_compute_svg_and_dxf(tmp_path):
    svg = tmp_path / "frame.svg"
    svg.write_text(SVG_HEAD + '<rect x="10" y="10" width="100" height="60" fill="none" stroke="black" '
                   'stroke-width="6"/></svg>')
    out = tmp_path / "frame.json"
    assert main(["compute", str(svg), "-o", str(out)]) == 0
    frame = mx.load(out)
    assert frame.n_cycles == 1  # a stroked frame is a ring, not a filled square
    # half the stroke width along the sides; at a corner the disc touching both outer sides and the
    # inner corner has radius 6 sqrt(2) / (1 + sqrt(2))
    assert np.median(frame.radii) == pytest.approx(3.0, rel=1e-3)
    assert frame.radii.max() == pytest.approx(6 * np.sqrt(2) / (1 + np.sqrt(2)), rel=1e-3)
    assert main(["compute", str(svg), "--fills-only", "-o", str(tmp_path / "f.json")]) == 1  # nothing filled

    dxf = _dxf_plate(tmp_path / "plate.dxf", layer_of_hole="HOLES")
    assert main(["compute", str(dxf), "-o", str(tmp_path / "plate.json")]) == 0
    assert mx.load(tmp_path / "plate.json").n_cycles == 1
    assert main(["compute", str(dxf), "--layers", "CUT", "-o", str(tmp_path / "cut.json")]) == 0
    cut = mx.load(tmp_path / "cut.json")
    assert cut.n_cycles == 0 and cut.metadata["drawing"]["format"] == "dxf"


def test_batch_folder_of_drawings(tmp_path, capsys):
    shapes = tmp_path / "shapes"
    shapes.mkdir()
    (shapes / "bar.svg").write_text(SVG_HEAD + '<rect width="100" height="20"/></svg>')
    _dxf_plate(shapes / "plate.dxf")
    out = tmp_path / "out"
    assert main(["compute", str(shapes), "--out-dir", str(out), "--format", "json"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["bar.json", "plate.json"]
    bar = json.loads((out / "bar.json").read_text())
    assert bar["metadata"]["drawing"]["format"] == "svg"


def test_compare_and_search_drawings(tmp_path, capsys):
    a = tmp_path / "a.svg"
    a.write_text(SVG_HEAD + '<rect width="100" height="40"/><circle cx="30" cy="20" r="8" fill="none"/></svg>')
    b = _dxf_plate(tmp_path / "b.dxf")
    assert main(["compare", str(a), str(b)]) == 0
    distance = float(capsys.readouterr().out.split()[-1])
    assert distance >= 0
    assert main(["search", str(b), str(tmp_path), "--top", "2", "--jobs", "1"]) == 0
    listed = capsys.readouterr().out
    assert "a.svg" in listed and "b.dxf" in listed


def test_warnings_are_one_line_after_a_result_and_none_after_an_error(tmp_path, capsys):
    # a skipped text (a warning) then a result: one warning line
    ok = tmp_path / "ok.svg"
    ok.write_text(SVG_HEAD + '<rect width="100" height="20"/><text x="0" y="50">label</text></svg>')
    assert main(["compute", str(ok), "-o", str(tmp_path / "ok.json")]) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert len(err) == 1 and err[0].startswith("medialaxis: warning:") and "1 text" in err[0]
    # a skipped text, then an error (a hole far below the resolution of the shape): the error line alone
    bad = tmp_path / "bad.svg"
    bad.write_text(
        SVG_HEAD + '<path fill-rule="evenodd" d="M 8 8 L 56 8 L 56 30 Q 40 -4e11 32 56 C 24 50 12 44 -8e10 30 Z '
        'M 20 14 h 10 v 8 h -10 Z"/><text x="0" y="50">label</text></svg>'
    )
    assert main(["compute", str(bad), "-o", str(tmp_path / "bad.json")]) == 1
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert len(err) == 1 and err[0].startswith("medialaxis: error:") and "ring" in err[0], err
