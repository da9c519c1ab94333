"""The Delaunay insertion's speed devices change no result (the geometry is checked in ``test_delaunay.py``).

* The tetrahedron arrays are made larger than the capacity the insertion
  runs at (``_SPARE``), so that a doubling copies nothing. The random walk
  depends on the capacity (a point is walked to again when it grows), so
  the results must not depend on the arrays' size.
* The points are renumbered in insertion order inside the kernel: the
  points moved further (exact ties, no joggle) must be given back on their
  own rows, where every tetrahedron is positively oriented (exact rational
  arithmetic).
* The finished arrays are written once in their final order: the
  tetrahedra follow a Z-order curve of their centroids, computed here by an
  independent bit interleave.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import trimesh

import medialaxis.mesh.sample.delaunay as delaunay
from medialaxis.mesh.sample.delaunay import _delaunay


def _lattice(n: int) -> np.ndarray:
    return np.stack(np.meshgrid(*[np.arange(float(n))] * 3, indexing="ij"), -1).reshape(-1, 3)


def _uv_sphere() -> np.ndarray:
    return np.asarray(trimesh.creation.uv_sphere(count=[20, 20]).vertices)


@pytest.mark.parametrize("joggle", [delaunay.JOGGLE, 0.0])
@pytest.mark.parametrize("make", [_uv_sphere, lambda: _lattice(6)])
def test_the_arrays_size_changes_nothing(monkeypatch, make, joggle):
    points = make()
    monkeypatch.setattr(delaunay, "_SLOTS_PER_POINT", 1.0)  # several doublings
    expected = _delaunay(points, joggle=joggle)
    for spare in (1, 16):  # 1: the arrays are copied at every doubling, 16: never
        monkeypatch.setattr(delaunay, "_SPARE", spare)
        got = _delaunay(points, joggle=joggle)
        for a, b in zip(got[:3], expected[:3]):
            np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(got[3]["joggled"], expected[3]["joggled"])


def _exact_orient(p: np.ndarray) -> int:
    a, b, c, d = ([Fraction(float(v)) for v in row] for row in p)
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])
    return (det > 0) - (det < 0)


def test_points_moved_further_come_back_on_their_rows():
    points = _lattice(5)  # exact ties everywhere: with no joggle, some points are moved further
    simplices, _, _, info = _delaunay(points, joggle=0.0)
    assert info["moved"] > 0
    joggled = info["joggled"]
    # scaled to a box of side 1 centred on 0: the points not moved are the lattice's, exactly
    scaled = (points - 2.0) / 4.0
    moved = (joggled != scaled).any(axis=1)
    assert 0 < moved.sum() <= info["moved"]
    assert all(_exact_orient(joggled[s]) == 1 for s in simplices)
    assert all(_exact_orient(scaled[s]) >= 0 for s in simplices[~moved[simplices].any(axis=1)])


def _morton(cells: np.ndarray) -> np.ndarray:
    """Bit interleave of three 16-bit integers per row (x in the lowest bit)."""
    code = np.zeros(len(cells), np.int64)
    for bit in range(16):
        for axis in range(3):
            code |= ((cells[:, axis] >> bit) & 1) << (3 * bit + axis)
    return code


def test_tetrahedra_follow_a_z_order_of_their_centroids():
    points = np.random.default_rng(2).random((3000, 3))
    simplices, _, _, info = _delaunay(points)
    centroid = info["joggled"][simplices].mean(axis=1)
    top = (1 << 16) - 1
    cells = np.clip(((centroid + 0.5) * top).astype(np.int64), 0, top)
    key = _morton(cells)
    assert (np.diff(key) >= 0).mean() > 0.999  # the centroid's rounding may differ in the last bit
    assert len(np.unique(key)) > 0.9 * len(key)
