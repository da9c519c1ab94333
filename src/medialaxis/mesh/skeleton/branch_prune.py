"""Re-pruning curve skeletons by branch: ``prune(lam=)`` of a flow skeleton.

The lambda-medial axis drops the points whose contact set (the surface points
nearest to them) is narrower than lambda; a tube of radius ``r`` keeps its
axis for ``lam <= 2 r``. A curve skeleton's node has a contact set too: the
input vertices that contracted onto it (``extras["correspondence"]``), each
with its inner ball; the node's width is twice their median radius, ``2 r``
along a tube (:func:`contact_widths`). Pruning removes, leaf
first, the terminal branches (from an endpoint to a junction) all of whose
nodes are narrower than ``lam``: thin limbs go, as in the lambda-medial axis,
while the skeleton keeps its components and cycles (a branch that is a whole
component, or part of a cycle, is never removed), as the planar route's leaf
peeling does.

The inner balls are computed once per input mesh and kept for later calls
(:func:`inner_radii`), so that trying one lambda after another costs the
pruning only.
"""

from __future__ import annotations

import weakref
from collections import OrderedDict
from typing import Any

import numpy as np

from medialaxis.core import graph as _graph
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import InvalidInputError

__all__ = ["contact_widths", "inner_radii", "reprune"]

#: Meshes whose inner-ball radii are kept, most recent last (each entry holds a copy of its vertices).
_KEPT = 4
_inner: OrderedDict[int, tuple[Any, np.ndarray, np.ndarray]] = OrderedDict()


def inner_radii(mesh: Any) -> np.ndarray:
    """The inner-ball radius of each vertex of ``mesh`` (shrinking balls), kept for the next call on it.

    An entry is used only for the same mesh object with the same vertices
    (a mesh changed in place is measured again).
    """
    from medialaxis.mesh.skeleton._flow_operators import pole_targets

    points = np.asarray(mesh.vertices, np.float64)
    kept = _inner.get(id(mesh))
    if kept is not None and kept[0]() is mesh and np.array_equal(kept[1], points):
        _inner.move_to_end(id(mesh))
        return kept[2]
    edge = float(np.median(np.asarray(mesh.edges_unique_length))) if len(mesh.faces) else 0.0
    diagonal = float(np.linalg.norm(np.ptp(points, axis=0)))
    _, inner = pole_targets(points, np.asarray(mesh.vertex_normals, np.float64), max_radius=0.5 * diagonal,
                            ignore=edge)
    inner.setflags(write=False)
    try:
        ref = weakref.ref(mesh)
    except TypeError:  # not weakly referable: not kept
        return inner
    _inner[id(mesh)] = (ref, points.copy(), inner)
    while len(_inner) > _KEPT:
        _inner.popitem(last=False)
    return inner


def contact_widths(ma: MedialAxis) -> np.ndarray:
    """The width of each node's contact set: twice the median inner-ball radius of the vertices that contracted onto it.

    The inner ball of a vertex is the largest ball inside the solid touching
    it (the shrinking-ball iteration,
    :func:`~medialaxis.mesh.skeleton._flow_operators.pole_targets`): along a tube of
    radius ``r`` it has radius ``r``, wherever along the tube the flow put the
    node. A node without vertices (or a result without its input mesh) takes
    twice its own radius.
    """
    widths = 2.0 * np.asarray(ma.radii, np.float64)
    mesh, node_of = ma.shape, ma.extras.get("correspondence")
    if node_of is None or not hasattr(mesh, "vertex_normals") or len(node_of) != len(mesh.vertices):
        return widths
    inner = inner_radii(mesh)
    node_of = np.asarray(node_of, np.int64)
    order = np.argsort(node_of, kind="stable")
    nodes, starts = np.unique(node_of[order], return_index=True)
    for node, group in zip(nodes, np.split(order, starts[1:])):
        if node >= 0:
            widths[node] = 2.0 * float(np.median(inner[group]))
    return widths


def _terminal_branches(n: int, edges: np.ndarray) -> list[np.ndarray]:
    """The branches from an endpoint to a junction (endpoint first), of components that have a junction."""
    degree = np.bincount(edges.ravel(), minlength=n)
    out = []
    for chain in _graph.branches(n, edges):
        chain = np.asarray(chain)
        if chain[0] == chain[-1]:
            continue  # a loop
        ends = degree[chain[[0, -1]]]
        if ends[0] == 1 and ends[1] >= 3:
            out.append(chain)
        elif ends[1] == 1 and ends[0] >= 3:
            out.append(chain[::-1])
    return out


def reprune(ma: MedialAxis, *, lam: float | None = None, **options: Any) -> MedialAxis:
    """The skeleton from ``ma.raw`` (or ``ma``) without its terminal branches narrower than ``lam``.

    Parameters
    ----------
    ma : MedialAxis
        A flow skeleton (curves, no faces).
    lam : float
        Smallest contact-set width kept (mesh units); ``None`` keeps the
        skeleton as computed.

    Returns
    -------
    MedialAxis
        The kept nodes (``raw``: the unpruned skeleton); ``correspondence``
        sends the vertices of a removed branch to the junction it hung from;
        ``metadata["lam"]`` and ``["pruned_branches"]``.
    """
    if options:
        raise InvalidInputError(f"flow skeletons re-prune by lam only, got {', '.join(map(repr, options))}")
    raw = ma.raw if ma.raw is not None else ma
    if lam is None:
        return ma
    lam = check_number(lam, "lam", positive=True)
    n = len(raw.points)
    widths = contact_widths(raw)
    alive = np.ones(n, bool)
    home = np.arange(n)  # where each node's vertices go: itself, or the junction its branch hung from
    edges = np.asarray(raw.edges, np.int64).reshape(-1, 2)
    removed = 0
    while True:
        live = edges[alive[edges].all(axis=1)]
        cut = [b for b in _terminal_branches(n, live) if widths[b[:-1]].max() < lam]
        if not cut:
            break
        for branch in cut:
            alive[branch[:-1]] = False
            home[branch[:-1]] = branch[-1]
        removed += len(cut)
    while not np.array_equal(home, home[home]):  # a branch hung from one removed later
        home = home[home]
    index = np.cumsum(alive) - 1
    kept = edges[alive[edges].all(axis=1)]
    extras = {}
    if "correspondence" in raw.extras:
        node_of = np.asarray(raw.extras["correspondence"], np.int64)
        extras["correspondence"] = np.where(node_of >= 0, index[home[np.maximum(node_of, 0)]], -1)
    metadata = dict(raw.metadata, lam=lam, pruned_branches=removed)
    return MedialAxis(raw.points[alive], raw.radii[alive], index[kept], extras=extras, metadata=metadata,
                      shape=raw.shape, raw=raw)
