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

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import Polygon

from medialaxis.core.validate import check_coordinates
from medialaxis.errors import EmptyShapeError, InputFileError, UnsupportedFeatureError
from medialaxis.planar.drawings.fill import fill_rings
from medialaxis.planar.drawings.svg_document import prepared_source
from medialaxis.planar.drawings.svg_paint import (
    apply_matrix,
    largest_scale,
    matrix_of,
    number,
    painted,
    stroke,
    subpaths,
)

__all__ = ["read_svg"]

#: Painting properties that change the painted shape in ways this reader cannot draw.
_REFUSED_PROPERTIES = {
    "marker-start": "markers (marker-start)",
    "marker-mid": "markers (marker-mid)",
    "marker-end": "markers (marker-end)",
    "marker": "markers",
    "mask": "masks",
    "filter": "filters",
}


def _filled(lines: list[tuple[np.ndarray, bool]], rule: str) -> Any:
    """The region subpaths fill under an SVG fill rule (an unknown rule is SVG's default, nonzero)."""
    return fill_rings([points for points, _ in lines], rule if rule in ("nonzero", "evenodd") else "nonzero")


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
        return matrix_of(Matrix(chain)) if chain else np.eye(3)

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
        return number(values, "opacity", 1.0) <= 0

    def viewport_clip(self, nested: Any, region: Any) -> Any:
        """A nested ``<svg>`` (or a used ``<symbol>``) clips to its viewport unless its overflow is visible."""
        if region.is_empty or str(nested.values.get("overflow", "hidden")).strip() in ("visible", "auto"):
            return region
        x, y, w, h = (float(v or 0.0) for v in (nested.x, nested.y, nested.width, nested.height))
        box = shapely.box(x, y, x + w, y + h)
        return region.intersection(apply_matrix(self.root_inverse @ matrix_of(nested.transform), box))

    def clip(self, element: Any, region: Any) -> Any:
        clip = getattr(element, "clip_path", None)
        if clip is None or region.is_empty:
            return region
        if str(clip.values.get("clipPathUnits", "userSpaceOnUse")).strip() == "objectBoundingBox":
            raise UnsupportedFeatureError(f"SVG {self.where} uses clipPathUnits='objectBoundingBox', which is not read")
        from svgelements import Matrix

        # Clip children are drawn in the user space of the element that references them.
        definition = matrix_of(Matrix(clip.values.get("transform", "") or ""))
        reference = matrix_of(element.transform) if hasattr(element, "transform") else definition
        to_reference = reference @ np.linalg.inv(definition)
        parts = []
        for child in clip:
            if not hasattr(child, "segments") or self.hidden(child):
                continue
            full = matrix_of(child.transform)
            rule = str(child.values.get("clip-rule", "nonzero")).strip()
            local = self.fill(child, full, rule)
            parts.append(self.clip(child, apply_matrix(self.root_inverse @ to_reference @ full, local)))
        mask = shapely.union_all(parts) if parts else Polygon()
        return region.intersection(mask)

    def fill(self, shape: Any, full: np.ndarray, rule: str) -> Any:
        return _filled(subpaths(shape.segments(transformed=False), self.tol / largest_scale(full)), rule)

    def shape_region(self, shape: Any) -> Any:
        from svgelements import SimpleLine

        self.check_properties(shape)
        full = matrix_of(shape.transform)
        scale = largest_scale(full)
        if scale == 0 or abs(np.linalg.det(full[:2, :2])) == 0:
            return Polygon()
        values = shape.values
        lines = subpaths(shape.segments(transformed=False), self.tol / scale)
        parts = []
        if not isinstance(shape, SimpleLine) and painted(shape.fill, values, "fill", self.ids, self.where):
            parts.append(_filled(lines, str(values.get("fill-rule", "nonzero")).strip()))
        if self.strokes and painted(shape.stroke, values, "stroke", self.ids, self.where):
            parts.append(stroke(shape, lines))
        parts = [p for p in parts if not p.is_empty]
        if not parts:
            return Polygon()
        local = shapely.union_all(parts) if len(parts) > 1 else parts[0]
        return apply_matrix(self.root_inverse @ full, local)

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
            if number(getattr(node, "values", {}), "opacity", 1.0) <= 0:
                return Polygon()
            if hasattr(node, "values"):
                self.check_properties(node)
            parts = [r for r in (self.region(child) for child in node) if not r.is_empty]
            merged = shapely.union_all(parts) if parts else Polygon()
            if isinstance(node, SVG) and node is not self.svg:
                merged = self.viewport_clip(node, merged)
            return self.clip(node, merged)
        return Polygon()


def _drawing_size(svg: Any, where: str) -> float:
    """The largest side of the painted elements' bounding box, in root user units.

    Raises InvalidInputError for an element with a NaN or infinite coordinate.
    """
    from svgelements import Shape

    boxes = []
    for element in svg.elements():
        if isinstance(element, Shape):
            try:
                box = element.bbox(transformed=True)
            except Exception:  # noqa: BLE001 - degenerate shapes have no box
                box = None
            if box is not None:
                check_coordinates(np.array(box, dtype=np.float64), f"SVG {where} <{element.values.get('tag')}>")
                boxes.append(box)
    if not boxes:
        return 0.0
    b = np.array(boxes, dtype=np.float64)
    return float((b[:, 2:].max(0) - b[:, :2].min(0)).max())


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
    source, ids = prepared_source(path)
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
    size = _drawing_size(svg, where) / max(largest_scale(viewport), 1e-300)
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
