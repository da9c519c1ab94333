"""The compact medial complex against the full one: sizes, topology, error, seconds.

For analytic solids (capsule, box, torus) and the real models of
``real_models.py``: ``mx.medial_axis(mesh, method="voronoi")`` (compact by
default; ``ma.raw`` is the full complex of the same run). Prints the points,
triangles and curve edges of both, the compact complex's Betti numbers
against the solid's (from the mesh's own Euler characteristic and shells),
the compaction's seconds and share of the run, and the compact complex's
two-sided error measured by ``mat_error.py`` (independent of the package),
beside the sampling density epsilon the tolerance follows, all over the
bounding-box diagonal.

Usage::

    python benchmarks/bench_compact.py [--models kitten,fertility] [--no-real] [--full-error]

``--full-error`` also measures the full complex's error the same way (slow:
the interpolation runs over every triangle of the full complex).
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from mat_error import two_sided_error
from real_models import MODELS, default_cache, fetch_models


def _analytic():
    import trimesh

    return {
        "capsule": trimesh.creation.capsule(height=2.0, radius=0.5, count=[64, 64]),
        "box": trimesh.creation.box(extents=(2.0, 1.0, 0.5)),
        "torus": trimesh.creation.torus(1.0, 0.3, major_sections=96, minor_sections=32),
    }


def _solid_betti(mesh) -> tuple[int, int, int]:
    shells = len(mesh.split(only_watertight=False))
    return shells, (2 * shells - int(mesh.euler_number)) // 2, 0


def row(name: str, mesh, full_error: bool = False) -> None:
    import medialaxis as mx

    t0 = time.perf_counter()
    ma = mx.medial_axis(mesh, method="voronoi")
    seconds = time.perf_counter() - t0
    full, md = ma.raw, ma.metadata
    diag = float(np.linalg.norm(np.ptp(np.asarray(mesh.vertices), axis=0)))
    err = two_sided_error(mesh, ma)
    solid = _solid_betti(mesh)
    topo = "ok" if ma.betti == solid else f"solid {solid}"
    compact_s = md["timings"].get("compact", 0.0)
    print(f"{name:13s} {len(mesh.vertices):8d} | {len(full.points):7d} {len(full.faces):7d} {full.metadata['n_curve_edges']:6d} | "
          f"{len(ma.points):6d} {len(ma.faces):6d} {md['n_curve_edges']:6d} {str(ma.betti):10s} {topo:4s} | "
          f"{100 * err['surface_to_medial']:6.2f}% {100 * err['medial_to_surface']:6.2f}% "
          f"(eps {100 * md['epsilon'] / diag:.2f}%) | {compact_s:5.1f} of {seconds:5.1f} s  [{md['compact']}]")
    if full_error:
        e = two_sided_error(mesh, full)
        print(f"{'':13s} full complex's error: {100 * e['surface_to_medial']:.2f}% {100 * e['medial_to_surface']:.2f}%")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--models", default="", help="comma-separated real models (default: all but the self-intersecting seahorse)")
    ap.add_argument("--no-real", action="store_true", help="analytic solids only")
    ap.add_argument("--full-error", action="store_true", help="also the full complex's two-sided error (slow)")
    args = ap.parse_args()
    print("                       |        full complex        |            compact complex            |"
          "  two-sided error, compact  | seconds")
    print("model         vertices |  points   faces  curve |  points  faces  curve betti      topo |"
          "  s->m    m->s  (sampling)  | compact of total")
    for name, mesh in _analytic().items():
        row(name, mesh, args.full_error)
    if args.no_real:
        return
    import trimesh

    paths = fetch_models(default_cache())
    names = [m["name"] for m in MODELS if m["name"] != "seahorse"]
    if args.models:
        names = [n for n in names if n in args.models.split(",")]
    for name in names:
        if name in paths:
            row(name, trimesh.load(paths[name], force="mesh", process=False), args.full_error)
        else:
            print(f"{name:13s} not available")


if __name__ == "__main__":
    main()
