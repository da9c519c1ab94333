"""The main job on bundled sample data: ``medialaxis demo OUTDIR``.

Each case computes an axis, writes the lossless result (``.json``), an
``.svg``/``.png`` picture and, for planar shapes, the pipeline stages, and
reports one summary line.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from importlib import resources
from pathlib import Path
from typing import Any

__all__ = ["run_demo", "DEMO_CASES", "data_path"]


def data_path(name: str) -> Path:
    """Path of a bundled sample file."""
    return Path(str(resources.files("medialaxis") / "data" / name))


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


#: Demo cases: (title, runner). Other domains append their own.
DEMO_CASES: list[tuple[str, Callable[[Path], Any]]] = [
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


#: Domain modules that may define their own ``DEMO_CASES`` list.
DOMAIN_DEMOS = ("medialaxis.mesh.demo", "medialaxis.mesh.demo_flow", "medialaxis.volume.demo", "medialaxis.compare.demo")


def all_cases() -> list[tuple[str, Callable[[Path], Any]]]:
    """The planar cases plus those of every domain demo module present."""
    import importlib

    cases = list(DEMO_CASES)
    for name in DOMAIN_DEMOS:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name != name:
                raise
            continue
        cases.extend(module.DEMO_CASES)
    return cases


def run_demo(outdir: str | Path) -> Iterator[str]:
    """Run every demo case, writing into ``outdir`` (created if missing)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    for _title, case in all_cases():
        yield case(outdir)
    yield f"results in {outdir.resolve()}"
