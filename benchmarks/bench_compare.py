"""Kimia-99 retrieval and collection timing of the medial-axis shape distance.

Prints, from one run: our retrieval row (ranks 1..10, standard protocol: each
of the 99 shapes queries the other 98) with the default distance (the axis
tour) on the shapes read as boolean masks and given as PNG paths, with the
previous default (skeleton paths plus the unordered axis context, moved out of
the package to ``benchmarks/research/``) and with collection-level re-ranking; the same row for two
baselines (Hu moments; shape contexts with Hungarian matching), the
literature's shock-graph row, the time per pair of each, and the time of
``distance_matrix`` on a 1,400-shape collection (Kimia-99 signatures
repeated, so the pairwise step is real; signatures are per-shape work,
measured separately).

    PYTHONPATH=src python benchmarks/bench_compare.py [--data DIR] [--collection 1400] [--jobs 2] [--variants]
    PYTHONPATH=src python benchmarks/bench_compare.py --mpeg7 ../shared/data/mpeg7_dev [--no-shape-context]

``--mpeg7 DIR`` instead computes the MPEG-7 bull's-eye (each shape queries the
whole set; same-class shapes among its 40 nearest, as a share of the most
possible) on any folder of ``<class>-<k>.gif`` silhouettes: the default
distance, its diffusion re-ranking (collection-level, a second row), the
default without the closed shapes (``closing=0``) and at two other closing
offsets, the previous default and invariant shape contexts, with a 5-fold split of the
classes (queries of every fifth class in sorted order against the whole set)
and the published figures for reference.

``--variants`` also prints the row of each variant evaluated for issue 6:
for the tour term, the gap cost and the pruning (signature pruning levels,
each of the two axis prunings alone) and the other terms added to it; for
the path term (the main term before the tour), pruning levels, coarser or finer axis pruning
through ``MedialAxis.prune``, more radius samples, Discrete Curve Evolution
skeleton pruning, and each matching weight halved and doubled. Each row has
the split check used against overfitting: its sum over the queries of the
odd-numbered classes (A) and of the even-numbered ones (B). A change is kept
only if it raises both halves; the rows of settings near the default differ
by a few units either way, which is the noise of this measure.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from PIL import Image
from scipy.optimize import linear_sum_assignment
from scipy.spatial.distance import cdist
from skimage import measure

import medialaxis as mx
from medialaxis.compare import shape_signature, signature
from medialaxis.compare.retrieval import diffusion_rerank, retrieval_row
from research.path_similarity import PATH_PARAMS, path_signature, previous_default, term_matrices

#: Shock-graph matching (Sebastian, Klein, Kimia, TPAMI 2004), as quoted in the issue.
SHOCK_GRAPH = np.array([99, 99, 99, 98, 98, 97, 96, 95, 93, 82])
#: Bai and Latecki's own path-similarity figure (TPAMI 2008), for reference.
BAI_LATECKI = np.array([99, 99, 99, 99, 96, 97, 95, 93, 89, 73])


def _default_data() -> Path:
    here = Path(__file__).resolve().parent.parent
    for cand in (here.parent / "shared" / "data" / "kimia99", Path("/work/shared/data/kimia99"), here / "tests" / "data" / "kimia99"):
        if cand.is_dir() and len(list(cand.glob("class*_*.png"))) == 99:
            return cand
    raise SystemExit("Kimia-99 folder not found; pass --data")


def _mask(path: Path) -> np.ndarray:
    return np.asarray(Image.open(path).convert("L")) > 127


# ------------------------------------------------------------ baselines
def hu_matrix(masks: list[np.ndarray]) -> tuple[np.ndarray, float]:
    """Hu moment invariants, log-scaled, L1 distance (OpenCV's CONTOURS_MATCH_I1 style)."""
    feats = []
    for m in masks:
        hu = measure.moments_hu(measure.moments_normalized(measure.moments_central(m.astype(float)), 3))
        feats.append(-np.sign(hu) * np.log10(np.abs(hu) + 1e-30))
    F = np.array(feats)
    t0 = time.perf_counter()
    D = np.abs(F[:, None, :] - F[None, :, :]).sum(axis=2)
    return D, (time.perf_counter() - t0) / (len(F) * (len(F) - 1) / 2)


def _shape_context(
    mask: np.ndarray, n_points: int = 100, n_r: int = 5, n_theta: int = 12, *, invariant: bool = False
) -> list[np.ndarray]:
    contour = max(measure.find_contours(np.pad(mask, 1).astype(float), 0.5), key=len)
    seg = np.linalg.norm(np.diff(contour, axis=0), axis=1)
    arc = np.concatenate([[0], np.cumsum(seg)])
    t = np.linspace(0, arc[-1], n_points, endpoint=False)
    pts = np.column_stack([np.interp(t, arc, contour[:, 0]), np.interp(t, arc, contour[:, 1])])
    d = cdist(pts, pts)
    d /= d[d > 0].mean()
    theta = np.arctan2(pts[None, :, 0] - pts[:, None, 0], pts[None, :, 1] - pts[:, None, 1])
    if invariant:
        tangent = np.roll(pts, -2, axis=0) - np.roll(pts, 2, axis=0)
        theta = np.mod(theta - np.arctan2(tangent[:, 0], tangent[:, 1])[:, None] + np.pi, 2 * np.pi) - np.pi
    r_edges = np.logspace(np.log10(0.125), np.log10(2.0), n_r + 1)
    r_bin = np.searchsorted(r_edges, d) - 1
    t_bin = ((theta + np.pi) / (2 * np.pi) * n_theta).astype(int) % n_theta
    ok = (r_bin >= 0) & (r_bin < n_r) & ~np.eye(n_points, dtype=bool)
    rows = np.nonzero(ok)[0]
    out = []
    for bins in ([t_bin, n_theta - 1 - t_bin] if invariant else [t_bin]):
        hist = np.zeros((n_points, n_r * n_theta))
        np.add.at(hist, (rows, (r_bin * n_theta + bins)[ok]), 1)
        out.append(hist / np.maximum(hist.sum(axis=1, keepdims=True), 1))
    return out


def shape_context_matrix(masks: list[np.ndarray], *, invariant: bool = False) -> tuple[np.ndarray, float]:
    """Shape contexts (Belongie, Malik, Puzicha), chi-squared costs, Hungarian matching (no TPS).

    ``invariant``: angles from the contour tangent and the mirrored histograms
    tried too (rotation and mirror invariant, as our distance is); otherwise
    image-axis angles (the plain version, which Kimia-99's upright shapes favour less).
    """
    H = [_shape_context(m, invariant=invariant) for m in masks]
    n = len(H)
    D = np.zeros((n, n))
    t0 = time.perf_counter()
    for i in range(n):
        for j in range(i + 1, n):
            best = np.inf
            for hb in H[j]:
                a, b = H[i][0][:, None, :], hb[None, :, :]
                cost = 0.5 * ((a - b) ** 2 / (a + b + 1e-12)).sum(axis=2)
                r, c = linear_sum_assignment(cost)
                best = min(best, cost[r, c].mean())
            D[i, j] = D[j, i] = best
    return D, (time.perf_counter() - t0) / (n * (n - 1) / 2)


def robustness(
    masks: list[np.ndarray], sigs: list, labels: np.ndarray, rng: np.random.Generator, make_signature=None
) -> dict[str, str]:
    """Share of perturbed shapes closer to their original than to any shape of another class.

    ``make_signature(mask)`` builds the perturbed shape's signature (default
    :func:`shape_signature`); ``sigs`` must be built the same way.
    """
    from scipy import ndimage
    from skimage import transform

    from medialaxis.compare import query_distances

    def noise(m: np.ndarray, width: int) -> np.ndarray:
        inside, outside = ndimage.distance_transform_edt(m), ndimage.distance_transform_edt(~m)
        band = (m & (inside <= width)) | (~m & (outside <= width))
        out = m.copy()
        flip = band & (rng.random(m.shape) < 0.2)
        out[flip] = ~out[flip]
        return ndimage.binary_fill_holes(out)

    kinds = {
        "rotated 37 deg": lambda m: transform.rotate(m.astype(float), 37, resize=True, order=1) > 0.5,
        "rescaled x1.6": lambda m: transform.rescale(m.astype(float), 1.6, order=1) > 0.5,
        "rescaled x0.7": lambda m: transform.rescale(m.astype(float), 0.7, order=1) > 0.5,
        "mirrored": lambda m: m[:, ::-1],
        "1-px boundary noise": lambda m: noise(m, 1),
        "2-px boundary noise": lambda m: noise(m, 2),
    }
    out = {}
    for name, make in kinds.items():
        ok = total = 0
        for q in range(0, len(masks), 2):
            moved = (make_signature or shape_signature)(make(masks[q]))
            others = [s for s, lab in zip(sigs, labels) if lab != labels[q]]
            d_self = mx.shape_distance(moved, sigs[q])
            ok += int(d_self < query_distances(moved, others, n_jobs=1).min())
            total += 1
        out[name] = f"{ok}/{total}"
    return out


def split_sums(D: np.ndarray, labels: np.ndarray, ranks: int = 10) -> tuple[int, int]:
    """Retrieval-row sums over the queries of odd-numbered classes and of even-numbered ones."""
    D = D.copy()
    np.fill_diagonal(D, np.inf)
    hits = labels[np.argsort(D, axis=1, kind="stable")[:, :ranks]] == labels[:, None]
    odd = labels % 2 == 1
    return int(hits[odd].sum()), int(hits[~odd].sum())


def variants(axes: list, labels: np.ndarray, jobs: int | None) -> None:
    """Rows of the variants tried (see the module docstring)."""

    def row(name: str, D: np.ndarray) -> None:
        a, b = split_sums(D, labels)
        print(f"  {name:38s}{_fmt(retrieval_row(D, labels))}  A {a} B {b}")

    def tour(sigs: list, **params: float) -> np.ndarray:
        return mx.distance_matrix(sigs, n_jobs=jobs, **params)

    def terms(params: dict[str, float] | None = None, **options) -> dict[str, np.ndarray]:
        return term_matrices([path_signature(ax, **options) for ax in axes], n_jobs=jobs, params=params)

    print("\nvariants (A: queries of classes 1,3,5,7,9; B: classes 2,4,6,8)")
    sigs = [signature(ax) for ax in axes]
    D = tour(sigs)
    row("defaults (tour)", D)
    for gap in (0.2, 0.25, 0.35, 0.4):
        row(f"gap={gap}", tour(sigs, gap=gap))
    for prune in (0.02, 0.045):
        row(f"prune={prune}", tour([signature(ax, prune=prune) for ax in axes]))
    for closing in (0.0, 0.02, 0.06):
        row(f"closing={closing}", tour([signature(ax, closing=closing) for ax in axes]))
    row("tour of the unpruned axis", tour([signature(ax, unpruned=True) for ax in axes]))
    base = terms()
    for weight in (0.05, 0.2):
        row(f"tour + {weight} paths", D + weight * base["paths"])
        row(f"tour + {weight} context", D + weight * base["context"])
    print("  -- the path term (the main term before the tour; benchmarks/research/)")
    row("paths alone", base["paths"])
    row("paths + 0.6 context (previous default)", previous_default(base))
    row("context alone", base["context"])
    for prune in (0.02, 0.045, 0.06):
        row(f"paths+context, prune={prune}", previous_default(terms(prune=prune)))
    for detour in (0.2, 0.35):
        detoured = term_matrices([path_signature(ax.prune(detour=detour)) for ax in axes], n_jobs=jobs)
        row(f"paths+context, axis detour={detour}", previous_default(detoured))
    row("paths+context, n_samples=50", previous_default(terms(n_samples=50)))
    for dce in (0.01, 0.02):
        row(f"paths+context, dce={dce}", previous_default(terms(dce=dce)))
    row("paths+context, unpruned", previous_default(terms(unpruned=True)))
    for k in (12, 16):
        row(f"paths+context, unpruned, DCE to {k}", previous_default(terms(unpruned=True, dce=1.0, dce_vertices=k)))
    for key, value in PATH_PARAMS.items():
        for factor in (0.5, 2.0):
            row(f"paths+context, {key}={value * factor:.4g}", previous_default(terms({**PATH_PARAMS, key: value * factor})))


def _fmt(row: np.ndarray) -> str:
    return " ".join(f"{v:3d}" for v in row) + f"   (sum {int(row.sum())})"


#: Published MPEG-7 bull's-eye scores (pairwise, no re-ranking), as quoted in issue 15.
MPEG7_LITERATURE = {"IDSC (Ling and Jacobs 2007)": 85.40, "shape tree (Felzenszwalb and Schwartz 2007)": 87.70,
                    "height functions (Wang et al. 2012)": 90.35}


def bulls_eye(D: np.ndarray, labels: np.ndarray, queries: np.ndarray | None = None) -> float:
    """MPEG-7 bull's-eye: same-class shapes among each query's 40 nearest (itself included), in %."""
    queries = np.arange(len(D)) if queries is None else queries
    per_class = np.bincount(np.unique(labels, return_inverse=True)[1])
    hits = 0
    for q in queries:
        top = np.argsort(D[q], kind="stable")[:40]
        hits += int((labels[top] == labels[q]).sum())
    best = sum(min(40, int(per_class[np.unique(labels, return_inverse=True)[1][q]])) for q in queries)
    return 100.0 * hits / best


def mpeg7(folder: Path, jobs: int | None, with_shape_context: bool, collection: int = 0) -> None:
    """Bull's-eye of the default distance, its re-ranked form, the previous default and shape contexts.

    With ``collection``, also times ``distance_matrix`` on that many of the
    set's masks and their mirror images (signatures included: every shape is
    computed from its pixels), and reports how far each mirror image's
    distances are from its original's (raster flips trace the contour a
    little differently; polygons are exactly mirror invariant).
    """
    files = sorted(folder.glob("*-*.gif"), key=lambda p: (p.stem.rsplit("-", 1)[0], int(p.stem.rsplit("-", 1)[1])))
    if not files:
        raise SystemExit(f"no <class>-<k>.gif files in {folder}")
    names = [p.stem.rsplit("-", 1)[0] for p in files]
    classes = sorted(set(names))
    labels = np.array([classes.index(n) for n in names])
    masks = [_mask(p) for p in files]
    print(f"MPEG-7 style set {folder}: {len(files)} shapes, {len(classes)} classes")
    mx.distance_matrix([masks[0], masks[1]], n_jobs=1)  # compile before timing
    t0 = time.perf_counter()
    axes = [mx.medial_axis(m) for m in masks]
    sigs = [shape_signature(ax) for ax in axes]
    t_sig = time.perf_counter() - t0
    t0 = time.perf_counter()
    D = mx.distance_matrix(sigs, n_jobs=jobs)
    t_pairs = time.perf_counter() - t0
    rows = [("ours (axis tour, the default)", D), ("ours + diffusion re-ranking (collection-level)", diffusion_rerank(D))]
    for closing in (0.0, 0.02, 0.06):
        name = "ours, shapes as given only (closing=0)" if closing == 0 else f"ours, closing={closing}"
        rows.append((name, mx.distance_matrix([signature(ax, closing=closing) for ax in axes], n_jobs=jobs)))
    t0 = time.perf_counter()
    rows.append(("before: paths + axis context", previous_default(term_matrices([path_signature(ax) for ax in axes], jobs))))
    t_before = time.perf_counter() - t0
    if with_shape_context:
        t0 = time.perf_counter()
        rows.append(("shape context + Hungarian, invariant", shape_context_matrix(masks, invariant=True)[0]))
        t_sc = time.perf_counter() - t0
    folds = [np.flatnonzero(labels % 5 == k) for k in range(5)]  # classes in sorted order, every 5th
    print(f"\n{'distance':48s} bull's-eye   5-fold class split (queries of each fold against all)")
    for name, M in rows:
        split = " ".join(f"{bulls_eye(M, labels, f):5.1f}" for f in folds)
        print(f"{name:48s} {bulls_eye(M, labels):8.2f}%   {split}")
    for name, value in MPEG7_LITERATURE.items():
        print(f"{name + ' (literature, all 70 classes)':48s} {value:8.2f}%")
    if collection:
        half = min(collection // 2, len(masks))
        shapes = masks[:half] + [m[:, ::-1].copy() for m in masks[:half]]
        t0 = time.perf_counter()
        big = mx.distance_matrix(shapes, n_jobs=jobs)
        elapsed = time.perf_counter() - t0
        mirror_gap = float(np.abs(big[half:, :half] - D[:half, :half]).max())
        print(f"\ndistance_matrix of {len(shapes)} shapes (the first {half} and their mirror images, from their pixels: "
              f"signatures included), jobs={jobs or 'all CPUs'}: {elapsed:.1f} s (limit 600 s); "
              f"mirror image vs original, largest difference of distances {mirror_gap:.2e}")
    print(f"\ntimes: signatures {t_sig:.1f} s ({1e3 * t_sig / len(sigs):.1f} ms per shape), pairwise {t_pairs:.1f} s "
          f"(jobs={jobs or 'all CPUs'}); previous default {t_before:.1f} s"
          + (f"; shape context {t_sc:.1f} s" if with_shape_context else ""))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--data", type=Path, default=None, help="Kimia-99 folder (class<C>_<K>.png)")
    parser.add_argument("--mpeg7", type=Path, default=None, help="folder of MPEG-7 style <class>-<k>.gif: bull's-eye only")
    parser.add_argument("--no-shape-context", action="store_true", help="with --mpeg7: skip the slow shape-context row")
    parser.add_argument("--collection", type=int, default=1400, help="shapes in the timing collection (0: skip)")
    parser.add_argument("--jobs", type=int, default=None, help="threads for distance_matrix (default: all CPUs)")
    parser.add_argument("--variants", action="store_true", help="also print the rows of the variants tried")
    args = parser.parse_args()
    if args.mpeg7 is not None:
        mpeg7(args.mpeg7, args.jobs, not args.no_shape_context, args.collection)
        return
    data = args.data or _default_data()
    files = sorted(data.glob("class*_*.png"))
    labels = np.array([int(p.stem.split("_")[0][5:]) for p in files])
    masks = [_mask(p) for p in files]
    print(f"Kimia-99 from {data}: {len(files)} shapes, {len(set(labels))} classes")

    mx.distance_matrix([masks[0], masks[1]], n_jobs=1)  # compile (cached on disk) before timing
    t0 = time.perf_counter()
    axes = [mx.medial_axis(m) for m in masks]
    sigs = [shape_signature(ax) for ax in axes]
    t_sig = (time.perf_counter() - t0) / len(sigs)
    t0 = time.perf_counter()
    D = mx.distance_matrix(sigs, n_jobs=1)
    t_pair = (time.perf_counter() - t0) / (len(sigs) * (len(sigs) - 1) / 2)
    ours = retrieval_row(D, labels)
    reranked = retrieval_row(diffusion_rerank(D), labels)
    before = retrieval_row(previous_default(term_matrices([path_signature(ax) for ax in axes], n_jobs=1)), labels)
    # The same files given by path (what `medialaxis search` does): read as grey images and
    # contoured at the threshold, without the staircase smoothing boolean masks get.
    from_files = retrieval_row(mx.distance_matrix([str(p) for p in files], n_jobs=1), labels)

    D_hu, t_hu = hu_matrix(masks)
    hu = retrieval_row(D_hu, labels)
    D_sc, t_sc = shape_context_matrix(masks)
    sc = retrieval_row(D_sc, labels)
    D_sci, t_sci = shape_context_matrix(masks, invariant=True)
    sci = retrieval_row(D_sci, labels)

    print("\nrank                                 1   2   3   4   5   6   7   8   9  10")
    print(f"ours (axis tour, the default)     {_fmt(ours)}")
    print(f"  same, PNG paths (grey route)    {_fmt(from_files)}")
    print(f"ours + diffusion re-ranking       {_fmt(reranked)}")
    print(f"before: paths + axis context      {_fmt(before)}")
    print(f"baseline Hu moments               {_fmt(hu)}")
    print(f"baseline shape context + Hungarian{_fmt(sc)}")
    print(f"  same, rotation/mirror invariant {_fmt(sci)}")
    print(f"target: shock graphs (literature) {_fmt(SHOCK_GRAPH)}")
    print(f"Bai & Latecki 2008 (literature)   {_fmt(BAI_LATECKI)}")
    print(f"ratio ours / shock graphs, sum     {ours.sum() / SHOCK_GRAPH.sum():.3f}")
    print(f"ratio ours / shape context, sum    {ours.sum() / sc.sum():.3f} (invariant one: {ours.sum() / sci.sum():.3f})")
    print(f"ratio ours / Hu moments, sum       {ours.sum() / hu.sum():.3f}")
    if args.variants:
        variants(axes, labels, args.jobs)
    print("\nperturbed shape closer to its original than to any shape of another class (every 2nd shape):")
    for name, share in robustness(masks, sigs, labels, np.random.default_rng(0)).items():
        print(f"  {name:22s} {share}")
    print("\ntimes (single thread; the machine is shared, so pessimistic)")
    print(f"  ours: signature (axis + tour) {t_sig * 1e3:.1f} ms per shape, pair {t_pair * 1e6:.1f} us")
    print(f"  shape context pair {t_sc * 1e6:.1f} us  -> ratio ours/shape context {t_pair / t_sc:.3f}")
    print(f"  invariant shape context pair {t_sci * 1e6:.1f} us (scipy Hungarian, both mirror images)")
    print(f"  Hu moments pair {t_hu * 1e6:.3f} us")

    if args.collection:
        n = args.collection
        coll = [sigs[k % len(sigs)] for k in range(n)]
        t0 = time.perf_counter()
        big = mx.distance_matrix(coll, n_jobs=args.jobs)
        elapsed = time.perf_counter() - t0
        pairs = n * (n - 1) // 2
        print(
            f"\ndistance_matrix of {n} shapes ({pairs} unordered pairs, {n * (n - 1)} ordered), "
            f"jobs={args.jobs or 'all CPUs'}: {elapsed:.1f} s pairwise "
            f"+ {n * t_sig:.1f} s of signatures (estimated from the per-shape time) "
            f"= {elapsed + n * t_sig:.1f} s (limit 600 s)"
        )
        assert np.isfinite(big).all()


if __name__ == "__main__":
    main()
