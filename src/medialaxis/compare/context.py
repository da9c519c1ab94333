"""Axis context: where the rest of the medial axis lies, seen from points of the axis.

A second, dense term of the shape distance. Points are sampled along the
axis branches at equal arc-length steps; each sample gets a log-polar
histogram of the *swept mass* of the whole axis (length times radius of each
axis piece, i.e. about the area its discs cover) around it, with angles
measured from the axis tangent at the sample (modulo pi, as the tangent has no
sign), and its own radius. Two shapes are compared by matching their samples
one-to-one (Hungarian) with chi-squared histogram costs plus the relative
radius difference; see :mod:`medialaxis.compare._kernels`.

Off by default (weight ``context=0``). Measured on MPEG-7 (35 dev classes, a set
it was not tuned on): the tour alone 87.59%, with 0.1 context 87.42%, with 0.3
86.79%: it does not help there.

The descriptor uses only the axis and its radius function: it is the
shape-context idea (Belongie, Malik and Puzicha, TPAMI 2002) carried over from
boundary points to medial points, as the path signature carries Bai and
Latecki's. Everything is divided by the signature's scale and measured from
the tangent, and the histograms use linear (soft) binning, so the descriptor
is a continuous function of the axis and invariant under similarity
transforms; a mirror image reverses the angle bins (``[..., ::-1]``).
"""

from __future__ import annotations

import numpy as np

from medialaxis.core import graph as _graph

__all__ = [
    "axis_context", "along", "mass_histograms", "pieces", "soft_bins", "N_CONTEXT", "N_RADIAL", "N_ANGULAR", "RADIAL_CENTRES",
]

#: Samples along the axis (about; each branch gets a whole number of them).
#: 32 gives the Kimia-99 row of 40 (903 vs 906) at about half the pair time.
N_CONTEXT = 32
#: Log-polar bins: distance bins (centres below, in units of the scale) and angle bins over [0, pi).
RADIAL_CENTRES = np.array([0.05, 0.15, 0.35, 0.7, 1.4])
N_RADIAL = len(RADIAL_CENTRES)
N_ANGULAR = 6
#: Pieces the axis is cut into for the mass around each sample.
N_PIECES = 400


def pieces(points: np.ndarray, radii: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Midpoints ``(q, 2)`` and swept mass ``(q,)`` (length times radius, summing to 1) of small axis pieces."""
    lengths = np.linalg.norm(points[edges[:, 1]] - points[edges[:, 0]], axis=1)
    step = lengths.sum() / N_PIECES
    counts = np.maximum(1, np.ceil(lengths / step - 1e-9)).astype(np.int64)
    edge_of = np.repeat(np.arange(len(edges)), counts)
    first = np.repeat(np.cumsum(counts) - counts, counts)
    frac = ((np.arange(len(edge_of)) - first) + 0.5) / counts[edge_of]
    a, b = edges[edge_of, 0], edges[edge_of, 1]
    mid = points[a] + frac[:, None] * (points[b] - points[a])
    mass = lengths[edge_of] / counts[edge_of] * (radii[a] + frac * (radii[b] - radii[a]))
    return mid, mass / mass.sum()


def along(
    points: np.ndarray, radii: np.ndarray, nodes: np.ndarray, fractions: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Positions ``(k, 2)``, headings ``(k,)`` and radii ``(k,)`` at ``fractions`` of the length of a node path.

    ``nodes`` lists the path's nodes in order (at least two); the heading is
    the direction of the path's segment holding each point.
    """
    p = points[nodes]
    step = np.diff(p, axis=0)
    seg = np.linalg.norm(step, axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    at = fractions * arc[-1]
    s = np.clip(np.searchsorted(arc, at, side="right") - 1, 0, len(seg) - 1)
    pos = np.column_stack([np.interp(at, arc, p[:, 0]), np.interp(at, arc, p[:, 1])])
    return pos, np.arctan2(step[s, 1], step[s, 0]), np.interp(at, arc, radii[nodes])


def _samples(points: np.ndarray, radii: np.ndarray, edges: np.ndarray, n_samples: int) -> tuple[np.ndarray, ...]:
    """Positions ``(m, 2)``, tangent angles ``(m,)`` and radii ``(m,)`` of samples along each branch."""
    chains = _graph.branches(len(points), edges)
    lengths = [float(np.linalg.norm(np.diff(points[c], axis=0), axis=1).sum()) for c in chains]
    step = sum(lengths) / n_samples
    parts = [along(points, radii, chain, (np.arange(k) + 0.5) / k)
             for chain, k in ((c, max(1, int(np.rint(total / step)))) for c, total in zip(chains, lengths))]
    return tuple(np.concatenate(column) for column in zip(*parts))


def soft_bins(x: np.ndarray, centres: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Linear binning on a line, clamped at the ends: (lower bin, upper bin, weight of upper)."""
    k = np.clip(np.searchsorted(centres, x, side="right") - 1, 0, len(centres) - 2)
    w = np.clip((x - centres[k]) / (centres[k + 1] - centres[k]), 0.0, 1.0)
    return k, k + 1, w


def mass_histograms(
    pos: np.ndarray, heading: np.ndarray, mid: np.ndarray, mass: np.ndarray, scale: float, n_angular: int, period: float
) -> np.ndarray:
    """Log-polar histograms of the swept mass around each of the points ``pos``.

    Distance bins: soft, log-spaced, centred on ``RADIAL_CENTRES * scale``
    (clamped at the ends, so every histogram sums to the total mass). Angle
    bins: ``n_angular`` soft bins over ``[0, period)`` measured from
    ``heading`` (``pi`` for an unsigned tangent, ``2 pi`` for a direction).
    Returns ``(len(pos), N_RADIAL * n_angular)``, flattened distance-major.
    """
    d = mid[None, :, :] - pos[:, None, :]
    dist = np.linalg.norm(d, axis=2) / scale
    r_lo, r_hi, r_w = soft_bins(np.log(np.maximum(dist, 1e-12)), np.log(RADIAL_CENTRES))
    theta = np.mod(np.arctan2(d[..., 1], d[..., 0]) - heading[:, None], period) / period * n_angular - 0.5
    t_lo = np.floor(theta).astype(np.int64)
    t_w = theta - t_lo
    t_hi = (t_lo + 1) % n_angular
    t_lo = t_lo % n_angular
    hist = np.zeros((len(pos), N_RADIAL * n_angular))
    rows = np.broadcast_to(np.arange(len(pos))[:, None], dist.shape)
    m = np.broadcast_to(mass[None, :], dist.shape)
    for r_bin, rw in ((r_lo, 1.0 - r_w), (r_hi, r_w)):
        for t_bin, tw in ((t_lo, 1.0 - t_w), (t_hi, t_w)):
            np.add.at(hist, (rows, r_bin * n_angular + t_bin), m * rw * tw)
    return hist


def axis_context(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, scale: float, n_samples: int = N_CONTEXT
) -> tuple[np.ndarray, np.ndarray]:
    """Axis-context histograms and radii of samples along a planar medial axis.

    Parameters
    ----------
    points : (n, 2) float ndarray
        Axis nodes (one connected component).
    radii : (n,) float ndarray
        Radius function at the nodes.
    edges : (m, 2) int ndarray
        Axis edges (no self-loop); may be empty (a disc: one node).
    scale : float
        Length unit (the signature's scale).
    n_samples : int
        About how many samples; each branch gets ``round(length / step)``
        (at least one), so symmetric branches get the same number.

    Returns
    -------
    histograms : (k, N_RADIAL * N_ANGULAR) float64 ndarray
        Row ``i``: the swept mass of the axis (summing to 1) around sample
        ``i`` by distance bin (log-spaced, linear interpolation between
        ``RADIAL_CENTRES``) and angle bin (from the tangent, modulo pi,
        circular linear interpolation), flattened distance-major.
    sample_radii : (k,) float64 ndarray
        Radius at each sample divided by ``scale``.

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    >>> h, r = axis_context(pts, np.array([0.1, 0.2, 0.1]), np.array([[0, 1], [1, 2]]), 1.0, n_samples=4)
    >>> h.shape, bool(np.allclose(h.sum(axis=1), 1.0)), r.round(2).tolist()
    ((4, 30), True, [0.12, 0.18, 0.18, 0.12])
    """
    if not len(edges):
        k = int(np.argmax(radii))
        hist = np.zeros((1, N_RADIAL * N_ANGULAR))
        hist[0, :N_ANGULAR] = 1.0 / N_ANGULAR  # everything at distance 0, in no direction
        return hist, np.array([radii[k] / scale])
    mid, mass = pieces(points, radii, edges)
    pos, tangent, rad = _samples(points, radii, edges, n_samples)
    hist = mass_histograms(pos, tangent, mid, mass, scale, N_ANGULAR, np.pi)
    return hist, rad / scale
