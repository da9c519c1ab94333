"""A volume of rods and tubes has no mid-surface: the error names the route that gives their curve skeleton."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from skimage.measure import marching_cubes

import medialaxis as mx
from medialaxis.cli import main


def _rod(radius: float) -> np.ndarray:
    """A solid rod along the last axis, ``2 * radius`` voxels across, with flat ends."""
    vol = np.zeros((40, 40, 70), bool)
    rows, cols = np.mgrid[:40, :40]
    vol[(rows - 19.5) ** 2 + (cols - 19.5) ** 2 < radius**2, 8:62] = True
    return vol


@pytest.mark.parametrize("radius", [3, 5, 8])
def test_a_rod_is_refused_with_the_route_that_works(radius: float) -> None:
    with pytest.raises(mx.EmptyShapeError, match=r"marching_cubes\(volume, level\).*method='flow'"):
        mx.medial_axis(_rod(radius))


def test_the_route_the_error_names_gives_the_rods_axis() -> None:
    verts, faces = marching_cubes(_rod(5).astype(np.float32), 0.5)[:2]  # as the error says
    ma = mx.medial_axis(trimesh.Trimesh(verts, faces), method="flow")
    assert len(ma.endpoints) == 2 and ma.n_cycles == 0
    assert np.abs(ma.points[:, :2] - 19.5).max() <= 1.0  # on the rod's axis


def test_cli_says_it_in_one_line(tmp_path, capsys) -> None:
    src = tmp_path / "rod.npy"
    np.save(src, _rod(5))
    assert main(["compute", str(src), "-o", str(tmp_path / "mid.ply")]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "method='flow'" in err[0]
    assert not (tmp_path / "mid.ply").exists()
