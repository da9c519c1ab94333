"""The benchmark's truth for the mesh routes: Betti numbers of the solid's open interior (benchmarks/solid_interior.py).

Checked on unions of unit cubes, whose open interior is the 6-connected
digital solid with a 26-connected complement, counted by scikit-image
(labels and the Euler number), independently of the surface count; the
closed solid is the 26-connected one, and the named cases are those where
the two differ.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from skimage.measure import euler_number, label

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from solid_interior import interior_betti  # noqa: E402

_DIRS = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]])


def _cube_surface(cells) -> tuple[np.ndarray, np.ndarray]:
    """The outward boundary of a union of unit cubes (integer corners, one id per position, two triangles a square)."""
    cells = {tuple(c) for c in np.asarray(cells, int).tolist()}
    corners: dict[tuple, int] = {}
    faces = []
    for c in cells:
        for d in _DIRS:
            if tuple(np.add(c, d)) in cells:
                continue
            axis = int(np.flatnonzero(d)[0])
            u, w = (axis + 1) % 3, (axis + 2) % 3
            base = np.array(c) + (d > 0)  # the square lies on this plane
            square = []
            for du, dw in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = base.copy()
                p[u] += du
                p[w] += dw
                square.append(corners.setdefault(tuple(p.tolist()), len(corners)))
            if d[axis] < 0:  # (u, w, axis) is right-handed: counterclockwise in (u, w) faces +axis
                square.reverse()
            faces += [[square[0], square[1], square[2]], [square[0], square[2], square[3]]]
    vertices = np.array(sorted(corners, key=corners.get), float)
    return vertices, np.array(faces)


def _digital_betti(cells, solid_conn: int, empty_conn: int) -> tuple[int, int, int]:
    cells = np.asarray(cells, int)
    lo = cells.min(axis=0) - 2
    grid = np.zeros(cells.max(axis=0) - lo + 3, bool)
    grid[tuple((cells - lo).T)] = True
    b0 = int(label(grid, connectivity=solid_conn).max())
    b2 = int(label(~grid, connectivity=empty_conn).max()) - 1
    return b0, b0 + b2 - int(euler_number(grid, connectivity=solid_conn)), b2


def _interior(cells) -> tuple[int, int, int]:
    return _digital_betti(cells, 1, 3)


def _closed(cells) -> tuple[int, int, int]:
    return _digital_betti(cells, 3, 1)


def _block(n: int) -> set:
    return {(x, y, z) for x in range(n) for y in range(n) for z in range(n)}


# a chain of face-sharing cubes from (0,0,0) round to (1,1,1), which touches (0,0,0) at one point
_PINCHED_RING = [
    (0, 0, 0),
    (0, 0, -1),
    (0, 0, -2),
    (1, 0, -2),
    (2, 0, -2),
    (3, 0, -2),
    (3, 1, -2),
    (3, 1, -1),
    (3, 1, 0),
    (3, 1, 1),
    (2, 1, 1),
    (1, 1, 1),
]
NAMED = {
    "two cubes sharing a vertex": ([(0, 0, 0), (1, 1, 1)], (2, 0, 0), (1, 0, 0)),
    "two cubes sharing an edge": ([(0, 0, 0), (1, 1, 0)], (2, 0, 0), (1, 0, 0)),
    "a solid torus closed at a point": (_PINCHED_RING, (1, 0, 0), (1, 1, 0)),
    "two cavities touching at a point": (sorted(_block(4) - {(1, 1, 1), (2, 2, 2)}), (1, 0, 1), (1, 0, 2)),
    "two cavities touching along an edge": (sorted(_block(4) - {(1, 1, 1), (2, 2, 1)}), (1, 0, 1), (1, 0, 2)),
    "a tunnel narrowed to a point": (
        sorted(_block(4) - {(1, 1, 0), (1, 1, 1), (2, 2, 2), (2, 2, 3)}),
        (1, 1, 0),
        (1, 0, 0),
    ),
    "a cavity touching the outside at a point": (sorted(_block(3) - {(1, 1, 1), (2, 2, 2)}), (1, 0, 0), (1, 0, 1)),
}


@pytest.mark.parametrize("name", NAMED)
def test_interior_differs_from_the_closed_solid_where_it_touches_itself(name: str) -> None:
    cells, interior, closed = NAMED[name]
    assert _interior(cells) == interior and _closed(cells) == closed  # the exact answers, counted digitally
    assert interior_betti(*_cube_surface(cells)) == interior


@pytest.mark.parametrize("seed", range(24))
def test_interior_of_random_cube_unions_matches_the_digital_count(seed: int) -> None:
    """Random unions hold pinches of every kind at once: at vertices, along edges, solid and empty.

    The sparse ones (seeds 0-11) fall apart into pieces and handles, the
    dense ones (12-23) closed cavities (2 to 10), most of which the interior merges.
    """
    rng = np.random.default_rng(seed)
    size, share = (5, 0.45 + 0.02 * seed) if seed < 12 else (6, 0.46 + 0.02 * seed)
    cells = np.argwhere(rng.random((size,) * 3) < share)
    assert interior_betti(*_cube_surface(cells)) == _interior(cells)


def test_interior_is_invariant_under_a_rigid_motion() -> None:
    """The pinch tests are geometric, not tied to the axes."""
    rng = np.random.default_rng(7)
    cells = np.argwhere(rng.random((5, 5, 5)) < 0.5)
    vertices, faces = _cube_surface(cells)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    q *= np.sign(np.linalg.det(q))
    assert interior_betti(vertices @ q.T + [3.0, -1.0, 2.0], faces) == _interior(cells)


def _cone(apex, axis, length: float, half_angle: float, sides: int = 12) -> tuple[np.ndarray, np.ndarray]:
    """A closed cone (apex, ring, base centre), faces outward."""
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    u = np.cross(axis, [0.3, 0.5, 0.8])
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)
    t = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    r = length * np.tan(half_angle)
    ring = apex + length * axis + r * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * w)
    vertices = np.vstack([apex, ring, apex + length * axis])
    k = np.arange(sides)
    faces = np.vstack(
        [
            np.c_[np.zeros(sides, int), 1 + (k + 1) % sides, 1 + k],
            np.c_[np.full(sides, sides + 1), 1 + k, 1 + (k + 1) % sides],
        ]
    )
    return vertices, faces


def _join(*parts) -> tuple[np.ndarray, np.ndarray]:
    vertices, faces, n = [], [], 0
    for v, f in parts:
        vertices.append(v)
        faces.append(f + n)
        n += len(v)
    return np.vstack(vertices), np.vstack(faces)


@pytest.mark.parametrize("half_angle", [0.5, 0.05])
def test_needle_cones_tip_to_tip(half_angle: float) -> None:
    """Two cones meeting at their apex, as a cut seahorse's slits of air do (needles of 3 to 30 degrees here)."""
    apex = np.array([0.3, -0.2, 0.1])
    axis = np.array([0.2, 1.0, -0.4])
    cones = [_cone(apex, axis, 2.0, half_angle), _cone(apex, -axis, 1.5, half_angle)]
    # two solid needles: the interior is two pieces, the closed solid one
    assert interior_betti(*_join(*cones)) == (2, 0, 0)
    # two needles of air in a block (faces turned inward): the interior holds one cavity (their closures meet), the closed solid two
    box_v, box_f = _cube_surface([(x, y, z) for x in range(-4, 4) for y in range(-4, 4) for z in range(-4, 4)])
    holes = [(v, f[:, ::-1]) for v, f in cones]
    assert interior_betti(*_join((box_v, box_f), *holes)) == (1, 0, 1)
