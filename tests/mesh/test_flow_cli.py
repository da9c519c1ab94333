"""``medialaxis compute MESH --method flow --frames DIR`` and the demo case."""

from __future__ import annotations

import json

import numpy as np
import pytest
import trimesh

from medialaxis import _dispatch
from medialaxis.cli import main
from medialaxis.cli.demo import DEMO_CASES, tripod_flow_case
from medialaxis.datasets import capsules_mesh


@pytest.fixture(scope="module")
def capsule_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("mesh") / "capsule.ply"
    capsules_mesh([[[0, 0, 0], [3, 0, 0]]], 0.5, pitch=0.12).export(path)
    return path


def test_frames_are_written_for_every_step(capsule_file, tmp_path, capsys):
    frames = tmp_path / "frames"
    out = tmp_path / "skeleton.json"
    assert main(["compute", str(capsule_file), "--method", "flow", "--frames", str(frames), "-o", str(out)]) == 0
    steps = json.loads(out.read_text())["metadata"]["steps"]
    plys = sorted(frames.glob("step_*.ply"))
    assert len(plys) == steps >= 1
    last = trimesh.load(plys[-1], process=False)
    colours = np.asarray(last.visual.vertex_colors)[:, :3]
    assert (colours == [220, 40, 40]).all()  # every vertex frozen at the end
    assert "plotly" in (frames / "flow.html").read_text()
    assert "endpoints=2" in capsys.readouterr().out


def test_frames_need_the_flow_method(capsule_file, tmp_path, capsys):
    assert main(["compute", str(capsule_file), "--frames", str(tmp_path / "f"), "-o", str(tmp_path / "a.json")]) == 2
    assert "--frames" in capsys.readouterr().err


def test_options_reach_the_flow(capsule_file, tmp_path):
    out = tmp_path / "sk.json"
    code = main(["compute", str(capsule_file), "--method", "flow", "--option", "dt=0.5", "--option", "max_steps=2", "-o", str(out)])
    meta = json.loads(out.read_text())["metadata"]
    assert code == 0 and meta["dt"] == 0.5 and meta["steps"] <= 2


def test_flow_is_registered():
    assert _dispatch.METHODS["mesh"]["flow"] == "medialaxis.mesh.flow:flow_skeleton"


def test_demo_case(demo_run):
    # the line and files of this case in the run of ``medialaxis demo`` (conftest.py), not computed again
    assert ("tripod_flow", tripod_flow_case) in DEMO_CASES
    _, lines, folder = demo_run
    (line,) = [line for line in lines if line.startswith("tripod (flow):")]
    assert "3 endpoints, 1 junctions" in line
    for name in ("tripod.ply", "tripod_flow.json", "tripod_flow.ply", "tripod_bent.ply"):
        assert (folder / name).is_file()
