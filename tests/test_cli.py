"""The command line: round trips of every output format, exit codes, safety."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import medialaxis as mx
from medialaxis.cli import main

DATA = Path(mx.__file__).parent / "data"


@pytest.fixture
def png(tmp_path):
    img = np.zeros((60, 100), np.uint8)
    img[10:50, 10:90] = 255
    path = tmp_path / "rect.png"
    Image.fromarray(img).save(path)
    return path


def test_help_and_version(capsys):
    assert main(["--help"]) == 0
    assert "compute" in capsys.readouterr().out
    assert main(["--version"]) == 0
    assert mx.__version__ in capsys.readouterr().out
    assert main(["compute", "--help"]) == 0
    out = capsys.readouterr().out
    assert "--lam" in out and "default" in out


def test_no_command_is_a_usage_error(capsys):
    assert main([]) == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_debug_shows_the_traceback(png):
    with pytest.raises(mx.InvalidInputError):
        main(["--debug", "compute", str(png), "--lam", "-3"])


def test_outputs_are_checked_before_any_work_and_all_or_none_appear(png, tmp_path, capsys, monkeypatch):
    ok, bad = tmp_path / "ok.json", tmp_path / "nodir" / "x.json"
    calls = []
    monkeypatch.setattr(mx, "medial_axis", lambda *a, **k: calls.append(a))  # must not be reached
    assert main(["compute", str(png), "-o", str(ok), "-o", str(bad)]) == 1
    assert calls == [] and not ok.exists()
    monkeypatch.undo()
    # A writer that fails after others have written: none of the outputs is left.
    from medialaxis.core import io

    def broken(ma, path):
        raise mx.InputFileError("disk full")

    monkeypatch.setitem(io.WRITERS, ".svg", broken)
    assert main(["compute", str(png), "-o", str(ok), "-o", str(tmp_path / "b.npz"), "-o", str(tmp_path / "c.svg")]) == 1
    assert "disk full" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rect.png"]


def test_interrupt_leaves_nothing_and_exits_130(png, tmp_path, capsys, monkeypatch):
    from medialaxis.core import io

    def interrupted(ma, path):
        raise KeyboardInterrupt

    monkeypatch.setitem(io.WRITERS, ".npz", interrupted)
    assert main(["compute", str(png), "-o", str(tmp_path / "a.json"), "-o", str(tmp_path / "b.npz")]) == 130
    assert capsys.readouterr().err == "medialaxis: interrupted\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rect.png"]


def test_sigint_during_start_up_is_one_line(png, tmp_path):
    """Ctrl-C at any moment of a run, start-up included: exit 130 (or 0 if done), never a traceback.

    The child says "ready" once it has imported the console script's entry
    module, as the installed ``medialaxis`` script does first (the
    interpreter's own start-up before that is Python's), then runs it; the
    Ctrl-C comes from 0 to 1 s later: during the imports of NumPy, SciPy and
    the rest (NumPy turns an interrupted import into an ImportError), the
    work, or after it.
    """
    import signal
    import time

    code = "import sys; from medialaxis._entry import run; print('ready', flush=True); sys.exit(run())"
    for delay in (0.0, 0.002, 0.005, 0.01, 0.02, 0.03, 0.05, 0.08, 0.1, 0.15, 0.2, 0.3, 0.5, 0.7, 1.0):
        proc = subprocess.Popen([sys.executable, "-c", code, "compute", str(png), "-o", str(tmp_path / "a.json")],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        assert proc.stdout.readline() == "ready\n"
        time.sleep(delay)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=120)
        assert "Traceback" not in err, (delay, err)
        assert proc.returncode in (0, 130), (delay, proc.returncode, err)
        if proc.returncode == 130:
            assert err == "medialaxis: interrupted\n"


@pytest.mark.parametrize("ext", [".json", ".npz", ".svg", ".png", ".graphml", ".geojson", ".ply", ".obj"])
def test_compute_writes_every_format(png, tmp_path, ext, capsys):
    out = tmp_path / f"axis{ext}"
    assert main(["compute", str(png), "-o", str(out)]) == 0
    assert out.is_file() and out.stat().st_size > 0
    assert "endpoints=4" in capsys.readouterr().out
    if ext in (".json", ".npz"):
        ma = mx.load(out)
        ref = mx.medial_axis(png)
        np.testing.assert_array_equal(ma.points, ref.points)
        np.testing.assert_array_equal(ma.edges, ref.edges)
        assert ma.metadata["lam"] == ref.metadata["lam"]
    if ext == ".geojson":
        doc = json.loads(out.read_text())
        kinds = {f["properties"]["kind"] for f in doc["features"]}
        assert {"branch", "junction", "endpoint"} <= kinds
    if ext == ".graphml":
        import networkx as nx

        g = nx.read_graphml(out)
        assert g.number_of_nodes() == len(mx.medial_axis(png).points)
    if ext == ".ply":
        import trimesh

        loaded = trimesh.load(out, process=False)
        assert len(loaded.vertices) == len(mx.medial_axis(png).points)
    if ext == ".svg":
        text = out.read_text()
        assert text.startswith("<svg") and "polyline" in text
    leftovers = [p for p in tmp_path.iterdir() if p.name.startswith(".")]
    assert not leftovers  # no temporary file left behind


def test_steps_figure(png, tmp_path):
    steps = tmp_path / "steps.png"
    assert main(["compute", str(png), "--steps", str(steps)]) == 0
    assert Image.open(steps).size[0] > 1000


@pytest.mark.parametrize("name", ["bracket_two_holes.wkt", "kimia_class1_01.png"])
def test_vector_and_bundled_inputs(name, tmp_path):
    out = tmp_path / "a.json"
    assert main(["compute", str(DATA / name), "-o", str(out), "--lam", "1.5", "--option", "detour=0.3"]) == 0
    ma = mx.load(out)
    assert ma.metadata["lam"] == 1.5 and ma.metadata["detour"] == 0.3


def test_never_overwrites_its_input(png, capsys):
    before = png.read_bytes()
    assert main(["compute", str(png), "-o", str(png)]) == 2
    err = capsys.readouterr().err
    assert "overwrite" in err and len(err.strip().splitlines()) == 1
    assert png.read_bytes() == before


@pytest.mark.parametrize(
    "args, code, words",
    [
        (["compute", "missing.png"], 1, "no such file"),
        (["compute", "{png}", "-o", "x.docx"], 2, "unsupported output format"),
        (["compute", "{png}", "--lam", "-3"], 1, "lam"),
        (["compute", "{png}", "--lam", "abc"], 2, "invalid float"),
        (["compute", "{png}", "--option", "novalue"], 2, "KEY=VALUE"),
        (["compute", "{png}", "--option", "colour=1"], 1, "colour"),
        (["compute", "{png}", "--method", "flux"], 2, "flux"),
        (["compute", "{png}", "--steps", "s.txt"], 2, "--steps"),
        (["compute", "{png}", "-o", "nodir/a.json"], 1, "does not exist"),
        (["frobnicate"], 2, "invalid choice"),
        (["compute"], 2, "required: input"),
        ([], 2, "a command is required"),
    ],
)
def test_errors_exit_codes_one_line_no_traceback(png, tmp_path, capsys, args, code, words):
    args = [a.replace("{png}", str(png)) for a in args]
    args = [str(tmp_path / a) if a in ("x.docx", "s.txt", "nodir/a.json") else a for a in args]
    assert main(args) == code
    captured = capsys.readouterr()
    assert words in captured.err
    assert "Traceback" not in captured.err
    assert len(captured.err.strip().splitlines()) == 1
    assert captured.out == ""  # failed before any work


def test_empty_image_fails_cleanly(tmp_path, capsys):
    path = tmp_path / "black.png"
    Image.fromarray(np.zeros((20, 20), np.uint8)).save(path)
    assert main(["compute", str(path)]) == 1
    assert "constant" in capsys.readouterr().err


def test_console_script_runs_as_module(png):
    proc = subprocess.run([sys.executable, "-m", "medialaxis", "compute", str(png)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "endpoints=4" in proc.stdout


def test_demo_writes_results_and_plots(demo_run):
    code, lines, folder = demo_run  # main(["demo", folder]), run once for the tests of its cases too (conftest.py)
    assert code == 0
    out = "\n".join(lines)
    assert "kimia_class1_01" in out and "IoU" in out
    files = {p.name for p in folder.iterdir()}
    assert {"kimia_class1_01.json", "kimia_class1_01.png", "kimia_class1_01.svg", "kimia_class1_01_steps.png"} <= files
    assert "bracket_two_holes.json" in files


def test_foreground_option(tmp_path, capsys):
    img = np.full((60, 100), 235, np.uint8)
    img[10:50, 10:90] = 25  # a dark rectangle on light paper
    path = tmp_path / "dark.png"
    Image.fromarray(img).save(path)
    out = tmp_path / "a.json"
    assert main(["compute", str(path), "-o", str(out)]) == 0
    assert mx.load(out).metadata["foreground"] == "dark"
    assert "endpoints=4 junctions=2" in capsys.readouterr().out
    assert main(["compute", str(path), "--foreground", "bright", "-o", str(out)]) == 0
    assert mx.load(out).metadata["foreground"] == "bright"
    assert main(["compute", str(path), "--foreground", "black"]) == 2
    err = capsys.readouterr().err
    assert "--foreground" in err and "black" in err


def test_warmup_runs_the_domains_asked_and_refuses_others(capsys):
    from medialaxis.cli import main

    assert main(["warmup", "--domains", "planar"]) == 0
    assert capsys.readouterr().out.startswith("planar: compiled in")
    assert main(["warmup", "--domains", "planar,cad"]) == 2
    assert "--domains takes planar, mesh, volume" in capsys.readouterr().err
