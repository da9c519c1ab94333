"""The first call after a fresh install: compile time of each method, from a clean snapshot, in one run.

Run:  .venv/bin/python benchmarks/bench_first_call.py [--rev HEAD] [--methods planar-image,voxels] [--no-warmup]

A fresh install has no numba cache, so its first ``medial_axis`` call of a
method compiles that method's kernels. This script exports ``src/`` of a
git revision (``git archive``, so no cache file of the work tree comes
along) to a temporary folder and, for each method, starts a new Python on it
with an empty ``NUMBA_CACHE_DIR`` of its own. There it times the first call
and a second call of the same input (CPU seconds of the process, all
threads, and wall seconds). Then ``medialaxis warmup`` runs once on another
empty cache (the CPU of the child process). The table prints at the end.

Inputs: the bundled Kimia PNG (planar image), the bundled WKT bracket
(planar polygon), a trimesh capsule (mesh voronoi with 4,000 samples, mesh
flow) and the T phantom of 40 x 64 x 64 voxels (midsurface, voxels), the
shapes ``medialaxis warmup`` runs. ``NUMBA_NUM_THREADS`` and
``OMP_NUM_THREADS`` are 1 unless ``--threads`` says otherwise: the CPU
seconds then measure the compiling, not the waiting of idle threads.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Each method: the code that makes its input ``shape`` and the keywords of its call.
METHODS = {
    "planar-image": ("from medialaxis.datasets import data_path; shape = data_path('kimia_class1_01.png')", {}),
    "planar-polygon": (
        "from medialaxis.datasets import data_path; shape = data_path('bracket_two_holes.wkt').read_text()",
        {},
    ),
    "mesh-voronoi": ("import trimesh; shape = trimesh.creation.capsule(height=2.0, radius=0.5)", {"samples": 4000}),
    "mesh-flow": ("import trimesh; shape = trimesh.creation.capsule(height=2.0, radius=0.5)", {"method": "flow"}),
    "midsurface": (
        "from medialaxis.datasets import t_phantom; shape = t_phantom((40, 64, 64), thickness=6, margin=8).volume",
        {"method": "midsurface"},
    ),
    "voxels": (
        "from medialaxis.datasets import t_phantom; shape = t_phantom((40, 64, 64), thickness=6, margin=8).volume",
        {"method": "voxels"},
    ),
}

#: What the child process runs: ``{setup}`` and ``{kwargs}`` filled in; prints one JSON line.
CHILD = """
import json, time, warnings
t0, w0 = time.process_time(), time.perf_counter()
import medialaxis as mx
{setup}
import_cpu, import_wall = time.process_time() - t0, time.perf_counter() - w0
out = {{"import_cpu": import_cpu, "import_wall": import_wall}}
warnings.simplefilter("ignore")
for call in ("first", "second"):
    t0, w0 = time.process_time(), time.perf_counter()
    mx.medial_axis(shape, **{kwargs})
    out[call + "_cpu"], out[call + "_wall"] = time.process_time() - t0, time.perf_counter() - w0
print("RESULT " + json.dumps(out))
"""


def snapshot(rev: str, folder: str) -> str:
    """Export ``src/`` of ``rev`` into ``folder``; returns the path for ``PYTHONPATH``."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", rev, "src"], check=True, capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", folder], input=archive, check=True)
    return os.path.join(folder, "src")


def child_env(src: str, cache: str, threads: int) -> dict[str, str]:
    """The environment of a child: the snapshot first on the path, an empty numba cache of its own."""
    env = dict(os.environ)
    env.update(PYTHONPATH=src, NUMBA_CACHE_DIR=cache, NUMBA_NUM_THREADS=str(threads), OMP_NUM_THREADS=str(threads))
    return env


def run_method(name: str, src: str, threads: int) -> dict[str, float]:
    """First and second call of one method in a new process with an empty cache."""
    setup, kwargs = METHODS[name]
    with tempfile.TemporaryDirectory(prefix="numba-cache-") as cache:
        done = subprocess.run(
            [sys.executable, "-c", CHILD.format(setup=setup, kwargs=repr(kwargs))],
            env=child_env(src, cache, threads),
            capture_output=True,
            text=True,
            cwd=cache,
        )
    for line in done.stdout.splitlines():
        if line.startswith("RESULT "):
            return json.loads(line[len("RESULT ") :])
    raise RuntimeError(f"{name} failed:\n{done.stderr[-3000:]}")


def run_warmup(src: str, threads: int) -> tuple[float, float]:
    """``medialaxis warmup`` on an empty cache: (CPU, wall) seconds of its process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="numba-cache-") as cache:
        subprocess.run(
            [sys.executable, "-m", "medialaxis", "warmup"],
            env=child_env(src, cache, threads),
            check=True,
            capture_output=True,
            cwd=cache,
        )
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rev", default="HEAD", help="git revision to export (default HEAD)")
    parser.add_argument("--methods", default=",".join(METHODS), help="comma-separated, of: " + ", ".join(METHODS))
    parser.add_argument("--threads", type=int, default=1, help="NUMBA_NUM_THREADS and OMP_NUM_THREADS (default 1)")
    parser.add_argument("--no-warmup", action="store_true", help="skip timing `medialaxis warmup`")
    args = parser.parse_args()
    names = [m for m in args.methods.split(",") if m]
    unknown = set(names) - set(METHODS)
    if unknown:
        parser.error(f"unknown methods {sorted(unknown)}")
    with tempfile.TemporaryDirectory(prefix="medialaxis-snapshot-") as folder:
        src = snapshot(args.rev, folder)
        loads = [os.getloadavg()[0]]  # the machine's 1-minute load before and after each run
        rows = []
        for name in names:
            r = run_method(name, src, args.threads)
            rows.append((name, r))
            loads.append(os.getloadavg()[0])
            print(f"{name}: first {r['first_cpu']:.1f} s CPU", file=sys.stderr, flush=True)
        warm = None if args.no_warmup else run_warmup(src, args.threads)
        loads.append(os.getloadavg()[0])
    print(
        f"\nFirst call after a fresh install ({args.rev}, {args.threads} thread(s), "
        f"load {min(loads):.1f} to {max(loads):.1f}; seconds)"
    )
    print(f"{'method':<16}{'first CPU':>11}{'first wall':>12}{'second CPU':>12}{'second wall':>13}{'import CPU':>12}")
    for name, r in rows:
        print(
            f"{name:<16}{r['first_cpu']:>11.1f}{r['first_wall']:>12.1f}{r['second_cpu']:>12.3f}"
            f"{r['second_wall']:>13.3f}{r['import_cpu']:>12.1f}"
        )
    if warm is not None:
        print(f"{'warmup (all)':<16}{warm[0]:>11.1f}{warm[1]:>12.1f}")


if __name__ == "__main__":
    main()
