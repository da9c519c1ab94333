"""``medialaxis centerlines``: the centerline of every polygon feature of a GIS layer, or a raster mask's network."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from medialaxis._help import HelpFormatter, UsageError
from medialaxis.cli.compute import check_outputs

__all__ = ["add_centerlines", "LAYER_DRIVERS"]

#: Output layer formats of ``centerlines`` (GDAL driver per extension).
LAYER_DRIVERS = {".gpkg": "GPKG", ".geojson": "GeoJSON", ".shp": "ESRI Shapefile", ".fgb": "FlatGeobuf"}


def add_centerlines(sub: Any) -> None:
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
    check_outputs([args.input], outputs, formats=tuple(LAYER_DRIVERS))
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
