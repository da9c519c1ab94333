"""Interactive, self-contained HTML view of a medial surface (plotly, works offline).

The medial faces are coloured by radius; the input mesh, when the result
keeps it (``ma.shape``), is drawn as a transparent shell. plotly.js is
embedded in the file, so it opens without a network connection.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InvalidInputError

__all__ = ["medial_figure", "write_html"]


def medial_figure(ma: MedialAxis, surface: Any = None, *, shell_opacity: float = 0.15) -> Any:
    """A plotly figure of ``ma``: faces (or edges) coloured by radius, plus the surface shell.

    Parameters
    ----------
    ma : MedialAxis
        A 3D result.
    surface : trimesh.Trimesh, optional
        Shell to draw; default ``ma.shape`` when it is a mesh.
    shell_opacity : float
        Opacity of the shell, in [0, 1].

    Returns
    -------
    plotly.graph_objects.Figure

    Raises
    ------
    InvalidInputError
        If ``ma`` is not 3D or ``shell_opacity`` is outside [0, 1].
    MissingDependencyError
        If plotly is not installed (``pip install medialaxis[mesh]``).
    """
    go = require("plotly.graph_objects", "medialaxis[mesh]")
    if not isinstance(ma, MedialAxis) or ma.dim != 3:
        raise InvalidInputError("the HTML view is for 3D medial axes")
    if not 0.0 <= shell_opacity <= 1.0:
        raise InvalidInputError(f"shell_opacity must be in [0, 1], got {shell_opacity!r}")
    p, r = ma.points, ma.radii
    traces = []
    shell = surface if surface is not None else ma.shape
    if shell is not None and hasattr(shell, "vertices") and hasattr(shell, "faces"):
        v, f = np.asarray(shell.vertices), np.asarray(shell.faces)
        traces.append(
            go.Mesh3d(
                x=v[:, 0], y=v[:, 1], z=v[:, 2], i=f[:, 0], j=f[:, 1], k=f[:, 2],
                color="lightgrey", opacity=shell_opacity, name="input surface", hoverinfo="skip", showlegend=True,
            )
        )
    colorbar = {"title": {"text": "radius"}}
    if len(ma.faces):
        f = ma.faces
        traces.append(
            go.Mesh3d(
                x=p[:, 0], y=p[:, 1], z=p[:, 2], i=f[:, 0], j=f[:, 1], k=f[:, 2], intensity=r,
                colorscale="Viridis", colorbar=colorbar, name="medial surface", showlegend=True,
                hovertemplate="radius %{intensity:.4g}<extra></extra>",
            )
        )
    curve = ma.edges
    if len(curve):
        xyz = np.full((3 * len(curve), 3), np.nan)
        xyz[0::3], xyz[1::3] = p[curve[:, 0]], p[curve[:, 1]]
        rr = np.full(3 * len(curve), np.nan)
        rr[0::3], rr[1::3] = r[curve[:, 0]], r[curve[:, 1]]
        traces.append(
            go.Scatter3d(
                x=xyz[:, 0], y=xyz[:, 1], z=xyz[:, 2], mode="lines", name="medial edges",
                line={"color": rr, "colorscale": "Viridis", "width": 3}, hoverinfo="skip",
                visible=True if not len(ma.faces) else "legendonly",
            )
        )
    fig = go.Figure(traces)
    method = ma.metadata.get("method", "?")
    fig.update_layout(
        title=f"medial axis ({method}): {len(p)} points, {len(ma.faces)} faces",
        scene={"aspectmode": "data"}, margin={"l": 0, "r": 0, "t": 40, "b": 0},
    )
    return fig


def write_html(ma: MedialAxis, path: str | os.PathLike[str], surface: Any = None) -> None:
    """Write the interactive view of ``ma`` to ``path`` (plotly.js inlined: works offline).

    Examples
    --------
    >>> import tempfile, pathlib, trimesh
    >>> from medialaxis.mesh.voronoi import voronoi_medial_axis
    >>> ma = voronoi_medial_axis(trimesh.creation.box(extents=(2, 1, 0.5)), samples=3000)
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "box.html"
    >>> write_html(ma, out)
    >>> "plotly" in out.read_text()[:5000].lower()
    True
    """
    from medialaxis.core.io import atomic_write

    html = medial_figure(ma, surface).to_html(include_plotlyjs=True, full_html=True)
    with atomic_write(path, "w") as fh:
        fh.write(html)
