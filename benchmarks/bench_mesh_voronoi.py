"""Benchmark: Voronoi lambda-medial surface of 100,000-vertex meshes (a bumpy torus, a uv ellipsoid).

Prints our time for the full complex and for the default compact one (with
the Delaunay step's share), the peer figure measured
in the same run (SciPy's Qhull Voronoi diagram of the mesh vertices alone,
``scipy.spatial.Voronoi``: the bare step every Voronoi medial method starts
from, with no sampling, inside test or filtering), and the ratio. Also
prints the Q-MAT simplification error against the number of spheres for two
meshes.

Run: ``PYTHONPATH=src python benchmarks/bench_mesh_voronoi.py [--vertices N] [--no-qmat] [--clock wall|cpu] [--ellipsoid-only]``

``--clock cpu`` reports our totals and the peer's as ``time.process_time``
(CPU seconds of all threads: on a shared machine, with ``NUMBA_NUM_THREADS=1``,
the figure that others' jobs disturb least); the per-step timings in
``metadata["timings"]`` stay wall-clock.
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def bumpy_torus(n_vertices: int, seed: int = 0):
    """A torus with smooth random bumps, about ``n_vertices`` vertices."""
    import trimesh

    minor = int(np.sqrt(n_vertices / 2.5))
    major = int(round(n_vertices / minor))
    mesh = trimesh.creation.torus(major_radius=1.0, minor_radius=0.35, major_sections=major, minor_sections=minor)
    rng = np.random.default_rng(seed)
    v = mesh.vertices.copy()
    theta = np.arctan2(v[:, 1], v[:, 0])
    ring = np.c_[np.cos(theta), np.sin(theta), np.zeros(len(v))]
    tube = v - ring
    phi = np.arctan2(tube[:, 2], (tube * ring).sum(1))
    bump = np.zeros(len(v))
    for _ in range(6):
        a, b, c = rng.integers(1, 6), rng.integers(1, 4), rng.uniform(0, 2 * np.pi)
        bump += 0.02 * np.sin(a * theta + b * phi + c)
    v = ring + tube * (1.0 + bump / 0.35)[:, None]
    return trimesh.Trimesh(v, mesh.faces, process=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vertices", type=int, default=100_000)
    parser.add_argument("--no-qmat", action="store_true", help="skip the Q-MAT error table")
    parser.add_argument("--qmat-only", action="store_true", help="only the Q-MAT error table")
    parser.add_argument("--clock", choices=("wall", "cpu"), default="wall", help="wall or CPU time (default %(default)s)")
    parser.add_argument("--ellipsoid-only", action="store_true", help="time the uv ellipsoid only (not the bumpy torus)")
    args = parser.parse_args()

    if not args.qmat_only:
        speed(args.vertices, time.process_time if args.clock == "cpu" else time.perf_counter, args.ellipsoid_only)
    if not args.no_qmat:
        qmat_table()


def uv_ellipsoid():
    """The 99,458-vertex uv sphere (224 x 224) scaled 3:1:1 of issue 14."""
    import trimesh

    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[224, 224])
    mesh.apply_scale([3.0, 1.0, 1.0])
    return mesh


def ellipsoid_axis_error(ma) -> str:
    """Distances of the points of the 3:1:1 ellipsoid's axis from the exact one, and of their radii.

    The medial axis of the prolate spheroid of semi-axes 3, 1, 1 is the
    segment ``|x| <= 3 - 1/3`` of the x axis; the ball at ``x`` has radius
    ``sqrt(1 - x^2 / 8)`` (the normal at the surface point nearest to it
    passes through it).
    """
    p = np.asarray(ma.points)
    x = np.clip(p[:, 0], -(3.0 - 1.0 / 3.0), 3.0 - 1.0 / 3.0)
    off = np.sqrt((p[:, 0] - x) ** 2 + p[:, 1] ** 2 + p[:, 2] ** 2)
    radius = np.abs(ma.radii - np.sqrt(np.maximum(1.0 - x**2 / 8.0, 0.0)))
    return (f"{len(p)} points, off the segment max {off.max():.4f} p99 {np.percentile(off, 99):.4f}, "
            f"radius error max {radius.max():.4f} p99 {np.percentile(radius, 99):.4f}")


def speed(n_vertices: int, clock=time.perf_counter, ellipsoid_only: bool = False) -> None:
    import trimesh
    from scipy.spatial import Voronoi

    from medialaxis.mesh.voronoi import voronoi_medial_axis

    voronoi_medial_axis(trimesh.creation.capsule(), samples=2000)  # warm the numba cache
    meshes = [("uv ellipsoid 224 x 224, 3:1:1", uv_ellipsoid)]
    if not ellipsoid_only:
        meshes.insert(0, (f"bumpy torus {n_vertices}", lambda: bumpy_torus(n_vertices)))
    for name, make in meshes:
        mesh = make()
        print(f"mesh: {name}, {len(mesh.vertices)} vertices, {len(mesh.faces)} faces, watertight {mesh.is_watertight}")
        t0 = clock()
        full = voronoi_medial_axis(mesh, compact=False)
        ours_full = clock() - t0
        t0 = clock()
        ma = voronoi_medial_axis(mesh)
        ours = clock() - t0
        md = full.metadata
        timing = ", ".join(f"{k} {v:.2f}" for k, v in md["timings"].items()) + " wall"
        print(f"clock: {'CPU (process_time, all threads)' if clock is time.process_time else 'wall'}")
        print(f"ours, full complex (compact=False): {ours_full:.2f} s ({md['n_samples']} samples, {md['n_tetrahedra']} tetrahedra; {timing})")
        print(f"  Delaunay share {md['delaunay_share']:.1%}; {len(full.points)} points, {len(full.faces)} faces")
        print(f"ours, default (compact complex): {ours:.2f} s; {len(ma.points)} points, {len(ma.faces)} faces "
              f"(compaction {ma.metadata['timings'].get('compact', 0.0):.2f} s)")
        print(f"  euler characteristic {ma.metadata['euler_characteristic']} (solid: {md['mesh_euler_characteristic'] // 2}),"
              f" components {ma.n_components}, epsilon {md['epsilon']:.4g}, lam {md['lam']:.4g}")
        if name.startswith("uv ellipsoid"):
            print(f"  exact axis: {ellipsoid_axis_error(ma)}; full complex {ellipsoid_axis_error(full)}")
        t0 = clock()
        Voronoi(np.asarray(mesh.vertices))
        peer = clock() - t0
        print(f"peer: scipy.spatial.Voronoi of the {len(mesh.vertices)} vertices: {peer:.2f} s")
        print(f"ratio ours / peer: full complex {ours_full / peer:.2f}, default {ours / peer:.2f}")
    print("(2 shared cores, other jobs running: timings are pessimistic)")


def qmat_table() -> None:
    import trimesh

    from medialaxis.mesh.simplify.qmat import simplify_medial_mesh
    from medialaxis.mesh.voronoi import voronoi_medial_axis

    for name, m in (
        ("bumpy torus 3k", bumpy_torus(3_000, seed=1)),
        ("box 2x1x0.5", trimesh.creation.box(extents=(2.0, 1.0, 0.5))),
    ):
        full = voronoi_medial_axis(m, samples=3_000, compact=False)
        print(f"Q-MAT on {name}: {len(full.points)} spheres before")
        for n in (2000, 500, 200, 50, 20):
            t0 = time.perf_counter()
            s = simplify_medial_mesh(full, n, surface=m)
            print(
                f"  {len(s.points):5d} spheres: two-sided Hausdorff {s.metadata['hausdorff']:.4g}"
                f" ({s.metadata['hausdorff'] / s.metadata['diagonal']:.2%} of the diagonal), {time.perf_counter() - t0:.2f} s"
            )


if __name__ == "__main__":
    main()
