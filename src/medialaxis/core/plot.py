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
        return _plot_3d(ma)
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


def _plot_3d(ma: Any, *, max_faces: int = 40000, max_shell_faces: int = 8000, max_spheres: int = 400) -> Any:
    """3D picture: input shell, medial faces and curves coloured by radius, spheres, one scale on all axes."""
    import matplotlib.pyplot as plt
    from matplotlib import colormaps
    from matplotlib.colors import Normalize
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    from medialaxis.core import mesh_files, scene3d

    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    p, r = ma.points, ma.radii
    norm = Normalize(float(r.min()) if len(r) else 0.0, float(r.max()) if len(r) and r.max() > r.min() else 1.0)
    cmap = colormaps["viridis"]
    drawn = [p]
    shell = scene3d.shell_of(ma)
    if shell is not None:
        sv, sf = scene3d.cluster_decimate(*shell, max_shell_faces)
        ax.add_collection3d(Poly3DCollection(sv[sf], facecolor=(0.6, 0.6, 0.6, 0.06), edgecolor="none"))
        drawn.append(sv)
    faces = ma.faces
    if len(faces) > max_faces:
        faces = faces[np.random.default_rng(0).choice(len(faces), max_faces, replace=False)]
    if len(faces):
        ax.add_collection3d(Poly3DCollection(p[faces], facecolor=cmap(norm(r[faces].mean(axis=1))), edgecolor="none"))
    curves = mesh_files.curve_edges(ma)
    if len(curves):
        ax.add_collection3d(Line3DCollection(p[curves], colors=cmap(norm(r[curves].mean(axis=1))), linewidths=1.2))
    lone = ma.degree == 0
    if lone.any():
        ax.scatter(*p[lone].T, c=cmap(norm(r[lone])), s=2, depthshade=False)
    if ma.metadata.get("simplified") and len(p):
        order = np.argsort(-r, kind="stable")[:max_spheres]
        bv, bf, br = scene3d.sphere_meshes(p[order], r[order])
        colours = cmap(norm(br[bf[:, 0]]))
        colours[:, 3] = 0.15
        ax.add_collection3d(Poly3DCollection(bv[bf], facecolor=colours, edgecolor="none"))
        drawn.append(bv)
    ranges, ratio = scene3d.equal_ranges(*drawn)
    ax.set(xlim=ranges[0], ylim=ranges[1], zlim=ranges[2], xlabel="x", ylabel="y", zlabel="z")
    ax.set_box_aspect(ratio)
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, shrink=0.6, pad=0.1, label="radius")
    kind = "spheres" if ma.metadata.get("simplified") else "points"
    ax.set_title(f"{ma.metadata.get('method', '')}: {len(p)} {kind}, {len(ma.faces)} faces, {len(curves)} curve edges")
    return fig
