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
    """Faces with their edge and vertex incidences, edited in place."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray) -> None:
        self.v = vertices
        self.faces = [tuple(int(x) for x in f) for f in faces]
        self.alive = [True] * len(self.faces)
        self.edge: dict[tuple[int, int], int] = {}  # directed edge -> face
        self.around: dict[int, set[int]] = {}  # vertex -> faces
        for i, f in enumerate(self.faces):
            self._add(i, f)

    def _add(self, i: int, f: tuple[int, int, int]) -> None:
        self.faces[i] = f
        for k in range(3):
            self.edge[(f[k], f[(k + 1) % 3])] = i
            self.around.setdefault(f[k], set()).add(i)

    def _remove(self, i: int) -> None:
        f = self.faces[i]
        for k in range(3):
            self.edge.pop((f[k], f[(k + 1) % 3]), None)
            self.around[f[k]].discard(i)

    def ring(self, a: int) -> set[int]:
        return {x for i in self.around.get(a, ()) for x in self.faces[i]} - {a}

    def flip(self, i: int, p: int, q: int, c: int) -> bool:
        """Flip edge ``pq`` of face ``(p, q, c)`` to ``cd``, ``d`` opposite in the neighbour."""
        j = self.edge.get((q, p))
        if j is None:
            return False
        d = next(x for x in self.faces[j] if x not in (p, q))
        if d == c or (c, d) in self.edge or (d, c) in self.edge:
            return False
        new = [(p, d, c), (q, c, d)]
        tri = self.v[np.array(new + [self.faces[j]])]
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
        on_edge = [self.edge.get((u, w)), self.edge.get((w, u))]
        if None in on_edge:
            return False
        opposite = {x for i in on_edge for x in self.faces[i]} - {u, w}  # type: ignore[index]
        if self.ring(u) & self.ring(w) != opposite or len(opposite) != 2:
            return False  # the link condition: the collapse would pinch the surface
        for i in on_edge:
            self._remove(i)  # type: ignore[arg-type]
            self.alive[i] = False  # type: ignore[index]
        for i in list(self.around.get(w, ())):
            f = self.faces[i]
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
            f = surface.faces[i]
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
        live = np.array([f for f, a in zip(surface.faces, surface.alive) if a], np.int64)
        bad_live = degenerate_faces(vertices, live, accuracy)
        if not len(bad_live) or not progress:
            return live, flipped, collapsed, len(bad_live)
        index = np.flatnonzero(surface.alive)
        bad = index[bad_live]
    return live, flipped, collapsed, len(bad_live)
