"""Write every step of the diffusion flow to disk: one PLY per step and an HTML animation.

Used by ``medialaxis compute MESH --method flow --frames DIR``; also usable
directly as the ``callback`` of :func:`medialaxis.mesh.flow.flow_skeleton`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._optional import require
from medialaxis.core.io import atomic_write
from medialaxis.errors import InvalidInputError

__all__ = ["FrameWriter"]


class FrameWriter:
    """Callback that saves each :class:`~medialaxis.mesh.skeleton.flow_mesh.FlowState` the flow reports (``Progress.state``).

    Parameters
    ----------
    outdir : path
        Folder (created if missing) receiving ``step_0001.ply``... (frozen
        vertices coloured red, moving ones grey) and, on :meth:`finish`,
        ``flow.html`` (an offline animation of the vertices, at most
        ``max_points`` per frame, over the input mesh, with a slider over the
        steps; the viewer library is written beside it).
    max_points : int
        Vertices drawn per animation frame (a random subset beyond that).
    rng : int or numpy.random.Generator, optional
        Seed for that subset.

    Examples
    --------
    >>> import tempfile, medialaxis as mx
    >>> from medialaxis.datasets import capsules_mesh
    >>> from medialaxis.mesh.skeleton.flow_frames import FrameWriter
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     writer = FrameWriter(tmp)
    ...     sk = mx.medial_axis(capsules_mesh([[[0, 0, 0], [2, 0, 0]]], 0.5, pitch=0.15), method="flow", callback=writer)
    ...     paths = writer.finish()
    ...     len(writer.paths) == sk.metadata["steps"], paths[-1].name
    (True, 'flow.html')
    """

    def __init__(self, outdir: Any, *, max_points: int = 20000, rng: Any = None) -> None:
        self.outdir = Path(outdir)
        if self.outdir.exists() and not self.outdir.is_dir():
            raise InvalidInputError(f"--frames needs a folder, {str(self.outdir)!r} is a file")
        self.outdir.mkdir(parents=True, exist_ok=True)
        self.max_points = int(max_points)
        self.rng = np.random.default_rng(rng)
        self.paths: list[Path] = []
        self._frames: list[tuple[np.ndarray, np.ndarray]] = []
        self._subset: np.ndarray | None = None
        self._first_mesh: tuple[np.ndarray, np.ndarray] = (np.zeros((0, 3)), np.zeros((0, 3), np.int64))

    def __call__(self, progress: Any) -> None:
        state = getattr(progress, "state", progress)  # the flow's Progress, or its FlowState itself
        trimesh = require("trimesh", "medialaxis[mesh]")
        colours = np.where(state.frozen[:, None], [[220, 40, 40, 255]], [[170, 170, 170, 255]]).astype(np.uint8)
        mesh = trimesh.Trimesh(np.asarray(state.positions), np.asarray(state.faces), vertex_colors=colours, process=False)
        path = self.outdir / f"step_{state.step:04d}.ply"
        data = mesh.export(file_type="ply")
        with atomic_write(path, "wb") as fh:
            fh.write(data)
        self.paths.append(path)
        if self._subset is None:
            self._first_mesh = (np.array(state.positions, float), np.array(state.faces, np.int64))
            n = len(state.positions)
            self._subset = np.sort(self.rng.choice(n, self.max_points, replace=False)) if n > self.max_points else np.arange(n)
        self._frames.append((np.array(state.positions[self._subset]), np.array(state.frozen[self._subset])))

    def finish(self) -> list[Path]:
        """Write ``flow.html`` (and the viewer library beside it) and return every file written."""
        if not self._frames:
            return list(self.paths)
        from medialaxis.core.export.html import Page, write_page
        from medialaxis.core.export.scene3d import cluster_decimate, equal_ranges

        page = Page("diffusion flow: red points are skeletal (frozen), grey ones still move")
        first = self._first_mesh
        shell_v, shell_f = cluster_decimate(first[0], first[1], 30000)
        x, y, z = shell_v.T
        page.data.append({"type": "mesh3d", "x": page.array(x), "y": page.array(y), "z": page.array(z),
                          "i": page.array(shell_f[:, 0], "i4d"), "j": page.array(shell_f[:, 1], "i4d"),
                          "k": page.array(shell_f[:, 2], "i4d"), "color": "lightgrey", "opacity": 0.12,
                          "name": "input surface", "showlegend": True, "hoverinfo": "skip"})

        def points(positions: np.ndarray, frozen: np.ndarray) -> dict[str, Any]:
            px, py, pz = positions.T
            return {"type": "scatter3d", "mode": "markers", "name": "vertices", "showlegend": True,
                    "x": page.array(px), "y": page.array(py), "z": page.array(pz), "hoverinfo": "skip",
                    "marker": {"size": 2, "color": page.array(frozen, "u1"), "cmin": 0, "cmax": 1,
                               "colorscale": [[0, "#999999"], [1, "#dc2828"]]}}

        page.data.append(points(*self._frames[0]))
        names = [str(k + 1) for k in range(len(self._frames))]
        page.frames = [{"name": name, "data": [points(*frame)], "traces": [1]} for name, frame in zip(names, self._frames)]
        ranges, ratio = equal_ranges(first[0])
        still = {"mode": "immediate", "frame": {"duration": 0, "redraw": True}, "transition": {"duration": 0}}
        page.layout.update(
            scene={"aspectmode": "manual", "aspectratio": dict(zip("xyz", ratio.tolist())),
                   **{f"{a}axis": {"range": ranges[k].tolist()} for k, a in enumerate("xyz")}},
            legend={"x": 0.01, "y": 0.99},
            margin={"l": 0, "r": 0, "t": 40, "b": 0},
            updatemenus=[{"type": "buttons", "x": 0.01, "y": 0.02, "xanchor": "left", "buttons": [
                {"label": "play", "method": "animate",
                 "args": [None, {"frame": {"duration": 300, "redraw": True}, "fromcurrent": True}]},
                {"label": "pause", "method": "animate", "args": [[None], still]}]}],
            sliders=[{"x": 0.15, "len": 0.8, "y": 0.02, "currentvalue": {"prefix": "step "},
                      "steps": [{"label": name, "method": "animate", "args": [[name], still]} for name in names]}],
        )
        return [*self.paths, *write_page(page, self.outdir / "flow.html")]
