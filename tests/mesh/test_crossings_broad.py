"""The broad phase of the crossing check finds every crossing pair, long slivers and caps included."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from medialaxis.mesh.solid import crossings
from medialaxis.mesh.solid._intersect_kernels import crossing_mask
from medialaxis.mesh.solid.crossings import candidate_pairs, crossing_pairs, unit_triangles


def _all_crossings(tri: np.ndarray, faces: np.ndarray) -> set[tuple[int, int]]:
    """Every pair tested (brute force): the truth the broad phase must keep."""
    i, j = np.triu_indices(len(tri), 1)
    pairs = np.column_stack([i, j]).astype(np.int64)
    shared = (faces[i][:, :, None] == faces[j][:, None, :]).sum(axis=(1, 2))
    pairs = pairs[shared < 2]
    hit = pairs[crossing_mask(tri, faces, pairs, 1e-15)]
    return set(map(tuple, np.sort(hit, axis=1).tolist()))


@pytest.mark.parametrize("budget", [None, -3000])
def test_a_soup_of_slivers_and_small_faces(budget: int | None, monkeypatch: pytest.MonkeyPatch) -> None:
    if budget is not None:  # no piece at all: every large face matched by its own sphere (a needle's faces)
        monkeypatch.setattr(crossings, "PIECE_BUDGET", budget)
    rng = np.random.default_rng(7)
    small = rng.random((400, 1, 3)) + 0.03 * rng.standard_normal((400, 3, 3))
    ends = rng.random((30, 2, 3))
    slivers = np.concatenate([ends, ends[:, :1] + 0.004 * rng.standard_normal((30, 1, 3))], axis=1)  # long, thin
    caps = rng.random((5, 1, 3)) + 0.4 * rng.standard_normal((5, 3, 3))  # large and wide
    tri = np.concatenate([small, slivers, caps])
    faces = np.arange(3 * len(tri), dtype=np.int64).reshape(-1, 3)
    tri, _, _ = unit_triangles(tri.reshape(-1, 3), faces)
    found = candidate_pairs(tri, faces)
    crossing = set(map(tuple, np.sort(found[crossing_mask(tri, faces, found, 1e-15)], axis=1).tolist()))
    truth = _all_crossings(tri, faces)
    large = sum(1 for i, j in truth if max(i, j) >= 400)  # a sliver or a cap in the pair
    assert large >= 10 and crossing == truth
    assert len(np.unique(np.sort(found, axis=1), axis=0)) == len(found)  # each pair once


def test_long_faces_of_a_capsule_do_not_cross() -> None:
    # the faces running the length of a capsule are large; two crossing capsules cross only where they meet
    capsule = trimesh.creation.capsule(height=2.0, radius=0.5, count=[64, 64])
    other = capsule.copy()
    other.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [1.0, 0.0, 0.0]))
    assert len(crossing_pairs(capsule)) == 0
    pairs = crossing_pairs(trimesh.util.concatenate([capsule, other]))
    f = np.arange(len(capsule.faces))
    both = np.isin(pairs[:, 0], f) != np.isin(pairs[:, 1], f)  # one face of each capsule
    assert len(pairs) > 0 and both.all()
