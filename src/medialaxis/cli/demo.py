"""``medialaxis demo OUTDIR``: the main job on the sample shapes of :mod:`medialaxis.datasets`.

Each case computes an axis, writes the lossless result (``.json``), pictures
(``.svg``/``.png``, or ``.ply``/``.html`` for 3D) and, for planar shapes,
the pipeline stages, and reports one summary line: the bundled planar files,
a torus's medial surface and Q-MAT, a tripod's flow skeleton bent by 30
degrees, the mid-surface of a CT-like T, and the distance between Kimia
silhouettes.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._help import HelpFormatter
from medialaxis.datasets import data_path

__all__ = ["run_demo", "DEMO_CASES", "add_demo", "tripod_flow_case", "compare_case"]


def _planar_case(name: str, **options: Any) -> Callable[[Path], str]:
    def run(outdir: Path) -> str:
        import medialaxis as mx
        from medialaxis.planar.pipeline import planar_stages
        from medialaxis.planar.plotting import save_stages_figure

        src = data_path(name)
        stem = src.stem
        t0 = time.perf_counter()
        try:
            stages = planar_stages(str(src), **options)
        except mx.MissingDependencyError as exc:  # a drawing format of an extra that is not installed
            return f"{stem}: skipped ({exc})"
        elapsed = time.perf_counter() - t0
        ma = stages.result
        for ext in (".json", ".svg", ".png"):
            ma.save(outdir / f"{stem}{ext}")
        save_stages_figure(stages, outdir / f"{stem}_steps.png")
        err = mx.reconstruction_error(ma)
        return (
            f"{stem}: {len(ma.points)} points, {len(ma.endpoints)} endpoints, {len(ma.junctions)} junctions, "
            f"{ma.n_cycles} cycles, rebuild IoU {err.iou:.4f}, Hausdorff {err.hausdorff:.3g}, {elapsed * 1000:.0f} ms"
        )

    return run


PLANAR_CASES: list[tuple[str, Callable[[Path], Any]]] = [
    *(
        (name, _planar_case(name))
        for name in (
            "kimia_class1_01.png",
            "kimia_class3_05.png",
            "kimia_class5_03.png",
            "kimia_class8_05.png",
            "bracket_two_holes.wkt",
            "gasket.svg",
        )
    ),
    ("plate_slot.dxf", _planar_case("plate_slot.dxf", layers=["CUT"])),
]


def _voronoi_torus(outdir: Path) -> str:
    from medialaxis.datasets import torus_mesh
    from medialaxis.mesh.voronoi import voronoi_medial_axis

    mesh = torus_mesh(1.0, 0.35, sections=(64, 24))
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


def tripod_flow_case(outdir: Path) -> str:
    """Skeletonize and bend a tripod of capsules (radius 0.5, arms 3); one summary line."""
    from medialaxis.datasets import segment_distance, tripod_mesh, tripod_segments
    from medialaxis.mesh.flow import flow_skeleton
    from medialaxis.mesh.skeleton.deform import deform

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


def t_demo(outdir: Path) -> str:
    """Mid-surface of a blurred, noisy T of two 6-voxel plates (generated).

    Writes ``volume_t.ply``/``.vtk`` (mesh with thickness), ``volume_t.json``
    (lossless) and ``volume_t.png``, and returns a summary with the accuracy
    against the known mid-planes.
    """
    from medialaxis.datasets import t_phantom
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


KIMIA = ("kimia_class1_01.png", "kimia_class3_05.png", "kimia_class5_03.png", "kimia_class8_05.png")


def compare_case(outdir: Path) -> str:
    import medialaxis as mx
    from medialaxis.cli.compare import save_match_picture
    from medialaxis.compare.distance import match_tour, shape_signature
    from medialaxis.compare.signature import DEFAULT_PRUNE
    from medialaxis.datasets import kimia_mask

    t0 = time.perf_counter()
    masks = [kimia_mask(name) for name in KIMIA]
    turned = np.rot90(masks[0])  # the first shape, turned by 90 degrees
    axes = [mx.medial_axis(m) for m in [*masks, turned]]
    D = mx.distance_matrix([shape_signature(a) for a in axes], n_jobs=1)
    distance, points_a, points_b = match_tour(axes[0], axes[-1])
    save_match_picture(axes[0], axes[-1], points_a, points_b, outdir / "compare_match.png", prune=DEFAULT_PRUNE,
                       titles=(KIMIA[0], KIMIA[0] + " turned"), distance=distance)
    elapsed = time.perf_counter() - t0
    nearest = int(np.argsort(D[-1])[1])
    return (
        f"compare: turned {KIMIA[0]} is at {D[-1, 0]:.3g} from itself, nearest other "
        f"{min(D[-1, 1:-1]):.3g}; nearest shape {KIMIA[nearest] if nearest < len(KIMIA) else '?'}; "
        f"compare_match.png, {elapsed * 1000:.0f} ms"
    )

#: Demo cases: (title, runner), run in this order.
DEMO_CASES: list[tuple[str, Callable[[Path], Any]]] = [
    *PLANAR_CASES,
    ("torus medial surface (voronoi)", _voronoi_torus),
    ("tripod_flow", tripod_flow_case),
    ("volume T mid-surface", t_demo),
    ("compare", compare_case),
]


def run_demo(outdir: str | Path) -> Iterator[str]:
    """Run every demo case, writing into ``outdir`` (created if missing)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    for _title, case in DEMO_CASES:
        yield case(outdir)
    yield f"results in {outdir.resolve()}"


def add_demo(sub: Any) -> None:
    p = sub.add_parser(
        "demo",
        help="run on the bundled sample shapes",
        description="Compute the medial axis of every bundled sample shape and write results and plots to a folder.",
        formatter_class=HelpFormatter,
    )
    p.add_argument("outdir", type=Path, nargs="?", default=Path("medialaxis-demo"), help="output folder")
    p.set_defaults(run=_run_demo)


def _run_demo(args: argparse.Namespace) -> int:
    for line in run_demo(args.outdir):
        print(line)
    return 0
