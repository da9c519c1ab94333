"""Vector shapes: shapely geometries, boundary loops, WKT, GeoJSON and SVG files, validated as polygons."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import Polygon

from medialaxis.core.validate import check_coordinates
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError

__all__ = ["validate_polygonal", "loop_polygon", "read_vector"]


def validate_polygonal(geom: Any, where: str) -> tuple[Any, str | None]:
    if geom.geom_type not in ("Polygon", "MultiPolygon", "GeometryCollection"):
        raise InvalidInputError(f"{where}: expected a Polygon or MultiPolygon, got a {geom.geom_type}")
    coords = shapely.get_coordinates(geom)
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


_SVG_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def _read_svg(path: Path) -> Any:
    """Filled shapes of an SVG (polygon, rect, circle, ellipse, path with straight or curved segments)."""
    import xml.etree.ElementTree as ET

    try:
        root = ET.parse(path).getroot()
    except Exception as exc:  # noqa: BLE001 - ParseError, OSError, LookupError (bad encoding), ValueError...
        raise InputFileError(f"cannot parse SVG {str(path)!r}: {exc}") from exc
    rings: list[np.ndarray] = []
    for el in root.iter():
        tag = el.tag.rsplit("}", 1)[-1]
        a = el.attrib
        try:
            if tag in ("polygon", "polyline"):
                nums = [float(v) for v in re.findall(_SVG_NUM, a.get("points", ""))]
                rings.append(np.array(nums).reshape(-1, 2))
            elif tag == "rect":
                x, y = float(a.get("x", 0)), float(a.get("y", 0))
                w, h = float(a["width"]), float(a["height"])
                rings.append(np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]]))
            elif tag in ("circle", "ellipse"):
                cx, cy = float(a.get("cx", 0)), float(a.get("cy", 0))
                rx = float(a.get("r", a.get("rx", 0)))
                ry = float(a.get("r", a.get("ry", 0)))
                t = np.linspace(0, 2 * np.pi, 720, endpoint=False)
                rings.append(np.c_[cx + rx * np.cos(t), cy + ry * np.sin(t)])
            elif tag == "path":
                rings.extend(_svg_path_rings(a.get("d", "")))
        except (KeyError, ValueError) as exc:
            raise InputFileError(f"malformed <{tag}> in SVG {str(path)!r}: {exc}") from exc
    rings = [r for r in rings if len(r) >= 3]
    if not rings:
        raise EmptyShapeError(f"SVG {str(path)!r} contains no closed shape")
    check_coordinates(np.vstack(rings), f"SVG {str(path)!r}")
    # Even-odd fill: symmetric difference of all rings.
    geom = Polygon()
    try:
        for r in rings:
            geom = geom.symmetric_difference(shapely.make_valid(Polygon(r)))
    except shapely.errors.GEOSException as exc:
        raise InputFileError(f"malformed shape in SVG {str(path)!r}: {exc}") from exc
    return geom


def _svg_path_rings(d: str) -> list[np.ndarray]:
    """Rings of an SVG path: M/L/H/V/C/Q/Z, absolute and relative; curves are sampled."""
    tokens = re.findall(r"[MmLlHhVvCcQqZz]|" + _SVG_NUM, d)
    rings, cur, pos, start = [], [], np.zeros(2), np.zeros(2)
    i, cmd = 0, None
    while i < len(tokens):
        if re.fullmatch(r"[A-Za-z]", tokens[i]):
            cmd = tokens[i]
            i += 1
            if cmd in "Zz":
                if len(cur) >= 3:
                    rings.append(np.array(cur))
                cur, pos = [], start.copy()
                continue
        if cmd is None:
            raise ValueError(f"path data starts with a number: {d[:30]!r}")

        def take(k: int) -> np.ndarray:
            nonlocal i
            vals = np.array([float(t) for t in tokens[i : i + k]])
            if len(vals) != k:
                raise ValueError("truncated path data")
            i += k
            return vals

        rel = cmd.islower()
        c = cmd.upper()
        if c == "M":
            pos = take(2) + (pos if rel else 0)
            if len(cur) >= 3:
                rings.append(np.array(cur))
            cur, start = [pos.copy()], pos.copy()
            cmd = "l" if rel else "L"
        elif c == "L":
            pos = take(2) + (pos if rel else 0)
            cur.append(pos.copy())
        elif c == "H":
            x = take(1)[0]
            pos = np.array([x + (pos[0] if rel else 0), pos[1]])
            cur.append(pos.copy())
        elif c == "V":
            y = take(1)[0]
            pos = np.array([pos[0], y + (pos[1] if rel else 0)])
            cur.append(pos.copy())
        elif c in "CQ":
            k = 3 if c == "C" else 2
            ctrl = take(2 * k).reshape(k, 2) + (pos if rel else 0)
            pts = np.vstack([pos, ctrl])
            t = np.linspace(0, 1, 17)[1:, None]
            if c == "C":
                curve = ((1 - t) ** 3 * pts[0] + 3 * (1 - t) ** 2 * t * pts[1]
                         + 3 * (1 - t) * t**2 * pts[2] + t**3 * pts[3])
            else:
                curve = (1 - t) ** 2 * pts[0] + 2 * (1 - t) * t * pts[1] + t**2 * pts[2]
            cur.extend(curve)
            pos = pts[-1].copy()
        else:  # pragma: no cover - regex admits only the commands above
            raise ValueError(f"unsupported path command {cmd!r}")
    if len(cur) >= 3:
        rings.append(np.array(cur))
    return rings


def read_vector(path: Path) -> Any:
    ext = path.suffix.lower()
    if ext == ".svg":
        return _read_svg(path)
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputFileError(f"cannot read {str(path)!r}: {exc}") from exc
    if ext == ".wkt":
        try:
            return shapely.from_wkt(text.strip())
        except shapely.errors.GEOSException as exc:
            raise InputFileError(f"cannot parse WKT in {str(path)!r}: {exc}") from exc
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputFileError(f"cannot parse JSON in {str(path)!r}: {exc}") from exc
    geoms = []
    feats = doc.get("features") if isinstance(doc, dict) else None
    if feats is not None and not isinstance(feats, list):
        raise InputFileError(f"bad GeoJSON in {str(path)!r}: 'features' must be a list, got {type(feats).__name__}")
    items = feats if feats is not None else [doc]
    for item in items:
        g = item.get("geometry", item) if isinstance(item, dict) else None
        if g is None:
            continue
        try:
            geoms.append(shapely.geometry.shape(g))
        except Exception as exc:  # noqa: BLE001 - shapely raises several types
            raise InputFileError(f"bad GeoJSON geometry in {str(path)!r}: {exc}") from exc
    polys = [g for g in geoms if g.geom_type in ("Polygon", "MultiPolygon")]
    if not polys:
        raise EmptyShapeError(f"{str(path)!r} holds no Polygon or MultiPolygon")
    return shapely.union_all(polys)
