"""Meshes as CAD tools and users make them: parts never put through a boolean union, folds, holes, thin plates.

For each input, the default call of both mesh methods, and the truth from
outside the code under test: manifold3d's boolean union of the same parts
(its Betti numbers from its shells and Euler characteristic; radii against
trimesh's distances to its surface, at 2,000 points at most). Prints one row per input and method:
refused or not, Betti numbers against the solid's, seconds, the largest
radius error as a share of the diagonal, and the warning.

    python benchmarks/bench_mesh_defects.py

On 910f943 every input gives the solid's Betti numbers with both methods but
one: the uv ellipsoid whose vertices moved along it (3 pairs of faces cross at
a pole), ``voronoi`` (1, 1, 0) in 34 s with the warning that names the solid's
(1, 0, 0), 16,119 points (the clean one compacts to 85); ``flow`` (1, 0, 0).
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np
import shapely
import trimesh

import medialaxis as mx


def _rotated(mesh: trimesh.Trimesh, axis: list[float]) -> trimesh.Trimesh:
    mesh.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, axis))
    return mesh


def _box(lo: list[float], hi: list[float]) -> trimesh.Trimesh:
    return trimesh.creation.box(bounds=np.array([lo, hi], float))


def cases() -> dict[str, tuple[trimesh.Trimesh, trimesh.Trimesh]]:
    """name -> (the mesh as given, the union that is its solid)."""
    out = {}
    parts = {
        "two boxes, overlapping": [trimesh.creation.box(), trimesh.creation.box().apply_translation([0.5, 0.3, 0.2])],
        "box cross (coplanar tops)": [trimesh.creation.box(extents=(2, 1, 1)), trimesh.creation.box(extents=(1, 2, 1))],
        "three crossing capsules": [trimesh.creation.capsule(height=2, radius=0.4),
                                    _rotated(trimesh.creation.capsule(height=2, radius=0.4), [1, 0, 0]),
                                    _rotated(trimesh.creation.capsule(height=2, radius=0.4), [0, 1, 0])],
        "two spheres (shared vertices)": [trimesh.creation.icosphere(3),
                                          trimesh.creation.icosphere(3).apply_translation([1.0, 0, 0])],
        "sphere in a sphere": [trimesh.creation.icosphere(3, 1.0), trimesh.creation.icosphere(2, 0.5)],
        "box through a torus's hole (apart)": [trimesh.creation.torus(1.0, 0.3, major_sections=48, minor_sections=16),
                                trimesh.creation.box(extents=(0.5, 0.5, 1.5))],
        "three boxes on one grid (touching, curves meet)": [_box([0, 0, 0], [2, 2, 2]), _box([1, 1, 1], [3, 3, 3]),
                                                            _box([1, -1, 1], [3, 1, 3])],
        "stacked boxes (faces in two planes)": [_box([0, 0, 0], [3, 1, 1]), _box([1, 0, 0], [2, 1, 3]),
                                                _box([1, -1, 0], [2, 2, 1])],
        "pipe tee (two cylinders)": [trimesh.creation.cylinder(0.3, 3.0, sections=48),
                                     _rotated(trimesh.creation.cylinder(0.3, 3.0, sections=48), [1, 0, 0])],
    }
    for name, pieces in parts.items():
        out[name] = (trimesh.util.concatenate(pieces), trimesh.boolean.union(pieces, engine="manifold"))
    touching = trimesh.util.concatenate([_box([0, 0, 0], [1, 1, 1]), _box([1, 1, 0], [2, 2, 1])])
    touching.merge_vertices()  # one edge of four faces
    out["two boxes sharing an edge"] = (touching, trimesh.boolean.union(
        [_box([0, 0, 0], [1, 1, 1]), _box([1, 1, 0], [2, 2, 1])], engine="manifold"))
    sphere = trimesh.creation.icosphere(4)
    gone = np.random.default_rng(0).choice(len(sphere.faces), 6, replace=False)
    out["sphere with 6 one-face holes"] = (
        trimesh.Trimesh(sphere.vertices, np.delete(sphere.faces, gone, axis=0), process=False), sphere)
    plate = trimesh.creation.box(extents=(10.0, 10.0, 0.2))
    out["CAD plate 10 x 10 x 0.2 (8 vertices)"] = (plate, plate)
    outline = shapely.Polygon([(0, 0), (4, 0), (4, 1), (1, 1), (1, 4), (0, 4)]).difference(
        shapely.Point(0.5, 2.5).buffer(0.25))
    lplate = trimesh.creation.extrude_polygon(outline, 0.3)
    out["extruded L-plate with a hole"] = (lplate, lplate)
    out["uv ellipsoid 160 x 160, vertices moved along it"] = (_noisy_ellipsoid(),) * 2
    return out


def _noisy_ellipsoid() -> trimesh.Trimesh:
    """A 3:1:1 uv ellipsoid whose vertices moved along it by a tenth of their shortest edge (crowded pole caps)."""
    mesh = trimesh.creation.uv_sphere(radius=1.0, count=[160, 160])
    mesh.apply_scale([3.0, 1.0, 1.0])
    shortest = np.full(len(mesh.vertices), np.inf)
    for k in range(2):
        np.minimum.at(shortest, mesh.edges_unique[:, k], mesh.edges_unique_length)
    move = np.random.default_rng(0).normal(size=mesh.vertices.shape) * 0.1 * shortest[:, None]
    move -= np.einsum("ij,ij->i", move, mesh.vertex_normals)[:, None] * mesh.vertex_normals
    return trimesh.Trimesh(mesh.vertices + move, mesh.faces, process=False)


def solid_betti(mesh: trimesh.Trimesh) -> tuple[int, int, int]:
    """(shells, genus, 0) of a closed mesh from its shells and Euler characteristic."""
    shells = len(mesh.split(only_watertight=False))
    return shells, (2 * shells - int(mesh.euler_number)) // 2, 0


def run(name: str, given: trimesh.Trimesh, solid: trimesh.Trimesh, method: str) -> dict:
    row = {"input": name, "method": method}
    start = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", mx.MedialAxisWarning)
        try:
            ma = mx.medial_axis(given, method=method)
        except mx.MedialAxisError as exc:
            row.update(refused=f"{type(exc).__name__}: {exc}", seconds=time.perf_counter() - start)
            return row
    row["seconds"] = time.perf_counter() - start
    row["betti"], row["truth"] = ma.betti, solid_betti(solid)
    diag = float(np.linalg.norm(solid.extents))
    if method == "voronoi":
        # at most 2,000 points, in chunks: trimesh's closest points take memory per point and face
        # (killed at 16k points against 100k faces, 10 min in chunks)
        pick = np.random.default_rng(0).permutation(len(ma.points))[:2000]
        inside = np.concatenate([trimesh.proximity.signed_distance(solid, ma.points[pick[i : i + 500]])
                                 for i in range(0, len(pick), 500)])
        row["radius_error"] = float(np.abs(inside - ma.radii[pick]).max()) / diag
    row["warning"] = "; ".join(str(w.message)[:90] for w in caught if issubclass(w.category, mx.MedialAxisWarning))
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--methods", default="voronoi,flow")
    args = parser.parse_args()
    rows = []
    for name, (given, solid) in cases().items():
        for method in args.methods.split(","):
            rows.append(run(name, given, solid, method))
            r = rows[-1]
            if "refused" in r:
                print(f"{name:40s} {method:8s} REFUSED {r['refused'][:100]}")
                continue
            err = f"{100 * r['radius_error']:.1e}%" if "radius_error" in r else "-"
            ok = "right" if r["betti"] == r["truth"] else "WRONG"
            print(f"{name:40s} {method:8s} betti {r['betti']} truth {r['truth']} {ok:5s} {r['seconds']:6.1f} s "
                  f"radius err {err:9s} {r['warning'][:70]}")
    done = [r for r in rows if "refused" not in r]
    print(f"\n{len(rows)} runs: {len(rows) - len(done)} refused, "
          f"{sum(r['betti'] == r['truth'] for r in done)} with the solid's Betti numbers")


if __name__ == "__main__":
    main()
