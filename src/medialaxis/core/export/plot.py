"""Matplotlib pictures of a result (imported lazily: matplotlib is slow to load)."""

from __future__ import annotations

import io
from typing import Any

import numpy as np

from medialaxis.core.frames import y_down
from medialaxis.errors import InvalidInputError

__all__ = ["plot", "plot_axis", "png_bytes", "draw_region", "draw_axis"]


def _xy(ma: Any, pts: np.ndarray) -> np.ndarray:
    # Raster results are (row, col): draw col to the right and row downwards.
    return pts[:, ::-1] if ma.frame == "image" else pts


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
    segs = list(xy[ma.edges]) if len(ma.edges) else []
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


def plot(ma: Any, ax: Any = None, *, shape: bool = True, color_by_radius: bool = True, nodes: bool = True,
         colorbar: bool = True, title: bool = True) -> Any:
    """Draw ``ma`` on ``ax`` (or on new axes) and return the axes. See :meth:`MedialAxis.plot`."""
    if ax is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(7, 6) if ma.dim == 3 else (6, 6))
        ax = fig.add_subplot(projection="3d") if ma.dim == 3 else fig.add_subplot()
    is_3d = hasattr(ax, "zaxis")
    if ma.dim == 3 and not is_3d:
        raise InvalidInputError("a 3D result is drawn on 3D axes: fig.add_subplot(projection='3d')")
    if ma.dim == 2 and is_3d:
        raise InvalidInputError("a planar result is drawn on 2D axes, not on 3D ones")
    draw = _draw_3d if ma.dim == 3 else _draw_2d
    draw(ax, ma, shape=shape, color_by_radius=color_by_radius, nodes=nodes, colorbar=colorbar, title=title)
    return ax


def plot_axis(ma: Any, ax: Any = None) -> Any:
    """Figure of the axis coloured by radius, over its shape when known (2D) or in 3D."""
    return plot(ma, ax).figure


def png_bytes(ma: Any, *, dpi: int = 80) -> bytes:
    """The picture of :func:`plot` as PNG bytes, on a figure pyplot does not know (for notebooks)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 6) if ma.dim == 3 else (6, 6))
    FigureCanvasAgg(fig)
    plot(ma, fig.add_subplot(projection="3d") if ma.dim == 3 else fig.add_subplot())
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    return buffer.getvalue()


def _draw_2d(ax: Any, ma: Any, *, shape: bool, color_by_radius: bool, nodes: bool, colorbar: bool,
             title: bool) -> None:
    if shape and ma.shape is not None:
        draw_region(ax, ma, ma.shape)
    lc = draw_axis(ax, ma, color_by_radius=color_by_radius)
    if colorbar and color_by_radius and len(ma.edges):
        ax.figure.colorbar(lc, ax=ax, shrink=0.7, label="radius")
    xy = _xy(ma, ma.points)
    if nodes and len(ma.junctions):
        ax.scatter(*xy[ma.junctions].T, s=14, c="k", zorder=3, label="junctions")
    if nodes and len(ma.endpoints):
        ax.scatter(*xy[ma.endpoints].T, s=14, c="#27ae60", zorder=3, label="endpoints")
    ax.set_aspect("equal")
    ax.autoscale_view()
    if y_down(ma) and not ax.yaxis_inverted():  # images and SVG drawings: y grows downwards
        ax.invert_yaxis()
    if title:
        ax.set_title(f"{ma.metadata.get('method', '')}: {len(ma.points)} points, {len(ma.branches())} branches")


def _draw_3d(ax: Any, ma: Any, *, shape: bool, color_by_radius: bool, nodes: bool, colorbar: bool, title: bool,
             max_faces: int = 40000, max_shell_faces: int = 8000, max_spheres: int = 400) -> None:
    """3D picture: input shell, medial faces and curves coloured by radius, spheres, one scale on all axes."""
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    from medialaxis.core.export import mesh_files, scene3d

    p, r = ma.points, ma.radii
    norm = Normalize(float(r.min()) if len(r) else 0.0, float(r.max()) if len(r) and r.max() > r.min() else 1.0)
    cmap = colormaps["viridis"]

    def colours(values: np.ndarray) -> Any:
        return cmap(norm(values)) if color_by_radius else "#c0392b"

    drawn = [p]
    shell = scene3d.shell_of(ma) if shape else None
    if shell is not None:
        sv, sf = scene3d.cluster_decimate(*shell, max_shell_faces)
        ax.add_collection3d(Poly3DCollection(sv[sf], facecolor=(0.6, 0.6, 0.6, 0.06), edgecolor="none"))
        drawn.append(sv)
    faces = ma.faces
    if len(faces) > max_faces:
        faces = faces[np.random.default_rng(0).choice(len(faces), max_faces, replace=False)]
    if len(faces):
        ax.add_collection3d(Poly3DCollection(p[faces], facecolor=colours(r[faces].mean(axis=1)), edgecolor="none"))
    curves = mesh_files.curve_edges(ma)
    if len(curves):
        ax.add_collection3d(Line3DCollection(p[curves], colors=colours(r[curves].mean(axis=1)), linewidths=1.2))
    lone = ma.degree == 0
    if lone.any():
        ax.scatter(*p[lone].T, c=colours(r[lone]), s=2, depthshade=False)
    if nodes and len(curves) and len(ma.junctions):
        ax.scatter(*p[ma.junctions].T, s=10, c="k", depthshade=False, label="junctions")
    if ma.metadata.get("simplified") and len(p):
        order = np.argsort(-r, kind="stable")[:max_spheres]
        bv, bf, br = scene3d.sphere_meshes(p[order], r[order])
        sphere_colours = cmap(norm(br[bf[:, 0]]))
        sphere_colours[:, 3] = 0.15
        ax.add_collection3d(Poly3DCollection(bv[bf], facecolor=sphere_colours, edgecolor="none"))
        drawn.append(bv)
    ranges, ratio = scene3d.equal_ranges(*drawn)
    ax.set(xlim=ranges[0], ylim=ranges[1], zlim=ranges[2], xlabel="x", ylabel="y", zlabel="z")
    ax.set_box_aspect(ratio)
    if colorbar and color_by_radius:
        ax.figure.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax, shrink=0.6, pad=0.1, label="radius")
    if title:
        kind = "spheres" if ma.metadata.get("simplified") else "points"
        ax.set_title(f"{ma.metadata.get('method', '')}: {len(p)} {kind}, {len(ma.faces)} faces, "
                     f"{len(curves)} curve edges")
