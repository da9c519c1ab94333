"""Two slits of air meeting tip to tip at a point: the medial axis has the open interior's handle there.

The solid is a wall (a box, top face ``z = 0``) and a knob on it whose
bottom is the surface ``z = a |y| - |x|`` over ``[-1, 1]^2`` (top ``z = 1``):
the knob sinks into the wall where ``|x| > a |y|`` and stands above it
elsewhere, so the two overlap (the input's shells overlap: the route takes
the solid where the winding number is at least 1/2). Under the knob, in the
plane ``x = 0``, the air is the two wedges ``0 < z < a |y|``, one on each
side of ``y = 0``, meeting at the origin only; for ``x != 0`` the air lies
at ``|y| > |x| / a`` only. So the closed solid is a ball (the knob is held
by one connected contact, two cones touching at the origin): Betti numbers
(1, 0, 0). Its open interior leaves the origin out: the air under the knob
runs from ``y = -1`` to ``y = 1`` through the origin, and a loop around the
knob's contact near the origin cannot be shrunk: (1, 1, 0), the homotopy
type the medial axis has (Lieutier 2004).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")

import medialaxis as mx  # noqa: E402
from medialaxis.mesh.solid.crossings import solid_betti  # noqa: E402
from medialaxis.mesh.solid.pinches import carve_pinches, pinch_points  # noqa: E402


def _knob(a: float) -> trimesh.Trimesh:
    """The knob ``a |y| - |x| <= z <= 1`` over ``[-1, 1]^2``: planar on each quadrant, so a 3 x 3 grid is exact."""
    xs = np.array([-1.0, 0.0, 1.0])
    x, y = np.meshgrid(xs, xs, indexing="ij")
    bottom = np.c_[x.ravel(), y.ravel(), (a * np.abs(y) - np.abs(x)).ravel()]
    top = np.c_[x.ravel(), y.ravel(), np.ones(9)]
    idx = np.arange(9).reshape(3, 3)
    faces = []
    for i in range(2):
        for j in range(2):
            p, q, r, s = idx[i, j], idx[i + 1, j], idx[i + 1, j + 1], idx[i, j + 1]
            faces += [[p, s, r], [p, r, q], [p + 9, q + 9, r + 9], [p + 9, r + 9, s + 9]]
    ring = [0, 3, 6, 7, 8, 5, 2, 1]  # the border of the grid, around
    for k in range(8):
        p, q = ring[k], ring[(k + 1) % 8]
        faces += [[p, q, q + 9], [p, q + 9, p + 9]]
    knob = trimesh.Trimesh(np.r_[bottom, top], np.array(faces), process=False)
    if knob.volume < 0:
        knob.invert()
    return knob


def _input(a: float) -> trimesh.Trimesh:
    wall = trimesh.creation.box(bounds=[[-2.0, -2.0, -2.0], [2.0, 2.0, 0.0]])
    return trimesh.util.concatenate([wall, _knob(a)])


def test_knob_is_closed_and_exact():
    knob = _knob(0.5)
    assert knob.is_watertight and knob.is_winding_consistent
    assert knob.volume == pytest.approx(6.0 - 2.0 * 0.5, rel=1e-12)  # the integral of 1 - (a |y| - |x|) over [-1, 1]^2


@pytest.mark.parametrize("a", [0.5, 0.2])
def test_default_call_has_the_interior_handle(a):
    """The default call gives the interior's (1, 1, 0), where sampling the closed solid gives its (1, 0, 0)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ma = mx.medial_axis(_input(a), method="voronoi")
    assert ma.betti == (1, 1, 0)
    assert ma.metadata["defects"]["pinches_opened"] == 1


def test_carved_solid_has_the_interior_topology():
    """The cut solid pinches at the origin (two vertex ids); with the ball out, the closed solid is a solid torus."""
    from medialaxis.mesh.solid.arrangement import solid_surface

    both = _input(0.5)
    cut = solid_surface(both.vertices, both.faces)
    solid = trimesh.Trimesh(cut.vertices, cut.faces, process=False)
    assert pinch_points(solid.vertices).tolist() == [[0.0, 0.0, 0.0]]
    assert solid_betti(solid) == (1, 0, 0)
    carved, n = carve_pinches(solid)
    assert n == 1 and carved.is_watertight
    assert solid_betti(carved) == (1, 1, 0)
    assert not len(pinch_points(carved.vertices))


def test_solid_pinch_parts_apart():
    """Two cubes sharing only a corner: one closed solid, two open ones; the ball parts them."""
    from medialaxis.mesh.solid.arrangement import solid_surface

    boxes = [trimesh.creation.box(bounds=b) for b in ([[0, 0, 0], [1, 1, 1]], [[1, 1, 1], [2, 2, 2]])]
    both = trimesh.util.concatenate(boxes)
    cut = solid_surface(both.vertices, both.faces)
    solid = trimesh.Trimesh(cut.vertices, cut.faces, process=False)
    carved, n = carve_pinches(solid)
    assert n == 1
    assert solid_betti(carved) == (2, 0, 0)
    assert 1.99 < carved.volume < 2.0  # an eighth of a small ball out of each cube
