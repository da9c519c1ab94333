"""Small shapes: milliseconds per 256 x 256 silhouette and seconds per label image, beside scikit-image.

Run:  .venv/bin/python benchmarks/bench_small_shapes.py [--quick] [--data DIR] [--clock wall|cpu]

Prints our figure, scikit-image's figures from the same run and the ratios
(issue 36, "small shapes fast"):

1. ms per 256 x 256 bool mask of ``mx.medial_axis(mask)`` (the default call),
   :func:`skimage.morphology.medial_axis` and :func:`skimage.morphology.skeletonize`,
   timed mask by mask in turn (so drift on a busy machine hits all three alike):

   - MPEG-7 silhouettes (the GIFs of ``--data``, default
     ``/work/shared/data/mpeg7_dev``; every one, or every 7th with ``--quick``),
     each fitted into 240 pixels and centred on a 256 x 256 mask, as the
     SkelNetOn silhouettes are. This is the set the speed work was tuned on.
   - Kimia-99 (``tests/data/kimia99``, 128 x 128) upscaled to 256 x 256: a check
     set nothing was tuned on.

2. seconds for a 2048 x 2048 label image of about 1,000 objects (random
   ellipses, 8 to 28 pixels semi-axes, some touching, labelled by
   :func:`skimage.measure.label`): ``mx.medial_axis(labels)`` gives one axis per
   label; the peers skeletonise the foreground mask once (they do not separate
   touching objects).

Every run warms up first (imports, numba's cache) and is timed with
``time.perf_counter`` (``--clock cpu``: ``time.process_time``, the CPU time of
this single-threaded process, which the other jobs of a shared machine move
less); the label image is the best of two runs (one with ``--quick``).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from PIL import Image
from skimage import draw, measure
from skimage.morphology import medial_axis as sk_medial_axis
from skimage.morphology import skeletonize
from skimage.transform import resize

import medialaxis as mx

ROOT = Path(__file__).resolve().parents[1]
MPEG7 = Path("/work/shared/data/mpeg7_dev")
KIMIA = ROOT / "tests" / "data" / "kimia99"
SIZE = 256


def fitted(mask: np.ndarray, size: int = SIZE, margin: int = 8) -> np.ndarray:
    """``mask`` scaled to fit ``size - 2 * margin`` pixels and centred on a ``size`` x ``size`` mask."""
    h, w = mask.shape
    scale = (size - 2 * margin) / max(h, w)
    small = resize(mask.astype(float), (max(1, int(h * scale)), max(1, int(w * scale))), order=1) > 0.5
    out = np.zeros((size, size), bool)
    r0, c0 = (size - small.shape[0]) // 2, (size - small.shape[1]) // 2
    out[r0 : r0 + small.shape[0], c0 : c0 + small.shape[1]] = small
    return out


def mpeg7_masks(folder: Path, step: int) -> list[np.ndarray]:
    files = sorted(folder.glob("*.gif"))[::step]
    return [fitted(np.asarray(Image.open(f).convert("L")) > 127) for f in files]


def kimia_masks() -> list[np.ndarray]:
    return [fitted(np.asarray(Image.open(f)).astype(bool), margin=0) for f in sorted(KIMIA.glob("*.png"))]


def label_image(n_objects: int = 1000, size: int = 2048, seed: int = 0) -> np.ndarray:
    """Random non-overlapping ellipses (they may touch), labelled by :func:`skimage.measure.label`."""
    rng = np.random.default_rng(seed)
    img = np.zeros((size, size), bool)
    placed = 0
    while placed < n_objects:
        r, c = rng.integers(40, size - 40, 2)
        a, b = rng.uniform(8, 28, 2)
        rr, cc = draw.ellipse(r, c, a, b, shape=img.shape, rotation=rng.uniform(0, np.pi))
        if img[rr, cc].any():
            continue
        img[rr, cc] = True
        placed += 1
    return measure.label(img)


PEERS = {
    "ours (mx.medial_axis)": lambda m: mx.medial_axis(m),
    "skimage medial_axis": lambda m: sk_medial_axis(m),
    "skimage skeletonize": lambda m: skeletonize(m),
}


CLOCK = {"wall": time.perf_counter, "cpu": time.process_time}


def per_mask_ms(masks: list[np.ndarray], clock=time.perf_counter) -> dict[str, float]:
    """Mean ms per mask of each method, the three timed one after the other on every mask."""
    total = dict.fromkeys(PEERS, 0.0)
    for m in masks:
        for name, fn in PEERS.items():
            t0 = clock()
            fn(m)
            total[name] += clock() - t0
    return {name: 1000.0 * t / len(masks) for name, t in total.items()}


def report(title: str, figures: dict[str, float], unit: str) -> None:
    if title:
        print(title)
    ours = figures["ours (mx.medial_axis)"]
    for name, value in figures.items():
        ratio = "" if value is ours else f"   ours is {value / ours:5.2f}x faster" if value >= ours \
            else f"   ours is {ours / value:5.2f}x slower"
        print(f"  {name:<24} {value:8.2f} {unit}{ratio}")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="every 7th MPEG-7 shape, one label-image run")
    parser.add_argument("--data", type=Path, default=MPEG7, help="folder of MPEG-7 GIFs (default %(default)s)")
    parser.add_argument("--clock", choices=tuple(CLOCK), default="wall", help="wall or CPU time (default %(default)s)")
    args = parser.parse_args(argv)
    clock = CLOCK[args.clock]
    print(f"medialaxis {mx.__version__}; numpy {np.__version__}; {args.clock} clock")
    mpeg = mpeg7_masks(args.data, 7 if args.quick else 1)
    kimia = kimia_masks()
    for fn in PEERS.values():  # warm up: imports, numba's cache
        fn(mpeg[0])
    report(f"\n1. {len(mpeg)} MPEG-7 silhouettes in 256 x 256 masks (tuning set), ms per mask", per_mask_ms(mpeg, clock), "ms")
    report(f"   {len(kimia)} Kimia-99 shapes upscaled to 256 x 256 (check set), ms per mask", per_mask_ms(kimia, clock), "ms")

    labels = label_image()
    foreground = labels > 0
    print(f"\n2. 2048 x 2048 label image of {labels.max()} objects (ellipses), s")
    figures = {}
    for name, fn in PEERS.items():
        image = labels if name.startswith("ours") else foreground
        best = np.inf
        for _ in range(1 if args.quick else 2):
            t0 = clock()
            out = fn(image)
            best = min(best, clock() - t0)
        figures[name] = best
        if name.startswith("ours"):
            print(f"  our axes: {len(out.metadata['labels'])} labels, {len(out.points)} points")
    report("", figures, "s ")


if __name__ == "__main__":
    main()
