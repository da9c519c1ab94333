"""Thin parts of a mesh for the Voronoi route's sample: more samples where the solid is thin or a gap narrow.

The spacing of :func:`~medialaxis.mesh.sample.sampling.adaptive_spacing` follows
the coarse medial points of :func:`~medialaxis.mesh.sample.sampling.lfs_estimate`,
which miss plates and gaps thinner than their own spacing. The shrinking
balls of a coarse sample (:func:`local_thickness`) see them: a mostly thin
part gets more samples everywhere, a gap narrower than the spacing more
samples there (:func:`thin_part_count`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.mesh.sample.sampling import MAX_SAMPLES, PseudoNormals, face_spacing_for_count, sample_surface

__all__ = ["thin_part_count", "local_thickness", "THIN_RATIO", "THIN_SHARE", "THIN_SLACK", "THIN_SAMPLES",
           "LOCAL_THIN_RATIO", "LOCAL_THIN_FLOOR", "LOCAL_THIN_GAIN"]

#: By default the sample grows until its spacing on ``THIN_SHARE`` of the
#: surface is at most the local thickness over ``THIN_RATIO``
#: (``voronoi_complex.THIN_SPACINGS`` with a margin: a plate keeps its sheet),
#: up to ``THIN_SAMPLES`` samples, unless it is within ``THIN_SLACK`` of that
#: (the surface next to a box's edges is thin: a box keeps its count).
THIN_RATIO = 3.0
THIN_SHARE = 0.75
THIN_SLACK = 1.25
THIN_SAMPLES = 250_000
#: Faces where a gap of the outside (a cavity, a slit) is narrower than ``LOCAL_THIN_RATIO``
#: spacings are sampled up to ``1 / LOCAL_THIN_FLOOR`` times as finely (:func:`thin_part_count`).
LOCAL_THIN_RATIO = 1.5
LOCAL_THIN_FLOOR = 0.35
#: ... where that makes them at least this factor finer. Each refined mesh costs a second Delaunay
#: insertion (kitten, rocker-arm, camel: 10-20% longer); at 0.5 those ran once, but a box's flat
#: cavity 1.4 spacings wide leaked out again.
LOCAL_THIN_GAIN = 0.9


def local_thickness(points: np.ndarray, normals: np.ndarray, cap: np.ndarray) -> np.ndarray:
    """Diameter of the largest empty ball touching each sample point opposite its normal, up to ``cap``.

    With outward normals the balls are inside the solid; with the normals
    turned, outside (in a gap between two parts, or a cavity).

    The shrinking ball (:func:`~medialaxis.mesh.skeleton._flow_operators.medial_poles`)
    started with the diameter ``cap``: a ball that starts empty gives
    ``cap`` (the thickness is at least that), and no query is made far out.
    """
    from medialaxis.mesh.skeleton._flow_operators import medial_poles

    return 2.0 * medial_poles(np.asarray(points, np.float64), np.asarray(normals, np.float64),
                              max_radius=0.5 * np.asarray(cap, np.float64))[1]


def _facing_back(points: np.ndarray, normals: np.ndarray, diameter: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """For the balls of ``rows``, whether their other contact's normal is over 120 degrees from theirs."""
    centres = points[rows] - 0.5 * diameter[rows, None] * normals[rows]
    near = cKDTree(points).query(centres, k=2)[1].reshape(-1, 2)
    other = np.where(near[:, 0] == rows, near[:, 1], near[:, 0])
    return np.einsum("ij,ij->i", normals[rows], normals[other]) < -0.5


def thin_part_count(mesh: Any, spacing: np.ndarray, count: int, normals: PseudoNormals) -> tuple[int, np.ndarray, str]:
    """``count`` and ``spacing``, or more samples where the surface is mostly thin for them, and a warning.

    The per-face ``spacing`` of :func:`adaptive_spacing` for ``count``
    samples follows the coarse medial points of :func:`lfs_estimate`, which
    miss plates thinner than their own spacing (a 10 x 10 x 0.2 CAD plate:
    0.76 for 0.1); the local thickness of a coarse sample
    (:func:`local_thickness`) sees them. Where the spacing is at most the
    thickness over ``THIN_RATIO`` on ``THIN_SHARE`` of the surface (up to
    ``THIN_SLACK``), both are kept; otherwise the count grows as needed,
    up to ``THIN_SAMPLES`` (then the text returned last, a warning for the
    caller to give, names the count that would do; it is empty otherwise),
    and the spacing shrinks with it.

    Then, locally, the faces where a gap of the outside (the shrinking ball
    on the outer side: a flat cavity, a slit between two parts) is thinner
    than ``LOCAL_THIN_RATIO`` spacings get a spacing of that width over
    ``LOCAL_THIN_RATIO``, bounded by ``LOCAL_THIN_FLOOR`` times the spacing
    (thin parts of the solid itself are the rule above's and the lambda
    filter's, ``voronoi_complex.THIN_SPACINGS``). A face is thin by the
    median of its coarse samples, or by one sample whose ball's other
    contact faces back (normals over 120 degrees apart: the balls of a
    coarse sample measure a gap narrower than their spacing only where two
    samples face each other); beside a concave edge only a strip of a large
    face is thin, and its balls' contacts are 90 degrees apart. The
    lambda-medial sampling asks for a spacing that follows the local feature
    size, which the outer medial axis bounds as well (Amenta and Bern 1999):
    a scanned ogre's cavity 1.2 across and 0.027 thick, 0.038 under its
    surface and sampled 0.1 apart, leaked into the outside (Betti numbers
    (1, 16, 3) for (1, 16, 4)), and two boxes 0.02 apart were joined
    ((1, 15, 0) for (2, 0, 0)).

    No warning is given here: the Voronoi route runs this on a second
    thread, beside the first sample's Delaunay insertion.

    References
    ----------
    .. [1] N. Amenta, M. Bern, "Surface reconstruction by Voronoi filtering", Discrete &
           Computational Geometry 22(4):481-504, 1999. doi:10.1007/PL00009475
    """
    area = np.asarray(mesh.area_faces, np.float64)
    h = face_spacing_for_count(area, np.ones(len(area)), max(count // 8, 2000))
    coarse = sample_surface(mesh, h, normals, limit=len(mesh.vertices) + 100 * count)
    at = spacing[coarse.face]
    thickness = local_thickness(coarse.points, coarse.normals, 2.0 * THIN_RATIO * at)  # a ball far out is slow to query
    need = float(np.percentile(THIN_RATIO * at / np.maximum(thickness, 1e-300), 100 * THIN_SHARE))
    note = ""
    if need > THIN_SLACK:
        wanted = int(min(np.ceil(count * need**2), MAX_SAMPLES))
        note = (
            f"the mesh is mostly thin for its size (a quarter of its surface is under "
            f"{np.percentile(thickness, 25):.3g} thick): {THIN_SAMPLES} samples are taken where about {wanted} "
            f"would keep all its sheets; pass samples={wanted} for them" if wanted > THIN_SAMPLES else "")
        grown = min(wanted, THIN_SAMPLES)
        spacing, count, at = spacing * np.sqrt(count / grown), grown, at * np.sqrt(count / grown)
    # gaps narrower than the spacing (the outer side's balls), in spacings: a face by the median of its
    # samples, or by a sample whose ball's other contact faces back
    cap = LOCAL_THIN_RATIO * at  # wider is not narrow: a ball left empty comes back as cap exactly
    gap = local_thickness(coarse.points, -coarse.normals, cap)
    narrow = gap < cap
    local = np.where(narrow, gap / at, np.inf)
    facing = np.full(len(at), np.inf)
    rows = np.flatnonzero(narrow)
    rows = rows[_facing_back(coarse.points, -coarse.normals, gap, rows)]
    facing[rows] = local[rows]
    order = np.lexsort((local, coarse.face))
    by_face = coarse.face[order]
    start = np.flatnonzero(np.r_[True, by_face[1:] != by_face[:-1]])
    median = local[order][(start + np.r_[start[1:], len(order)]) // 2]
    ratio = np.full(len(spacing), np.inf)
    ratio[by_face[start]] = np.where(median < LOCAL_THIN_RATIO, median, np.inf)
    np.minimum.at(ratio, coarse.face, facing)
    factor = np.maximum(ratio / LOCAL_THIN_RATIO, LOCAL_THIN_FLOOR)
    thin = factor < LOCAL_THIN_GAIN  # a few per cent finer is not worth a second Delaunay insertion
    spacing = spacing.copy()
    spacing[thin] *= factor[thin]
    return count, spacing, note
