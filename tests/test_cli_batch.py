"""``medialaxis compute`` over many inputs: files, globs and folders, one output per input and format."""

import json
import os

import numpy as np
import pytest
from PIL import Image

from medialaxis.cli import main


def _png(path, rows=(10, 30), cols=(10, 50)):
    image = np.zeros((40, 60), np.uint8)
    image[rows[0]:rows[1], cols[0]:cols[1]] = 255
    Image.fromarray(image).save(path)
    return path


@pytest.fixture()
def folder(tmp_path):
    shapes = tmp_path / "shapes"
    shapes.mkdir()
    _png(shapes / "a.png")
    _png(shapes / "b.png", rows=(5, 35))
    (shapes / "broken.png").write_bytes(b"\x89PNG\r\n\x1a\n not an image")
    (shapes / "notes.txt").write_text("not a shape")
    return shapes


def test_a_folder_writes_one_output_per_input_and_format_and_reports_failures(folder, tmp_path, capsys):
    out = tmp_path / "out"
    code = main(["compute", str(folder), "--out-dir", str(out), "--format", "json,svg"])
    captured = capsys.readouterr()
    assert code == 1  # one input failed, at the end
    assert sorted(os.listdir(out)) == ["a.json", "a.svg", "b.json", "b.svg"]
    errors = [line for line in captured.err.splitlines() if line]
    assert len(errors) == 2 and "broken.png" in errors[0] and errors[1].endswith("1 of 3 inputs failed")
    assert "notes.txt" not in captured.out + captured.err
    assert json.loads((out / "a.json").read_text())["metadata"]["method"]


def test_a_quoted_glob_and_several_files(folder, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["compute", str(folder / "[ab].png"), "--out-dir", str(out)]) == 0
    assert sorted(os.listdir(out)) == ["a.json", "b.json"]
    other = tmp_path / "other"
    other.mkdir()
    _png(other / "a.png", cols=(5, 55))
    out2 = tmp_path / "out2"
    assert main(["compute", str(folder / "a.png"), str(other / "a.png"), str(folder / "b.png"),
                 "--out-dir", str(out2), "--format", "geojson"]) == 0
    assert sorted(os.listdir(out2)) == ["a_1.geojson", "a_2.geojson", "b.geojson"]


def test_usage_errors_exit_2_before_any_work(folder, tmp_path, capsys):
    out = tmp_path / "out"
    a, b = str(folder / "a.png"), str(folder / "b.png")
    assert main(["compute", a, b, "-o", str(tmp_path / "x.json")]) == 2
    assert main(["compute", a, b]) == 2  # no --out-dir
    assert main(["compute", a, b, "--out-dir", str(out), "--format", "json,xyz"]) == 2
    assert main(["compute", a, b, "--out-dir", str(out), "--steps", str(tmp_path / "s.png")]) == 2
    assert not out.exists() or not os.listdir(out)
    lines = [line for line in capsys.readouterr().err.splitlines() if line]
    assert len(lines) == 4 and all(line.startswith("medialaxis: error:") for line in lines)


def test_one_input_with_o_still_works(folder, tmp_path):
    target = tmp_path / "one.json"
    assert main(["compute", str(folder / "a.png"), "-o", str(target)]) == 0
    assert target.is_file()


def test_a_folder_of_tiff_slices_is_one_volume(tmp_path, capsys):
    tifffile = pytest.importorskip("tifffile")
    stack = tmp_path / "stack"
    stack.mkdir()
    volume = np.zeros((20, 30, 30), np.uint8)
    volume[7:13, 4:26, 4:26] = 255
    for k, page in enumerate(volume):
        tifffile.imwrite(stack / f"slice_{k:03d}.tif", page)
    out = tmp_path / "out"
    assert main(["compute", str(stack), "--method", "voxels", "--out-dir", str(out)]) == 0
    assert os.listdir(out) == ["stack.json"]


def test_first_class_options_reach_the_methods(tmp_path, capsys):
    from medialaxis.datasets import t_phantom

    ph = t_phantom((40, 60, 60), thickness=6, margin=6)
    raw = tmp_path / "part.raw"
    (ph.volume > 0.5).astype(np.uint16).tofile(raw)
    out = tmp_path / "mid.json"
    assert main(["compute", str(raw), "--raw-shape", "40", "60", "60", "--raw-dtype", "uint16", "--threshold", "0.5",
                 "--thickness", "2", "20", "-o", str(out)]) == 0
    assert json.loads(out.read_text())["metadata"]["thickness_range"] == [2.0, 20.0]
    assert main(["compute", str(raw), "--raw-shape", "40", "60", "60", "--raw-dtype", "uint16",
                 "--thickness", "1", "2", "3"]) == 2
    box = tmp_path / "box.off"
    import trimesh

    trimesh.creation.box().export(box)
    simple = tmp_path / "box.json"
    # --samples 1000 (the fewest the method takes): the same Voronoi and Q-MAT steps, 4 times faster than the
    # default; the medial mesh then has 21 spheres, so 10 asked tell --simplify was applied
    assert main(["compute", str(box), "--samples", "1000", "--simplify", "10", "-o", str(simple)]) == 0
    assert len(json.loads(simple.read_text())["points"]) <= 10
    assert main(["compute", str(box), "--samples", "1000", "--simplify-error", "0.05", "-o", str(simple)]) == 0
    meta = json.loads(simple.read_text())["metadata"]
    assert meta["target_met"] and meta["hausdorff"] <= 0.05 * meta["diagonal"]
    capsys.readouterr()
    assert main(["compute", str(box), "--simplify", "5", "--simplify-error", "0.05", "-o", str(simple)]) == 1
    assert "not both" in capsys.readouterr().err
    from medialaxis.cli import build_parser
    from medialaxis.cli.compute import compute_options as _options

    args = build_parser().parse_args(["compute", str(box), "--repair", "--thickness", "6"])
    assert _options(args)[0] == {"repair": True, "thickness": 6.0}
    capsys.readouterr()
    assert main(["compute", "--help"]) == 0
    help_text = capsys.readouterr().out
    assert "(default: None)" not in help_text and "--raw-shape Z Y X" in help_text
    for command in ("compare", "search", "centerlines"):
        assert main([command, "--help"]) == 0
        text = capsys.readouterr().out
        assert "(default: None)" not in text and ") (default:" not in text, command
