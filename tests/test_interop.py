"""Results handed to 3D viewers: pyvista meshes and napari layer data."""

import sys

import numpy as np
import pytest
import trimesh

import medialaxis as mx
from medialaxis.datasets import t_phantom


@pytest.fixture(scope="module")
def surface():
    return mx.medial_axis(t_phantom((40, 60, 60), margin=6).volume, method="midsurface", iso=0.5)


@pytest.fixture(scope="module")
def curve():
    return mx.medial_axis(trimesh.creation.torus(2.0, 0.5), method="flow")


def test_pyvista_mesh_has_the_results_cells_and_fields(surface, curve):
    pytest.importorskip("pyvista")
    mesh = surface.to_pyvista()
    assert mesh.n_points == len(surface.points) and mesh.n_faces_strict == len(surface.faces)
    np.testing.assert_allclose(mesh.point_data["radius"], surface.radii)
    np.testing.assert_allclose(mesh.points, surface.points)
    lines = curve.to_pyvista()
    assert lines.n_points == len(curve.points) and lines.n_lines == len(curve.edges)


def test_pyvista_of_a_2d_axis_lies_in_z_0():
    pytest.importorskip("pyvista")
    image = np.zeros((40, 60), bool)
    image[10:30, 10:50] = True
    ma = mx.medial_axis(image)
    mesh = ma.to_pyvista()
    assert np.all(mesh.points[:, 2] == 0) and mesh.n_lines == len(ma.edges)


def test_without_pyvista_the_error_says_what_to_install(surface, monkeypatch):
    monkeypatch.setitem(sys.modules, "pyvista", None)
    with pytest.raises(mx.MissingDependencyError, match="pip install pyvista"):
        surface.to_pyvista()


def test_napari_layers(surface, curve):
    kinds = {kind: (data, meta) for data, meta, kind in surface.to_napari()}
    vertices, faces, values = kinds["surface"][0]
    assert vertices.shape == surface.points.shape and np.array_equal(faces, surface.faces)
    np.testing.assert_allclose(values, surface.radii)
    np.testing.assert_allclose(kinds["points"][1]["size"], 2 * surface.radii)
    paths = {kind: data for data, _, kind in curve.to_napari()}["shapes"]
    assert len(paths) == len(curve.edges) and all(p.shape == (2, 3) for p in paths)
