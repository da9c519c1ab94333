"""Mid-surfaces of CT scans larger than memory: seconds, peak memory, accuracy (issue 12).

Writes the ribbed panel (:func:`medialaxis.datasets.ribbed_panel`: a
base plate, three webs and a cross rib, 8-voxel plates, blurred and noisy,
16-bit grey values 1000/3000) to ``panel_<N>.npy`` slab by slab (never whole
in memory), then runs, each in a fresh child process:

* ours, chunked: ``medial_axis("panel_N.npy", method="midsurface", chunks=C, n_jobs=J)``;
* ours, in memory (``chunks=0``), at the sizes that fit (today's route);
* kimimaro (bench extra, GPL-3.0: measured, never a dependency) on the
  same volume binarized at 2000, half-way between the grey levels (it needs the
  whole label volume in memory).

Peak memory: for ours, the child's high-water resident memory (``ru_maxrss``)
when the axis is done, before the accuracy is scored (one process: the blocks
run on threads); for the peers, the largest sum of the resident memory of the
child and its own children, sampled every 0.25 s (psutil). Both include the
interpreter, the libraries and the pages of the memory-mapped input. A tool whose tree passes ``--cap`` GiB is stopped
(the machine has 24 GB) and reported as such. Accuracy against the exact mid-planes (voxels):
99th percentile distance of the mesh vertices, share of the true mid-surface
within 1 voxel of the mesh, components, median thickness.

* ours on a Dask ``LocalCluster`` of worker processes (``--workers 1 2``),
  the mesh streamed to a PLY file (``out=``): the largest process's own
  high-water mark (the client's and each worker's, from the processes
  themselves; the client's alone in its own column) and the tree's sampled peak until
  the axis is done. The PLY's SHA-256 compares runs bit for bit.

Usage::

    PYTHONPATH=src python benchmarks/bench_volume_scale.py --sizes 256 512 1024 --chunks 256 --jobs 2 \
        [--workers 1 2] [--no-threads] [--dir /tmp/panels] [--no-kimimaro] [--no-memory-route]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / "src"
sys.path.insert(0, str(SRC))

THICKNESS = 8
MARGIN = 8
LEVELS = (1000.0, 3000.0)
NOISE = 0.05


def write_panel(path: Path, n: int, slab: int = 32) -> float:
    """Write the n^3 uint16 panel to ``path`` slab by slab; returns seconds."""
    from medialaxis.datasets import ribbed_panel_slab

    t0 = time.perf_counter()
    shape = (n, n, n)
    tmp = path.with_suffix(".part")
    with open(tmp, "wb") as fh:
        np.lib.format.write_array_header_2_0(fh, {"descr": np.dtype("<u2").str, "fortran_order": False, "shape": shape})
        for z in range(0, n, slab):
            block = ribbed_panel_slab(shape, z, min(z + slab, n), thickness=THICKNESS, margin=MARGIN, noise=NOISE,
                                      levels=LEVELS, dtype=np.uint16)
            fh.write(np.ascontiguousarray(block, "<u2").tobytes())
    os.replace(tmp, path)
    return time.perf_counter() - t0


def read_ply(path: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points, faces and radii of the binary PLY the mesh was streamed to (its own header: x y z radius ...)."""
    with open(path, "rb") as fh:
        header = []
        while not header or header[-1] != "end_header":
            header.append(fh.readline().decode("ascii").strip())
        nv = int(next(h for h in header if h.startswith("element vertex")).split()[-1])
        nf = int(next(h for h in header if h.startswith("element face")).split()[-1])
        names = [h.split()[-1] for h in header[header.index(f"element vertex {nv}"):] if h.startswith("property double")]
        vert = np.fromfile(fh, dtype=[(k, "<f8") for k in names], count=nv)
        face = np.fromfile(fh, dtype=[("k", "u1"), ("v", "<i4", (3,))], count=nf)
    return np.stack([vert["x"], vert["y"], vert["z"]], axis=1), face["v"].astype(np.int64), vert["radius"]


def child(tool: str, path: str, n: int, chunks: int, jobs: int) -> dict:
    """Runs in the measured process; prints a JSON line.

    ``cluster``: the blocks run on a ``LocalCluster`` of ``jobs`` worker
    processes (one thread each) and the mesh is streamed to a PLY file
    (``out=``); the workers' own high-water marks come from the workers.
    """
    out: dict = {"tool": tool, "size": n}
    if tool in ("chunked", "memory", "cluster"):
        import medialaxis as mx
        from medialaxis.datasets import ribbed_panel_truth
        from medialaxis.volume.validation import coverage, distance_to_rects, mesh_topology

        cluster = client = None
        options: dict = {"n_jobs": jobs}
        ply = Path(path).with_suffix(f".{tool}.ply")
        if tool == "cluster":
            from distributed import Client, LocalCluster

            cluster = LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True, dashboard_address=None,
                                   memory_limit="3GiB")
            client = Client(cluster)
            options = {"scheduler": client, "out": ply}
        t0 = time.perf_counter()
        ma = mx.medial_axis(path, method="midsurface", chunks=chunks if tool != "memory" else 0, **options)
        out["seconds"] = time.perf_counter() - t0
        # the run's own high-water mark, before the scoring below allocates its samples
        own = resource.getrusage(resource.RUSAGE_SELF)
        out["own_peak_gib"] = own.ru_maxrss / 2**20
        out["cpu_seconds"] = own.ru_utime + own.ru_stime  # the client's (or the threads') CPU time
        if client is not None:
            usage = client.run(lambda: resource.getrusage(resource.RUSAGE_SELF))
            out["worker_peaks_gib"] = sorted(u.ru_maxrss / 2**20 for u in usage.values())
            out["cpu_seconds"] += sum(u.ru_utime + u.ru_stime for u in usage.values())
            client.close()
            cluster.close()
        done = os.environ.get("BENCH_DONE")
        if done:
            Path(done).touch()  # the parent stops sampling the tree here
        out["blocks"] = dict(ma.metadata.get("blocks") or {}, **(ma.metadata.get("timings") or {}))
        out["halo"] = ma.metadata.get("halo")
        out["mesh_halo"] = ma.metadata.get("mesh_halo")
        points, faces, radii = (read_ply(str(ply)) if tool == "cluster" else (ma.points, ma.faces, ma.radii))
        rects = ribbed_panel_truth((n, n, n), thickness=THICKNESS, margin=MARGIN)
        d = distance_to_rects(points, rects)
        truth = np.concatenate([r.sample(1.0) for r in rects])
        out["p99"] = float(np.percentile(d, 99))
        out["covered"] = coverage(truth, points, faces, tolerance=1.0, step=0.5)[0]
        topo = mesh_topology(faces)
        out["components"], out["euler"], out["boundary_edges"] = topo.components, topo.euler, topo.boundary_edges
        out["faces"], out["vertices"] = len(faces), len(points)
        out["thickness"] = float(np.median(2 * radii))
        out["iso"] = ma.metadata["iso"]
        if ply.exists():
            out["mesh_sha256"] = hashlib.sha256(ply.read_bytes()).hexdigest()  # runs compared bit for bit
            ply.unlink()
    elif tool == "kimimaro":
        import kimimaro

        from medialaxis.volume.files.sources import open_source

        src = open_source(path)
        t0 = time.perf_counter()
        labels = np.empty(src.shape, np.uint8)
        for z in range(0, n, 64):
            labels[z:z + 64] = src.read((slice(z, min(z + 64, n)), slice(0, n), slice(0, n))) > 2000
        skels = kimimaro.skeletonize(labels, anisotropy=(1, 1, 1), parallel=jobs, progress=False)
        out["seconds"] = time.perf_counter() - t0
        out["vertices"] = int(sum(len(s.vertices) for s in skels.values()))
    return out


def measure(tool: str, path: Path, n: int, chunks: int, jobs: int, timeout: float, cap_gib: float) -> dict:
    import psutil

    cmd = [sys.executable, __file__, "--child", tool, str(path), str(n), str(chunks), str(jobs)]
    env = dict(os.environ, PYTHONPATH=str(SRC) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    done = path.with_suffix(f".{tool}.done")
    done.unlink(missing_ok=True)
    env["BENCH_DONE"] = str(done)
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    peak = largest = 0
    watched = psutil.Process(proc.pid)
    while proc.poll() is None:
        try:
            if not done.exists():  # the tree until the axis is done (the scoring comes after)
                sizes = [watched.memory_info().rss] + [c.memory_info().rss for c in watched.children(recursive=True)]
                peak, largest = max(peak, sum(sizes)), max(largest, max(sizes))
        except psutil.Error:
            pass
        if time.perf_counter() - t0 > timeout or peak > cap_gib * 2**30:
            for child_proc in watched.children(recursive=True):
                child_proc.kill()
            proc.kill()
            proc.communicate()
            why = f"timeout after {timeout:.0f} s" if peak <= cap_gib * 2**30 else \
                f"stopped above {cap_gib:g} GiB after {time.perf_counter() - t0:.0f} s"
            return {"tool": tool, "size": n, "error": why}
        time.sleep(0.25)
    stdout, stderr = proc.communicate()
    if proc.returncode != 0:
        return {"tool": tool, "size": n, "error": (stderr.strip().splitlines() or ["?"])[-1]}
    done.unlink(missing_ok=True)
    result = json.loads(stdout.strip().splitlines()[-1])
    # ours: the process's high-water mark when the axis was done (scoring comes after), and for a
    # cluster the largest of the client's and the workers' own; peers: the sampled peak of the tree
    result["client_peak_gib"] = result.get("own_peak_gib")  # the client alone (the process that stitches)
    result["peak_gib"] = max([result.pop("own_peak_gib", peak / 2**30), *result.get("worker_peaks_gib", [])])
    result["tree_gib"], result["sampled_largest_gib"] = peak / 2**30, largest / 2**30
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    parser.add_argument("--chunks", type=int, default=256, help="block size (at most half the size: 8 blocks or more)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--dir", type=Path, default=Path(os.environ.get("TMPDIR", "/tmp")) / "medialaxis-panels")
    parser.add_argument("--no-kimimaro", action="store_true")
    parser.add_argument("--workers", type=int, nargs="*", default=[],
                        help="also run on a LocalCluster of this many worker processes (one thread each; repeatable: 1 2)")
    parser.add_argument("--no-threads", action="store_true", help="skip the local-threads run of the chunked route")
    parser.add_argument("--no-memory-route", action="store_true", help="skip the in-memory route (chunks=0)")
    parser.add_argument("--memory-limit", type=int, default=512, help="largest size run in memory (default 512)")
    parser.add_argument("--timeout", type=float, default=3600)
    parser.add_argument("--cap", type=float, default=18.0, help="stop a tool whose memory passes this many GiB")
    args = parser.parse_args()
    args.dir.mkdir(parents=True, exist_ok=True)
    # warm the numba caches once, outside the measurements
    subprocess.run([sys.executable, "-c", "import medialaxis as mx; from medialaxis.datasets import ribbed_panel;"
                    "mx.medial_axis(ribbed_panel((64, 96, 96)).volume, method='midsurface')"],
                   env=dict(os.environ, PYTHONPATH=str(SRC)), check=True)
    rows = []
    for n in args.sizes:
        path = args.dir / f"panel_{n}.npy"
        if not path.exists():
            print(f"writing {path} ({n}^3 uint16, {n**3 * 2 / 2**30:.2f} GiB) ...", flush=True)
            print(f"  written in {write_panel(path, n):.1f} s", flush=True)
        tools = [] if args.no_threads else ["chunked"]
        tools += [f"cluster{w}" for w in args.workers]
        if not args.no_memory_route and n <= args.memory_limit:
            tools.append("memory")
        if not args.no_kimimaro:
            tools.append("kimimaro")
        chunks = min(args.chunks, n // 2)  # at least 8 blocks, so that both cores work
        for name in tools:
            tool, jobs = ("cluster", int(name[7:])) if name.startswith("cluster") else (name, args.jobs)
            r = measure(tool, path, n, chunks, jobs, args.timeout, args.cap)
            r["chunks"] = chunks if tool != "memory" else None
            r["jobs"] = jobs
            if "seconds" in r:
                r["mvox_per_s"] = n**3 / r["seconds"] / 1e6
            rows.append(r)
            print(json.dumps(r), flush=True)
    print()
    print("| size | tool | seconds | M voxels/s | largest process GiB | client GiB | tree GiB | p99 (vox) | covered | pieces | euler | thickness |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    name = {"chunked": "ours, chunks={}, {} threads", "memory": "ours, in memory", "kimimaro": "kimimaro",
            "cluster": "ours, chunks={}, LocalCluster of {} workers"}
    for r in rows:
        label = name[r["tool"]].format(r.get("chunks"), r.get("jobs"))
        if "error" in r:
            print(f"| {r['size']}^3 | {label} | {r['error']} |")
            continue
        acc = (f"{r['p99']:.2f} | {100 * r['covered']:.1f}% | {r['components']} | {r['euler']} | {r['thickness']:.2f}"
               if "p99" in r else "- | - | - | - | -")
        client = "-" if r.get("client_peak_gib") is None else f"{r['client_peak_gib']:.2f}"
        print(f"| {r['size']}^3 | {label} | {r['seconds']:.1f} | {r['mvox_per_s']:.2f} | {r['peak_gib']:.2f} | "
              f"{client} | {r['tree_gib']:.2f} | {acc} |")
    for r in rows:
        b = r.get("blocks")
        if b:
            print(f"{r['size']}^3 {r['tool']} x{r['jobs']}: {b['blocks']} blocks ({b['sheet_blocks']} with sheet), "
                  f"first pass {b['medial']:.1f} s, mesh pass {b['mesh']:.1f} s "
                  f"({b['mesh_blocks'] / max(b['sheet_blocks'], 1):.2f} s, "
                  f"{b.get('mesh_blocks_cpu', float('nan')) / max(b['sheet_blocks'], 1):.2f} s CPU per sheet block), sheet "
                  f"{b['sheet_bytes'] / max(b['sheet_blocks'], 1) / 2**20:.2f} MiB and piece "
                  f"{b['piece_bytes'] / max(b['sheet_blocks'], 1) / 2**20:.3f} MiB per sheet block, "
                  f"{b['medial_voxels']} medial voxels, mesh halo {r.get('mesh_halo')}")
            if "cpu_seconds" in r:
                halo = max(r.get("halo") or [0])
                read = (r["chunks"] + 2 * halo) ** 3 * 2  # uint16 voxels each block reads (core and halo)
                first = r["cpu_seconds"] - b.get("mesh_blocks_cpu", 0.0)
                print(f"  CPU {r['cpu_seconds']:.0f} s in all: the rest (first pass, stitching) {first / b['blocks']:.2f} s CPU per block, "
                      f"mesh {b.get('mesh_blocks_cpu', 0.0) / max(b['sheet_blocks'], 1):.2f} s CPU per sheet block; "
                      f"each block reads {read / 2**20:.1f} MiB (halo {halo})")
    print(f"\nchunks=min({args.chunks}, size/2), n_jobs={args.jobs}; targets: peak <= 8 GiB at 1024^3, >= 2.6 M voxels/s (goal 5), "
          "p99 <= 1 voxel, >= 98% covered, one piece, thickness within 10% of 8")


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        _, _, tool, path, n, chunks, jobs = sys.argv
        print(json.dumps(child(tool, path, int(n), int(chunks), int(jobs))))
    else:
        main()
