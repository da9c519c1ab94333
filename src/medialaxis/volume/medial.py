"""Medial voxels: the grid form of the lambda-medial axis (Prohaska and Hege).

Two 6-adjacent foreground voxels ``p``, ``q`` whose nearest boundary points
``f(p)``, ``f(q)`` are more than ``lam`` apart, in directions more than 120
degrees apart, straddle the medial surface;
the one closer to the bisector plane of ``f(p)`` and ``f(q)`` is marked
(ties go to the lower index), so even thicknesses give a one-voxel sheet.
Each medial voxel keeps the sub-voxel mid-surface point (on the bisector
planes of the pairs that marked it), half the distance between the boundary
points (the radius) and their direction (the sheet normal).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.volume.distance import Features

__all__ = ["MedialVoxels", "medial_voxels", "estimate_thickness", "DEFAULT_LAM_RATIO"]

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
    unit = float(features.spacing.max())
    P = (features.voxels + features.offset) * features.spacing
    found = []
    for p, q, gap in _pair_gaps(features):
        keep = gap > 2.0 * unit
        p, q, gap = p[keep], q[keep], gap[keep]
        up = features.feature[p] - P[p]
        uq = features.feature[q] - P[q]
        cos = np.einsum("ij,ij->i", up, uq) / np.maximum(
            np.linalg.norm(up, axis=1) * np.linalg.norm(uq, axis=1), 1e-12)
        found.append(gap[cos < -ANTIPODAL_COS])
    gaps = np.concatenate(found)
    if len(gaps) == 0:
        raise EmptyShapeError("the part is too thin to have medial voxels (thinner than ~2 voxels)")
    return float(np.median(gaps))


def medial_voxels(features: Features, lam: float, thickness: float | None = None) -> MedialVoxels:
    """Medial voxels whose contact points are more than ``lam`` apart.

    Parameters
    ----------
    features : Features
    lam : float
        Smallest distance between the two nearest boundary points of a medial
        voxel pair (physical units), the lambda of the lambda-medial axis.
    thickness : float, optional
        Nominal thickness; when given, pairs narrower than 0.9 of it must also
        pass the separation-angle test.

    Returns
    -------
    MedialVoxels

    Raises
    ------
    InvalidInputError
        If ``lam`` is not positive.
    EmptyShapeError
        If no voxel is medial for this ``lam``.
    """
    if not np.isfinite(lam) or lam <= 0:
        raise InvalidInputError(f"lam must be finite and > 0, got {lam!r}")
    n = len(features.voxels)
    unit = float(features.spacing.min())
    if thickness is None:
        thickness = 0.0
    F = features.feature
    P = (features.voxels + features.offset) * features.spacing
    acc_mid = np.zeros((n, 3))
    acc_normal = np.zeros((n, 3))
    acc_q = np.zeros((n, 3, 3))  # sum of u u^T over the pairs (plane quadric)
    acc_qm = np.zeros((n, 3))  # sum of u u^T mid
    acc_gap = np.zeros(n)
    count = np.zeros(n)
    for p, q, gap in _pair_gaps(features):
        keep = gap > lam
        p, q, gap = p[keep], q[keep], gap[keep]
        fp, fq = F[p], F[q]
        # separation angle: the contact directions of a sheet are opposite; at
        # convex edges and where an end face meets a junction they are ~90 deg
        up, uq = fp - P[p], fq - P[q]
        cos = np.einsum("ij,ij->i", up, uq) / np.maximum(np.linalg.norm(up, axis=1) * np.linalg.norm(uq, axis=1), 1e-12)
        wide = (cos < SEPARATION_COS) | (gap >= FULL_GAP * thickness)
        p, q, gap, fp, fq = p[wide], q[wide], gap[wide], fp[wide], fq[wide]
        mid = 0.5 * (fp + fq)
        u = (fq - fp) / gap[:, None]
        sp = np.abs(np.einsum("ij,ij->i", P[p] - mid, u))
        sq = np.abs(np.einsum("ij,ij->i", P[q] - mid, u))
        # near-ties go to the lower voxel so noise does not make the sheet ragged
        chosen = np.where(sp <= sq + TIE_TOLERANCE * unit, p, q)
        # orient normals consistently (largest component positive) before averaging
        flip = np.take_along_axis(u, np.abs(u).argmax(axis=1)[:, None], axis=1)[:, 0] < 0
        u[flip] *= -1
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
        raise EmptyShapeError(f"no medial voxel for lam={lam:g}: the thickness or lam is larger than the part allows")
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
    return MedialVoxels(
        voxels=features.voxels[rows],
        position=position,
        radius=0.5 * acc_gap[rows] / c,
        normal=normal,
        distance=features.distance[rows],
        coherence=coherence,
    )
