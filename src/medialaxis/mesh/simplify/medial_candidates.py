"""Medial candidates for the simplification: spheres of the medial complex that touch two sides.

A sphere of the Voronoi medial complex carries its contacts (the four
samples of its Delaunay tetrahedron). When those on its sphere (within
``ON_SPHERE`` of its radius) span 90 degrees or more as seen from its
centre, the sphere touches the surface on two sides: it stands for the
medial axis, not for a patch of one side. The
simplification (:mod:`medialaxis.mesh.simplify.qmat`, ``mode="medial"``) keeps only
such spheres.

The complex is pruned by lambda (Chazal and Lieutier, "The lambda-medial
axis", Graphical Models, 2005, doi:10.1016/j.gmod.2005.01.002): its small spheres near the tips of
limbs and ears are gone, and a surface point there was covered by a ball
touching one side only. The shrinking balls of the surface samples (Ma, Bae and
Choi, "3D medial axis point approximation using nearest neighbors
and the normal field", The Visual Computer 28(1), 2012) give the medial balls
there too; those whose two contacts span ``SPAN`` join the candidates.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.core.result import MedialAxis
from medialaxis.mesh.simplify._simplify_kernels import PENDING, kd_build, snap_many, span_cosines

__all__ = ["MedialCandidates", "shrinking_balls", "tangent_bound", "inscribed_along", "SPAN", "ON_SPHERE", "SNAP", "DEPTH", "TIP_SAMPLES",
           "TIP_SLACK", "TIP_SPAN", "BOUND_NEIGHBOURS"]

#: Contacts spanning at least this many degrees from the centre make a sphere a candidate (the
#: independent test asks 90 of the surface within 2% of the radius, which spans a little more than
#: the four contacts; at 90 the sheets of a box reaching its right-angled edges fell out).
SPAN = 80.0

#: Only contacts within this share of the radius of a sphere count for its span (0: all). The complex's
#: radii are refined after the Delaunay step, so a contact can lie well off its sphere (gt-vase: median
#: 1.1%, a tenth past 3.8%): the thin walls' spheres then touched one side only. Peers' models at Q-MAT's
#: counts, error / medial share, 0 -> 0.02: dog 1.61 / 86% -> 1.60 / 92%, vase 1.96 / 75% -> 2.03 / 92%,
#: hand 1.59 / 100% unchanged; 0.01: vase 3.32 / 97%.
ON_SPHERE = 0.02

#: Candidates a collapsed sphere is snapped among (nearest in centre and radius).
SNAP = 16

#: A candidate is kept when its centre's depth (exact signed distance) is within this share of its radius.
DEPTH = 0.02

#: :func:`shrinking_balls` starts each ball no larger than the least ball tangent at its point through one of
#: this many nearest samples (:func:`tangent_bound`).
BOUND_NEIGHBOURS = 16

#: :meth:`MedialCandidates.tip` takes the shrinking balls of at most this many samples near the point.
TIP_SAMPLES = 64

#: The tip balls touch their sample within this share of their radius (:func:`inscribed_along`). dog at 49
#: spheres: 0.02: 96% medial (a ball 1.4% of the diagonal touching its sample 2-4% off), 0.005: 98%.
TIP_SLACK = 0.005

#: A tip ball's contacts span at least this many degrees (the medial test's own; ``SPAN`` for the
#: candidates): kitten at 200 spheres, 80: 92.0% medial (20 tip balls, 12 of them spanning 83-90 degrees in
#: the independent test), 90: 94.5%.
TIP_SPAN = 90.0


def shrinking_balls(points: np.ndarray, normals: np.ndarray, start: float | None = None, samples: np.ndarray | None = None,
                    tree: cKDTree | None = None, steps: int = 40) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The largest ball inside touching each of ``points`` (outward ``normals``): shrinking balls, all at once.

    The balls are empty of ``samples`` (default ``points``; ``tree`` is
    theirs when given). The ball at ``p`` starts with radius ``start`` (default: the sample's
    box diagonal; a bound on the largest inscribed ball is faster) and shrinks to the
    ball through ``p`` and its nearest other sample ``q`` until no sample is
    nearer its centre than its radius (Ma et al. 2012).

    Returns
    -------
    centres : (n, 3) ndarray
    radii : (n,) ndarray
        ``0`` where no ball was found (the normal points along the surface).
    other : (n, 3) ndarray
        The second contact ``q`` of each ball.

    References
    ----------
    .. [1] J. Ma, S. W. Bae, S. Choi, "3D medial axis point approximation using nearest
           neighbors and the normal field", The Visual Computer 28(1):7-19, 2012.
    """
    points = np.asarray(points, np.float64)
    normals = np.asarray(normals, np.float64)
    samples = points if samples is None else np.asarray(samples, np.float64)
    tree = cKDTree(samples) if tree is None else tree
    n = len(points)
    if start is None:
        start = float(np.linalg.norm(np.ptp(points, axis=0))) if n else 0.0
    radius = np.minimum(start, tangent_bound(points, normals, samples, tree))
    other = points.copy()
    active = np.arange(n)
    for _ in range(steps):
        if not len(active):
            break
        p, nrm, r = points[active], normals[active], radius[active]
        d, q = tree.query(p - r[:, None] * nrm, k=2)
        self_hit = np.linalg.norm(samples[q[:, 0]] - p, axis=1) <= 1e-12 * (1.0 + r)
        near, dist = np.where(self_hit, q[:, 1], q[:, 0]), np.where(self_hit, d[:, 1], d[:, 0])
        done = dist >= r * (1.0 - 1e-6)
        v = p - samples[near]
        cos = np.einsum("ij,ij->i", v, nrm)
        shrunk = np.where(cos > 1e-12, np.einsum("ij,ij->i", v, v) / (2.0 * np.maximum(cos, 1e-300)), 0.0)
        stuck = ~done & ((shrunk >= r) | (shrunk <= 0.0))
        radius[active[stuck]] = np.clip(shrunk[stuck], 0.0, r[stuck])
        moving = ~done & ~stuck
        radius[active[moving]] = shrunk[moving]
        other[active[~stuck]] = samples[near[~stuck]]
        active = active[moving]
    return points - radius[:, None] * normals, radius, other


def tangent_bound(points: np.ndarray, normals: np.ndarray, samples: np.ndarray, tree: cKDTree) -> np.ndarray:
    """An upper bound on each shrinking ball's radius: the least radius of the balls tangent at the point through
    one of its ``BOUND_NEIGHBOURS`` nearest samples (the empty ball tangent there holds none of them).

    The ball tangent at ``p`` (outward normal ``n``) through ``q`` has radius ``|p - q|^2 / (2 (p - q).n)``, and
    the larger ones tangent there hold ``q``: the largest empty one is no larger. Started from this bound, the
    shrinking balls skip their first steps, whose centres lie deep inside, where many samples are nearly
    equidistant (near a sphere's centre the k-d tree visits all of them: gt-sphere-soup's tip balls took 4 s).
    """
    k = min(BOUND_NEIGHBOURS, len(samples))
    if not len(points) or k < 2:
        return np.full(len(points), np.inf)
    _, q = tree.query(points, k=k)
    v = (points[:, None, :] - samples[q]).reshape(-1, 3)
    cos = np.einsum("ij,ij->i", v, np.repeat(normals, k, axis=0))
    rho = np.where(cos > 1e-12, np.einsum("ij,ij->i", v, v) / (2.0 * np.maximum(cos, 1e-300)), np.inf)
    return rho.reshape(-1, k).min(axis=1)


def inscribed_along(points: np.ndarray, normals: np.ndarray, lengths: np.ndarray, signed: Any, rounds: int = 12,
                    slack: float = DEPTH) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Balls inside centred on the inward normals of ``points``, as far in as they still touch their point.

    The centre ``p - t n`` (``n`` the outward normal, ``t`` at most ``lengths``) is taken as far in as its
    depth (``signed.exact``) stays at least ``(1 - slack) t``: the ball of that depth touches the surface
    within ``slack`` of its radius of ``p`` (at a corner of a faceted surface no ball tangent at ``p`` is
    inside). The depth is nearly ``t`` up to the medial axis and falls behind it past there, so ``rounds``
    of bisection find it. Returns the centres, their depths (the radii; ``0`` where no ball touches ``p``)
    and each ball's second contact: the closest surface point to the centre of the nearest one tried past it.
    """
    lo, hi = np.zeros(len(lengths)), np.asarray(lengths, np.float64).copy()
    depth, near = signed.exact(points - hi[:, None] * normals)
    inside = -depth >= (1.0 - slack) * hi
    lo[inside] = hi[inside]
    other = np.asarray(near, np.float64).copy()
    todo = np.flatnonzero(~inside & (hi > 0.0))
    for _ in range(rounds):
        if not len(todo):
            break
        t = 0.5 * (lo[todo] + hi[todo])
        depth, near = signed.exact(points[todo] - t[:, None] * normals[todo])
        good = -depth >= (1.0 - slack) * t
        lo[todo[good]] = t[good]
        hi[todo[~good]] = t[~good]
        other[todo[~good]] = near[~good]
    centres = points - lo[:, None] * normals
    radii = np.where(lo > 0.0, np.maximum(-signed.exact(centres)[0], 0.0), 0.0)
    return centres, radii, other


def _spans(centres: np.ndarray, contacts: np.ndarray, radii: np.ndarray | None = None) -> np.ndarray:
    """Per sphere: do its ``contacts`` (n, k, 3) span at least ``SPAN`` degrees as seen from its centre?

    With ``radii``, only the contacts within ``ON_SPHERE`` of the radius count.
    """
    centres, contacts = np.ascontiguousarray(centres, np.float64), np.ascontiguousarray(contacts, np.float64)
    on = np.zeros(len(centres)) if radii is None else np.ascontiguousarray(radii, np.float64)
    return span_cosines(centres, contacts, on, 0.0 if radii is None else ON_SPHERE) <= np.cos(np.radians(SPAN))


class MedialCandidates:
    """Medial candidates: the spheres of the medial complex whose contacts span at least ``SPAN``.

    From ``ma`` and the complex it was made from (``ma.raw``: the full
    complex under the compact one), each sphere with its contacts (the
    samples of its Delaunay tetrahedron, on its sphere). One whose contacts
    span 90 degrees or more as seen from its centre touches two sides of the
    surface: it stands for the medial axis. Collapsed spheres are replaced by
    the candidate nearby of least quadric error (:meth:`snap_all`); spheres
    added where the surface is farthest out are the candidate balls
    reaching nearest to it (:meth:`cover`).
    """

    def __init__(self, ma: MedialAxis, sample: Any = None, signed: Any = None) -> None:
        sources = [m for m in (ma, ma.raw) if m is not None and m.dim == 3 and "contacts" in m.extras]
        centres = [m.points for m in sources]
        radii = [m.radii for m in sources]
        contacts = [np.asarray(m.extras["contacts"]) for m in sources]
        centres = np.concatenate(centres) if centres else np.zeros((0, 3))
        radii = np.concatenate(radii) if radii else np.zeros(0)
        contacts = np.concatenate(contacts) if contacts else np.zeros((0, 4, 3))
        ok = _spans(centres, contacts, radii if ON_SPHERE else None) & (radii > 0)
        self.sample = sample if sample is not None and len(sample.points) > 2 else None
        self.sample_tree = cKDTree(sample.points) if self.sample is not None else None
        self.start = 1.5 * float(radii.max()) if len(radii) else None
        self.spheres = np.c_[centres, radii][ok]
        self.tree = cKDTree(self.spheres) if len(self.spheres) else None
        self.kd = kd_build(self.spheres)  # the snaps' (compiled)
        touch = contacts[ok]
        self.contact_tree = cKDTree(touch.reshape(-1, 3)) if len(self.spheres) else None
        self.per = touch.shape[1]
        self.signed = signed
        self.state = np.zeros(len(self.spheres), np.int8)  # 1: its radius is its centre's depth, -1: not, 0: not asked, 2: pending

    def inscribed(self, index: np.ndarray) -> np.ndarray:
        """Which of the candidates ``index`` are inscribed: the centre's depth within ``DEPTH`` of the radius.

        A Voronoi sphere of a sparse sample may poke out between its samples
        (or stay clear of the surface); asked once per candidate, when first met.
        """
        if self.signed is None:
            return np.ones(len(index), bool)
        ask = np.unique(index[self.state[index] == 0])
        if len(ask):
            depth = -self.signed.exact(self.spheres[ask, :3])[0]
            r = self.spheres[ask, 3]
            self.state[ask] = np.where(np.abs(depth - r) <= DEPTH * r, 1, -1)
        return self.state[index] > 0

    def snap_all(self, spheres: np.ndarray, qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
        """Each of ``spheres`` snapped to the candidate of least quadric error ``(qa[i], qb[i])``.

        Among the ``SNAP`` candidates nearest in (centre, radius) that are
        inscribed (:meth:`inscribed`), else among ``4 SNAP``, else all of these
        (:func:`~medialaxis.mesh.simplify._simplify_kernels.snap_one`).
        """
        if self.tree is None or not len(spheres):
            return spheres.copy()
        index = snap_many(spheres, qa, qb, self.spheres, self.state, self.kd, SNAP)
        while not self.settle():  # again where a candidate taken before it was asked is not inscribed
            again = np.flatnonzero(self.state[index] < 0)
            index[again] = snap_many(spheres[again], qa[again], qb[again], self.spheres, self.state, self.kd, SNAP)
        return self.spheres[index]

    def settle(self) -> bool:
        """Ask the candidates the snaps took before asking (``PENDING``); whether all are inscribed."""
        pending = np.flatnonzero(self.state == PENDING)
        if not len(pending):
            return True
        self.state[pending] = 0
        return bool(self.inscribed(pending).all())

    def tip(self, x: np.ndarray, radius: float, within: float) -> tuple[np.ndarray, float]:
        """An inscribed ball touching two sides, tangent at a sample within ``radius`` of ``x``, reaching near ``x``.

        Near a tip the lambda pruning left no candidate and the shrinking balls of the samples next to ``x`` touch
        one side only. Here the shrinking balls of up to ``TIP_SAMPLES`` samples spread over the disc of ``radius``
        about ``x``, each moved in along its normal as far as it still touches its sample (within ``TIP_SLACK``
        of its radius; exact signed distance: :func:`inscribed_along`), that touch two sides: their two contacts
        (the sample and where the ball one step further in reaches out) span ``TIP_SPAN``, or the samples within
        ``ON_SPHERE`` of their sphere do (a cap: the end of the axis at a rounded tip). Of those whose sphere
        reaches within ``within`` of ``x``, the largest (the most stable under a change of the surface: the tip
        balls shrink to the sampling's scale); else the one reaching nearest. ``(x, 0.0)`` when there is none.
        """
        if self.sample is None or self.signed is None:
            return x, 0.0
        points = self.sample.points
        near = np.asarray(self.sample_tree.query_ball_point(x, radius), np.int64)
        near = near[np.argsort(np.linalg.norm(points[near] - x, axis=1), kind="stable")]
        if len(near) > TIP_SAMPLES:  # spread from the point outward
            near = near[np.linspace(0, len(near) - 1, TIP_SAMPLES).astype(np.int64)]
        if not len(near):
            return x, 0.0
        p, n = points[near], self.sample.normals[near]
        _, r, _ = shrinking_balls(p, n, self.start, points, self.sample_tree)
        c, r, q = inscribed_along(p, n, r, self.signed, slack=TIP_SLACK)
        two = span_cosines(c, np.stack([p, q], axis=1), r, 0.0)
        least = np.minimum(two, span_cosines(c, self._band(c, r, p), r, ON_SPHERE))
        ok = (r > 0.0) & (least <= np.cos(np.radians(TIP_SPAN)))
        if not ok.any():
            return x, 0.0
        reach = np.where(ok, np.linalg.norm(x - c, axis=1) - r, np.inf)
        close = reach <= within
        best = int(np.argmax(np.where(close, r, -1.0))) if close.any() else int(np.argmin(reach))
        return c[best].copy(), float(r[best])

    def _band(self, centres: np.ndarray, radii: np.ndarray, own: np.ndarray, most: int = 64) -> np.ndarray:
        """(n, k, 3): the samples within ``ON_SPHERE`` of each sphere (at most ``most``, padded with ``own``)."""
        points = self.sample.points
        lists = self.sample_tree.query_ball_point(centres, (1.0 + ON_SPHERE) * radii)
        out = np.repeat(own[:, None, :], most + 1, axis=1)
        for k, found in enumerate(lists):
            found = np.asarray(found, np.int64)
            found = found[np.linalg.norm(points[found] - centres[k], axis=1) >= (1.0 - ON_SPHERE) * radii[k]]
            if len(found) > most:
                found = found[np.linspace(0, len(found) - 1, most).astype(np.int64)]
            out[k, 1 : 1 + len(found)] = points[found]
        return out

    def cover(self, x: np.ndarray) -> tuple[np.ndarray, float]:
        """The candidate ball reaching nearest to ``x`` among those touching the surface near it.

        Besides the complex's, the shrinking balls of the ``SNAP`` samples
        nearest ``x`` whose two contacts span ``SPAN`` and that are inscribed
        (the balls the lambda pruning left out near tips).
        """
        if self.tree is None:
            return x, 0.0
        _, near = self.contact_tree.query(x, k=min(4 * SNAP, len(self.spheres) * self.per))
        index = np.unique(np.atleast_1d(near) // self.per)
        ok = self.inscribed(index)
        t = self.spheres[index[ok] if ok.any() else index]
        if self.sample is not None:
            _, near = self.sample_tree.query(x, k=min(SNAP, len(self.sample.points)))
            p = self.sample.points[near]
            c, r, q = shrinking_balls(p, self.sample.normals[near], self.start, self.sample.points, self.sample_tree)
            keep = _spans(c, np.stack([p, q], axis=1)) & (r > 0)
            if keep.any() and self.signed is not None:
                depth = -self.signed.exact(c[keep])[0]
                keep[keep] = np.abs(depth - r[keep]) <= DEPTH * r[keep]
            t = np.concatenate([t, np.c_[c, r][keep]])
        best = int(np.argmin(np.linalg.norm(t[:, :3] - x, axis=1) - t[:, 3]))
        return t[best, :3].copy(), float(t[best, 3])
