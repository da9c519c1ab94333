"""The solid's Betti numbers from its surface, and the warning when the medial complex's differ."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import trimesh
from skimage.measure import euler_number, label

import medialaxis as mx
import medialaxis.mesh.voronoi as voronoi
from medialaxis.mesh.solid.crossings import solid_betti


def _block_with_tunnels_and_a_cavity() -> trimesh.Trimesh:
    """A 10-cube with two crossing-free tunnels and a spherical cavity (manifold3d booleans)."""
    block = trimesh.creation.box([10.0, 10.0, 10.0])
    for x in (-2.5, 2.5):
        tunnel = trimesh.creation.cylinder(radius=1.0, height=12.0, sections=24)
        block = block.difference(tunnel.apply_translation([x, 0.0, 0.0]), engine="manifold")
    cavity = trimesh.creation.icosphere(2, radius=1.2).apply_translation([0.0, 3.0, 0.0])
    return block.difference(cavity, engine="manifold")


def _voxel_betti(mesh: trimesh.Trimesh, pitch: float) -> tuple[int, int, int]:
    """Betti numbers of the solid on a grid (trimesh's ray test): skimage's Euler number (26-connected) and labels."""
    axes = [np.arange(lo + pitch / 2, hi, pitch) for lo, hi in zip(*mesh.bounds)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    solid = np.pad(mesh.contains(grid.reshape(-1, 3)).reshape(grid.shape[:3]), 2)
    b0 = int(label(solid, connectivity=3).max())
    b2 = int(label(~solid, connectivity=1).max()) - 1
    return b0, b0 + b2 - int(euler_number(solid, connectivity=3)), b2


def test_solid_betti_matches_a_voxelization() -> None:
    mesh = _block_with_tunnels_and_a_cavity()
    assert solid_betti(mesh) == _voxel_betti(mesh, 0.4) == (1, 2, 1)


def test_two_solids_and_an_inward_shell() -> None:
    outer = trimesh.creation.icosphere(2, radius=3.0)
    hollow = trimesh.creation.icosphere(2, radius=1.0)
    hollow.invert()
    apart = trimesh.creation.torus(2.0, 0.5).apply_translation([10.0, 0.0, 0.0])
    assert solid_betti(trimesh.util.concatenate([outer, hollow, apart])) == (2, 1, 1)


def test_the_result_carries_the_solids_betti_numbers() -> None:
    mesh = _block_with_tunnels_and_a_cavity()
    with warnings.catch_warnings():
        warnings.simplefilter("error", mx.MedialAxisWarning)
        ma = mx.medial_axis(mesh, method="voronoi")
    assert ma.betti == tuple(ma.metadata["solid_betti"]) == (1, 2, 1)


def test_a_complex_whose_topology_differs_is_reported(monkeypatch: pytest.MonkeyPatch) -> None:
    # the solid said to have one handle more than the complex: what a handle finer than the sampling gives
    monkeypatch.setattr(voronoi, "solid_betti", lambda mesh: (1, 2, 0))
    with pytest.warns(mx.MedialAxisWarning, match=r"Euler characteristic 0 where the solid has -1 .*raise samples"):
        ma = mx.medial_axis(trimesh.creation.torus(3.0, 1.0), method="voronoi")
    assert ma.betti == (1, 1, 0)
