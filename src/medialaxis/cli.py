"""The ``medialaxis`` command line.

Exit codes: 0 success, 1 failure (bad or unreadable input, computation
failed, an output that cannot be written), 2 usage error (bad arguments),
130 interrupted (Ctrl-C). Errors print one line on stderr, never a
traceback (``--debug`` shows it); the libraries' warnings and log records
are silenced. Outputs are checked before any work, written atomically and
never over the input, and appear together at the end or not at all.
"""

from __future__ import annotations

import argparse
import logging
import sys
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from medialaxis._help import HelpFormatter, UsageError
from medialaxis._help import Parser as _Parser
from medialaxis._help import print_error as _fail
from medialaxis._version import __version__
from medialaxis.cli_compute import add_compute as _add_compute
from medialaxis.cli_compute import check_outputs as _check_outputs
from medialaxis.errors import Cancelled, MedialAxisError, MedialAxisWarning, UnsupportedFormatError

__all__ = ["main", "SUBCOMMANDS"]


#: Exit code of an interrupted run (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130


# ------------------------------------------------------------ compute


# -------------------------------------------------------- centerlines
#: Output layer formats of ``centerlines`` (GDAL driver per extension).
LAYER_DRIVERS = {".gpkg": "GPKG", ".geojson": "GeoJSON", ".shp": "ESRI Shapefile", ".fgb": "FlatGeobuf"}


def _add_centerlines(sub: Any) -> None:
    p = sub.add_parser(
        "centerlines",
        help="centerlines of a polygon layer, feature by feature, or the network of a raster water mask",
        description="Medial axis of every polygon feature of a GIS layer, with its attributes, index and CRS "
                    "and the columns width_min, width_mean, width_max (twice the radius). A GeoTIFF mask "
                    "(.tif .tiff .vrt: non-zero pixels of the band) gives its network in the raster's CRS: "
                    "one row per branch with its end nodes, their kind (end, junction) and widths in map units.",
        formatter_class=HelpFormatter,
    )
    p.add_argument("input", type=Path, help="polygon layer: any file geopandas reads (GeoPackage, GeoJSON, "
                                            "Shapefile, FlatGeobuf, ...), or a GeoTIFF mask")
    p.add_argument("-o", "--output", type=Path, required=True,
                   help=f"output layer ({' '.join(LAYER_DRIVERS)})")
    p.add_argument("--stations", type=Path, default=None,
                   help="also write stations: points along the lines with width and distance along their branch")
    p.add_argument("--step", type=float, default=None,
                   help="distance between stations (map units; default: one per vertex of the line)")
    p.add_argument("--lam", type=float, default=None, help="lambda: smallest contact-set diameter kept (layer units)")
    p.add_argument("--tolerance", type=float, default=None, help="accuracy (layer units)")
    p.add_argument("--detour", type=float, default=None, help="pruning detour ratio")
    p.add_argument("--band", type=int, default=1, help="band of a raster mask")
    p.add_argument("-j", "--jobs", type=int, default=None,
                   help="features computed at once (threads; default 1, or all CPUs with --scheduler)")
    p.add_argument("--scheduler", default=None,
                   help="threads, processes, synchronous, or a Dask scheduler address (tcp://host:8786)")
    p.set_defaults(run=_run_centerlines)


def _write_layer(frame: Any, path: Path) -> None:
    """Write a layer atomically: a layer can be several files (a shapefile's .shx, .dbf, .prj), all
    written in a hidden folder beside the output, then moved in place."""
    import shutil
    import tempfile

    import medialaxis as mx

    folder = Path(tempfile.mkdtemp(prefix=".medialaxis-", dir=path.parent))
    try:
        try:
            frame.to_file(folder / path.name, driver=LAYER_DRIVERS[path.suffix.lower()])
        except (OSError, ValueError, RuntimeError) as exc:
            raise mx.InputFileError(f"cannot write {str(path)!r}: {exc}") from exc
        for part in sorted(folder.iterdir()):
            part.replace(path.parent / part.name)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _run_centerlines(args: argparse.Namespace) -> int:
    import medialaxis as mx
    from medialaxis.core.io import check_writable
    from medialaxis.gis import stations
    from medialaxis.gis.parallel import LOCAL_SCHEDULERS
    from medialaxis.gis.rasters import is_raster

    outputs = [args.output] + ([args.stations] if args.stations else [])
    _check_outputs([args.input], outputs, formats=tuple(LAYER_DRIVERS))
    if args.jobs is not None and args.jobs < 1:
        raise UsageError(f"--jobs must be a positive integer, got {args.jobs}")
    if args.scheduler is not None and args.scheduler not in LOCAL_SCHEDULERS and "://" not in args.scheduler:
        raise UsageError(f"--scheduler takes {', '.join(LOCAL_SCHEDULERS)} or an address like tcp://host:8786, "
                         f"got {args.scheduler!r}")
    if args.step is not None and not args.step > 0:
        raise UsageError(f"--step must be a positive distance, got {args.step}")
    options = {k: getattr(args, k) for k in ("lam", "tolerance", "detour") if getattr(args, k) is not None}
    run = {"n_jobs": args.jobs, "scheduler": args.scheduler, "band": args.band}
    out = mx.centerlines(str(args.input), **run, **options)
    points = stations(str(args.input), step=args.step, **run, **options) if args.stations else None
    for path in outputs:
        check_writable(path)
    _write_layer(out, args.output)
    if points is not None:
        _write_layer(points, args.stations)
    if is_raster(args.input):
        kinds = list({**dict(zip(out["start_node"], out["start_kind"])), **dict(zip(out["end_node"], out["end_kind"]))
                      }.values())
        print(f"{args.input}: {len(out)} branches, {kinds.count('end')} ends, {kinds.count('junction')} junctions")
    else:
        print(f"{args.input}: {len(out)} features, {int(out.geometry.notna().sum())} centerlines")
    for path in outputs:
        print(f"wrote {path}")
    return 0


# --------------------------------------------------------------- demo
def _add_demo(sub: Any) -> None:
    p = sub.add_parser(
        "demo",
        help="run on the bundled sample shapes",
        description="Compute the medial axis of every bundled sample shape and write results and plots to a folder.",
        formatter_class=HelpFormatter,
    )
    p.add_argument("outdir", type=Path, nargs="?", default=Path("medialaxis-demo"), help="output folder")
    p.set_defaults(run=_run_demo)


def _run_demo(args: argparse.Namespace) -> int:
    from medialaxis.demo import run_demo

    for line in run_demo(args.outdir):
        print(line)
    return 0


# ------------------------------------------------------------- warmup
def _add_warmup(sub: Any) -> None:
    p = sub.add_parser(
        "warmup",
        help="compile the kernels once (the first call after an install is then fast)",
        description="Run every method on a small shape so that its compiled kernels are cached on disk; "
                    "scripts/setup.sh runs it after installing.",
        formatter_class=HelpFormatter,
    )
    p.add_argument("--domains", default="planar,mesh,volume", help="comma-separated: planar, mesh, volume")
    p.set_defaults(run=_run_warmup)


def _run_warmup(args: argparse.Namespace) -> int:
    from medialaxis.warmup import DOMAINS, warm_up

    domains = tuple(d.strip() for d in args.domains.split(",") if d.strip())
    unknown = [d for d in domains if d not in DOMAINS]
    if unknown or not domains:
        raise UsageError(f"--domains takes {', '.join(DOMAINS)}; got {args.domains!r}")
    for name, seconds in warm_up(domains):
        print(f"{name}: compiled in {seconds:.1f} s")
    return 0


#: Subcommand builders; each adds a parser whose ``run`` default handles it.
SUBCOMMANDS: list[Callable[[Any], None]] = [_add_compute, _add_centerlines, _add_demo, _add_warmup]

from medialaxis.compare.cli import add_compare, add_search  # noqa: E402

SUBCOMMANDS += [add_compare, add_search]


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="medialaxis",
        description="Medial axis transforms of images, polygons, meshes and volumes.",
    )
    parser.add_argument("--version", action="version", version=f"medialaxis {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for add in SUBCOMMANDS:
        add(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``medialaxis`` console script; returns the exit code.

    0 success; 1 failure (bad or unreadable input, the computation failed,
    an output could not be written); 2 usage error; 130 interrupted
    (Ctrl-C). An error is one line on stderr, never a traceback unless
    ``--debug`` is given.
    """
    debug = "--debug" in (sys.argv[1:] if argv is None else argv)
    if debug:
        return _main(argv, debug)
    # The libraries' warnings and log records about a bad file are not ours to
    # print: the error line says what went wrong (--debug shows them). Our
    # own warnings (something left out of a result) are one line each.
    # They are held until the run ends: after a result they are printed as one line, after an
    # error not at all (the error is the one line).
    previous = logging.root.manager.disable
    logging.disable(logging.CRITICAL)
    held: list[str] = []
    code = 1
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            warnings.simplefilter("default", MedialAxisWarning)
            warnings.showwarning = lambda message, *args, **kwargs: held.append(str(message))
            code = _main(argv, debug)
            return code
    finally:
        logging.disable(previous)
        if code == 0 and held:
            _warning_line("; ".join(dict.fromkeys(held)))


def _was_interrupted() -> bool:
    """Whether the console script's Ctrl-C handler has fired (not imported here:
    the library's callers keep Python's handler)."""
    return bool(getattr(sys.modules.get("medialaxis._entry"), "interrupted", False))


def _warning_line(message: Warning | str, *args: Any, **kwargs: Any) -> None:
    print(f"medialaxis: warning: {message}", file=sys.stderr)


def _main(argv: Sequence[str] | None, debug: bool) -> int:
    try:
        parser = build_parser()
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # --help and --version
            return int(exc.code or 0)
        if not getattr(args, "run", None):
            commands = ", ".join(sorted(parser._subparsers._group_actions[0].choices))  # type: ignore[union-attr]
            raise UsageError(f"a command is required: {commands} (see medialaxis --help)")
        return int(args.run(args))
    except (UsageError, UnsupportedFormatError) as exc:
        if debug:
            raise
        _fail(str(exc))
        return 2
    except (Cancelled, KeyboardInterrupt):
        if debug:
            raise
        print("medialaxis: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except MedialAxisError as exc:
        if debug:
            raise
        if _was_interrupted():  # a Ctrl-C turned into this error (an import it broke)
            print("medialaxis: interrupted", file=sys.stderr)
            return EXIT_INTERRUPTED
        _fail(str(exc))
        return 1
    except MemoryError:
        if debug:
            raise
        _fail("out of memory")
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
