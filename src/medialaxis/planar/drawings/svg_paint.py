"""SVG paint as regions: path segments flattened to a chord error, paint servers, strokes with dashes.

References
----------
W3C, Scalable Vector Graphics (SVG) 1.1 (Second Edition), Recommendation,
2011: sections 8 (paths), 11.3-11.4 (fill and stroke properties), 13.2
(gradients). https://www.w3.org/TR/SVG11/
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import shapely
import shapely.ops
from shapely.geometry import Polygon

from medialaxis.errors import UnsupportedFeatureError
from medialaxis.planar.drawings.fill import stroke_region
from medialaxis.planar.drawings.svg_document import href_of, local_name

__all__ = ["matrix_of", "apply_matrix", "subpaths", "number", "painted", "stroke", "largest_scale"]

def matrix_of(m: Any) -> np.ndarray:
    """svgelements Matrix as a 3 x 3 array acting on column vectors (x, y, 1)."""
    return np.array([[m.a, m.c, m.e], [m.b, m.d, m.f], [0.0, 0.0, 1.0]])


def apply_matrix(matrix: np.ndarray, geom: Any) -> Any:
    a, c, e = matrix[0]
    b, d, f = matrix[1]
    return shapely.affinity.affine_transform(geom, [a, c, b, d, e, f])


def _segment_points(seg: Any, tol: float) -> np.ndarray:
    """Points after ``seg.start`` up to ``seg.end``, within ``tol`` (chord error) of the curve."""
    from svgelements import Arc, CubicBezier, QuadraticBezier

    end = np.array([seg.end.x, seg.end.y], dtype=np.float64)
    if isinstance(seg, (CubicBezier, QuadraticBezier)):
        ctrl = np.array([[p.x, p.y] for p in seg], dtype=np.float64)
        # |B''| <= degree * (degree - 1) * the largest second difference of the control points;
        # n chords of a curve with |B''| <= K deviate from it by at most K / (8 n^2).
        degree = len(ctrl) - 1
        second = np.abs(ctrl[2:] - 2 * ctrl[1:-1] + ctrl[:-2]).max(axis=0) if degree >= 2 else np.zeros(2)
        bound = degree * (degree - 1) * float(np.hypot(*second))
        n = max(1, math.ceil(math.sqrt(bound / (8.0 * tol)))) if bound > 0 else 1
    elif isinstance(seg, Arc):
        radius = max(float(seg.rx or 0.0), float(seg.ry or 0.0))
        sweep = abs(float(seg.sweep or 0.0))
        if radius <= tol or sweep == 0:
            n = 1
        else:
            # A chord of angle t on a circle of radius r lies r (1 - cos(t / 2)) from it.
            n = max(1, math.ceil(sweep / (2.0 * math.acos(1.0 - tol / radius))))
    else:
        return end[None, :]
    n = min(n, 100_000)
    pts = np.asarray(seg.npoint(np.linspace(0.0, 1.0, n + 1)[1:]), dtype=np.float64).reshape(-1, 2)
    pts[-1] = end
    return pts


def subpaths(segments: Any, tol: float) -> list[tuple[np.ndarray, bool]]:
    """Flattened subpaths of a segment list, each with whether it was closed by ``Z``."""
    from svgelements import Close, Move

    out: list[tuple[np.ndarray, bool]] = []
    current: list[np.ndarray] = []
    start: np.ndarray | None = None

    def finish(closed: bool) -> None:
        nonlocal current
        if current:
            out.append((np.vstack(current), closed))
        current = []

    for seg in segments:
        if isinstance(seg, Move):
            finish(False)
            start = np.array([[seg.end.x, seg.end.y]], dtype=np.float64)
            current = [start]
            continue
        if not current:  # drawing after Z without M starts at the closed subpath's start
            origin = start if start is not None else np.array([[seg.start.x, seg.start.y]], dtype=np.float64)
            current = [origin]
        if isinstance(seg, Close):
            current.append(current[0][:1])
            finish(True)
            continue
        current.append(_segment_points(seg, tol))
    finish(False)
    return out


def number(values: dict, key: str, default: float) -> float:
    raw = values.get(key)
    if raw is None:
        return default
    try:
        return float(str(raw).strip().rstrip("%")) / (100.0 if str(raw).strip().endswith("%") else 1.0)
    except ValueError:
        return default


def _gradient_stops(gradient: Any, ids: dict[str, Any]) -> list[Any]:
    """The stops of a gradient, inherited through ``xlink:href`` when it has none of its own."""
    seen = set()
    while gradient is not None and id(gradient) not in seen:
        seen.add(id(gradient))
        stops = [e for e in gradient if local_name(e.tag) == "stop"]
        if stops:
            return stops
        href = href_of(gradient)
        gradient = ids.get(href.strip()[1:]) if href and href.strip().startswith("#") else None
    return []


def _stop_opacity(stop: Any) -> float:
    raw = stop.get("stop-opacity")
    for item in (stop.get("style") or "").split(";"):
        key, _, value = item.partition(":")
        if key.strip() == "stop-opacity":
            raw = value
    try:
        return float(raw) if raw is not None else 1.0
    except ValueError:
        return 1.0


def painted(paint: Any, values: dict, key: str, ids: dict[str, Any], where: str) -> bool:
    """Whether a fill or stroke paints: a colour, or a paint server with something to paint.

    A gradient without stops, or whose stops are all transparent, paints
    nothing (SVG 1.1 section 13.2.4); a reference to nothing paints its
    fallback colour, if any. Patterns paint only where their tiles do, which
    this reader cannot draw: refused.
    """
    raw = str(values.get(key, "") or "").strip()
    if number(values, f"{key}-opacity", 1.0) <= 0:
        return False
    if raw.startswith("url("):
        ident, _, fallback = raw[4:].partition(")")
        server = ids.get(ident.strip().strip("'\"").lstrip("#"))
        if server is None:
            return fallback.strip() not in ("", "none")
        kind = local_name(server.tag)
        if kind == "pattern":
            raise UnsupportedFeatureError(f"SVG {where} paints with a pattern ({raw}), which is not read")
        if kind in ("linearGradient", "radialGradient"):
            stops = _gradient_stops(server, ids)
            return any(_stop_opacity(stop) > 0 for stop in stops)
        return False
    if paint is None or getattr(paint, "value", None) is None:
        return False
    return getattr(paint, "alpha", 255) > 0


def _dashed(lines: list[tuple[np.ndarray, bool]], dashes: list[float], offset: float) -> list[tuple[np.ndarray, bool]]:
    """The dashes of each polyline (SVG ``stroke-dasharray``, ``stroke-dashoffset``) as open polylines."""
    if len(dashes) % 2:
        dashes = dashes * 2  # an odd list is repeated to yield an even one
    period = sum(dashes)
    out = []
    for points, closed in lines:
        line = shapely.LineString(np.vstack([points, points[:1]]) if closed else points)
        length = line.length
        if length == 0:
            continue
        pos = -(offset % period)
        k = 0
        while pos < length:
            dash = dashes[k % len(dashes)]
            if k % 2 == 0 and pos + dash > 0:
                piece = shapely.ops.substring(line, max(pos, 0.0), min(pos + dash, length))
                out.append((np.asarray(piece.coords), False))
            pos += dash
            k += 1
    return out


def stroke(shape: Any, lines: list[tuple[np.ndarray, bool]]) -> Any:
    values = shape.values
    width = float(shape.stroke_width or 0.0)
    if width <= 0:
        return Polygon()
    dash_raw = str(values.get("stroke-dasharray", "none")).strip()
    if dash_raw not in ("none", "", "inherit"):
        from svgelements import Length

        try:
            dashes = [float(Length(v).value()) for v in dash_raw.replace(",", " ").split()]
        except (ValueError, TypeError) as exc:
            raise UnsupportedFeatureError(f"stroke-dasharray {dash_raw!r} is not read") from exc
        if dashes and all(d >= 0 for d in dashes) and sum(dashes) > 0:
            try:
                offset = float(Length(str(values.get("stroke-dashoffset", "0")).strip() or "0").value())
            except (ValueError, TypeError):
                offset = 0.0
            lines = _dashed(lines, dashes, offset)
    return stroke_region(
        lines,
        width,
        cap=str(values.get("stroke-linecap", "butt")).strip(),
        join=str(values.get("stroke-linejoin", "miter")).strip(),
        miter_limit=number(values, "stroke-miterlimit", 4.0),
    )


def largest_scale(matrix: np.ndarray) -> float:
    return float(np.linalg.svd(matrix[:2, :2], compute_uv=False)[0])
