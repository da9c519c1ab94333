"""The source's frame of a 2D result: the (x, y) every output writes, which way y points, the SVG picture.

Every output names a 2D result's coordinates the same way (README, "Coordinates of the outputs"):

- an image's result (points ``(row, column) * spacing``, ``metadata["image_shape"]``): x = column,
  y = row, y down, as the image is shown; the SVG picture has one CSS pixel per image pixel and lies
  over the image;
- an SVG drawing's result (``metadata["drawing"]["format"] == "svg"``): the drawing's root user units,
  y down; the SVG picture has the drawing's width, height and viewBox and lies over the drawing;
- any other vector input (shapely, WKT, GeoJSON, DXF model space, a boundary loop): its own (x, y),
  y up; the SVG picture flips y in a transform so that the coordinates written are the input's.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any
from xml.sax.saxutils import escape

import numpy as np

__all__ = ["SvgFrame", "coordinates_note", "from_image", "plane_xy", "svg_document", "svg_drawing", "svg_frame",
           "y_down"]

#: Longest side, in CSS pixels, of the picture of a vector input with y up.
PICTURE_SIZE = 800.0


def from_image(ma: Any) -> bool:
    """A 2D result in image index order (row, column)."""
    return ma.dim == 2 and ma.frame == "image"


def svg_drawing(ma: Any) -> Mapping[str, Any] | None:
    """The ``metadata["drawing"]`` of a result of an SVG file (points in its user units, y down), else None."""
    drawing = ma.metadata.get("drawing")
    return drawing if ma.dim == 2 and isinstance(drawing, Mapping) and drawing.get("format") == "svg" else None


def y_down(ma: Any) -> bool:
    """True when a 2D result's y grows downwards (images, SVG drawings)."""
    return from_image(ma) or svg_drawing(ma) is not None


def plane_xy(ma: Any, points: Any) -> np.ndarray:
    """Points of a 2D result as every output writes them: (column, row) for an image, the input's (x, y) otherwise."""
    points = np.asarray(points, np.float64)
    return points[..., ::-1] if from_image(ma) else points


def coordinates_note(ma: Any) -> str:
    """What the x and y written for a 2D result are (GeoJSON ``properties``, GraphML, SVG ``<desc>``)."""
    if from_image(ma):
        return "x = column, y = row (image pixels times spacing, y down)"
    if svg_drawing(ma) is not None:
        return "x, y in the SVG drawing's user units (y down)"
    return "the result's own coordinates"


@dataclasses.dataclass(frozen=True)
class SvgFrame:
    """The root of an SVG picture: its size, viewBox and the transform of the group holding the drawn (x, y)."""

    width: float
    height: float
    view_box: tuple[float, float, float, float]
    preserve_aspect_ratio: str | None = None
    transform: str | None = None
    #: One CSS pixel in the units the group draws in (for stroke widths and dot sizes).
    pixel: float = 1.0

    def open_tags(self) -> str:
        attrs = (f'width="{_num(self.width)}" height="{_num(self.height)}" '
                 f'viewBox="{" ".join(_num(v) for v in self.view_box)}"')
        if self.preserve_aspect_ratio:
            attrs += f' preserveAspectRatio="{self.preserve_aspect_ratio}"'
        group = f'<g transform="{self.transform}">' if self.transform else "<g>"
        return f'<svg xmlns="http://www.w3.org/2000/svg" {attrs}>\n{group}'


def _num(value: float) -> str:
    return f"{float(value) + 0.0:.10g}"  # no "-0"


def _spacing(ma: Any) -> tuple[float, float]:
    spacing = ma.metadata.get("spacing", 1.0)
    values = np.broadcast_to(np.asarray(spacing, np.float64).reshape(-1), (2,))
    return float(values[0]), float(values[1])


def svg_frame(ma: Any, drawn: np.ndarray) -> SvgFrame:
    """The picture's frame for a 2D result; ``drawn`` are the (x, y) to be drawn (for the extent of a y-up picture)."""
    drawing = svg_drawing(ma)
    if drawing is not None and "viewport" in drawing and "size" in drawing:
        a, b, c, d, e, f = (float(v) for v in drawing["viewport"])
        width, height = (float(v) for v in drawing["size"])
        pixel = 1.0 / math.sqrt(abs(a * d - b * c)) if a * d - b * c else 1.0
        if b == 0 and c == 0 and a > 0 and d > 0:  # a viewBox: scale and shift
            aspect = None if math.isclose(a, d, rel_tol=1e-9) else "none"
            return SvgFrame(width, height, (-e / a, -f / d, width / a, height / d), aspect, None, pixel)
        return SvgFrame(width, height, (0.0, 0.0, width, height), None,
                        "matrix(" + " ".join(_num(v) for v in (a, b, c, d, e, f)) + ")", pixel)
    if from_image(ma):
        rows, cols = (int(v) for v in ma.metadata["image_shape"][:2])
        row_step, col_step = _spacing(ma)
        aspect = None if math.isclose(row_step, col_step, rel_tol=1e-9) else "none"
        return SvgFrame(float(cols), float(rows), (-0.5 * col_step, -0.5 * row_step, cols * col_step, rows * row_step),
                        aspect, None, min(row_step, col_step))
    # y up: the group flips y, so the coordinates written are the input's own
    drawn = np.asarray(drawn, np.float64).reshape(-1, 2)
    if not len(drawn):
        drawn = np.zeros((1, 2))
    lo, hi = drawn.min(0), drawn.max(0)
    size = max(float((hi - lo).max()), 1e-12)
    pad = 0.05 * size
    scale = PICTURE_SIZE / (size + 2 * pad)
    span = hi - lo + 2 * pad
    return SvgFrame(float(span[0] * scale), float(span[1] * scale),
                    (float(lo[0] - pad), float(-hi[1] - pad), float(span[0]), float(span[1])),
                    None, "scale(1,-1)", 1.0 / scale)


def _rings(shape: Any) -> list[np.ndarray]:
    if shape is None:
        return []
    import shapely

    return [np.asarray(ring.coords)[:, :2] for poly in shapely.get_parts(shape)
            for ring in [poly.exterior, *poly.interiors]]


def _pairs(xy: np.ndarray) -> str:
    return " ".join(f"{_num(x)},{_num(y)}" for x, y in xy)


def svg_document(ma: Any, note: str | None = None) -> str:
    """An SVG picture of a 2D result: the shape (translucent, even-odd) and the axis over it, in the source's frame.

    The branches are ``<polyline>`` elements of the ``medial-axis`` group, junctions and endpoints
    ``<circle>`` elements; their coordinates are the (x, y) of :func:`plane_xy`.
    """
    outline = [plane_xy(ma, ring) for ring in _rings(ma.shape)]
    points = plane_xy(ma, ma.points)
    frame = svg_frame(ma, np.vstack([points, *outline]) if len(points) or outline else np.zeros((0, 2)))
    px = frame.pixel
    out = [frame.open_tags(), f"<desc>medial axis; coordinates: {escape(note or coordinates_note(ma))}</desc>"]
    if outline:
        d = " ".join("M " + _pairs(ring) + " Z" for ring in outline)
        out.append(f'<path id="shape" d="{d}" fill="#dde6f0" fill-opacity="0.6" stroke="#445" '
                   f'stroke-width="{_num(px)}" fill-rule="evenodd"/>')
    out.append(f'<g id="medial-axis" fill="none" stroke="#c0392b" stroke-width="{_num(1.5 * px)}" '
               'stroke-linejoin="round" stroke-linecap="round">')
    for br in ma.branches():
        out.append(f'<polyline points="{_pairs(plane_xy(ma, br.points))}"/>')
    out.append("</g>")
    for name, colour, idx in (("junctions", "#2c3e50", ma.junctions), ("endpoints", "#27ae60", ma.endpoints)):
        if len(idx):
            out.append(f'<g id="{name}" fill="{colour}">')
            out += [f'<circle cx="{_num(x)}" cy="{_num(y)}" r="{_num(3 * px)}"/>' for x, y in points[idx]]
            out.append("</g>")
    out.append("</g>\n</svg>\n")
    return "\n".join(out)
