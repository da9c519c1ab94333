"""Benchmark of the volume mid-surface pipeline on the issue's T phantom.

Builds the 140 x 240 x 240 CT-like T (two 6-voxel plates, blurred, noisy,
iso 0.5), then runs, each in a fresh child process (so that peak memory is
per tool):

* ours: ``medial_axis(volume, method="midsurface", iso=0.5)``, after a warm-up
  on a small phantom so the numba kernels come from their on-disk cache;
* scikit-image ``skeletonize`` on the same binarized volume;
* kimimaro ``skeletonize`` on the same binarized volume;
* the distance-transform choices: our sub-voxel k-d tree feature transform,
  SciPy ``distance_transform_edt(return_indices=True)`` and ``edt.edt``.

It prints our figures, the peers' figures and the ratios, and the issue's
targets with PASS/FAIL. Timings depend on the machine's load.

Usage::

    PYTHONPATH=src python benchmarks/bench_volume.py [--shape 140 240 240]
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

import numpy as np


def _peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def child(tool: str, path: str) -> dict:
    volume = np.load(path)
    out: dict = {}
    if tool == "ours":
        import medialaxis as mx
        from medialaxis.datasets import t_phantom
        from medialaxis.volume.pipeline import volume_stages

        mx.medial_axis(t_phantom((40, 60, 60), margin=6).volume, method="midsurface", iso=0.5)  # warm caches
        base = _peak_mb()
        t0 = time.perf_counter()
        stages = volume_stages(volume, iso=0.5)
        out["seconds"] = time.perf_counter() - t0
        out["timings"] = stages.timings
        ma = stages.result
        np.savez(path + ".ours.npz", points=ma.points, faces=ma.faces, radii=ma.radii, kind=ma.vertex_kind)
        out["baseline_mb"] = base
        out["vertices"], out["faces"] = len(ma.points), len(ma.faces)
    elif tool == "skimage":
        from skimage.morphology import skeletonize

        mask = volume > 0.5
        t0 = time.perf_counter()
        skel = skeletonize(mask)
        out["seconds"] = time.perf_counter() - t0
        out["voxels"] = int(np.count_nonzero(skel))
    elif tool == "kimimaro":
        import kimimaro

        labels = (volume > 0.5).astype(np.uint32)
        t0 = time.perf_counter()
        skels = kimimaro.skeletonize(labels, anisotropy=(1, 1, 1), parallel=1, progress=False)
        out["seconds"] = time.perf_counter() - t0
        out["vertices"] = int(sum(len(s.vertices) for s in skels.values()))
        out["edges"] = int(sum(len(s.edges) for s in skels.values()))
    elif tool == "ft_ours":
        from medialaxis.volume.distance import feature_transform
        from medialaxis.volume.inputs import load_volume

        vol = load_volume(volume, iso=0.5)
        base = _peak_mb()
        t0 = time.perf_counter()
        feature_transform(vol)
        out["seconds"] = time.perf_counter() - t0
        out["baseline_mb"] = base
    elif tool == "ft_scipy":
        from scipy import ndimage

        mask = volume > 0.5
        base = _peak_mb()
        t0 = time.perf_counter()
        ndimage.distance_transform_edt(mask, return_indices=True)
        out["seconds"] = time.perf_counter() - t0
        out["baseline_mb"] = base
    elif tool == "ft_edt":
        import edt

        mask = volume > 0.5
        base = _peak_mb()
        t0 = time.perf_counter()
        edt.edt(mask, parallel=2)
        out["seconds"] = time.perf_counter() - t0
        out["baseline_mb"] = base
    out["peak_mb"] = _peak_mb()
    return out


def run_child(tool: str, path: str) -> dict:
    env = dict(os.environ)
    src = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    res = subprocess.run([sys.executable, os.path.abspath(__file__), "--child", tool, path],
                         capture_output=True, text=True, env=env, check=False)
    if res.returncode != 0:
        return {"error": res.stderr.strip().splitlines()[-1] if res.stderr.strip() else f"exit {res.returncode}"}
    return json.loads(res.stdout.strip().splitlines()[-1])


def score_arrays(points, faces, radii, phantom) -> dict:
    from medialaxis.volume.validation import coverage, distance_to_rects, mesh_topology

    d = distance_to_rects(points, phantom.midsurface)
    truth = np.concatenate([r.sample(0.5) for r in phantom.midsurface])
    frac, dist = coverage(truth, points, faces, tolerance=1.0)
    # the junction line is where the two true mid-planes meet
    flange, stem = phantom.midsurface
    zj, yj = flange.origin[0], stem.origin[1]
    near_v = np.hypot(points[:, 0] - zj, points[:, 1] - yj) <= phantom.thickness
    near_t = np.hypot(truth[:, 0] - zj, truth[:, 1] - yj) <= phantom.thickness
    # away from the plate ends (x within one thickness of the end faces): the dent proper
    x0, x1 = flange.origin[2], flange.origin[2] + flange.v[2]
    inner_v = near_v & (points[:, 2] > x0 + phantom.thickness) & (points[:, 2] < x1 - phantom.thickness)
    lo = np.array([flange.origin[1], flange.origin[2]])
    hi = lo + np.array([flange.u[1], flange.v[2]])
    end_z = stem.origin[0] + stem.u[0]
    free = (np.minimum(truth[:, 1] - lo[0], hi[0] - truth[:, 1]) <= 2) & (np.abs(truth[:, 0] - zj) < 0.1)
    free |= (np.minimum(truth[:, 2] - lo[1], hi[1] - truth[:, 2]) <= 2)
    free |= (end_z - truth[:, 0] <= 2) & (np.abs(truth[:, 1] - yj) < 0.1)
    topo = mesh_topology(faces)
    return {
        "vertex_p99": float(np.percentile(d, 99)),
        "vertex_max": float(d.max()),
        "coverage": frac,
        "coverage_free_edges": float(np.mean(dist[free] <= 1.0)),
        "junction_vertex_max": float(d[near_v].max()),
        "dent_vertex_max": float(d[inner_v].max()),
        "junction_truth_max": float(dist[near_t].max()),
        "junction_coverage": float(np.mean(dist[near_t] <= 1.0)),
        "median_thickness": float(np.median(2 * radii)),
        "topology": topo,
    }


def score(path: str, phantom) -> dict:
    z = np.load(path + ".ours.npz")
    return score_arrays(z["points"], z["faces"], z["radii"], phantom)


def other_phantoms() -> list[tuple[str, int, int, dict]]:
    """The member (tube with a flange: Euler 0) and the X junction (Euler 1), over seeds."""
    import medialaxis as mx
    from medialaxis.datasets import member_phantom, x_phantom
    from medialaxis.volume.validation import coverage, distance_to_rects, mesh_topology

    rows = []
    for name, make in (("member", member_phantom), ("X", x_phantom)):
        for noise_seed, rng in ((0, 0), (1, 0), (2, 0), (0, 1), (3, 1), (4, 0)):
            ph = make(rng=noise_seed)
            ma = mx.medial_axis(ph.volume, method="midsurface", iso=0.5, rng=rng)
            d = distance_to_rects(ma.points, ph.midsurface)
            truth = np.concatenate([r.sample(0.5) for r in ph.midsurface])
            rows.append((name, noise_seed, rng, {
                "p99": float(np.percentile(d, 99)), "max": float(d.max()),
                "coverage": coverage(truth, ma.points, ma.faces)[0], "topology": mesh_topology(ma.faces),
            }))
    return rows


def different_plates() -> list[tuple[str, float, list[tuple[float, float, float]]]]:
    """A T with an 8-voxel flange and a 4-voxel rib (issue 11), isotropic and
    with slices twice as far apart as pixels (two fine slices averaged):
    per plate, the true mid-plane covered within 1.5 voxels and the median
    thickness of the vertices on it."""
    import medialaxis as mx
    from medialaxis.datasets import Rect, t_phantom
    from medialaxis.volume.validation import coverage, distance_to_rects

    ph = t_phantom((100, 160, 160), thickness=8, stem_thickness=4, margin=16)
    rows = []
    for name, order in (("isotropic", None), ("slices 2x, flange across", [0, 1, 2]),
                        ("slices 2x, flange along", [2, 1, 0]), ("slices 2x, rib across", [1, 0, 2])):
        if order is None:
            vol, spacing, rects = ph.volume, (1.0, 1.0, 1.0), ph.midsurface
        else:
            fine = np.ascontiguousarray(ph.volume.transpose(order))
            z = fine.shape[0] // 2 * 2
            vol, spacing = 0.5 * (fine[0:z:2] + fine[1:z:2]), (2.0, 1.0, 1.0)
            rects = [Rect(r.origin[order] - np.array([0.5, 0, 0]), r.u[order], r.v[order]) for r in ph.midsurface]
        t0 = time.perf_counter()
        ma = mx.medial_axis(vol, method="midsurface", iso=0.5, spacing=spacing)
        secs = time.perf_counter() - t0
        plates = []
        for k, rect in enumerate(rects):
            frac, _ = coverage(rect.sample(0.5), ma.points, ma.faces, tolerance=1.5)
            on = (distance_to_rects(ma.points, [rect]) < 1.5) & (distance_to_rects(ma.points, rects[1 - k:2 - k]) > 6)
            plates.append((frac, float(np.median(2 * ma.radii[on])), ph.plate_thickness[k]))
        rows.append((name, secs, plates))
    return rows


def robustness(shape: tuple[int, int, int]) -> list[tuple[int, int, float, dict]]:
    """Our pipeline over noise seeds x sampling seeds (in this process)."""
    import medialaxis as mx
    from medialaxis.datasets import t_phantom

    rows = []
    for noise_seed in (0, 1, 2):
        ph = t_phantom(shape, rng=noise_seed)
        for rng in (0, 1):
            t0 = time.perf_counter()
            ma = mx.medial_axis(ph.volume, method="midsurface", iso=0.5, rng=rng)
            rows.append((noise_seed, rng, time.perf_counter() - t0, score_arrays(ma.points, ma.faces, ma.radii, ph)))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shape", type=int, nargs=3, default=(140, 240, 240))
    parser.add_argument("--quick", action="store_true", help="skip the robustness table over seeds")
    parser.add_argument("--child", nargs=2, metavar=("TOOL", "PATH"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        print(json.dumps(child(*args.child)))
        return
    from medialaxis.datasets import t_phantom

    ph = t_phantom(tuple(args.shape))
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "t.npy")
        np.save(path, ph.volume)
        print(f"T phantom {tuple(args.shape)}: plates {ph.thickness:g} voxels, blur 1, noise 0.05, iso 0.5; "
              f"{os.cpu_count()} cores (shared: timings are pessimistic)")
        res = {tool: run_child(tool, path) for tool in ("ours", "skimage", "kimimaro", "ft_ours", "ft_scipy", "ft_edt")}
        ours = res["ours"]
        if "error" in ours:
            raise SystemExit(f"ours failed: {ours['error']}")
        s = score(path, ph)
    mb = ours["peak_mb"]
    print(f"\nours (midsurface): {ours['seconds']:.2f} s, peak RSS {mb:.0f} MB (process incl. imports and input), "
          f"{ours['vertices']} vertices, {ours['faces']} faces")
    print("  stages: " + ", ".join(f"{k} {v:.2f} s" for k, v in ours["timings"].items()))
    for tool in ("skimage", "kimimaro"):
        r = res[tool]
        if "error" in r:
            print(f"{tool}: failed: {r['error']}")
            continue
        size = f"{r['voxels']} skeleton voxels" if tool == "skimage" else f"{r['vertices']} vertices, {r['edges']} edges (trees)"
        print(f"{tool}: {r['seconds']:.2f} s, peak RSS {r['peak_mb']:.0f} MB, {size}; "
              f"time ratio ours/{tool} = {ours['seconds'] / r['seconds']:.2f}")
    print("\ndistance / feature transform of the same volume:")
    for tool, label in (("ft_ours", "ours: sub-voxel boundary + k-d tree"), ("ft_scipy", "scipy distance_transform_edt(return_indices)"),
                        ("ft_edt", "edt.edt (distance only, no feature transform)")):
        r = res[tool]
        if "error" in r:
            print(f"  {label}: failed: {r['error']}")
            continue
        extra = r["peak_mb"] - r["baseline_mb"]
        print(f"  {label}: {r['seconds']:.2f} s, +{extra:.0f} MB peak over baseline; ratio to ours {r['seconds'] / res['ft_ours']['seconds']:.2f}")
    ext = ours["timings"].get("extension", float("nan"))
    print(f"\nextension stage: {ext:.3f} s (paper Table 1, T 240x240x140: 1,190 s; ratio {1190 / max(ext, 1e-9):.0f}x); "
          f"dent removal {ours['timings'].get('dents', float('nan')):.3f} s (paper: 7 s)")
    t = s["topology"]
    checks = [
        ("vertex distance to true mid-planes p99 <= 1 voxel", s["vertex_p99"], s["vertex_p99"] <= 1.0),
        ("vertex distance max <= 2 voxels", s["vertex_max"], s["vertex_max"] <= 2.0),
        ("true mid-surface within 1 voxel of the mesh >= 98.5%", s["coverage"], s["coverage"] >= 0.985),
        ("  of it within 2 voxels of a free edge (extension)", s["coverage_free_edges"], s["coverage_free_edges"] >= 0.985),
        ("max deviation of vertices near the junction <= 0.75", s["junction_vertex_max"], s["junction_vertex_max"] <= 0.75),
        ("  true mid-surface near the junction within 1 voxel (no slit)", s["junction_coverage"],
         s["junction_coverage"] >= 0.985),
        ("  same, away from the plate ends (the dent) <= 0.75", s["dent_vertex_max"], s["dent_vertex_max"] <= 0.75),
        ("median thickness within 10% of 6", s["median_thickness"], abs(s["median_thickness"] - 6) <= 0.6),
        ("one connected mesh", t.components, t.components == 1),
        ("contractible (Euler characteristic 1)", t.euler, t.euler == 1),
        ("non-manifold junction edges present", t.junction_edges, t.junction_edges > 0),
        ("whole pipeline <= 10 s", ours["seconds"], ours["seconds"] <= 10),
        ("peak memory <= 2 GB", mb, mb <= 2048),
    ]
    print("\ntargets:")
    for name, value, ok in checks:
        print(f"  [{'PASS' if ok else 'FAIL'}] {name}: {value:.4g}" if isinstance(value, float) else
              f"  [{'PASS' if ok else 'FAIL'}] {name}: {value}")
    print(f"  (truth points near the junction: max distance to the mesh {s['junction_truth_max']:.3f}; mesh {t})")
    print("\nplates of different thickness (T, flange 8, rib 4; targets: >= 97% covered within 1.5 voxels,"
          " thickness within 15%):")
    for name, secs, plates in different_plates():
        cells = "  ".join(f"{label} {frac:.1%} thick {thick:.2f}/{true:g}"
                          for label, (frac, thick, true) in zip(("flange", "rib"), plates))
        ok = all(frac >= 0.97 and abs(thick - true) <= 0.15 * true for frac, thick, true in plates)
        print(f"  [{'PASS' if ok else 'FAIL'}] {name:26s} {secs:5.2f} s  {cells}")
    if not args.quick:
        rows = robustness(tuple(args.shape))
        print("\nrobustness: noise seed x sampling seed (rng), same T, in-process:")
        print("  noise rng  time_s  p99    max    cover   free    junct  dent   jcover  thick  euler  comps  jedges")
        for noise_seed, rng, secs, r in rows:
            tp = r["topology"]
            print(f"  {noise_seed:5d} {rng:3d}  {secs:6.2f}  {r['vertex_p99']:.3f}  {r['vertex_max']:.3f}  {r['coverage']:.4f}  "
                  f"{r['coverage_free_edges']:.4f}  {r['junction_vertex_max']:.3f}  {r['dent_vertex_max']:.3f}  "
                  f"{r['junction_coverage']:.4f}  {r['median_thickness']:.3f}  {tp.euler:5d}  {tp.components:5d}  "
                  f"{tp.junction_edges:6d}")
        print("\nmember (expected Euler 0) and X junction (expected Euler 1), noise seed x rng:")
        print("  phantom noise rng  p99    max    cover   euler  comps  jedges")
        for name, noise_seed, rng, r in other_phantoms():
            tp = r["topology"]
            print(f"  {name:7s} {noise_seed:5d} {rng:3d}  {r['p99']:.3f}  {r['max']:.3f}  {r['coverage']:.4f}  "
                  f"{tp.euler:5d}  {tp.components:5d}  {tp.junction_edges:6d}")


if __name__ == "__main__":
    main()
