"""A table of branches (one row per chain between junctions and endpoints), as skan's ``summarize``.

Needs pandas (``pip install pandas`` or ``medialaxis[table]``), loaded on first use.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from medialaxis import _optional
from medialaxis.core import graph as _graph

if TYPE_CHECKING:  # pragma: no cover
    from medialaxis.core.result import MedialAxis

__all__ = ["branch_table", "BRANCH_KINDS"]

#: Branch kinds by the degrees of their two ends (skan's branch types 0-3).
BRANCH_KINDS = ("endpoint-endpoint", "endpoint-junction", "junction-junction", "cycle")


def branch_table(ma: MedialAxis) -> Any:
    """One row per branch of ``ma``'s edge graph.

    Parameters
    ----------
    ma : MedialAxis

    Returns
    -------
    pandas.DataFrame
        Columns: ``start``, ``end`` (point indices), ``kind`` (one of
        :data:`BRANCH_KINDS`), ``n_points``, ``length`` (along the chain;
        the lengths sum to the axis length), ``euclidean`` (between the
        ends), ``radius_min``, ``radius_mean`` (mean over the chain's length),
        ``radius_max``, and the ends' coordinates ``start_0``, ``start_1``
        (, ``start_2``), ``end_0`` ... in the result's coordinate order.

    Raises
    ------
    MissingDependencyError
        pandas is not installed.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> image = np.zeros((60, 90), bool); image[15:45, 10:80] = True
    >>> table = mx.medial_axis(image).summary()
    >>> sorted(table["kind"].value_counts().items())
    [('endpoint-junction', 4), ('junction-junction', 1)]
    """
    pd = _optional.require("pandas", "pandas")
    degree = _graph.degree(len(ma.points), ma.edges)
    rows = []
    for branch in ma.branches():
        idx = branch.indices
        start, end = int(idx[0]), int(idx[-1])
        steps = np.linalg.norm(np.diff(branch.points, axis=0), axis=1)
        length = float(steps.sum())
        r = branch.radii
        mean = float(np.sum(steps * 0.5 * (r[1:] + r[:-1])) / length) if length > 0 else float(r.mean())
        if branch.is_cycle:
            kind = BRANCH_KINDS[3]
        else:
            kind = BRANCH_KINDS[int(degree[start] >= 3) + int(degree[end] >= 3)]
        row = {"start": start, "end": end, "kind": kind, "n_points": len(idx), "length": length,
               "euclidean": float(np.linalg.norm(branch.points[-1] - branch.points[0])),
               "radius_min": float(r.min()), "radius_mean": mean, "radius_max": float(r.max())}
        for k in range(ma.points.shape[1]):
            row[f"start_{k}"] = float(branch.points[0, k])
            row[f"end_{k}"] = float(branch.points[-1, k])
        rows.append(row)
    columns = ["start", "end", "kind", "n_points", "length", "euclidean", "radius_min", "radius_mean", "radius_max"]
    columns += [f"{side}_{k}" for side in ("start", "end") for k in range(ma.points.shape[1])]
    return pd.DataFrame(rows, columns=columns)
