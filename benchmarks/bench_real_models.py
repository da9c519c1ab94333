"""Medial complexes of real closed meshes of genus 0 to 8 (issue 11).

For each model of :mod:`real_models` (downloaded once into a cache), prints:

* the solid's topology from the input mesh alone: components ``b0`` (shells)
  and first Betti number ``b1`` (the sum of the shells' genera, from the
  mesh's own Euler characteristic);
* ``method="voronoi"``: the medial complex's Betti numbers (``MedialAxis.betti``:
  collapses and GF(2) ranks of the complex itself, not the method's
  metadata), the share of the solid's volume covered by the union of its
  balls (uniform samples inside the mesh), face count and seconds;
* ``method="flow"``: the curve skeleton's ``b0``, ``b1`` and seconds.

Usage::

    python benchmarks/bench_real_models.py [--cache DIR] [--models bunny,fertility] [--samples 200000]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, str(Path(__file__).resolve().parent))

from real_models import MODELS, default_cache, fetch_models


def interior_grid(vertices: np.ndarray, faces: np.ndarray, n: int) -> np.ndarray:
    """About ``n`` points of a regular grid inside a closed mesh, by ray parity.

    Each grid column (offset by an irrational fraction of a cell, so that no
    ray meets an edge or a vertex) is crossed by the triangles whose
    projections contain it; a grid point is inside when an odd number of
    crossings lies below it. Needs nothing but the mesh.
    """
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    volume_box = float(np.prod(hi - lo))
    h = (volume_box / (2.0 * n)) ** (1.0 / 3.0)  # the solid fills about half of its box
    shift = h * np.array([0.318309886, 0.271828183])
    ny = int(np.ceil((hi[1] - lo[1]) / h)) + 1  # columns are numbered i * ny + j
    tri = vertices[faces]
    # grid cells covered by each triangle's bounding box in xy
    i0 = np.ceil((tri[:, :, 0].min(axis=1) - lo[0] - shift[0]) / h).astype(np.int64)
    i1 = np.floor((tri[:, :, 0].max(axis=1) - lo[0] - shift[0]) / h).astype(np.int64)
    j0 = np.ceil((tri[:, :, 1].min(axis=1) - lo[1] - shift[1]) / h).astype(np.int64)
    j1 = np.floor((tri[:, :, 1].max(axis=1) - lo[1] - shift[1]) / h).astype(np.int64)
    wi, wj = np.maximum(i1 - i0 + 1, 0), np.maximum(j1 - j0 + 1, 0)
    per = wi * wj
    t = np.repeat(np.arange(len(faces)), per)
    k = np.arange(per.sum()) - np.repeat(np.cumsum(per) - per, per)
    ci, cj = i0[t] + k // np.maximum(wj[t], 1), j0[t] + k % np.maximum(wj[t], 1)
    px, py = lo[0] + shift[0] + ci * h, lo[1] + shift[1] + cj * h
    a, b, c = tri[t, 0], tri[t, 1], tri[t, 2]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        u = ((px - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (py - a[:, 1])) / det
        v = ((b[:, 0] - a[:, 0]) * (py - a[:, 1]) - (px - a[:, 0]) * (b[:, 1] - a[:, 1])) / det
        hit = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1)
    z = (a[:, 2] + u * (b[:, 2] - a[:, 2]) + v * (c[:, 2] - a[:, 2]))[hit]
    column = (ci * ny + cj)[hit]
    nz = int(np.ceil((hi[2] - lo[2]) / h)) + 1
    zs = lo[2] + (np.arange(nz) + 0.5) * h
    order = np.lexsort((z, column))
    column, z = column[order], z[order]
    out = []
    for col, start, stop in zip(*_runs(column)):
        crossings = z[start:stop]
        inside = np.searchsorted(crossings, zs) % 2 == 1
        if inside.any():
            x, y = lo[0] + shift[0] + (col // ny) * h, lo[1] + shift[1] + (col % ny) * h
            zk = zs[inside]
            out.append(np.column_stack([np.full(len(zk), x), np.full(len(zk), y), zk]))
    return np.concatenate(out) if out else np.empty((0, 3))


def _runs(sorted_keys: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Distinct keys of a sorted array with their start and stop rows."""
    if len(sorted_keys) == 0:
        return np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0, np.int64)
    start = np.flatnonzero(np.r_[True, sorted_keys[1:] != sorted_keys[:-1]])
    stop = np.r_[start[1:], len(sorted_keys)]
    return sorted_keys[start], start, stop


def covered_volume(points: np.ndarray, centres: np.ndarray, radii: np.ndarray) -> float:
    """Share of ``points`` that lie in some ball.

    Exact per point: the nearest lifted centre ``(c, sqrt(R^2 - r^2))`` to
    ``(x, 0)`` minimises ``|x - c|^2 - r^2`` (the power distance).
    """
    big = float(radii.max())
    lifted = np.column_stack([centres, np.sqrt(np.maximum(big**2 - radii**2, 0.0))])
    dist, _ = cKDTree(lifted).query(np.column_stack([points, np.zeros(len(points))]))
    return float(np.mean(dist**2 - big**2 <= 1e-9 * big**2))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cache", type=Path, default=default_cache())
    parser.add_argument("--models", default="", help="comma-separated names (default: all)")
    parser.add_argument("--samples", type=int, default=200_000, help="interior samples for the coverage")
    parser.add_argument("--no-flow", action="store_true")
    args = parser.parse_args()
    import trimesh

    import medialaxis as mx

    names = [m["name"] for m in MODELS]
    if args.models:
        names = [n for n in names if n in args.models.split(",")]
    paths = fetch_models(args.cache)
    print("model         vertices  solid b0/b1 | voronoi b0/b1/b2  cover   faces    seconds | flow b0/b1 seconds")
    for name in names:
        if name not in paths:
            print(f"{name:13s} not available")
            continue
        mesh = trimesh.load(paths[name], force="mesh", process=False)
        shells = len(mesh.split(only_watertight=False))
        solid_b1 = (2 * shells - int(mesh.euler_number)) // 2
        line = f"{name:13s} {len(mesh.vertices):8d}  {shells:5d}/{solid_b1:<5d} |"
        t0 = time.perf_counter()
        try:
            ma = mx.medial_axis(mesh, method="voronoi")
        except mx.MedialAxisError as exc:
            print(f"{line} voronoi refused: {exc}")
            continue
        secs = time.perf_counter() - t0
        b0, b1, b2 = ma.betti
        full = ma.raw if ma.raw is not None else ma  # the balls of the full complex (the compact one's are few)
        cover = covered_volume(interior_grid(np.asarray(mesh.vertices), np.asarray(mesh.faces), args.samples),
                               full.points, full.radii)
        ok = "ok" if (b0, b1) == (shells, solid_b1) and cover >= 0.95 else "MISS"
        line += f" {b0:5d}/{b1:<3d}/{b2:<3d} {cover:6.1%} {len(full.faces):8d} {secs:7.1f} {ok:4s} |"
        if not args.no_flow:
            t0 = time.perf_counter()
            try:
                sk = mx.medial_axis(mesh, method="flow")
                line += f" {sk.n_components:3d}/{sk.n_cycles:<3d} {time.perf_counter() - t0:6.1f}"
            except mx.MedialAxisError as exc:
                line += f" refused: {exc}"
        print(line, flush=True)


if __name__ == "__main__":
    main()
