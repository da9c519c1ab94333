"""Zero-area faces of a closed surface taken out without opening it.

Boolean unions (manifold3d), CAD exporters and scanners leave faces whose
area is zero at the accuracy of the coordinates: a *cap*, whose third vertex
lies on its longest edge (a T-junction closed by a flat triangle), or a
*needle*, two of whose vertices coincide. Each edge of such a face is still
shared by two faces, so the surface is closed; dropping the face would open
it (three open edges). Here a cap is removed by flipping its longest edge
(the two new triangles tile the neighbour exactly, since the vertex lies on
that edge) and a needle by collapsing its zero-length edge (no point moves),
each only when the result stays a closed 2-manifold (no edge created twice;
the link condition of Dey, Edelsbrunner, Guha, Nekhayev, "Topology
preserving edge contraction", Publ. Inst. Math. (Beograd) 66(80), 1999).
The surface, its topology and its volume are unchanged.
"""

from __future__ import annotations

import numpy as np

__all__ = ["coordinate_accuracy", "degenerate_faces", "remove_degenerate_faces"]

#: A face is degenerate when its height over its longest edge is at most this
#: many units in the last place of the largest coordinate (a few roundings of
#: the coordinates, the accuracy of a float32 STL or of a boolean's output).
ULPS = 4.0
#: Rounds of flips and collapses at most (one usually does).
MAX_ROUNDS = 8


def coordinate_accuracy(vertices: np.ndarray) -> float:
    """Resolution of the coordinates: ``ULPS`` units in the last place of the largest one.

    Coordinates that are all exact float32 values (STL, manifold3d,
    most scanners) have float32's resolution, 2^-23 relative; others float64's.
    """
    v = np.asarray(vertices, np.float64)
    magnitude = float(np.abs(v).max()) if v.size else 0.0
    single = bool(np.all(v.astype(np.float32).astype(np.float64) == v))
    return ULPS * float(np.spacing(np.float32(magnitude) if single else magnitude))


def degenerate_faces(vertices: np.ndarray, faces: np.ndarray, accuracy: float) -> np.ndarray:
    """Indices of the faces whose height over their longest edge is at most ``accuracy``."""
    tri = np.asarray(vertices, np.float64)[faces]
    twice_area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    longest = np.linalg.norm(tri - np.roll(tri, -1, axis=1), axis=2).max(axis=1)
    return np.flatnonzero(twice_area <= accuracy * longest)


class _Surface:
    """Faces with their edge and vertex incidences, edited in place.

    The faces around a vertex are gathered when first asked for (from one
    sort of the corners), and a directed edge's face is found among those of
    its first vertex: a closed surface has each directed edge once. Dicts of
    every edge and vertex cost 0.8 s per 100k faces, for the few faces a
    mesh has degenerate (a scanned ogre's 4 among 124k).
    """

    def __init__(self, vertices: np.ndarray, faces: np.ndarray) -> None:
        self.v = vertices
        self._faces = np.asarray(faces, np.int64)
        self._edited: dict[int, tuple[int, int, int]] = {}
        self.alive = np.ones(len(self._faces), bool)
        corners = self._faces.ravel()
        order = np.argsort(corners, kind="stable")
        self._start = np.searchsorted(corners[order], np.arange(int(corners.max(initial=-1)) + 2))
        self._face_of = order // 3
        self._around: dict[int, set[int]] = {}

    def face(self, i: int) -> tuple[int, int, int]:
        f = self._edited.get(i)
        if f is None:
            f = (int(self._faces[i, 0]), int(self._faces[i, 1]), int(self._faces[i, 2]))
        return f

    def live_faces(self) -> np.ndarray:
        out = self._faces.copy()
        for i, f in self._edited.items():
            out[i] = f
        return out[self.alive]

    def around(self, a: int) -> set[int]:
        """The faces with vertex ``a``."""
        faces = self._around.get(a)
        if faces is None:
            faces = set(self._face_of[self._start[a]:self._start[a + 1]].tolist()) if a + 1 < len(self._start) else set()
            self._around[a] = faces
        return faces

    def edge(self, a: int, b: int) -> int | None:
        """The face with directed edge ``a -> b``, if any."""
        for i in self.around(a):
            f = self.face(i)
            if (f[0], f[1]) == (a, b) or (f[1], f[2]) == (a, b) or (f[2], f[0]) == (a, b):
                return i
        return None

    def _add(self, i: int, f: tuple[int, int, int]) -> None:
        self._edited[i] = f
        for k in range(3):
            self.around(f[k]).add(i)

    def _remove(self, i: int) -> None:
        for x in self.face(i):
            self.around(x).discard(i)

    def ring(self, a: int) -> set[int]:
        return {x for i in self.around(a) for x in self.face(i)} - {a}

    def flip(self, i: int, p: int, q: int, c: int) -> bool:
        """Flip edge ``pq`` of face ``(p, q, c)`` to ``cd``, ``d`` opposite in the neighbour."""
        j = self.edge(q, p)
        if j is None:
            return False
        d = next(x for x in self.face(j) if x not in (p, q))
        if d == c or self.edge(c, d) is not None or self.edge(d, c) is not None:
            return False
        new = [(p, d, c), (q, c, d)]
        tri = self.v[np.array(new + [self.face(j)])]
        normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        if np.any(normal[:2] @ normal[2] <= 0):
            return False  # d on the line too, or the new faces would fold over the neighbour
        self._remove(i)
        self._remove(j)
        self._add(i, new[0])
        self._add(j, new[1])
        return True

    def collapse(self, u: int, w: int) -> bool:
        """Merge vertex ``w`` into ``u`` (at the same place), dropping the two faces on edge ``uw``."""
        on_edge = [self.edge(u, w), self.edge(w, u)]
        if None in on_edge:
            return False
        opposite = {x for i in on_edge for x in self.face(i)} - {u, w}  # type: ignore[arg-type]
        if self.ring(u) & self.ring(w) != opposite or len(opposite) != 2:
            return False  # the link condition: the collapse would pinch the surface
        for i in on_edge:
            self._remove(i)  # type: ignore[arg-type]
            self.alive[i] = False  # type: ignore[index]
        for i in list(self.around(w)):
            f = self.face(i)
            self._remove(i)
            self._add(i, tuple(u if x == w else x for x in f))  # type: ignore[arg-type]
        return True


def remove_degenerate_faces(
    vertices: np.ndarray, faces: np.ndarray, accuracy: float
) -> tuple[np.ndarray, int, int, int]:
    """Flip caps and collapse needles of a closed, consistently oriented surface.

    Parameters
    ----------
    vertices : (n, 3) float64 ndarray
    faces : (k, 3) int64 ndarray
        Every edge shared by two faces, in opposite directions.
    accuracy : float
        Largest height of a degenerate face (:func:`coordinate_accuracy`).

    Returns
    -------
    faces : (k', 3) int64 ndarray
        The same surface (vertices unmoved; a collapsed one is left unused).
    flipped, collapsed, kept : int
        Degenerate faces removed by an edge flip, by an edge collapse, and
        those left because neither keeps the surface a closed manifold.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [2, 0, 0], [1, 0, 0], [1, 1, 0], [1, -1, 1]], float)
    >>> f = np.array([[0, 1, 2], [1, 0, 3], [0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4]])
    >>> g, flipped, collapsed, kept = remove_degenerate_faces(v, f, 1e-12)
    >>> len(g), flipped, collapsed, kept
    (6, 1, 0, 0)
    """
    bad = degenerate_faces(vertices, faces, accuracy)
    if not len(bad):
        return faces, 0, 0, 0
    surface = _Surface(np.asarray(vertices, np.float64), faces)
    flipped = collapsed = 0
    for _ in range(MAX_ROUNDS):
        progress = False
        for i in bad:
            if not surface.alive[i]:
                continue
            f = surface.face(i)
            tri = vertices[list(f)]
            length = np.linalg.norm(tri - np.roll(tri, -1, axis=0), axis=1)  # edge k: f[k] -> f[k+1]
            if float(length.max()) == 0.0:
                continue
            if 2.0 * float(np.linalg.norm(np.cross(tri[1] - tri[0], tri[2] - tri[0]))) > accuracy * float(length.max()):
                continue  # no longer degenerate
            short, long = int(np.argmin(length)), int(np.argmax(length))
            if length[short] <= accuracy:
                done = surface.collapse(f[short], f[(short + 1) % 3])
                collapsed += done
            else:
                done = surface.flip(i, f[long], f[(long + 1) % 3], f[(long + 2) % 3])
                flipped += done
            progress |= done
        live = surface.live_faces()
        bad_live = degenerate_faces(vertices, live, accuracy)
        if not len(bad_live) or not progress:
            return live, flipped, collapsed, len(bad_live)
        index = np.flatnonzero(surface.alive)
        bad = index[bad_live]
    return live, flipped, collapsed, len(bad_live)
