"""Splits of the simplified medial mesh where its interpolated spheres reach out of the surface.

A medial mesh stands for the union of the spheres interpolated linearly (in
centre and radius) over its edges and triangles. The distance to a contact
point is convex along a sheet, so the interpolated radius over a large
triangle exceeds the distance to the surface between its corners: the
interpolated spheres reach out of the surface although every corner sphere
is inscribed. Voronoi facets spanning twice their radius already do this in
the full complex (cheburashka: 2.5% of the diagonal), and the collapses of
the simplification make such triangles larger. The two-sided error counts
it (a surface point inside the union is as far from its boundary as its
depth); at 200 spheres it made most of the error on the tuning models.

:func:`split_at` puts an inscribed sphere where the interpolated sphere
holding a surface point deepest is centred, splitting the triangle there
(into three, or its side and the triangles on it into two each when the
point lies near the side) or the curve edge: a subdivision, so the mesh's
topology is kept. :func:`~medialaxis.mesh.simplify.simplify_cover.cover_repair`
calls it when the deepest surface point inside is deeper than the farthest
one outside is far.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["split_at", "SIDE"]

#: A point of a triangle with a barycentric weight below this splits the side opposite it (the triangles on
#: it into two each), not the triangle into three: no sliver next to the side.
SIDE = 0.15

_STEPS = 8
_I, _J = np.meshgrid(np.arange(_STEPS + 1), np.arange(_STEPS + 1))
_KEEP = _I + _J <= _STEPS
#: Barycentric grid over a triangle (an eighth of its sides apart) and the parameters along an edge.
_GRID = np.c_[_I[_KEEP], _J[_KEEP], _STEPS - _I[_KEEP] - _J[_KEEP]] / _STEPS
_LINE = np.linspace(0.0, 1.0, 2 * _STEPS + 1)


def _deepest(p: np.ndarray, spheres: np.ndarray, curve: np.ndarray, faces: np.ndarray) -> tuple[str, int, np.ndarray, np.ndarray]:
    """The interpolated sphere holding ``p`` deepest: ``(kind, index, weights, sphere)`` (``kind`` "face" or "edge")."""
    best: tuple[float, str, int, np.ndarray, np.ndarray] = (-np.inf, "", -1, np.zeros(0), np.zeros(4))
    for kind, prims, weights in (("face", faces, _GRID), ("edge", curve, np.c_[1.0 - _LINE, _LINE])):
        if not len(prims):
            continue
        s = np.einsum("gk,pkd->pgd", weights, spheres[prims])
        depth = s[..., 3] - np.linalg.norm(s[..., :3] - p, axis=2)
        k, g = np.unravel_index(int(np.argmax(depth)), depth.shape)
        if depth[k, g] > best[0]:
            best = (float(depth[k, g]), kind, int(k), weights[g], s[k, g])
    return best[1:]


def _inscribed(centre: np.ndarray, signed: Any, medial: Any) -> np.ndarray | None:
    """The sphere to insert at ``centre``: a medial candidate near it (touching two sides), else the inscribed one."""
    depth = -float(signed.exact(centre[None])[0][0])
    if depth <= 0.0:
        return None
    own = np.r_[centre, depth]
    if medial is None or medial.tree is None:
        return own
    dist, near = medial.tree.query(own, k=min(8, len(medial.spheres)))
    near, dist = np.atleast_1d(near), np.atleast_1d(dist)
    ok = medial.inscribed(near) & (dist <= 0.5 * depth)
    return medial.spheres[near[ok][0]].copy() if ok.any() else own


def split_at(
    p: np.ndarray, spheres: np.ndarray, curve: np.ndarray, faces: np.ndarray, signed: Any, medial: Any = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """``(spheres, curve, faces)`` with a sphere inserted where an interpolated sphere holds ``p`` deepest.

    ``None`` when that sphere is a corner's own (a split cannot lower it) or
    its centre lies outside the surface. ``signed`` gives the exact signed
    distance (``signed.exact``); ``medial`` (a
    :class:`~medialaxis.mesh.simplify.medial_candidates.MedialCandidates`) the medial
    spheres the new one is taken among when one is near.
    """
    kind, k, w, s = _deepest(p, spheres, curve, faces)
    if not kind or w.max() > 1.0 - 1e-9:
        return None
    new = _inscribed(s[:3], signed, medial)
    if new is None:
        return None
    m = len(spheres)
    spheres = np.r_[spheres, new[None]]
    if kind == "edge":
        a, b = curve[k]
        return spheres, np.r_[np.delete(curve, k, axis=0), [[a, m], [m, b]]], faces
    tri = faces[k]
    if w.min() >= SIDE:
        split = np.array([[tri[0], tri[1], m], [tri[1], tri[2], m], [tri[2], tri[0], m]])
        return spheres, curve, np.r_[np.delete(faces, k, axis=0), split]
    u, v = tri[np.argsort(w)[1:]]  # the side opposite the smallest weight
    on = np.isin(faces, [u, v]).sum(axis=1) == 2
    halves = []
    for f in faces[on]:
        o = f[(f != u) & (f != v)][0]
        halves += [[u, m, o], [m, v, o]]
    return spheres, curve, np.r_[faces[~on], np.array(halves, np.int64).reshape(-1, 3)]
