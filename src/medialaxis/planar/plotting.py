"""The pipeline's stages in one figure.

As in figures 3, 5, 6 and 7 of "A Qualitative Approach for Medial Computation"
(docs/references.md).
"""

from __future__ import annotations

from typing import Any

from medialaxis.planar.pipeline import Stages

__all__ = ["stages_figure", "save_stages_figure"]


def stages_figure(stages: Stages) -> Any:
    """Four panels: boundary samples, Delaunay triangulation, raw axis, pruned axis."""
    import matplotlib.pyplot as plt

    from medialaxis.core.export.plot import _xy, draw_axis, draw_region

    ma = stages.result
    fig, axes = plt.subplots(1, 4, figsize=(18, 5))
    smp = _xy(ma, stages.samples.points)
    tri = stages.triangulation
    titles = [
        f"boundary samples ({len(smp)})",
        f"Delaunay ({len(tri.simplices)} triangles, {int(stages.inside.sum())} inside)",
        f"raw Voronoi axis ({len(stages.raw.edges)} edges)",
        f"pruned axis (lam={ma.metadata['lam']:.3g}, {len(ma.endpoints)} endpoints, {len(ma.junctions)} junctions)",
    ]
    for ax, title in zip(axes, titles):
        draw_region(ax, ma, stages.source.region, facecolor="#eef2f7", lw=0.5)
        ax.set_title(title, fontsize=9)
        ax.set_aspect("equal")
    axes[0].plot(*smp.T, ".", ms=2, color="#2c3e50")
    for mask, lw, color in ((~stages.inside, 0.2, "#aaa"), (stages.inside, 0.3, "#2c3e50")):
        if mask.any():
            axes[1].triplot(smp[:, 0], smp[:, 1], tri.simplices[mask], lw=lw, color=color)
    draw_axis(axes[2], stages.raw, color_by_radius=False, lw=0.6)
    draw_axis(axes[3], ma, lw=1.5)
    for ax in axes:
        ax.autoscale_view()
        if "image_shape" in ma.metadata:
            ax.invert_yaxis()
    fig.tight_layout()
    return fig


def save_stages_figure(stages: Stages, path: Any) -> None:
    """Write :func:`stages_figure` to ``path`` (PNG, SVG or PDF by extension), atomically."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from medialaxis.core.io import atomic_write

    fig = stages_figure(stages)
    fmt = str(path).rsplit(".", 1)[-1].lower()
    try:
        with atomic_write(path, "wb") as fh:
            fig.savefig(fh, format=fmt, dpi=110)
    finally:
        plt.close(fig)
