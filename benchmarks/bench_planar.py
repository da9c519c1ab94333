"""Planar benchmarks: medialaxis side by side with scikit-image, in one run.

Run:  .venv/bin/python benchmarks/bench_planar.py [--quick]

Prints, for each case, our figure, scikit-image's figure from the same run
and the ratio:
1. speed and peak memory on a 2048 x 2048 mask (skimage.morphology.medial_axis
   and skeletonize);
2. a 1,000,000-vertex polygon (and how the work follows the axis, not the
   vertex count: samples used for 10k / 100k / 1M vertices of one shape);
3. accuracy on analytic shapes (polygons, anti-aliased and binary 512 x 512
   images at 0/10/30/45 degrees) against the exact axis;
4. Kimia-99 robustness: connected axes, cycles = holes, endpoint count kept
   after a 30 degree rotation;
5. the tolerance (accuracy parameter) trade-off;
6. images with holes (1-3 round and square holes, 4 rotations, bool, float and
   uint8, bright and dark shapes) and the annulus of radii 60 and 150.

Pieces and holes are counted by scikit-image (``label`` and ``euler_number``
with 4-connected foreground), never read from our own metadata.
"""

from __future__ import annotations

import argparse
import time
import tracemalloc
from pathlib import Path

import numpy as np
import shapely
from PIL import Image
from scipy import ndimage
from shapely import affinity
from skimage.morphology import medial_axis as sk_medial_axis
from skimage.morphology import skeletonize
from skimage.transform import resize, rotate

import medialaxis as mx
from medialaxis.datasets import (
    annulus,
    ellipse,
    ellipse_axis,
    holed_shapes,
    in_image,
    rasterize,
    rectangle_axis,
    render,
    rotation,
)
from medialaxis.datasets import raster_counts as truth_counts
from medialaxis.datasets import segment_distance as distance_to_segments

ROOT = Path(__file__).resolve().parents[1]

KIMIA = ROOT / "tests" / "data" / "kimia99"


def best_of(fn, repeat=3):
    times = []
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def peak_memory(fn):
    tracemalloc.start()
    fn()
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return peak


def row(name, ours, peer, unit="", better="lower"):
    ratio = peer / ours if better == "lower" else ours / peer
    print(f"  {name:<44} ours {ours:>10.4g}{unit}   peer {peer:>10.4g}{unit}   ratio {ratio:6.2f}x")


def skeleton_endpoints(skel: np.ndarray) -> int:
    nb = ndimage.convolve(skel.astype(np.uint8), np.ones((3, 3), np.uint8), mode="constant") - skel
    return int(((nb == 1) & skel).sum())


# --------------------------------------------------------------- 1. speed
def bench_mask(repeat):
    print("\n1. 2048 x 2048 mask (Kimia class3_05 upsampled, plus two holes)")
    src = np.asarray(Image.open(KIMIA / "class3_05.png")).astype(float)
    mask = resize(src, (2048, 2048), order=1) > 0.5
    rr, cc = np.mgrid[:2048, :2048]
    mask &= (rr - 700) ** 2 + (cc - 1000) ** 2 > 60**2
    mx.medial_axis(mask)  # warm up (numba cache, imports)
    t_ours, ma = best_of(lambda: mx.medial_axis(mask), repeat)
    t_sk, _ = best_of(lambda: sk_medial_axis(mask), repeat)
    t_skel, _ = best_of(lambda: skeletonize(mask), repeat)
    row("time vs skimage.morphology.medial_axis [s]", t_ours, t_sk, "s")
    row("time vs skimage.morphology.skeletonize [s]", t_ours, t_skel, "s")
    m_ours = peak_memory(lambda: mx.medial_axis(mask)) / 2**20
    m_sk = peak_memory(lambda: sk_medial_axis(mask)) / 2**20
    row("peak traced memory vs medial_axis [MiB]", m_ours, m_sk, "MiB")
    print(f"  our axis: {len(ma.points)} points, {ma.metadata['n_samples']} boundary samples, "
          f"{len(ma.endpoints)} endpoints, {ma.n_cycles} cycles")


def star(n_vertices: int) -> shapely.Polygon:
    th = np.linspace(0, 2 * np.pi, n_vertices, endpoint=False)
    r = 1 + 0.3 * np.cos(5 * th) + 0.05 * np.sin(17 * th)
    return shapely.Polygon(np.c_[r * np.cos(th), r * np.sin(th)]).difference(shapely.Point(0, 0).buffer(0.3, quad_segs=64))


def bench_polygon(repeat):
    print("\n2. Large polygons (a 5-lobed star with a hole)")
    for n in (10_000, 100_000, 1_000_000):
        poly = star(n)
        mx.medial_axis(poly)
        t, ma = best_of(lambda poly=poly: mx.medial_axis(poly), repeat)
        print(f"  {n:>9,} vertices: {t:6.3f} s, {ma.metadata['n_samples']:>6} boundary samples, "
              f"{len(ma.points)} axis points, {len(ma.endpoints)} endpoints, {ma.n_cycles} cycle")
    print("  (SciPy Qhull on all 1M vertices of a closed curve: ~66 s; the samples follow the axis, not the vertex count)")


# ------------------------------------------------------------ 3. accuracy
def bench_accuracy():
    print("\n3. Accuracy against the exact axis")
    for name, geom, segs in (
        ("rectangle 4 x 2", shapely.box(-2, -1, 2, 1), rectangle_axis(4, 2)),
        ("ellipse 2 x 1 (2000-gon)", ellipse(), ellipse_axis()),
    ):
        worst = 0.0
        for angle in (0, 10, 30, 45):
            ma = mx.medial_axis(affinity.rotate(geom, angle, origin=(0, 0)))
            back = ma.points @ rotation(angle)
            diag = float(np.linalg.norm(np.ptp(np.array([p for s in segs for p in s]), axis=0)))
            worst = max(worst, distance_to_segments(back, segs).max() / diag)
        print(f"  polygon {name:<26} max error / exact-axis diagonal: {worst:.2e} (target 2e-3)")
    ma = mx.medial_axis(annulus())
    print(f"  polygon annulus 2/1               max | |p| - 1.5 |: {np.abs(np.linalg.norm(ma.points, axis=1) - 1.5).max():.2e}")
    for label, binary in (("anti-aliased", False), ("binary mask", True)):
        for name, geom, segs in (
            ("rectangle 360 x 180", shapely.box(-180, -90, 180, 90), rectangle_axis(360, 180)),
            ("ellipse 400 x 200", ellipse(200, 100), ellipse_axis(200, 100)),
        ):
            ours, peer = [], []
            for angle in (0, 10, 30, 45):
                img = render(in_image(geom, angle))
                image = img > 0.5 if binary else img
                rot = rotation(angle)
                exact = [((rot @ np.array(a))[::-1] + 256, (rot @ np.array(b))[::-1] + 256) for a, b in segs]
                ma = mx.medial_axis(image)
                ours.append(np.percentile(distance_to_segments(ma.points, exact), 99))
                skel = sk_medial_axis(img > 0.5)
                peer.append(np.percentile(distance_to_segments(np.argwhere(skel).astype(float), exact), 99))
            print(f"  512^2 {label:<12} {name:<20} p99 error [px] ours max {max(ours):5.2f}   "
                  f"skimage max {max(peer):6.2f}   (target {'1.5' if binary else '1.0'})")


# -------------------------------------------------------------- 4. Kimia
def bench_kimia():
    print("\n4. Kimia-99: endpoint count after a 30 degree rotation, connectivity, cycles")
    files = sorted(KIMIA.glob("*.png"))
    same_ours = same_sk = connected = cycles_ok = holes = with_holes = 0
    t_ours = t_sk = 0.0
    for f in files:
        m = np.asarray(Image.open(f)).astype(bool)
        r = rotate(m.astype(float), 30, resize=True, order=1) > 0.5
        t0 = time.perf_counter()
        a, b = mx.medial_axis(m), mx.medial_axis(r)
        t_ours += time.perf_counter() - t0
        t0 = time.perf_counter()
        sa, sb = sk_medial_axis(m), sk_medial_axis(r)
        t_sk += time.perf_counter() - t0
        same_ours += len(a.endpoints) == len(b.endpoints)
        same_sk += skeleton_endpoints(sa) == skeleton_endpoints(sb)
        (pa, ha), (pb, hb) = truth_counts(m), truth_counts(r)
        connected += a.n_components == pa and b.n_components == pb
        cycles_ok += a.n_cycles == ha and b.n_cycles == hb
        holes += ha + hb
        with_holes += (ha > 0) + (hb > 0)
    n = len(files)
    print(f"  same endpoint count after rotation: ours {same_ours}/{n}, skimage medial_axis {same_sk}/{n} (target >= 90%)")
    print(f"  axis components = pieces (skimage) at 0 and 30 deg: {connected}/{n}; cycles = holes (skimage): "
          f"{cycles_ok}/{n} ({with_holes} of the {2 * n} masks have holes, {holes} holes in all)")
    row("time per shape [ms]", 1000 * t_ours / (2 * n), 1000 * t_sk / (2 * n), "ms")


# ------------------------------------------------------------ 5. trade-off
def bench_tolerance():
    print("\n5. The accuracy parameter (tolerance) on the 100k-vertex star")
    poly = star(100_000)
    ref = mx.medial_axis(poly, tolerance=1e-6)
    ref_lines = shapely.MultiLineString([ref.points[e] for e in ref.edges])
    for tol in (1e-5, 1e-4, 1e-3, 1e-2):
        t, ma = best_of(lambda tol=tol: mx.medial_axis(poly, tolerance=tol), 3)
        err = shapely.distance(shapely.points(ma.points), ref_lines)
        print(f"  tolerance {tol:7.0e}: {t * 1000:7.1f} ms, {ma.metadata['n_samples']:>6} samples, "
              f"p99 distance to the tolerance-1e-6 axis {np.percentile(err, 99):.2e}")


# ---------------------------------------------------------------- 6. holes
def skeleton_cycles(skel: np.ndarray) -> int:
    """Independent cycles of a pixel skeleton (8-connected): its holes, by scikit-image."""
    from skimage.measure import euler_number, label

    return int(label(skel, connectivity=2).max()) - int(euler_number(skel, connectivity=2))


def bench_holes():
    print("\n6. Images with holes: cycles = holes and components = pieces, counted by scikit-image")
    shapes = holed_shapes()
    ok = total = ok_sk = total_sk = 0
    t_ours = t_sk = 0.0
    for geom in shapes.values():
        for angle in (0, 15, 30, 45):
            for kind in ("bool", "float", "uint8"):
                image = rasterize(geom, 320, angle, kind)
                mask = image if kind == "bool" else image > (0.5 if kind == "float" else 127)
                pieces, holes = truth_counts(mask)
                dark = ~image if kind == "bool" else (1.0 - image if kind == "float" else 255 - image)
                for img in (image, dark):
                    t0 = time.perf_counter()
                    ma = mx.medial_axis(img)
                    t_ours += time.perf_counter() - t0
                    ok += ma.n_cycles == holes and ma.n_components == pieces
                    total += 1
                t0 = time.perf_counter()
                skel = sk_medial_axis(mask)
                t_sk += time.perf_counter() - t0
                ok_sk += skeleton_cycles(skel) == holes and int(ndimage.label(skel, np.ones((3, 3)))[1]) == pieces
                total_sk += 1
    print(f"  {len(shapes)} shapes x 4 rotations x (bool, float, uint8) x (bright, dark): ours {ok}/{total} right; "
          f"skimage medial_axis (bright masks) {ok_sk}/{total_sk}")
    row("time per image [ms]", 1000 * t_ours / total, 1000 * t_sk / total_sk, "ms")
    centre = 255.5
    rr, cc = np.mgrid[:512, :512]
    r = np.hypot(rr - centre, cc - centre)
    cover = np.clip(150.5 - r, 0, 1) * np.clip(r - 59.5, 0, 1)
    images = {"binary": (r < 150) & (r > 60), "anti-aliased": cover, "dark uint8": np.round(255 * (1 - cover)).astype(np.uint8)}
    for label_, img in images.items():
        for boundary in ("contour", "canny"):
            ma = mx.medial_axis(img, boundary=boundary)
            off = np.abs(np.hypot(ma.points[:, 0] - centre, ma.points[:, 1] - centre) - 105)
            print(f"  annulus 60/150 {label_:<12} {boundary:<7}: {ma.n_cycles} cycle, p99 distance to the circle of "
                  f"radius 105 {np.percentile(off, 99):.2f} px, p99 radius error {np.percentile(np.abs(ma.radii - 45), 99):.2f} px")
    mask = images["binary"]
    sk = sk_medial_axis(mask)
    pts = np.argwhere(sk)
    off = np.abs(np.hypot(pts[:, 0] - centre, pts[:, 1] - centre) - 105)
    print(f"  peer: skimage medial_axis on the binary annulus: {skeleton_cycles(sk)} cycle, p99 {np.percentile(off, 99):.2f} px")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one repetition per timing")
    args = parser.parse_args(argv)
    repeat = 1 if args.quick else 3
    print(f"medialaxis {mx.__version__}; numpy {np.__version__}; 2 cores")
    bench_mask(repeat)
    bench_polygon(repeat)
    bench_accuracy()
    bench_kimia()
    bench_tolerance()
    bench_holes()


if __name__ == "__main__":
    main()
