"""Loops of a DXF drawing: open curves joined end to end, repeated curves dropped, gaps named.

Part of the DXF reader (:mod:`medialaxis.planar.drawings.dxf`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from shapely.geometry import LineString, Point, Polygon

from medialaxis.errors import InvalidInputError

__all__ = ["chain", "along_loops", "drop_repeated_loops", "polygonal", "without_slivers", "MAX_GAPS_LISTED"]

#: Loose ends listed in the message of an open drawing.
MAX_GAPS_LISTED = 5


def polygonal(geom: Any) -> Any:
    """The polygons of a geometry, valid."""
    if not geom.is_valid:
        geom = shapely.make_valid(geom)
    if geom.geom_type in ("Polygon", "MultiPolygon"):
        return geom
    polys = [g for g in shapely.get_parts(geom) if g.geom_type in ("Polygon", "MultiPolygon") and g.area > 0]
    return shapely.union_all(polys) if polys else Polygon()


def without_slivers(region: Any, width: float) -> tuple[Any, int]:
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


def along_loops(pieces: list[np.ndarray], loops: list[np.ndarray], tol: float) -> np.ndarray:
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


def chain(
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


def drop_repeated_loops(loops: list[np.ndarray], tol: float) -> tuple[list[np.ndarray], int]:
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
