"""Mesh demo cases for ``medialaxis demo OUTDIR`` (generated meshes, a few seconds each).

Each case writes the medial surface as ``.ply`` (with radius), ``.json`` and
an interactive ``.html`` view, and returns one summary line.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

__all__ = ["DEMO_CASES"]


def _voronoi_torus(outdir: Path) -> str:
    import trimesh

    from medialaxis.mesh.voronoi import voronoi_medial_axis

    mesh = trimesh.creation.torus(major_radius=1.0, minor_radius=0.35, major_sections=64, minor_sections=24)
    t0 = time.perf_counter()
    ma = voronoi_medial_axis(mesh, samples=3_000, simplify=200)
    elapsed = time.perf_counter() - t0
    full = ma.raw
    for result, stem in ((full, "torus_medial"), (ma, "torus_qmat200")):
        for ext in (".ply", ".json", ".html"):
            result.save(outdir / f"{stem}{ext}")
    md = full.metadata
    return (
        f"torus (voronoi): {len(full.points)} points, {len(full.faces)} faces, euler characteristic "
        f"{md['euler_characteristic']} (solid {md['mesh_euler_characteristic'] // 2}), epsilon {md['epsilon']:.3g}, "
        f"lam {md['lam']:.3g}; Q-MAT {len(ma.points)} spheres, Hausdorff {ma.metadata['hausdorff']:.3g}; "
        f"{elapsed:.1f} s"
    )


#: Demo cases: (title, runner). The flow skeleton cases are appended in their own branch.
DEMO_CASES: list[tuple[str, Callable[[Path], Any]]] = [
    ("torus medial surface (voronoi)", _voronoi_torus),
]
