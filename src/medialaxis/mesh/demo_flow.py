"""Demo case for ``medialaxis demo``: the diffusion-flow skeleton of a generated tripod, then a bend.

Writes ``tripod.ply`` (the mesh), ``tripod_flow.json``/``.ply`` (the curve
skeleton) and ``tripod_bent.ply`` (the mesh after bending one arm's skeleton
by 30 degrees with :func:`medialaxis.deform`).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["DEMO_CASES", "tripod_flow_case"]


def tripod_flow_case(outdir: Path) -> str:
    """Skeletonize and bend a tripod of capsules (radius 0.5, arms 3); one summary line."""
    from medialaxis.mesh.deform import deform
    from medialaxis.mesh.flow import flow_skeleton
    from medialaxis.mesh.flow_samples import segment_distance, tripod_mesh, tripod_segments

    mesh = tripod_mesh(radius=0.5, arm=3.0, pitch=0.08)
    mesh.export(outdir / "tripod.ply")
    t0 = time.perf_counter()
    sk = flow_skeleton(mesh)
    elapsed = time.perf_counter() - t0
    for ext in (".json", ".ply"):
        sk.save(outdir / f"tripod_flow{ext}")
    segments = tripod_segments(3.0)
    d = segment_distance(sk.points, segments)
    junction = sk.points[sk.junctions[0]] if len(sk.junctions) else np.zeros(3)
    arm = np.argmin(np.stack([segment_distance(sk.points, segments[k : k + 1]) for k in range(3)]), axis=0) == 0
    arm &= np.linalg.norm(sk.points - junction, axis=1) > 0
    angle = np.radians(30.0)
    rot = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1.0]])
    new = sk.points.copy()
    new[arm] = (sk.points[arm] - junction) @ rot.T + junction
    bent = deform(mesh, sk, new)
    bent.export(outdir / "tripod_bent.ply")
    return (
        f"tripod (flow): {len(mesh.vertices)} vertices -> {len(sk.points)} nodes, {len(sk.endpoints)} endpoints, "
        f"{len(sk.junctions)} junctions, axis distance p99 {np.percentile(d, 99):.3f}, "
        f"median radius {np.median(sk.radii):.3f} (true 0.5), {elapsed * 1000:.0f} ms; "
        f"bent arm volume change {100 * (bent.volume / mesh.volume - 1):+.2f}%"
    )


#: Picked up by :func:`medialaxis.demo.all_cases`.
DEMO_CASES: list[tuple[str, Callable[[Path], Any]]] = [("tripod_flow", tripod_flow_case)]
