"""Which entities of a DXF drawing bound its region, and their curves flattened by ezdxf.

Part of the DXF reader (:mod:`medialaxis.planar.drawings.dxf`): the model space and
its blocks are walked (layers, visibility, block transforms), each entity is
classified (a curve, a fill, a compound to decompose, skipped, unreadable)
and its curves are flattened to the chord tolerance by ezdxf's own curve
maths.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from medialaxis.core.validate import check_coordinates
from medialaxis.errors import InputFileError, InvalidInputError, UnsupportedFeatureError
from medialaxis.planar.drawings.fill import fill_rings

__all__ = ["Gatherer", "flatten", "attr", "describe"]

#: Deepest nesting of block references followed (a block that inserts
#: itself would recurse forever).
MAX_BLOCK_DEPTH = 32

#: Curves that bound a region, alone or joined to others.
_CURVES = frozenset({"LINE", "ARC", "CIRCLE", "ELLIPSE", "SPLINE", "HELIX", "LWPOLYLINE", "POLYLINE"})
#: Entities that fill their own area.
_FILLS = frozenset({"HATCH", "MPOLYGON", "SOLID", "TRACE", "3DFACE"})
#: Entities read through the entities ezdxf decomposes them into (and
#: proxies, and entities ezdxf does not know, through their proxy graphics).
_COMPOUNDS = frozenset({"INSERT", "MLINE"})
#: Entities that bound a region but that ezdxf cannot read: refused.
_UNREADABLE = {
    "REGION": "an ACIS region (ezdxf cannot read ACIS geometry)",
    "3DSOLID": "an ACIS solid (ezdxf cannot read ACIS geometry)",
    "BODY": "an ACIS body (ezdxf cannot read ACIS geometry)",
    "SURFACE": "an ACIS surface (ezdxf cannot read ACIS geometry)",
    "EXTRUDEDSURFACE": "an ACIS surface (ezdxf cannot read ACIS geometry)",
    "LOFTEDSURFACE": "an ACIS surface (ezdxf cannot read ACIS geometry)",
    "REVOLVEDSURFACE": "an ACIS surface (ezdxf cannot read ACIS geometry)",
    "SWEPTSURFACE": "an ACIS surface (ezdxf cannot read ACIS geometry)",
    "PLANESURFACE": "an ACIS surface (ezdxf cannot read ACIS geometry)",
    "NURBSURFACE": "an ACIS surface (ezdxf cannot read ACIS geometry)",
    "MESH": "a 3D mesh, not a planar outline",
}


class Gatherer:
    """Walks the model space and blocks, keeping the entities to read with their effective layer."""

    def __init__(self, where: str, wanted: set[str] | None, hidden_layers: set[str], frozen_layers: set[str]):
        self.where = where
        self.wanted = wanted
        self.hidden_layers = hidden_layers
        self.frozen_layers = frozen_layers
        self.items: list[tuple[Any, str, str]] = []
        self.skipped: Counter[str] = Counter()
        self.hidden = 0
        self.used_layers: set[str] = set()

    def shown(self, layer: str) -> bool:
        if self.wanted is not None:
            return layer.lower() in self.wanted
        return layer.lower() not in self.hidden_layers

    def walk(self, entities: Iterable[Any], inherited: str | None, context: str, depth: int) -> None:
        for entity in entities:
            kind = entity.dxftype()
            own = attr(entity, "layer", "0") or "0"
            layer = inherited if inherited is not None and own == "0" else own
            label = _label(entity, layer, context)
            if attr(entity, "invisible", 0):
                self.hidden += 1
            elif kind == "INSERT":
                self.insert(entity, layer, label, depth)
            elif not self.shown(layer):
                self.hidden += 1
            elif kind in _UNREADABLE:
                raise UnsupportedFeatureError(f"{self.where}: {label} is {_UNREADABLE[kind]}; {_leave_out(layer)}")
            elif kind == "POLYLINE" and (entity.is_poly_face_mesh or entity.is_polygon_mesh):
                raise UnsupportedFeatureError(f"{self.where}: {label} is a 3D mesh, not an outline; {_leave_out(layer)}")
            elif kind in _CURVES or kind in _FILLS:
                self.items.append((entity, layer, label))
            elif kind == "MLINE" or _has_proxy_graphic(entity):
                self.explode(entity, layer, label, context, depth)
            else:
                self.skipped[kind] += 1

    def insert(self, insert: Any, layer: str, label: str, depth: int) -> None:
        if self.wanted is None and layer.lower() in self.frozen_layers:
            self.hidden += 1
            return
        if depth >= MAX_BLOCK_DEPTH:
            raise InputFileError(f"{self.where}: blocks nested more than {MAX_BLOCK_DEPTH} deep at {label}")
        name = attr(insert, "name", "")
        block = insert.block()
        if block is None:
            raise InputFileError(f"{self.where}: {label} refers to block {name!r}, which the drawing does not define")
        if block.block is not None and (block.block.is_xref or block.block.is_xref_overlay):
            raise UnsupportedFeatureError(
                f"{self.where}: {label} inserts the external reference {name!r}, which is not in the file; "
                f"bind it in the CAD tool first, or {_leave_out(layer)}"
            )
        from ezdxf.xclip import XClip

        clip = XClip(insert)
        if clip.has_clipping_path and clip.is_clipping_enabled:
            raise UnsupportedFeatureError(
                f"{self.where}: {label} (block {name!r}) is clipped (XCLIP), which is not read; "
                f"remove the clipping in the CAD tool, or {_leave_out(layer)}"
            )
        if self.shown(layer) and len(insert.attribs):
            self.skipped["ATTRIB"] += len(insert.attribs)
        context = f" in block {name!r} ({label.split(' on layer')[0]})"
        cells = insert.multi_insert() if insert.mcount > 1 else [insert]
        for cell in cells:
            dropped: list[tuple[Any, str]] = []
            children = list(cell.virtual_entities(skipped_entity_callback=lambda e, why, out=dropped: out.append((e, why))))
            for child, why in dropped:
                kind = child.dxftype()
                if kind in _CURVES or kind in _FILLS or kind in _COMPOUNDS:
                    raise UnsupportedFeatureError(
                        f"{self.where}: {_label(child, layer, context)} cannot be placed by its block reference "
                        f"({why}); {_leave_out(layer)}"
                    )
                self.skipped[kind] += 1
            self.walk(children, layer, context, depth + 1)

    def explode(self, entity: Any, layer: str, label: str, context: str, depth: int) -> None:
        try:
            children = list(entity.virtual_entities())
        except (UnsupportedFeatureError, InvalidInputError):
            raise
        except Exception as exc:  # noqa: BLE001 - proxy graphics are decoded from binary data by ezdxf
            raise InputFileError(f"{self.where}: cannot decompose {label}: {describe(exc)}") from exc
        self.walk(children, layer, context or f" in {label.split(' on layer')[0]}", depth + 1)


def flatten(
    ezdxf: Any, gather: Gatherer, chord: float, join: float
) -> tuple[list[np.ndarray], list[np.ndarray], list[str], list[Any], int]:
    """The gathered entities as closed loops, open pieces (with their labels), filled regions, and the rings filled."""
    where = gather.where
    loops: list[np.ndarray] = []
    pieces: list[np.ndarray] = []
    piece_labels: list[str] = []
    fills: list[Any] = []
    n_fill_rings = 0
    for entity, layer, label in gather.items:
        kind = entity.dxftype()
        try:
            if kind in _FILLS:
                rings = [_flat(ring, f"{where}: {label}", join) for ring in _fill_rings_of(ezdxf, entity, chord)]
                rings = [r for r in rings if len(r) >= 3]
                check_coordinates(np.vstack(rings) if rings else np.empty((0, 2)), f"{where}, {label}")
                filled = fill_rings(rings, "evenodd")
                if not filled.is_empty:
                    fills.append(filled)
                    n_fill_rings += len(rings)
                    gather.used_layers.add(layer)
                continue
            for piece in _curve_pieces(entity, chord):
                piece = _flat(piece, f"{where}: {label}", join)
                if len(piece) < 2 or float(np.ptp(piece, axis=0).max()) <= join:
                    continue  # a point, or a curve shorter than the join tolerance
                check_coordinates(piece, f"{where}, {label}")
                gather.used_layers.add(layer)
                if np.hypot(*(piece[-1] - piece[0])) <= join:
                    loops.append(piece)
                else:
                    pieces.append(piece)
                    piece_labels.append(label)
        except (UnsupportedFeatureError, InvalidInputError):
            raise
        except (ezdxf.DXFError, ValueError, ArithmeticError, IndexError) as exc:
            raise InputFileError(f"cannot read {label} of {where}: {describe(exc)}") from exc
    return loops, pieces, piece_labels, fills, n_fill_rings


def _has_proxy_graphic(entity: Any) -> bool:
    """A proxy entity, or one of a class ezdxf does not know, that carries the graphics CAD shows for it."""
    from ezdxf.entities import ACADProxyEntity, DXFTagStorage

    unknown = isinstance(entity, (ACADProxyEntity, DXFTagStorage))
    return unknown and bool(getattr(entity, "proxy_graphic", None)) and hasattr(entity, "virtual_entities")


def attr(entity: Any, name: str, default: Any) -> Any:
    """A DXF attribute of an entity, or ``default`` if unset or not defined for its type (ezdxf raises then)."""
    try:
        return entity.dxf.get(name, default)
    except AttributeError:  # ezdxf's DXFAttributeError: not an attribute of this entity type
        return default


def _label(entity: Any, layer: str, context: str) -> str:
    handle = attr(entity, "handle", None)
    name = f"{entity.dxftype()} #{handle}" if handle else entity.dxftype()
    return f"{name} on layer {layer!r}{context}"


def _leave_out(layer: str) -> str:
    return f"pick the other layers with layers=[...] to leave layer {layer!r} out"


def _xyz(points: Iterable[Any]) -> np.ndarray:
    out = np.array([(p[0], p[1], p[2] if len(p) > 2 else 0.0) for p in points], dtype=np.float64)
    return out.reshape(-1, 3)


def _flat(points: np.ndarray, label: str, join: float) -> np.ndarray:
    """The xy of WCS points, refused if they are not in a plane parallel to xy."""
    if len(points) and float(np.ptp(points[:, 2])) > join:
        raise UnsupportedFeatureError(
            f"{label} is not parallel to the xy plane (z from {points[:, 2].min():.6g} to "
            f"{points[:, 2].max():.6g}): only planar drawings seen from above are read"
        )
    return np.ascontiguousarray(points[:, :2])


def _in_order(segments: list[np.ndarray]) -> np.ndarray:
    """Consecutive segments of one path joined into one polyline, each turned to follow the last."""
    segments = [s for s in segments if len(s)]
    if not segments:
        return np.empty((0, 3))
    if len(segments) > 1:
        first, second = segments[0], segments[1]
        gap_forward = min(np.linalg.norm(first[-1] - second[0]), np.linalg.norm(first[-1] - second[-1]))
        gap_backward = min(np.linalg.norm(first[0] - second[0]), np.linalg.norm(first[0] - second[-1]))
        if gap_backward < gap_forward:
            segments[0] = first[::-1]
    out = [segments[0]]
    for segment in segments[1:]:
        end = out[-1][-1]
        if np.linalg.norm(segment[-1] - end) < np.linalg.norm(segment[0] - end):
            segment = segment[::-1]
        out.append(segment[1:] if np.array_equal(segment[0], end) else segment)
    return np.vstack(out)


def _curve_pieces(entity: Any, chord: float) -> list[np.ndarray]:
    """WCS polylines (k, 3) of a curve entity, flattened to ``chord``."""
    kind = entity.dxftype()
    if kind == "LINE":
        return [_xyz([entity.dxf.start, entity.dxf.end])]
    if kind in ("ARC", "CIRCLE"):
        if not abs(entity.dxf.radius) > 0:
            return []
        return [_xyz(entity.flattening(chord))]
    if kind in ("ELLIPSE", "SPLINE", "HELIX"):
        return [_xyz(entity.flattening(chord))]
    # LWPOLYLINE, 2D and 3D POLYLINE: ezdxf's LINE and ARC segments, in order.
    segments = []
    for part in entity.virtual_entities():
        segments.extend(_curve_pieces(part, chord))
    return [_in_order(segments)]


def _fill_rings_of(ezdxf: Any, entity: Any, chord: float) -> list[np.ndarray]:
    """WCS rings (k, 3) of a filled entity: the boundary paths of a hatch, the corners of a SOLID."""
    kind = entity.dxftype()
    if kind in ("SOLID", "TRACE", "3DFACE"):
        return [_xyz(entity.wcs_vertices())]
    from ezdxf.entities.boundary_paths import EdgePath

    ocs = entity.ocs()
    elevation = float(entity.dxf.elevation.z)
    offset = attr(entity, "offset_vector", (0.0, 0.0, 0.0)) if kind == "MPOLYGON" else (0.0, 0.0, 0.0)
    paths = list(entity.paths.rendering_paths(attr(entity, "hatch_style", 0))) or list(entity.paths)
    rings = []
    for boundary in paths:
        if isinstance(boundary, EdgePath):
            segments = [_edge_points(ezdxf, edge, chord) for edge in boundary.edges]
            ring = _in_order([s for s in segments if s is not None])
        else:
            ring = _bulge_polyline(ezdxf, boundary.vertices, chord)
        if len(ring) < 3:
            continue
        ring = ring.copy()
        ring[:, 0] += offset[0]
        ring[:, 1] += offset[1]
        ring[:, 2] = elevation
        rings.append(_xyz(ocs.points_to_wcs(ring.tolist())))
    return rings


def _edge_points(ezdxf: Any, edge: Any, chord: float) -> np.ndarray | None:
    """OCS points (k, 3) of one hatch edge, by the edge's ezdxf construction tool."""
    from ezdxf.entities.boundary_paths import ArcEdge, EllipseEdge, LineEdge, SplineEdge

    if isinstance(edge, LineEdge):
        return _xyz([edge.start, edge.end])
    if isinstance(edge, ArcEdge):
        return _xyz(edge.construction_tool().flattening(chord)) if abs(edge.radius) > 0 else None
    if isinstance(edge, EllipseEdge):
        return _xyz(edge.construction_tool().flattening(chord)) if edge.major_axis[0] or edge.major_axis[1] else None
    if isinstance(edge, SplineEdge):
        if len(edge.control_points):
            spline = edge.construction_tool()
        elif len(edge.fit_points):
            tangents = (edge.start_tangent, edge.end_tangent) if edge.start_tangent and edge.end_tangent else None
            spline = ezdxf.math.fit_points_to_cad_cv(edge.fit_points, tangents=tangents)
        else:
            return None
        return _xyz(spline.flattening(chord))
    raise UnsupportedFeatureError(f"a hatch edge of type {type(edge).__name__} is not read")


def _bulge_polyline(ezdxf: Any, vertices: Sequence[Any], chord: float) -> np.ndarray:
    """OCS points (k, 3) of a closed polyline of (x, y, bulge) vertices: bulges are ezdxf arcs."""
    from ezdxf.math import ConstructionArc, bulge_to_arc

    segments = []
    n = len(vertices)
    for i in range(n):
        x, y, bulge = (tuple(vertices[i]) + (0.0, 0.0, 0.0))[:3]
        nx, ny = vertices[(i + 1) % n][:2]
        if bulge and (x, y) != (nx, ny):
            centre, start, end, radius = bulge_to_arc((x, y), (nx, ny), bulge)
            arc = ConstructionArc(centre, radius, math.degrees(start), math.degrees(end))
            segments.append(_xyz(arc.flattening(chord)))
        else:
            segments.append(_xyz([(x, y), (nx, ny)]))
    return _in_order(segments)

def describe(exc: BaseException) -> str:
    text = str(exc).strip()
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__
