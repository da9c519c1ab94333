"""A layer of 100,000 lakes: mx.centerlines on 1 and 2 workers beside pygeoops.centerline, one run.

Data: the 30 OpenStreetMap lakes of ``tests/data/osm_lakes.geojson`` (42 to
392 vertices, 18 islands; see ``tests/data/README.md``), projected to World
Mercator and tiled: copy k of the 30 is translated to its own cell of a
grid, so the layer is ``--count`` real shapes spread over a plane as a
country's lakes are.

Each configuration runs in its own Python process (so its peak memory is its
own): the seconds of the call alone (reading and tiling apart), ms per
feature, the peak resident memory of the process and all its worker
processes together (sampled every 0.2 s with psutil, reading and tiling
included) and of the main process alone (``ru_maxrss``). Configurations:

- ``medialaxis-1``: ``mx.centerlines(layer)``, the default call (one thread);
- ``medialaxis-2``: ``n_jobs=2`` (the default pool: two threads);
- ``threads-2``: ``n_jobs=2, scheduler="threads"`` (the same, named);
- ``processes-2``: ``n_jobs=2, scheduler="processes"`` (two worker processes);
- ``dask-2``: a ``dask_geopandas.GeoDataFrame`` of 8 partitions computed on a
  ``distributed.LocalCluster`` of 2 single-threaded workers;
- ``pygeoops``: ``pygeoops.centerline(layer.geometry)`` with its defaults (one
  process; pygeoops is in the ``bench`` extra).

Usage::

    NUMBA_NUM_THREADS=1 python benchmarks/bench_gis_scale.py [--count 100000]
        [--configs medialaxis-1,medialaxis-2,processes-2,dask-2,pygeoops] [--count-for medialaxis-1=10000]

The wall time depends on what else runs on the machine: the CPU seconds of
the call (workers included), the cores they amount to and the load average
are printed beside it. ``--count-for`` runs a configuration on fewer features (the ratios are per
feature) when the whole layer would take too long on one worker.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import shapely

LAKES = Path(__file__).resolve().parents[1] / "tests" / "data" / "osm_lakes.geojson"
CONFIGS = ("medialaxis-1", "medialaxis-2", "processes-2", "dask-2", "pygeoops")


def tiled_lakes(count: int):
    """``count`` polygons: the 30 lakes again and again, each copy in its own grid cell (EPSG:3857)."""
    import geopandas as gpd

    lakes = gpd.read_file(LAKES).to_crs("EPSG:3857")
    base = lakes.geometry.values
    bounds = shapely.bounds(base)
    cell = float(np.max(bounds[:, 2:] - bounds[:, :2])) * 1.1
    base = shapely.transform(base, lambda xy: xy - bounds[:, :2].min(axis=0))
    side = int(np.ceil(np.sqrt(count)))
    k = np.arange(count)
    geoms = [shapely.transform(base[j % len(base)], lambda xy, j=j: xy + [cell * (j % side), cell * (j // side)])
             for j in range(count)]
    return gpd.GeoDataFrame({"lake": k % len(base), "islands": lakes["islands"].to_numpy()[k % len(base)]},
                            geometry=geoms, crs=lakes.crs)


class PeakMemory:
    """The largest resident memory of this process and all its descendants (workers), sampled every 0.2 s."""

    def __enter__(self) -> PeakMemory:
        import psutil

        self.peak, self._stop, self._cpu = 0, threading.Event(), {}

        def sample() -> None:
            me = psutil.Process()
            while not self._stop.wait(0.2):
                total = 0
                for proc in [me, *me.children(recursive=True)]:
                    try:
                        with proc.oneshot():
                            total += proc.memory_info().rss
                            times = proc.cpu_times()
                        self._cpu[proc.pid] = times.user + times.system
                    except psutil.Error:
                        pass
                self.peak = max(self.peak, total)

        self._thread = threading.Thread(target=sample, daemon=True)
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()

    @property
    def cpu_seconds(self) -> float:
        """CPU seconds of the process and its workers, as last sampled (a worker's last 0.2 s may be missed)."""
        return float(sum(self._cpu.values()))


def run_one(config: str, count: int) -> dict:
    """One configuration in this process: seconds, features, lines and peak memory."""
    with PeakMemory() as memory:
        out = _run(config, count, memory)
    return {**out, "peak_mb": memory.peak / 2**20, "load": os.getloadavg()[0]}


def _run(config: str, count: int, memory: PeakMemory) -> dict:
    layer = tiled_lakes(count)
    import medialaxis as mx

    mx.centerlines(layer.iloc[:30])  # compiled kernels loaded, as in any session after the first call
    time.sleep(0.3)
    cpu = memory.cpu_seconds
    start = time.perf_counter()
    if config == "pygeoops":
        import pygeoops

        lines = pygeoops.centerline(layer.geometry)
    elif config == "dask-2":
        import dask_geopandas
        from distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
                Client(cluster):
            start = time.perf_counter()
            lines = mx.centerlines(dask_geopandas.from_geopandas(layer, npartitions=8)).compute().geometry
    else:
        jobs = int(config.rsplit("-", 1)[1])
        scheduler = config.split("-")[0] if config.startswith(("threads", "processes")) else None
        lines = mx.centerlines(layer, n_jobs=jobs, scheduler=scheduler, show_progress=False).geometry
    seconds = time.perf_counter() - start
    time.sleep(0.3)
    cpu = memory.cpu_seconds - cpu
    lines = np.asarray(lines)
    return {"config": config, "count": count, "seconds": seconds, "cpu_s": cpu,
            "lines": int(np.count_nonzero(~shapely.is_empty(lines) & ~shapely.is_missing(lines))),
            "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--count", type=int, default=100_000)
    parser.add_argument("--configs", default=",".join(CONFIGS))
    parser.add_argument("--count-for", default="", help="config=count,...: fewer features for these")
    parser.add_argument("--one", default=None, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.one:
        print(json.dumps(run_one(args.one, args.count)))
        return
    counts = dict(item.split("=") for item in args.count_for.split(",") if item)
    rows = []
    for config in args.configs.split(","):
        count = int(counts.get(config, args.count))
        done = subprocess.run([sys.executable, __file__, "--one", config, "--count", str(count)],
                              capture_output=True, text=True)
        if done.returncode:
            print(f"{config}: failed\n{done.stderr[-2000:]}", file=sys.stderr)
            continue
        rows.append(json.loads(done.stdout.strip().splitlines()[-1]))
        print(json.dumps(rows[-1]), file=sys.stderr)
    peer = next((r for r in rows if r["config"] == "pygeoops"), None)
    one = next((r for r in rows if r["config"] == "medialaxis-1"), None)
    print(f"{'config':14} {'features':>9} {'lines':>9} {'seconds':>9} {'ms/feature':>11} {'x pygeoops':>11} "
          f"{'x 1 worker':>11} {'CPU s':>8} {'cores':>6} {'peak MB':>8} {'main MB':>8} {'load':>5}")
    for r in rows:
        ms = 1e3 * r["seconds"] / r["count"]
        ratio = f"{ms / (1e3 * peer['seconds'] / peer['count']):.2f}" if peer else "-"
        speedup = f"{(1e3 * one['seconds'] / one['count']) / ms:.2f}" if one else "-"
        print(f"{r['config']:14} {r['count']:9d} {r['lines']:9d} {r['seconds']:9.1f} {ms:11.2f} {ratio:>11} "
              f"{speedup:>11} {r['cpu_s']:8.1f} {r['cpu_s'] / r['seconds']:6.2f} {r['peak_mb']:8.0f} {r['rss_mb']:8.0f} "
              f"{r['load']:5.1f}")


if __name__ == "__main__":
    main()
