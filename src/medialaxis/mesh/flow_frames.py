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
    """Callback that saves each :class:`~medialaxis.mesh.flow.FlowState`.

    Parameters
    ----------
    outdir : path
        Folder (created if missing) receiving ``step_0001.ply``... (frozen
        vertices coloured red, moving ones grey) and, on :meth:`finish`,
        ``flow.html`` (a plotly animation of the vertices, at most
        ``max_points`` per frame).
    max_points : int
        Vertices drawn per animation frame (a random subset beyond that).
    rng : int or numpy.random.Generator, optional
        Seed for that subset.

    Examples
    --------
    >>> import tempfile, medialaxis as mx
    >>> from medialaxis.mesh.flow_samples import capsules_mesh
    >>> from medialaxis.mesh.flow_frames import FrameWriter
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     writer = FrameWriter(tmp)
    ...     sk = mx.medial_axis(capsules_mesh([[[0, 0, 0], [2, 0, 0]]], 0.5, pitch=0.15), method="flow", callback=writer)
    ...     paths = writer.finish()
    ...     len(paths) == sk.metadata["steps"] + 1
    True
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

    def __call__(self, state: Any) -> None:
        trimesh = require("trimesh", "medialaxis[mesh]")
        colours = np.where(state.frozen[:, None], [[220, 40, 40, 255]], [[170, 170, 170, 255]]).astype(np.uint8)
        mesh = trimesh.Trimesh(np.asarray(state.positions), np.asarray(state.faces), vertex_colors=colours, process=False)
        path = self.outdir / f"step_{state.step:04d}.ply"
        data = mesh.export(file_type="ply")
        with atomic_write(path, "wb") as fh:
            fh.write(data)
        self.paths.append(path)
        if self._subset is None:
            n = len(state.positions)
            self._subset = np.sort(self.rng.choice(n, self.max_points, replace=False)) if n > self.max_points else np.arange(n)
        self._frames.append((np.array(state.positions[self._subset]), np.array(state.frozen[self._subset])))

    def finish(self) -> list[Path]:
        """Write ``flow.html`` and return every file written."""
        if not self._frames:
            return list(self.paths)
        go = require("plotly.graph_objects", "medialaxis[mesh]")

        def scatter(points: np.ndarray, frozen: np.ndarray) -> Any:
            return go.Scatter3d(
                x=points[:, 0], y=points[:, 1], z=points[:, 2], mode="markers",
                marker={"size": 2, "color": np.where(frozen, "#dc2828", "#999999")},
            )

        frames = [go.Frame(data=[scatter(p, f)], name=str(k + 1)) for k, (p, f) in enumerate(self._frames)]
        fig = go.Figure(data=[scatter(*self._frames[0])], frames=frames)
        fig.update_layout(
            title="diffusion flow (red: skeletal points)",
            scene={"aspectmode": "data"},
            updatemenus=[{"type": "buttons", "buttons": [{"label": "play", "method": "animate", "args": [None]}]}],
            sliders=[{"steps": [{"label": fr.name, "method": "animate", "args": [[fr.name]]} for fr in frames]}],
        )
        path = self.outdir / "flow.html"
        html = fig.to_html(include_plotlyjs="cdn")
        with atomic_write(path, "w") as fh:
            fh.write(html)
        return [*self.paths, path]
