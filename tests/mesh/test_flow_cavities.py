"""Flow skeletons of solids with cavities: a curve has no room for a void, so the cavities are filled."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

import medialaxis as mx
from medialaxis.datasets import capsules_mesh, segment_distance
from medialaxis.errors import MedialAxisWarning

AXIS = np.array([[[0.0, 0.0, 0.0], [3.0, 0.0, 0.0]]])


def _with_cavity(outer: trimesh.Trimesh, centre, radius: float) -> trimesh.Trimesh:
    inner = trimesh.creation.icosphere(subdivisions=2, radius=radius)
    inner.apply_translation(centre)
    inner.invert()  # a cavity's surface faces into the hollow
    return trimesh.util.concatenate([outer, inner])


def test_a_hollow_ball_is_one_point_at_its_centre():
    ball = _with_cavity(trimesh.creation.icosphere(subdivisions=4, radius=2.0), [0.0, 0.0, 0.0], 1.0)
    assert trimesh.Trimesh(ball.vertices, ball.faces).body_count == 2  # two shells, one solid
    with pytest.warns(MedialAxisWarning, match="filled 1 cavity"):
        sk = mx.medial_axis(ball, method="flow")
    assert sk.n_components == 1  # the solid is connected (two components before)
    assert np.linalg.norm(sk.points, axis=1).max() < 0.05
    assert sk.metadata["repairs"][-1] == "filled 1 cavity of the solid"
    n_outer = len(trimesh.creation.icosphere(subdivisions=4).vertices)
    corr = sk.extras["correspondence"]
    assert (corr[:n_outer] >= 0).all() and (corr[n_outer:] == -1).all()


def test_a_capsule_with_a_pore_keeps_its_axis():
    capsule = capsules_mesh(AXIS, 0.5, pitch=0.1)
    porous = _with_cavity(capsule, [1.5, 0.1, 0.0], 0.15)
    with pytest.warns(MedialAxisWarning, match="cavity"):
        sk = mx.medial_axis(porous, method="flow")
    assert sk.n_components == 1 and len(sk.endpoints) == 2 and len(sk.junctions) == 0
    assert segment_distance(sk.points, AXIS).max() < 0.05  # the capsule's own axis, as without the pore
