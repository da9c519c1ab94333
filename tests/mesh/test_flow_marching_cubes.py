"""Flow skeletons of marching-cubes surfaces (voxel staircases, as CT and segmentation tools export them).

The one-ring normals of a staircase tilt by tens of degrees; the inner balls
aimed along them stopped at the next step, and the skeletons grew a spur at
every step (a rod: 10 ends, nodes 1.5 voxels off its axis). The truth here is
the analytic axis of the voxelized solid.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from scipy import ndimage
from scipy.spatial.transform import Rotation
from skimage.measure import marching_cubes

import medialaxis as mx


def _surface(volume: np.ndarray, blur: float = 0.0) -> trimesh.Trimesh:
    grey = np.pad(volume, 1).astype(np.float64)
    if blur:  # a grey scan's partial-volume edges
        grey = ndimage.gaussian_filter(grey, blur)
    vertices, faces, _, _ = marching_cubes(grey, 0.5)
    return trimesh.Trimesh(vertices - 1.0, faces)  # back to the volume's indices


def _degrees(ma: mx.MedialAxis) -> np.ndarray:
    return np.bincount(np.asarray(ma.edges).ravel(), minlength=len(ma.points))


def _turn(seed: int) -> np.ndarray:
    """A random rotation (a scanner's direction cosines), uniform over rotations."""
    return Rotation.random(random_state=seed).as_matrix()


@pytest.mark.parametrize(
    ("radius", "blur", "turn"), [(3.0, 0.0, None), (5.0, 0.0, None), (8.0, 0.0, None), (8.0, 0.7, None), (8.0, 0.0, 1), (5.0, 0.7, 2)]
)
def test_a_rod_is_one_centred_segment(radius: float, blur: float, turn: int | None) -> None:
    # the blurred rod of radius 8 had 14 ends when only binary staircases were recognized; turned
    # after meshing (a scanner's orientation), rods had 8-18 ends and sat up to 5 voxels off the axis
    size, centre = int(2 * radius) + 10, radius + 5.0
    z, y, x = np.mgrid[:80, :size, :size]
    rod = ((y - centre) ** 2 + (x - centre) ** 2 <= radius**2) & (z >= 10) & (z < 70)
    mesh = _surface(rod, blur)
    rotation = np.eye(3) if turn is None else _turn(turn)
    mesh.vertices = mesh.vertices @ rotation.T
    ma = mx.medial_axis(mesh, method="flow")
    points = ma.points @ rotation  # back in the volume's indices
    degree = _degrees(ma)
    assert ma.betti == (1, 0, 0)
    assert (degree == 1).sum() == 2 and (degree >= 3).sum() == 0
    inner = (points[:, 0] > 10 + radius) & (points[:, 0] < 70 - radius)  # away from the flat ends
    off_axis = np.hypot(points[inner, 1] - centre, points[inner, 2] - centre)
    assert inner.sum() >= 5 and off_axis.max() <= 1.0


def test_a_torus_is_one_centred_ring() -> None:
    z, y, x = np.mgrid[-24:25, -24:25, -24:25].astype(np.float64)
    major = 12.0
    torus = (np.hypot(x, y) - major) ** 2 + z**2 <= 25.0
    mesh = _surface(torus)
    mesh.apply_translation([-24.0, -24.0, -24.0])
    ma = mx.medial_axis(mesh, method="flow")
    assert ma.betti == (1, 1, 0)
    assert (_degrees(ma) != 2).sum() == 0
    to_core = np.hypot(np.hypot(ma.points[:, 1], ma.points[:, 2]) - major, ma.points[:, 0])
    assert np.percentile(to_core, 99) <= 0.03 * major


def test_what_is_a_voxel_staircase() -> None:
    from medialaxis.mesh.skeleton._flow_operators import on_voxel_grid

    z, y, x = np.mgrid[:40, :40, :40]
    ball = (x - 20) ** 2 + (y - 20) ** 2 + (z - 20) ** 2 <= 144
    grey = ndimage.gaussian_filter(ball.astype(np.float64), 1.0)
    anisotropic = marching_cubes(grey, 0.5, spacing=(0.3, 0.3, 0.6))[0]
    assert on_voxel_grid(anisotropic) and on_voxel_grid(_surface(ball).vertices)
    assert not on_voxel_grid(trimesh.creation.icosphere(4).vertices)
    assert not on_voxel_grid(trimesh.creation.box().subdivide().subdivide().vertices)  # a lattice: three grid coordinates


def test_a_turned_staircase_is_one() -> None:
    from medialaxis.mesh.skeleton._flow_operators import _snapped, grid_frames, on_voxel_grid

    z, y, x = np.mgrid[:40, :40, :40]
    ball = _surface((x - 20) ** 2 + (y - 20) ** 2 + (z - 20) ** 2 <= 144)
    turned = ball.vertices @ _turn(3).T
    assert not on_voxel_grid(turned)
    assert any(on_voxel_grid(_snapped(turned @ frame.T)) for frame in grid_frames(turned, ball.faces))
    sphere = trimesh.creation.icosphere(4)
    assert grid_frames(sphere.vertices @ _turn(4).T, sphere.faces) == []  # a smooth surface: no axis wins
    box = trimesh.creation.box().subdivide().subdivide()
    box_turned = box.vertices @ _turn(5).T
    # a lattice: its axes are found, but its vertices have three grid coordinates, not two
    assert not any(on_voxel_grid(_snapped(box_turned @ frame.T)) for frame in grid_frames(box_turned, box.faces))
