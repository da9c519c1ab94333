"""Points where the solid of a cut surface touches itself, opened by a small ball of air.

Where faces cross, the surface of the solid (:mod:`~medialaxis.mesh.solid.arrangement`)
can touch itself at a point: two vertex ids at one position, each with its
fan of faces. The medial axis has the homotopy type of the solid's open
interior (Lieutier 2004), which differs there from the closed solid's: two
solids touching at a point are apart in the interior, and two slits of air
meeting tip to tip join in it (on a scanned cow, a knob 0.26 across
touches the body at a point between two such slits; the interior has a
handle there that the closed solid lacks). A sample cannot see a point: its Delaunay tetrahedra
close the pinch as the closed solid does.

Taking out a ball ``B`` of radius ``r`` around such a point ``p`` gives a
solid whose closed set has the interior's homotopy type, when ``B`` meets
no other part of the surface: near ``p`` the solid is a cone from ``p``
over the part ``L`` of the sphere around ``p`` that it holds, the interior
near ``p`` is ``L`` times an interval, and the solid minus ``B`` keeps
``L`` times an interval too, with ``p`` gone. So :func:`carve_pinches` takes
out, at each such point, a ball of the spacing of the default sample (so
that the sample resolves it), or of half that, where the surface in the ball is one disk
around each of the point's fans (the ball reaches no other sheet and cuts
through no bar: either would change more than the pinch).

References
----------
.. [1] A. Lieutier, "Any open bounded subset of R^n has the same homotopy type as its
       medial axis", Computer-Aided Design 36(11):1029-1046, 2004. doi:10.1016/j.cad.2004.01.011
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph

__all__ = ["pinch_points", "carve_pinches", "CARVE_SPACINGS"]

#: Radii of the ball taken out at a pinch, the first that fits, in spacings of
#: the default sample (``sampling.sample_count``'s default count, spread
#: evenly); where none fits the pinch is left. A ball of half a spacing is not
#: resolved by that sample: a scanned seahorse, whose pinch lies among bars
#: thinner than a spacing, lost a handle more with it, until the Voronoi
#: route sampled more finely where the inner set fills such air
#: (``inner_set.POCKET_FLAT``); then it gets its handle there.
CARVE_SPACINGS = (1.0, 0.5)


def pinch_points(vertices: np.ndarray) -> np.ndarray:
    """Positions held by more than one vertex id (a cut surface keeps a pinch so), ``(k, 3)``.

    Examples
    --------
    >>> import numpy as np
    >>> pinch_points(np.array([[0, 0, 0], [1, 0, 0], [0, 0, 0.0]])).tolist()
    [[0.0, 0.0, 0.0]]
    """
    unique, count = np.unique(np.asarray(vertices, np.float64), axis=0, return_counts=True)
    return unique[count > 1]


def _faces_near(tri: np.ndarray, p: np.ndarray, r: float) -> np.ndarray:
    """Faces with a point within ``r`` of ``p``."""
    from trimesh.triangles import closest_point

    near = np.flatnonzero((tri.min(axis=1) <= p + r).all(axis=1) & (tri.max(axis=1) >= p - r).all(axis=1))
    if not len(near):
        return near
    dist = np.linalg.norm(closest_point(tri[near], np.broadcast_to(p, (len(near), 3))) - p, axis=1)
    return near[dist < r]


def _cones_only(faces: np.ndarray, tri: np.ndarray, p: np.ndarray, r: float) -> bool:
    """Whether the faces within ``r`` of ``p`` are one disk around each of ``p``'s fans, and nothing else.

    Faces are joined across shared edges; each piece must hold ``p`` and
    have Euler characteristic 1 (a disk, as the cone over the fan's link
    circle is). A piece away from ``p`` (another sheet within the ball) or
    with a hole (the ball cuts through a bar or a plate around ``p``) makes
    the ball too large.
    """
    near = _faces_near(tri, p, r)
    sub = faces[near]
    edges = np.sort(np.concatenate([sub[:, [0, 1]], sub[:, [1, 2]], sub[:, [2, 0]]]), axis=1)
    owner = np.tile(np.arange(len(near)), 3)
    order = np.lexsort((edges[:, 1], edges[:, 0]))
    edges, owner = edges[order], owner[order]
    same = np.flatnonzero((edges[1:] == edges[:-1]).all(axis=1))
    graph = sparse.coo_matrix((np.ones(len(same)), (owner[same], owner[same + 1])), shape=(len(near), len(near)))
    n, label = csgraph.connected_components(graph, directed=False)
    at_p = (np.linalg.norm(tri[near] - p, axis=2) == 0).any(axis=1)
    if not np.isin(np.arange(n), label[at_p]).all():
        return False
    first = np.r_[True, (edges[1:] != edges[:-1]).any(axis=1)]
    n_edges = np.bincount(label[owner[first]], minlength=n)
    corner = np.unique(np.c_[np.repeat(label, 3), sub.ravel()], axis=0)
    chi = np.bincount(corner[:, 0], minlength=n) - n_edges + np.bincount(label, minlength=n)
    return bool((chi == 1).all())


def carve_pinches(mesh: Any) -> tuple[Any, int]:
    """``mesh`` with a ball of air taken out at each point where it touches itself, and how many were.

    ``mesh``: a closed, outward-oriented surface (a cut solid's, pinches kept
    as two vertex ids at one position). The ball's radius is the first of
    ``CARVE_SPACINGS`` spacings of the default sample within which the faces
    are one disk around each of the pinch's fans (:func:`_cones_only`); a
    pinch where none is, is left. The
    difference is the solid where the winding number of the surface and of
    the balls turned inward is at least 1/2
    (:func:`~medialaxis.mesh.solid.arrangement.solid_surface`).

    Examples
    --------
    Two cubes sharing only a corner (a solid pinch: apart in the interior):

    >>> import numpy as np, trimesh
    >>> from medialaxis.mesh.solid.arrangement import solid_surface
    >>> boxes = [trimesh.creation.box(bounds=b) for b in ([[0, 0, 0], [1, 1, 1]], [[1, 1, 1], [2, 2, 2]])]
    >>> both = trimesh.util.concatenate(boxes)
    >>> cut = solid_surface(both.vertices, both.faces)
    >>> solid = trimesh.Trimesh(cut.vertices, cut.faces, process=False)
    >>> pinch_points(solid.vertices).tolist()
    [[1.0, 1.0, 1.0]]
    >>> carved, n = carve_pinches(solid)
    >>> n, len(pinch_points(carved.vertices)), bool(carved.volume < 2.0)
    (1, 0, True)
    """
    from medialaxis.mesh.sample.sampling import sample_count  # here: sampling imports this package
    from medialaxis.mesh.solid.arrangement import solid_surface
    from medialaxis.mesh.solid.degenerate import coordinate_accuracy

    v = np.asarray(mesh.vertices, np.float64)
    f = np.asarray(mesh.faces, np.int64)
    points = pinch_points(v)
    if not len(points):
        return mesh, 0
    tri = v[f]
    spacing = float(np.sqrt(2.0 / np.sqrt(3.0) * mesh.area / sample_count(None, len(v))))
    balls = []
    for p in points:
        fits = [k * spacing for k in CARVE_SPACINGS if _cones_only(f, tri, p, k * spacing)]
        balls += [(p, fits[0])] if fits else []
    if not balls:
        return mesh, 0
    import trimesh

    unit = trimesh.creation.icosphere(subdivisions=2)
    vertices, faces = [v], [f]
    for p, r in balls:
        faces.append(unit.faces[:, ::-1] + sum(len(x) for x in vertices))  # turned inward: air
        vertices.append(p + r * unit.vertices)
    vertices, faces = np.concatenate(vertices), np.concatenate(faces)
    cut = solid_surface(vertices, faces, coordinate_accuracy(v))
    return type(mesh)(cut.vertices, cut.faces, process=False), len(balls)
