"""Compact medial complexes: sheets thinner than the sampling error collapse to curves.

The Voronoi medial complex of a surface sample carries the sampling noise:
the axis of a capsule comes out as a fan of narrow sheets around its segment,
a box's planar sheets as tens of thousands of small triangles. This step
contracts edges of the complex, cheapest first, while the result stays
within ``tolerance`` of what it replaces, keeping its topology:

- *half-edge collapses*: a vertex ``j`` is merged into a neighbour ``i``,
  whose sphere stays where it is, so every kept point is a Voronoi vertex
  of the full complex with its exact radius and extras;
- the *cost* of merging ``j`` into ``i`` is the largest of (a) the root mean
  square distance from sphere ``i`` to the tangent planes at the contacts
  ``j`` stands for (the spherical quadric error of Q-MAT, accumulated over
  earlier merges and divided by their number) and (b) how far the merge
  moves the complex's features: nothing for a vertex inside a sheet; for a
  vertex on a feature line (a curve, a sheet's free border or a junction of
  three sheets or more: the edges not shared by exactly two triangles) moved
  along it, its distance to the line that replaces it; otherwise the
  distance moved; for every vertex, (c) the distance in (centre, radius)
  from its sphere to the edges and triangles that replace its star, over
  which the spheres are interpolated (a merge that would join a body's
  centre straight to a finger's root makes a slab bulging out of the
  finger); a kept vertex carries the largest move merged into
  it, and later merges of it pay at least that. A sheet
  narrower than the tolerance therefore collapses onto its spine (a curve),
  while a wide sheet keeps its outline and a straight curve its ends;
- under the ``"link condition"`` rule a collapse is done only when it
  passes the link condition (the common neighbours of ``i`` and ``j`` are
  exactly the apexes of the triangles on edge ``ij``, and no two of those
  apexes are joined), which makes it a homotopy equivalence (Dey,
  Edelsbrunner, Guha and Nekhayev, "Topology preserving edge contraction",
  1999); the faster rules do not test it, and :func:`compact_medial_axis`
  keeps their result only if its Betti numbers are the solid's (or, without
  the mesh's shell count, its components and Euler characteristic those of
  the full complex), after opening the pockets they pinch out of thin
  sheets (it falls back to the link condition otherwise);
- given the surface's signed distance, a round's collapses are kept only
  while the spheres interpolated over the edges and triangles they make
  reach at most ``tolerance`` out of the solid (sampled
  :data:`~medialaxis.mesh.medial.compact_inside.LATTICE_SPACING` tolerances apart
  in centre and radius); the others are refused until their neighbourhood changes. Without it a chain of merges, each within the tolerance, drifts:
  kitten's compact complex reached 1.63% of the diagonal out of the
  surface, twice its tolerance;
- collapses run in rounds: each round takes, cheapest first, edges whose
  endpoints' neighbourhoods are untouched by the others taken, so the link
  conditions tested at the start of the round still hold when it is applied
  (the faster rules keep apart only the collapses' vertices, or the removed
  vertices' neighbourhoods: the costs stay valid, as kept spheres never move).

References
----------
.. [1] P. Li, B. Wang, F. Sun, X. Guo, C. Zhang, W. Wang, "Q-MAT: Computing medial axis
       transform by quadratic error minimization", ACM Transactions on Graphics
       35(1):8:1-8:16, 2015. doi:10.1145/2753755 (spherical quadrics)
.. [2] M. Garland, P. S. Heckbert, "Surface simplification using quadric error metrics",
       Proc. SIGGRAPH 97, 209-216, 1997. doi:10.1145/258734.258849
.. [3] Dey, Edelsbrunner, Guha, Nekhayev, "Topology preserving edge contraction", 1999 (the
       link condition; venue and DOI unconfirmed: docs/references.md).
"""

from __future__ import annotations

import contextlib
import dataclasses
from collections.abc import Callable, Iterator
from typing import Any

import numba
import numpy as np
from scipy.spatial import cKDTree

from medialaxis.core.arrays import unique_ints
from medialaxis.core.homology import betti_numbers, void_faces
from medialaxis.core.result import MedialAxis
from medialaxis.errors import ResourceLimitError
from medialaxis.mesh.medial._compact_kernels import costs, feature_lines, link_ok, moves, select, structure
from medialaxis.mesh.medial._compact_round_kernels import (
    merge_into,
    morton_codes,
    quadrics,
    remap_faces,
    ties_by_source,
)
from medialaxis.mesh.medial.compact_inside import collapses_inside
from medialaxis.mesh.sample._rows import first_of_rows

__all__ = [
    "Compacted", "compact_complex", "compact_medial_axis", "sphere_quadrics", "complex_edges", "COMPACT_TOLERANCE", "RULES",
]

#: Default tolerance of the compact complex, times the measured sampling density epsilon.
COMPACT_TOLERANCE = 1.0

#: Most rounds of collapses (each halves the remaining candidates or more in practice).
MAX_ROUNDS = 400


#: Fewest rows (edges) the compaction's parallel kernels (costs, moves) run on all of numba's threads for. Smaller
#: rounds run on one: each parallel region waits for all its threads, and on a loaded machine for one descheduled
#: (fandisk's 43 rounds took 5.1 s on two threads at load 4.5, 0.5 s on one).
PARALLEL_ROWS = 32_768


@contextlib.contextmanager
def threads_for(rows: int) -> Iterator[None]:
    """Run the parallel kernels inside on one of numba's threads if ``rows < PARALLEL_ROWS`` (this thread only)."""
    if rows >= PARALLEL_ROWS:
        yield
        return
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        yield
    finally:
        numba.set_num_threads(before)


@dataclasses.dataclass(frozen=True)
class Compacted:
    """A compacted complex over a subset of the input points.

    ``keep`` (p,): input index of each output point; ``faces`` (k, 3) and
    ``edges`` (m, 2) over the output points (curve pieces first, ``n_curve``
    of them, then triangle sides on a free border or a junction);
    ``face_origin`` (k,): the input triangle each output triangle comes from.
    """

    keep: np.ndarray
    faces: np.ndarray
    face_origin: np.ndarray
    edges: np.ndarray
    n_curve: int
    rounds: int


def sphere_quadrics(points: np.ndarray, contacts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Spherical quadrics ``(A (n, 4, 4), b (n, 4), c (n,))`` of the tangent planes at each point's contacts.

    The plane at contact ``p`` has the normal ``n`` from the sphere's centre
    to ``p``; the signed distance of a sphere ``s = (x, r)`` to it is
    ``n.(p - x) - r``, so its square is ``s.A.s - 2 b.s + c``.
    """
    return quadrics(np.ascontiguousarray(points, np.float64), np.ascontiguousarray(contacts, np.float64))


def complex_edges(faces: np.ndarray, edges: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """All edges ``(u < v)`` of a complex (curve pieces and triangle sides), sorted, and their triangle counts.

    The keys of triangle sides (tagged 0) and of ``edges`` (tagged 1) are
    sorted together: the triangles on an edge are the 0s in its run.
    """
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    pairs = np.asarray(edges, np.int64).reshape(-1, 2)
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    tagged = np.sort(np.concatenate([2 * _edge_keys(u, v, n) + tag for u, v, tag in (
        (faces[:, 0], faces[:, 1], 0), (faces[:, 1], faces[:, 2], 0), (faces[:, 2], faces[:, 0], 0), (pairs[:, 0], pairs[:, 1], 1))]))
    keys = tagged >> 1
    start = np.flatnonzero(np.r_[True, keys[1:] != keys[:-1]]) if len(keys) else np.empty(0, np.int64)
    count = np.add.reduceat(1 - (tagged & 1), start) if len(keys) else np.empty(0, np.int64)
    return np.c_[keys[start] // n, keys[start] % n], count


def _working_order(points: np.ndarray) -> np.ndarray:
    """The points in Z order (Morton codes over their box)."""
    return np.argsort(morton_codes(points), kind="stable")


def _relabelled(edges: np.ndarray, to: np.ndarray, n: int) -> np.ndarray:
    """The edges ``to[edges]`` that keep two ends, sorted and distinct."""
    u, v = to[edges[:, 0]], to[edges[:, 1]]
    keys = unique_ints(_edge_keys(u, v, n)[u != v], nearly_sorted=True)  # a round merges few: still in order
    return np.c_[keys // n, keys % n]


def _edge_keys(u: np.ndarray, v: np.ndarray, n: int) -> np.ndarray:
    """``min * n + max`` of the edges ``(u, v)``: their order is that of the sorted pairs."""
    return np.minimum(u, v) * n + np.maximum(u, v)


#: Collapse rules, fastest first: (link condition tested, how far apart the collapses of a round are).
RULES = {"matching": (False, 0), "apart": (False, 1), "link condition": (True, 2)}


def compact_complex(
    points: np.ndarray, radii: np.ndarray, faces: np.ndarray, edges: np.ndarray, contacts: np.ndarray,
    tolerance: float,
    rule: str = "link condition",
    signed: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
    all_edges: np.ndarray | None = None,
) -> Compacted:
    """Contract the complex while it stays within ``tolerance`` (see the module docstring).

    Parameters
    ----------
    points, radii : (n, 3), (n,) float64 ndarray
        Medial spheres.
    faces : (k, 3) int ndarray
        Triangles.
    edges : (m, 2) int ndarray
        Edges not on any triangle (curve pieces); triangle sides may be listed too.
    contacts : (n, c, 3) float64 ndarray
        Surface points on each sphere (their tangent planes give the quadrics).
    tolerance : float
        Largest cost of a collapse, in the units of ``points``.
    rule : {"matching", "apart", "link condition"}
        ``"link condition"``: every collapse passes it (the homotopy type is
        kept); the others do not test it and keep the collapses of a round
        apart by a shared vertex or by the removed vertex's neighbourhood
        (faster; :func:`compact_medial_axis` checks the result's topology).
    signed : callable, optional
        ``signed(points, near)``: signed distance to the surface (negative
        inside) of ``points`` (q, 3), whose nearest input spheres are
        ``near`` (q, k) (their contacts show where to search). A round's
        collapses are kept only while the spheres interpolated over the
        edges and triangles they make reach at most ``tolerance`` out of it
        (:func:`~medialaxis.mesh.medial.compact_inside.collapses_inside`).
    all_edges : (e, 2) int64 ndarray, optional
        Every edge of the complex, as :func:`complex_edges` gives them (made if not given).

    Returns
    -------
    Compacted
    """
    strict, apart = RULES[rule]
    n = len(points)
    points = np.asarray(points, np.float64)
    # work on the points in Z order (input point name[v] is vertex v): neighbours close in memory, costs 0.47 -> 0.27 s
    # CPU on the uv ellipsoid's first round; ties go by the input's labels, so the result does not depend on it
    name = _working_order(points)
    label = np.empty(n, np.int64)
    label[name] = np.arange(n)
    faces = label[np.asarray(faces, np.int64).reshape(-1, 3)]
    spheres = np.c_[points, radii].astype(np.float64)
    centres = None if signed is None else cKDTree(spheres[:, :3], balanced_tree=False, compact_nodes=False)  # 8x faster: crowded axes
    spheres = spheres[name]
    qa, qb, qc = sphere_quadrics(points[name], np.asarray(contacts, np.float64)[name])
    count = np.full(n, float(contacts.shape[1]))
    moved = np.zeros(n)
    origin = np.arange(len(faces))
    alive = np.ones(n, bool)
    blocked = np.empty(0, np.int64)
    all_edges = complex_edges(name[faces], edges, n)[0] if all_edges is None else all_edges
    all_edges = _relabelled(all_edges, label, n)
    if max(n, len(all_edges)) >= 2**31:  # structure() numbers them in int32
        raise ResourceLimitError(f"a complex of {n:,} points and {len(all_edges):,} edges is too large to compact")
    rounds = 0
    while rounds < MAX_ROUNDS:
        rounds += 1
        star = ok = cand = src = dst = cost = move = lines = None  # the last round's, freed before this one's are made
        ptr, idx, eid, apex_ptr, apex = structure(n, all_edges, faces)
        tri_count = np.diff(apex_ptr)
        ok = link_ok(all_edges, ptr, idx, apex_ptr, apex) if strict else np.ones(len(all_edges), bool)
        cand = np.flatnonzero(ok)
        if not len(cand):
            break
        star = (ptr, idx, eid, apex_ptr, apex)
        lines = feature_lines(all_edges, tri_count != 2, n)
        with threads_for(len(cand)):
            src, dst, cost, move = costs(all_edges, cand, spheres, qa, qb, qc, count, moved, lines, star, name)
        within = np.flatnonzero(cost <= tolerance)
        if len(blocked):
            key = all_edges[cand[within], 0] * n + all_edges[cand[within], 1]
            within = within[~np.isin(key, blocked)]
        if not len(within):
            break
        order = ties_by_source(within[np.argsort(cost[within])], cost, src, all_edges[cand] if strict else all_edges, name)
        chosen = np.flatnonzero(select(order, src, dst, ptr, idx, n, apart))
        if signed is not None:
            chosen, refused, touched = collapses_inside(chosen, src, dst, faces, all_edges, spheres, signed, centres, tolerance,
                                                        label)
            if len(blocked):
                blocked = blocked[~(np.isin(blocked // n, touched) | np.isin(blocked % n, touched))]  # stale
            if len(refused):
                blocked = np.union1d(blocked, _edge_keys(src[refused], dst[refused], n))
            if not len(chosen):
                continue
        j, i = src[chosen], dst[chosen]  # no vertex in two merges: i and j are apart
        step = move[chosen]
        unknown = np.flatnonzero(np.isnan(step))  # the slab searches of costs() that stopped before fixing the move
        with threads_for(len(unknown)):
            step[unknown] = moves(j[unknown], i[unknown], spheres, qa, qb, qc, count, moved, lines, star)
        moved[i] = np.maximum(moved[i], step)
        merge_into(j, i, qa, qb, qc, count)
        alive[j] = False
        to = np.arange(n)
        to[j] = i
        faces, origin, corners = remap_faces(faces, origin, to)
        if not strict:
            first = first_of_rows(corners)
            faces, origin = faces[first], origin[first]
        corners = None
        all_edges = _relabelled(all_edges, to, n)
    keep = np.sort(name[alive])
    new = np.full(n, -1, np.int64)
    new[keep] = np.arange(len(keep))
    faces, all_edges = name[faces], name[all_edges]
    faces_out = new[faces]
    all_edges, tri_count = complex_edges(faces, all_edges, n)
    curve = all_edges[tri_count == 0]
    border = all_edges[(tri_count != 0) & (tri_count != 2)]
    edges_out = new[np.concatenate([curve, border])].reshape(-1, 2)
    return Compacted(keep, faces_out, origin, edges_out, int(len(curve)), rounds)


def _components_and_euler(n: int, faces: np.ndarray, all_edges: np.ndarray) -> tuple[int, int]:
    """Components and Euler characteristic of a complex, given all its edges (both cheap, unlike b1 and b2)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(all_edges)), (all_edges[:, 0], all_edges[:, 1])), shape=(n, n))
    return int(connected_components(graph, directed=False)[0]), int(n - len(all_edges) + len(faces))


def _open_voids(c: Compacted, points: np.ndarray, count: int) -> Compacted:
    """``c`` without ``count`` of its voids: the smallest faces that close a 2-cycle are removed.

    A faster rule may squeeze the thin sheets of a sampled axis into closed
    pockets (the 99k-vertex uv ellipsoid's complex came out with 5); each
    removed face that closes a cycle opens one and leaves ``b0`` and ``b1`` as
    they are.
    """
    cut = void_faces(len(c.keep), c.edges, c.faces)
    tri = points[c.faces[cut]]
    area = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    cut = cut[np.argsort(area, kind="stable")[:count]]
    faces = np.delete(c.faces, cut, axis=0)
    all_edges, tri_count = complex_edges(faces, c.edges, len(c.keep))
    curve = all_edges[tri_count == 0]
    border = all_edges[(tri_count != 0) & (tri_count != 2)]
    return dataclasses.replace(
        c, faces=faces, face_origin=np.delete(c.face_origin, cut), edges=np.concatenate([curve, border]),
        n_curve=len(curve),
    )


def compact_medial_axis(
    ma: MedialAxis, tolerance: float, exact: Any = None, shells: int | None = None,
    signed: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
) -> MedialAxis:
    """The compact form of a Voronoi medial complex (``ma.raw`` is the full one).

    Collapses run first without the link condition, which the foam of small
    facets around a sampled axis blocks almost everywhere (a capsule's
    complex stops at a quarter of its points with it), as a matching per
    round, then (if the result's topology differs from the full complex's)
    with the removed vertices' neighbourhoods apart, then with the link
    condition, which cannot change the homotopy type.
    ``metadata["compact"]`` names the rule whose result was kept.

    The full complex's Betti numbers would cost more than the compaction on
    large complexes; they follow from cheap counts instead. Without
    ``shells``, a result is kept when its components and Euler
    characteristic are the full complex's (an edge contraction that kills a
    tunnel or closes a void changes the Euler characteristic by one, so the
    check catches each single change). With ``shells``, the number of
    closed surfaces bounding the solid (outer ones and cavities), the full
    complex has ``b2 = shells - b0`` voids and ``b1 = b0 + b2 - chi``
    tunnels; a result is kept when its Betti numbers are these, after
    opening the voids it has in excess (:func:`_open_voids`): they are
    pockets pinched out of sheets thinner than the tolerance.

    Per-point extras are those of the kept points (the spheres do not move);
    per-triangle extras (``face_*``) those of the triangle each one comes from.
    ``exact(points)``, if given, returns the signed distance and the
    closest surface point of the kept points with an exhaustive search (the
    full complex's radii come from a local one): the few spheres left get
    their exact radius and closest point. ``signed(points, near)``, if given, is
    the signed distance to the surface (negative inside), given the nearest
    input spheres of each point: the spheres interpolated over the result
    then reach at most ``tolerance`` out of the solid (see
    :func:`compact_complex`).
    """
    contacts = ma.extras["contacts"] if "contacts" in ma.extras else ma.points[:, None, :]
    all_edges = complex_edges(np.asarray(ma.faces, np.int64).reshape(-1, 3), ma.edges, len(ma.points))[0]
    components, chi = _components_and_euler(len(ma.points), ma.faces, all_edges)
    voids = None if shells is None else shells - components
    target = None if voids is None or voids < 0 or components + voids < chi else (components, components + voids - chi, voids)
    for mode in RULES:
        c = compact_complex(ma.points, ma.radii, ma.faces, ma.edges, contacts, tolerance, rule=mode, signed=signed,
                            all_edges=all_edges)
        betti = betti_numbers(len(c.keep), c.edges, c.faces)
        if target is None:
            if (betti[0], betti[0] - betti[1] + betti[2]) == (components, chi):
                break
            continue
        if betti[:2] == target[:2] and betti[2] > target[2]:
            c = _open_voids(c, ma.points[c.keep], betti[2] - target[2])
            betti = betti_numbers(len(c.keep), c.edges, c.faces)
        if betti == target:
            break
    extras = {}
    for name, value in ma.extras.items():
        if name.startswith("face_") and len(value) == len(ma.faces):
            extras[name] = np.asarray(value)[c.face_origin]
        elif len(value) == len(ma.points):
            extras[name] = np.asarray(value)[c.keep]
    metadata = dict(ma.metadata)
    metadata.update(
        compact=mode, compact_tolerance=float(tolerance), compact_rounds=c.rounds,
        full_points=int(len(ma.points)), full_faces=int(len(ma.faces)), n_curve_edges=c.n_curve,
        euler_characteristic=int(betti[0] - betti[1] + betti[2]),
    )
    radii = ma.radii[c.keep]
    if exact is not None and len(c.keep):
        signed, closest = exact(ma.points[c.keep])
        radii = np.minimum(np.abs(signed), radii)
        extras["closest"] = np.where((np.abs(signed) <= ma.radii[c.keep])[:, None], closest, extras.get("closest", closest))
    if "face_certified" in extras:
        metadata["n_filling_faces"] = int((~extras["face_certified"]).sum())
    if "inside" in extras:
        metadata["n_outside_points"] = int((~extras["inside"]).sum())
    return MedialAxis(ma.points[c.keep], radii, c.edges, c.faces, extras=extras, metadata=metadata,
                      shape=ma.shape, raw=ma)
