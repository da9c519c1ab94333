"""Axis tour: the medial axis walked around, as the boundary would be, with its context at each step.

The main term of the shape distance. A walk around a planar tree, keeping it
on the same side (at each node leave by the edge next in angular order), runs
along every axis edge once in each direction: it is the *Euler tour* of the
axis, and it meets the axis's parts in the order in which the boundary meets
them (each boundary point's nearest axis point moves along this tour). For an
axis with cycles (a shape with holes) the walk of the outer face is used.

``n`` samples are placed at equal steps along the tour, starting from a
canonical place (the tip of the branch that protrudes most, see
:func:`outer_face` and :func:`medialaxis.compare.signature`). Each sample
is an axis point with a direction (that of the walk, so the two sides of a branch differ) and its
radius; its descriptor is the log-polar histogram of the swept mass of the
whole axis (length times radius of each axis piece) around it, with angles
measured from the walk direction over the full circle. Two shapes are compared
by aligning their sample sequences cyclically, keeping the order, with a cost
for each skipped sample (see :func:`medialaxis.compare._kernels.tour_distances`).

Everything here is the axis and its radius function: the sample points are
medial points, the histograms count medial mass, the radius is compared
directly; only the *order* of the samples is the boundary's. It is the
medial counterpart of matching shape contexts with an order-keeping dynamic
program (Belongie, Malik and Puzicha, TPAMI 2002; Ling and Jacobs, TPAMI
2007), and it lifts the Kimia-99 row from 912 (path matching plus the
unordered axis context) to 955, and to 961 when the distance keeps the best of
the axis, the raw axis and the closed shape's axis (``benchmarks/bench_compare.py``).
Similarity invariant: distances are divided by the signature's scale and
angles are measured from the walk; a mirror image walks the tour the other
way (:func:`tour_context` of the reflected axis gives it).
"""

from __future__ import annotations

import numpy as np

from medialaxis.compare.histograms import RADIAL_CENTRES, along, mass_histograms, pieces

__all__ = ["tour_context", "rotation_system", "outer_face", "N_TOUR", "N_TOUR_ANGULAR"]

#: Samples along the tour. On the Kimia-99 row (one axis pruning): 48 gives
#: 954, 64 955, 80 957, 96 953, equal within the few units of noise of that
#: measure, while the pair time grows as the square; 32 gave 925 in the prototype.
N_TOUR = 64
#: Angle bins over the full circle (8: 952, 12: 955-960, 16: 958-961 on
#: Kimia-99 in the prototype and here, at 20% more time for 16).
N_TOUR_ANGULAR = 12


def rotation_system(points: np.ndarray, edges: np.ndarray) -> tuple[list[list[int]], list[dict[int, int]]]:
    """Neighbours of each node in angular order, and each neighbour's rank in that order.

    The angular order is that of ``arctan2(d[:, 1], d[:, 0])`` for the
    offsets ``d`` to the neighbours; a reflection of the points reverses it.
    """
    n = len(points)
    nbrs: list[list[int]] = [[] for _ in range(n)]
    for a, b in edges:
        if a != b:
            nbrs[int(a)].append(int(b))
            nbrs[int(b)].append(int(a))
    rank: list[dict[int, int]] = []
    for v in range(n):
        if nbrs[v]:
            d = points[nbrs[v]] - points[v]
            order = np.argsort(np.arctan2(d[:, 1], d[:, 0]), kind="stable")
            nbrs[v] = [nbrs[v][k] for k in order]
        rank.append({u: k for k, u in enumerate(nbrs[v])})
    return nbrs, rank


def outer_face(points: np.ndarray, edges: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """The darts ``(k, 2)`` of the walk around the outer face of the axis, from one of ``starts``.

    For a tree there is one face, the Euler tour (``2 * len(edges)`` darts).
    With cycles, the outer face is the one of largest signed area: this
    walk turns the faces bounded by cycles clockwise (negative area) and the
    outer face the other way, whatever the pose (a reflection reverses both
    the angular order and the sign).

    The walk starts by leaving a node of ``starts`` (all the nodes of the
    face if none is on it). Among several ways to do so (several candidate
    nodes, or a junction the walk passes several times), it takes the one
    followed by the longest stretch of walk before the next of them: a rule
    that depends only on the walk, so the same start is found whatever the
    pose or the numbering (a mirror image walks the other way, and its walk
    is the one the mirrored version of the signature takes).
    """
    edges = np.asarray(edges, np.int64).reshape(-1, 2)
    edges = edges[edges[:, 0] != edges[:, 1]]
    m = len(edges)
    darts = np.empty((2 * m, 2), np.int64)  # edge i gives darts 2i (a -> b) and 2i + 1 (b -> a)
    darts[0::2], darts[1::2] = edges, edges[:, ::-1]
    step = points[darts[:, 1]] - points[darts[:, 0]]
    # Darts leaving each node in angular order (stable: ties keep the edge order), and the
    # dart that follows each: arriving at b from a, leave by the neighbour after a around b.
    order = np.lexsort((np.arctan2(step[:, 1], step[:, 0]), darts[:, 0]))
    place = np.empty(2 * m, np.int64)
    place[order] = np.arange(2 * m)
    first = np.searchsorted(darts[order, 0], np.arange(len(points)))
    count = np.bincount(darts[:, 0], minlength=len(points))
    back = np.arange(2 * m) ^ 1
    node = darts[:, 1]
    following = order[first[node] + (place[back] - first[node] + 1) % np.maximum(count[node], 1)].tolist()
    seen = bytearray(2 * m)
    faces: list[list[int]] = []
    for start in [*range(0, 2 * m, 2), *range(1, 2 * m, 2)]:
        if seen[start]:
            continue
        face, dart = [], start
        while not seen[dart]:
            seen[dart] = 1
            face.append(dart)
            dart = following[dart]
        faces.append(face)

    def area(face: list[int]) -> float:
        p = points[darts[face, 0]]
        return float(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1))) / 2

    darts = darts[faces[0] if len(faces) == 1 else max(faces, key=area)]
    leaving = np.flatnonzero(np.isin(darts[:, 0], starts))
    if not len(leaving):
        leaving = np.arange(len(darts))
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(points[darts[:, 1]] - points[darts[:, 0]], axis=1))])
    stretch = np.diff(np.append(arc[leaving], arc[-1] + arc[leaving[0]]))
    k = int(leaving[int(np.argmax(stretch >= stretch.max() * (1 - 1e-9)))])
    return np.concatenate([darts[k:], darts[:k]])


def tour_context(
    points: np.ndarray,
    radii: np.ndarray,
    edges: np.ndarray,
    scale: float,
    starts: np.ndarray,
    n_samples: int = N_TOUR,
    n_angular: int = N_TOUR_ANGULAR,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tour-context histograms, radii and positions of samples along the axis tour.

    Parameters
    ----------
    points : (n, 2) float ndarray
        Axis nodes (one connected component).
    radii : (n,) float ndarray
        Radius function at the nodes.
    edges : (m, 2) int ndarray
        Axis edges; may be empty (a disc: one node, one sample).
    scale : float
        Length unit (the signature's scale).
    starts : (c,) int ndarray
        Nodes the tour may start from (see :func:`outer_face` for the choice).
    n_samples, n_angular : int
        Samples along the tour; angle bins over the full circle.

    Returns
    -------
    histograms : (k, N_RADIAL * n_angular) float64 ndarray
        Row ``i``: the swept mass of the axis (summing to 1) around sample
        ``i``, by distance (log-spaced soft bins centred on ``RADIAL_CENTRES``
        times ``scale``) and by angle from the walk direction (soft bins over
        ``[0, 2 pi)``), flattened distance-major.
    sample_radii : (k,) float64 ndarray
        Radius at each sample divided by ``scale``.
    positions : (k, 2) float64 ndarray
        Sample positions (input units), for pictures.

    References
    ----------
    .. [1] S. Belongie, J. Malik, J. Puzicha, "Shape matching and object recognition using shape
           contexts", IEEE Transactions on Pattern Analysis and Machine Intelligence
           24(4):509-522, 2002. doi:10.1109/34.993558
    .. [2] H. Ling, D. W. Jacobs, "Shape classification using the inner-distance", IEEE
           Transactions on Pattern Analysis and Machine Intelligence 29(2):286-299, 2007.

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    >>> h, r, p = tour_context(pts, np.array([0.1, 0.2, 0.1]), np.array([[0, 1], [1, 2]]), 1.0, [0], n_samples=4)
    >>> h.shape, bool(np.allclose(h.sum(axis=1), 1.0)), p[:, 0].tolist()   # out along the bar and back
    ((4, 60), True, [0.5, 1.5, 1.5, 0.5])
    """
    n_bins = len(RADIAL_CENTRES) * n_angular
    if not len(edges):
        hist = np.zeros((1, n_bins))
        hist[0, :n_angular] = 1.0 / n_angular  # everything at distance 0, in no direction
        node = int(starts[0])
        return hist, np.array([radii[node] / scale]), points[[node]].astype(np.float64)
    darts = outer_face(points, edges, np.asarray(starts, np.int64))
    walk = np.append(darts[:, 0], darts[-1, 1])
    pos, heading, rad = along(points, radii, walk, (np.arange(n_samples) + 0.5) / n_samples)
    mid, mass = pieces(points, radii, edges)
    hist = mass_histograms(pos, heading, mid, mass, scale, n_angular, 2 * np.pi)
    return hist, rad / scale, pos
