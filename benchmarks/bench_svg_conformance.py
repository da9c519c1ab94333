"""SVG outlines against an independent renderer: librsvg's W3C SVG 1.1 reference tests.

For every SVG of ``rsvg/tests/fixtures/reftests/svg1.1/`` in a snapshot of
GNOME/librsvg (W3C test suite files under the W3C licence; librsvg LGPL-2.1+),
this script reads the outline with :func:`medialaxis.planar.drawings.svg.read_svg`,
rasterizes it at pixel centres on the reference's grid, and compares it with
the pixels librsvg paints (alpha > 0):

- the reference is ``rsvg-convert`` (Debian's librsvg2-bin) of the file with
  its ``<text>`` and ``<image>`` elements removed, since medialaxis skips
  those with a warning; the shipped ``*-ref.png`` is compared with
  ``rsvg-convert`` of the unmodified file to show the renderer agrees with it;
- pixels within 2 px of the reference's edges are uncertain (anti-aliasing)
  and not counted; a file is **right** when the pixels that disagree outside
  that band are <= 0.5% of the painted ones;
- a file that raises one of medialaxis's errors is a **clear error** (its
  message is printed); any other exception is a crash.

Run (about a minute)::

    apt-get install librsvg2-bin          # rsvg-convert
    .venv/bin/python benchmarks/bench_svg_conformance.py [--git DIR] [--baseline REV] [--only PREFIX ...]

``--git`` is the librsvg git directory (default ``$MEDIALAXIS_LIBRSVG_GIT`` or
``/work/.mirror/GNOME+librsvg/repo``, as the search tool's ``fetch`` brings
it); ``--baseline REV`` also scores the SVG reader of medialaxis at git
revision ``REV`` (``src/medialaxis/planar/reading/vectors.py:_read_svg``, before
svgelements) in the same run.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
import types
import warnings
import xml.etree.ElementTree as ET
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np
import shapely
from scipy import ndimage
from skimage import io

from medialaxis.errors import MedialAxisError
from medialaxis.planar.drawings.svg import read_svg

FIXTURES = "rsvg/tests/fixtures/reftests/svg1.1"
#: The categories issue 32 names (those of them librsvg ships).
NAMED = ("paths-data", "coords-trans", "shapes", "painting-fill")
W3C_NAME = re.compile(r"[a-z]+(-[a-z]+)+-\d\d-[a-z]\.svg")
BAND = 2
BAD_FRACTION = 0.005


def extract(git_dir: Path, out: Path) -> Path:
    """The fixtures folder of the snapshot's HEAD, written under ``out``."""
    target = out / FIXTURES
    if target.is_dir():
        return target
    archive = subprocess.run(
        ["git", f"--git-dir={git_dir}", "archive", "HEAD", FIXTURES], check=True, capture_output=True
    ).stdout
    subprocess.run(["tar", "-x", "-C", str(out)], input=archive, check=True)
    return target


def without_text(svg: Path, out: Path) -> Path:
    tree = ET.parse(svg)
    for parent in tree.getroot().iter():
        for child in list(parent):
            if child.tag.rsplit("}", 1)[-1] in ("text", "image"):
                parent.remove(child)
    tree.write(out, encoding="utf-8", xml_declaration=True)
    return out


def render(svg: Path, png: Path) -> np.ndarray:
    subprocess.run(["rsvg-convert", "-f", "png", "-o", str(png), str(svg)], check=True, capture_output=True)
    return painted(io.imread(png))


def painted(image: np.ndarray) -> np.ndarray:
    if image.ndim == 3 and image.shape[2] == 4:
        return image[..., 3] > 0  # any paint: translucent fills and strokes are painted too
    grey = image if image.ndim == 2 else image[..., :3].mean(axis=2)
    return grey < 250  # an opaque reference on white paper


def raster(region, viewport, shape: tuple[int, int]) -> np.ndarray:
    a, b, c, d, e, f = viewport
    px = shapely.affinity.affine_transform(region, [a, c, b, d, e, f])
    rows, cols = np.mgrid[: shape[0], : shape[1]]
    shapely.prepare(px)
    return shapely.contains_xy(px, cols.ravel() + 0.5, rows.ravel() + 0.5).reshape(shape)


def score(ours: np.ndarray, ref: np.ndarray) -> float:
    """Share of the reference's painted pixels that disagree outside the 2-px band along its edges."""
    band = ndimage.binary_dilation(ref, iterations=BAND) & ~ndimage.binary_erosion(ref, iterations=BAND)
    wrong = (ours != ref) & ~band
    return float(wrong.sum()) / max(int(ref.sum()), 1)


def old_reader(rev: str):
    source = subprocess.run(
        ["git", "show", f"{rev}:src/medialaxis/planar/reading/vectors.py"], check=True, capture_output=True, text=True
    ).stdout
    module = types.ModuleType("medialaxis_old_vectors")
    exec(compile(source, "old_vectors.py", "exec"), module.__dict__)  # noqa: S102 - our own source at REV
    return module._read_svg


def category(name: str) -> str:
    parts = name.split("-")
    return "-".join(parts[:2]) if len(parts) > 2 else parts[0]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    default_git = os.environ.get("MEDIALAXIS_LIBRSVG_GIT", "/work/.mirror/GNOME+librsvg/repo")
    p.add_argument("--git", type=Path, default=Path(default_git))
    p.add_argument("--baseline", default=None, help="git revision of medialaxis whose old SVG reader is also scored")
    p.add_argument("--only", nargs="*", default=None, help="file name prefixes to keep")
    p.add_argument("--verbose", action="store_true")
    p.add_argument("--dump", type=Path, default=None, help="folder for pictures of the files not right (ours, reference)")
    args = p.parse_args(argv)
    baseline = old_reader(args.baseline) if args.baseline else None
    with tempfile.TemporaryDirectory() as tmp:
        folder = extract(args.git, Path(tmp))
        # the W3C suite's files (name-NN-x.svg), not librsvg's own additions to the folder
        files = sorted(
            f for f in folder.glob("*.svg")
            if W3C_NAME.fullmatch(f.name) and (folder / (f.stem + "-ref.png")).exists()
        )
        if args.only:
            files = [f for f in files if f.name.startswith(tuple(args.only))]
        rows = []
        agree_ref = []
        t0 = time.perf_counter()
        for svg in files:
            ref_png = folder / (svg.stem + "-ref.png")
            shipped = painted(io.imread(ref_png))
            try:
                full = render(svg, Path(tmp) / "full.png")
                stripped = without_text(svg, svg.with_name(svg.stem + "-notext.svg"))
                ref = render(stripped, Path(tmp) / "notext.png")
            except subprocess.CalledProcessError as exc:
                rows.append((svg.name, "skip", f"rsvg-convert failed: {exc.stderr[:80]!r}", None, None))
                continue
            if full.shape == shipped.shape:
                # fonts differ between machines: the text's pixels (and 3 px around them) are not compared
                text = ndimage.binary_dilation(full != ref, iterations=3) if full.shape == ref.shape else False
                agree_ref.append(score(full & ~text, shipped & ~text))
            outcome, detail, fraction = _ours(svg, ref, args.dump)
            old = _old(baseline, svg, ref) if baseline else None
            rows.append((svg.name, outcome, detail, fraction, old))
        seconds = time.perf_counter() - t0
    if args.dump:
        args.dump.mkdir(parents=True, exist_ok=True)
    _report(rows, agree_ref, seconds, args.verbose, baseline is not None)
    crashes = sum(1 for r in rows if r[1] == "crash")
    return 1 if crashes else 0


def _ours(svg: Path, ref: np.ndarray, dump: Path | None = None) -> tuple[str, str, float | None]:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            region, info = read_svg(svg)
    except MedialAxisError as exc:
        return "error", f"{type(exc).__name__}: {_without_path(str(exc), svg)}", None
    except Exception as exc:  # noqa: BLE001 - a crash is what this benchmark counts
        return "crash", f"{type(exc).__name__}: {_without_path(str(exc), svg)}", None
    ours = raster(region, info["viewport"], ref.shape)
    fraction = score(ours, ref)
    if dump is not None and fraction > BAD_FRACTION:
        dump.mkdir(parents=True, exist_ok=True)
        picture = np.stack([ref, ours, np.zeros_like(ref)], axis=-1).astype(np.uint8) * 255
        io.imsave(dump / (svg.stem + ".png"), picture, check_contrast=False)
    skipped = ", ".join(f"{v} {k}" for k, v in info["skipped"].items())
    return ("right" if fraction <= BAD_FRACTION else "wrong"), skipped, fraction


def _without_path(message: str, svg: Path) -> str:
    return message.replace(f"SVG {str(svg)!r} ", "").replace(repr(str(svg)), "<file>")


def _old(reader, svg: Path, ref: np.ndarray) -> str:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            region = reader(svg)
    except MedialAxisError:
        return "error"
    except Exception:  # noqa: BLE001
        return "crash"
    if region.is_empty:
        return "error"
    # The old reader ignored viewBox and transforms: its coordinates are taken as pixels.
    fraction = score(raster(region, (1, 0, 0, 1, 0, 0), ref.shape), ref)
    return "right" if fraction <= BAD_FRACTION else "wrong"


def _report(rows, agree_ref, seconds, verbose, with_old) -> None:
    by_cat: dict[str, Counter] = defaultdict(Counter)
    old_cat: dict[str, Counter] = defaultdict(Counter)
    for name, outcome, detail, fraction, old in rows:
        by_cat[category(name)][outcome] += 1
        if old:
            old_cat[category(name)][old] += 1
        if verbose or outcome in ("wrong", "crash", "error"):
            shown = f"{100 * fraction:6.2f}%" if fraction is not None else "      "
            print(f"{name:32s} {outcome:6s} {shown}  {detail[:110]}")
    print()
    header = f"{'category':22s} {'files':>5s} {'right':>5s} {'error':>5s} {'wrong':>5s} {'crash':>5s}"
    print(header + ("   old: right wrong error" if with_old else ""))
    totals: Counter = Counter()
    named: Counter = Counter()
    old_totals: Counter = Counter()
    for cat in sorted(by_cat):
        c = by_cat[cat]
        n = sum(c.values())
        totals.update(c)
        old_totals.update(old_cat[cat])
        if cat.startswith(NAMED):
            named.update(c)
        line = f"{cat:22s} {n:5d} {c['right']:5d} {c['error']:5d} {c['wrong']:5d} {c['crash']:5d}"
        if with_old:
            o = old_cat[cat]
            line += f"        {o['right']:5d} {o['wrong']:5d} {o['error'] + o['crash']:5d}"
        print(line)
    for label, c in (("named categories", named), ("all files", totals)):
        n = sum(c.values()) - c["skip"]
        print(
            f"{label}: {c['right']}/{n} right ({100 * c['right'] / max(n, 1):.1f}%), {c['error']} clear errors, "
            f"{c['wrong']} wrong, {c['crash']} crashes"
        )
    if with_old:
        n = sum(old_totals.values())
        print(f"old reader, all files: {old_totals['right']}/{n} right, {old_totals['wrong']} wrong")
    if agree_ref:
        a = np.array(agree_ref)
        print(
            f"rsvg-convert here vs the shipped reference PNGs: {int((a <= BAD_FRACTION).sum())}/{len(a)} agree "
            f"(median {100 * np.median(a):.3f}% of painted pixels outside the band)"
        )
    print(f"{len(rows)} files in {seconds:.1f} s")


if __name__ == "__main__":
    sys.exit(main())
