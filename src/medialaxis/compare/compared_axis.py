"""The axis a signature describes: its largest component, spurious terminal branches removed, and its scale."""

from __future__ import annotations

import numpy as np

from medialaxis.core import graph as _graph
from medialaxis.core.result import MedialAxis
from medialaxis.errors import EmptyShapeError, InvalidInputError

__all__ = ["compared_axis", "main_component", "drop_spurious", "edge_lengths", "terminal_protrusions"]


def edge_lengths(points: np.ndarray, edges: np.ndarray) -> np.ndarray:
    return np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1)


def _largest_component(points: np.ndarray, radii: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Keep the component sweeping the largest area; return (node indices, edges renumbered)."""
    n = len(points)
    count, labels = _graph.component_labels(n, edges)
    if count > 1:
        area = np.pi * radii**2  # an isolated node still sweeps its disc
        weight = np.zeros(count)
        np.maximum.at(weight, labels, area)
        if len(edges):
            sweep = edge_lengths(points, edges) * (radii[edges[:, 0]] + radii[edges[:, 1]])
            np.add.at(weight, labels[edges[:, 0]], sweep)
        keep = np.flatnonzero(labels == int(np.argmax(weight)))
    else:
        keep = np.arange(n)
    remap = np.full(n, -1, np.int64)
    remap[keep] = np.arange(len(keep))
    sub = remap[edges] if len(edges) else edges.reshape(0, 2)
    if len(sub):
        sub = sub[(sub >= 0).all(axis=1)]
    return keep, sub


def _scale(points: np.ndarray, radii: np.ndarray, edges: np.ndarray) -> float:
    sweep = float((edge_lengths(points, edges) * (radii[edges[:, 0]] + radii[edges[:, 1]])).sum()) if len(edges) else 0.0
    return float(np.sqrt(sweep + np.pi * float(radii.max()) ** 2))


def terminal_protrusions(points: np.ndarray, radii: np.ndarray, edges: np.ndarray) -> list[tuple[np.ndarray, float]]:
    """Terminal branches (junction first) and how far each protrudes past its junction's disc.

    A terminal branch from junction ``J`` protrudes by
    ``max_i(|p_i - p_J| + r_i) - r_J``: how far its discs reach past the disc
    at ``J``.
    """
    deg = _graph.degree(len(points), edges)
    out = []
    for chain in _graph.branches(len(points), edges):
        a, b = int(chain[0]), int(chain[-1])
        if deg[a] == 1 and deg[b] >= 3:
            chain = chain[::-1]
        elif not (deg[b] == 1 and deg[a] >= 3):
            continue
        junction = int(chain[0])
        reach = np.linalg.norm(points[chain] - points[junction], axis=1) + radii[chain]
        out.append((chain, float(reach.max() - radii[junction])))
    return out


def _prune_spurious(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, limit: float, max_endpoints: int
) -> np.ndarray:
    """Drop terminal branches that barely leave the disc of their junction.

    Each round removes, all at once, every terminal branch protruding less
    than ``limit`` (boundary noise), or, when none is but there are more
    than ``max_endpoints`` endpoints, the least protruding ones (ties
    together, so symmetric shapes stay symmetric). Rounds repeat on the
    remaining axis; a round that would leave no edge is not applied.
    """
    for _ in range(len(points)):
        n_ends = int((_graph.degree(len(points), edges) == 1).sum())
        terminal = terminal_protrusions(points, radii, edges)
        if n_ends <= 2 or not terminal:
            break
        values = np.array([value for _, value in terminal])
        drop = values < limit
        if not drop.any():
            if n_ends <= max_endpoints:
                break
            drop = values <= values.min() * (1 + 1e-6) + 1e-12 * (1 + abs(values).max())
        nodes = np.concatenate([terminal[k][0][1:] for k in np.flatnonzero(drop)])
        kept = edges[~np.isin(edges, nodes).any(axis=1)]
        if not len(kept):
            break
        edges = kept
    return edges


def main_component(ma: MedialAxis) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """``(points, radii, edges, scale)`` of the axis's component sweeping the largest area (self-loops dropped)."""
    if len(ma.points) == 0:
        raise EmptyShapeError("the medial axis is empty (no axis left after pruning): nothing to compare")
    if not (np.isfinite(ma.points).all() and np.isfinite(ma.radii).all()):
        raise InvalidInputError("the medial axis has NaN or infinite coordinates or radii")
    edges = np.asarray(ma.edges)
    edges = edges[edges[:, 0] != edges[:, 1]] if len(edges) else edges.reshape(0, 2)
    keep, edges = _largest_component(ma.points, ma.radii, edges)
    points, radii = np.array(ma.points[keep]), np.array(ma.radii[keep])
    if radii.max() <= 0:
        raise EmptyShapeError("the medial axis has no positive radius: the shape has no interior")
    return points, radii, edges, _scale(points, radii, edges)


def drop_spurious(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, scale: float, prune: float, max_endpoints: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(points, radii, edges)`` without the spurious terminal branches, renumbered (see :func:`_prune_spurious`)."""
    edges = _prune_spurious(points, radii, edges, prune * scale, max_endpoints)
    lone = np.zeros(len(points), bool)
    if not len(edges):
        lone[int(np.argmax(radii))] = True  # a disc: its axis is one point
    keep, edges = _graph.compact(len(points), edges, lone)
    return points[keep], radii[keep], edges


def compared_axis(ma: MedialAxis, prune: float, max_endpoints: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """``(points, radii, edges, scale)`` of the axis compared: largest component, spurious branches removed."""
    points, radii, edges, scale = main_component(ma)
    return (*drop_spurious(points, radii, edges, scale, prune, max_endpoints), scale)
