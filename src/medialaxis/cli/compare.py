"""``medialaxis compare A B`` and ``medialaxis search QUERY FOLDER``: shape distances through medial axes.

Registered in :func:`medialaxis.cli.build_parser`; errors are raised as
:class:`~medialaxis.errors.MedialAxisError` or ``UsageError`` and turned into
exit codes by :func:`medialaxis.cli.main`.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._help import HelpFormatter, UsageError
from medialaxis.core.formats import suffix_of, suffixes

__all__ = ["add_compare", "add_search", "PLANAR_SUFFIXES", "save_match_picture", "save_search_grid"]

#: File types ``search`` ranks inside a folder: planar shapes and saved results (not ``.npy``
#: arrays, which may as well be volumes).
PLANAR_SUFFIXES = tuple(s for s in suffixes("planar", "result") if s != ".npy")


def _add_matching_options(p: argparse.ArgumentParser) -> None:
    from medialaxis.compare.distance import DEFAULTS
    from medialaxis.compare.signature import DEFAULT_PRUNE

    p.add_argument("--gap", type=float, default=DEFAULTS["gap"], help="cost of a tour sample left unaligned")
    p.add_argument("--prune", type=float, default=DEFAULT_PRUNE, help="drop terminal branches protruding less than this fraction of the shape scale")


def _matching(args: argparse.Namespace) -> dict[str, Any]:
    return {"gap": args.gap, "prune": args.prune}


# ------------------------------------------------------------ compare
def add_compare(sub: Any) -> None:
    """Add the ``compare`` subcommand."""
    p = sub.add_parser(
        "compare",
        help="distance between two shapes through their medial axes",
        description="Print the medial-axis distance between two planar shapes (0: same shape) "
        "and optionally draw the matched parts of their axes side by side.",
        formatter_class=HelpFormatter,
    )
    p.add_argument("first", type=Path, help="image, SVG, GeoJSON or WKT file, or a saved axis (.json/.npz)")
    p.add_argument("second", type=Path, help="the other shape")
    p.add_argument("-o", "--output", type=Path, default=None, help="picture of the matched axis parts (.png, .svg or .pdf)")
    _add_matching_options(p)
    p.set_defaults(run=_run_compare)


def _axis(path: Path) -> Any:
    import medialaxis as mx

    return mx.medial_axis(str(path))  # a saved result (.json/.npz) comes back as loaded


def _check_picture(output: Path | None, inputs: list[Path]) -> None:
    """Refuse a picture path that is not .png/.svg/.pdf, is one of the inputs, or cannot be written; before any work."""
    if output is None:
        return
    if output.suffix.lower() not in (".png", ".svg", ".pdf"):
        raise UsageError(f"--output needs a .png, .svg or .pdf file, got {str(output)!r}")
    if output.exists() and any(output.resolve() == p.resolve() for p in inputs):
        raise UsageError(f"refusing to overwrite the input file {str(output)!r}")
    from medialaxis.core.io import check_writable

    check_writable(output)


def _save_figure(fig: Any, path: Path) -> None:
    """Write a matplotlib figure atomically in the format of ``path``'s suffix and close it."""
    import matplotlib.pyplot as plt

    from medialaxis.core.io import atomic_write

    with atomic_write(path, "wb") as fh:
        fig.savefig(fh, format=path.suffix.lower().lstrip("."), dpi=100, bbox_inches="tight")
    plt.close(fig)


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _run_compare(args: argparse.Namespace) -> int:
    from medialaxis.compare.distance import match_tour, shape_distance

    _check_picture(args.output, [args.first, args.second])
    a, b = _axis(args.first), _axis(args.second)
    options = _matching(args)
    distance = shape_distance(a, b, **options)
    print(f"{distance:.6g}")
    if args.output is not None:
        _, points_a, points_b = match_tour(a, b, **options)
        save_match_picture(a, b, points_a, points_b, args.output, prune=args.prune,
                           titles=(args.first.name, args.second.name), distance=distance)
        print(f"wrote {args.output}", file=sys.stderr)
    return 0


def save_match_picture(
    a: Any,
    b: Any,
    points_a: np.ndarray,
    points_b: np.ndarray,
    path: Path,
    *,
    prune: float,
    titles: tuple[str, str],
    distance: float,
) -> None:
    """Draw two axes side by side; aligned tour samples (``points_a[i]``, ``points_b[i]``) share a colour.

    The colour runs along the walk around the first axis, so matched parts
    of the two shapes show in the same hues.
    """
    from medialaxis.compare.distance import shape_signature
    from medialaxis.core.export.plot import draw_region

    fig, axes = _pyplot().subplots(1, 2, figsize=(10, 5))
    hue = np.linspace(0.0, 1.0, max(len(points_a), 1))
    for ma, ax, title, matched in zip((a, b), axes, titles, (points_a, points_b)):
        sig = shape_signature(ma, prune=prune)
        raster = ma.frame == "image"

        def xy(p: np.ndarray, raster: bool = raster) -> np.ndarray:
            return p[:, ::-1] if raster else p

        if ma.shape is not None:
            draw_region(ax, ma, ma.shape)
        for i, j in sig.edges:
            seg = xy(sig.points[[i, j]])
            ax.plot(seg[:, 0], seg[:, 1], color="#555", lw=1.2)
        if len(matched):
            pts = xy(np.asarray(matched, np.float64).reshape(-1, 2))
            ax.scatter(pts[:, 0], pts[:, 1], s=28, c=hue[: len(pts)], cmap="turbo", zorder=4, edgecolors="none")
        ax.set_aspect("equal")
        if raster:
            ax.invert_yaxis()
        ax.set_title(title)
        ax.set_axis_off()
    fig.suptitle(f"distance {distance:.4g}; aligned samples of the walks around the axes share a colour")
    _save_figure(fig, path)


def save_search_grid(query: Path, results: list[tuple[Path, float]], path: Path, *, columns: int = 4) -> None:
    """Draw the query and its best matches as a grid: each shape with its medial axis, rank and distance."""
    import medialaxis as mx
    from medialaxis.core.export.plot import draw_axis, draw_region

    panels = [(query, "query", "#2c6fbb")] + [
        (p, f"{rank}. distance {d:.3g}", "#445") for rank, (p, d) in enumerate(results, 1)
    ]
    cols = max(1, min(columns, len(panels)))
    rows = -(-len(panels) // cols)
    fig, axes = _pyplot().subplots(rows, cols, figsize=(2.6 * cols, 2.9 * rows), squeeze=False)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    for ax, (shape_path, title, colour) in zip(axes.ravel(), panels):
        ma = mx.medial_axis(str(shape_path))
        if ma.shape is not None:
            draw_region(ax, ma, ma.shape)
        draw_axis(ax, ma, color_by_radius=False, lw=1.0)
        ax.autoscale_view()
        ax.set_aspect("equal")
        if ma.frame == "image":
            ax.invert_yaxis()
        ax.set_title(f"{title}\n{shape_path.name}", fontsize=9, color=colour)
        ax.set_xticks([])
        ax.set_yticks([])
        for spine in ax.spines.values():
            spine.set_color(colour)
    fig.suptitle(f"{query.name}: the {len(results)} nearest by medial-axis distance", fontsize=11)
    _save_figure(fig, path)


# ------------------------------------------------------------- search
def add_search(sub: Any) -> None:
    """Add the ``search`` subcommand."""
    p = sub.add_parser(
        "search",
        help="rank the shapes of a folder by distance to a query",
        description="Rank the planar shape files of a folder by their medial-axis distance to a query shape.",
        formatter_class=HelpFormatter,
    )
    p.add_argument("query", type=Path, help="query shape file")
    p.add_argument("folder", type=Path, help="folder of shape files (" + " ".join(PLANAR_SUFFIXES) + ")")
    p.add_argument("--top", type=int, default=10, help="number of results printed")
    p.add_argument("--jobs", type=int, default=None, help="worker threads (default: all CPUs)")
    p.add_argument("--scheduler", default=None, help="Dask scheduler address (tcp://host:port) to run the pairs on a cluster")
    p.add_argument("-o", "--output", type=Path, default=None,
                   help="picture of the query and the top matches as a grid with distances (.png, .svg or .pdf)")
    p.add_argument("--columns", type=int, default=4, help="panels per row of the --output grid")
    _add_matching_options(p)
    p.set_defaults(run=_run_search)


def _run_search(args: argparse.Namespace) -> int:
    from medialaxis.compare.distance import shape_signature
    from medialaxis.compare.matrix import query_distances
    from medialaxis.errors import InputFileError, MedialAxisError

    if args.top < 1:
        raise UsageError(f"--top must be >= 1, got {args.top}")
    if args.jobs is not None and args.jobs < 1:
        raise UsageError(f"--jobs must be >= 1, got {args.jobs}")
    if args.columns < 1:
        raise UsageError(f"--columns must be >= 1, got {args.columns}")
    if not args.folder.is_dir():
        raise InputFileError(f"not a folder: {str(args.folder)!r}")
    files = sorted(p for p in args.folder.iterdir() if p.is_file() and suffix_of(p) in PLANAR_SUFFIXES)
    if not files:
        raise InputFileError(f"no shape files ({', '.join(PLANAR_SUFFIXES)}) in {str(args.folder)!r}")
    _check_picture(args.output, [args.query, *files])
    options = _matching(args)
    query = shape_signature(str(args.query), prune=args.prune)
    sigs, kept = [], []
    for path in files:
        try:
            sigs.append(shape_signature(str(path), prune=args.prune))
            kept.append(path)
        except MedialAxisError as exc:
            print(f"medialaxis: skipped {path}: {exc}", file=sys.stderr)
    if not sigs:
        raise InputFileError(f"no readable shape in {str(args.folder)!r}")
    distances = query_distances(query, sigs, n_jobs=args.jobs, scheduler=args.scheduler, **options)
    order = np.lexsort((np.arange(len(kept)), distances))[: args.top]
    for rank, k in enumerate(order, 1):
        print(f"{rank}\t{distances[k]:.6g}\t{kept[k]}")
    skipped = len(files) - len(kept)
    if skipped:
        print(f"medialaxis: {skipped} file(s) skipped", file=sys.stderr)
    if args.output is not None:
        save_search_grid(args.query, [(kept[k], float(distances[k])) for k in order], args.output, columns=args.columns)
        print(f"wrote {args.output}", file=sys.stderr)
    return 0
