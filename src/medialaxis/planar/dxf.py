"""The region a DXF drawing bounds: closed outlines, chains of curves, hatches and blocks, read with ezdxf.

A CAD drawing of a part describes its region by boundary curves, not by a
polygon: a closed polyline with bulges for the outline, a CIRCLE for a hole,
a slot drawn as two LINEs and two ARCs in any order and direction. This
module reads the model space of a DXF file with ezdxf (the optional extra
``dxf``) and returns the region as a valid shapely geometry in the drawing's
own coordinates (WCS x and y; nothing is rescaled):

1. Entities are gathered from the model space, and from blocks through
   ``Insert.virtual_entities`` (block transforms, non-uniform and negative
   scales, rotations, MINSERT grids, nested blocks), on the chosen layers.
   With ``layers=None`` every layer is read except those turned off or
   frozen, as CAD tools show them; a block entity on layer ``"0"`` takes the
   layer of its INSERT.
2. Curves are flattened by ezdxf's own curve maths (``Arc.flattening``,
   ``Ellipse.flattening``, ``Spline.flattening``, the construction tools of
   hatch edges) to the chord tolerance, in WCS (entities with a non-default
   extrusion are mapped by ezdxf). Entities in planes parallel to xy (any
   elevation) are projected on it; a tilted one is refused.
3. Closed curves (CIRCLE, a full ELLIPSE, closed polylines and splines) are
   loops; open curves (LINE, ARC, open polylines and splines, elliptic arcs)
   are joined end to end into loops, ends closer than the *join tolerance*
   ``max(1e-6 * size, tolerance)`` being one point. A drawing left open (an
   end that meets no other end) is refused with the positions of the gaps.
   A curve drawn twice, or along a closed loop, is left out where both its
   ends would otherwise be loose (the stray copy CAD drawings often hold),
   and a closed loop drawn twice counts once.
4. The region is the even-odd fill of all loops (holes by nesting, see
   :func:`medialaxis.planar.fill.fill_rings`), united with the filled
   entities (HATCH and MPOLYGON by their boundary paths and hatch style,
   SOLID, TRACE, flat 3DFACE), so that an outline and the hatch of the same
   area give the area once.

Entities that do not bound a region (TEXT, MTEXT, DIMENSION, POINT,
XLINE, IMAGE, WIPEOUT, ...) are skipped and counted; MLINE and proxy
entities are read through the entities ezdxf decomposes them into. The
width of polylines is not read (a polyline is its centre line). Those that
bound a region but cannot be read
(ACIS REGION and solids, meshes, clipped block references, external
references) raise :class:`~medialaxis.errors.UnsupportedFeatureError` naming
the entity.
"""

from __future__ import annotations

import contextlib
import logging
import math
from collections import Counter
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from shapely.geometry import LineString, Point, Polygon

from medialaxis._optional import require
from medialaxis.core.validate import check_coordinates, check_number
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError, UnsupportedFeatureError
from medialaxis.planar.fill import fill_rings

__all__ = ["read_dxf", "DEFAULT_TOLERANCE", "JOIN_FRACTION"]

#: Default chord tolerance, as a fraction of the largest side of the bounding
#: box of the entities read.
DEFAULT_TOLERANCE = 1e-4
#: Smallest join tolerance, as a fraction of that side: curve ends closer
#: than ``max(JOIN_FRACTION * size, tolerance)`` are joined.
JOIN_FRACTION = 1e-6
#: Deepest nesting of block references followed (a block that inserts
#: itself would recurse forever).
MAX_BLOCK_DEPTH = 32
#: Loose ends listed in the message of an open drawing.
MAX_GAPS_LISTED = 5

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


def read_dxf(
    path: Path, *, layers: Sequence[str] | None = None, tolerance: float | None = None
) -> tuple[Any, dict[str, Any]]:
    """The region bounded by the curves of a DXF drawing's model space.

    Parameters
    ----------
    path : path-like
        A DXF file (ASCII or binary, any version ezdxf reads).
    layers : sequence of str, optional
        Layers to read (names are case-insensitive, as in CAD; one string is
        one layer). Named layers are read even when turned off or frozen.
        Default: every layer that is on and thawed.
    tolerance : float, optional
        Chord tolerance of the flattening of arcs, ellipses and splines, in
        drawing units. Default ``1e-4`` times the largest side of the
        bounding box of the entities read. Curve ends closer than
        ``max(1e-6 * that side, tolerance)`` (the join tolerance) are joined.

    Returns
    -------
    region : shapely Polygon or MultiPolygon
        Valid, of positive area, in the drawing's WCS x and y.
    info : dict
        JSON-able: ``format`` (``"dxf"``), ``version`` (the DXF version,
        e.g. ``"AC1027"``), ``units`` (from ``$INSUNITS`` as ezdxf
        abbreviates them, e.g. ``"mm"``; None if unitless), ``layers`` (the
        layers whose entities bound the region), ``loops`` (closed loops
        filled), ``skipped`` (entity type -> count of entities that bound no
        region, e.g. ``{"TEXT": 3}``), ``hidden`` (entities on layers off or
        frozen, or invisible), ``duplicates`` (curves dropped because they
        repeat another), ``slivers`` (pieces and holes thinner than ``1e-6``
        of the size, left by rounding where rings meet, removed),
        ``tolerance`` and ``join_tolerance``.

    Raises
    ------
    InputFileError
        The file is missing, unreadable, not a DXF, truncated, or an entity
        in it is malformed.
    InvalidInputError
        ``layers`` names a layer the drawing lacks (the message lists the
        drawing's layers), ``tolerance`` is not positive, or the curves do
        not close (the message gives the loose ends and the gaps between
        them).
    EmptyShapeError
        No closed shape on the chosen layers.
    UnsupportedFeatureError
        An entity that would change the shape cannot be read: ACIS REGION,
        3DSOLID, BODY and surfaces, MESH, polyface and polygon meshes, a
        clipped block reference, an external reference, an entity not
        parallel to the xy plane.
    MissingDependencyError
        ezdxf is not installed.

    References
    ----------
    Autodesk, "DXF Reference" (AutoCAD 2012), sections ENTITIES and HEADER
    ($INSUNITS); M. Moitzi, ezdxf documentation, https://ezdxf.mozman.at.

    Examples
    --------
    A 4 x 2 plate with a hole of radius 0.5:

    >>> import tempfile, ezdxf
    >>> doc = ezdxf.new()
    >>> plate = doc.modelspace().add_lwpolyline([(0, 0), (4, 0), (4, 2), (0, 2)], close=True)
    >>> hole = doc.modelspace().add_circle((2, 1), 0.5)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     doc.saveas(Path(folder) / "plate.dxf")
    ...     region, info = read_dxf(Path(folder) / "plate.dxf")
    >>> len(region.interiors), round(region.area, 3), info["loops"]
    (1, 7.215, 2)
    """
    ezdxf = require("ezdxf", "medialaxis[dxf]")
    with _ezdxf_messages() as messages:
        region, info = _read(ezdxf, Path(path), layers, tolerance)
    if messages:
        info["ezdxf_messages"] = sorted(set(messages))[:MAX_GAPS_LISTED]
    return region, info


class _Collected(logging.Handler):
    def __init__(self, messages: list[str]):
        super().__init__(logging.WARNING)
        self.messages = messages

    def emit(self, record: logging.LogRecord) -> None:
        self.messages.append(record.getMessage())


@contextlib.contextmanager
def _ezdxf_messages() -> Iterator[list[str]]:
    """ezdxf's warnings while reading, kept for the result's metadata instead of printed on stderr."""
    logger = logging.getLogger("ezdxf")
    messages: list[str] = []
    handler = _Collected(messages)
    propagate = logger.propagate
    logger.addHandler(handler)
    logger.propagate = False
    try:
        yield messages
    finally:
        logger.removeHandler(handler)
        logger.propagate = propagate


def _read(ezdxf: Any, path: Path, layers: Sequence[str] | None, tolerance: float | None) -> tuple[Any, dict[str, Any]]:
    """:func:`read_dxf` once ezdxf is imported and its log is collected."""
    where = f"DXF {str(path)!r}"
    if tolerance is not None:
        tolerance = check_number(tolerance, "tolerance", positive=True)
    if isinstance(layers, str):
        layers = [layers]
    try:
        doc = ezdxf.readfile(path)
    except MemoryError:
        raise
    except Exception as exc:  # noqa: BLE001 - OSError, DXFStructureError, StopIteration (truncated), UnicodeError...
        raise InputFileError(f"cannot read {where}: {_describe(exc)}") from exc

    msp = doc.modelspace()
    table = {layer.dxf.name.lower(): layer for layer in doc.layers}
    wanted = None
    if layers is not None:
        known = {name: layer.dxf.name for name, layer in table.items()}
        for entity in msp:
            name = _attr(entity, "layer", "0") or "0"
            known.setdefault(name.lower(), name)
        wanted = {str(name).lower() for name in layers}
        unknown = [name for name in layers if str(name).lower() not in known]
        if unknown or not wanted:
            raise InvalidInputError(
                f"{where} has no layer {', '.join(map(repr, unknown)) or '(none named)'}; "
                f"its layers: {', '.join(map(repr, sorted(known.values(), key=str.lower)))}"
            )
    hidden_layers = {name for name, layer in table.items() if layer.is_off() or layer.is_frozen()}
    frozen_layers = {name for name, layer in table.items() if layer.is_frozen()}
    gather = _Gatherer(where, wanted, hidden_layers, frozen_layers)
    gather.walk(msp, inherited=None, context="", depth=0)

    items = gather.items
    if not items:
        raise EmptyShapeError(f"{where} has no closed shape in model space on {_layer_phrase(layers)}{_skipped_phrase(gather)}")
    size = _drawing_size(ezdxf, [entity for entity, _, _ in items], where)
    if not size > 0:
        raise EmptyShapeError(
            f"{where}: the curves on {_layer_phrase(layers)} have no measurable extent "
            "(all are points, or their coordinates overflow)"
        )
    chord = DEFAULT_TOLERANCE * size if tolerance is None else tolerance
    join = max(JOIN_FRACTION * size, chord)

    loops, pieces, piece_labels, fills, n_fill_rings = _flatten(ezdxf, gather, chord, join)

    duplicate_tolerance = 2.0 * join
    along = _along_loops(pieces, loops, duplicate_tolerance)
    chained, n_repeated = _chain(pieces, piece_labels, along, join, duplicate_tolerance, where)
    loops, n_same = _drop_repeated_loops(loops + chained, duplicate_tolerance)

    parts = [fill_rings(loops, "evenodd")] if loops else []
    parts += fills
    parts = [p for p in parts if not p.is_empty]
    region = _polygonal(shapely.union_all(parts)) if parts else Polygon()
    region, n_slivers = _without_slivers(region, JOIN_FRACTION * size)
    if region.is_empty or not region.area > 0:
        raise EmptyShapeError(f"{where} has no closed shape in model space on {_layer_phrase(layers)}{_skipped_phrase(gather)}")

    info = {
        "format": "dxf",
        "version": str(doc.dxfversion),
        "units": _units(ezdxf, doc.header.get("$INSUNITS", 0)),
        "layers": sorted(gather.used_layers, key=str.lower),
        "loops": len(loops) + n_fill_rings,
        "skipped": dict(sorted(gather.skipped.items())),
        "hidden": gather.hidden,
        "duplicates": n_repeated + n_same,
        "slivers": n_slivers,
        "tolerance": chord,
        "join_tolerance": join,
    }
    return region, info


class _Gatherer:
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
            own = _attr(entity, "layer", "0") or "0"
            layer = inherited if inherited is not None and own == "0" else own
            label = _label(entity, layer, context)
            if _attr(entity, "invisible", 0):
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
        name = _attr(insert, "name", "")
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
            raise InputFileError(f"{self.where}: cannot decompose {label}: {_describe(exc)}") from exc
        self.walk(children, layer, context or f" in {label.split(' on layer')[0]}", depth + 1)


def _flatten(
    ezdxf: Any, gather: _Gatherer, chord: float, join: float
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
            raise InputFileError(f"cannot read {label} of {where}: {_describe(exc)}") from exc
    return loops, pieces, piece_labels, fills, n_fill_rings


def _has_proxy_graphic(entity: Any) -> bool:
    """A proxy entity, or one of a class ezdxf does not know, that carries the graphics CAD shows for it."""
    from ezdxf.entities import ACADProxyEntity, DXFTagStorage

    unknown = isinstance(entity, (ACADProxyEntity, DXFTagStorage))
    return unknown and bool(getattr(entity, "proxy_graphic", None)) and hasattr(entity, "virtual_entities")


def _attr(entity: Any, name: str, default: Any) -> Any:
    """A DXF attribute of an entity, or ``default`` if unset or not defined for its type (ezdxf raises then)."""
    try:
        return entity.dxf.get(name, default)
    except AttributeError:  # ezdxf's DXFAttributeError: not an attribute of this entity type
        return default


def _label(entity: Any, layer: str, context: str) -> str:
    handle = _attr(entity, "handle", None)
    name = f"{entity.dxftype()} #{handle}" if handle else entity.dxftype()
    return f"{name} on layer {layer!r}{context}"


def _leave_out(layer: str) -> str:
    return f"pick the other layers with layers=[...] to leave layer {layer!r} out"


def _layer_phrase(layers: Sequence[str] | None) -> str:
    if layers is None:
        return "the layers shown (on and thawed)"
    return "layers " + ", ".join(map(repr, layers))


def _skipped_phrase(gather: _Gatherer) -> str:
    notes = []
    if gather.skipped:
        notes.append("skipped " + ", ".join(f"{n} {kind}" for kind, n in sorted(gather.skipped.items())))
    if gather.hidden:
        notes.append(f"{gather.hidden} entities hidden (layer off or frozen, or invisible)")
    return f" ({'; '.join(notes)})" if notes else ""


def _describe(exc: BaseException) -> str:
    text = str(exc).strip()
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _units(ezdxf: Any, code: Any) -> str | None:
    """``$INSUNITS`` as ezdxf abbreviates it (``4`` -> ``"mm"``); None if unitless or unknown."""
    try:
        code = int(code)
        return ezdxf.units.decode(code) or (ezdxf.units.unit_name(code) if code else None)
    except (TypeError, ValueError, IndexError):
        return None


def _drawing_size(ezdxf: Any, entities: list[Any], where: str) -> float:
    """Largest side of the bounding box of ``entities`` (from control points: fast, never too small)."""
    from ezdxf.bbox import extents

    try:
        box = extents(entities, fast=True)
    except (ezdxf.DXFError, ValueError, ArithmeticError, IndexError) as exc:
        raise InputFileError(f"cannot measure the entities of {where}: {_describe(exc)}") from exc
    if not box.has_data:
        return 0.0
    corners = np.array([box.extmin.xyz, box.extmax.xyz], dtype=np.float64)
    check_coordinates(corners[:, :2], where)
    with np.errstate(over="ignore"):
        size = float(np.max(corners[1, :2] - corners[0, :2]))
    if not math.isfinite(size):
        raise InvalidInputError(f"{where}: the drawing spans {size}; coordinates this large cannot be measured")
    return size


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
    offset = _attr(entity, "offset_vector", (0.0, 0.0, 0.0)) if kind == "MPOLYGON" else (0.0, 0.0, 0.0)
    paths = list(entity.paths.rendering_paths(_attr(entity, "hatch_style", 0))) or list(entity.paths)
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


def _polygonal(geom: Any) -> Any:
    """The polygons of a geometry, valid."""
    if not geom.is_valid:
        geom = shapely.make_valid(geom)
    if geom.geom_type in ("Polygon", "MultiPolygon"):
        return geom
    polys = [g for g in shapely.get_parts(geom) if g.geom_type in ("Polygon", "MultiPolygon") and g.area > 0]
    return shapely.union_all(polys) if polys else Polygon()


def _without_slivers(region: Any, width: float) -> tuple[Any, int]:
    """Pieces and holes thinner than ``width`` (twice the area over the perimeter) removed, with their count.

    The fill and the union leave such slivers where rings meet to within
    rounding (a closed spline's seam): far below the join tolerance, and
    below what the triangulation of the pipeline can resolve.
    """
    kept, dropped = [], 0
    for part in shapely.get_parts(region):
        shell = Polygon(part.exterior)
        if 2.0 * shell.area <= width * shell.length:
            dropped += 1
            continue
        holes = []
        for ring in part.interiors:
            if 2.0 * Polygon(ring).area <= width * ring.length:
                dropped += 1
            else:
                holes.append(ring)
        kept.append(Polygon(part.exterior, holes) if len(holes) < len(part.interiors) else part)
    if not dropped:
        return region, 0
    return (shapely.MultiPolygon(kept) if len(kept) > 1 else kept[0] if kept else Polygon()), dropped


def _along_loops(pieces: list[np.ndarray], loops: list[np.ndarray], tol: float) -> np.ndarray:
    """(k,) bool: which open curves lie along a closed loop, to within ``tol`` (a LINE over a polyline's edge)."""
    along = np.zeros(len(pieces), dtype=bool)
    if not pieces or not loops:
        return along
    outlines = [LineString(np.vstack([r, r[:1]])) for r in loops]
    tree = shapely.STRtree(outlines)
    bands: dict[int, Any] = {}
    for i, piece in enumerate(pieces):
        line = LineString(piece)
        near = tree.query(line, predicate="dwithin", distance=tol)
        if len(near):
            for j in near:
                if j not in bands:
                    bands[j] = outlines[j].buffer(tol, quad_segs=2)
            along[i] = line.difference(shapely.union_all([bands[j] for j in near])).length <= tol
    return along


def _chain(
    pieces: list[np.ndarray],
    labels: list[str],
    along_loops: np.ndarray,
    join: float,
    duplicate_tol: float,
    where: str,
) -> tuple[list[np.ndarray], int]:
    """Open curves joined end to end into closed rings; an open drawing raises with its gaps.

    Ends closer than ``join`` are one node. Where more than two curves meet,
    the rings pair them arbitrarily: the even-odd fill depends only on the
    curves, not on how they are grouped into rings. A curve drawn twice
    (same ends, same course within ``duplicate_tol``) or along a closed loop
    (``along_loops``) is left out where both its ends would otherwise be
    loose: the stray copy CAD drawings often hold. Elsewhere it stays, so
    two outlines that share an edge fill their union.
    """
    if not pieces:
        return [], 0
    ends = np.array([(p[0], p[-1]) for p in pieces]).reshape(-1, 2)
    pairs = cKDTree(ends).query_pairs(join, output_type="ndarray")
    links = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(ends), len(ends)))
    _, node = connected_components(links, directed=False)
    start, stop = node[0::2], node[1::2]

    degree = np.bincount(np.r_[start, stop], minlength=len(ends))
    keep = np.ones(len(pieces), dtype=bool)
    by_ends: dict[tuple[int, int], list[int]] = {}
    for i in range(len(pieces)):
        key = (min(start[i], stop[i]), max(start[i], stop[i]))
        repeated = bool(along_loops[i]) or any(
            shapely.hausdorff_distance(LineString(pieces[i]), LineString(pieces[j])) <= duplicate_tol
            for j in by_ends.get(key, [])
        )
        if repeated and start[i] != stop[i] and degree[start[i]] % 2 and degree[stop[i]] % 2:
            keep[i] = False
            degree[start[i]] -= 1
            degree[stop[i]] -= 1
        else:
            by_ends.setdefault(key, []).append(i)
    kept = np.flatnonzero(keep)

    odd = np.flatnonzero(degree % 2)
    if len(odd):
        raise InvalidInputError(_open_message(odd, degree, node, ends, pieces, labels, join, where))

    incident: dict[int, list[int]] = {}
    for i in kept:
        incident.setdefault(start[i], []).append(i)
        incident.setdefault(stop[i], []).append(i)
    used = ~keep
    rings = []
    for first in kept:
        if used[first]:
            continue
        used[first] = True
        origin, here = start[first], stop[first]
        parts = [pieces[first]]
        while here != origin:
            candidates = incident[here]
            while used[candidates[-1]]:
                candidates.pop()
            nxt = candidates.pop()
            used[nxt] = True
            if start[nxt] == here:
                parts.append(pieces[nxt][1:])
                here = stop[nxt]
            else:
                parts.append(pieces[nxt][::-1][1:])
                here = start[nxt]
        ring = np.vstack(parts)
        rings.append(ring[:-1] if len(ring) > 3 else ring)
    return rings, int(len(pieces) - len(kept))


def _open_message(
    odd: np.ndarray,
    degree: np.ndarray,
    node: np.ndarray,
    ends: np.ndarray,
    pieces: list[np.ndarray],
    labels: list[str],
    join: float,
    where: str,
) -> str:
    """Where a drawing is open: its loose ends, paired with their nearest loose end, smallest gaps first."""
    first_end = {}
    for e in range(len(ends) - 1, -1, -1):
        first_end[node[e]] = e
    end_index = np.array([first_end[n] for n in odd])
    where_end, owner = ends[end_index], end_index // 2
    tree: list[Any] = []

    def at(k: int) -> str:
        x, y = where_end[k]
        note = f"; {degree[odd[k]]} curve ends meet there" if degree[odd[k]] > 1 else ""
        if degree[odd[k]] == 1:  # does it end on another curve, away from that curve's ends?
            if not tree:
                tree.append(shapely.STRtree([LineString(p) for p in pieces]))
            hits = [h for h in tree[0].query(Point(x, y), predicate="dwithin", distance=join) if h != owner[k]]
            if hits:
                note = f"; it ends on {labels[hits[0]]}, away from that curve's ends: curves must meet end to end"
        return f"({x:.6g}, {y:.6g}) [an end of {labels[owner[k]]}{note}]"

    gaps, alone = [], []
    if len(odd) > 1:
        distance, nearest = cKDTree(where_end).query(where_end, k=2)
        paired = np.zeros(len(odd), dtype=bool)
        for k in np.argsort(distance[:, 1], kind="stable"):
            m = nearest[k, 1]
            if paired[k]:
                continue
            if not paired[m]:
                paired[k] = paired[m] = True
                gaps.append((float(distance[k, 1]), k, m))
            else:
                alone.append(k)
    else:
        alone.append(0)
    notes, largest = [], None
    for gap, k, m in gaps[:MAX_GAPS_LISTED]:
        if owner[k] == owner[m]:
            notes.append(f"both ends of one curve are loose: {at(k)} and {at(m)}")
        else:
            notes.append(f"gap of {gap:.6g} between {at(k)} and {at(m)}")
            largest = gap if largest is None else max(largest, gap)
    notes += [f"loose end at {at(k)}" for k in alone[: max(0, MAX_GAPS_LISTED - len(notes))]]
    more = len(gaps) + len(alone) - len(notes)
    hint = (
        f"; close the gaps in the drawing, or pass tolerance={largest * 1.01:.3g} or more (it also sets the "
        "chord tolerance of curves)"
        if largest is not None
        else "; close the outline in the drawing"
    )
    return (
        f"{where} is not closed: {len(odd)} curve ends meet no other end within the join tolerance {join:.3g}: "
        + "; ".join(notes)
        + (f"; and {more} more" if more > 0 else "")
        + hint
    )


def _drop_repeated_loops(loops: list[np.ndarray], tol: float) -> tuple[list[np.ndarray], int]:
    """The same closed loop drawn twice (a CIRCLE on two layers) counts once; even-odd would erase it."""
    if len(loops) < 2:
        return loops, 0
    boxes = np.array([np.r_[r.min(axis=0), r.max(axis=0)] for r in loops])
    pairs = cKDTree(boxes).query_pairs(tol, p=np.inf, output_type="ndarray")
    drop = np.zeros(len(loops), dtype=bool)
    for i, j in sorted(map(tuple, pairs)):
        if drop[i] or drop[j]:
            continue
        a, b = LineString(np.vstack([loops[i], loops[i][:1]])), LineString(np.vstack([loops[j], loops[j][:1]]))
        if shapely.hausdorff_distance(a, b) <= tol:
            drop[j] = True
    return [r for r, d in zip(loops, drop) if not d], int(drop.sum())
