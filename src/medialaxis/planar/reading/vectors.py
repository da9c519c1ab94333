"""Vector shapes: shapely geometries, boundary loops, WKT and GeoJSON files, validated as polygons."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import Polygon

from medialaxis.core.validate import check_coordinates
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError

__all__ = ["validate_polygonal", "loop_polygon", "read_vector", "parse_vector", "NEAR_DUPLICATE"]

#: Consecutive vertices closer than this fraction of the shape's extent are one vertex.
NEAR_DUPLICATE = 1e-9


def validate_polygonal(geom: Any, where: str) -> tuple[Any, str | None]:
    if geom.geom_type not in ("Polygon", "MultiPolygon", "GeometryCollection"):
        raise InvalidInputError(f"{where}: expected a Polygon or MultiPolygon, got a {geom.geom_type}")
    coords, given = shapely.get_coordinates(geom), geom
    if len(coords) == 0 or geom.is_empty:
        raise EmptyShapeError(f"{where}: the geometry is empty")
    check_coordinates(coords, where)
    repaired = None
    if not geom.is_valid:
        reason = shapely.is_valid_reason(geom)
        fixed = shapely.make_valid(geom)
        parts = [g for g in shapely.get_parts(fixed) if g.geom_type in ("Polygon", "MultiPolygon")]
        fixed = shapely.union_all(parts) if parts else Polygon()
        repaired = f"invalid input ({reason}) repaired with shapely.make_valid"
        geom = fixed
    if geom.geom_type == "GeometryCollection":
        parts = [g for g in shapely.get_parts(geom) if g.area > 0]
        geom = shapely.union_all(parts) if parts else Polygon()
    if geom.is_empty or geom.area <= 0:
        raise EmptyShapeError(f"{where}: the polygon has zero area")
    # Vertices a hair apart (a ring closed with a rounding error, 1e-15 off its start) make a
    # degenerate Delaunay triangle whose circle is not a medial disc: merge them.
    if geom is not given:
        coords = shapely.get_coordinates(geom)  # repaired or collected above
    extent = float(np.ptp(coords, axis=0).max())
    try:
        merged = shapely.remove_repeated_points(geom, NEAR_DUPLICATE * extent)
    except shapely.errors.GEOSException:  # a ring that would collapse: kept as it is
        merged = geom
    merged_some = shapely.get_num_coordinates(merged) != len(coords)  # else the geometry as it was
    if merged_some and merged.is_valid and not merged.is_empty and merged.area > 0:
        geom = merged
    return shapely.normalize(geom), repaired


def loop_polygon(loop: np.ndarray) -> Any:
    if loop.ndim != 2 or loop.shape[1] != 2:
        raise InvalidInputError(f"a boundary loop must have shape (n, 2), got {loop.shape}")
    if not np.all(np.isfinite(loop)):
        bad = np.argwhere(~np.isfinite(loop))[0]
        raise InvalidInputError(f"boundary loop has a non-finite coordinate at row {bad[0]}")
    if len(np.unique(loop, axis=0)) < 3:
        raise EmptyShapeError(f"a boundary loop needs at least 3 distinct points, got {len(loop)}")
    return Polygon(loop)


def read_vector(path: Path) -> Any:
    """The polygons of a WKT or GeoJSON file, merged."""
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputFileError(f"cannot read {str(path)!r}: {exc}") from exc
    return parse_vector(text, wkt=path.suffix.lower() == ".wkt", what=repr(str(path)))


def parse_vector(text: str, *, wkt: bool, what: str = "the text") -> Any:
    """The polygons of WKT (``wkt``) or GeoJSON text, merged; ``what`` names the source in errors."""
    if wkt:
        try:
            return shapely.from_wkt(text.strip())
        except shapely.errors.GEOSException as exc:
            raise InputFileError(f"cannot parse WKT in {what}: {exc}") from exc
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputFileError(f"cannot parse JSON in {what}: {exc}") from exc
    geoms = []
    feats = doc.get("features") if isinstance(doc, dict) else None
    if feats is not None and not isinstance(feats, list):
        raise InputFileError(f"bad GeoJSON in {what}: 'features' must be a list, got {type(feats).__name__}")
    items = feats if feats is not None else [doc]
    for item in items:
        g = item.get("geometry", item) if isinstance(item, dict) else None
        if g is None:
            continue
        try:
            geoms.append(shapely.geometry.shape(g))
        except Exception as exc:  # noqa: BLE001 - shapely raises several types
            raise InputFileError(f"bad GeoJSON geometry in {what}: {exc}") from exc
    polys = [g for g in geoms if g.geom_type in ("Polygon", "MultiPolygon")]
    if not polys:
        raise EmptyShapeError(f"{what} holds no Polygon or MultiPolygon")
    return shapely.union_all(polys)
