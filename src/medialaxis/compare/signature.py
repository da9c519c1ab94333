"""Signature of a planar medial axis: what the shape distance compares, computed once per shape.

The *axis tour* (:mod:`medialaxis.compare.tour`) of the axis after removing
spurious branches: samples along the walk around the axis with their
swept-mass histograms and radii, for the shape and its mirror image, for
the axis before the method's own pruning, and for the shape *closed*
(:func:`closed_axis`: slits, cracks and narrow notches filled, as occluders
and scratches make them). The walk starts at the endpoint whose branch
protrudes most (endpoints listed in the order a walk around the shape's
boundary meets them). Everything is divided by one scale, the square root of
the area swept by the axis, so the signature is invariant under similarity
transforms (rotation, translation, uniform scaling, mirroring).

Bai and Latecki's skeleton paths and an unordered axis context were part of
the signature as two more terms; measured on MPEG-7 they did not add to the
tour and moved to ``benchmarks/research/`` (issue 17).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import shapely.errors
from shapely.geometry.base import BaseGeometry

from medialaxis.compare.compared_axis import compared_axis
from medialaxis.compare.endpoints import endpoint_order, endpoint_weights, path_lengths
from medialaxis.compare.tour import N_TOUR, tour_context
from medialaxis.core import graph as _graph
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import ComputationError, InvalidInputError

__all__ = ["Signature", "signature", "closed_axis", "DEFAULT_PRUNE", "CLOSING"]

#: Terminal branches protruding less than this fraction of the shape scale
#: beyond the disc of their junction are dropped before matching. Measured on
#: MPEG-7 (35 dev classes, 5 class folds; issue 15): one pruning at 0.03 gave
#: 87.59%; the better of 0.02 and 0.045 (both compared) 88.66%, at twice
#: the pair time. With the closed shape compared too, the second level no
#: longer helps: 0.02 alone with the raw and closed axes gives 90.87%; both
#: levels of the axis and of the closed axis 90.78% (Kimia-99 955).
DEFAULT_PRUNE = 0.02
#: Offset that closes the shape, times the square root of its area: gaps
#: narrower than twice this are filled (see :func:`closed_axis`). Measured on
#: MPEG-7 (35 dev classes, 5 class folds; issue 15; ``bench_compare.py
#: --mpeg7``): the shapes as given only, 88.16%; closing 0.02, 89.13% (the
#: slits of the ``device6`` pentagons stay open); 0.04, 90.87%; 0.06, 90.79%.
#: In the side study at 0.04 the ``device4`` triangles cut by slits went from
#: 68% to 100% and ``device6`` from 29% to 60%. Skipping the closed axis when
#: the closing changes less than 0.1% of the area (half the shapes: raster
#: staircases) lowered the figure by 1.3 points: that second axis is a second
#: sample of the shape too.
CLOSING = 0.04


@dataclasses.dataclass(frozen=True, eq=False)
class Signature:
    """What :func:`medialaxis.shape_distance` compares; computed once per shape.

    Attributes
    ----------
    weights : (e,) float64 ndarray
        Significance of each endpoint: how far its terminal branch protrudes
        past the disc of its junction (half the path length for an axis
        without junction), divided by ``scale``. The tour starts at an
        endpoint of largest weight.
    endpoints : (e, 2) float64 ndarray
        Endpoint coordinates (input units), in boundary order.
    scale : float
        ``sqrt(sum over axis edges of length * (r_a + r_b) + pi * r_max**2)``:
        about the square root of the shape's area, from the axis alone.
    points, radii_at_points, edges : ndarray
        The axis actually used (largest component, spurious branches removed),
        kept for pictures.
    tour : (6, t, h) float64 ndarray
        Tour-context histograms of ``t`` samples along the walk around the
        axis (see :func:`medialaxis.compare.tour.tour_context`) in six
        versions: the shape and its mirror image (the walk the other way);
        both again for the axis before the method's own pruning (``ma.raw``,
        spurious branches removed by ``prune`` alone; a copy of the first two
        when the axis carries no raw graph); both again for the axis of the
        closed shape (:func:`closed_axis`; a copy of the first two when the
        axis carries no shapely shape or ``closing`` is 0). Each walk starts
        at an endpoint of largest weight (the node of largest radius if the
        axis has no endpoint), chosen by the walk itself.
    tour_radii : (6, t) float64 ndarray
        Radius at each tour sample divided by the scale of its axis.
    tour_points : (6, t, 2) float64 ndarray
        Positions of the samples of each version on the axis (input units), for pictures.
    closing_gain : float
        Area the closing changed (filled, or cut off bevelled spikes), as a
        fraction of the shape's area (0 when the closed versions are
        copies). The distance charges it when it compares closed shapes
        (see :mod:`medialaxis.compare._kernels`).
    """

    weights: np.ndarray
    endpoints: np.ndarray
    scale: float
    points: np.ndarray
    radii_at_points: np.ndarray
    edges: np.ndarray
    tour: np.ndarray
    tour_radii: np.ndarray
    tour_points: np.ndarray
    closing_gain: float = 0.0

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


def closed_axis(ma: MedialAxis, closing: float = CLOSING) -> tuple[MedialAxis | None, float]:
    """Medial axis of the shape closed by offsetting, and the area the closing changed (a fraction of the area).

    The outline is offset outwards by ``closing * sqrt(area)``, then back
    inwards, with mitred joins: slits, cracks and gaps narrower than twice
    that are filled, and everything else comes back as it was, corners
    included (a closing by a disc would round every concave corner, and its
    polygonized arcs change by a thousandth under a 1 degree rotation, which
    the exact similarity invariance of the distance does not allow). Corners
    sharper than about 11 degrees are bevelled (``mitre_limit=10``), so a
    needle-thin spike cannot reach across the shape. Computed from
    ``ma.shape`` (the shapely geometry planar results carry) with ``ma``'s
    own ``tolerance`` and ``lam``; ``ma`` itself when the closing changes
    nothing. Returns ``(None, 0.0)`` if ``ma`` has no valid shapely shape of
    positive area (its axis is then compared alone) or ``closing`` is 0.
    """
    shape = ma.shape
    if closing <= 0 or not isinstance(shape, BaseGeometry) or shape.is_empty or not shape.area > 0:
        return None, 0.0
    if not (np.isfinite(shape.bounds).all() and shape.is_valid):
        return None, 0.0  # e.g. a saved result edited by hand: compare its axis alone
    from medialaxis.api import medial_axis

    offset = closing * float(np.sqrt(shape.area))
    try:
        closed = shape.buffer(offset, join_style="mitre", mitre_limit=10.0)
        closed = closed.buffer(-offset, join_style="mitre", mitre_limit=10.0)
    except shapely.errors.GEOSException:
        return None, 0.0  # a robustness failure of the offset: compare the axis alone
    changed = float(closed.symmetric_difference(shape).area / shape.area)
    if changed <= 1e-9:
        # Nothing filled: the same shape, whose own axis is kept (the closed polygon
        # starts at another vertex, and a degenerate one can triangulate differently).
        return ma, 0.0
    options = {key: ma.metadata[key] for key in ("tolerance", "lam") if key in ma.metadata}
    try:
        return medial_axis(closed, **options), changed
    except (InvalidInputError, ComputationError):
        return None, 0.0  # the closed outline has no axis of its own: compare the axis alone


def _versions(ma: MedialAxis, level: float, max_endpoints: int) -> tuple[tuple[np.ndarray, ...], tuple]:
    """Tours of one axis at one pruning level (see :func:`_tour_versions`) and the signature fields it gives."""
    points, radii, edges, scale = compared_axis(ma, level, int(max_endpoints))
    order = endpoint_order(points, edges)
    lengths = path_lengths(points, edges, order)
    weights = endpoint_weights(points, radii, edges, order, lengths)
    tours = _tour_versions(points, radii, edges, scale, order, weights, lengths)
    return tours, (weights / scale, points[order], scale, points, radii, edges)


def signature(
    ma: MedialAxis,
    *,
    prune: float = DEFAULT_PRUNE,
    max_endpoints: int = 24,
    unpruned: bool = False,
    closing: float = CLOSING,
) -> Signature:
    """Signature of a planar medial axis (its tour, in six versions).

    Parameters
    ----------
    ma : MedialAxis
        A planar (2D) axis, e.g. from :func:`medialaxis.medial_axis`.
    prune : float
        Terminal branches protruding less than ``prune * scale`` beyond the
        disc at their junction are dropped (spurious branches of boundary
        noise). ``0`` keeps every branch.
    max_endpoints : int
        If the axis still has more endpoints, the least protruding terminal
        branches are dropped until it has this many.
    unpruned : bool
        Compare the axis before the method's own pruning (``ma.raw``) when
        the result carries it; the spurious branches are then removed only
        by ``prune``.
    closing : float
        Offset that closes the shape for the last two versions, times
        the square root of the shape's area
        (:func:`closed_axis`); ``0`` compares the shape as it is only.

    Returns
    -------
    Signature

    Raises
    ------
    InvalidInputError
        ``ma`` is not a 2D :class:`MedialAxis` or a parameter is out of range.
    EmptyShapeError
        The axis has no point (nothing left after pruning).

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> from medialaxis.compare import signature
    >>> mask = np.zeros((40, 80), bool); mask[10:30, 10:70] = True
    >>> sig = signature(mx.medial_axis(mask))
    >>> sig.n_endpoints, sig.tour.shape[0]   # a rectangle: four corner branches; six tour versions
    (4, 6)
    """
    if not isinstance(ma, MedialAxis):
        raise InvalidInputError(f"expected a MedialAxis, got {type(ma).__name__}")
    if ma.dim != 2 or len(ma.faces):
        raise InvalidInputError(
            f"shape comparison needs a planar (2D curve) axis, got a {ma.dim}D axis with {len(ma.faces)} faces"
        )
    prune = check_number(prune, "prune")
    closing = check_number(closing, "closing")
    if not isinstance(max_endpoints, (int, np.integer)) or max_endpoints < 2:
        raise InvalidInputError(f"max_endpoints must be an integer >= 2, got {max_endpoints!r}")
    closed, gain = closed_axis(ma, closing)
    raw = ma.raw if ma.raw is not None and len(ma.raw.points) else None
    if unpruned and raw is not None:
        ma, raw = raw, None
    # The axis as pruned, the axis before the method's own pruning (spurious branches removed by
    # prune alone) and the closed shape's axis: the distance keeps the best comparison of all the
    # versions, charging the closed ones for the area the closing changed.
    versions = [_versions(ma, prune, max_endpoints)]
    versions.append(versions[0] if raw is None else _versions(raw, prune, max_endpoints))
    versions.append(versions[0] if closed is None or closed is ma else _versions(closed, prune, max_endpoints))
    # An axis pruned to one point (a disc) has a one-sample tour: that sample, all along the
    # walk, as many times as the others have samples (a 1-sample walk cannot be aligned within
    # the band to a 64-sample one: the distance of a disc to any other shape was infinite).
    t = max(N_TOUR, *(tours[0].shape[1] for tours, _ in versions))
    parts = [tuple(np.repeat(part, t // part.shape[1], axis=1) for part in tours) for tours, _ in versions]
    tour, tour_radii, tour_points = (np.concatenate(column) for column in zip(*parts))
    return Signature(*versions[0][1], tour, tour_radii, tour_points, gain)

