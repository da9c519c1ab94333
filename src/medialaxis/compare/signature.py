"""Signature of a planar medial axis: what the shape distance compares, computed once per shape.

Three descriptions of the axis (after removing spurious branches), one per
term of :func:`medialaxis.shape_distance`: the *axis tour* (samples along
the walk around the axis with their mass histograms and radii, see
:mod:`medialaxis.compare.tour`); the *skeleton paths* between every pair of
axis endpoints (Bai and Latecki: the radius function sampled at
``n_samples`` points equally spaced along the geodesic path, the path's
length, chord and bend; endpoints listed in the order a walk around the
shape's boundary meets them); and the unordered *axis context*
(:mod:`medialaxis.compare.context`). Everything is divided by one scale, the
square root of the area swept by the axis, so the signature is invariant
under similarity transforms (rotation, translation, uniform scaling,
mirroring).

References
----------
X. Bai and L. J. Latecki, "Path similarity skeleton graph matching",
IEEE TPAMI 30(7), 2008. Paper 000 (medial axis "for comparing two shapes").
X. Bai, L. J. Latecki and W.-Y. Liu, "Skeleton pruning by contour partitioning
with discrete curve evolution", IEEE TPAMI 29(3), 2007 (the optional ``dce``
pruning, :mod:`medialaxis.compare.dce`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from medialaxis.compare.compared_axis import compared_axis
from medialaxis.compare.context import axis_context
from medialaxis.compare.endpoints import endpoint_order, endpoint_paths, endpoint_weights, path_lengths
from medialaxis.compare.tour import tour_context
from medialaxis.core import graph as _graph
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InvalidInputError

__all__ = ["Signature", "signature", "DEFAULT_SAMPLES", "DEFAULT_PRUNE"]

#: Radius samples per skeleton path.
DEFAULT_SAMPLES = 24
#: Interior samples of each path's bend profile.
N_BEND = 7
#: Terminal branches protruding less than this fraction of the shape scale
#: beyond the disc of their junction are dropped before matching. Chosen with
#: a class split of Kimia-99 (``benchmarks/bench_compare.py --variants``):
#: 0.03 raises the row on both halves over 0.045; 0.06 lowers half B.
DEFAULT_PRUNE = 0.03


@dataclasses.dataclass(frozen=True, eq=False)
class Signature:
    """What :func:`medialaxis.shape_distance` compares; computed once per shape.

    Attributes
    ----------
    radii : (e, e, s) float64 ndarray
        ``radii[i, j]`` is the radius function along the geodesic axis path
        from endpoint ``i`` to endpoint ``j``, sampled at ``s`` points equally
        spaced in arc length, divided by ``scale``. ``radii[j, i]`` is its reverse.
    lengths : (e, e) float64 ndarray
        Geodesic path lengths divided by ``scale`` (symmetric, zero diagonal).
    chords : (e, e) float64 ndarray
        Straight-line distances between endpoints divided by ``scale``.
    bends : (e, e, b) float64 ndarray
        Bend profile of each path: distance from the midpoint of its chord of
        the path points at arc-length fractions ``1/(b+1) ... b/(b+1)``,
        divided by ``scale`` (0 for a straight path's middle).
    weights : (e,) float64 ndarray
        Significance of each endpoint: how far its terminal branch protrudes
        past the disc of its junction (half the path length for an axis
        without junction), divided by ``scale``. Leaving an endpoint or a
        path to it unmatched costs in proportion to it.
    endpoints : (e, 2) float64 ndarray
        Endpoint coordinates (input units), in boundary order.
    scale : float
        ``sqrt(sum over axis edges of length * (r_a + r_b) + pi * r_max**2)``:
        about the square root of the shape's area, from the axis alone.
    points, radii_at_points, edges : ndarray
        The axis actually used (largest component, spurious branches removed),
        kept for pictures.
    context : (k, h) float64 ndarray
        Axis-context histograms of ``k`` samples along that axis (see
        :func:`medialaxis.compare.context.axis_context`).
    context_radii : (k,) float64 ndarray
        Radius at each context sample divided by ``scale``.
    tour : (4, t, h) float64 ndarray
        Tour-context histograms of ``t`` samples along the walk around the
        axis (see :func:`medialaxis.compare.tour.tour_context`) in four
        versions: the shape and its mirror image (the walk the other way),
        then both again for the axis before the method's own pruning
        (``ma.raw``, with spurious branches removed by ``prune`` alone; a
        copy of the first two when the axis carries no raw graph). Each
        walk starts at an endpoint of largest weight (the node of largest
        radius if the axis has no endpoint), chosen by the walk itself.
    tour_radii : (4, t) float64 ndarray
        Radius at each tour sample divided by the scale of its axis.
    tour_points : (4, t, 2) float64 ndarray
        Positions of the samples of each version on the axis (input units), for pictures.
    """

    radii: np.ndarray
    lengths: np.ndarray
    chords: np.ndarray
    bends: np.ndarray
    weights: np.ndarray
    endpoints: np.ndarray
    scale: float
    points: np.ndarray
    radii_at_points: np.ndarray
    edges: np.ndarray
    context: np.ndarray
    context_radii: np.ndarray
    tour: np.ndarray
    tour_radii: np.ndarray
    tour_points: np.ndarray

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, np.ndarray):
                value.setflags(write=False)

    @property
    def n_endpoints(self) -> int:
        """Number of endpoints compared."""
        return int(len(self.endpoints))


def _tour_starts(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, ends: np.ndarray, weights: np.ndarray, lengths: np.ndarray
) -> np.ndarray:
    """Nodes the tour may start from, found the same way whatever the pose or numbering of the shape.

    The endpoints whose branch protrudes most (within 1e-6: symmetric
    limbs, the corner branches of a limb's end) and, among those, the ones
    farthest along the axis from the others (largest sum of path lengths);
    the node of largest radius when the axis has no endpoint.
    :func:`medialaxis.compare.tour.outer_face` picks one by the walk.
    """
    if len(ends) < 2 or _graph.degree(len(points), edges)[ends[0]] != 1:
        return np.array([int(np.argmax(radii))])
    tied = np.flatnonzero(weights >= weights.max() * (1 - 1e-6) - 1e-12)
    reach = lengths[tied].sum(axis=1)
    return ends[tied[reach >= reach.max() * (1 - 1e-6) - 1e-12]]


def _tour_versions(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, scale: float, order: np.ndarray, weights: np.ndarray,
    lengths: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tour histograms ``(2, t, h)``, radii ``(2, t)`` and positions ``(2, t, 2)`` of the shape and its mirror image."""
    starts = _tour_starts(points, radii, edges, order, weights, lengths)
    flips = (np.array([1.0, 1.0]), np.array([1.0, -1.0]))  # the shape, then its mirror image
    versions = [tour_context(points * flip, radii, edges, scale, starts) for flip in flips]
    return (
        np.stack([v[0] for v in versions]),
        np.stack([v[1] for v in versions]),
        np.stack([v[2] * flip for v, flip in zip(versions, flips)]),
    )


def signature(
    ma: MedialAxis,
    *,
    n_samples: int = DEFAULT_SAMPLES,
    prune: float = DEFAULT_PRUNE,
    max_endpoints: int = 24,
    dce: float = 0.0,
    dce_vertices: int = 3,
    unpruned: bool = False,
) -> Signature:
    """Signature of a planar medial axis (tour, skeleton paths, axis context).

    Parameters
    ----------
    ma : MedialAxis
        A planar (2D) axis, e.g. from :func:`medialaxis.medial_axis`.
    n_samples : int
        Radius samples per endpoint-to-endpoint path (Bai and Latecki use 50;
        24 keeps the pairwise step fast with the same retrieval on Kimia-99).
    prune : float
        Terminal branches protruding less than ``prune * scale`` beyond the
        disc at their junction are dropped (spurious branches of boundary
        noise). ``0`` keeps every branch.
    max_endpoints : int
        If the axis still has more endpoints, the least protruding terminal
        branches are dropped until it has this many (bounds the pairwise cost).
    dce : float
        If > 0, first prune the axis by Discrete Curve Evolution of the
        shape's outline (``ma.shape``; skipped if it has none): evolve the
        largest polygon's exterior until every vertex has relevance at least
        ``dce`` (or ``dce_vertices`` remain), then keep only terminal
        branches whose tip reaches a convex surviving vertex (Bai, Latecki
        and Liu; see :mod:`medialaxis.compare.dce`). ``0`` (default): off,
        as it did not raise the Kimia-99 row (``benchmarks/bench_compare.py
        --variants``).
    dce_vertices : int
        Least number of vertices the evolution keeps (>= 3); with a large
        ``dce`` (e.g. 1) it is the fixed vertex count.
    unpruned : bool
        Compare the axis before the method's own pruning (``ma.raw``) when
        the result carries it; the spurious branches are then removed only
        by ``prune`` (and ``dce``).

    Returns
    -------
    Signature

    Raises
    ------
    InvalidInputError
        ``ma`` is not a 2D :class:`MedialAxis` or a parameter is out of range.
    EmptyShapeError
        The axis has no point (nothing left after pruning).

    References
    ----------
    Bai and Latecki, "Path similarity skeleton graph matching", TPAMI 2008.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> from medialaxis.compare import signature
    >>> mask = np.zeros((40, 80), bool); mask[10:30, 10:70] = True
    >>> sig = signature(mx.medial_axis(mask))
    >>> sig.n_endpoints, sig.radii.shape   # a rectangle: four corner branches
    (4, (4, 4, 24))
    """
    if not isinstance(ma, MedialAxis):
        raise InvalidInputError(f"expected a MedialAxis, got {type(ma).__name__}")
    if ma.dim != 2 or len(ma.faces):
        raise InvalidInputError(
            f"shape comparison needs a planar (2D curve) axis, got a {ma.dim}D axis with {len(ma.faces)} faces"
        )
    if not isinstance(n_samples, (int, np.integer)) or n_samples < 2:
        raise InvalidInputError(f"n_samples must be an integer >= 2, got {n_samples!r}")
    try:
        prune = float(prune)
    except (TypeError, ValueError):
        raise InvalidInputError(f"prune must be a number, got {prune!r}") from None
    if not np.isfinite(prune) or prune < 0:
        raise InvalidInputError(f"prune must be finite and >= 0, got {prune!r}")
    if not isinstance(max_endpoints, (int, np.integer)) or max_endpoints < 2:
        raise InvalidInputError(f"max_endpoints must be an integer >= 2, got {max_endpoints!r}")
    try:
        dce = float(dce)
    except (TypeError, ValueError):
        raise InvalidInputError(f"dce must be a number, got {dce!r}") from None
    if not np.isfinite(dce) or dce < 0:
        raise InvalidInputError(f"dce must be finite and >= 0, got {dce!r}")
    if not isinstance(dce_vertices, (int, np.integer)) or dce_vertices < 3:
        raise InvalidInputError(f"dce_vertices must be an integer >= 3, got {dce_vertices!r}")
    raw = ma.raw if ma.raw is not None and len(ma.raw.points) else None
    if unpruned and raw is not None:
        ma, raw = raw, None
    points, radii, edges, scale = compared_axis(ma, prune, int(max_endpoints), dce, int(dce_vertices))
    order = endpoint_order(points, edges)
    path_r, path_l, bends = endpoint_paths(points, radii, edges, order, int(n_samples), N_BEND)
    weights = endpoint_weights(points, radii, edges, order, path_l)
    ends_xy = points[order]
    chords = np.linalg.norm(ends_xy[:, None, :] - ends_xy[None, :, :], axis=2)
    context, context_radii = axis_context(points, radii, edges, scale)
    tours = [_tour_versions(points, radii, edges, scale, order, weights, path_l)]
    if raw is not None:
        # The tour of the axis without the method's own pruning (spurious branches removed by
        # ``prune`` alone): the distance keeps the better of the two comparisons.
        r_points, r_radii, r_edges, r_scale = compared_axis(raw, prune, int(max_endpoints), dce, int(dce_vertices))
        r_order = endpoint_order(r_points, r_edges)
        r_lengths = path_lengths(r_points, r_edges, r_order)
        r_weights = endpoint_weights(r_points, r_radii, r_edges, r_order, r_lengths)
        tours.append(_tour_versions(r_points, r_radii, r_edges, r_scale, r_order, r_weights, r_lengths))
    else:
        tours.append(tours[0])
    t = max(version[0].shape[1] for version in tours)
    # An axis pruned to one point has a one-sample tour: that sample, all along the walk.
    tours = [tuple(np.repeat(part, t // part.shape[1], axis=1) for part in version) for version in tours]
    tour, tour_radii, tour_points = (np.concatenate(parts) for parts in zip(*tours))
    return Signature(
        path_r / scale, path_l / scale, chords / scale, bends / scale, weights / scale, ends_xy, scale, points, radii,
        edges, context, context_radii, tour, tour_radii, tour_points,
    )
