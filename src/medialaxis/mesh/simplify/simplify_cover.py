"""The cover repair of the simplification: spheres added where the surface is farthest outside.

Edge collapses of least quadric error (:mod:`medialaxis.mesh.simplify.qmat`, after
Li et al., "Q-MAT: Computing medial axis transform by quadratic error
minimization", ACM TOG 35(1), 2015) leave the tips of limbs and fins
without a sphere. :func:`cover_repair` adds spheres one at a time at the
surface sample farthest outside the interpolated spheres (the exact gaps of
:mod:`medialaxis.mesh.simplify.envelope`): the medial candidate reaching nearest to it
(:mod:`medialaxis.mesh.simplify.medial_candidates`); where none reaches it (a tip,
where the lambda pruning cut the axis), the end of the medial axis there:
the largest inscribed ball touching two sides among those tangent near it
(:meth:`~medialaxis.mesh.simplify.medial_candidates.MedialCandidates.tip`); where
none of these reaches it either, the shrinking ball there (Ma, Bai, Song and
Wang, "3D medial axis point approximation using nearest neighbors and the
normal field", The Visual Computer 28(1), 2012) for at most ``PATCH_SHARE``
of them, brought inside the mesh (:func:`_inscribed`): a patch.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.mesh.simplify.envelope import envelope_gap
from medialaxis.mesh.simplify.medial_candidates import tangent_bound
from medialaxis.mesh.simplify.simplify_split import split_at

__all__ = ["cover_repair", "PATCH_GAP", "PATCH_SHARE", "SPLIT_GAIN", "TIP_DISC", "TIP_REACH"]

#: In ``mode="medial"``, a surface point that no medial candidate reaches within this share of its
#: gap gets the shrinking ball there instead (a patch: convex corners, where the medial spheres shrink
#: to nothing before their contacts span 90 degrees).
PATCH_GAP = 0.9

#: In ``mode="medial"``, at most this share of :func:`cover_repair`'s spheres are patches (the worst gaps
#: first), then such points are passed over. kitten: 0.1: 1.19% / 97% medial, 0.2: 1.01 / 94%, 0.4: 0.93 / 90%.
PATCH_SHARE = 0.2

#: A patch is inside when its centre is at least ``1 - INSCRIBED`` of its radius deep (:func:`_inscribed`).
INSCRIBED = 1e-3

#: :meth:`~medialaxis.mesh.simplify.medial_candidates.MedialCandidates.tip` looks for the end of the medial axis among the
#: balls tangent within the larger of the gap and this many radii of the patch (the shrinking ball at the point).
TIP_DISC = 2.0

#: Of the tip balls reaching within this share of the gap, the largest is taken (else the one reaching nearest).
TIP_REACH = 0.5

#: A split is kept when the surface point it was made for lies at most this share as deep as before.
SPLIT_GAIN = 0.8

_ONE_EDGE, _NO_FACES = np.array([[0, 1]], np.int64), np.zeros((0, 3), np.int64)


def _medial_ball(p: np.ndarray, n: np.ndarray, tree: cKDTree, samples: np.ndarray, start: float) -> tuple[np.ndarray, float]:
    """The largest ball inside touching the surface at ``p`` (normal ``n``): shrinking ball (Ma et al. 2012).

    Started no larger than :func:`~medialaxis.mesh.simplify.medial_candidates.tangent_bound`.
    """
    r = min(start, float(tangent_bound(p[None], n[None], samples, tree)[0]))
    for _ in range(60):
        c = p - r * n
        d, q = tree.query(c, k=2)
        q = q[1] if np.allclose(samples[q[0]], p) else q[0]
        if np.linalg.norm(samples[q] - c) >= r * (1.0 - 1e-6):
            break
        v = p - samples[q]
        cos = float(v @ n)
        r_new = float(v @ v) / (2.0 * cos) if cos > 1e-12 else 0.0
        if r_new >= r or r_new <= 0.0:
            r = max(min(r_new, r), 0.0)
            break
        r = r_new
    return p - r * n, r


def _inscribed(p: np.ndarray, n: np.ndarray, r: float, signed: Any) -> tuple[np.ndarray, float]:
    """A ball inside the mesh in place of the shrinking ball tangent at ``p`` (normal ``n``) of radius ``r``.

    A shrinking ball among sparse samples is empty of samples but may reach
    out of the surface between them (dog's patches at the tips of its ears
    and paws: centres 0.53-0.99 of their radius deep). Balls tangent at
    ``p`` are nested, so the largest one inside (within ``INSCRIBED`` of its
    radius, exact signed distance) is found by three rounds of 32 radii, to
    ``r / 32768``: it touches ``p`` and the surface elsewhere. Where ``p`` is
    a convex corner or on a crease (its normal is the faces' mean), no ball
    tangent there is inside; where the largest tangent ball inside is at most
    half as large as the ball at the shrinking ball's centre with its radius
    brought to that centre's depth, the latter is taken.
    """
    lo, hi = 0.0, r
    for _ in range(3):
        t = lo + (hi - lo) * np.arange(1, 33) / 32.0
        inside = -signed.exact(p - t[:, None] * n)[0] >= (1.0 - INSCRIBED) * t
        k = int(np.argmin(inside)) if not inside.all() else 32  # the first radius reaching out
        lo, hi = (lo if k == 0 else t[k - 1]), (t[k] if k < 32 else hi)
        if k == 32:
            break
    c = p - r * n
    depth = float(min(r, max(-float(signed.exact(c[None])[0][0]), 0.0)))
    return (p - lo * n, float(lo)) if lo > 0.5 * depth else (c, depth)


def cover_repair(
    centres: np.ndarray, radii: np.ndarray, curve: np.ndarray, faces: np.ndarray, sample: Any, extra: int,
    medial: Any = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Add ``extra`` spheres where the surface is farthest outside the interpolated spheres, or deepest inside.

    Each step takes the worse of the two errors at the surface samples. Outside:
    the new sphere is the medial ball touching the farthest surface point (a
    shrinking ball among the surface samples, so it reaches tips the lambda
    pruning cut; with ``medial``, made to lie inside the mesh), joined by an edge to the sphere with the least power
    distance to its centre (the one it overlaps most): a hanging edge, so the
    topology stays the collapsed mesh's. Inside (with ``medial``'s exact
    signed distance): the triangle or edge whose interpolated sphere holds the
    deepest surface point is split there by an inscribed sphere
    (:func:`~medialaxis.mesh.simplify.simplify_split.split_at`). The gaps are exact
    (:func:`medialaxis.mesh.simplify.envelope.envelope_gap`). Returns ``(centres,
    radii, curve, faces, gaps)``: ``gaps`` is the envelope gap of the result at the samples, kept up to
    date exactly (the ``gaps`` of :func:`~medialaxis.mesh.simplify.envelope.two_sided_distance`).

    References
    ----------
    .. [1] P. Li, B. Wang, F. Sun, X. Guo, C. Zhang, W. Wang, "Q-MAT: Computing medial axis
           transform by quadratic error minimization", ACM Transactions on Graphics
           35(1):8:1-8:16, 2015. doi:10.1145/2753755
    .. [2] J. Ma, S. W. Bae, S. Choi, "3D medial axis point approximation using nearest
           neighbors and the normal field", The Visual Computer 28(1):7-19, 2012.
    """
    x, normals = sample.points, sample.normals
    sample_tree = cKDTree(x)
    signed = None if medial is None else medial.signed
    spheres = np.c_[centres, radii]
    curve, faces = np.asarray(curve, np.int64).reshape(-1, 2), np.asarray(faces, np.int64).reshape(-1, 3)
    exact = envelope_gap(x, centres, radii, curve, faces)  # the mesh's gap; ``gap``: 0 where settled
    gap = exact.copy()
    settled = np.zeros(len(x), bool)  # passed over: no sphere or split helps there
    goal = len(spheres) + extra
    patches = passed = 0
    start = float(radii.max()) * 2.0 if len(radii) else 1.0
    while len(spheres) < goal:  # a point whose medial ball is empty is passed over, not counted
        w, d = int(np.argmax(gap)), int(np.argmin(gap))
        if signed is not None and -gap[d] > max(gap[w], 0.0):
            split = split_at(x[d], spheres, curve, faces, signed, medial)
            trial = None if split is None else _gap_after(x, exact, spheres, curve, faces, *split)
            if trial is None or -trial[d] > SPLIT_GAIN * -gap[d]:  # no split lowers it: passed over
                settled[sample_tree.query(x[d], k=min(16, len(x)))[1]] = True
                gap[settled] = 0.0
                passed += 1
                if passed > extra:
                    break
                continue
            spheres, curve, faces = split
            exact = trial
            gap = np.where(settled, 0.0, trial)
            continue
        if gap[w] <= 0:
            break
        c, r = medial.cover(x[w]) if medial is not None else (x[w], -np.inf)
        if np.linalg.norm(x[w] - c) - r > PATCH_GAP * gap[w]:  # no candidate reaches it: a tip
            c_patch, r_patch = _medial_ball(x[w], normals[w], sample_tree, x, start)
            if signed is not None and r_patch > 0.0:
                c_patch, r_patch = _inscribed(x[w], normals[w], r_patch, signed)
            if medial is not None:  # the end of the medial axis there, or a patch
                c_tip, r_tip = medial.tip(x[w], max(gap[w], TIP_DISC * r_patch), TIP_REACH * gap[w])
                if r_tip > 0.0 and np.linalg.norm(x[w] - c_tip) - r_tip < np.linalg.norm(x[w] - c) - r:
                    c, r = c_tip, r_tip
        if np.linalg.norm(x[w] - c) - r > PATCH_GAP * gap[w]:  # nor a tip ball: a patch
            if medial is not None and patches >= PATCH_SHARE * extra:  # passed over with its neighbours
                passed += 1
                if passed > extra:  # what is left is out of the candidates' reach
                    break
                settled[sample_tree.query(x[w], k=min(16, len(x)))[1]] = True
                gap[settled] = 0.0
                continue
            patches += 1
            c, r = c_patch, r_patch
        if r <= 0.0:
            settled[w] = True
            gap[w] = 0.0
            continue
        link = int(np.argmin(((spheres[:, :3] - c) ** 2).sum(axis=1) - spheres[:, 3] ** 2))
        spheres = np.r_[spheres, [np.r_[c, r]]]
        curve = np.r_[curve, [[link, len(spheres) - 1]]]
        cone = envelope_gap(x, spheres[[link, -1], :3], spheres[[link, -1], 3], _ONE_EDGE, _NO_FACES)
        exact = np.minimum(exact, cone)
        gap = np.where(settled, 0.0, exact)
    return spheres[:, :3], spheres[:, 3], curve, faces, exact


def _rows_not_in(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The rows of ``a`` (index tuples) that ``b`` lacks."""
    have = set(map(tuple, b.tolist()))
    return a[[tuple(r) not in have for r in a.tolist()]] if len(a) else a


def _gap_after(
    x: np.ndarray, gap: np.ndarray, spheres: np.ndarray, curve: np.ndarray, faces: np.ndarray,
    new_spheres: np.ndarray, new_curve: np.ndarray, new_faces: np.ndarray,
) -> np.ndarray:
    """:func:`envelope_gap` of the split mesh, computed again only where the primitives it removed were the nearest."""
    gone_c, gone_f = _rows_not_in(curve, new_curve), _rows_not_in(faces, new_faces)
    made_c, made_f = _rows_not_in(new_curve, curve), _rows_not_in(new_faces, faces)
    out = np.minimum(gap, _pieces_gap(x, new_spheres, made_c, made_f))
    was = _pieces_gap(x, spheres, gone_c, gone_f)
    again = was <= gap + 1e-12 * max(1.0, float(np.abs(gap).max()))
    if again.any():
        out[again] = envelope_gap(x[again], new_spheres[:, :3], new_spheres[:, 3], new_curve, new_faces)
    return out


def _pieces_gap(x: np.ndarray, spheres: np.ndarray, curve: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """:func:`envelope_gap` of the edges ``curve`` and triangles ``faces`` alone (with their corners, not every sphere).

    A cone or slab holds its corner spheres, so these add nothing to its gap; the other spheres are
    left out: the split keeps them, and counting them flagged every point nearest a sphere as changed.
    """
    used, inverse = np.unique(np.r_[curve.ravel(), faces.ravel()], return_inverse=True)
    return envelope_gap(x, spheres[used, :3], spheres[used, 3], inverse[: curve.size].reshape(-1, 2),
                        inverse[curve.size :].reshape(-1, 3))
