"""Matplotlib pictures of a result (imported lazily: matplotlib is slow to load)."""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["plot_axis", "draw_region", "draw_axis"]


def _xy(ma: Any, pts: np.ndarray) -> np.ndarray:
    # Raster results are (row, col): draw col to the right and row downwards.
    return pts[:, ::-1] if "image_shape" in ma.metadata else pts


def draw_region(ax: Any, ma: Any, region: Any, **style: Any) -> None:
    """Fill ``region`` (shapely) on ``ax`` in the result's picture orientation."""
    import shapely
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    verts, codes = [], []
    for poly in shapely.get_parts(region):
        for ring in [poly.exterior, *poly.interiors]:
            xy = _xy(ma, np.asarray(ring.coords))
            verts.extend(xy.tolist())
            codes.extend([MplPath.MOVETO] + [MplPath.LINETO] * (len(xy) - 2) + [MplPath.CLOSEPOLY])
    if verts:
        style = {"facecolor": "#dde6f0", "edgecolor": "#445", "lw": 0.8, **style}
        ax.add_patch(PathPatch(MplPath(verts, codes), **style))


def draw_axis(ax: Any, ma: Any, *, color_by_radius: bool = True, lw: float = 1.5, color: str = "#c0392b") -> Any:
    """Draw the axis edges of a planar result; returns the LineCollection."""
    from matplotlib.collections import LineCollection

    xy = _xy(ma, ma.points)
    segs = xy[ma.edges] if len(ma.edges) else np.empty((0, 2, 2))
    lc = LineCollection(segs, linewidths=lw, cmap="viridis" if color_by_radius else None)
    if color_by_radius and len(ma.edges):
        lc.set_array(ma.radii[ma.edges].mean(axis=1))
    else:
        lc.set_color(color)
    ax.add_collection(lc)
    lone = ma.degree == 0
    if lone.any():
        ax.scatter(xy[lone, 0], xy[lone, 1], c=ma.radii[lone] if color_by_radius else color, s=12, zorder=3)
    return lc


def plot_axis(ma: Any, ax: Any = None) -> Any:
    """Figure of the axis coloured by radius, over its shape when known (2D) or in 3D."""
    import matplotlib.pyplot as plt

    if ma.dim == 3:
        fig = plt.figure(figsize=(6, 6))
        ax3 = fig.add_subplot(projection="3d")
        p = ma.points
        if len(ma.faces):
            ax3.plot_trisurf(p[:, 0], p[:, 1], p[:, 2], triangles=ma.faces, color="#c0392b", alpha=0.6)
        for a, b in ma.edges[:20000]:
            ax3.plot(*p[[a, b]].T, color="#555", lw=0.6)
        sc = ax3.scatter(p[:, 0], p[:, 1], p[:, 2], c=ma.radii, s=4, cmap="viridis")
        fig.colorbar(sc, ax=ax3, shrink=0.6, label="radius")
        return fig
    fig = ax.figure if ax is not None else plt.figure(figsize=(6, 6))
    ax = ax if ax is not None else fig.add_subplot()
    if ma.shape is not None:
        draw_region(ax, ma, ma.shape)
    lc = draw_axis(ax, ma)
    if len(ma.edges):
        fig.colorbar(lc, ax=ax, shrink=0.7, label="radius")
    xy = _xy(ma, ma.points)
    if len(ma.junctions):
        ax.scatter(*xy[ma.junctions].T, s=14, c="k", zorder=3, label="junctions")
    if len(ma.endpoints):
        ax.scatter(*xy[ma.endpoints].T, s=14, c="#27ae60", zorder=3, label="endpoints")
    ax.set_aspect("equal")
    ax.autoscale_view()
    if "image_shape" in ma.metadata:
        ax.invert_yaxis()
    ax.set_title(f"{ma.metadata.get('method', '')}: {len(ma.points)} points, {len(ma.branches())} branches")
    return fig
