"""A table of branches (one row per chain between junctions and endpoints), as skan's ``summarize``.

Two column sets over the same rows: ours (``style="medialaxis"``, the
default) and skan's (``style="skan"``: the names, branch-type codes and
column order of ``skan.summarize(..., separator="_")``, so code written for
skan reads it). Needs pandas (``pip install pandas`` or ``medialaxis[table]``),
loaded on first use.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from medialaxis import _optional
from medialaxis.core import graph as _graph
from medialaxis.errors import InvalidInputError

if TYPE_CHECKING:  # pragma: no cover
    from medialaxis.core.result import MedialAxis

__all__ = ["branch_table", "BRANCH_KINDS", "STYLES"]

#: Branch kinds by the degrees of their two ends; the position is skan's
#: ``branch_type`` code (0 endpoint-endpoint, 1 junction-endpoint,
#: 2 junction-junction, 3 cycle).
BRANCH_KINDS = ("endpoint-endpoint", "endpoint-junction", "junction-junction", "cycle")

#: The column sets :func:`branch_table` knows.
STYLES = ("medialaxis", "skan")


def _weighted_mean_std(steps: np.ndarray, values: np.ndarray) -> tuple[float, float]:
    """Mean and standard deviation of ``values`` along a polyline, each point weighted by its half-steps."""
    weights = np.zeros(len(values))
    weights[1:] += 0.5 * steps
    weights[:-1] += 0.5 * steps
    if weights.sum() <= 0:
        return float(values.mean()), float(values.std())
    mean = float(np.average(values, weights=weights))
    return mean, float(np.sqrt(np.average((values - mean) ** 2, weights=weights)))


def _rows(ma: MedialAxis) -> list[dict[str, Any]]:
    """Per branch: ends, kind code, length, distances and radius figures (both styles read these)."""
    n = len(ma.points)
    degree = _graph.degree(n, ma.edges)
    labels = _graph.component_labels(n, ma.edges)[1]
    rows = []
    for branch in ma.branches():
        idx = branch.indices
        start, end = int(idx[0]), int(idx[-1])
        steps = np.linalg.norm(np.diff(branch.points, axis=0), axis=1)
        length = float(steps.sum())
        r = branch.radii
        if branch.is_cycle:
            code = 3
        else:
            code = int(degree[start] >= 3) + int(degree[end] >= 3)
        mean, std = _weighted_mean_std(steps, r)
        rows.append({"start": start, "end": end, "code": code, "component": int(labels[start]), "n_points": len(idx),
                     "length": length, "euclidean": float(np.linalg.norm(branch.points[-1] - branch.points[0])),
                     "radius_min": float(r.min()), "radius_mean": mean, "radius_std": std,
                     "radius_max": float(r.max()), "src": branch.points[0], "dst": branch.points[-1]})
    return rows


def _medialaxis_table(pd: Any, ma: MedialAxis, rows: list[dict[str, Any]]) -> Any:
    dim = ma.points.shape[1]
    columns = ["start", "end", "kind", "n_points", "length", "euclidean", "radius_min", "radius_mean", "radius_max"]
    columns += [f"{side}_{k}" for side in ("start", "end") for k in range(dim)]
    out = []
    for row in rows:
        line = {key: row[key] for key in columns[:9] if key != "kind"}
        line["kind"] = BRANCH_KINDS[row["code"]]
        for k in range(dim):
            line[f"start_{k}"] = float(row["src"][k])
            line[f"end_{k}"] = float(row["dst"][k])
        out.append(line)
    return pd.DataFrame(out, columns=columns)


def _skan_table(pd: Any, ma: MedialAxis, rows: list[dict[str, Any]]) -> Any:
    dim = ma.points.shape[1]
    spacing = ma.metadata.get("spacing") if "image_shape" in ma.metadata else None
    _, skeleton_id = np.unique(np.asarray([row["component"] for row in rows], np.int64), return_inverse=True)
    table: dict[str, Any] = {
        "skeleton_id": skeleton_id.reshape(-1).astype(np.int64),
        "node_id_src": np.asarray([row["start"] for row in rows], np.int64),
        "node_id_dst": np.asarray([row["end"] for row in rows], np.int64),
        "branch_distance": np.asarray([row["length"] for row in rows], np.float64),
        "branch_type": np.asarray([row["code"] for row in rows], np.int64),
        "mean_pixel_value": np.asarray([row["radius_mean"] for row in rows], np.float64),
        "stdev_pixel_value": np.asarray([row["radius_std"] for row in rows], np.float64),
    }
    src = np.asarray([row["src"] for row in rows], np.float64).reshape(-1, dim)
    dst = np.asarray([row["dst"] for row in rows], np.float64).reshape(-1, dim)
    if spacing is not None:
        step = np.broadcast_to(np.asarray(spacing, np.float64), (dim,))
        for name, ends in (("src", src), ("dst", dst)):
            for k in range(dim):
                table[f"image_coord_{name}_{k}"] = ends[:, k] / step[k]
    for name, ends in (("src", src), ("dst", dst)):
        for k in range(dim):
            table[f"coord_{name}_{k}"] = ends[:, k]
    table["euclidean_distance"] = np.asarray([row["euclidean"] for row in rows], np.float64)
    return pd.DataFrame(table)


def branch_table(ma: MedialAxis, *, style: str = "medialaxis") -> Any:
    """One row per branch of ``ma``'s edge graph.

    Parameters
    ----------
    ma : MedialAxis
    style : {"medialaxis", "skan"}
        The column set. Both have the same rows in the same order (those of
        :meth:`MedialAxis.branches`).

        ``"medialaxis"``: ``start``, ``end`` (point indices), ``kind`` (one
        of :data:`BRANCH_KINDS`), ``n_points``, ``length`` (along the chain;
        the lengths sum to the axis length), ``euclidean`` (between the
        ends), ``radius_min``, ``radius_mean`` (mean over the chain's
        length), ``radius_max``, and the ends' coordinates ``start_0``,
        ``start_1`` (, ``start_2``), ``end_0`` ... in the result's
        coordinate order.

        ``"skan"``: the columns of ``skan.summarize(skeleton,
        separator="_")`` in its order: ``skeleton_id`` (connected component,
        numbered from 0), ``node_id_src``, ``node_id_dst`` (point indices),
        ``branch_distance`` (= ``length``), ``branch_type`` (0
        endpoint-endpoint, 1 junction-endpoint, 2 junction-junction, 3
        cycle), ``mean_pixel_value`` and ``stdev_pixel_value`` (the radius
        along the branch, weighted by length: what skan gives for the image
        ``skeleton * distance``), for image results ``image_coord_src_0``
        ... ``image_coord_dst_1`` (pixel index units, fractional), then
        ``coord_src_0`` ... ``coord_dst_1`` (the result's coordinates,
        physical units) and ``euclidean_distance``.

    Returns
    -------
    pandas.DataFrame

    Raises
    ------
    MissingDependencyError
        pandas is not installed.
    InvalidInputError
        ``style`` is not one of :data:`STYLES`.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> image = np.zeros((60, 90), bool); image[15:45, 10:80] = True
    >>> table = mx.medial_axis(image).summary()
    >>> sorted(table["kind"].value_counts().items())
    [('endpoint-junction', 4), ('junction-junction', 1)]
    >>> skan_table = mx.medial_axis(image).summary(style="skan")
    >>> sorted(skan_table["branch_type"].tolist())
    [1, 1, 1, 1, 2]
    """
    if style not in STYLES:
        raise InvalidInputError(f"style must be one of {', '.join(map(repr, STYLES))}, got {style!r}")
    pd = _optional.require("pandas", "pandas")
    rows = _rows(ma)
    return _skan_table(pd, ma, rows) if style == "skan" else _medialaxis_table(pd, ma, rows)
