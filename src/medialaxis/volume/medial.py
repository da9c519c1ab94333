"""Medial voxels: the grid form of the lambda-medial axis (Prohaska and Hege).

Two 6-adjacent foreground voxels ``p``, ``q`` whose nearest boundary points
``f(p)``, ``f(q)`` are more than ``lam`` apart, in directions more than 120
degrees apart, straddle the medial surface;
the one closer to the bisector plane of ``f(p)`` and ``f(q)`` is marked
(ties go to the lower index), so even thicknesses give a one-voxel sheet.
Each medial voxel keeps the sub-voxel mid-surface point (on the bisector
planes of the pairs that marked it), half the distance between the boundary
points (the radius) and their direction (the sheet normal).

``lam`` and the separation-angle exemption are measured against a plate
thickness (:class:`PlateThickness`): one nominal value for the whole part, or
the thickness of the plate each boundary point belongs to, so that a part
whose ribs are thinner than its walls keeps both (a pair compares itself with
the thinner of the two plates it touches).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.volume.distance import Features

__all__ = ["MedialVoxels", "PlateThickness", "medial_voxels", "plate_thickness", "estimate_thickness",
           "plate_pairs", "plate_summary", "plate_labels", "nominal_thicknesses", "label_shortest",
           "DEFAULT_LAM_RATIO", "DEFAULT_MIN_THICKNESS"]

#: Default ``lam`` as a fraction of the thickness: keeps every sheet (contact
#: sets ~ thickness apart) and drops the branches into convex edges and corners,
#: whose contact sets are at most ``thickness / sqrt(2)`` apart.
DEFAULT_LAM_RATIO = 0.75
#: A pair whose bisector is within this many voxels of the middle marks its
#: lower voxel, so that noise on an even-thickness plate gives a flat sheet.
TIE_TOLERANCE = 0.5
#: A medial pair narrower than ``FULL_GAP * thickness`` must have contact
#: directions more than 120 degrees apart (cos below this): the separation
#: angle of Foskey et al. It removes the fins into convex edges that survive
#: ``lam`` where the radius is large (an end face next to a junction: gap up
#: to ~0.88 thickness at 90 degrees); pairs spanning a full thickness (sheets,
#: the corners of an X junction) are kept whatever their angle.
SEPARATION_COS = -0.5
FULL_GAP = 0.9
#: Weight (relative to one plane) that holds a medial voxel's position near the
#: mean midpoint of its pairs along directions no plane constrains.
POSITION_REGULARIZATION = 0.01
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
class MedialVoxels:
    """The medial voxels of a volume.

    Attributes
    ----------
    voxels : (n, 3) int64 ndarray
        Crop indices (see :class:`~medialaxis.volume.distance.Features`).
    position : (n, 3) float64 ndarray
        Sub-voxel mid-surface point: the least-squares point of the bisector
        planes of the voxel's pairs, near their mean midpoint (physical units).
    radius : (n,) float64 ndarray
        Half the mean distance between the pairs' boundary points.
    normal : (n, 3) float64 ndarray
        Unit direction between the boundary points (sign arbitrary).
    distance : (n,) float64 ndarray
        Distance transform at the voxel.
    coherence : (n,) float64 ndarray
        Length of the mean pair direction: 1 on a sheet, lower on creases
        and junctions where the pairs cross two sheets.
    """

    voxels: np.ndarray
    position: np.ndarray
    radius: np.ndarray
    normal: np.ndarray
    distance: np.ndarray
    coherence: np.ndarray
    sheet_pairs: int = 0
    dropped_gaps: np.ndarray = dataclasses.field(default_factory=lambda: np.empty(0))


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


def _pair_gaps(features: Features) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    out = []
    for axis in range(3):
        p, q = _pairs(features, axis)
        gap = np.linalg.norm(features.feature[p] - features.feature[q], axis=1)
        out.append((p, q, gap))
    return out


def _cosines(features: Features, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Cosine of the angle between the directions from ``p`` and ``q`` to their nearest boundary points."""
    P_p = (features.voxels[p] + features.offset) * features.spacing
    P_q = (features.voxels[q] + features.offset) * features.spacing
    up = features.feature[p] - P_p
    uq = features.feature[q] - P_q
    return np.einsum("ij,ij->i", up, uq) / np.maximum(np.linalg.norm(up, axis=1) * np.linalg.norm(uq, axis=1), 1e-12)


def plate_pairs(features: Features, shortest: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Adjacent voxel pairs that see the two faces of a plate (antipodal contacts), longer than ``shortest``."""
    out_p, out_q, out_gap = [], [], []
    for p, q, gap in _pair_gaps(features):
        keep = gap > shortest
        p, q, gap = p[keep], q[keep], gap[keep]
        sheet = _cosines(features, p, q) < -ANTIPODAL_COS
        out_p.append(p[sheet])
        out_q.append(q[sheet])
        out_gap.append(gap[sheet])
    return np.concatenate(out_p), np.concatenate(out_q), np.concatenate(out_gap)


def estimate_thickness(features: Features) -> float:
    """Nominal plate thickness from the pairs of adjacent voxels that see
    opposite faces of a plate.

    A pair straddling a plate's mid-surface has nearest boundary points on
    the two faces, in opposite directions (antipodal), and their distance is
    the local thickness. Pairs near edges and corners see faces at an angle
    and are left out. The estimate is the median over antipodal pairs.

    Parameters
    ----------
    features : Features

    Returns
    -------
    float
        Thickness in physical units.

    Raises
    ------
    EmptyShapeError
        If the part has no interior (no straddling pair).
    """
    gaps = plate_pairs(features, 2.0 * float(features.spacing.max()))[2]
    if len(gaps) == 0:
        raise EmptyShapeError("the part is too thin to have medial voxels (thinner than ~2 voxels)")
    return float(np.median(gaps))


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
        found = f"; the plates found are {np.min(gap):.3g} to {np.max(gap):.3g} thick" if len(gap) else ""
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
    from scipy.ndimage import gaussian_filter1d
    from scipy.signal import find_peaks

    step = 0.25 * unit
    edges = np.arange(gap.min() - 2 * step, gap.max() + 3 * step, step)
    hist = gaussian_filter1d(np.histogram(gap, edges)[0].astype(np.float64), 2.0)
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


def medial_voxels(features: Features, lam: float | None, thickness: float | PlateThickness | None = None,
                  counted: np.ndarray | None = None) -> MedialVoxels:
    """Medial voxels whose contact points are more than ``lam`` apart.

    Parameters
    ----------
    features : Features
    lam : float or None
        Smallest distance between the two nearest boundary points of a medial
        voxel pair (physical units), the lambda of the lambda-medial axis.
        ``None`` (local ``thickness`` only): ``DEFAULT_LAM_RATIO`` times the
        thickness of the plate each pair touches.
    thickness : float or PlateThickness, optional
        Nominal thickness, or the thickness of each plate: pairs narrower
        than 0.9 of it must also pass the separation-angle test, and in
        local mode pairs on plates outside its bounds are left out.
    counted : (n,) bool ndarray, optional
        Voxels whose pairs (as the lower voxel) count in ``sheet_pairs`` and
        ``dropped_gaps`` (a block of a volume counts the pairs it owns).

    Returns
    -------
    MedialVoxels
        With ``sheet_pairs`` (pairs that see both faces of a plate) and
        ``dropped_gaps`` (the thickness at each of those that was left out).

    Raises
    ------
    InvalidInputError
        If ``lam`` is not positive.
    EmptyShapeError
        If no voxel is medial for this ``lam``.
    """
    plates = thickness if isinstance(thickness, PlateThickness) else None
    if lam is None and not (plates is not None and plates.local):
        if plates is None:
            raise InvalidInputError("lam is required unless the thickness is given per plate")
        lam = DEFAULT_LAM_RATIO * plates.value
    if lam is not None and (not np.isfinite(lam) or lam <= 0):
        raise InvalidInputError(f"lam must be finite and > 0, got {lam!r}")
    nominal = 0.0 if thickness is None else (plates.value if plates is not None else float(thickness))
    unit = float(features.spacing.min())
    if plates is not None and plates.local:
        shortest = DEFAULT_LAM_RATIO * plates.lower if lam is None else lam
    else:
        shortest = float(lam)  # type: ignore[arg-type]
    # pairs of a plate too thin for lam are counted (they are dropped)
    pairs = medial_pairs(features, min(shortest, 1.5 * unit),
                         plates.boundary if plates is not None and plates.local else None)
    keep, sheet = judge_pairs(pairs, lam, plates, nominal, unit)
    if counted is not None:
        sheet &= counted[pairs.p]
    medial = pairs_to_voxels(pairs, keep, len(features.voxels))
    if medial is None:
        what = f"lam={lam:g}" if lam is not None else f"plates {plates.lower:g} to {plates.upper:g} thick"  # type: ignore[union-attr]
        raise EmptyShapeError(f"no medial voxel for {what}: the thickness or lam is larger than the part allows")
    rows, position, radius, normal, coherence = medial
    return MedialVoxels(
        voxels=features.voxels[rows],
        position=position,
        radius=radius,
        normal=normal,
        distance=features.distance[rows],
        coherence=coherence,
        sheet_pairs=int(sheet.sum()),
        dropped_gaps=pairs.gap[sheet & ~keep],
    )


@dataclasses.dataclass(frozen=True)
class MedialPairs:
    """Candidate medial pairs of adjacent voxels, axis by axis in grid order.

    Attributes
    ----------
    axis : (k,) int8 ndarray
        The axis along which the pair is adjacent (pairs are sorted by it).
    p, q : (k,) int64 ndarray
        Rows of the lower and upper voxel.
    gap, cos : (k,) float64 ndarray
        Distance between their nearest boundary points, and the cosine of
        the angle between the directions to them.
    local : (k,) float64 ndarray or None
        Thickness of the thinner plate the pair touches (per-plate mode).
    chosen : (k,) int64 ndarray
        Row of the voxel the pair marks (nearer the bisector plane).
    mid, u : (k, 3) float64 ndarray
        Mid-point of the boundary points and the unit direction between
        them, oriented with its largest component positive.
    """

    axis: np.ndarray
    p: np.ndarray
    q: np.ndarray
    gap: np.ndarray
    cos: np.ndarray
    local: np.ndarray | None
    chosen: np.ndarray
    mid: np.ndarray
    u: np.ndarray

    def subset(self, keep: np.ndarray) -> MedialPairs:
        return MedialPairs(*(None if v is None else v[keep] for v in dataclasses.astuple(self)))  # type: ignore[arg-type]


def medial_pairs(features: Features, shortest: float, labels: np.ndarray | None = None) -> MedialPairs:
    """Adjacent voxel pairs whose nearest boundary points are more than ``shortest`` apart.

    ``labels`` (per boundary point plate thickness) gives each pair the
    thinner plate it touches.
    """
    unit = float(features.spacing.min())
    F = features.feature
    P = (features.voxels + features.offset) * features.spacing
    out = []
    for axis, (p, q, gap) in enumerate(_pair_gaps(features)):
        candidate = gap > shortest
        p, q, gap = p[candidate], q[candidate], gap[candidate]
        fp, fq = F[p], F[q]
        # separation angle: the contact directions of a sheet are opposite; at
        # convex edges and where an end face meets a junction they are ~90 deg
        cos = _cosines(features, p, q)
        local = None
        if labels is not None:
            # each pair is judged by the thinner of the plates it touches
            local = np.minimum(labels[features.feature_index[p]], labels[features.feature_index[q]])
        mid = 0.5 * (fp + fq)
        u = (fq - fp) / gap[:, None]
        sp = np.abs(np.einsum("ij,ij->i", P[p] - mid, u))
        sq = np.abs(np.einsum("ij,ij->i", P[q] - mid, u))
        # near-ties go to the lower voxel so noise does not make the sheet ragged
        chosen = np.where(sp <= sq + TIE_TOLERANCE * unit, p, q)
        # orient normals consistently (largest component positive) before averaging
        flip = np.take_along_axis(u, np.abs(u).argmax(axis=1)[:, None], axis=1)[:, 0] < 0
        u[flip] *= -1
        out.append(MedialPairs(np.full(len(p), axis, np.int8), p, q, gap, cos, local, chosen, mid, u))
    return MedialPairs(*(
        None if out[0].local is None and name == "local" else np.concatenate([getattr(o, name) for o in out])
        for name in (f.name for f in dataclasses.fields(MedialPairs))
    ))


def judge_pairs(pairs: MedialPairs, lam: float | None, plates: PlateThickness | None, nominal: float,
                unit: float) -> tuple[np.ndarray, np.ndarray]:
    """Which pairs mark a medial voxel (``keep``), and which see both faces of a plate (``sheet``)."""
    gap, cos = pairs.gap, pairs.cos
    if plates is not None and plates.local:
        local = pairs.local
        lam_pair = DEFAULT_LAM_RATIO * local if lam is None else np.full(len(gap), float(lam))
        keep = (gap > lam_pair) & (local >= plates.lower) & (local <= plates.upper)
    else:
        local = np.full(len(gap), nominal)
        keep = gap > float(lam)  # type: ignore[arg-type]
    keep &= (cos < SEPARATION_COS) | (gap >= FULL_GAP * local)
    sheet = (cos < -ANTIPODAL_COS) & (gap > 1.5 * unit)
    return keep, sheet


def pairs_to_voxels(pairs: MedialPairs, keep: np.ndarray, n: int) -> tuple[np.ndarray, ...] | None:
    """Rows, positions, radii, normals and coherence of the voxels the kept pairs mark (None: none).

    Sums run axis by axis in pair order, as the medial test visits them, so a
    voxel gets the same figures from any block that holds all its pairs.
    """
    acc_mid = np.zeros((n, 3))
    acc_normal = np.zeros((n, 3))
    acc_q = np.zeros((n, 3, 3))  # sum of u u^T over the pairs (plane quadric)
    acc_qm = np.zeros((n, 3))  # sum of u u^T mid
    acc_gap = np.zeros(n)
    count = np.zeros(n)
    for axis in range(3):
        sel = keep & (pairs.axis == axis)
        chosen, mid, u, gap = pairs.chosen[sel], pairs.mid[sel], pairs.u[sel], pairs.gap[sel]
        uu = u[:, :, None] * u[:, None, :]
        uum = np.einsum("kij,kj->ki", uu, mid)
        for k in range(3):
            acc_mid[:, k] += np.bincount(chosen, mid[:, k], minlength=n)
            acc_normal[:, k] += np.bincount(chosen, u[:, k], minlength=n)
            acc_qm[:, k] += np.bincount(chosen, uum[:, k], minlength=n)
            for m in range(3):
                acc_q[:, k, m] += np.bincount(chosen, uu[:, k, m], minlength=n)
        acc_gap += np.bincount(chosen, gap, minlength=n)
        count += np.bincount(chosen, minlength=n)
    rows = np.flatnonzero(count)
    if len(rows) == 0:
        return None
    c = count[rows]
    normal = acc_normal[rows] / c[:, None]
    coherence = np.linalg.norm(normal, axis=1)
    normal /= np.maximum(coherence[:, None], 1e-12)
    # Position: least squares on the bisector planes of the voxel's pairs, held
    # near their mean midpoint. One plane (a sheet): the midpoint. Planes of
    # two sheets (a crease or a junction): their intersection next to it.
    centre = acc_mid[rows] / c[:, None]
    q = acc_q[rows] / c[:, None, None] + POSITION_REGULARIZATION * np.eye(3)
    rhs = acc_qm[rows] / c[:, None] + POSITION_REGULARIZATION * centre
    position = np.linalg.solve(q, rhs[:, :, None])[:, :, 0]
    return rows, position, 0.5 * acc_gap[rows] / c, normal, coherence
