"""Parts narrower than lambda everywhere: each still has its point in the medial complex."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

import medialaxis as mx
from medialaxis.mesh.sample.sampling import MIN_SHELL_SAMPLES, shell_spacing


def test_a_small_box_beside_a_ball_keeps_its_point():
    # an assembly: a unit ball and a 0.05 x 0.05 x 0.1 box apart from it, both closed and outward.
    # The box is narrower than the default lambda (0.22) everywhere, so all its facets collapse; it
    # collapsed to a point that no facet or curve named, and the result had one component
    ball = trimesh.creation.icosphere(subdivisions=4, radius=1.0)
    box = trimesh.creation.box([0.05, 0.05, 0.1])
    box.apply_translation([3.0, 0.0, 0.0])
    ma = mx.medial_axis(trimesh.util.concatenate([ball, box]))
    assert ma.metadata["lam"] > 0.1
    assert ma.betti == (2, 0, 0)  # two separate solids
    at = int(np.argmin(np.linalg.norm(ma.points - [3.0, 0.0, 0.0], axis=1)))
    assert np.linalg.norm(ma.points[at] - [3.0, 0.0, 0.0]) < 0.03  # on the box's medial segment (|z| <= 0.025)
    assert abs(ma.radii[at] - 0.025) < 0.005  # its inscribed radius, half its width


@pytest.mark.parametrize("width", [0.01, 0.003])
def test_a_box_smaller_than_the_spacing_is_sampled_and_kept(width):
    # the default spacing here is about 0.02: a box of 0.01 or 0.003 got its 8 vertices and a few edge
    # points, too few to resolve it, and was lost; each piece of the surface now gets MIN_SHELL_SAMPLES
    ball = trimesh.creation.icosphere(subdivisions=4, radius=1.0)
    box = trimesh.creation.box([width, width, 2 * width])
    box.apply_translation([3.0, 0.0, 0.0])
    ma = mx.medial_axis(trimesh.util.concatenate([ball, box]))
    assert ma.betti == (2, 0, 0)
    at = int(np.argmin(np.linalg.norm(ma.points - [3.0, 0.0, 0.0], axis=1)))
    assert np.linalg.norm(ma.points[at] - [3.0, 0.0, 0.0]) < 0.6 * width
    assert abs(ma.radii[at] - 0.5 * width) < 0.1 * width


def test_shell_spacing_refines_small_pieces_only():
    ball = trimesh.creation.icosphere(subdivisions=4, radius=1.0)
    box = trimesh.creation.box([0.01, 0.01, 0.02])
    box.apply_translation([3.0, 0.0, 0.0])
    both = trimesh.util.concatenate([ball, box])
    spacing = np.full(len(both.faces), 0.03)
    out = shell_spacing(both, spacing)
    n = len(ball.faces)
    assert (out[:n] == 0.03).all()  # the ball has thousands of samples at 0.03
    # MIN_SHELL_SAMPLES on its area (a triangular lattice), or along its edges if that is coarser
    wanted = max(np.sqrt(2 / np.sqrt(3) * box.area / MIN_SHELL_SAMPLES), box.edges_unique_length.sum() / MIN_SHELL_SAMPLES)
    assert np.allclose(out[n:], wanted)
    assert (shell_spacing(ball, spacing[:n]) == spacing[:n]).all()  # one piece: as given
