"""Command line and file outputs for volume results."""

import numpy as np

import medialaxis as mx
from medialaxis.cli import main


def test_cli_compute_npy_to_ply_and_json(tmp_path, flat_plate, capsys):
    src = tmp_path / "plate.npy"
    np.save(src, flat_plate)
    ply, js = tmp_path / "mid.ply", tmp_path / "mid.json"
    code = main(["compute", str(src), "-o", str(ply), "-o", str(js), "--option", "thickness=6"])
    assert code == 0
    out = capsys.readouterr().out
    assert "method=midsurface" in out and "faces=" in out
    text = ply.read_bytes()
    assert b"element face" in text and b"radius" in text
    back = mx.load(js)
    ma = mx.medial_axis(flat_plate, method="midsurface", thickness=6)
    assert np.allclose(back.points, ma.points) and np.array_equal(back.faces, ma.faces)


def test_cli_voxels_method_and_bad_input(tmp_path, capsys):
    src = tmp_path / "empty.npy"
    np.save(src, np.zeros((8, 8, 8), bool))
    assert main(["compute", str(src), "--method", "voxels", "-o", str(tmp_path / "v.npz")]) == 1
    err = capsys.readouterr().err
    assert "empty" in err and "Traceback" not in err
    assert main(["compute", str(tmp_path / "missing.nrrd"), "-o", str(tmp_path / "o.ply")]) == 1
