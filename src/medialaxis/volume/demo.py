"""Volume demo case for ``medialaxis demo``: the mid-surface of a CT-like T."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["DEMO_CASES", "t_demo"]


def t_demo(outdir: Path) -> str:
    """Mid-surface of a blurred, noisy T of two 6-voxel plates (generated).

    Writes ``volume_t.ply``/``.vtk`` (mesh with thickness), ``volume_t.json``
    (lossless) and ``volume_t.png``, and returns a summary with the accuracy
    against the known mid-planes.
    """
    from medialaxis.volume.phantoms import t_phantom
    from medialaxis.volume.pipeline import midsurface_medial_axis
    from medialaxis.volume.validation import coverage, distance_to_rects, mesh_topology

    ph = t_phantom((70, 120, 120), margin=10)
    t0 = time.perf_counter()
    ma = midsurface_medial_axis(ph.volume, iso=0.5)
    elapsed = time.perf_counter() - t0
    for ext in (".ply", ".vtk", ".json", ".png"):
        ma.save(Path(outdir) / f"volume_t{ext}")
    d = distance_to_rects(ma.points, ph.midsurface)
    frac, _ = coverage(np.concatenate([r.sample(0.5) for r in ph.midsurface]), ma.points, ma.faces)
    topo = mesh_topology(ma.faces)
    return (
        f"volume_t (T of 6-voxel plates, {ph.volume.shape}): {len(ma.points)} vertices, {len(ma.faces)} faces, "
        f"{topo.junction_edges} junction edges, vertex error p99 {np.percentile(d, 99):.2f} voxel, "
        f"mid-plane covered {100 * frac:.1f}%, median thickness {np.median(2 * ma.radii):.2f}, {elapsed * 1000:.0f} ms"
    )


#: (title, runner) pairs picked up by :mod:`medialaxis.demo`.
DEMO_CASES: list[tuple[str, Callable[[Path], Any]]] = [("volume T mid-surface", t_demo)]
