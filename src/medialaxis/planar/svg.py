"""SVG drawings read as they are painted: the region every fill and stroke covers.

svgelements (MIT) parses the document: the whole path grammar (arcs, smooth
curves), transforms, units and viewBox, ``<use>``, CSS ``style`` and
``display``. This module starts where it ends: each painted element becomes
a shapely region in its own coordinate system (its fill under its fill rule,
its stroke as the band the pen covers, with width, caps, joins, miter limit
and dashes), which the element's transform then maps to the document. The
union of the painted regions is the shape; colours do not matter, a white
fill on a white page is painted.

The result is in the root's user units (the viewBox's), y down, as the
drawing's own coordinates: a medial axis of it overlays the drawing.

Not read, with a clear error: markers, masks, filters, ``<switch>``,
``clipPathUnits="objectBoundingBox"``. Skipped with a count (the caller
warns): text and raster images.

References
----------
W3C, Scalable Vector Graphics (SVG) 1.1 (Second Edition), Recommendation,
2011: sections 7 (coordinate systems and transforms), 8 (paths), 11
(painting: fill rules, stroke properties), 14.3 (clipping paths).
https://www.w3.org/TR/SVG11/
"""

from __future__ import annotations

import copy
import io
import math
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np
import shapely
import shapely.ops
from shapely.geometry import Polygon

from medialaxis.core.validate import check_coordinates
from medialaxis.errors import EmptyShapeError, InputFileError, UnsupportedFeatureError
from medialaxis.planar.fill import fill_rings, stroke_region

__all__ = ["read_svg"]

#: Containers whose children are painted only where they are referenced.
_REFERENCED_ONLY = ("symbol", "marker", "mask", "linearGradient", "radialGradient", "filter", "font", "glyph")
#: Containers this reader cannot draw: their semantics would change the shape.
_REFUSED_TAGS = {"switch": "<switch> (conditional processing)", "foreignObject": "<foreignObject>"}
#: Painting properties that change the painted shape in ways this reader cannot draw.
_REFUSED_PROPERTIES = {
    "marker-start": "markers (marker-start)",
    "marker-mid": "markers (marker-mid)",
    "marker-end": "markers (marker-end)",
    "marker": "markers",
    "mask": "masks",
    "filter": "filters",
}
_SVG_NS = "{http://www.w3.org/2000/svg}"


def _local_name(tag: Any) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


_XLINK = "{http://www.w3.org/1999/xlink}href"


def _href(element: Any) -> str | None:
    return element.get(_XLINK) or element.get("href")


def _parse_tree(path: Path) -> Any:
    try:
        return ET.parse(path)
    except Exception as exc:  # noqa: BLE001 - ParseError, OSError, LookupError (bad encoding), ValueError...
        raise InputFileError(f"cannot parse SVG {str(path)!r}: {exc}") from exc


def _external_target(path: Path, href: str, cache: dict[Path, Any]) -> Any:
    """The element ``file#id`` of another SVG file, next to ``path``."""
    name, _, ident = href.partition("#")
    other = (path.parent / name).resolve()
    if other not in cache:
        if not other.is_file():
            raise InputFileError(f"SVG {str(path)!r} uses {href!r}, but {str(other)!r} does not exist")
        cache[other] = _parse_tree(other).getroot()
    root = cache[other]
    found = next((e for e in root.iter() if e.get("id") == ident), None) if ident else root
    if found is None:
        raise InputFileError(f"SVG {str(path)!r} uses {href!r}, but {name!r} has no element with id {ident!r}")
    return found


def _symbol_viewport(use: Any, symbol: Any) -> Any:
    """A ``<use>`` of a ``<symbol>`` as SVG 1.1 section 5.6 draws it: a nested ``<svg>`` of the use's size."""
    group = ET.Element(f"{_SVG_NS}g", {k: v for k, v in use.attrib.items() if k not in (_XLINK, "href", "x", "y",
                                                                                        "width", "height", "id")})
    x, y = use.get("x", "0"), use.get("y", "0")
    if x not in ("0", "") or y not in ("0", ""):
        group.set("transform", f"{group.get('transform', '')} translate({x or 0},{y or 0})".strip())
    viewport = ET.SubElement(group, f"{_SVG_NS}svg", {"width": use.get("width", "100%"),
                                                      "height": use.get("height", "100%")})
    for key in ("viewBox", "preserveAspectRatio", "overflow", "style"):
        if symbol.get(key) is not None:
            viewport.set(key, symbol.get(key))
    viewport.extend(copy.deepcopy(list(symbol)))
    return group


def _style_items(element: Any) -> list[tuple[str, str]]:
    items = []
    for item in (element.get("style") or "").split(";"):
        key, sep, value = item.partition(":")
        if sep:
            items.append((key.strip(), value.strip()))
    return items


def _resolve_inherit(element: Any, parent_values: dict[str, str]) -> None:
    """Replace the keyword ``inherit`` by the parent's value (SVG 1.1 section 6.2), in attributes and styles.

    svgelements would take the keyword for a value (a colour named "inherit").
    """
    values = dict(parent_values)
    for key, value in list(element.attrib.items()):
        if value.strip() == "inherit":
            if key in parent_values:
                element.set(key, parent_values[key])
            else:
                del element.attrib[key]
    items = _style_items(element)
    if any(value == "inherit" for _, value in items):
        kept = [(k, parent_values[k] if v == "inherit" else v) for k, v in items if v != "inherit" or k in parent_values]
        element.set("style", "; ".join(f"{k}: {v}" for k, v in kept))
    values.update({k: v for k, v in element.attrib.items() if isinstance(k, str) and not k.startswith("{")})
    values.update(dict(_style_items(element)))
    for key in ("id", "transform", "x", "y", "width", "height", "d", "points", "style", "class"):
        values.pop(key, None)
    for child in element:
        _resolve_inherit(child, values)


def _prepared_source(path: Path) -> tuple[io.BytesIO, dict[str, Any]]:
    """The document made plain for svgelements, as SVG defines it.

    - Containers drawn only where referenced (``symbol``, ``marker``, ``mask``,
      gradients) move into ``<defs>``: svgelements would draw the children of
      elements it does not know where they stand.
    - A ``<use>`` of a ``<symbol>`` becomes a nested ``<svg>`` of the use's
      size (SVG 1.1 section 5.6), so the symbol's viewBox and clipping apply.
    - A ``<use>`` of an element of another file gets a copy of that element.
    """
    tree = _parse_tree(path)
    root = tree.getroot()
    if _local_name(root.tag) != "svg":
        raise InputFileError(f"{str(path)!r} is not an SVG document (root element <{_local_name(root.tag)}>)")
    _resolve_inherit(root, {})
    ids = {e.get("id"): e for e in root.iter() if e.get("id")}
    external: dict[Path, Any] = {}
    copies = []
    for parent in list(root.iter()):
        for index, child in enumerate(list(parent)):
            if _local_name(child.tag) != "use" or not _href(child):
                continue
            href = _href(child).strip()
            if href.startswith("#"):
                target = ids.get(href[1:])
            elif "(" in href or "#" not in href:
                continue  # not an IRI of an element: svgelements draws nothing for it, as SVG says
            else:
                target = _external_target(path, href, external)
                if _local_name(target.tag) != "symbol":
                    ident = f"medialaxis-external-{len(copies)}"
                    copied = copy.deepcopy(target)
                    copied.set("id", ident)
                    copies.append(copied)
                    child.set(_XLINK, f"#{ident}")
                    child.attrib.pop("href", None)
                    continue
            if target is not None and _local_name(target.tag) == "symbol":
                parent.remove(child)
                parent.insert(index, _symbol_viewport(child, target))
    moved = list(copies)
    for parent in root.iter():
        if _local_name(parent.tag) in _REFERENCED_ONLY and parent is not root:
            continue
        for child in list(parent):
            name = _local_name(child.tag)
            if name in _REFUSED_TAGS:
                raise UnsupportedFeatureError(f"SVG {str(path)!r} uses {_REFUSED_TAGS[name]}, which is not read")
            if name in _REFERENCED_ONLY:
                parent.remove(child)
                moved.append(child)
    if moved:
        defs = ET.Element(f"{_SVG_NS}defs")
        defs.extend(moved)
        root.insert(0, defs)  # first: a <use> finds what it references wherever it stands
    out = io.BytesIO()
    tree.write(out, encoding="utf-8", xml_declaration=True)
    out.seek(0)
    return out, {e.get("id"): e for e in root.iter() if e.get("id")}


def _matrix(m: Any) -> np.ndarray:
    """svgelements Matrix as a 3 x 3 array acting on column vectors (x, y, 1)."""
    return np.array([[m.a, m.c, m.e], [m.b, m.d, m.f], [0.0, 0.0, 1.0]])


def _apply(matrix: np.ndarray, geom: Any) -> Any:
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


def _subpaths(segments: Any, tol: float) -> list[tuple[np.ndarray, bool]]:
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


def _number(values: dict, key: str, default: float) -> float:
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
        stops = [e for e in gradient if _local_name(e.tag) == "stop"]
        if stops:
            return stops
        href = _href(gradient)
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


def _painted(paint: Any, values: dict, key: str, ids: dict[str, Any], where: str) -> bool:
    """Whether a fill or stroke paints: a colour, or a paint server with something to paint.

    A gradient without stops, or whose stops are all transparent, paints
    nothing (SVG 1.1 section 13.2.4); a reference to nothing paints its
    fallback colour, if any. Patterns paint only where their tiles do, which
    this reader cannot draw: refused.
    """
    raw = str(values.get(key, "") or "").strip()
    if _number(values, f"{key}-opacity", 1.0) <= 0:
        return False
    if raw.startswith("url("):
        ident, _, fallback = raw[4:].partition(")")
        server = ids.get(ident.strip().strip("'\"").lstrip("#"))
        if server is None:
            return fallback.strip() not in ("", "none")
        kind = _local_name(server.tag)
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


def _stroke(shape: Any, lines: list[tuple[np.ndarray, bool]]) -> Any:
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
        miter_limit=_number(values, "stroke-miterlimit", 4.0),
    )


def _singular_max(matrix: np.ndarray) -> float:
    return float(np.linalg.svd(matrix[:2, :2], compute_uv=False)[0])


class _Reader:
    """One pass over the parsed document, collecting painted regions in root user units."""

    def __init__(self, svg: Any, ids: dict[str, Any], tol: float, strokes: bool, where: str):
        self.svg = svg
        self.ids = ids
        self.tol = tol
        self.strokes = strokes
        self.where = where
        self.skipped: dict[str, int] = {}
        self.root_inverse = np.linalg.inv(self.viewport(svg))

    @staticmethod
    def viewport(svg: Any) -> np.ndarray:
        """Root user units to CSS pixels (the root's viewBox and transform)."""
        from svgelements import Matrix

        # svgelements composes the root's own transform, then its viewBox, into every element's matrix.
        chain = " ".join(t for t in (str(svg.values.get("transform", "") or ""), svg.viewbox_transform or "") if t)
        return _matrix(Matrix(chain)) if chain else np.eye(3)

    def check_properties(self, element: Any) -> None:
        values = element.values
        for key, what in _REFUSED_PROPERTIES.items():
            raw = str(values.get(key, "none")).strip()
            if raw not in ("none", "", "inherit"):
                tag = values.get("tag", type(element).__name__.lower())
                raise UnsupportedFeatureError(f"SVG {self.where} uses {what} on <{tag}>, which are not read")

    def hidden(self, element: Any) -> bool:
        values = getattr(element, "values", {})
        if str(values.get("visibility", "visible")).strip() in ("hidden", "collapse"):
            return True
        return _number(values, "opacity", 1.0) <= 0

    def viewport_clip(self, nested: Any, region: Any) -> Any:
        """A nested ``<svg>`` (or a used ``<symbol>``) clips to its viewport unless its overflow is visible."""
        if region.is_empty or str(nested.values.get("overflow", "hidden")).strip() in ("visible", "auto"):
            return region
        x, y, w, h = (float(v or 0.0) for v in (nested.x, nested.y, nested.width, nested.height))
        box = shapely.box(x, y, x + w, y + h)
        return region.intersection(_apply(self.root_inverse @ _matrix(nested.transform), box))

    def clip(self, element: Any, region: Any) -> Any:
        clip = getattr(element, "clip_path", None)
        if clip is None or region.is_empty:
            return region
        if str(clip.values.get("clipPathUnits", "userSpaceOnUse")).strip() == "objectBoundingBox":
            raise UnsupportedFeatureError(f"SVG {self.where} uses clipPathUnits='objectBoundingBox', which is not read")
        from svgelements import Matrix

        # Clip children are drawn in the user space of the element that references them.
        definition = _matrix(Matrix(clip.values.get("transform", "") or ""))
        reference = _matrix(element.transform) if hasattr(element, "transform") else definition
        to_reference = reference @ np.linalg.inv(definition)
        parts = []
        for child in clip:
            if not hasattr(child, "segments") or self.hidden(child):
                continue
            full = _matrix(child.transform)
            rule = str(child.values.get("clip-rule", "nonzero")).strip()
            local = self.fill(child, full, rule)
            parts.append(self.clip(child, _apply(self.root_inverse @ to_reference @ full, local)))
        mask = shapely.union_all(parts) if parts else Polygon()
        return region.intersection(mask)

    def fill(self, shape: Any, full: np.ndarray, rule: str) -> Any:
        scale = _singular_max(full)
        lines = _subpaths(shape.segments(transformed=False), self.tol / scale)
        return fill_rings([p for p, _ in lines], rule if rule in ("nonzero", "evenodd") else "nonzero")

    def shape_region(self, shape: Any) -> Any:
        from svgelements import SimpleLine

        self.check_properties(shape)
        full = _matrix(shape.transform)
        scale = _singular_max(full)
        if scale == 0 or abs(np.linalg.det(full[:2, :2])) == 0:
            return Polygon()
        values = shape.values
        lines = _subpaths(shape.segments(transformed=False), self.tol / scale)
        parts = []
        if not isinstance(shape, SimpleLine) and _painted(shape.fill, values, "fill", self.ids, self.where):
            rule = str(values.get("fill-rule", "nonzero")).strip()
            parts.append(fill_rings([p for p, _ in lines], rule if rule in ("nonzero", "evenodd") else "nonzero"))
        if self.strokes and _painted(shape.stroke, values, "stroke", self.ids, self.where):
            parts.append(_stroke(shape, lines))
        parts = [p for p in parts if not p.is_empty]
        if not parts:
            return Polygon()
        local = shapely.union_all(parts) if len(parts) > 1 else parts[0]
        return _apply(self.root_inverse @ full, local)

    def region(self, node: Any) -> Any:
        from svgelements import SVG, Image, Shape, Text

        if self.hidden(node) and not isinstance(node, list):
            return Polygon()
        if isinstance(node, Text):
            if (node.text or "").strip():
                self.skipped["text"] = self.skipped.get("text", 0) + 1
            return Polygon()
        if isinstance(node, Image):
            self.skipped["image"] = self.skipped.get("image", 0) + 1
            return Polygon()
        if isinstance(node, Shape):
            if self.hidden(node):
                return Polygon()
            return self.clip(node, self.shape_region(node))
        if isinstance(node, list):
            if _number(getattr(node, "values", {}), "opacity", 1.0) <= 0:
                return Polygon()
            if hasattr(node, "values"):
                self.check_properties(node)
            parts = [r for r in (self.region(child) for child in node) if not r.is_empty]
            merged = shapely.union_all(parts) if parts else Polygon()
            if isinstance(node, SVG) and node is not self.svg:
                merged = self.viewport_clip(node, merged)
            return self.clip(node, merged)
        return Polygon()


def _drawing_size(svg: Any) -> float:
    """The largest side of the painted elements' bounding box, in root user units."""
    from svgelements import Shape

    boxes = []
    for element in svg.elements():
        if isinstance(element, Shape):
            try:
                box = element.bbox(transformed=True)
            except Exception:  # noqa: BLE001 - degenerate shapes have no box
                box = None
            if box is not None and all(math.isfinite(v) for v in box):
                boxes.append(box)
    if not boxes:
        return 0.0
    b = np.array(boxes, dtype=np.float64)
    lo, hi = b[:, :2].min(0), b[:, 2:].max(0)
    corners = np.array([[lo[0], lo[1], 1], [hi[0], hi[1], 1]]).T
    return float(np.ptp(corners[:2], axis=1).max())


def read_svg(path: Path, *, tolerance: float | None = None, strokes: bool = True) -> tuple[Any, dict[str, Any]]:
    """The region an SVG drawing paints, in its root user units.

    Parameters
    ----------
    path : Path
        An SVG file.
    tolerance : float, optional
        Largest distance from a curve (arc, Bezier) to its polyline, in
        root user units. Default ``1e-4`` of the drawing's size (the largest
        side of the painted elements' bounding box).
    strokes : bool
        Take strokes as regions (the band the pen paints). False reads
        fills only.

    Returns
    -------
    region : shapely Polygon or MultiPolygon
        The union of what is painted.
    info : dict
        ``format``, ``viewport`` (the 6 numbers ``a b c d e f`` of the map
        from root user units to CSS pixels, SVG's matrix order), ``size``
        (width and height in CSS pixels), ``skipped`` (elements not read:
        ``text``, ``image``).

    Raises
    ------
    InputFileError
        The file is not an SVG document or cannot be parsed.
    UnsupportedFeatureError
        The drawing uses a feature that changes the painted shape and is
        not read (markers, masks, filters, ``<switch>``).
    EmptyShapeError
        Nothing is painted.
    """
    from svgelements import SVG

    where = repr(str(path))
    source, ids = _prepared_source(path)
    errors = []
    try:
        svg = SVG.parse(source, reify=False, on_error="raise")
    except ValueError as exc:
        # SVG 1.1 section F.2: a path is drawn up to its first error; the error goes into the warnings.
        errors.append(f"path data in error, drawn up to the error: {exc}")
        source.seek(0)
        try:
            svg = SVG.parse(source, reify=False, on_error="ignore")
        except (ValueError, IndexError, KeyError, TypeError, ET.ParseError) as again:
            raise InputFileError(f"cannot parse SVG {where}: {again}") from again
    except (IndexError, KeyError, TypeError, ET.ParseError) as exc:
        raise InputFileError(f"cannot parse SVG {where}: {exc}") from exc
    if not isinstance(svg, SVG):
        raise InputFileError(f"{where} is not an SVG document")
    viewport = _Reader.viewport(svg)
    size = _drawing_size(svg) / max(_singular_max(viewport), 1e-300)
    tol = float(tolerance) if tolerance is not None else 1e-4 * size
    if not tol > 0:
        raise EmptyShapeError(f"SVG {where} paints nothing")
    reader = _Reader(svg, ids, tol, strokes, where)
    region = reader.region(svg)
    if region.is_empty or region.area <= 0:
        raise EmptyShapeError(f"SVG {where} paints nothing" + (" but strokes (strokes=False)" if not strokes else ""))
    check_coordinates(shapely.get_coordinates(region), f"SVG {where}")
    a, c, e = viewport[0]
    b, d, f = viewport[1]
    info = {
        "format": "svg",
        "viewport": [float(v) for v in (a, b, c, d, e, f)],
        "size": [float(svg.width), float(svg.height)],
        "skipped": dict(reader.skipped),
        "errors": errors,
    }
    return region, info
