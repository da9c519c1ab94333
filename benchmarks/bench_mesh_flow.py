"""Benchmark: diffusion-flow curve skeleton of a large tripod mesh vs. skeletor.

Builds a tripod of three capsules (radius 0.5, arms 3) by marching cubes with
about 164,000 vertices, skeletonizes it with ``medial_axis(method="flow")`` and
with skeletor's mesh contraction (Au et al. 2008) followed by its vertex
clustering, in the same run, and prints time and accuracy of both and the
ratio. skeletor is GPL-3.0 and only used here (``pip install medialaxis[bench]``).

Usage::

    PYTHONPATH=src python benchmarks/bench_mesh_flow.py [--pitch 0.0167] [--skeletor-time-limit 300]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np


def accuracy(points: np.ndarray, segments: np.ndarray) -> str:
    from medialaxis.datasets import segment_distance

    d = segment_distance(points, segments)
    return f"{len(points)} nodes, distance to axes p99 {np.percentile(d, 99):.3f} mean {d.mean():.3f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pitch", type=float, default=0.0167, help="marching-cubes step (0.0167: ~164k vertices)")
    parser.add_argument("--skeletor-time-limit", type=float, default=300.0, help="seconds allowed to skeletor's contraction")
    parser.add_argument("--cache", default="", help="PLY path to cache the generated mesh")
    args = parser.parse_args()

    import trimesh

    import medialaxis as mx
    from medialaxis.datasets import tripod_mesh, tripod_segments

    if args.cache and os.path.exists(args.cache):
        mesh = trimesh.load(args.cache, process=False)
    else:
        mesh = tripod_mesh(radius=0.5, arm=3.0, pitch=args.pitch)
        if args.cache:
            mesh.export(args.cache)
    segments = tripod_segments(3.0)
    print(f"mesh: tripod, {len(mesh.vertices)} vertices, {len(mesh.faces)} faces; {os.cpu_count()} CPUs (shared)")

    t0 = time.perf_counter()
    sk = mx.medial_axis(mesh, method="flow")
    ours = time.perf_counter() - t0
    print(
        f"medialaxis flow: {ours:.1f} s ({sk.metadata['steps']} steps); {accuracy(sk.points, segments)}; "
        f"{len(sk.endpoints)} endpoints, {len(sk.junctions)} junctions"
    )

    try:
        import skeletor
    except ImportError:
        print("skeletor not installed (pip install skeletor); no peer figure")
        return
    # 1. mesh contraction (Au et al. 2008) + vertex clusters, the method the issue compares with.
    #    WL0=1: skeletor's WL0="auto" (1e-3 sqrt(mean face area)) leaves even small versions of
    #    this mesh uncontracted.
    t0 = time.perf_counter()
    contracted = skeletor.pre.contract(mesh, epsilon=1e-3, WL0=1, time_lim=args.skeletor_time_limit, progress=False)
    t_contract = time.perf_counter() - t0
    skel = skeletor.skeletonize.by_vertex_clusters(contracted, sampling_dist=0.25, progress=False)
    theirs = time.perf_counter() - t0
    moved = float(np.linalg.norm(np.asarray(contracted.vertices) - np.asarray(mesh.vertices), axis=1).max())
    note = " (contraction stopped without moving the mesh)" if moved < 1e-6 else ""
    print(
        f"skeletor contract + by_vertex_clusters: {theirs:.1f} s (contraction {t_contract:.1f} s{note}); "
        f"{accuracy(np.asarray(skel.vertices), segments)}"
    )
    print(f"ratio skeletor contraction / medialaxis flow (time): {theirs / ours:.2f}x")
    # 2. skeletor's fastest method, for reference: wavefront on the original mesh.
    t0 = time.perf_counter()
    wave = skeletor.skeletonize.by_wavefront(mesh, waves=1, step_size=1, progress=False)
    t_wave = time.perf_counter() - t0
    print(f"skeletor by_wavefront: {t_wave:.1f} s; {accuracy(np.asarray(wave.vertices), segments)}")
    print(f"ratio skeletor wavefront / medialaxis flow (time): {t_wave / ours:.2f}x")


if __name__ == "__main__":
    main()
