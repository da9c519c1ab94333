"""3D Delaunay tetrahedralisation: incremental Bowyer-Watson insertion, compiled.

:func:`delaunay_tetrahedra` returns the Delaunay tetrahedra of a point set,
their neighbours (SciPy's ``Delaunay.neighbors`` convention) and the convex
hull's triangles. It replaced Qhull (``scipy.spatial.Delaunay`` with ``QJ``)
in the Voronoi pipeline: 139k samples of a bumpy torus take 0.84 s instead of
7.2 s (TetGen 0.62 s, CGAL 0.99 s; ``benchmarks/bench_delaunay.py``).

Design (and why)
----------------
* **Joggle, then exact predicates.** Surface samples are highly degenerate
  (co-planar grids, co-circular and co-spherical groups). As Qhull's ``QJ``
  does, a copy of the points, scaled to a box of side 1, is moved by a
  seeded uniform random amount of at most ``JOGGLE`` (1e-10 of the bounding
  box's longest side) per coordinate, then rounded to multiples of
  ``2**-GRID_BITS`` (1e-15), so that coordinate differences are exact. The
  predicates ``orient3d`` and ``insphere`` are J. R. Shewchuk's: floating
  point with his error bound (``errboundA`` times the permanent), and
  exact arithmetic on floating-point expansions when the bound does not
  settle the sign (about one call in 10^5 on the pipeline's samples, 3% on
  a regular torus grid). So the result is
  exactly the Delaunay tetrahedralisation of the joggled points, whatever
  the input. The joggle only makes exact ties (five co-spherical points,
  four co-planar ones on the hull) vanishingly rare.
  Why not floating point alone, even with a larger joggle (1e-9, 1e-8)?
  Five points both co-planar and co-circular (the grid rings of a cylinder
  or a torus, the squares of a box face's grid) give an ``insphere``
  proportional to the joggle squared, below rounding error up to a joggle
  of about 1e-7; the conflict regions of those points are then
  inconsistent, and the repairs below cascade (up to 3 per point, and
  circumspheres holding other points well inside on coarse cylinder and
  capsule samples).
* **Every change that a tie could break is checked.** A
  tetrahedron is in the cavity only if the new point is strictly inside its
  circumsphere. Every boundary face of the cavity must then be strictly
  visible from the new point (the new tetrahedron is positively oriented).
  Exact Delaunay promises it while no boundary neighbour is tied and no
  repair below has happened yet, so only then is the check skipped (13% of
  the insertion on the uv ellipsoid's samples); otherwise
  a finite tetrahedron with a face that is not is taken out of the cavity
  and the check repeats (all faces visible makes the cavity star-shaped).
  If the tetrahedron found by the walk or an infinite one would have to go,
  the point is moved by a further random amount (twice as large at each of
  at most ``MAX_ATTEMPTS`` attempts) and inserted again. With the joggle
  neither happens on any input tried; with no joggle at all (exact ties
  everywhere, on lattices, grids and spheres) they keep the triangulation
  valid (the tests check it).
* **A vertex at infinity** (index ``m``, the number of distinct points),
  CGAL and geogram style, instead of a finite super-tetrahedron (which
  changes the hull and leaves flat tetrahedra to clean up). Every
  tetrahedron, finite or infinite, is positively oriented; an infinite
  tetrahedron ``(a, b, c, inf)`` is in conflict with ``p`` when ``p`` is
  strictly on the outer side of its hull triangle ``abc``, that is when
  ``(a, b, c, p)`` is positively oriented. A new infinite tetrahedron is
  checked by putting the far vertex of its old hull neighbour in place of
  ``inf``: that vertex must lie strictly inside, so the hull stays convex.
* **Insertion order: BRIO** (Amenta, Choi and Rote 2003): random rounds of
  doubling size, each sorted along a Morton (Z-order) curve, so the walk
  from the last created tetrahedron to the next point is short (12 steps on
  average on the torus samples), while the random rounds keep the
  intermediate triangulations well shaped: one Morton order of all the
  surface samples makes cavities 4 times larger and the whole 2.8 times
  slower. (A Hilbert curve was no faster than Morton's.)
* **Point location: a stochastic visibility walk** (random first face at
  each step, never back across the face it came through; Devillers, Pion and
  Teillaud 2002), capped at ``MAX_WALK`` steps, then a scan of every
  tetrahedron.
* **Data structures:** one flat ``(cap, 8)`` int32 array, four vertices then
  four neighbours per tetrahedron (32 bytes, half a cache line; int64 in
  two arrays took 1.09 s instead of 0.80 s on the torus samples), a
  neighbour stored as
  ``4 * tet + face`` so the face seen from the other side is known without
  a search; a stack of free slots; stamps instead of cleared flags; a small
  open addressing hash table, keyed by the cavity-boundary edge, to connect
  the new tetrahedra across their faces through the new point (a row of
  stamp, key and value per entry: one cache line per probe). The kernel
  allocates nothing: when an array is full it returns, the caller doubles
  it and calls again (arrays reassigned inside the loop cost 13%).
* **Memory waits.** The insertion mostly waits for rows (the cavity search
  49% and the walk 21% of its cycles on the uv ellipsoid's samples, 140-160
  cycles per tetrahedron tested). Both ask for the next rows ahead
  (``_delaunay_locate.prefetch``), the points are renumbered in insertion
  order, and the arrays start at twice the capacity the insertion runs at,
  so the first doubling copies nothing (all three: 1.43 -> 1.16 s on those
  samples, the same tetrahedra bit for bit).

Duplicates (exactly equal coordinates; ``-0.0 == 0.0``) are dropped before
the joggle: the first one (lowest index) is kept, the others are in no
tetrahedron. Points closer than the joggle (1e-10 of the extent) are kept,
but their tetrahedra are those of the joggled points.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.errors import ComputationError, InvalidInputError, ResourceLimitError
from medialaxis.mesh.sample._delaunay_extract import _finite_keys, _morton, _sorted_tetrahedra
from medialaxis.mesh.sample._delaunay_kernels import (
    _COLLINEAR,
    _DONE,
    _GROW_BUFFERS,
    _GROW_TETS,
    _HSTAMP,
    _NT,
    _OK,
    _RNG,
    _initial,
    _insert,
)
from medialaxis.mesh.sample._predicates import _GRID
from medialaxis.mesh.sample._rows import first_of_rows, radix_argsort

__all__ = ["delaunay_tetrahedra", "JOGGLE"]

#: Largest joggle of each coordinate, relative to the longest side of the bounding box.
JOGGLE = 1e-10
#: Seed of the joggle and of the insertion order (the results are deterministic).
SEED = 20240531
#: Size of the first BRIO round; the next ones double.
BRIO_BASE = 64
#: Most distinct points (the tetrahedra are indexed by int32, four faces each).
MAX_POINTS = 20_000_000

#: First sizes of the arrays (doubled when full): tetrahedron slots per point (6.5 for uniform points,
#: 8 for surface samples, with the infinite ones), cavity tetrahedra, hash table of the cavity's edges.
_SLOTS_PER_POINT = 8.5
_BUFFER = 256
_HASH = 1024
#: The tetrahedron arrays are made this many times the capacity the insertion starts at.
_SPARE = 2


def _triangulate(P: np.ndarray, order: np.ndarray, seed: int, jog: float) -> tuple[np.ndarray, int, np.ndarray]:
    """Delaunay tetrahedralisation of ``P[:-1]`` (the last row stands for the vertex at infinity).

    Returns the tetrahedra (``(n, 8)``: vertices, then neighbours as
    ``4 * tet + face``; ``-1`` in free slots; the rows from the number of
    slots used on are not set), the number of slots used, and
    the statistics (status, points given up, extra moves, tetrahedra taken
    out of a cavity).
    """
    m = len(P) - 1
    stats = np.zeros(4, np.int64)
    # The insertion's random walks depend on the capacity it is resumed at, so that starts as it always
    # did; the arrays are made _SPARE times as large (np.empty: the pages never used are never touched)
    # so that the first doubling copies nothing (the uv ellipsoid's 2.1M slots need it).
    cap = int(_SLOTS_PER_POINT * m) + 64
    tet = np.empty((_SPARE * cap, 8), np.int32)
    status, a, b, c, d = _initial(P, order, tet, m)
    if status != _OK:
        stats[0] = status
        return tet, 0, stats
    order = order.copy()
    order[np.isin(order, (a, b, c, d))] = -1
    mark = np.zeros(len(tet), np.int32)
    free = np.empty(len(tet), np.int32)
    nbuf = _BUFFER
    cav = np.empty(nbuf, np.int32)
    bf = np.empty((nbuf, 6), np.int32)
    htab = np.zeros((_HASH, 4), np.int64)
    state = np.zeros(6, np.int64)
    state[_NT] = 5
    state[_RNG] = 2 * seed + 1
    start = 0
    while True:
        start, why = _insert(P, order, start, jog, tet, cap, mark, free, cav, bf, htab, state, stats[1:])
        if why == _DONE:
            break
        if why == _GROW_TETS:
            cap *= 2
            if cap > len(tet):
                tet = np.concatenate([tet, np.empty((cap - len(tet), 8), np.int32)])
                mark = np.concatenate([mark, np.zeros(cap - len(mark), np.int32)])
                free = np.concatenate([free, np.empty(cap - len(free), np.int32)])
        elif why == _GROW_BUFFERS:
            nbuf *= 2
            cav = np.empty(nbuf, np.int32)
            bf = np.empty((nbuf, 6), np.int32)
        else:
            htab = np.zeros((2 * len(htab), 4), np.int64)
            state[_HSTAMP] = 0
    return tet, int(state[_NT]), stats


# ----------------------------------------------------------------------------
# preparation: duplicates, insertion order
# ----------------------------------------------------------------------------


@njit(cache=True, nogil=True)
def _brio_order(Q, perm, base):  # type: ignore[no-untyped-def]
    """BRIO insertion order: rounds of ``perm`` positions ``[0, base)``, ``[base, 2 base)``, ... each in Morton order.

    ``Q`` lies in ``[-0.5, 0.5]^3`` (up to the joggle).
    """
    m = Q.shape[0]
    key = np.empty(m, np.int64)
    for j in range(m):
        i = perm[j]
        r = 0
        s = base
        while j >= s:
            r += 1
            s *= 2
        key[i] = (r << 50) | _morton(Q[i, 0], Q[i, 1], Q[i, 2])
    return np.argsort(key)


# ----------------------------------------------------------------------------
# public function
# ----------------------------------------------------------------------------


def delaunay_tetrahedra(points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Delaunay tetrahedralisation of 3D points (incremental, joggled input; see the module docstring).

    Parameters
    ----------
    points : (n, 3) array_like of float
        Finite coordinates. Exact duplicates are allowed: the first of each
        group (lowest index) is used, the others are in no tetrahedron.

    Returns
    -------
    simplices : (t, 4) int64 ndarray
        Point indices of the finite tetrahedra, each positively oriented
        (``det[p1 - p0, p2 - p0, p3 - p0] > 0`` on the joggled points, so
        ``>= 0`` up to the joggle, about 1e-10 of the extent, on ``points``).
    neighbors : (t, 4) int64 ndarray
        ``neighbors[i, k]``: the tetrahedron across the face opposite vertex
        ``k`` of tetrahedron ``i``, -1 on the convex hull (SciPy's convention).
    hull : (h, 3) int64 ndarray
        The convex hull's triangles (the faces with neighbour -1), oriented
        with their normal ``(b - a) x (c - a)`` pointing outwards.

    Raises
    ------
    InvalidInputError
        If ``points`` is not an ``(n, 3)`` array of finite numbers.
    ComputationError
        If there are fewer than 5 distinct points, or all are coplanar or
        collinear (within about 1e-9 of the extent).
    ResourceLimitError
        More than ``MAX_POINTS`` distinct points.
    """
    simplices, neighbors, hull, _ = _delaunay(points)
    return simplices, neighbors, hull


def _delaunay(
    points: np.ndarray, joggle: float = JOGGLE, seed: int = SEED
) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, float]]:
    """:func:`delaunay_tetrahedra` with a given joggle and seed, and what it took.

    The last item counts the points moved further (``moved``; one count per
    extra attempt), the tetrahedra taken out of a cavity (``shrunk``), the
    runs with a new seed and a ten times larger joggle (``retries``), and
    gives the final ``joggle`` and the points triangulated (``joggled``:
    ``(n, 3)``, scaled to a box of side 1 centred on 0 and joggled; NaN for
    dropped duplicates).
    """
    try:
        x = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError(f"points must be an (n, 3) array of numbers: {exc}") from exc
    if x.ndim != 2 or x.shape[1] != 3:
        raise InvalidInputError(f"points must be an (n, 3) array, got shape {x.shape}")
    if not np.isfinite(x).all():
        raise InvalidInputError("points must be finite (no NaN or infinity)")
    if len(x) < 5:
        raise ComputationError(f"the 3D Delaunay tetrahedralisation needs at least 5 points, got {len(x)}")
    x = np.ascontiguousarray(x + 0.0)  # -0.0 -> 0.0, so equal coordinates have equal bits
    keep = first_of_rows(x.view(np.int64))  # exact duplicates: equal bits
    m = len(keep)
    if m < 5:
        raise ComputationError(f"the 3D Delaunay tetrahedralisation needs at least 5 distinct points, got {m}")
    if m > MAX_POINTS:
        raise ResourceLimitError(f"the 3D Delaunay tetrahedralisation takes at most {MAX_POINTS} points, got {m}")
    q = x[keep]
    lo, hi = q.min(axis=0), q.max(axis=0)
    extent = float((hi - lo).max())
    if not np.isfinite(extent):
        raise InvalidInputError("points must be finite: their extent overflows")
    q = (q - 0.5 * (lo + hi)) / extent
    # flat inputs: thickness across the least-squares plane
    centred = q - q.mean(axis=0)
    _, vecs = np.linalg.eigh(centred.T @ centred)
    thickness = float(np.ptp(centred @ vecs[:, 0]))
    if thickness <= 10.0 * JOGGLE:
        raise ComputationError(
            "the 3D Delaunay tetrahedralisation failed: all points are coplanar or collinear "
            f"(thickness {thickness * extent:.3g}, extent {extent:.3g})"
        )
    for retry in range(3):
        rng = np.random.default_rng(seed + retry)
        jog = joggle * 10.0**retry
        pts = np.zeros((m + 1, 3))
        pts[:m] = np.rint((q + rng.uniform(-jog, jog, (m, 3))) * _GRID) / _GRID
        order = _brio_order(pts[:m], rng.permutation(m), BRIO_BASE)
        # renumbered in insertion order, so that the vertices of nearby tetrahedra are in nearby rows (1-2%
        # on the uv ellipsoid's samples, whose rows are near in space already); the same tetrahedra
        ins = np.zeros_like(pts)
        ins[:m] = pts[order]
        tet, nt, stats = _triangulate(ins, np.arange(m), seed + retry, max(jog, 1e-12))
        pts[order] = ins[:m]  # with the points moved further
        if stats[0] != _OK:
            raise ComputationError(
                "the 3D Delaunay tetrahedralisation failed: all points are "
                + ("collinear" if stats[0] == _COLLINEAR else "coplanar")
            )
        if stats[1] == 0:
            break
    else:
        raise ComputationError(f"the 3D Delaunay tetrahedralisation failed: {stats[1]} points could not be inserted")
    # numbered along a Z-order curve of their centroids (the insertion leaves them scattered):
    # walks over neighbours afterwards stay in the cache (the Voronoi route's inside test,
    # edge rings and compaction: 10.1-10.7 -> 8.5-8.8 s on the 100k-vertex torus)
    slot, rank, keys = _finite_keys(tet, nt, m, ins)
    perm = radix_argsort(keys)  # ties by slot (stable); NumPy's: 0.22 s for 0.10 s
    simplices, neighbors, hull = _sorted_tetrahedra(tet, slot, rank, perm, keep[order])
    joggled = np.full(x.shape, np.nan)
    joggled[keep] = pts[:m]
    info = {"moved": int(stats[2]), "shrunk": int(stats[3]), "retries": retry, "joggle": jog, "joggled": joggled}
    return simplices, neighbors, hull, info
