"""Centerlines of real lakes: medialaxis beside pygeoops.centerline and centerline, one run.

Data: the lakes of OpenStreetMap generalized to 1 km (``@geo-maps/earth-lakes-1km``
0.6.0 from the npm registry, pinned by SHA-256; data (c) OpenStreetMap contributors,
ODbL 1.0; downloaded into ``$MEDIALAXIS_GIS`` or ``~/.cache/medialaxis-gis``, not
redistributed). Of its 131,725 polygons, those with at least ``--min-vertices``
boundary vertices are real shapes (most others are 1 km triangles); ``--count``
of them are taken evenly over the list, projected to World Mercator (conformal:
shapes are kept locally).

Every tool runs with its defaults, per feature. Measured the same way for all
three on their output, with shapely only:

- CPU seconds for the whole layer;
- terminal branches per feature, and spurious ones. A terminal branch runs from
  an end (degree 1) to a junction; with d( ) the distance to the shore, its
  reach is how far the disc at its end gets beyond the disc at its junction,
  ``length + d(end) - d(junction)``. It is spurious when the reach is under half
  of ``d(junction)``: it explains a bump of the shore shallower than half the
  local half-width (noise of the shore line), not an arm or a bay;
- inside: no part of the line is farther outside its polygon than 1e-6 of the
  polygon's size (square root of its area; float rounding along a shore), the
  parts outside densified to a thousandth of that size (an edge cutting across a
  bend of the shore has only its crossings, on the shore, as vertices);
- coverage: the share of the lake inside the union of the discs centred on the
  line that reach the shore (median over lakes): an arm the line leaves out
  is missing from it, so pruning cannot look good by cutting real arms;
- failures: an error or an empty line.

``medialaxis`` is timed by its default call on the layer,
``mx.centerlines(lakes)`` (one process; ``--call feature`` times one call
per feature on a one-row GeoSeries instead, which adds geopandas' per-call
cost); the peers are called feature by feature, their only way. The tools
take turns on chunks of ``--chunk`` lakes and their seconds are the CPU time
of this process, so the load of a shared machine moves all of them alike. Speed work
was tuned on ``--half tune`` (the even positions of the picked lakes) and is
checked on ``--half check`` (the odd ones).

Usage::

    python benchmarks/bench_centerlines.py [--count 3000] [--min-vertices 12] [--half all|tune|check]
                                           [--call layer|feature] [--chunk 50]

pygeoops (BSD-3) and centerline (MIT) come with the ``bench`` extra.
"""

from __future__ import annotations

import argparse
import hashlib
import io
import os
import sys
import tarfile
import time
import urllib.request
import warnings
from pathlib import Path

import numpy as np
import shapely

TARBALL = "https://registry.npmjs.org/@geo-maps/earth-lakes-1km/-/earth-lakes-1km-0.6.0.tgz"
SHA256 = "d9c87f27023aee3fcc7050ef08f0cc2ef3ee8d677397b76ef94f4485b96ccf4c"


def cache_dir() -> Path:
    return Path(os.environ.get("MEDIALAXIS_GIS") or Path.home() / ".cache" / "medialaxis-gis")


def lakes_file() -> Path:
    """The lakes GeoJSON, downloaded and checked on first use."""
    target = cache_dir() / "earth-lakes-1km.geo.json"
    if target.exists():
        return target
    target.parent.mkdir(parents=True, exist_ok=True)
    with urllib.request.urlopen(TARBALL, timeout=120) as response:
        data = response.read()
    if hashlib.sha256(data).hexdigest() != SHA256:
        sys.exit(f"{TARBALL} does not match its SHA-256")
    with tarfile.open(fileobj=io.BytesIO(data)) as tar:
        member = tar.extractfile("package/map.geo.json")
        part = target.with_suffix(".part")
        part.write_bytes(member.read())
        part.replace(target)
    return target


def lake_polygons(count: int, min_vertices: int):
    """``count`` lakes with at least ``min_vertices`` vertices, as a GeoSeries in EPSG:3857."""
    import geopandas as gpd

    collection = shapely.from_geojson(lakes_file().read_text())  # one GeometryCollection
    parts = shapely.get_parts(shapely.get_parts(collection))
    parts = parts[shapely.get_num_coordinates(parts) >= min_vertices]
    pick = np.unique(np.linspace(0, len(parts) - 1, min(count, len(parts))).round().astype(int))
    lakes = gpd.GeoSeries(shapely.make_valid(parts[pick]), crs="EPSG:4326").to_crs("EPSG:3857")
    return lakes[lakes.geom_type == "Polygon"].reset_index(drop=True)


def coverage(line, polygon, samples: int = 400) -> float:
    """Share of the polygon's area inside the discs centred on the line, each reaching the shore.

    The union of those discs is what the line with its widths says of the
    polygon: an arm the line does not enter is missing from it.
    """
    if line is None or line.is_empty:
        return 0.0
    points = shapely.line_interpolate_point(line, np.linspace(0.0, 1.0, samples), normalized=True) \
        if line.geom_type == "LineString" else shapely.points(_spread(line, samples))
    radii = shapely.distance(points, polygon.boundary)
    discs = shapely.union_all(shapely.buffer(points, radii, quad_segs=8))
    return float(discs.intersection(polygon).area / polygon.area)


def _spread(line, samples: int) -> np.ndarray:
    parts = shapely.get_parts(line)
    lengths = shapely.length(parts)
    out = []
    for part, length in zip(parts, lengths):
        k = max(2, int(round(samples * length / max(lengths.sum(), 1e-300))))
        out.append(shapely.get_coordinates(shapely.line_interpolate_point(part, np.linspace(0, 1, k), normalized=True)))
    return np.concatenate(out)


def branch_figures(line, polygon) -> tuple[int, int, bool]:
    """Terminal branches, spurious terminal branches, and whether ``line`` lies inside ``polygon``."""
    size = np.sqrt(polygon.area)
    # the parts outside, densified: an edge between two nodes inside that cuts across a bend of the
    # shore has only its two crossings (on the shore) as vertices outside
    outside = shapely.get_coordinates(shapely.segmentize(line.difference(polygon), 1e-3 * size))
    inside = not len(outside) or float(shapely.distance(shapely.points(outside), polygon.boundary).max()) <= 1e-6 * size
    merged = shapely.line_merge(shapely.unary_union(line))
    branches = [g for g in shapely.get_parts(merged) if g.length > 0]
    ends: dict[tuple[float, float], int] = {}
    for b in branches:
        c = np.asarray(b.coords)
        for p in (c[0], c[-1]):
            key = (round(float(p[0]), 6), round(float(p[1]), 6))
            ends[key] = ends.get(key, 0) + 1
    terminal = spurious = 0
    shore = polygon.boundary
    for b in branches:
        c = np.asarray(b.coords)
        a, z = ((round(float(p[0]), 6), round(float(p[1]), 6)) for p in (c[0], c[-1]))
        degrees = ends[a], ends[z]
        if 1 not in degrees or degrees == (1, 1):
            continue
        terminal += 1
        end, junction = (shapely.Point(c[0]), shapely.Point(c[-1])) if degrees[0] == 1 else \
            (shapely.Point(c[-1]), shapely.Point(c[0]))
        depth = junction.distance(shore)
        if b.length + end.distance(shore) - depth < 0.5 * depth:
            spurious += 1
    return terminal, spurious, inside


def _lines(compute, layer, chunk):
    """Every feature's line of one chunk: ``layer`` on the whole chunk, else ``compute`` feature by feature."""
    if layer is not None:
        return list(layer(chunk))
    lines = []
    for poly in chunk:
        try:
            lines.append(compute(poly))
        except Exception:  # noqa: BLE001 - a peer's failure is a figure, not a crash
            lines.append(None)
    return lines


def run_tools(tools, lakes, chunk: int) -> list[dict]:
    """Lines and CPU seconds of every tool, the tools taking turns chunk by chunk (load drift hits all alike)."""
    lines = {name: [] for name, _, _ in tools}
    seconds = dict.fromkeys(lines, 0.0)
    for start in range(0, len(lakes), chunk):
        part = lakes.iloc[start : start + chunk]
        for name, compute, layer in tools:
            t0 = time.process_time()
            lines[name] += _lines(compute, layer, part)
            seconds[name] += time.process_time() - t0
    return [figures(name, lines[name], seconds[name], lakes) for name in lines]


def figures(name, lines, seconds, lakes) -> dict:
    """Quality figures of one tool's lines."""
    failures = 0
    terminal, spurious, inside, covered = [], [], [], []
    for line, poly in zip(lines, lakes):
        if line is None or line.is_empty:
            failures += 1
            continue
        t, s, i = branch_figures(line, poly)
        terminal.append(t)
        spurious.append(s)
        inside.append(i)
        covered.append(coverage(line, poly))
    return {"tool": name, "seconds": seconds, "failures": failures, "terminal": np.array(terminal),
            "spurious": np.array(spurious), "inside": np.array(inside), "coverage": np.array(covered)}


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=3000)
    ap.add_argument("--min-vertices", type=int, default=12)
    ap.add_argument("--half", choices=("all", "tune", "check"), default="all",
                    help="all lakes, the even positions (tuning half) or the odd ones (check half)")
    ap.add_argument("--call", choices=("layer", "feature"), default="layer",
                    help="time medialaxis on the whole layer (default call) or one call per feature")
    ap.add_argument("--chunk", type=int, default=50, help="features per turn of each tool (default %(default)s)")
    args = ap.parse_args(argv)
    lakes = lake_polygons(args.count, args.min_vertices)
    if args.half != "all":
        lakes = lakes.iloc[0 if args.half == "tune" else 1 :: 2].reset_index(drop=True)
    n_vertices = shapely.get_num_coordinates(lakes.values)
    print(f"{len(lakes)} OSM lakes (1 km generalization, >= {args.min_vertices} vertices; "
          f"median {int(np.median(n_vertices))}, max {int(n_vertices.max())} vertices; "
          f"{int((shapely.get_num_interior_rings(lakes.values) > 0).sum())} with islands), EPSG:3857; "
          f"half: {args.half}; medialaxis timed per {args.call}")

    import geopandas as gpd

    import medialaxis as mx

    tools = []

    def ours(poly):
        out = mx.centerlines(gpd.GeoSeries([poly], crs=lakes.crs), show_progress=False)
        return out.geometry.iloc[0]

    def ours_layer(layer):
        return mx.centerlines(layer, show_progress=False).geometry

    tools.append(("medialaxis", ours, ours_layer if args.call == "layer" else None))
    try:
        import pygeoops

        tools.append(("pygeoops.centerline", pygeoops.centerline, None))
    except ImportError:
        print("pygeoops not installed (pip install 'medialaxis[bench]'): row left out")
    try:
        from centerline.geometry import Centerline

        def peer(poly):
            width = 2.0 * poly.area / poly.length  # pygeoops' automatic densify distance
            return Centerline(poly, interpolation_distance=width).geometry

        tools.append(("centerline", peer, None))
    except ImportError:
        print("centerline not installed (pip install 'medialaxis[bench]'): row left out")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mx.medial_axis(lakes.iloc[0], detour=1.0)  # compiled kernels loaded before any clock runs,
        ours_layer(lakes.iloc[:2])  # the layer route's as well
        rows = run_tools(tools, lakes, args.chunk)
    print(f"{'tool':22s} {'seconds':>8s} {'ms/feat':>8s} {'fail':>5s} {'terminal/feat':>14s} "
          f"{'spurious/feat':>14s} {'with spurious':>14s} {'inside':>8s} {'coverage':>9s}")
    base = rows[0]["seconds"]
    for r in rows:
        n = len(r["terminal"])
        print(f"{r['tool']:22s} {r['seconds']:8.1f} {1000 * r['seconds'] / len(lakes):8.1f} {r['failures']:5d} "
              f"{r['terminal'].mean() if n else np.nan:14.2f} {r['spurious'].mean() if n else np.nan:14.3f} "
              f"{100 * (r['spurious'] > 0).mean() if n else np.nan:13.1f}% "
              f"{100 * r['inside'].mean() if n else np.nan:7.1f}% "
              f"{100 * np.median(r['coverage']) if n else np.nan:8.1f}%   (time x{r['seconds'] / base:.2f})")
    peer = [r for r in rows if r["tool"] == "pygeoops.centerline"]
    if peer:
        print(f"medialaxis takes {base / peer[0]['seconds']:.2f} times pygeoops.centerline's time")


if __name__ == "__main__":
    main()
