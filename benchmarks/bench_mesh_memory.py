"""Benchmark: peak memory and seconds of the default mesh call on float32 files, 8 to 100k vertices (issue 31).

Each solid (torus, capsule, cylinder, cone, sphere, box, thin plate, extruded
L profile) is written by trimesh to a PLY file (float32 coordinates, as every
STL has) in a temporary folder and computed by ``medialaxis.medial_axis(path)``
in a subprocess under an address-space limit; the table gives its seconds,
peak resident memory, GB per 100k vertices (the target: at most 2), and the
Betti numbers of the axis against the solid's. The peer figure, from the same
run, is the same solid given as the float64 mesh it was made from (the issue:
1.8 GB for the float64 torus, past 24 GB for its float32 file), and the ratio
of the peaks. Last, the Delaunay tetrahedra per sample of the Voronoi route
("jittered" where the lattice sample was degenerate and taken again:
``sampling.degenerate``).

Run: ``PYTHONPATH=src python benchmarks/bench_mesh_memory.py [--sizes 2000 40000 100000]
[--models torus box] [--method voronoi] [--format ply] [--limit-gb 8] [--no-float64]``
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
from typing import Any

import numpy as np

#: The issue's torus (51,200 vertices) and capsule (40,000).
ISSUE_SIZES = {"torus": 51_200, "capsule": 40_000}
#: GB per 100k vertices is shown from this size on (below it the interpreter's 0.3 GB dominates).
PER_VERTEX_FROM = 10_000
#: Betti numbers of each solid (its medial axis has its homotopy type).
EXPECTED = {"torus": (1, 1, 0)}


def _revolved(profile: np.ndarray, spacing: float) -> Any:
    """A solid of revolution about z of a (r, z) polyline from the axis back to it, about ``spacing`` apart."""
    import trimesh

    dense = [profile[0]]
    for a, b in zip(profile[:-1], profile[1:]):
        steps = max(int(np.ceil(np.linalg.norm(b - a) / spacing)), 1)
        dense.extend(a + (b - a) * t for t in np.arange(1, steps + 1) / steps)
    sections = max(int(np.ceil(2 * np.pi * profile[:, 0].max() / spacing)), 8)
    return trimesh.creation.revolve(np.asarray(dense), sections=sections)


def _subdivided(mesh: Any, vertices: int) -> Any:
    while len(mesh.vertices) * 4 - 6 <= vertices * 1.5:  # each subdivision about quadruples the vertices
        mesh = mesh.subdivide()
    return mesh


def model(name: str, vertices: int) -> Any:
    """The solid ``name`` with about ``vertices`` vertices (float64)."""
    import trimesh

    if name == "torus":
        minor = max(int(round(np.sqrt(vertices / 2))), 3)
        return trimesh.creation.torus(3, 1, major_sections=2 * minor, minor_sections=minor)
    if name == "capsule":
        count = max(int(round(np.sqrt(vertices))), 4)
        return trimesh.creation.capsule(height=2.0, radius=0.5, count=[count, count])
    if name == "sphere":  # a uv sphere: whole rings of faces equidistant from its centre
        count = max(int(round(np.sqrt(vertices / 2))), 4)
        return trimesh.creation.uv_sphere(radius=1.0, count=[count, count])
    if name == "cylinder":
        profile = np.array([[0.0, -1.0], [0.5, -1.0], [0.5, 1.0], [0.0, 1.0]])
        return _revolved(profile, float(np.sqrt(9.4 / vertices)))
    if name == "cone":
        profile = np.array([[0.0, -1.0], [1.0, -1.0], [0.0, 1.0]])
        return _revolved(profile, float(np.sqrt(20.0 / vertices)))
    if name == "box":
        return _subdivided(trimesh.creation.box([2.0, 1.5, 1.0]), vertices)
    if name == "plate":
        return _subdivided(trimesh.creation.box([10.0, 10.0, 0.2]), vertices)
    if name == "extrusion":
        from shapely.geometry import Polygon

        outline = Polygon([(0, 0), (3, 0), (3, 1), (1, 1), (1, 2), (0, 2)])
        return _subdivided(trimesh.creation.extrude_polygon(outline, 1.0), vertices)
    raise ValueError(f"unknown model {name!r}")


MODELS = ["torus", "capsule", "cylinder", "cone", "sphere", "box", "plate", "extrusion"]

CHILD = """
import json, sys, time
import numpy as np
sys.path[:0] = [{bench!r}]
import medialaxis
from bench_mesh_memory import model
name, vertices, path, method = {args!r}
shape = model(name, vertices) if path is None else path
start = time.perf_counter()
ma = medialaxis.medial_axis(shape, method=method)
seconds = time.perf_counter() - start
hwm = [int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("VmHWM")]
meta = ma.metadata  # the compact result's holds the full complex's sample figures
per_sample = meta["n_tetrahedra"] / meta["n_samples"] if meta.get("n_samples") else None
print(json.dumps(dict(seconds=seconds, betti=list(ma.betti), points=len(ma.points), peak_gb=hwm[0] / 1e6 if hwm else None,
                      per_sample=per_sample, jittered=meta.get("sample_jittered"))))
"""


def run(name: str, vertices: int, path: str | None, method: str, limit_gb: float) -> dict[str, Any]:
    """One call in a subprocess limited to ``limit_gb`` of address space: its figures and its peak RSS."""
    limit = int(limit_gb * 1e9)

    def cap() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    code = CHILD.format(bench=os.path.dirname(os.path.abspath(__file__)), args=(name, vertices, path, method))
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        child = subprocess.Popen([sys.executable, "-c", code], stdout=out, stderr=err, text=True, preexec_fn=cap)
        _, status, usage = os.wait4(child.pid, 0)  # the child's own peak, not the largest of all children
        child.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        # the child's own high-water mark (VmHWM); ru_maxrss, for a run that failed, also counts the
        # resident set of this process, which the child had at the fork
        peak = usage.ru_maxrss / 1e6  # kB on Linux
        if child.returncode != 0:
            lines = err.read().strip().splitlines() or [f"killed ({child.returncode})"]
            return {"error": lines[-1][:70], "peak_gb": peak}
        figures = json.loads(out.read().strip().splitlines()[-1])
        return {**figures, "peak_gb": figures["peak_gb"] or peak}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2_000, 40_000, 100_000], help="vertex counts")
    parser.add_argument("--models", nargs="+", default=MODELS, choices=MODELS)
    parser.add_argument("--method", default="voronoi", choices=["voronoi", "flow"])
    parser.add_argument("--format", default="ply", choices=["ply", "stl"], help="file written (both float32)")
    parser.add_argument("--limit-gb", type=float, default=8.0, help="address-space limit of each run")
    parser.add_argument("--issue", action="store_true", help="also the issue's sizes (torus 51,200, capsule 40,000)")
    parser.add_argument("--no-float64", action="store_true", help="skip the float64 peer runs")
    args = parser.parse_args()

    print(f"method={args.method}, float32 {args.format} files, limit {args.limit_gb:g} GB per run")
    print(
        f"{'model':10} {'vertices':>8} {'seconds':>8} {'peak GB':>8} {'GB/100k':>8} {'betti':>10} {'expect':>10}"
        f" {'f64 s':>7} {'f64 GB':>7} {'ratio':>6} {'tets/sample':>11}"
    )
    with tempfile.TemporaryDirectory() as folder:
        for name in args.models:
            sizes = sorted(set(args.sizes) | ({ISSUE_SIZES[name]} if args.issue and name in ISSUE_SIZES else set()))
            for size in sizes:
                mesh = model(name, size)
                path = os.path.join(folder, f"{name}-{size}.{args.format}")
                mesh.export(path)
                n = len(mesh.vertices)
                ours = run(name, size, path, args.method, args.limit_gb)
                peer = {} if args.no_float64 else run(name, size, None, args.method, args.limit_gb)
                expect = EXPECTED.get(name, (1, 0, 0))
                print(_row(name, n, ours, peer, expect), flush=True)


def _row(name: str, n: int, ours: dict[str, Any], peer: dict[str, Any], expect: tuple[int, ...]) -> str:
    def figures(r: dict[str, Any]) -> str:
        if not r:
            return f"{'':>7} {'':>7}"
        return f"{r.get('seconds', float('nan')):7.1f} {r['peak_gb']:7.2f}"

    per = f"{ours['peak_gb'] / n * 1e5:8.2f}" if n >= PER_VERTEX_FROM else f"{'-':>8}"
    if "error" in ours:
        return f"{name:10} {n:8d} {'failed':>8} {ours['peak_gb']:8.2f} {per} {ours['error']}"
    betti = ",".join(map(str, ours["betti"]))
    mark = "" if tuple(ours["betti"]) == expect else " !"
    ratio = f"{ours['peak_gb'] / peer['peak_gb']:6.2f}" if peer.get("peak_gb") and "error" not in peer else f"{'':>6}"
    # tetrahedra per sample of the Voronoi route's sample, "jittered" where it was taken again (sampling.degenerate)
    tets = f"{ours['per_sample']:5.1f}{' jittered' if ours.get('jittered') else ''}" if ours.get("per_sample") else ""
    return (
        f"{name:10} {n:8d} {ours['seconds']:8.1f} {ours['peak_gb']:8.2f} {per}"
        f" {betti + mark:>10} {','.join(map(str, expect)):>10} {figures(peer)} {ratio} {tets:>11}"
    )


if __name__ == "__main__":
    main()
