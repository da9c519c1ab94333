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

from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.volume.distance import Features
from medialaxis.volume.plates import ANTIPODAL_COS, PlateThickness, pair_cosines, pair_gaps

__all__ = ["MedialVoxels", "MedialPairs", "PlateThickness", "medial_voxels", "medial_pairs", "judge_pairs",
           "pairs_to_voxels", "DEFAULT_LAM_RATIO"]

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

    References
    ----------
    .. [1] S. Prohaska, H.-C. Hege, "Fast visualization of plane-like structures in voxel data",
           Proc. IEEE Visualization 2002, 29-36, 2002. doi:10.1109/VISUAL.2002.1183753
    .. [2] M. Foskey, M. C. Lin, D. Manocha, "Efficient computation of a simplified medial
           axis", Proc. ACM Symposium on Solid Modeling and Applications, 96-107, 2003.
           doi:10.1145/781606.781623
    .. [3] F. Chazal, A. Lieutier, "The lambda-medial axis", Graphical Models, 2005.
           doi:10.1016/j.gmod.2005.01.002
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
    for axis, (p, q, gap) in enumerate(pair_gaps(features, shortest)):
        fp, fq = F[p], F[q]
        # separation angle: the contact directions of a sheet are opposite; at
        # convex edges and where an end face meets a junction they are ~90 deg
        cos = pair_cosines(features, p, q)
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
