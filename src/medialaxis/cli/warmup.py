"""Compile the numba kernels once, ahead of the first real call (``medialaxis warmup``).

The kernels are compiled on first use and cached on disk (``cache=True``,
next to the installed package or in :mod:`medialaxis._jit`'s fallback
folder), so only the first call after an install pays for compiling: about
a minute for the mesh routes on two cores. ``scripts/setup.sh`` runs this
after installing; a user who installs otherwise can run it once. Each
method is run on a small shape of its domain, which compiles the same
signatures (float64 and int64 arrays) that real inputs use.
"""

from __future__ import annotations

import argparse
import time
import warnings
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np

from medialaxis._help import HelpFormatter, UsageError
from medialaxis.errors import MedialAxisWarning

__all__ = ["DOMAINS", "warm_up", "add_warmup"]


def _planar() -> None:
    import medialaxis as mx
    from medialaxis.datasets import data_path

    mx.medial_axis(data_path("kimia_class1_01.png")).betti  # noqa: B018 (compiles the homology kernel)
    mx.medial_axis(data_path("bracket_two_holes.wkt").read_text())
    labels = np.zeros((40, 60), np.int32)
    labels[5:35, 5:25], labels[5:35, 30:55] = 1, 2
    mx.medial_axis(labels)


def _mesh() -> None:
    import trimesh

    import medialaxis as mx

    capsule = trimesh.creation.capsule(height=2.0, radius=0.5)
    mx.medial_axis(capsule, samples=4000, simplify=40)  # the compact complex and the simplification too
    mx.medial_axis(capsule, method="flow")
    crossing = trimesh.util.concatenate([trimesh.creation.box(extents=(2, 1, 1)), trimesh.creation.box(extents=(1, 2, 1))])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MedialAxisWarning)
        mx.medial_axis(crossing, samples=2000)  # the arrangement and winding-number kernels
    from medialaxis.mesh.medial.stray_cycles import complement_voids
    from medialaxis.mesh.medial.voronoi_diagram import tetrahedralise

    dt = tetrahedralise(np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [1, 1, 1.0]]))
    complement_voids(dt.simplices, dt.neighbors, np.array([[0, 4], [1, 4]]))  # only where a complex has extra cycles


def _volume() -> None:
    import medialaxis as mx
    from medialaxis.datasets import t_phantom

    phantom = t_phantom((40, 64, 64), thickness=6, margin=8)
    mx.medial_axis(phantom.volume, method="midsurface")
    mx.medial_axis(phantom.volume, method="voxels")


#: What each domain runs; its optional dependencies must be installed.
DOMAINS: dict[str, Callable[[], None]] = {"planar": _planar, "mesh": _mesh, "volume": _volume}


def warm_up(domains: tuple[str, ...] = tuple(DOMAINS)) -> Iterator[tuple[str, float]]:
    """Run each domain's small shapes; yields ``(domain, seconds)`` as each is done."""
    from medialaxis import _jit

    quiet, _jit.QUIET = _jit.QUIET, True  # compiling is what was asked for: no notice per call
    try:
        for name in domains:
            start = time.perf_counter()
            DOMAINS[name]()
            yield name, time.perf_counter() - start
    finally:
        _jit.QUIET = quiet


def add_warmup(sub: Any) -> None:
    p = sub.add_parser(
        "warmup",
        help="compile the kernels once (the first call after an install is then fast)",
        description="Run every method on a small shape so that its compiled kernels are cached on disk; "
                    "scripts/setup.sh runs it after installing.",
        formatter_class=HelpFormatter,
    )
    p.add_argument("--domains", default="planar,mesh,volume", help="comma-separated: planar, mesh, volume")
    p.set_defaults(run=_run_warmup)


def _run_warmup(args: argparse.Namespace) -> int:
    domains = tuple(d.strip() for d in args.domains.split(",") if d.strip())
    unknown = [d for d in domains if d not in DOMAINS]
    if unknown or not domains:
        raise UsageError(f"--domains takes {', '.join(DOMAINS)}; got {args.domains!r}")
    for name, seconds in warm_up(domains):
        print(f"{name}: compiled in {seconds:.1f} s")
    return 0
