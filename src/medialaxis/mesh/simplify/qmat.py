"""Q-MAT-style simplification of a medial mesh by quadric error minimisation on spheres.

The step past the papers (Li, Wang, Sun, Guo, Zhang and Wang, "Q-MAT:
Computing medial axis transform by quadratic error minimization", ACM TOG
35(1), 2015). Each medial vertex is a sphere ``s = (c, r)`` in R^4. A contact point
``p`` with outward surface normal ``n`` gives the tangent plane of the input
surface there; the signed distance of sphere ``s`` to that plane is
``n . (p - c) - r``, linear in ``s``, so its square is a quadric in R^4 (the
spherical quadric error metric, SQEM). Each vertex starts with the quadric
of its contacts (the four samples on its Delaunay sphere, normals taken
along the radius). Edges are collapsed cheapest first; the merged sphere
minimises the sum of the two quadrics (kept near the two it replaces), and
the quadrics add. Collapses alone leave the tips of limbs and fins without a
sphere, so for ``simplify=n`` a quarter of the spheres is kept back and then
placed where the surface is farthest from the interpolated spheres, or, where
the interpolated spheres of a large triangle or edge reach out of the surface
(a surface point inside them deeper than the farthest one outside is far),
split there by an inscribed sphere
(:func:`medialaxis.mesh.simplify.simplify_cover.cover_repair`, :mod:`medialaxis.mesh.simplify.simplify_split`). The result is judged by the two-sided Hausdorff
distance between the input surface and the boundary of the union of the
spheres interpolated over the simplified mesh (vertices, edges and
triangles), as Q-MAT does, computed on the exact envelope
(:mod:`medialaxis.mesh.simplify.envelope`).

By default (``mode="medial"``) the spheres stand for the medial axis: the
complex's spheres and each collapse's optimum are replaced by the nearby
inscribed sphere whose contacts span 90 degrees or so (it touches two
sides), and the spheres added at the farthest surface points are such
spheres too (:mod:`medialaxis.mesh.simplify.medial_candidates`; at a tip the
lambda pruning cut, the end of the axis there:
:meth:`~medialaxis.mesh.simplify.medial_candidates.MedialCandidates.tip`), but for at
most ``simplify_cover.PATCH_SHARE`` of them, patches where no such sphere reaches.
``"packing"`` (before issue 31) fills the gaps along one side with small
balls (a torus at 40 spheres: 60% of the spheres touch two sides).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from medialaxis.core.graph import sheet_edges
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InvalidInputError
from medialaxis.mesh.medial.compact import sphere_quadrics
from medialaxis.mesh.simplify._simplify_kernels import collapse, kd_build
from medialaxis.mesh.simplify.envelope import surface_sample, two_sided_distance
from medialaxis.mesh.simplify.medial_candidates import SNAP, MedialCandidates
from medialaxis.mesh.simplify.simplify_cover import cover_repair

__all__ = ["simplify_medial_mesh", "check_simplify", "REGULARISATION"]

#: Weight (relative to the mean quadric scale) pulling a merged sphere toward
#: the two it replaces; keeps the 4x4 systems well posed on flat sheets.
REGULARISATION = 1e-3

#: Share of the spheres of ``simplify=n`` added after the collapses, each at
#: the medial ball touching the surface point farthest from the simplified
#: mesh's spheres, joined to the sphere it overlaps most (:func:`medialaxis.mesh.simplify.simplify_cover.cover_repair`).
#: Ten real models at 200 spheres, median / worst two-sided error measured apart:
#: 0.1: 1.54 / 2.15%, 0.15: 1.52 / 2.15%, 0.2: 1.49 / 2.15%, 0.25: 1.45 / 2.15%.
REPAIR_SHARE = 0.25

#: ``mode`` of :func:`simplify_medial_mesh` (``"medial"``: spheres touching two sides, ``"packing"``: the
#: collapses' optima and shrinking balls, the default before issue 31).
MODES = ("medial", "packing")

#: Sphere count the search for ``simplify=e`` (an error bound) starts from, doubling.
MIN_SEARCH = 32


def check_simplify(simplify: Any, mode: str = "medial") -> None:
    """Validate ``simplify`` (an int >= 1, spheres to keep, or a float in (0, 1), an error bound) and ``mode``."""
    if mode not in MODES:
        raise InvalidInputError(f"simplify_mode must be one of {', '.join(MODES)}, got {mode!r}")
    if isinstance(simplify, bool):
        raise InvalidInputError(f"simplify must be an int or a float in (0, 1), got {simplify!r}")
    if isinstance(simplify, (int, np.integer)):
        if simplify < 1:
            raise InvalidInputError(f"simplify must keep at least 1 sphere, got {simplify}")
        return
    if isinstance(simplify, (float, np.floating)) and 0.0 < simplify < 1.0:
        return
    raise InvalidInputError(
        f"simplify must be a number of spheres (int) or an error bound in (0, 1) of the diagonal, got {simplify!r}"
    )


def _initial_quadrics(ma: MedialAxis) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per-vertex SQEM ``(A, b, c)`` with error ``s.A.s - 2 b.s + c`` from the contacts."""
    contacts = ma.contacts if "contacts" in ma.extras else ma.points[:, None, :]
    return sphere_quadrics(ma.points, contacts)


def simplify_medial_mesh(
    ma: MedialAxis, simplify: int | float, surface: Any = None, signed: Any = None, mode: str = "medial"
) -> MedialAxis:
    """Reduce a medial mesh to fewer spheres by edge collapses of least spherical quadric error.

    Parameters
    ----------
    ma : MedialAxis
        A 3D medial mesh (``points``, ``radii``, ``faces``/``edges``); the
        ``contacts`` extra of :func:`medialaxis.mesh.voronoi.voronoi_medial_axis`
        gives the quadrics. The compact complex (the Voronoi route's default,
        hundreds of spheres) is simplified in a few seconds with a smaller
        error than its full complex (tens of thousands).
    simplify : int or float
        ``int``: number of spheres to keep; when ``ma`` holds fewer, the
        missing ones are placed by the cover repair (at most ``simplify`` in all: it stops once no surface
        sample is left outside, or none left can be reached by an inscribed sphere: kitten at 200 gives 193).
        ``float`` in (0, 1): a bound on the two-sided error, as a fraction of
        the bounding-box diagonal: the fewest spheres (found to a tenth by
        doubling from 32, then bisection) whose measured ``hausdorff`` is
        within it; ``metadata["target_met"]`` says whether any count up to
        twice ``len(ma.points)`` met it (if not, the most accurate one is
        returned). Without a surface to measure against, the collapses stop
        before the first whose root quadric error exceeds the bound.
    surface : trimesh.Trimesh, optional
        The input surface, for the Hausdorff distance (default ``ma.shape``).
    signed : SignedDistance, optional
        Of ``surface``, when the caller has one (made here otherwise).
    mode : {"medial", "packing"}
        ``"medial"`` (default): the spheres are inscribed spheres of the
        medial complex (``ma`` or the full complex ``ma.raw``) or shrinking
        balls whose contacts span at least 90 degrees from the centre (they
        touch two sides), but for at most ``simplify_cover.PATCH_SHARE`` of the spheres
        added at the farthest surface points. ``"packing"``: the optima and
        shrinking balls as they come (a tighter fill, lower error, many
        spheres touching one side only; ``benchmarks/bench_simplify_medial.py``).

    Returns
    -------
    MedialAxis
        ``points``, ``radii`` of the kept spheres, ``faces`` and ``edges``
        (curve pieces not bounding a triangle); ``raw`` is the complex simplified. Metadata:
        ``n_spheres``, ``timings["simplify"]`` (seconds; ``"simplify_cpu"``: CPU seconds), ``hausdorff`` (two-sided, input surface vs. the
        boundary of the interpolated spheres), ``hausdorff_surface_to_mat``,
        ``hausdorff_mat_to_surface``, ``diagonal`` (the distances are those of
        :func:`medialaxis.mesh.simplify.envelope.two_sided_distance`; absent without a
        surface).

    Raises
    ------
    InvalidInputError
        If ``simplify`` is not valid or ``ma`` is not 3D.

    References
    ----------
    .. [1] P. Li, B. Wang, F. Sun, X. Guo, C. Zhang, W. Wang, "Q-MAT: Computing medial axis
           transform by quadratic error minimization", ACM Transactions on Graphics
           35(1):8:1-8:16, 2015. doi:10.1145/2753755
    .. [2] J.-M. Thiery, E. Guy, T. Boubekeur, "Sphere-Meshes: Shape approximation using
           spherical quadric error metrics", ACM Transactions on Graphics (Proc. SIGGRAPH Asia),
           2013. doi:10.1145/2508363.2508384
    .. [3] M. Garland, P. S. Heckbert, "Surface simplification using quadric error metrics",
           Proc. SIGGRAPH 97, 209-216, 1997. doi:10.1145/258734.258849

    Examples
    --------
    >>> import trimesh
    >>> from medialaxis.mesh.voronoi import voronoi_medial_axis
    >>> box = trimesh.creation.box(extents=(2, 1, 0.5))
    >>> s = simplify_medial_mesh(voronoi_medial_axis(box, samples=3000), 40)
    >>> len(s.points)
    40
    """
    check_simplify(simplify, mode)
    t_start, cpu_start = time.perf_counter(), time.process_time()
    if ma.dim != 3:
        raise InvalidInputError("simplify applies to 3D medial meshes")
    if surface is None:
        surface = ma.shape
    measured = surface is not None and hasattr(surface, "vertices")
    points = np.asarray(surface.vertices) if measured else ma.points
    diag = float(np.linalg.norm(np.ptp(points, axis=0))) if len(points) else 0.0
    sample = surface_sample(surface) if measured else None
    metadata = dict(ma.metadata, simplified=True, diagonal=diag, simplify_mode=mode)
    if measured and signed is None:
        from medialaxis.mesh.sample.signed_distance import SignedDistance

        signed = SignedDistance(surface)  # one for every count tried
    medial = MedialCandidates(ma, sample, signed) if mode == "medial" else None
    if isinstance(simplify, (int, np.integer)):
        parts, gaps = _reduce(ma, int(simplify), None, sample, medial)
        errors = two_sided_distance(*parts, surface, sample, signed=signed, gaps=gaps) if measured else None
    elif measured:
        parts, errors = _fewest(ma, float(simplify) * diag, surface, sample, signed, medial)
        metadata["target_met"] = max(errors) <= float(simplify) * diag
    else:
        parts, errors = _reduce(ma, 1, float(simplify) * diag, None)[0], None
    centres, radii, curve, out_faces = parts
    if errors is not None:
        h_sm, h_ms = errors
        metadata.update(hausdorff=max(h_sm, h_ms), hausdorff_surface_to_mat=h_sm, hausdorff_mat_to_surface=h_ms)
    metadata["n_spheres"] = int(len(centres))
    metadata["timings"] = dict(ma.metadata.get("timings", {}), simplify=time.perf_counter() - t_start,
                               simplify_cpu=time.process_time() - cpu_start)
    edges = np.concatenate([np.asarray(curve, np.int64).reshape(-1, 2), sheet_edges(out_faces)])  # as every surface
    return MedialAxis(centres, radii, edges, out_faces, metadata=metadata, shape=ma.shape, raw=ma)


def _fewest(
    ma: MedialAxis, bound: float, surface: Any, sample: Any, signed: Any, medial: Any
) -> tuple[tuple, tuple[float, float]]:
    """The fewest spheres (to a tenth) whose two-sided error is at most ``bound``: doubling, then bisection.

    The search goes up to twice the spheres ``ma`` holds (those past its
    own are placed by the cover repair); when even these miss the bound, the
    most accurate result tried is returned.
    """
    tried: dict[int, tuple[tuple, tuple[float, float]]] = {}

    def error(k: int) -> float:
        if k not in tried:
            parts, gaps = _reduce(ma, k, None, sample, medial)
            tried[k] = (parts, two_sided_distance(*parts, surface, sample, signed=signed, gaps=gaps))
        return max(tried[k][1])

    cap = 2 * len(ma.points) + MIN_SEARCH
    lo, hi = 0, min(MIN_SEARCH, cap)
    while error(hi) > bound and hi < cap:
        lo, hi = hi, min(2 * hi, cap)
    if error(hi) > bound:
        return min(tried.values(), key=lambda t: max(t[1]))
    while hi - lo > max(1, hi // 10):
        mid = (lo + hi) // 2
        if error(mid) <= bound:
            hi = mid
        else:
            lo = mid
    return tried[hi]


def _reduce(ma: MedialAxis, count: int, bound: float | None, sample: Any, medial: Any = None) -> tuple:
    """``(centres, radii, edges, faces)`` of ``ma`` collapsed to ``count`` spheres, or until the root quadric error passes ``bound``,
    and the envelope gap at the ``sample``'s points when the cover repair has it (else ``None``).

    With a surface ``sample``, ``REPAIR_SHARE`` of the ``count`` spheres (or all
    that ``ma`` lacks) are placed last by :func:`~medialaxis.mesh.simplify.simplify_cover.cover_repair`.
    """
    n = len(ma.points)
    spheres = np.c_[ma.points, ma.radii]
    qa, qb, qc = _initial_quadrics(ma)
    if medial is not None:  # the compact complex's spheres are refitted, and a third of them touch one side only
        spheres = medial.snap_all(spheres, qa, qb)
    reg = REGULARISATION * float(np.mean(np.trace(qa, axis1=1, axis2=2))) if n else 0.0
    target = count
    repair = 0
    if sample is not None and bound is None:
        # a share of the spheres go where the collapsed mesh leaves the surface farthest (tips, limbs)
        repair = int(REPAIR_SHARE * target) if target >= 20 else 0
        repair = max(repair, target - n)  # a compact complex may hold fewer spheres than asked
    target -= repair

    edges = np.concatenate([ma.edges, ma.faces[:, [0, 1]], ma.faces[:, [1, 2]], ma.faces[:, [2, 0]]]).astype(np.int64)
    snap = medial is not None and medial.tree is not None
    cand, state, tree = (medial.spheres, medial.state, medial.kd) if snap else (_NO_SPHERES, _NO_STATE, kd_build(_NO_SPHERES))
    while True:  # again when a candidate a snap took before asking it is not inscribed
        out, into = collapse(spheres, qa, qb, qc, reg, edges.reshape(-1, 2), target, np.inf if bound is None else bound,
                             snap, cand, state, tree, SNAP)
        if not snap or medial.settle():
            break
    spheres, keep, out_faces, curve = out, *_collapsed_mesh(into, ma.faces, edges)
    centres, radii = spheres[keep, :3], np.maximum(spheres[keep, 3], 0.0)
    gaps = None
    if repair:
        centres, radii, curve, out_faces, gaps = cover_repair(centres, radii, curve, out_faces, sample, repair, medial)
    return (centres, radii, curve, out_faces), gaps


_NO_SPHERES, _NO_STATE = np.zeros((0, 4)), np.zeros(0, np.int8)


def _distinct(rows: np.ndarray) -> np.ndarray:
    """Number of distinct entries of each row of three."""
    s = np.sort(rows, axis=1)
    return 1 + (s[:, 1] != s[:, 0]) + (s[:, 2] != s[:, 1])


def _collapsed_mesh(into: np.ndarray, faces: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, ...]:
    """``(kept, faces, curve)`` after the collapses ``into`` (sphere ``j`` merged into ``into[j]``, ``-1``: kept).

    A triangle goes when two of its corners were merged; the curve is the
    merged mesh's edges that bound no triangle, both in the kept spheres'
    numbering, rows sorted and unique.
    """
    n = len(into)
    rep = np.where(into >= 0, into, np.arange(n))
    while True:  # follow the merges to the sphere kept
        nxt = rep[rep]
        if np.array_equal(nxt, rep):
            break
        rep = nxt
    keep = np.flatnonzero(into < 0)
    new = np.full(n, -1, np.int64)
    new[keep] = np.arange(len(keep))
    faces = faces.reshape(-1, 3)
    merged = rep[faces]
    out_faces = np.sort(new[merged[_distinct(merged) == _distinct(faces)]], axis=1)
    out_faces = np.unique(out_faces, axis=0) if len(out_faces) else out_faces.reshape(-1, 3)
    ends = new[rep[edges.reshape(-1, 2)]]
    ends = np.sort(ends[ends[:, 0] != ends[:, 1]], axis=1)
    m = max(len(keep), 1)
    sides = np.concatenate([out_faces[:, [0, 1]], out_faces[:, [1, 2]], out_faces[:, [0, 2]]])
    code = np.setdiff1d(ends[:, 0] * m + ends[:, 1], sides[:, 0] * m + sides[:, 1])
    return keep, out_faces, np.c_[code // m, code % m].astype(np.int64).reshape(-1, 2)
