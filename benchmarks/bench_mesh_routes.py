"""What the mesh routes do with meshes as people have them (issue 31).

For each model of :mod:`real_models` (``ALL_MODELS``: scans, CAD exports, meshes with
crossing or degenerate faces, small holes, triangle soups), runs in a
subprocess of its own (address space limited by ``--memory``, killed after
``--timeout`` seconds) the default call ``medialaxis.medial_axis(path)``
(``method="voronoi"``) and ``medialaxis.medial_axis(path, method="flow")``, and
records:

* refused or not: the exception's type and first line (a
  :class:`~medialaxis.MedialAxisError` is a refusal; anything else, a
  timeout or a killed process is an error);
* the warnings the call gave (crossing faces resolved by winding number,
  holes closed, zero-area faces, ...);
* ``ma.betti`` against the Betti numbers of the solid's open interior (which the
  medial axis has the homotopy type of: where the solid touches itself at a
  point, a cavity touching another or a slit narrowing to a point, they
  differ from the closed solid's): from the surface
  the loader makes of the file (crossings resolved by winding number, holes
  capped: :func:`solid_topology`, after the timed call), else from the
  input mesh alone (its Euler characteristic, holes counted as capped);
  ``flow``'s against ``(outer shells, genus, 0)``: a curve holds no void
  (the flow fills the solid's cavities, with a warning);
* the seconds of the call (after a warm-up on a small sphere in the same
  process, so that loading compiled kernels is not counted) and the peak
  memory (the subprocess's ``VmHWM`` after the call, warm-up included;
  ``ru_maxrss`` from ``os.wait4`` if it was killed);
* for voronoi, the two-sided check that each ball touches the input and
  holds none of it: ``trimesh.proximity.signed_distance`` of the points
  (a subset of ``--check-points``) against their radii, as the largest and
  the median ``|d - r|`` in percent of the bounding-box diagonal and the
  share of points farther than 1% off, for the compact complex (``ma``) and
  for the full complex (``ma.raw``).

Prints one row per model and method and a summary (models, refused, errors,
Betti right, median and largest seconds), and writes all of it as JSON with
``--json``. ``--half tuning|check`` takes a fixed half of the models (by a
hash of the name), so that work can be tuned on one half and reported on the
other.

Measured on c7b14c0 (57 models, one thread, a loaded 2-core machine):
voronoi refused 15, one timeout, Betti right 34 of 41 computed. On 3d4de6d
(voronoi only, ``--check-points 0``): tuning half (27 models) refused 4,
Betti right 21 of 23 (seahorse (1,7,0) for (1,9,0); ogre, open and crossing
in 9,090 face pairs, (1,17,4) for (5,16,0)), median 4.2 s; check half (30)
refused 7 (gt-sphere-soup, a triangle soup, bounds no solid once each
triangle is capped), Betti right 23 of 23, median 6.0 s. On 1765008-7a9341a
(holes capped where the winding number decides, a lid's ring, contoured
solids; the five models those changed re-run on 7a9341a): tuning half
refused 1 (truck: winding number undecided over 29%), Betti right 24 of 26
(seahorse, ogre as before), median 7.9 s; check half refused 2 (alligator,
beetle: open shells, undecided over 89-100%), Betti right 26 of 28 (beast
(8,138,15) for (29,56,4) and orc (1,5,5) for (1,6,6), open, crossing and
unoriented, refused before; both with the warning that names the solid's
Betti numbers), median 7.5 s, on a machine at load 8-14. On 132506d (cavities
of the inner union too small for the sampling filled): the same counts, Betti
right 24 of 26 and 26 of 28, with ogre (1,17,3) and orc (1,5,4) (the cavities
filled lay away from the solid's, which are thinner than the sampling spacing)
and beast (8,137,5); median 1.7 s and 1.3 s at load 1-3.
With the interior's Betti numbers as the truth (c2d3415, routes as on
673a791): three models' truths change, each at one kind of pinch of the cut
solid, two slits of air meeting tip to tip (the interior gains a handle
there): seahorse (1,10,0) (closed solid (1,9,0)), cow (1,2,0) (was
(1,1,0)), and orc (1,8,4) (closed (1,6,6): two such pinches, and two tiny
cavities touching a larger one at a point, which the interior merges);
tuning half Betti right 24 of 26 (seahorse (1,7,0), cow (1,1,0)), check
half 27 of 28 (orc (1,6,5)), at load 3-6. With a ball of air of one default
spacing taken out at each pinch of the cut solid where it fits
(``mesh.solid.pinches``, fc6b298; the truth taken without the balls):
tuning 25 of 26 (cow right; seahorse (1,7,0), its ball does not fit among
its bars), check 27 of 28 (orc (1,7,5), one of its pinches opened), at
load 9-11. With a ball of half a spacing where one does not fit, and a
second sample three times finer around the thick tetrahedra of air the
inner set is mended through (``inner_set.POCKET_FLAT``,
``voronoi.REFINE_FACTOR``) where the complex lacks the solid's Euler
characteristic: tuning 26 of 26 (seahorse (1,10,0)), check 28 of 28 (orc
(1,8,4)), each of them the only model of its half sampled twice; the
refused ones as before; at load 2-4.

Run it single-threaded and one model at a time so as to share the machine::

    NUMBA_NUM_THREADS=1 OMP_NUM_THREADS=1 python benchmarks/bench_mesh_routes.py \\
        [--from-mirror /work/.mirror] [--models bunny,spot] [--half check] \\
        [--methods voronoi,flow] [--json out.json] [--timeout 900] [--memory 8e9]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import resource
import signal
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from real_models import ALL_MODELS, default_cache, describe, fetch_models, fill_from_mirror

METHODS = ("voronoi", "flow")


def half_of(name: str) -> str:
    """``"tuning"`` or ``"check"``: a fixed split of the models by a hash of the name."""
    return "tuning" if hashlib.sha256(name.encode()).digest()[0] % 2 == 0 else "check"


def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else ''}"[:400]


def _distance_check(mesh, points, radii, diagonal: float, n: int) -> dict:
    """``| |signed distance| - radius |`` of up to ``n`` evenly spaced points, in percent of ``diagonal``.

    ``outside``: the share of points on the outer side of the input (the
    sign of trimesh's signed distance, positive inside; ``mesh`` turned
    outward by the caller, as the loader turns inward-facing meshes).
    """
    import numpy as np
    import trimesh

    if len(points) == 0:
        return {"points": 0}
    take = np.unique(np.linspace(0, len(points) - 1, min(n, len(points))).astype(int))
    d = trimesh.proximity.signed_distance(mesh, np.asarray(points)[take])
    err = np.abs(np.abs(d) - np.asarray(radii)[take]) / diagonal * 100.0
    return {
        "points": int(len(take)),
        "max_pct": float(f"{err.max():.3g}"),
        "median_pct": float(f"{np.median(err):.3g}"),
        "over_1pct": round(float(np.mean(err > 1.0)), 4),
        "outside": round(float(np.mean(d < 0)), 4),
    }


def _peak_mb() -> int | None:
    """This process's peak resident memory since it started its program (``VmHWM``), in MB.

    Not ``ru_maxrss``: Linux carries the parent's resident set at the fork
    over the ``exec`` into it, so a small worker would show the parent's size.
    """
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return round(int(line.split()[1]) / 1024)
    except OSError:
        pass
    return None


def solid_topology(path: str) -> dict | None:
    """Betti numbers of the open interior of the solid the loader makes of the file, with what it repaired.

    ``None`` if refused. Where faces cross, the solid where the winding
    number is at least 1/2 can differ from the surface's own topology (a
    dragon's tail crossing its body makes a handle); where that solid
    touches itself at a point (a pinch), its interior (which the medial
    axis follows, Lieutier 2004) and the closed solid differ again:
    :func:`solid_interior.interior_betti` counts the interior,
    ``"closed"`` keeps the closed solid's count (shells by face adjacency,
    a pinch split, as the cut surface stores it). The loader opens each
    pinch with a small ball (:mod:`medialaxis.mesh.solid.pinches`) so that
    the routes see the interior's topology; the truth is taken from the
    solid without those balls, so that it does not lean on them.
    """
    import warnings
    from unittest import mock

    import numpy as np
    import trimesh
    from solid_interior import interior_betti

    import medialaxis as mx
    from medialaxis.mesh.solid.inputs import load_mesh

    with warnings.catch_warnings(), mock.patch("medialaxis.mesh.solid.pinches.carve_pinches", lambda m: (m, 0)):
        warnings.simplefilter("ignore")
        try:
            loaded = load_mesh(path)
        except mx.MedialAxisError:
            return None
    mesh = loaded.mesh
    labels = trimesh.graph.connected_component_labels(mesh.face_adjacency, node_count=len(mesh.faces))
    shells = int(labels.max()) + 1
    euler = len(np.unique(mesh.faces)) - len(mesh.edges_unique) + len(mesh.faces)
    # an outward-oriented closed surface: a shell of negative signed volume bounds a cavity (ogre's cut leaves 4)
    tri = np.asarray(mesh.vertices, np.float64)[np.asarray(mesh.faces)]
    volume = np.bincount(labels, np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])) / 6.0, shells)
    voids = int((volume < 0).sum())
    components, genus, cavities = interior_betti(mesh.vertices, mesh.faces)
    return {"components": components, "genus": genus, "voids": cavities, "repairs": list(loaded.repairs),
            "closed": [shells - voids, (2 * shells - int(euler)) // 2, voids]}


def worker(path: str, method: str, check_points: int) -> dict:
    """Run one method on one model in this process; the record of :func:`run_one` without memory."""
    import warnings

    import numpy as np
    import trimesh

    import medialaxis as mx

    out: dict = {"method": method}
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            mx.medial_axis(trimesh.creation.icosphere(subdivisions=2), method=method)
        except Exception as exc:  # noqa: BLE001 - a warm-up only
            out["warmup_error"] = _one_line(exc)
    out["warmup_seconds"] = round(time.perf_counter() - t0, 2)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t0 = time.perf_counter()
        try:
            ma = mx.medial_axis(path) if method == "voronoi" else mx.medial_axis(path, method=method)
        except mx.MedialAxisError as exc:
            out["refused"] = _one_line(exc)
        except Exception as exc:  # noqa: BLE001 - recorded as an error
            out["error"] = _one_line(exc)
        out["seconds"] = round(time.perf_counter() - t0, 2)
    seen: list[str] = []
    for w in caught:
        text = f"{w.category.__name__}: {str(w.message).strip()}"[:400]
        if text not in seen:
            seen.append(text)
    out["warnings"] = seen
    out["peak_mb"] = _peak_mb()  # of the call, before the checks below
    if "refused" in out or "error" in out:
        return out
    t0 = time.perf_counter()
    out["betti"] = [int(b) for b in ma.betti]
    out["betti_seconds"] = round(time.perf_counter() - t0, 2)
    out["points"] = int(len(ma.points))
    out["refine_seconds"] = round(float(ma.metadata.get("timings", {}).get("refine", 0.0)), 2)  # voronoi: a finer pass
    out["faces"] = int(len(ma.faces)) if getattr(ma, "faces", None) is not None else 0
    out["solid"] = solid_topology(path)  # flow too: a flow-only run has the loader's solid as its truth
    if method == "voronoi" and check_points:
        mesh = trimesh.load(path, force="mesh", process=False)
        if mesh.volume < 0:  # faces pointing inward (the loader turns them too)
            mesh.invert()
        diagonal = float(np.linalg.norm(np.ptp(np.asarray(mesh.vertices), axis=0)))
        t0 = time.perf_counter()
        out["distance"] = _distance_check(mesh, ma.points, ma.radii, diagonal, check_points)
        if getattr(ma, "raw", None) is not None:
            out["distance_raw"] = _distance_check(mesh, ma.raw.points, ma.raw.radii, diagonal, check_points)
        out["check_seconds"] = round(time.perf_counter() - t0, 2)
    return out


def run_one(path: Path, method: str, *, timeout: float, memory: float, check_points: int) -> dict:
    """Run :func:`worker` in a subprocess; add its peak memory, or say how it ended if it gave no record."""
    out_file = path.parent / f".bench-{os.getpid()}-{method}.json"
    out_file.unlink(missing_ok=True)
    cmd = [sys.executable, __file__, "--worker", str(path), method, str(out_file), str(check_points)]

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (int(memory), int(memory)))

    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, preexec_fn=limit, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    timer = threading.Timer(timeout, proc.kill)
    timer.start()
    try:
        stderr = proc.stderr.read().decode(errors="replace")
        _, status, usage = os.wait4(proc.pid, 0)
    finally:
        timer.cancel()
        if proc.returncode is None and proc.poll() is None:  # stopped while it ran: do not leave it running
            proc.kill()
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - t0
    if out_file.exists():
        record = json.loads(out_file.read_text())
        out_file.unlink()
    else:
        tail = [line for line in stderr.strip().splitlines() if line.strip()][-1:] or [""]
        ended = (f"timeout after {timeout:g} s" if wall >= timeout else f"process ended with code {proc.returncode}")
        record = {"method": method, "error": f"{ended}: {tail[0][:300]}", "seconds": round(wall, 1), "warnings": []}
    # the worker's own figure; else (killed) ru_maxrss, in KiB on Linux, at least the parent's size at the fork
    record["maxrss_mb"] = round(usage.ru_maxrss / 1024)
    if record.get("peak_mb") is None:
        record["peak_mb"] = record["maxrss_mb"]
    record["wall_seconds"] = round(wall, 1)
    return record


def _betti_text(record: dict) -> str:
    if "refused" in record:
        return "refused"
    if "error" in record:
        return "ERROR"
    return "/".join(map(str, record["betti"]))


def print_row(row: dict) -> None:
    m = row["model"]
    expected = "/".join(f"{x:g}" for x in row["expected"])
    flags = ",".join(x for x, on in [("open", m["holes"] > 0), ("cross", bool(m["crossing_pairs"])),
                                     ("welded", m["welded"] > 0), ("soup", m["components"] > 1000), ("unoriented", not m["oriented"])] if on) or "-"
    line = f"{row['name']:<16} {m['vertices']:>7} {expected:>8} {flags:<18}"
    for method in row["methods"]:
        r = row["methods"][method]
        ok = "" if "betti" not in r else (" ok" if r["betti_right"] else " MISS")
        line += f" | {method[:3]} {_betti_text(r):>9}{ok:<5} {r['seconds']:7.1f}s {r['peak_mb']:6d}MB"
        if "distance" in r:
            raw = r.get("distance_raw", {})
            line += (f" |d-r| max {r['distance'].get('max_pct', float('nan')):.2g}% (full complex "
                     f"{raw.get('max_pct', float('nan')):.2g}%, outside {raw.get('outside', float('nan')):.1%})")
    print(line, flush=True)
    for method, r in row["methods"].items():
        for text in [r.get("refused"), r.get("error")] + r["warnings"]:
            if text:
                print(f"{'':16}   {method}: {text[:220]}", flush=True)


def summary(rows: list[dict], methods: list[str]) -> dict:
    """Per method: models, refused, errors, Betti right (of those computed), median and largest seconds."""
    out = {}
    for method in methods:
        records = [row["methods"][method] for row in rows if method in row["methods"]]
        done = [r for r in records if "betti" in r]
        secs = [r["seconds"] for r in done]
        out[method] = {
            "models": len(records),
            "refused": sum("refused" in r for r in records),
            "errors": sum("error" in r for r in records),
            "betti_right": sum(r["betti_right"] for r in done),
            "computed": len(done),
            "median_seconds": round(statistics.median(secs), 1) if secs else None,
            "max_seconds": max(secs) if secs else None,
            "max_peak_mb": max((r["peak_mb"] for r in records), default=None),
        }
    return out


def main() -> None:
    if len(sys.argv) > 1 and sys.argv[1] == "--worker":
        path, method, out_file, check_points = sys.argv[2:6]
        record = worker(path, method, int(check_points))
        Path(out_file).write_text(json.dumps(record))
        return
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # ends the running subprocess too (run_one)
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cache", type=Path, default=default_cache(), help="model cache directory")
    parser.add_argument("--from-mirror", type=Path, help="fill the cache from local git snapshots (see real_models.py)")
    parser.add_argument("--models", default="", help="comma-separated names (default: all)")
    parser.add_argument("--half", choices=["tuning", "check"], help="only one fixed half of the models")
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds per model and method")
    parser.add_argument("--memory", type=float, default=8e9, help="address-space limit of each subprocess, bytes")
    parser.add_argument("--check-points", type=int, default=1000, help="points of the radius check (0: none)")
    parser.add_argument("--json", type=Path, help="write the rows and the summary here")
    args = parser.parse_args()

    methods = [m for m in args.methods.split(",") if m]
    wanted = set(args.models.split(",")) - {""}
    unknown = wanted - {m["name"] for m in ALL_MODELS}
    if unknown:
        parser.error(f"unknown models: {', '.join(sorted(unknown))}")
    models = [m for m in ALL_MODELS if (not wanted or m["name"] in wanted) and (not args.half or half_of(m["name"]) == args.half)]
    if args.from_mirror:
        paths = fill_from_mirror(args.cache, args.from_mirror, [m["name"] for m in models])
    else:
        paths = fetch_models(args.cache, [m["name"] for m in models])
    import medialaxis

    meta = {"argv": sys.argv, "medialaxis": str(Path(medialaxis.__file__).parent), "started": time.strftime("%Y-%m-%d %H:%M:%S"),
            "threads": {k: os.environ.get(k) for k in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS")}}
    print("model            vertices expected flags              | method betti ok seconds peak memory radius check")
    rows = []
    for model in models:
        name = model["name"]
        if name not in paths:
            print(f"{name:<16} not available", flush=True)
            continue
        row = {"name": name, "half": half_of(name), "source": f"{model['repo']}@{model['commit'][:10]}:{model['path']}",
               "model": describe(paths[name]), "methods": {}}
        expected = [row["model"]["components"], row["model"]["genus"], 0]
        for method in methods:
            record = run_one(paths[name], method, timeout=args.timeout, memory=args.memory,
                             check_points=args.check_points)
            if record.get("solid"):
                row["solid"] = record["solid"]
            row["methods"][method] = record
        if row.get("solid"):  # the loader's solid (crossings resolved, holes capped) where it made one
            expected = [row["solid"]["components"], row["solid"]["genus"], row["solid"].get("voids", 0)]
        row["expected"] = expected
        for method, record in row["methods"].items():
            if "betti" in record:  # a curve skeleton holds no void: flow's solid cavities are filled
                record["betti_right"] = record["betti"] == (expected[:2] + [0] if method == "flow" else expected)
        rows.append(row)
        print_row(row)
        if args.json:
            args.json.write_text(json.dumps({"meta": meta, "rows": rows, "summary": summary(rows, methods)}, indent=1))
    total = summary(rows, methods)
    print()
    for method, s in total.items():
        print(f"{method:8s} models {s['models']}, refused {s['refused']}, errors {s['errors']}, Betti right "
              f"{s['betti_right']}/{s['computed']}, seconds median {s['median_seconds']} max {s['max_seconds']}, "
              f"peak memory max {s['max_peak_mb']} MB")
    if args.json:
        args.json.write_text(json.dumps({"meta": meta, "rows": rows, "summary": total}, indent=1))


if __name__ == "__main__":
    main()
