"""The inner Delaunay tetrahedra of a surface sample: their union stands for the solid.

The medial complex of the Voronoi route is the dual of the union of the
Delaunay tetrahedra inside the solid
(:func:`~medialaxis.mesh.medial.voronoi_complex.medial_complex`), so that union must
have the solid's topology. A tetrahedron is inner when its centroid is
inside; two things made the union wrong, and are mended here:

* flat tetrahedra on the surface whose centroids are a hair inside
  (``FLAT_DEPTH``);
* a centroid signed by the faces at the tetrahedron's own samples although
  it lies nearer another part of the surface (checked against its nearest
  sample, :meth:`~medialaxis.mesh.sample.signed_distance.SignedDistance.recheck_sides`).

What is left, pinched edges and points of the union, is :func:`unpinch`'s; it also
finds where the sample is too coarse for the solid (``POCKET_FLAT``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.mesh.medial._voronoi_kernels import (
    minor_star_groups,
    nearest_other_sample,
    small_cavities,
    tet_centroids,
)
from medialaxis.mesh.sample.signed_distance import SignedDistance

__all__ = ["inner_tets", "unpinch", "FLAT_DEPTH", "CAVITY_SHARE", "POCKET_FLAT"]

#: A tetrahedron is inner when its centroid is deeper than this fraction of
#: its longest edge. Surface slivers on a sphere of radius R sampled at
#: spacing s lie about s / (8 R) deep: 1e-5 keeps them up to R = 12,500 s;
#: 1e-3 leaves samples covered on the uv ellipsoid again.
FLAT_DEPTH = 1e-5
#: Rounds of :func:`unpinch` at most.
UNPINCH_ROUNDS = 5
#: A cavity of the inner union (outer tetrahedra it encloses) holding at most
#: this share of its longest edge cubed is filled by :func:`unpinch`: a
#: cavity the sample resolves is at least a few spacings across (a gap this
#: thin between two shells is a hundredth of their sampling spacing).
CAVITY_SHARE = 0.01
#: An outer tetrahedron :func:`unpinch` fills as a pocket is thick when its height over its largest
#: face is at least this share of its longest edge: not a sliver on the surface, but air the sample
#: does not resolve (a scanned seahorse's two air passages narrower than its spacing: 0.22 and 0.26;
#: its slivers 0.004-0.035).
POCKET_FLAT = 0.1



def inner_tets(dt: Any, smp: Any, sd: SignedDistance, tolerance: float) -> np.ndarray:
    """Inner tetrahedra: centroid deeper than ``tolerance`` and than ``FLAT_DEPTH`` times the longest edge.

    Flat tetrahedra lying on a face of the mesh are not inner, nor those
    lying on a nearly flat part of it: on the cap of a uv sphere, stacks of
    them with three nearly collinear samples are a hair inside, cover
    samples of the cap (every tetrahedron around such a sample is inner, its
    Voronoi cell is closed and the medial complex gains a void: 57 on a
    224 x 224 uv ellipsoid) and bring circumcentres from far away. The
    side found among the faces at a tetrahedron's samples is checked against
    the sample nearest to its centroid.

    Parameters
    ----------
    dt : Tetrahedralisation
    smp : SurfaceSample
        The samples (``face``: the face of each).
    sd : SignedDistance
    tolerance : float
        Smallest depth of an inner centroid.

    Returns
    -------
    (t,) bool ndarray
    """
    centroids = tet_centroids(dt.points, dt.simplices)
    signed, _ = sd.query(centroids, smp.face[dt.simplices])
    normals = sd.normals.face[smp.face]
    nearest = nearest_other_sample(centroids, dt.points, dt.simplices, dt.centres, dt.radii, normals, signed)
    sd.recheck_sides(centroids, signed, nearest, dt.points, smp.face)
    return signed < -np.maximum(tolerance, FLAT_DEPTH * dt.longest)


def unpinch(dt: Any, inner: np.ndarray, thick: np.ndarray | None = None) -> np.ndarray:
    """Inner tetrahedra whose union is not pinched at a sample point.

    Around a sample point on the surface, flat tetrahedra whose centroids
    lie a hair inside or outside can alternate: the union of the inner ones
    is pinched there, and its dual complex, which joins tetrahedra only
    through shared triangles, gains cycles that the solid does not have. In
    each round, around every point, inner tetrahedra outside the point's
    largest inner group (by volume) become outer, and outer tetrahedra
    outside its largest outer group (the one reaching beyond the convex
    hull) become inner, and so do the cavities of the union too small for
    the sampling (``CAVITY_SHARE``: sliver tetrahedra a hair outside, enclosed
    by others a hair inside where the surface is noisy; 61 of them on a uv
    ellipsoid whose vertices were moved along it by a tenth of their
    shortest edge, each a void of the medial complex). Rounds repeat until nothing changes
    (``UNPINCH_ROUNDS`` at most). A pinch along an edge is a pinch at both
    its points, and is mended there: dropping all but the largest run of
    inner tetrahedra around such an edge as well (the rule until now) cut
    thin bridges and gave extra cycles on a scanned cow and a perforated
    plate (at 20k-80k samples: (1, 2, 0) for (1, 1, 0), (1, 25, 0) for
    (1, 24, 0)), while no model of ``benchmarks/bench_mesh_routes.py``
    needed it.

    A pocket filled is flat when the surface is noisy, but a thick one
    (``POCKET_FLAT``) is air the sample does not resolve: either a thin
    wall of the solid sealed (right) or an air passage narrower than the
    sample closed (wrong: a scanned seahorse loses two handles so). The
    two look alike to every local measure tried; a finer sample there
    tells them apart (:func:`~medialaxis.mesh.sample.sampling.local_caps`).

    Parameters
    ----------
    dt : Tetrahedralisation
    inner : (t,) bool ndarray
    thick : (t,) bool ndarray, optional
        Set where a thick pocket is filled.

    Returns
    -------
    (t,) bool ndarray
        A corrected copy.
    """
    inner = np.array(inner, dtype=bool, copy=True)
    volume = dt.volume
    # A point's groups depend on its star alone: a call needs to look only at the points with a
    # tetrahedron written since the same call last ran (a flag set back counts: pockets filled
    # and strays dropped can alternate on the same tetrahedra round after round).
    written_stray, written_pocket = np.ones(len(inner), bool), np.ones(len(inner), bool)
    for _ in range(UNPINCH_ROUNDS):
        # around a point, the inner tetrahedra must be one group and the
        # outer ones one group: drop inner strays, fill outer pockets
        stray = minor_star_groups(dt.simplices, dt.neighbors, inner, volume, len(dt.points), False, written_stray)
        written_stray[:] = False
        inner[stray] = False
        written_stray |= stray
        written_pocket |= stray
        pocket = minor_star_groups(dt.simplices, dt.neighbors, ~inner, volume, len(dt.points), True, written_pocket)
        written_pocket[:] = False
        inner[pocket] = True
        if thick is not None and pocket.any():
            thick[np.flatnonzero(pocket)[flat_share(dt, np.flatnonzero(pocket)) >= POCKET_FLAT]] = True
        # cavities of the union too small for the sampling (sliver tetrahedra on a noisy surface)
        cavity = small_cavities(dt.neighbors, inner, volume, dt.longest, CAVITY_SHARE)
        inner[cavity] = True
        for flags in (written_stray, written_pocket):
            flags |= pocket | cavity
        if not stray.any() and not pocket.any() and not cavity.any():
            break
    return inner


def flat_share(dt: Any, tets: np.ndarray) -> np.ndarray:
    """Height of each tetrahedron over its largest face, over its longest edge (a regular one: 0.58)."""
    c = dt.points[dt.simplices[tets]]
    twice_area = np.max([np.linalg.norm(np.cross(c[:, j] - c[:, i], c[:, k] - c[:, i]), axis=1)
                         for i, j, k in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3))], axis=0)
    return 6.0 * dt.volume[tets] / np.maximum(twice_area * dt.longest[tets], 1e-300)
