"""Shells an exporter turned over: a shell facing inward that nothing encloses is a solid, not a cavity."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

import medialaxis as mx
from medialaxis.errors import MedialAxisWarning
from medialaxis.mesh.solid.crossings import inside_out_shells


def _ball(radius: float, at=(0.0, 0.0, 0.0), inward: bool = False, subdivisions: int = 3) -> trimesh.Trimesh:
    ball = trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius)
    ball.apply_translation(at)
    if inward:
        ball.invert()
    return ball


# (parts, the solid's Betti numbers by construction: separate balls, cavities, an island in a cavity)
CASES = {
    "a ball beside a ball turned over": ([_ball(1.0), _ball(1.0, (5, 0, 0), True)], (2, 0, 0)),
    "the larger one turned over": ([_ball(1.0), _ball(2.0, (6, 0, 0), True)], (2, 0, 0)),
    "a hollow ball": ([_ball(2.0, subdivisions=4), _ball(1.0, inward=True)], (1, 0, 1)),
    "a hollow ball turned over whole": ([_ball(2.0, inward=True, subdivisions=4), _ball(1.0)], (1, 0, 1)),
    "an island in a cavity": ([_ball(3.0, subdivisions=4), _ball(2.0, inward=True, subdivisions=4), _ball(1.0)], (2, 0, 1)),
}


@pytest.mark.parametrize("name", list(CASES))
def test_shells_turned_over_by_an_exporter(name):
    parts, betti = CASES[name]
    if "beside" in name or "larger" in name:  # a part turned over: said so
        with pytest.warns(MedialAxisWarning, match="turned outward"):
            ma = mx.medial_axis(trimesh.util.concatenate(parts))
    else:
        ma = mx.medial_axis(trimesh.util.concatenate(parts))
    assert ma.betti == betti
    if betti == (2, 0, 0):  # both balls solid: a medial ball at each centre, of about its radius
        for part in parts:
            at = np.argmin(np.linalg.norm(ma.points - part.vertices.mean(axis=0), axis=1))
            assert np.linalg.norm(ma.points[at] - part.vertices.mean(axis=0)) < 0.1 * part.extents[0]
            assert abs(ma.radii[at] - 0.5 * part.extents[0]) < 0.1 * part.extents[0]


def test_only_free_shells_facing_inward_are_found():
    hollow = trimesh.util.concatenate([_ball(2.0), _ball(1.0, inward=True)])
    assert len(inside_out_shells(hollow.vertices, hollow.faces)) == 0  # a cavity
    apart = trimesh.util.concatenate([_ball(1.0), _ball(1.0, (5, 0, 0), True)])
    n = len(_ball(1.0).faces)
    assert inside_out_shells(apart.vertices, apart.faces).tolist() == list(range(n, 2 * n))


@pytest.mark.filterwarnings("ignore:.*turned outward")
def test_the_flow_skeleton_of_a_ball_turned_over_beside_another():
    sk = mx.medial_axis(trimesh.util.concatenate([_ball(1.0), _ball(1.0, (5, 0, 0), True)]), method="flow")
    assert sk.n_components == 2  # one point per ball (the turned one was left out as a cavity)
    assert sorted(np.round(sk.points[:, 0]).tolist()) == [0.0, 5.0]


def test_a_porous_block_keeps_its_pores_by_both_winding_paths(monkeypatch):
    # 200 pores (cavities, winding number 1 around them) and one ball turned over apart from the block
    rng = np.random.default_rng(0)
    parts = [trimesh.creation.box([10.0, 10.0, 10.0])]
    parts += [_ball(0.05, c, True, subdivisions=1) for c in rng.uniform(-4.0, 4.0, (200, 3))]
    parts.append(_ball(1.0, (20.0, 0.0, 0.0), True, subdivisions=2))
    porous = trimesh.util.concatenate(parts)
    n_free = len(parts[-1].faces)
    expected = list(range(len(porous.faces) - n_free, len(porous.faces)))
    assert inside_out_shells(porous.vertices, porous.faces).tolist() == expected
    from medialaxis.mesh.solid import crossings

    monkeypatch.setattr(crossings, "EXACT_TERMS", 0)  # the fast winding tree
    assert inside_out_shells(porous.vertices, porous.faces).tolist() == expected
