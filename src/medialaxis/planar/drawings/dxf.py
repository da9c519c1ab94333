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
   :func:`medialaxis.planar.drawings.fill.fill_rings`), united with the filled
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
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import Polygon

from medialaxis._optional import require
from medialaxis.core.validate import check_coordinates, check_number
from medialaxis.errors import EmptyShapeError, InputFileError, InvalidInputError
from medialaxis.planar.drawings.dxf_entities import Gatherer, attr, describe, flatten
from medialaxis.planar.drawings.dxf_loops import (
    MAX_GAPS_LISTED,
    along_loops,
    chain,
    drop_repeated_loops,
    polygonal,
    without_slivers,
)
from medialaxis.planar.drawings.fill import fill_rings

__all__ = ["read_dxf", "DEFAULT_TOLERANCE", "JOIN_FRACTION"]

#: Default chord tolerance, as a fraction of the largest side of the bounding
#: box of the entities read.
DEFAULT_TOLERANCE = 1e-4
#: Smallest join tolerance, as a fraction of that side: curve ends closer
#: than ``max(JOIN_FRACTION * size, tolerance)`` are joined.
JOIN_FRACTION = 1e-6


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
        raise InputFileError(f"cannot read {where}: {describe(exc)}") from exc

    msp = doc.modelspace()
    table = {layer.dxf.name.lower(): layer for layer in doc.layers}
    wanted = None
    if layers is not None:
        known = {name: layer.dxf.name for name, layer in table.items()}
        for entity in msp:
            name = attr(entity, "layer", "0") or "0"
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
    gather = Gatherer(where, wanted, hidden_layers, frozen_layers)
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

    loops, pieces, piece_labels, fills, n_fill_rings = flatten(ezdxf, gather, chord, join)

    duplicate_tolerance = 2.0 * join
    along = along_loops(pieces, loops, duplicate_tolerance)
    chained, n_repeated = chain(pieces, piece_labels, along, join, duplicate_tolerance, where)
    loops, n_same = drop_repeated_loops(loops + chained, duplicate_tolerance)

    parts = [fill_rings(loops, "evenodd")] if loops else []
    parts += fills
    parts = [p for p in parts if not p.is_empty]
    region = polygonal(shapely.union_all(parts)) if parts else Polygon()
    region, n_slivers = without_slivers(region, JOIN_FRACTION * size)
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


def _layer_phrase(layers: Sequence[str] | None) -> str:
    if layers is None:
        return "the layers shown (on and thawed)"
    return "layers " + ", ".join(map(repr, layers))


def _skipped_phrase(gather: Gatherer) -> str:
    notes = []
    if gather.skipped:
        notes.append("skipped " + ", ".join(f"{n} {kind}" for kind, n in sorted(gather.skipped.items())))
    if gather.hidden:
        notes.append(f"{gather.hidden} entities hidden (layer off or frozen, or invisible)")
    return f" ({'; '.join(notes)})" if notes else ""




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
        raise InputFileError(f"cannot measure the entities of {where}: {describe(exc)}") from exc
    if not box.has_data:
        return 0.0
    corners = np.array([box.extmin.xyz, box.extmax.xyz], dtype=np.float64)
    check_coordinates(corners[:, :2], where)
    with np.errstate(over="ignore"):
        size = float(np.max(corners[1, :2] - corners[0, :2]))
    if not math.isfinite(size):
        raise InvalidInputError(f"{where}: the drawing spans {size}; coordinates this large cannot be measured")
    return size
