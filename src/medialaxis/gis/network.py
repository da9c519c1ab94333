"""An axis as a river network: its branches with their end nodes, and stations along them.

RivGraph (Schwenk, Piliouras, Rowland. Determining flow directions in river
channel networks using planform morphology and topology. Earth Surface
Dynamics 8, 2020, doi:10.5194/esurf-8-87-2020) and GRWL (Allen, Pavelsky.
Global extent of rivers and streams. Science 361, 2018,
doi:10.1126/science.aat0636) describe a channel network by its links (one per
branch, with widths) between nodes that are channel ends or junctions, and
its centre line by stations that carry the width. Both are read here from the
axis's points, radii and edges, already in map coordinates.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from medialaxis.core import graph as _graph

__all__ = ["BRANCH_COLUMNS", "STATION_COLUMNS", "NODE_KINDS", "branch_table", "branch_stations"]

#: Columns of :func:`branch_table`, the geometry (a LineString per branch) apart.
BRANCH_COLUMNS = ("branch", "component", "start_node", "end_node", "start_kind", "end_kind", "length",
                  "width_min", "width_mean", "width_max")

#: Columns of :func:`branch_stations`: the branch, the distance along it from its
#: start, the width (twice the radius) and the station's map coordinates.
STATION_COLUMNS = ("branch", "distance", "width", "x", "y")

#: Kind of a node by its degree in the axis graph: a channel end (1), a
#: junction (3 or more), or the one node of a closed loop without junction.
NODE_KINDS = ("end", "junction", "loop")


def _kind(degree: int) -> str:
    return "end" if degree == 1 else "junction" if degree >= 3 else "loop"


def _station_weights(steps: np.ndarray) -> np.ndarray:
    """Each vertex of a polyline weighted by half of each step next to it."""
    weights = np.zeros(len(steps) + 1)
    weights[1:] += 0.5 * steps
    weights[:-1] += 0.5 * steps
    return weights


def branch_table(points: np.ndarray, radii: np.ndarray, edges: np.ndarray) -> tuple[dict[str, list[Any]], list[Any]]:
    """One row per branch of the axis: columns of :data:`BRANCH_COLUMNS`, and the branches' polylines.

    Nodes are the points where branches end (degree 1) or meet (degree 3 or
    more), numbered 0, 1, ... in the order of the points; ``width_mean`` is
    the mean of twice the radius along the branch's length.
    """
    n = len(points)
    degree = _graph.degree(n, edges)
    labels = _graph.component_labels(n, edges)[1]
    chains = _graph.branches(n, edges)
    ends = np.unique(np.concatenate([[c[0], c[-1]] for c in chains])) if chains else np.empty(0, np.int64)
    node = {int(k): j for j, k in enumerate(ends)}
    columns: dict[str, list[Any]] = {name: [] for name in BRANCH_COLUMNS}
    lines = []
    for k, chain in enumerate(chains):
        xy, r = points[chain], 2.0 * radii[chain]
        steps = np.linalg.norm(np.diff(xy, axis=0), axis=1)
        weights = _station_weights(steps)
        start, end = int(chain[0]), int(chain[-1])
        row = (k, int(labels[start]), node[start], node[end], _kind(int(degree[start])), _kind(int(degree[end])),
               float(steps.sum()), float(r.min()),
               float(np.average(r, weights=weights)) if weights.sum() > 0 else float(r.mean()), float(r.max()))
        for name, value in zip(BRANCH_COLUMNS, row):
            columns[name].append(value)
        lines.append(xy)
    return columns, lines


def branch_stations(points: np.ndarray, radii: np.ndarray, edges: np.ndarray, step: float | None = None
                    ) -> dict[str, np.ndarray]:
    """Stations along every branch: columns of :data:`STATION_COLUMNS`.

    ``step`` None: one station per vertex of the axis (a junction is a
    station of each branch that meets there). A positive ``step``: stations
    every ``step`` along each branch from its start, and one at its end, the
    position and width interpolated linearly between the vertices.
    """
    out: dict[str, list[np.ndarray]] = {name: [] for name in STATION_COLUMNS}
    for k, chain in enumerate(_graph.branches(len(points), edges)):
        xy, width = points[chain], 2.0 * radii[chain]
        distance = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
        if step is not None:
            at = np.unique(np.append(np.arange(0.0, distance[-1], step), distance[-1]))
            xy = np.column_stack([np.interp(at, distance, xy[:, 0]), np.interp(at, distance, xy[:, 1])])
            width, distance = np.interp(at, distance, width), at
        for name, values in zip(STATION_COLUMNS, (np.full(len(distance), k), distance, width, xy[:, 0], xy[:, 1])):
            out[name].append(values)
    return {name: np.concatenate(v) if v else np.empty(0) for name, v in out.items()}
