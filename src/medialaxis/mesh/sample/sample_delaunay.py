"""The surface sample's Delaunay tetrahedralisation, and the work that runs beside it.

The Delaunay insertion (:func:`~medialaxis.mesh.medial.voronoi_diagram.tetrahedralise`)
is serial; the core it leaves idle does the work that needs no tetrahedra. What needs
the mesh only, the crossing faces and the closest-point structures of the inside test
(:func:`surface_structures`), starts before the sampling and runs beside it; what needs
the sample, the check for thin parts of a default sample count
(:func:`~medialaxis.mesh.sample.thin_parts.thin_part_count`, on most meshes keeping the
sample being inserted) and the sampling density epsilon, runs beside the insertion.
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

__all__ = ["tetrahedralised_sample", "surface_structures"]


def surface_structures(work: Any, normals: Any) -> tuple[np.ndarray, SignedDistance | None]:
    """The mesh's crossing face pairs and, if there are none, its signed distance (closest-point structures built).

    Needs the mesh only: started with :class:`~medialaxis._jit.Beside` before the
    sampling, it runs beside it and the Delaunay insertion, and serves every
    sample of the same mesh (a larger count for thin parts, the finer second
    sample). On the uv ellipsoid's 198k faces: 0.65 s and 0.2 s of CPU.
    """
    pairs = crossing_pairs(work)
    if len(pairs):
        return pairs, None  # the sample is of the wrong surface: the caller starts again
    sd = SignedDistance(work, normals)
    sd.prepare_exact(tree=True)  # for the sides in doubt and the compact complex's radii (0.3 s on 200k faces)
    return pairs, sd


def _beside_delaunay(
    work: Any, points: np.ndarray, rng: np.random.Generator, tree: Any, normals: Any, thin: Any, surface: Beside
) -> tuple[Any, float, float]:
    """What needs the sample but not its Delaunay: the thin-part check, then epsilon.

    Waits for ``surface`` first (the crossing check), then checks ``thin``, the
    sample's ``(count, spacing)`` (:func:`thin_part_count`). If the surface
    crosses itself or the check wants more samples, epsilon is not measured
    (it draws from ``rng``: only the sample the complex is built on draws).
    """
    crossing = len(surface.result()[0])  # first, so that no third thread competes with the insertion
    more = None if thin is None else thin_part_count(work, thin[1], thin[0], normals)
    if crossing or more is not None and (more[0] != thin[0] or not np.array_equal(more[1], thin[1])):
        return more, 0.0, 0.0
    eps, eps_lfs = measure_epsilon(work, points, rng, 100_000, lambda x: tree.query(x, workers=-1)[0])
    return more, eps, eps_lfs


def tetrahedralised_sample(
    work: Any, smp: Any, rng: Any, tree: Any, normals: Any, thin: Any, timings: dict[str, float], surface: Beside
) -> tuple[Any, ...]:
    """The sample's Delaunay tetrahedralisation (or the error it raised), ``more``, the crossing pairs, epsilon, epsilon/lfs, the signed distance.

    Beside the serial insertion run the thin-part check and epsilon
    (:func:`_beside_delaunay`; about 1 s of CPU beside the 1.5 s of the uv
    ellipsoid's insertion, one thread each) and what is left of
    ``surface`` (a :class:`~medialaxis._jit.Beside` of :func:`surface_structures`
    for ``work``). The pairs and the signed distance are ``surface``'s;
    epsilon is 0 when ``more`` asks for another sample or there are pairs.
    """
    t0 = time.perf_counter()
    side = Beside(_beside_delaunay, work, smp.points, rng, tree, normals, thin, surface)
    try:
        dt = tetrahedralise(smp.points)
    except MedialAxisError as exc:
        dt = exc
    timings["delaunay"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    more, eps, eps_lfs = side.result()
    pairs, sd = surface.result()
    timings["epsilon"] = time.perf_counter() - t0
    return dt, more, pairs, eps, eps_lfs, sd
