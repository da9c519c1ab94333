"""Tables of a result: branches of curves (one row per chain between junctions and endpoints, as skan's
``summarize``), sheets of surfaces, classes of voxel sets.

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

__all__ = ["branch_table", "sheet_table", "voxel_count_table", "BRANCH_KINDS", "STYLES"]

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
    spacing = ma.metadata.get("spacing") if ma.frame == "image" else None
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


def sheet_table(ma: MedialAxis) -> Any:
    """One row per sheet of a surface result: its triangles joined across the edges two of them share.

    Columns: ``sheet`` (numbered from 0, largest area first), ``faces``,
    ``area``, ``thickness_min``, ``thickness_mean`` (area-weighted over its
    corners), ``thickness_max`` (thickness: twice the radius),
    ``free_edge_length`` (sides of one triangle only: where the sheet ends)
    and ``junction_edge_length`` (sides of three or more triangles: where
    sheets meet). Curve pieces of the result are not sheets.

    Examples
    --------
    >>> import medialaxis as mx
    >>> square = mx.MedialAxis([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [0.5] * 4, faces=[[0, 1, 2], [0, 2, 3]])
    >>> row = sheet_table(square).iloc[0]
    >>> float(row["area"]), float(row["thickness_mean"]), float(row["free_edge_length"])
    (1.0, 1.0, 4.0)
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    pd = _optional.require("pandas", "pandas")
    faces = np.asarray(ma.faces, np.int64)
    k, n = len(faces), len(ma.points)
    sides = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, side, uses = np.unique(sides[:, 0] * n + sides[:, 1], return_inverse=True, return_counts=True)
    side = side.reshape(-1)
    owner = np.repeat(np.arange(k), 3)
    # triangles on a side of exactly two: joined (the side's two entries, after sorting by side)
    order = np.argsort(side, kind="stable")
    pair = (uses[side[order]] == 2)[:-1] & (side[order][1:] == side[order][:-1])
    a, b = owner[order][:-1][pair], owner[order][1:][pair]
    _, label = connected_components(coo_matrix((np.ones(len(a)), (a, b)), shape=(k, k)), directed=False)
    tri = np.asarray(ma.points, np.float64)[faces]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    length = np.linalg.norm(ma.points[sides[:, 0]] - ma.points[sides[:, 1]], axis=1)
    thick = 2.0 * np.asarray(ma.radii, np.float64)[faces]
    n_sheets = int(label.max()) + 1 if k else 0
    sheet_area = np.bincount(label, area, n_sheets)
    rows = {
        "faces": np.bincount(label, minlength=n_sheets),
        "area": sheet_area,
        "thickness_min": np.full(n_sheets, np.inf),
        "thickness_mean": np.bincount(label, area * thick.mean(axis=1), n_sheets) / np.maximum(sheet_area, 1e-300),
        "thickness_max": np.zeros(n_sheets),
        "free_edge_length": np.bincount(label[owner], length * (uses[side] == 1), n_sheets),
        # a junction side is counted once for each sheet it bounds
        "junction_edge_length": np.bincount(label[owner], length * (uses[side] >= 3), n_sheets),
    }
    np.minimum.at(rows["thickness_min"], label, thick.min(axis=1))
    np.maximum.at(rows["thickness_max"], label, thick.max(axis=1))
    table = pd.DataFrame(rows).sort_values("area", ascending=False, kind="stable").reset_index(drop=True)
    table.insert(0, "sheet", np.arange(n_sheets))
    return table


def voxel_count_table(ma: MedialAxis) -> Any:
    """One row per class of voxel of a voxel set (``extras["voxel_kind"]``, named by ``metadata["voxel_kinds"]``).

    Columns: ``kind``, ``voxels``, ``radius_min``, ``radius_mean``,
    ``radius_max``; one row ``"all"`` when the result has no classes.
    """
    pd = _optional.require("pandas", "pandas")
    radii = np.asarray(ma.radii, np.float64)
    codes = np.asarray(ma.extras["voxel_kind"], np.int64) if "voxel_kind" in ma.extras else np.zeros(len(radii), np.int64)
    names = ma.metadata.get("voxel_kinds") if "voxel_kind" in ma.extras else ("all",)
    rows = []
    for code in np.unique(codes) if len(codes) else []:
        r = radii[codes == code]
        name = names[code] if names is not None and 0 <= code < len(names) else str(int(code))
        rows.append({"kind": name, "voxels": len(r), "radius_min": float(r.min()), "radius_mean": float(r.mean()),
                     "radius_max": float(r.max())})
    return pd.DataFrame(rows, columns=["kind", "voxels", "radius_min", "radius_mean", "radius_max"])
