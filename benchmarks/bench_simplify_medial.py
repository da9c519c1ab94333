"""Simplified medial meshes: are their spheres medial? Error, medial share, inside share, seconds (issue 31).

A sphere of a simplified medial mesh stands for the medial axis only if it
touches the surface on two sides. The measure here (the issue's definition),
computed apart from the package:

* the input surface is sampled independently and densely
  (``trimesh.sample.sample_surface_even``, 200,000 points, not the
  package's sampler);
* a sphere ``(c, r)`` is **medial** when the samples within ``2%`` of ``r``
  of its sphere (``| |p - c| - r | <= 0.02 r``) span at least 90 degrees as
  seen from ``c`` (some two of them, ``u.v <= 0`` for their directions
  ``u, v`` from ``c``): it touches two sides. One that touches one side only
  is a patch (or, touching nothing, a filler);
* a sphere is **inside** when ``trimesh.proximity.signed_distance`` of its
  centre is at least ``0.98 r`` (it holds no more than 2% of its radius of
  the outside);
* **both**: medial and inside. A sphere reaching past the surface meets it
  in a circle, and the surface points in its band there can span 90 degrees
  from one side: Q-MAT's radii reach past the surface (crab: by 8% of the
  radius), so its medial share counts such spheres;
* the surface is the input's, or, where the Voronoi route made a solid of an
  open, self-crossing or many-shelled input (its ``repairs`` / ``defects``),
  that solid's (``ma.shape``: caps on the holes, cut where it crosses
  itself): the spheres stand for the solid, and an open input's surface
  has no points where they fill its holes. The error to the input surface
  is printed beside it (``error_input``);
* the two-sided error is ``mat_error.two_sided_error`` (balls interpolated
  over the edges and triangles, the triangles' sides among the edges), the
  larger of the two directions, in percent of the bounding-box diagonal
  (for MATFP's thousands of spheres, the package's exact envelope instead:
  ``mat_error``'s Python loops take minutes there).

Two runs:

``--spheres 200 [--half tuning|check]``: per model of ``real_models.py``
(the same hash split as ``bench_mesh_routes.py``), the compact complex
``voronoi_medial_axis(mesh)`` (seconds "axis") and then
``simplify_medial_mesh(ma, 200)`` (seconds "simplify"), with its error, medial
and inside shares; then the median and largest error and the median medial
share.

``--peers``: the Q-MAT and MATFP medial meshes shipped in
Frank-ZY-Dou/Geometry_Tools (``data/01<model>_QMAT.ma``, ``_MATFP.ma``) of
crab, dog, fertility, hand and vase, read from a local git snapshot
(``--mirror``), against ours at Q-MAT's sphere counts (42 to 106), on both
figures. (``_QMAT+.ma`` is the same file as ``_QMAT.ma`` there.)

``--mode packing`` measures the former default (spheres added at the surface
points farthest out, whatever they touch); ``--reuse DIR`` keeps each
model's compact complex in ``DIR`` between runs (for tuning).

Usage::

    NUMBA_NUM_THREADS=1 python benchmarks/bench_simplify_medial.py --half check
    NUMBA_NUM_THREADS=1 python benchmarks/bench_simplify_medial.py --peers
"""

from __future__ import annotations

import argparse
import json
import pickle
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, str(Path(__file__).resolve().parent))

from mat_error import two_sided_error  # noqa: E402
from real_models import default_cache, fetch_models  # noqa: E402

try:  # the closed models and the meshes as people have them
    from real_models import ALL_MODELS as MODELS  # noqa: E402
except ImportError:  # pragma: no cover
    from real_models import MODELS  # noqa: E402

#: ``half_of`` of bench_mesh_routes.py (imported from there when it has it).
try:
    from bench_mesh_routes import half_of  # noqa: E402
except ImportError:  # pragma: no cover
    import hashlib

    def half_of(name: str) -> str:
        return "tuning" if hashlib.sha256(name.encode()).digest()[0] % 2 == 0 else "check"


PEERS = ("crab", "dog", "fertility", "hand", "vase")
MIRROR = Path("/work/.mirror/Frank-ZY-Dou+Geometry_Tools/repo")
BAND = 0.02
INDEPENDENT = 2000
SAMPLES = 200_000


def surface_points(mesh, count: int = SAMPLES, seed: int = 7) -> np.ndarray:
    """An even sample of the surface made by trimesh (not the package's sampler)."""
    import trimesh

    return np.asarray(trimesh.sample.sample_surface_even(mesh, count, seed=seed)[0])


def medial_flags(points: np.ndarray, centres: np.ndarray, radii: np.ndarray, band: float = BAND,
                 tree: cKDTree | None = None, most: int = 3000) -> np.ndarray:
    """Per sphere: do the surface ``points`` within ``band * r`` of it span >= 90 degrees from its centre?"""
    tree = cKDTree(points) if tree is None else tree
    rng = np.random.default_rng(0)
    out = np.zeros(len(centres), bool)
    for k, (c, r) in enumerate(zip(np.asarray(centres, float), np.asarray(radii, float))):
        if r <= 0:
            continue
        near = np.asarray(tree.query_ball_point(c, (1 + band) * r), np.int64)
        if len(near) < 2:
            continue
        v = points[near] - c
        d = np.linalg.norm(v, axis=1)
        u = v[d >= (1 - band) * r] / d[d >= (1 - band) * r, None]
        if len(u) < 2:
            continue
        if len(u) > most:
            u = u[rng.choice(len(u), most, replace=False)]
        out[k] = bool((u @ u.T).min() <= 0.0)
    return out


def inside_flags(mesh, centres: np.ndarray, radii: np.ndarray, slack: float = BAND) -> np.ndarray:
    """Per sphere: trimesh's signed distance of the centre (positive inside) >= ``(1 - slack) r``."""
    import trimesh

    sd = trimesh.proximity.signed_distance(mesh, np.asarray(centres, float))
    return sd >= (1 - slack) * np.asarray(radii, float)


def error(mesh, centres, radii, edges, faces) -> float:
    """Two-sided error over the diagonal: ``mat_error``'s (the triangles' sides counted as edges), or,
    past ``INDEPENDENT`` spheres (MATFP's thousands, where its loops take minutes), the package's
    exact envelope (``medialaxis.mesh.simplify.envelope.two_sided_distance``)."""
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    sides = np.concatenate([np.asarray(edges, np.int64).reshape(-1, 2), faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    sides = np.unique(np.sort(sides, axis=1), axis=0)
    if len(centres) > INDEPENDENT:
        from medialaxis.mesh.simplify.envelope import two_sided_distance

        diag = float(np.linalg.norm(np.ptp(np.asarray(mesh.vertices), axis=0)))
        return max(two_sided_distance(np.asarray(centres, float), np.asarray(radii, float), sides, faces, mesh)) / diag
    m = SimpleNamespace(points=np.asarray(centres, float), radii=np.asarray(radii, float), edges=sides, faces=faces)
    e = two_sided_error(mesh, m)
    return max(e["surface_to_medial"], e["medial_to_surface"])


def figures(mesh, points, centres, radii, edges, faces, tree=None) -> dict:
    """Error, medial and inside shares, and the share both medial and inside ("both"): a sphere reaching
    past the surface meets it in a circle, whose points in the band can span 90 degrees from one side."""
    medial, inside = medial_flags(points, centres, radii, tree=tree), inside_flags(mesh, centres, radii)
    return {
        "spheres": len(centres),
        "error": error(mesh, centres, radii, edges, faces),
        "medial": float(medial.mean()),
        "inside": float(inside.mean()),
        "both": float((medial & inside).mean()),
    }


def read_ma(text: str):
    """``(centres, radii, edges, faces)`` of a ``.ma`` file (``v x y z r``, ``e i j``, ``f i j k``)."""
    v, e, f = [], [], []
    for line in text.splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            v.append([float(x) for x in parts[1:5]])
        elif parts[0] == "e":
            e.append([int(x) for x in parts[1:3]])
        elif parts[0] == "f":
            f.append([int(x) for x in parts[1:4]])
    v = np.array(v, float)
    return v[:, :3], v[:, 3], np.array(e, np.int64).reshape(-1, 2), np.array(f, np.int64).reshape(-1, 3)


def _git_show(mirror: Path, path: str) -> str:
    return subprocess.run(["git", "--git-dir", str(mirror), "show", f"HEAD:{path}"], check=True,
                          capture_output=True, text=True).stdout


def _kept(ma):
    """``ma`` (a compact complex) over its full complex, without the chain of what each was made from (for pickling)."""
    from medialaxis.core.result import MedialAxis

    full = ma.raw
    if full is not None:  # the full complex (the medial candidates)
        full = MedialAxis(full.points, full.radii, full.edges, full.faces, extras=dict(full.extras),
                          metadata=dict(full.metadata), shape=full.shape)
    return MedialAxis(ma.points, ma.radii, ma.edges, ma.faces, extras=dict(ma.extras), metadata=dict(ma.metadata),
                      shape=ma.shape, raw=full)


def ours(mesh, name: str, count: int, mode: str, reuse: Path | None, points, tree) -> dict:
    """Our simplified mesh of ``count`` spheres and its figures.

    Without a kept complex: the default call as users make it,
    ``medial_axis(mesh, method="voronoi", simplify=count)``, wall-clock
    seconds "call" (its compact complex is then kept in ``reuse``). With
    one: ``simplify_medial_mesh`` on it only, and "call" is the kept
    complex's seconds plus these. "simplify" is the simplification's share
    (wall clock; ``metadata["timings"]``); "call_cpu" and "cpu" the call's and the
    simplification's CPU seconds (``time.process_time``, steady while others
    load the machine; the simplification's own, ``timings["simplify_cpu"]``,
    is taken from the call's).
    """
    import medialaxis as mx
    from medialaxis.mesh.simplify.qmat import simplify_medial_mesh

    kept = reuse / f"{name}.pkl" if reuse else None
    stored = pickle.loads(kept.read_bytes()) if kept is not None and kept.exists() else None
    if isinstance(stored, dict):
        ma, axis_seconds, axis_cpu = stored["complex"], stored["seconds"], stored["cpu"]
        s = simplify_medial_mesh(ma, count, **({} if mode == "default" else {"mode": mode}))
    else:  # none kept (or kept by an older version of this file, whose CPU seconds were wrong)
        t0, c0 = time.perf_counter(), time.process_time()
        s = mx.medial_axis(mesh, method="voronoi", simplify=count, **({} if mode == "default" else {"simplify_mode": mode}))
        axis_seconds, axis_cpu = time.perf_counter() - t0, time.process_time() - c0
        axis_seconds -= s.metadata["timings"]["simplify"]
        axis_cpu -= s.metadata["timings"]["simplify_cpu"]
        if kept is not None:  # the complex, and the call's seconds without the simplification (wall, CPU)
            kept.parent.mkdir(parents=True, exist_ok=True)
            kept.write_bytes(pickle.dumps(dict(complex=_kept(s.raw), seconds=axis_seconds, cpu=axis_cpu)))
    seconds, cpu = s.metadata["timings"]["simplify"], s.metadata["timings"]["simplify_cpu"]
    surface = solid_surface(s, mesh)
    if surface is not mesh:  # an open or self-crossing input: the solid's surface, sampled by trimesh too
        points = surface_points(surface)
        tree = cKDTree(points)
    row = figures(surface, points, s.points, s.radii, s.edges, s.faces, tree)
    if surface is not mesh:
        row["error_input"] = error(mesh, s.points, s.radii, s.edges, s.faces)
    row.update(call_seconds=axis_seconds + seconds, call_cpu=axis_cpu + cpu, seconds=seconds, cpu=cpu)
    return row


def solid_surface(s, mesh):
    """The surface the spheres stand for: the input's, or where the loader made a solid of an open,
    self-crossing or many-shelled input (``metadata["repairs"]`` / ``["defects"]``), that solid's
    (``s.shape``: the input cut where it crosses itself, with the caps of its holes)."""
    if s.shape is not None and (s.metadata.get("repairs") or s.metadata.get("defects")):
        return s.shape
    return mesh


def _load(path):
    import trimesh

    mesh = trimesh.load(path, force="mesh", process=False)
    if mesh.is_watertight and mesh.volume < 0:  # faces pointing inward (the bunny): trimesh's inside test flips
        mesh.invert()
    return mesh


def _done(results: Path | None) -> dict:
    """Rows already in the ``--results`` file (JSON lines), by model name."""
    if results is None or not results.exists():
        return {}
    rows = [json.loads(line) for line in results.read_text().splitlines() if line.strip()]
    return {r["name"]: r for r in rows}


def _print_row(row: dict) -> None:
    if "failed" in row:
        print(f"{row['name']:16s} {half_of(row['name']):8s} refused: {row['failed']}", flush=True)
        return
    print(f"{row['name']:16s} {half_of(row['name']):8s} {row['spheres']:7d} {100 * row['error']:5.2f}% "
          f"{100 * row['medial']:6.0f}% {100 * row['inside']:6.0f}% {row['call_seconds']:7.1f} {row['call_cpu']:6.1f} "
          f"{row['seconds']:11.1f} {row.get('cpu', np.nan):8.1f}"
          + (f"  (solid; to the input surface {100 * row['error_input']:.2f}%)" if "error_input" in row else ""),
          flush=True)


def run_models(args) -> None:
    names = [m["name"] for m in MODELS if (not args.half or half_of(m["name"]) == args.half)]
    if args.models:
        names = [n for n in names if n in args.models.split(",")]
    paths = fetch_models(default_cache(), names)
    done = _done(args.results)
    print(f"simplify={args.spheres}, mode {args.mode}: error = two-sided (mat_error), medial = two-sided contact "
          f"within {100 * BAND:.0f}% of r spanning >= 90 deg, inside = centre depth >= {100 - 100 * BAND:.0f}% of r; "
          "call s = medial_axis(mesh, method='voronoi', simplify=n), wall clock and CPU, then the simplification's own")
    print("model            half     spheres  error  medial  inside  call s  cpu s  simplify s  cpu s")
    rows = []
    for name in names:
        if name in done:  # measured by an earlier run into the same --results file
            rows.append(done[name])
            _print_row(done[name])
            continue
        if name not in paths:
            print(f"{name:16s} not available")
            continue
        mesh = _load(paths[name])
        try:
            points = surface_points(mesh)
            row = dict(name=name, **ours(mesh, name, args.spheres, args.mode, args.reuse, points, cKDTree(points)))
        except Exception as exc:  # a refused or failing model is reported, not fatal
            row = dict(name=name, failed=f"{type(exc).__name__}: {str(exc).splitlines()[0][:90]}")
        rows.append(row)
        _print_row(row)
        if args.results is not None:
            with args.results.open("a") as out:
                out.write(json.dumps(row) + "\n")
    ok = [r for r in rows if "failed" not in r]
    if ok:
        err = np.array([r["error"] for r in ok])
        print(f"models {len(ok)} (refused {len(rows) - len(ok)}): error median {100 * np.median(err):.2f}%, "
              f"largest {100 * err.max():.2f}%, over 3%: {int((err > 0.03).sum())}; medial share median "
              f"{100 * np.median([r['medial'] for r in ok]):.0f}%, inside share median "
              f"{100 * np.median([r['inside'] for r in ok]):.0f}%; call seconds largest "
              f"{max(r['call_seconds'] for r in ok):.1f} (CPU {max(r['call_cpu'] for r in ok):.1f}), simplify seconds largest "
              f"{max(r['seconds'] for r in ok):.1f} (CPU {np.nanmax([r.get('cpu', np.nan) for r in ok]):.1f}, over 5 s: "
              f"{sum(r.get('cpu', 0.0) > 5.0 for r in ok)})")


def run_peers(args) -> None:
    paths = fetch_models(default_cache(), [f"gt-{m}" for m in PEERS])
    print("Q-MAT and MATFP medial meshes of Geometry_Tools against ours at Q-MAT's sphere count "
          f"(mode {args.mode}); error = two-sided (mat_error), medial / inside shares as above")
    print("model      spheres | error: ours  Q-MAT  MATFP | medial: ours  Q-MAT  MATFP | inside: ours  Q-MAT  MATFP "
          "| both: ours  Q-MAT  MATFP | MATFP spheres | ours s")  # wall clock (CPU of the call, of the simplification)
    for model in [m for m in PEERS if not args.models or m in args.models.split(",")]:
        name = f"gt-{model}"
        mesh = _load(paths[name])
        points = surface_points(mesh)
        tree = cKDTree(points)
        peer = {}
        for tool in ("QMAT", "MATFP"):
            c, r, e, f = read_ma(_git_show(args.mirror, f"data/01{model}_{tool}.ma"))
            if tool == "MATFP":  # MATFP works on the model centred on its box, the longest side scaled to 10
                lo, hi = mesh.bounds
                scale = 10.0 / float(np.max(hi - lo))
                c, r = c / scale + 0.5 * (lo + hi), r / scale
            peer[tool] = figures(mesh, points, c, r, e, f, tree)
        try:
            mine = ours(mesh, name, peer["QMAT"]["spheres"], args.mode, args.reuse, points, tree)
        except Exception as exc:  # refused by the Voronoi route: the peers' figures still print
            print(f"{model:10s} ours failed: {type(exc).__name__}: {str(exc).splitlines()[0][:70]}; Q-MAT {peer['QMAT']}, "
                  f"MATFP {peer['MATFP']}", flush=True)
            continue
        cols = [(mine, peer["QMAT"], peer["MATFP"])]
        print(f"{model:10s} {mine['spheres']:7d} | " + "  ".join(
            f"{100 * a[k]:5.2f}% {100 * b[k]:5.2f}% {100 * c[k]:5.2f}% |" if k == "error" else
            f"{100 * a[k]:4.0f}% {100 * b[k]:5.0f}% {100 * c[k]:5.0f}% |"
            for a, b, c in cols for k in ("error", "medial", "inside", "both"))
            + f" {peer['MATFP']['spheres']:13d} | {mine['call_seconds']:.1f} (CPU {mine['call_cpu']:.1f}, "
            f"simplify {mine['cpu']:.1f})", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--spheres", type=int, default=200)
    ap.add_argument("--half", choices=["tuning", "check"])
    ap.add_argument("--models", default="", help="comma-separated names (default: all of the half)")
    ap.add_argument("--mode", default="default", help="simplify_mode (default: the package's default)")
    ap.add_argument("--peers", action="store_true", help="the Q-MAT / MATFP comparison instead")
    ap.add_argument("--mirror", type=Path, default=MIRROR, help="bare git dir of Frank-ZY-Dou/Geometry_Tools")
    ap.add_argument("--reuse", type=Path, help="keep / reuse each model's compact complex here")
    ap.add_argument("--results", type=Path, help="append each model's row here (JSON lines); models already there are "
                    "not run again (resume a half run in parts)")
    args = ap.parse_args()
    import trimesh

    from medialaxis.mesh.simplify.qmat import simplify_medial_mesh
    from medialaxis.mesh.voronoi import voronoi_medial_axis

    # compile the kernels first (cached on disk after the first run): seconds are steady state
    simplify_medial_mesh(voronoi_medial_axis(trimesh.creation.icosphere(subdivisions=3)), 40)
    run_peers(args) if args.peers else run_models(args)


if __name__ == "__main__":
    main()
