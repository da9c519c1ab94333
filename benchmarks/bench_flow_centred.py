"""Benchmark: how centred flow skeletons are on shapes whose axes are known (issue 31, point 5).

Every figure comes from geometry, never from the result's metadata:

- tori (major radius 3, minor 1) at a few resolutions: distance of each skeleton
  node to the core circle, p50 / p99 / max as a percentage of the major radius,
  and the number of independent cycles (one);
- a bent tube (a half torus of major radius 3, minor 1, capped by hemispheres,
  by marching cubes): distance of each node to the arc (continued straight into
  the caps), as a percentage of the bend radius;
- a helical tube swept by ``trimesh.creation.sweep_polygon`` (radius 0.5 around a
  helix of radius 3): distance to the helix, as a percentage of the helix radius;
- a disc and a square swept along a half circle of radius 3 (flat ends): distance
  to the arc, one tube radius away from the ends;
- straight rods voxelized and meshed by marching cubes (5 and 10 voxels across
  the radius), as meshed and turned by a random rotation after meshing (a
  scanner's direction cosines): their numbers of endpoints (two);
- an extruded L-shaped plate with a round hole, written and read back as float32
  STL: its Betti numbers (one cycle).

Usage::

    .venv/bin/python benchmarks/bench_flow_centred.py

Before issue 31 point 5 (commit 6171f7a) the torus of 4,608 vertices had every
node 4.13% of R inside its core circle, the swept disc 4.27% (p99, away from the
ends), the square 7.1%, and the L-plate one node, Betti (1, 0, 0).
"""

from __future__ import annotations

import io
import time

import numpy as np


def torus_distance(points: np.ndarray, major: float) -> np.ndarray:
    return np.hypot(np.hypot(points[:, 0], points[:, 1]) - major, points[:, 2])


def bent_tube(step: float = 0.1, bend: float = 3.0, radius: float = 1.0) -> object:
    """Half torus (y >= 0) capped by hemispheres at its two ends, by marching cubes."""
    import trimesh
    from skimage.measure import marching_cubes

    grid = np.arange(-bend - radius - 0.6, bend + radius + 0.6 + step / 2, step)
    x, y, z = np.meshgrid(grid, grid, grid, indexing="ij")
    angle = np.arctan2(y, x)
    angle = np.where(angle < 0, np.where(x > 0, 0.0, np.pi), angle)
    sdf = np.sqrt((x - bend * np.cos(angle)) ** 2 + (y - bend * np.sin(angle)) ** 2 + z**2) - radius
    verts, faces, _, _ = marching_cubes(sdf, 0.0, spacing=(step,) * 3)
    return trimesh.Trimesh(verts + grid[0], faces)


def bent_tube_distance(points: np.ndarray, bend: float = 3.0, radius: float = 1.0) -> np.ndarray:
    """Distance to the half circle of radius ``bend`` (y >= 0), continued straight into the caps."""
    from medialaxis.datasets import segment_distance

    angle = np.clip(np.arctan2(points[:, 1], points[:, 0]), 0.0, np.pi)
    angle = np.where(points[:, 1] < 0, np.where(points[:, 0] > 0, 0.0, np.pi), angle)
    foot = np.column_stack([bend * np.cos(angle), bend * np.sin(angle), np.zeros(len(points))])
    arc = np.linalg.norm(points - foot, axis=1)
    caps = np.array([[[bend, 0, 0], [bend, -radius, 0]], [[-bend, 0, 0], [-bend, -radius, 0]]], dtype=float)
    return np.minimum(arc, segment_distance(points, caps))


def helix(samples: int = 400, radius: float = 3.0, pitch: float = 4.0, turns: float = 1.0) -> np.ndarray:
    t = np.linspace(0.0, 2 * np.pi * turns, samples)
    return np.column_stack([radius * np.cos(t), radius * np.sin(t), pitch * t / (2 * np.pi)])


def helix_tube(tube: float = 0.5, sections: int = 24, samples: int = 160) -> object:
    import trimesh
    from shapely.geometry import Point

    circle = Point(0, 0).buffer(tube, quad_segs=sections // 4)
    return trimesh.creation.sweep_polygon(circle, helix(samples))


def polyline_distance(points: np.ndarray, line: np.ndarray) -> np.ndarray:
    from medialaxis.datasets import segment_distance

    return segment_distance(points, np.stack([line[:-1], line[1:]], axis=1))


def marching_cubes_rod(length: float = 6.0, radius: float = 0.5, pitch: float = 0.1) -> object:
    """A straight cylinder (flat ends) voxelized on a grid and meshed by marching cubes."""
    import trimesh
    from skimage.measure import marching_cubes

    xs = np.arange(-length / 2 - 3 * pitch, length / 2 + 3 * pitch + pitch / 2, pitch)
    ys = np.arange(-radius - 3 * pitch, radius + 3 * pitch + pitch / 2, pitch)
    x, y, z = np.meshgrid(xs, ys, ys, indexing="ij")
    solid = (np.hypot(y, z) <= radius) & (np.abs(x) <= length / 2)
    verts, faces, _, _ = marching_cubes(solid.astype(np.float32), 0.5, spacing=(pitch,) * 3)
    return trimesh.Trimesh(verts + [xs[0], ys[0], ys[0]], faces)


def l_plate_with_hole() -> object:
    """An L-shaped plate (thickness 2) with a round hole, through a float32 STL file."""
    import trimesh
    from shapely.geometry import Point, Polygon

    outline = Polygon([(0, 0), (20, 0), (20, 8), (8, 8), (8, 20), (0, 20)])
    plate = trimesh.creation.extrude_polygon(outline.difference(Point(4, 4).buffer(2.0, quad_segs=16)), 2.0)
    data = io.BytesIO(plate.export(file_type="stl"))
    return trimesh.load(data, file_type="stl")


def pct(d: np.ndarray, scale: float) -> str:
    return f"p50 {100 * np.median(d) / scale:.2f}% p99 {100 * np.percentile(d, 99) / scale:.2f}% max {100 * d.max() / scale:.2f}%"


def run(name: str, mesh: object) -> tuple[object, float]:
    import medialaxis as mx

    t0 = time.perf_counter()
    sk = mx.medial_axis(mesh, method="flow")
    return sk, time.perf_counter() - t0


def main() -> None:
    import trimesh
    from shapely.geometry import Point, box

    total = 0.0
    for sections in ((32, 32), (96, 48), (128, 48)):
        mesh = trimesh.creation.torus(3.0, 1.0, major_sections=sections[0], minor_sections=sections[1])
        sk, sec = run("torus", mesh)
        total += sec
        print(f"torus R=3 r=1 {sections} ({len(mesh.vertices)} v): {len(sk.points)} nodes, to core circle "
              f"{pct(torus_distance(sk.points, 3.0), 3.0)} of R; betti {tuple(sk.betti)}; {sec:.2f} s")
    mesh = bent_tube()
    sk, sec = run("bent", mesh)
    total += sec
    print(f"bent tube (half torus R=3 r=1, capped; {len(mesh.vertices)} v): to arc "
          f"{pct(bent_tube_distance(sk.points), 3.0)} of R; ends {len(sk.endpoints)} betti {tuple(sk.betti)}; {sec:.2f} s")
    mesh = helix_tube()
    sk, sec = run("helix", mesh)
    total += sec
    line = helix()
    away = np.minimum(np.linalg.norm(sk.points - line[0], axis=1), np.linalg.norm(sk.points - line[-1], axis=1)) > 1.0
    print(f"helix tube (R=3 r=0.5 pitch 4, flat ends; {len(mesh.vertices)} v): to helix "
          f"{pct(polyline_distance(sk.points, line), 0.5)} of r, two radii from the ends "
          f"{pct(polyline_distance(sk.points[away], line), 0.5)} of r; "
          f"ends {len(sk.endpoints)} betti {tuple(sk.betti)}; {sec:.2f} s")
    for name, section in (("disc r=1", Point(0, 0).buffer(1.0, quad_segs=12)), ("square 1.6", box(-0.8, -0.8, 0.8, 0.8))):
        t = np.linspace(0.0, np.pi, 49)
        path = np.column_stack([3.0 * np.cos(t), 3.0 * np.sin(t), np.zeros_like(t)])
        mesh = trimesh.creation.sweep_polygon(section, path)
        sk, sec = run("arc", mesh)
        total += sec
        angle = np.arctan2(sk.points[:, 1], sk.points[:, 0])
        inside = (angle > 1.0 / 3.0) & (angle < np.pi - 1.0 / 3.0)
        print(f"{name} swept along a half circle R=3 ({len(mesh.vertices)} v): to arc, away from the ends, "
              f"{pct(torus_distance(sk.points[inside], 3.0), 3.0)} of R; ends {len(sk.endpoints)}; {sec:.2f} s")
    from scipy.spatial.transform import Rotation

    from medialaxis.datasets import segment_distance

    for length, radius, pitch, turn in ((6.0, 0.5, 0.1, None), (6.0, 0.5, 0.05, None), (6.0, 0.5, 0.1, 11), (6.0, 0.5, 0.05, 12)):
        mesh = marching_cubes_rod(length, radius, pitch)
        rotation = np.eye(3) if turn is None else Rotation.random(random_state=turn).as_matrix()
        mesh.vertices = mesh.vertices @ rotation.T  # turned after meshing: a scanner's direction cosines
        sk, sec = run("rod", mesh)
        total += sec
        axis = np.array([[[-length / 2, 0, 0], [length / 2, 0, 0]]])
        print(f"marching-cubes rod{' turned' if turn is not None else ''} (length {length:g} r={radius:g}, "
              f"{radius / pitch:g} voxels; {len(mesh.vertices)} v): ends {len(sk.endpoints)} junctions {len(sk.junctions)}; "
              f"to axis {pct(segment_distance(sk.points @ rotation, axis), radius)} of r; {sec:.2f} s")
    mesh = l_plate_with_hole()
    sk, sec = run("plate", mesh)
    total += sec
    print(f"L-plate with a hole (float32 STL; {len(mesh.vertices)} v): {len(sk.points)} nodes, betti {tuple(sk.betti)}; "
          f"{sec:.2f} s")
    print(f"total {total:.1f} s")


if __name__ == "__main__":
    main()
