"""Loops around the holes of an oriented surface (:func:`~medialaxis.mesh.solid.holes.boundary_loops`).

Holes are made by removing faces of an icosphere, so each loop is known: a
removed face ``(a, b, c)`` leaves the loop ``a -> c -> b`` (its edges reversed,
as the neighbours have them).
"""

from __future__ import annotations

import numpy as np
import pytest

from medialaxis.mesh.solid.holes import boundary_loops

trimesh = pytest.importorskip("trimesh")


def _cyclic(loop) -> tuple[int, ...]:
    """A loop as a tuple starting at its smallest vertex."""
    loop = [int(x) for x in loop]
    k = loop.index(min(loop))
    return tuple(loop[k:] + loop[:k])


def _fan(faces: np.ndarray, v: int) -> list[int]:
    """The faces about vertex ``v`` in order (each the next across the edge from ``v``)."""
    around = [int(i) for i in np.flatnonzero((faces == v).any(axis=1))]
    order = [around[0]]
    while len(order) < len(around):
        f = list(faces[order[-1]])
        out = f[(f.index(v) + 2) % 3]  # the edge out -> v of this face ...
        order.append(next(i for i in around if i not in order and list(faces[i])[(list(faces[i]).index(v) + 1) % 3] == out))
    return order


def test_two_holes_meeting_at_a_vertex_get_a_loop_each():
    faces = np.asarray(trimesh.creation.icosphere(2).faces)
    v = 0
    fan = _fan(faces, v)
    gone = [fan[0], fan[2]]  # not adjacent: the holes touch at v only
    loops = boundary_loops(np.delete(faces, gone, axis=0))
    assert loops is not None
    expected = {_cyclic([a, c, b]) for a, b, c in faces[gone]}
    assert {_cyclic(x) for x in loops} == expected


def test_one_hole_and_none_where_it_cannot_chain():
    faces = np.asarray(trimesh.creation.icosphere(2).faces)
    loops = boundary_loops(faces[1:])
    assert loops is not None and [_cyclic(x) for x in loops] == [_cyclic(faces[0][[0, 2, 1]])]
    assert boundary_loops(faces) == []  # closed
    assert boundary_loops(np.vstack([faces, faces[:1]])) is None  # an edge used twice in one direction
    v = int(np.flatnonzero(np.bincount(faces.ravel()) == 6)[0])
    fan = _fan(faces, v)
    assert boundary_loops(np.delete(faces, fan[0:6:2], axis=0)) is None  # three holes at one vertex
