"""Plate thickness: from the pairs of adjacent voxels that see the two faces of a plate.

A pair of 6-adjacent foreground voxels whose nearest boundary points lie in
opposite directions (antipodal) straddles a plate's mid-surface, and the
distance between those points is the plate's local thickness. The part-wide
figures (:func:`plate_summary`, :func:`nominal_thicknesses`) come from all
such pairs; with several nominal thicknesses (a rib thinner than its wall)
every boundary point is labelled with its plate's (:func:`plate_labels`).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.errors import EmptyShapeError
from medialaxis.volume._kernels import adjacent_gaps
from medialaxis.volume.distance import Features

__all__ = ["PlateThickness", "plate_thickness", "plate_pairs", "plate_summary", "plate_labels", "nominal_thicknesses",
           "label_shortest", "pair_gaps", "pair_gaps_reference", "pair_cosines", "DEFAULT_MIN_THICKNESS", "ANTIPODAL_COS", "LABEL_RADIUS",
           "TUBE_ROUTE"]

#: What a part without plates needs instead of a mid-surface (said by the errors that refuse one).
TUBE_ROUTE = ("for the curve skeleton of rods and tubes, take their surface, verts, faces = "
              "skimage.measure.marching_cubes(volume, level)[:2], and call medial_axis(trimesh.Trimesh(verts, faces), "
              "method='flow')")


#: Pairs whose nearest boundary points are within ~18 degrees of opposite
#: directions see the two faces of a plate (thickness estimate).
ANTIPODAL_COS = 0.95


#: A boundary point's plate thickness is the median label within this many
#: voxels (of the coarsest spacing).
LABEL_RADIUS = 1.5


#: Neighbours looked at within ``LABEL_RADIUS`` (boundary points lie on voxel
#: edges: about 7 per side within 1.5 voxels of an axis-aligned face).
LABEL_NEIGHBOURS = 16


#: The nominal thicknesses of a part are the peaks of the histogram of its
#: plate-crossing pairs holding at least this share of them (prominence).
NOMINAL_SHARE = 0.02


#: A boundary label up to this fraction above a nominal thickness is that
#: nominal thickness (pairs across a corner see a plate as thicker).
CORNER_EXCESS = 0.25


#: A boundary label up to this fraction below a nominal thickness is that
#: nominal thickness (noise).
LABEL_NOISE = 0.15


#: Default lower bound of the plate thickness when none is given, in voxels
#: (of the finest spacing): thinner plates cannot be told from noise.
DEFAULT_MIN_THICKNESS = 2.0


@dataclasses.dataclass(frozen=True)
class PlateThickness:
    """The plate thickness the medial test compares voxel pairs with.

    Attributes
    ----------
    value : float
        Nominal thickness: the one given, or the median thickness of the
        plates kept (physical units).
    lower, upper : float
        Plates whose thickness is outside ``[lower, upper]`` are left out
        (``upper`` may be ``inf``).
    boundary : (b,) float64 ndarray or None
        Local mode: thickness of the plate each boundary sample belongs to
        (see :func:`plate_thickness`). ``None``: one thickness, ``value``,
        for the whole part.
    ranged : bool
        True when the thickness was not given as one number (the plates
        outside ``[lower, upper]`` are left out); False for a nominal
        thickness, whose ``lower`` is ``lam``.
    """

    value: float
    lower: float
    upper: float
    boundary: np.ndarray | None = None
    ranged: bool = False

    @property
    def local(self) -> bool:
        """True when each plate is judged by its own thickness."""
        return self.boundary is not None


def _pairs(features: Features, axis: int) -> tuple[np.ndarray, np.ndarray]:
    """Rows (p, q) of 6-adjacent foreground voxel pairs along ``axis``."""
    index = features.index
    lo = [slice(None)] * 3
    hi = [slice(None)] * 3
    lo[axis], hi[axis] = slice(None, -1), slice(1, None)
    a, b = index[tuple(lo)], index[tuple(hi)]
    both = (a >= 0) & (b >= 0)
    return a[both].astype(np.int64), b[both].astype(np.int64)


def pair_gaps(features: Features, shortest: float = -np.inf) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Per axis, the rows ``(p, q)`` of 6-adjacent foreground voxels whose nearest boundary points are more
    than ``shortest`` apart, and that distance (compiled: :func:`~medialaxis.volume._kernels.adjacent_gaps`)."""
    feature = np.ascontiguousarray(features.feature, np.float64)
    return [adjacent_gaps(features.index, feature, axis, float(shortest)) for axis in range(3)]


def pair_gaps_reference(features: Features, shortest: float = -np.inf) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """NumPy reference of :func:`pair_gaps`."""
    out = []
    for axis in range(3):
        p, q = _pairs(features, axis)
        gap = np.linalg.norm(features.feature[p] - features.feature[q], axis=1)
        keep = gap > shortest
        out.append((p[keep], q[keep], gap[keep]))
    return out


def pair_cosines(features: Features, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Cosine of the angle between the directions from ``p`` and ``q`` to their nearest boundary points."""
    P_p = (features.voxels[p] + features.offset) * features.spacing
    P_q = (features.voxels[q] + features.offset) * features.spacing
    up = features.feature[p] - P_p
    uq = features.feature[q] - P_q
    return np.einsum("ij,ij->i", up, uq) / np.maximum(np.linalg.norm(up, axis=1) * np.linalg.norm(uq, axis=1), 1e-12)


def plate_pairs(features: Features, shortest: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Adjacent voxel pairs that see the two faces of a plate (antipodal contacts), longer than ``shortest``."""
    out_p, out_q, out_gap = [], [], []
    for p, q, gap in pair_gaps(features, shortest):
        sheet = pair_cosines(features, p, q) < -ANTIPODAL_COS
        out_p.append(p[sheet])
        out_q.append(q[sheet])
        out_gap.append(gap[sheet])
    return np.concatenate(out_p), np.concatenate(out_q), np.concatenate(out_gap)


def plate_thickness(features: Features, lower: float | None = None, upper: float = np.inf) -> PlateThickness:
    """The thickness of every plate of the part, on its boundary.

    Each pair of adjacent voxels that sees the two faces of a plate
    (antipodal nearest boundary points) labels both boundary points with
    their distance, the plate's local thickness; a boundary point keeps the
    smallest label it gets (where a thin rib meets a thick wall, the corner
    belongs to the rib), then the median of the labels around it, which is
    snapped to the nearest of the part's nominal thicknesses (the peaks of
    the histogram of the labels) when within 15% below or 25% above it.
    Boundary points that no such pair reaches (end faces, convex edges)
    take the label of the nearest labelled point.

    Parameters
    ----------
    features : Features
    lower, upper : float, optional
        Plates thinner than ``lower`` (default 2 voxels of the finest spacing)
        or thicker than ``upper`` are left out by :func:`medial_voxels`.

    Returns
    -------
    PlateThickness
        ``value`` is the median thickness of the plates kept. When the part
        has one nominal thickness (one peak in the histogram of the pair
        lengths: a part of uniform or smoothly varying thickness) no
        boundary labels are kept and the part is judged by ``value``, as
        with a nominal thickness; with several (a rib thinner than its
        wall), by the labels.

    Raises
    ------
    EmptyShapeError
        If no plate has a thickness in ``[lower, upper]``.
    """
    unit = float(features.spacing.min())
    lower = DEFAULT_MIN_THICKNESS * unit if lower is None else float(lower)
    p, q, gap = plate_pairs(features, label_shortest(lower, unit))
    plates = plate_summary(gap, lower, upper, unit)
    nominal = nominal_thicknesses(gap, lower, unit)
    if len(nominal) <= 1:
        # one plate thickness (or a thickness that varies smoothly): the
        # whole part is judged by it, as with a nominal thickness
        return plates
    return dataclasses.replace(plates, boundary=plate_labels(features, p, q, gap, nominal))


def label_shortest(lower: float, unit: float) -> float:
    """Shortest pair that labels a plate (pairs a little thinner than ``lower`` still say where plates are)."""
    return min(0.75 * lower, 1.5 * unit)


def plate_summary(gap: np.ndarray, lower: float, upper: float, unit: float) -> PlateThickness:
    """The part-wide figures of :func:`plate_thickness` from the lengths of all its plate-crossing pairs.

    Returns a :class:`PlateThickness` without boundary labels; whether the
    part needs them (several nominal thicknesses) is ``len(nominal_thicknesses(...)) > 1``.
    """
    inside = (gap >= lower) & (gap <= upper)
    if not inside.any():
        if len(gap):
            found = f"; the plates found are {np.min(gap):.3g} to {np.max(gap):.3g} thick (thickness= chooses them)"
        else:
            found = f"; the part has no plates (rods, tubes and blobs have no two parallel faces): {TUBE_ROUTE}"
        raise EmptyShapeError(f"no plate of the part is between {lower:g} and {upper:g} thick{found}")
    return PlateThickness(float(np.median(gap[inside])), lower, float(upper), None, ranged=True)


def nominal_thicknesses(gap: np.ndarray, lower: float, unit: float) -> np.ndarray:
    """The part's nominal plate thicknesses from its plate-crossing pair lengths (see :func:`plate_thickness`)."""
    return _nominal(gap[gap >= lower], unit)


def plate_labels(features: Features, p: np.ndarray, q: np.ndarray, gap: np.ndarray, nominal: np.ndarray) -> np.ndarray:
    """Plate thickness at every boundary point of ``features`` from its plate-crossing pairs ``(p, q, gap)``.

    Each point keeps the smallest length of the pairs whose voxels it is
    nearest to, then the median of the labels around it, snapped to the
    nearest ``nominal`` thickness (see :func:`plate_thickness`).
    """
    label = np.full(len(features.boundary), np.inf)
    np.minimum.at(label, features.feature_index[p], gap)
    np.minimum.at(label, features.feature_index[q], gap)
    label = _smooth_labels(features.boundary, label, LABEL_RADIUS * float(features.spacing.max()))
    return _snap(label, nominal)


def _nominal(gap: np.ndarray, unit: float) -> np.ndarray:
    """The part's nominal plate thicknesses: the peaks of the histogram of
    plate-crossing pair lengths that hold at least ``NOMINAL_SHARE`` of them."""
    edges = nominal_edges(float(gap.min()), float(gap.max()), unit)
    return nominal_peaks(np.histogram(gap, edges)[0], edges, unit)


def nominal_edges(shortest: float, longest: float, unit: float) -> np.ndarray:
    """Bin edges of the histogram of pair lengths from ``shortest`` to ``longest`` (quarter-voxel bins)."""
    step = 0.25 * unit
    return np.arange(shortest - 2 * step, longest + 3 * step, step)


def nominal_peaks(counts: np.ndarray, edges: np.ndarray, unit: float) -> np.ndarray:
    """The nominal thicknesses from the histogram ``counts`` of pair lengths over ``edges`` (:func:`nominal_edges`)."""
    from scipy.ndimage import gaussian_filter1d
    from scipy.signal import find_peaks

    step = 0.25 * unit
    hist = gaussian_filter1d(np.asarray(counts).astype(np.float64), 2.0)
    peaks, _ = find_peaks(hist, prominence=NOMINAL_SHARE * hist.sum() * step / unit)
    return np.sort(0.5 * (edges[peaks] + edges[peaks + 1]))


def _snap(label: np.ndarray, nominal: np.ndarray) -> np.ndarray:
    """Labels near a nominal thickness take it: up to ``LABEL_NOISE`` below
    (noise) or ``CORNER_EXCESS`` above (pairs across a corner see a plate as
    thicker than it is); others (a tapered plate) keep their own."""
    if len(nominal) == 0:
        return label
    ratio = label[:, None] / nominal[None, :]
    near = (ratio >= 1.0 - LABEL_NOISE) & (ratio <= 1.0 + CORNER_EXCESS)
    closest = np.where(near, np.abs(np.log(ratio)), np.inf).argmin(axis=1)
    return np.where(near.any(axis=1), nominal[closest], label)


def _smooth_labels(points: np.ndarray, label: np.ndarray, radius: float, block: int = 200_000) -> np.ndarray:
    """Plate thickness at every boundary point from the labels of some.

    The median of the labels within ``radius`` takes out the noise, and
    gives a point beside a corner, which only pairs across the corner reach
    (longer than the plate is thick), the thickness of the plate faces next
    to it. Points with no label nearby (end faces, convex edges) take the
    nearest labelled point's.
    """
    tree = cKDTree(points)
    neighbours = np.empty((len(points), LABEL_NEIGHBOURS), np.int32)
    for lo in range(0, len(points), block):
        _, idx = tree.query(points[lo:lo + block], k=LABEL_NEIGHBOURS, distance_upper_bound=radius)
        neighbours[lo:lo + block] = idx  # len(points) where fewer are within radius
    padded = np.append(label, np.inf)
    median = np.full(len(points), np.nan)
    for lo in range(0, len(points), block):
        near = padded[neighbours[lo:lo + block]]
        near[~np.isfinite(near)] = np.nan
        some = ~np.all(np.isnan(near), axis=1)  # all-NaN rows stay NaN (no warning: blocks run in threads)
        median[lo:lo + block][some] = np.nanmedian(near[some], axis=1)
    known = np.isfinite(median)
    if not known.all() and known.any():
        _, nearest = cKDTree(points[known]).query(points[~known], k=1)
        median[~known] = median[known][nearest]
    return median
