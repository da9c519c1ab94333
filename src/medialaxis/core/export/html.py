"""Interactive pages of a result (3D, and 2D in the source's frame): light, offline, one viewer library per folder.

A page holds its geometry as compressed binary arrays (float32 coordinates,
32-bit indices, zlib-deflated, base64) that a few lines of script inflate
in the browser (``DecompressionStream``: Chromium 80+, Firefox 113+,
Safari 16.4+) before plotly.js draws them. plotly.js itself is not inlined:
``viewer="folder"`` (default) copies it once into the page's folder as
``plotly-<version>.min.js`` (from the installed plotly package; pages in the
same folder share it, keep them together when moving them);
``viewer="inline"`` embeds it for a single file that travels alone (about
4.7 MB more). No page loads anything from the network.

The page draws the medial faces coloured by radius (legend and colour bar
apart), the medial curves and lone points, the input as a translucent shell
(``ma.shape`` or ``surface=``; thinned to ``max_shell_faces``), the spheres
of a simplified result, on axes with one scale. A 2D result's page draws the shape and the axis
coloured by radius (:func:`planar_page`).
"""

from __future__ import annotations

import base64
import json
import os
import zlib
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.core.export import mesh_files, scene3d
from medialaxis.core.frames import from_image, plane_xy, y_down
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InvalidInputError, MissingDependencyError

__all__ = ["Page", "medial_page", "planar_page", "write_html", "write_page"]

VIEWERS = ("folder", "inline")
COLORSCALE = "Viridis"

_LOADER = """
(async () => {
  const note = (text) => { document.getElementById('medialaxis-plot').innerText = text; };
  if (typeof Plotly === 'undefined') {
    note('The viewer library %(library)s was not found next to this page: keep the page in the folder it was written to.');
    return;
  }
  if (typeof DecompressionStream === 'undefined') {
    note('This browser cannot inflate the page data (DecompressionStream): use a current Chromium, Firefox or Safari.');
    return;
  }
  const spec = JSON.parse(document.getElementById('medialaxis-data').textContent);
  const types = {f4: Float32Array, i4d: Int32Array, u1: Uint8Array};
  const arrays = await Promise.all(spec.blobs.map(async (blob) => {
    const bytes = Uint8Array.from(atob(blob.data), (c) => c.charCodeAt(0));
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
    const values = new types[blob.dtype](await new Response(stream).arrayBuffer());
    if (blob.dtype === 'i4d') for (let n = 1; n < values.length; n++) values[n] += values[n - 1];
    return values;
  }));
  const fill = (node) => {
    if (Array.isArray(node)) return node.map(fill);
    if (node && typeof node === 'object') {
      if ('__blob' in node) return arrays[node.__blob];
      const out = {};
      for (const key in node) out[key] = fill(node[key]);
      return out;
    }
    return node;
  };
  const figure = fill(spec.figure);
  await Plotly.newPlot('medialaxis-plot', figure.data, figure.layout, {responsive: true, displaylogo: false});
  if (figure.frames && figure.frames.length) await Plotly.addFrames('medialaxis-plot', figure.frames);
  document.body.dataset.rendered = 'yes';
})();
"""

_TEMPLATE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>%(title)s</title>
<style>html, body {margin: 0; height: 100%%; font-family: sans-serif;} #medialaxis-plot {width: 100%%; height: 100vh;}</style>
%(library_tag)s
</head>
<body>
<div id="medialaxis-plot"></div>
<script id="medialaxis-data" type="application/json">%(data)s</script>
<script>%(loader)s</script>
</body>
</html>
"""


class Page:
    """A plotly figure as plain dicts whose large arrays travel as compressed blobs.

    Use :meth:`array` for every array value; :func:`write_page` writes it.
    """

    def __init__(self, title: str) -> None:
        self.title = title
        self.data: list[dict[str, Any]] = []
        self.layout: dict[str, Any] = {"title": {"text": title}}
        self.frames: list[dict[str, Any]] = []
        self._blobs: list[dict[str, str]] = []

    def array(self, values: Any, dtype: str = "f4") -> dict[str, int]:
        """Store ``values`` as a blob; returns the reference to put in a trace.

        ``dtype``: ``"f4"`` (float32), ``"u1"`` (uint8) or ``"i4d"`` (integers
        stored as int32 differences of neighbours: mesh indices compress better).
        """
        values = np.asarray(values).reshape(-1)
        if dtype == "i4d":
            values = np.diff(values.astype(np.int64), prepend=0)
        kinds = {"f4": np.float32, "i4d": np.int32, "u1": np.uint8}
        raw = np.ascontiguousarray(values, dtype=kinds[dtype]).tobytes()
        self._blobs.append({"dtype": dtype, "data": base64.b64encode(zlib.compress(raw, 6)).decode("ascii")})
        return {"__blob": len(self._blobs) - 1}

    def to_json(self) -> str:
        spec = {"figure": {"data": self.data, "layout": self.layout, "frames": self.frames}, "blobs": self._blobs}
        return json.dumps(spec, separators=(",", ":")).replace("</", "<\\/")


def _plotly_js() -> tuple[str, Path]:
    """The installed plotly.js: its file name ``plotly-<version>.min.js`` and path."""
    try:
        import plotly
        from plotly.offline import get_plotlyjs_version
    except ImportError as exc:
        raise MissingDependencyError("the HTML view needs plotly: pip install 'medialaxis[mesh]'") from exc
    source = Path(plotly.__file__).parent / "package_data" / "plotly.min.js"
    return f"plotly-{get_plotlyjs_version()}.min.js", source


def write_page(page: Page, path: str | os.PathLike[str], *, viewer: str = "folder") -> list[Path]:
    """Write ``page`` to ``path`` (and the viewer library beside it); returns the files written."""
    from medialaxis.core.io import atomic_write

    if viewer not in VIEWERS:
        raise InvalidInputError(f"viewer must be one of {', '.join(VIEWERS)}, got {viewer!r}")
    path = Path(path)
    name, source = _plotly_js()
    written = []
    if viewer == "inline":
        tag = "<script>" + source.read_text(encoding="utf-8") + "</script>"
    else:
        library = path.parent / name
        if not (library.is_file() and library.stat().st_size == source.stat().st_size):
            with atomic_write(library, "wb") as fh:
                fh.write(source.read_bytes())
            written.append(library)
        tag = f'<script src="{name}"></script>'
    html = _TEMPLATE % {
        "title": page.title.replace("&", "&amp;").replace("<", "&lt;"),
        "library_tag": tag,
        "data": page.to_json(),
        "loader": _LOADER % {"library": name},
    }
    with atomic_write(path, "w") as fh:
        fh.write(html)
    return [*written, path]


def _mesh_trace(
    page: Page, vertices: np.ndarray, faces: np.ndarray, intensity: np.ndarray | None = None, **style: Any
) -> dict[str, Any]:
    """A mesh3d trace; vertices renumbered in order of first use so that the index deltas stay small."""
    faces = np.asarray(faces, np.int64)
    used, first = np.unique(faces.ravel(), return_index=True)
    order = used[np.argsort(first, kind="stable")]
    index = np.full(len(vertices), -1, np.int64)
    index[order] = np.arange(len(order))
    x, y, z = np.asarray(vertices, float)[order].T
    i, j, k = index[faces].T
    trace = {"type": "mesh3d", "x": page.array(x), "y": page.array(y), "z": page.array(z),
             "i": page.array(i, "i4d"), "j": page.array(j, "i4d"), "k": page.array(k, "i4d"), **style}
    if intensity is not None:
        trace["intensity"] = page.array(np.asarray(intensity)[order])
    return trace


def _colorbar(r: np.ndarray) -> dict[str, Any]:
    lo, hi = (float(r.min()), float(r.max())) if len(r) else (0.0, 1.0)
    return {"colorscale": COLORSCALE, "cmin": lo, "cmax": hi if hi > lo else lo + 1.0,
            "colorbar": {"title": {"text": "radius"}, "x": 1.0, "xanchor": "left", "len": 0.7}}


def _title(ma: MedialAxis, shown: int) -> str:
    method = ma.metadata.get("method", "?")
    if ma.metadata.get("simplified"):
        head = f"simplified medial mesh (Q-MAT, from {method}): {len(ma.points)} spheres"
    else:
        head = f"medial axis ({method}): {len(ma.points)} points"
    parts = [head, f"{len(ma.faces)} faces"] if len(ma.faces) else [head, f"{len(ma.edges)} edges"]
    if shown < len(ma.points) and not len(ma.faces) and not len(ma.edges):
        parts.append(f"{shown} drawn")
    return ", ".join(parts)


def medial_page(
    ma: MedialAxis,
    surface: Any = None,
    *,
    shell_opacity: float = 0.15,
    max_shell_faces: int = 30000,
    max_points: int = 100000,
    max_spheres: int = 3000,
) -> Page:
    """The page of a 3D result: medial faces, curves and points coloured by radius, input shell, spheres.

    Parameters
    ----------
    ma : MedialAxis
        A 3D result.
    surface : trimesh.Trimesh or object with ``vertices`` and ``faces``, optional
        Shell to draw; default ``ma.shape`` (the input mesh, or the isosurface of a volume).
    shell_opacity : float
        Opacity of the shell, in [0, 1].
    max_shell_faces, max_points, max_spheres : int
        Budgets: the shell is thinned, lone points and spheres beyond them are
        subsampled (largest spheres first).

    Raises
    ------
    InvalidInputError
        If ``ma`` is not 3D or ``shell_opacity`` is outside [0, 1].
    """
    if not isinstance(ma, MedialAxis) or ma.dim != 3:
        raise InvalidInputError("the HTML view is for 3D medial axes")
    if not 0.0 <= shell_opacity <= 1.0:
        raise InvalidInputError(f"shell_opacity must be in [0, 1], got {shell_opacity!r}")
    p, r = ma.points, ma.radii
    colour = _colorbar(r)
    drawn = [p]
    lone = np.flatnonzero(ma.degree == 0) if not len(ma.faces) else np.zeros(0, np.int64)
    if len(lone) > max_points:
        lone = np.sort(np.random.default_rng(0).choice(lone, max_points, replace=False))
    page = Page(_title(ma, len(lone)))
    shell = scene3d.shell_of(ma, surface)
    if shell is not None:
        sv, sf = scene3d.cluster_decimate(*shell, max_shell_faces)
        drawn.append(sv)
        page.data.append(_mesh_trace(page, sv, sf, color="lightgrey", opacity=shell_opacity, name="input surface",
                                     hoverinfo="skip", showlegend=True, flatshading=False))
    bar_used = False
    if len(ma.faces):
        page.data.append(_mesh_trace(page, p, ma.faces, r, name="medial surface",
                                     showlegend=True, hovertemplate="radius %{intensity:.4g}<extra></extra>", **colour))
        bar_used = True
    e = mesh_files.curve_edges(ma)
    if len(e):
        xyz = np.full((3 * len(e), 3), np.nan)
        xyz[0::3], xyz[1::3] = p[e[:, 0]], p[e[:, 1]]
        rr = np.full(3 * len(e), np.nan)
        rr[0::3], rr[1::3] = r[e[:, 0]], r[e[:, 1]]
        line = {"color": page.array(rr), "width": 4, **{k: v for k, v in colour.items() if k != "colorbar"}}
        if not bar_used:
            line["colorbar"] = colour["colorbar"]
            bar_used = True
        page.data.append({"type": "scatter3d", "mode": "lines", "name": "medial curves", "showlegend": True,
                          "x": page.array(xyz[:, 0]), "y": page.array(xyz[:, 1]), "z": page.array(xyz[:, 2]),
                          "line": line, "hoverinfo": "skip"})
    if len(lone):
        marker = {"size": 2.5, "color": page.array(r[lone]), **{k: v for k, v in colour.items() if k != "colorbar"}}
        if not bar_used:
            marker["colorbar"] = colour["colorbar"]
        page.data.append({"type": "scatter3d", "mode": "markers", "name": "medial points", "showlegend": True,
                          "x": page.array(p[lone, 0]), "y": page.array(p[lone, 1]), "z": page.array(p[lone, 2]),
                          "marker": marker, "hovertemplate": "radius %{marker.color:.4g}<extra></extra>"})
    if ma.metadata.get("simplified") and len(p):
        order = np.argsort(-r, kind="stable")[:max_spheres]
        bv, bf, br = scene3d.sphere_meshes(p[order], r[order])
        drawn.append(bv)
        page.data.append(_mesh_trace(page, bv, bf, br, opacity=0.25, name="medial spheres",
                                     showlegend=True, hoverinfo="skip", showscale=False,
                                     **{k: v for k, v in colour.items() if k != "colorbar"}))
    ranges, ratio = scene3d.equal_ranges(*drawn)
    page.layout.update(
        scene={
            "aspectmode": "manual",
            "aspectratio": dict(zip("xyz", ratio.tolist())),
            **{f"{a}axis": {"range": ranges[k].tolist(), "title": {"text": a}} for k, a in enumerate("xyz")},
        },
        legend={"x": 0.01, "y": 0.99, "xanchor": "left", "yanchor": "top", "bgcolor": "rgba(255,255,255,0.7)"},
        margin={"l": 0, "r": 0, "t": 40, "b": 0},
    )
    return page


def _planar_outline(ma: MedialAxis) -> tuple[np.ndarray, np.ndarray] | None:
    """The shape's rings in output (x, y), exteriors one way round and holes the other, NaN between rings."""
    if ma.shape is None:
        return None
    import shapely

    rings = []
    for poly in shapely.get_parts(shapely.orient_polygons(ma.shape)):
        for ring in [poly.exterior, *poly.interiors]:
            rings += [plane_xy(ma, np.asarray(ring.coords)[:, :2]), np.full((1, 2), np.nan)]
    if not rings:
        return None
    xy = np.vstack(rings)
    return xy[:, 0], xy[:, 1]


def planar_page(ma: MedialAxis, *, radius_bands: int = 16, max_svg_points: int = 20000) -> Page:
    """The page of a 2D result: the shape, the axis coloured by radius, its points with their radii on hover.

    Drawn in the source's frame (:mod:`medialaxis.core.frames`): an image's x = column and y = row
    downwards, an SVG drawing's user units with y down, other inputs with y up; one scale on both axes.
    The axis edges are drawn in ``radius_bands`` colours (a plotly line has one colour), the points
    (WebGL beyond ``max_svg_points``) carry the exact radius and the colour bar.

    Raises
    ------
    InvalidInputError
        If ``ma`` is not 2D.
    """
    if not isinstance(ma, MedialAxis) or ma.dim != 2:
        raise InvalidInputError("the planar page is for 2D medial axes")
    from plotly.colors import sample_colorscale

    xy, r = plane_xy(ma, ma.points), ma.radii
    colour = _colorbar(r)
    page = Page(_title(ma, len(ma.points)))
    outline = _planar_outline(ma)
    if outline is not None:
        page.data.append({"type": "scatter", "mode": "lines", "name": "shape", "fill": "toself",
                          "fillcolor": "rgba(120,150,190,0.25)", "line": {"color": "#445", "width": 1},
                          "x": page.array(outline[0]), "y": page.array(outline[1]), "hoverinfo": "skip"})
    edges = np.asarray(ma.edges, np.int64).reshape(-1, 2)
    if len(edges):
        lo, hi = colour["cmin"], colour["cmax"]
        level = np.clip((r[edges].mean(axis=1) - lo) / (hi - lo), 0.0, 1.0)
        band = np.minimum((level * radius_bands).astype(np.int64), radius_bands - 1)
        for k in np.unique(band).tolist():
            e = edges[band == k]
            seg = np.full((3 * len(e), 2), np.nan)
            seg[0::3], seg[1::3] = xy[e[:, 0]], xy[e[:, 1]]
            page.data.append({"type": "scatter", "mode": "lines", "name": "medial axis", "legendgroup": "axis",
                              "showlegend": not any(t.get("legendgroup") == "axis" for t in page.data),
                              "line": {"color": sample_colorscale(COLORSCALE, [(k + 0.5) / radius_bands])[0],
                                       "width": 2.5},
                              "x": page.array(seg[:, 0]), "y": page.array(seg[:, 1]), "hoverinfo": "skip"})
    page.data.append({"type": "scattergl" if len(xy) > max_svg_points else "scatter", "mode": "markers",
                      "name": "medial points", "x": page.array(xy[:, 0]), "y": page.array(xy[:, 1]),
                      "marker": {"size": 3, "color": page.array(r), **colour},
                      "hovertemplate": "x %{x:.4g}, y %{y:.4g}<br>radius %{marker.color:.4g}<extra></extra>"})
    down = y_down(ma)
    names = ("x (column)", "y (row)") if from_image(ma) else ("x", "y")
    page.layout.update(
        xaxis={"title": {"text": names[0]}, "constrain": "domain"},
        yaxis={"title": {"text": names[1]}, "scaleanchor": "x", "scaleratio": 1,
               "autorange": "reversed" if down else True},
        legend={"x": 0.01, "y": 0.99, "xanchor": "left", "yanchor": "top", "bgcolor": "rgba(255,255,255,0.7)"},
        margin={"l": 50, "r": 20, "t": 40, "b": 40}, plot_bgcolor="white",
    )
    return page


def write_html(ma: MedialAxis, path: str | os.PathLike[str], surface: Any = None, *, viewer: str = "folder") -> list[Path]:
    """Write the interactive view of ``ma`` to ``path``; returns the files written.

    A 3D result is shown by :func:`medial_page`, a 2D one by :func:`planar_page` (``surface`` is for 3D).

    ``viewer="folder"`` puts ``plotly-<version>.min.js`` beside the page once
    (shared by every page of the folder); ``"inline"`` embeds it.

    Examples
    --------
    >>> import tempfile, pathlib, trimesh
    >>> from medialaxis.mesh.voronoi import voronoi_medial_axis
    >>> ma = voronoi_medial_axis(trimesh.creation.box(extents=(2, 1, 0.5)), samples=3000)
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> [p.suffix for p in write_html(ma, folder / "box.html")]
    ['.js', '.html']
    >>> [p.suffix for p in write_html(ma, folder / "again.html")]  # the library is there already
    ['.html']
    """
    page = planar_page(ma) if isinstance(ma, MedialAxis) and ma.dim == 2 else medial_page(ma, surface)
    return write_page(page, path, viewer=viewer)
