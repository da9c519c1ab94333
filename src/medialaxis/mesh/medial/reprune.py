"""Re-pruning a Voronoi medial complex with a larger lambda, without computing it again (``MedialAxis.prune``).

The full complex of :func:`~medialaxis.mesh.voronoi.voronoi_medial_axis`
keeps, per triangle, the width of its facet's contact set
(``face_contact_diameter``, the Delaunay edge it is dual to) and whether its
facet was certified medial (``face_certified``). A larger lambda removes the
triangles narrower than it the way the route selected them: collapses of free
faces, narrowest first (:func:`~medialaxis.mesh.medial._collapse_kernels.collapse_facets`),
so that pruning never punches a hole in a sheet, then the curve pieces left
dangling (:func:`~medialaxis.mesh.medial._collapse_kernels.collapse_free_sides`); a
component the collapse empties keeps its largest ball. A certified triangle
spanning a part thinner than lambda (``face_thin``: contacts several sample
spacings apart and nearly opposite) is that part's sheet, and stays, as the
route keeps it. A compact result is compacted again
from the re-pruned full complex.

A smaller lambda than the complex was computed with needs the Voronoi
diagram again: that is refused with the call to make.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import InvalidInputError
from medialaxis.mesh.medial._collapse_kernels import collapse_facets, collapse_free_sides
from medialaxis.mesh.medial.compact import compact_medial_axis, complex_edges

__all__ = ["reprune"]


def reprune(ma: MedialAxis, *, lam: float | None = None) -> MedialAxis:
    """``ma`` with the facets narrower than ``lam`` collapsed away (see the module docstring).

    Parameters
    ----------
    ma : MedialAxis
        A result of the mesh ``voronoi`` method: the compact complex (its
        ``raw`` is the full one) or the full one (``compact=False``).
    lam : float, optional
        The new lambda, at least the one ``ma`` was computed with; None
        returns ``ma``.

    Returns
    -------
    MedialAxis
        Compact when ``ma`` is, with the re-pruned full complex as ``raw``.

    Raises
    ------
    InvalidInputError
        A simplified result, a result without its full complex, or ``lam``
        below the one the complex was computed with.
    """
    if ma.metadata.get("simplified"):
        raise InvalidInputError("a simplified medial mesh is re-pruned through the complex it came from: "
                                "ma.raw.prune(lam=...), then simplify_medial_mesh")
    if lam is None:
        return ma
    lam = check_number(lam, "lam", positive=True)
    full = ma.raw if ma.raw is not None else ma
    if "face_contact_diameter" not in full.extras or "lam" not in full.metadata:
        raise InvalidInputError("this mesh result keeps no full Voronoi complex (face_contact_diameter) to re-prune")
    lam0 = float(full.metadata["lam"])
    if lam < lam0 * (1.0 - 1e-12):
        raise InvalidInputError(f"this complex was selected at lam={lam0:.6g}; a smaller lam needs the Voronoi diagram "
                                f"again: medial_axis(shape, lam={lam:.6g})")
    pruned = _collapsed(full, lam)
    if ma.raw is None:
        return pruned
    shells = None
    if ma.shape is not None and hasattr(ma.shape, "faces"):
        from medialaxis.mesh.solid.crossings import vertex_shells

        shells = vertex_shells(len(ma.shape.vertices), np.asarray(ma.shape.faces, np.int64))[0]
    return compact_medial_axis(pruned, float(ma.metadata["compact_tolerance"]), shells=shells)


def _collapsed(full: MedialAxis, lam: float) -> MedialAxis:
    """The full complex ``full`` collapsed down to the facets at least ``lam`` wide (and the thin parts' sheets)."""
    faces = np.asarray(full.faces, np.int64)
    n, k = len(full.points), len(faces)
    width = np.asarray(full.extras["face_contact_diameter"], np.float64)
    certified = np.asarray(full.extras.get("face_certified", np.ones(k, bool)), bool)
    # wide enough, or the sheet of a part thinner than lambda (a certified facet narrower than the lambda the
    # complex was computed with is one, where a complex of an earlier release does not say)
    thin = np.asarray(full.extras["face_thin"], bool) if "face_thin" in full.extras else width < float(full.metadata["lam"])
    protected = certified & ((width >= lam) | thin)

    # sides: every triangle side and curve piece once (complex_edges sorts them by key)
    sides, _ = complex_edges(faces, full.edges, n)
    key = sides[:, 0] * n + sides[:, 1]
    tri_sides = np.empty((k, 3), np.int64)
    for c, (a, b) in enumerate(((0, 1), (1, 2), (2, 0))):
        u, v = np.minimum(faces[:, a], faces[:, b]), np.maximum(faces[:, a], faces[:, b])
        tri_sides[:, c] = np.searchsorted(key, u * n + v)
    order = np.argsort(width, kind="stable")
    fptr = np.arange(0, 3 * k + 1, 3, dtype=np.int64)
    fsides = tri_sides[order].ravel()
    alive_sorted, side_alive = collapse_facets(fptr, fsides, len(sides), width[order], protected[order])
    alive = np.empty(k, bool)
    alive[order] = alive_sorted
    uses = np.bincount(tri_sides[alive].ravel(), minlength=len(sides))
    side_alive = collapse_free_sides(side_alive, uses > 0, sides, n)

    # a component the collapse emptied keeps its largest ball
    kept = np.zeros(n, bool)
    kept[faces[alive].ravel()] = True
    kept[sides[side_alive].ravel()] = True
    graph = coo_matrix((np.ones(len(sides)), (sides[:, 0], sides[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    emptied = np.setdiff1d(label, label[kept])
    for comp in emptied:
        members = np.flatnonzero(label == comp)
        kept[members[np.argmax(full.radii[members])]] = True

    used = np.flatnonzero(kept)
    index = np.full(n, -1, np.int64)
    index[used] = np.arange(len(used))
    # edges: the curve pieces (alive sides no triangle uses) and the sheets' borders (sides of one or of three or
    # more triangles), as the route writes them
    edges = sides[side_alive & (uses != 2)]
    extras = {}
    for name, value in full.extras.items():
        value = np.asarray(value)
        extras[name] = value[alive] if name.startswith("face_") and len(value) == k else value[used]
    new_faces = index[faces[alive]]
    new_edges = index[edges]
    metadata = dict(full.metadata, lam=lam, lam_default=False, repruned_from=float(full.metadata["lam"]),
                    n_curve_edges=int((side_alive & (uses == 0)).sum()), n_filling_faces=int((~certified[alive]).sum()),
                    euler_characteristic=int(len(used) - len(complex_edges(new_faces, new_edges, len(used))[0])
                                             + len(new_faces)))
    metadata.pop("timings", None)
    return MedialAxis(full.points[used], full.radii[used], new_edges, new_faces, extras=extras, metadata=metadata,
                      shape=full.shape)
