"""Meshes whose own faces bound no closed surface: the solid contoured from the fast winding number.

Truths: the exact winding number (a sum of solid angles, a formula of its own),
the analytic sphere and box, the mesh's Euler characteristic.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import medialaxis as mx

trimesh = pytest.importorskip("trimesh")

from medialaxis.mesh.solid._fast_winding_kernels import WindingTree  # noqa: E402
from medialaxis.mesh.solid._winding_kernels import winding_numbers_reference  # noqa: E402
from medialaxis.mesh.solid.inputs import load_mesh  # noqa: E402


def _soup(mesh, shrink: float = 0.02):
    """Each face on vertices of its own, shrunk toward its centroid: slits between all faces, as an STL soup."""
    t = mesh.triangles
    t = t + shrink * (t.mean(axis=1, keepdims=True) - t)
    return trimesh.Trimesh(t.reshape(-1, 3), np.arange(3 * len(t)).reshape(-1, 3), process=False)


def test_fast_winding_numbers_agree_with_the_exact_sum():
    torus = trimesh.creation.torus(3, 1, major_sections=48, minor_sections=24)
    points = np.random.default_rng(0).uniform(-5, 5, (1000, 3))
    exact = winding_numbers_reference(points, torus.triangles)
    tree = WindingTree(torus.triangles)
    assert np.allclose(tree(points, beta=1e9), exact, atol=1e-10)  # every cluster opened: the exact sum
    fast = tree(points)
    assert np.abs(fast - exact).max() < 0.1
    assert np.array_equal(fast >= 0.5, exact >= 0.5)
    assert np.array_equal(fast >= 0.5, torus.contains(points))


def test_a_triangle_soup_gets_its_solid_contoured(monkeypatch):
    sphere = trimesh.creation.icosphere(3)
    soup = _soup(sphere)
    with pytest.warns(mx.MedialAxisWarning, match="triangle soup.*contoured from its winding number"):
        loaded = load_mesh(soup)
    solid = loaded.mesh
    assert solid.is_watertight and solid.euler_number == 2
    assert solid.volume == pytest.approx(sphere.volume, rel=0.02)
    assert loaded.found["contoured"] == 1
    # through the whole route on a coarser grid than the default 128 cells (time: the contour's vertices)
    monkeypatch.setattr("medialaxis.mesh.solid.contour.CELLS", 48)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mx.MedialAxisWarning)
        ma = mx.medial_axis(soup, samples=6000)
    assert ma.betti == (1, 0, 0)
    assert ma.radii.max() == pytest.approx(1.0, abs=2 * 2.0 / 48)  # the ball's centre, within two cells


def test_a_fin_on_an_edge_is_no_part_of_the_solid():
    # a box with a triangle hanging from one of its edges: an edge of three faces that do not pair up
    box = trimesh.creation.box()
    a, b = box.vertices[box.edges_unique[0]]
    tip = (a + b) / 2 + 2 * ((a + b) / 2 - box.centroid)
    fin = trimesh.Trimesh(np.vstack([box.vertices, tip]),
                          np.vstack([box.faces, [[*box.edges_unique[0], len(box.vertices)]]]), process=False)
    with pytest.warns(mx.MedialAxisWarning, match="do not pair up.*contoured"):
        solid = load_mesh(fin).mesh
    assert solid.volume == pytest.approx(1.0, rel=0.03)
    assert solid.euler_number == 2


def test_an_open_sheet_is_still_refused():
    plane = trimesh.creation.box(extents=(2, 2, 0.5))
    sheet = trimesh.Trimesh(plane.vertices, plane.faces[plane.face_normals[:, 2] > 0.5], process=False)  # the top only
    soup = _soup(trimesh.Trimesh(*trimesh.remesh.subdivide(sheet.vertices, sheet.faces)))
    with pytest.raises(mx.InvalidInputError, match="bounds no solid"):
        load_mesh(soup)
