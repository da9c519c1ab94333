"""prune(lam=) of flow skeletons: terminal branches narrower than lambda go, as thin tubes leave the lambda-medial axis.

Truth: the tubes' radii, set when the solid is built (a tube of radius r has contact sets 2 r wide).
"""

from __future__ import annotations

import numpy as np
import pytest

import medialaxis as mx

trimesh = pytest.importorskip("trimesh")

TRUNK, ARM = 0.6, 0.2  # radii of the thick trunk and the thin arm


@pytest.fixture(scope="module")
def t_skeleton():
    """A trunk along x (radius 0.6, axis 4 long) with a thin arm along y from its middle (radius 0.2), united."""
    pytest.importorskip("manifold3d")
    trunk = trimesh.creation.capsule(height=4.0, radius=TRUNK, count=[32, 32])
    trunk.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    arm = trimesh.creation.capsule(height=2.2, radius=ARM, count=[24, 24])
    arm.apply_transform(trimesh.transformations.rotation_matrix(-np.pi / 2, [1, 0, 0]))
    arm.apply_translation([0, 1.1, 0])
    return mx.medial_axis(trimesh.boolean.union([trunk, arm], engine="manifold"), method="flow")


def test_the_thin_arm_goes_between_its_width_and_the_trunks(t_skeleton):
    sk = t_skeleton
    assert len(sk.endpoints) == 3 and len(sk.junctions) == 1  # trunk ends and the arm's tip
    kept = sk.prune(lam=1.0)  # wider than the arm (0.4), narrower than the trunk (1.2)
    assert len(kept.endpoints) == 2 and len(kept.junctions) == 0 and kept.n_components == 1
    assert kept.metadata["pruned_branches"] == 1 and kept.raw is sk
    assert np.abs(kept.points[:, 1]).max() < TRUNK  # nothing left up the arm (y up to 2.4): all in the trunk
    # every input vertex still has a node: the arm's now go to where the arm hung
    node_of = kept.extras["correspondence"]
    assert node_of.max() < len(kept.points) and (node_of >= 0).sum() == (sk.extras["correspondence"] >= 0).sum()
    assert sk.prune(lam=0.2).betti == sk.betti and len(sk.prune(lam=0.2).points) == len(sk.points)


def test_pruning_keeps_components_and_starts_from_the_unpruned_skeleton(t_skeleton):
    sk = t_skeleton
    gone = sk.prune(lam=50.0)  # wider than everything: the skeleton keeps a point, its homotopy type
    assert gone.n_components == 1 and len(gone.points) > 0
    again = gone.prune(lam=0.2)  # from the unpruned skeleton, not from the pruned one
    assert len(again.points) == len(sk.points)
    with pytest.raises(mx.InvalidInputError, match="by lam only"):
        sk.prune(lam=1.0, detour=0.1)


def test_the_inner_balls_are_measured_once_per_mesh(t_skeleton, monkeypatch):
    """Trying one lambda after another re-prunes only: the shrinking balls ran once, and the answer is the same."""
    from collections import OrderedDict

    from medialaxis.mesh.skeleton import _flow_operators, branch_prune

    monkeypatch.setattr(branch_prune, "_inner", OrderedDict())
    calls = []
    real = _flow_operators.pole_targets
    monkeypatch.setattr(_flow_operators, "pole_targets", lambda *a, **k: calls.append(1) or real(*a, **k))
    first = branch_prune.contact_widths(t_skeleton)
    again = [t_skeleton.prune(lam=lam) for lam in (0.3, 1.0, 0.3)]
    assert len(calls) == 1
    assert np.array_equal(branch_prune.contact_widths(t_skeleton), first)
    assert np.array_equal(again[0].points, again[2].points) and again[1].metadata["pruned_branches"] == 1
    moved = t_skeleton.shape.copy()  # another mesh object, and then changed in place: measured again each time
    before = branch_prune.inner_radii(moved).copy()
    moved.vertices = moved.vertices * 2.0
    assert len(calls) == 2
    assert np.allclose(branch_prune.inner_radii(moved), 2.0 * before)  # twice the mesh, twice its inner balls
    assert len(calls) == 3
