"""Benchmark: 3D Delaunay tetrahedralisation engines on the Voronoi pipeline's surface samples.

Times, in one run and side by side, the engines a user could pick for the
Delaunay step of :func:`medialaxis.mesh.voronoi.voronoi_medial_axis`, on two
inputs: the pipeline's own surface samples of the bumpy torus of
``bench_mesh_voronoi.py`` (100,000 vertices unless ``--vertices``; the samples
are made by the pipeline's functions, exactly as it makes them), and 100,000
uniform random points in a cube (seed 0). For each input it prints the number
of points, then per engine the seconds (best of ``--repeat`` runs, 3 by
default), the tetrahedra and the ratio engine / ours (above 1: slower than
ours). Every engine runs on one thread.

Engines:

* ours: ``medialaxis.mesh.sample.delaunay.delaunay_tetrahedra`` (simplices,
  neighbours and hull), warmed up on a small input first (numba compilation);
* SciPy's Qhull, our previous engine: ``scipy.spatial.Delaunay`` with
  ``"Qbb Qc Q12 QJ"`` on the points in Morton (Z-order) order; the time
  includes the ordering (:func:`morton_order`);
* TetGen (PyPI ``tetgen``, pyvista's wrapper), if installed: plain Delaunay
  tetrahedralisation of the point cloud (TetGen's ``-Q`` with no ``-p``, no
  ``-q``; see :func:`run_tetgen` for how the wrapper is made to take a bare
  point cloud);
* CGAL (PyPI ``cgal``, the official SWIG bindings), if installed:
  ``Delaunay_triangulation_3`` built from a Python list of ``Point_3`` (range
  insertion, which CGAL spatially sorts); the time includes building that
  list (its share is printed).

Run: ``python benchmarks/bench_delaunay.py [--vertices N] [--repeat 3]``
(``PYTHONPATH=src`` in front when the package is not installed).

The peers are optional. Their licences, AGPL-3.0 (TetGen) and GPL-3.0
(CGAL's 3D triangulations), make them benchmark peers only, never
dependencies: install them in a separate virtual environment, not the
project's, e.g. from the repository root::

    python -m venv /tmp/peers && /tmp/peers/bin/pip install -e ".[mesh]" tetgen cgal
    /tmp/peers/bin/python benchmarks/bench_delaunay.py
"""

from __future__ import annotations

import argparse
import importlib.metadata
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np

#: Engine rows that are not installed: (import name, PyPI name, licence).
PEERS = {
    "tetgen": ("tetgen", "tetgen", "AGPL-3.0"),
    "cgal": ("CGAL", "cgal", "GPL-3.0"),
}


def morton_order(points: np.ndarray, bits: int = 21) -> np.ndarray:
    """Order of ``points`` along a Z-order (Morton) curve of their bounding box.

    The coordinates are quantised to ``bits`` bits per axis (the box's longest
    side spans ``2**bits - 1`` cells), interleaved into one int64 code, and
    sorted. This is the order the pipeline gave Qhull before it had its own
    engine.
    """
    lo = points.min(axis=0)
    extent = max(float(np.ptp(points, axis=0).max()), 1e-300)
    top = (1 << bits) - 1
    cells = np.clip(((points - lo) / extent * top).astype(np.int64), 0, top)
    code = np.zeros(len(points), np.int64)
    for bit in range(bits):
        for axis in range(3):
            code |= ((cells[:, axis] >> bit) & 1) << (3 * bit + axis)
    return np.argsort(code, kind="stable")


def torus_samples(n_vertices: int) -> tuple[np.ndarray, int]:
    """The surface samples ``voronoi_medial_axis`` triangulates for the bumpy torus (default settings).

    Returns the samples and the mesh's number of vertices.
    """
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_mesh_voronoi import bumpy_torus

    from medialaxis.mesh.sample.sampling import adaptive_spacing, lfs_estimate, pseudo_normals, sample_surface
    from medialaxis.mesh.sample.sampling import sample_count as _sample_count
    from medialaxis.mesh.solid.inputs import load_mesh

    work = load_mesh(bumpy_torus(n_vertices), watertight=True).mesh
    count = _sample_count(None, len(work.vertices))  # the number of vertices (at least 20,000)
    normals = pseudo_normals(work)
    tree = lfs_estimate(work, max(count // 8, 2000), normals)
    spacing = adaptive_spacing(work, tree, count)
    return np.asarray(sample_surface(work, spacing, normals).points, np.float64), len(work.vertices)


def run_ours(points: np.ndarray) -> tuple[int, str]:
    from medialaxis.mesh.sample.delaunay import delaunay_tetrahedra

    simplices, _, _ = delaunay_tetrahedra(points)
    return len(simplices), ""


def run_qhull(points: np.ndarray) -> tuple[int, str]:
    from scipy.spatial import Delaunay

    order = morton_order(points)
    tri = Delaunay(points[order], qhull_options="Qbb Qc Q12 QJ")
    return len(tri.simplices), ""


def run_tetgen(points: np.ndarray) -> tuple[int, str]:
    """TetGen's Delaunay tetrahedralisation of the bare point cloud.

    ``tetgen.TetGen`` takes a surface only: points alone raise ``TypeError``
    and an empty face array ``RuntimeError``. Without ``-p`` (``plc=False``)
    TetGen never reads the facets, so one dummy triangle satisfies the
    wrapper. ``quality=False`` (no ``-q``: no Steiner points) and
    ``quiet=True`` (``-Q``) give the plain Delaunay tetrahedralisation.
    ``nofacewritten=True`` (``-F``) is needed: without ``-p`` TetGen outputs
    the hull triangles with no markers, and the wrapper, which always reads
    the markers back, crashes (segmentation fault, tetgen 0.8.4). Keyword
    arguments rather than ``switches="QF"``, which is the same but prints
    two lines from C++.
    """
    import tetgen

    tg = tetgen.TetGen(points, np.array([[0, 1, 2]], np.int32))
    _, elem, *_ = tg.tetrahedralize(plc=False, quality=False, quiet=True, nofacewritten=True)
    return len(elem), ""


def run_cgal(points: np.ndarray) -> tuple[int, str]:
    from CGAL.CGAL_Kernel import Point_3
    from CGAL.CGAL_Triangulation_3 import Delaunay_triangulation_3

    t0 = time.perf_counter()
    pts = [Point_3(x, y, z) for x, y, z in points.tolist()]
    t_list = time.perf_counter() - t0
    dt = Delaunay_triangulation_3(pts)
    return dt.number_of_finite_cells(), f"incl. {t_list:.2f} s for the Point_3 list"


ENGINES: list[tuple[str, str | None, Callable[[np.ndarray], tuple[int, str]]]] = [
    ("ours (delaunay_tetrahedra)", None, run_ours),
    ("SciPy Qhull (Morton order, QJ)", None, run_qhull),
    ("TetGen (tetgen, -Q, no -p)", "tetgen", run_tetgen),
    ("CGAL Delaunay_triangulation_3", "cgal", run_cgal),
]


def best_of(run: Callable[[np.ndarray], tuple[int, str]], points: np.ndarray, repeat: int) -> tuple[float, int, str]:
    """Best time of ``repeat`` runs, the tetrahedra and the note of the best run."""
    best = (np.inf, 0, "")
    for _ in range(repeat):
        t0 = time.perf_counter()
        n_tets, note = run(points)
        seconds = time.perf_counter() - t0
        if seconds < best[0]:
            best = (seconds, n_tets, note)
    return best


def installed(peer: str | None) -> bool:
    if peer is None:
        return True
    try:
        __import__(PEERS[peer][0])
    except ImportError:
        return False
    return True


def versions() -> str:
    names = ["scipy", "numba", "tetgen", "cgal"]
    found = []
    for name in names:
        try:
            found.append(f"{name} {importlib.metadata.version(name)}")
        except importlib.metadata.PackageNotFoundError:
            continue
    return ", ".join(found)


def table(name: str, points: np.ndarray, repeat: int) -> None:
    print(f"\n{name}: {len(points)} points")
    print(f"  {'engine':34s} {'seconds':>8s} {'tetrahedra':>11s} {'ratio':>7s}")
    ours = None
    for label, peer, run in ENGINES:
        if not installed(peer):
            _, pypi, licence = PEERS[peer]
            print(f"  {label:34s} not installed (pip install {pypi}; licence {licence}: "
                  "benchmark peer only, not a dependency)")
            continue
        seconds, n_tets, note = best_of(run, points, repeat)
        if ours is None:
            ours = seconds
        print(f"  {label:34s} {seconds:8.2f} {n_tets:11d} {seconds / ours:7.2f}" + (f"  ({note})" if note else ""))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vertices", type=int, default=100_000, help="vertices of the bumpy torus")
    parser.add_argument("--repeat", type=int, default=3, help="runs per engine and input; the best is kept")
    args = parser.parse_args()

    from medialaxis.mesh.sample.delaunay import delaunay_tetrahedra

    print(versions())
    delaunay_tetrahedra(np.random.default_rng(1).random((2000, 3)))  # warm the numba cache
    samples, n_vertices = torus_samples(args.vertices)
    table(f"(a) surface samples of the bumpy torus ({n_vertices} vertices)", samples, args.repeat)
    cube = np.random.default_rng(0).random((100_000, 3))
    table("(b) uniform random points in a cube (seed 0)", cube, args.repeat)
    print(f"\nbest of {args.repeat} runs; ratio: engine / ours; one thread each"
          " (2 shared cores, other jobs running: timings are pessimistic)")


if __name__ == "__main__":
    main()
