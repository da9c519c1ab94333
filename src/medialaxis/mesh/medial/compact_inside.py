"""The compact complex's check that the spheres interpolated over new edges and triangles stay inside.

A round of collapses of :func:`~medialaxis.mesh.medial.compact.compact_complex`
is kept only while the spheres interpolated over the edges and triangles it
makes reach at most ``tolerance`` out of the solid: they are sampled
``LATTICE_SPACING`` tolerances apart in centre and radius, those that the
input balls nearest to them already keep inside are skipped, and the rest
get the surface's signed distance.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.core.arrays import unique_ints
from medialaxis.mesh.medial._compact_kernels import lattice
from medialaxis.mesh.medial._compact_round_kernels import changed_prims

__all__ = ["collapses_inside", "CHUNK", "LATTICE_SPACING", "NEAR_BALLS"]

#: Input balls (nearest centres) whose emptiness bounds an interpolated sphere's reach before the surface is searched.
NEAR_BALLS = 4

#: Spacing of the spheres sampled over new edges and triangles (in centre and radius), times the tolerance.
LATTICE_SPACING = 2.0

#: Rows (spheres, triangles) whose temporaries are made at once: memory bounded whatever the complex's size.
CHUNK = 65_536

def collapses_inside(
    chosen: np.ndarray, src: np.ndarray, dst: np.ndarray, faces: np.ndarray, edges: np.ndarray,
    spheres: np.ndarray, signed: Callable[[np.ndarray, np.ndarray], np.ndarray], centres: cKDTree, tolerance: float,
    label: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The collapses ``src -> dst`` of ``chosen`` whose new edges and triangles stay inside the surface.

    The spheres interpolated over every edge and triangle the round's
    collapses change are sampled ``LATTICE_SPACING`` tolerances apart (in
    centre and radius); a sphere ``(x, r)`` reaches ``r + signed(x, near)`` out of the
    surface, at most ``tolerance`` for a kept collapse;
    the collapses that made an edge or triangle failing this are refused,
    and the rest tested again. Returns the kept collapses, the refused ones
    and the vertices whose stars the kept ones change. ``label[q]`` is the
    vertex (row of ``spheres``) of point ``q`` of ``centres`` and of
    ``signed``'s ``near`` (by default the same).
    """
    n = len(spheres)
    label = np.arange(n) if label is None else label
    refused = np.zeros(len(src), bool)
    while True:
        to = np.arange(n)
        to[src[chosen]] = dst[chosen]
        after, before, touched = changed_prims(faces, edges, to, spheres, LATTICE_SPACING * tolerance)  # an edge: (a, b, b)
        # their samples CHUNK primitives at a time: 2M on the first round of a 40k-vertex torus's complex, whose
        # sample arrays took 0.3 GB at once
        deep = [before[lo : lo + CHUNK][_reaching_out(after[lo : lo + CHUNK], before[lo : lo + CHUNK], spheres, signed,
                                                      centres, tolerance, label)] for lo in range(0, len(after), CHUNK)]
        deep_prims = np.concatenate([np.empty((0, 3), np.int64)] + deep)
        if not len(deep_prims):
            return chosen, np.flatnonzero(refused), np.flatnonzero(touched)
        culprit = np.isin(src[chosen], deep_prims)
        refused[chosen[culprit]] = True
        chosen = chosen[~culprit]


def _reaching_out(
    after: np.ndarray, before: np.ndarray, spheres: np.ndarray, signed: Callable[[np.ndarray, np.ndarray], np.ndarray],
    centres: cKDTree, tolerance: float, label: np.ndarray,
) -> np.ndarray:
    """Which primitives ``after`` (replacing ``before``) carry a sphere reaching more than ``tolerance`` out."""
    samples, owner = lattice(spheres, after, np.c_[after, before], LATTICE_SPACING * tolerance, tolerance)  # corners old and new
    if not len(samples):
        return np.empty(0, np.int64)
    k = min(NEAR_BALLS, len(spheres))
    near, which = centres.query(samples[:, :3], k=k, workers=-1)
    near, which = near.reshape(len(samples), k), which.reshape(len(samples), k)
    far = (samples[:, 3, None] - spheres[label[which], 3] + near).min(axis=1) > tolerance
    samples, owner = samples[far], owner[far]
    deep = samples[:, 3] + signed(samples[:, :3], which[far]) > tolerance if len(samples) else np.zeros(0, bool)
    return unique_ints(owner[deep])
