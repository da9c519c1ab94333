"""The surface sample's Delaunay tetrahedralisation, and the work that needs the sample but not its tetrahedra.

The Delaunay insertion (:func:`~medialaxis.mesh.medial.voronoi_diagram.tetrahedralise`)
is serial; beside it, on the other core, run the check for thin parts of a
default sample count (:func:`~medialaxis.mesh.sample.thin_parts.thin_part_count`, on
most meshes keeping the sample being inserted), the crossing faces, the
sampling density epsilon and the closest-point structures of the inside test.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from medialaxis._jit import Beside
from medialaxis.errors import MedialAxisError
from medialaxis.mesh.medial.voronoi_diagram import tetrahedralise
from medialaxis.mesh.sample.sampling import measure_epsilon
from medialaxis.mesh.sample.signed_distance import SignedDistance
from medialaxis.mesh.sample.thin_parts import thin_part_count
from medialaxis.mesh.solid.crossings import crossing_pairs

__all__ = ["tetrahedralised_sample"]


def _beside_delaunay(
    work: Any, points: np.ndarray, rng: np.random.Generator, tree: Any, normals: Any, thin: Any
) -> tuple[Any, np.ndarray, float, float, SignedDistance | None]:
    """What needs the sample but not its Delaunay: the thin-part check, the crossing faces, epsilon, the signed distance.

    ``thin``: the sample's ``(count, spacing)``, checked first (:func:`thin_part_count`, whose
    answer comes first); if that wants more samples, nothing else is done.
    """
    more = None if thin is None else thin_part_count(work, thin[1], thin[0], normals)
    if more is not None and (more[0] != thin[0] or not np.array_equal(more[1], thin[1])):
        return more, np.empty((0, 2), np.int64), 0.0, 0.0, None
    pairs = crossing_pairs(work)
    if len(pairs):
        return more, pairs, 0.0, 0.0, None  # the sample is of the wrong surface: the caller starts again
    eps, eps_lfs = measure_epsilon(work, points, rng, 100_000, lambda x: tree.query(x, workers=-1)[0])
    sd = SignedDistance(work, normals)
    sd.prepare_exact(tree=True)  # for the sides in doubt and the compact complex's radii (0.3 s on 200k faces)
    return more, pairs, eps, eps_lfs, sd


def tetrahedralised_sample(work: Any, smp: Any, rng: Any, tree: Any, normals: Any, thin: Any, timings: dict[str, float]) -> tuple[Any, ...]:
    """The sample's Delaunay tetrahedralisation (or the error it raised), then what :func:`_beside_delaunay` gives.

    That runs on the core the serial Delaunay insertion leaves idle (the
    thin-part check, the crossing check, epsilon and the closest-point
    structures: 1.4-1.7 s of CPU beside the 1.6 s of the uv ellipsoid's
    Delaunay, one thread each; as long, so a faster or parallel insertion
    alone would not shorten this step).
    """
    t0 = time.perf_counter()
    side = Beside(_beside_delaunay, work, smp.points, rng, tree, normals, thin)
    try:
        dt = tetrahedralise(smp.points)
    except MedialAxisError as exc:
        dt = exc
    timings["delaunay"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    found = side.result()
    timings["epsilon"] = time.perf_counter() - t0
    return (dt, *found)
