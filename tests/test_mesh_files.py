"""Files other tools open: each mesh and curve output read back by the reader itself
(meshio, trimesh, pyvista, networkx, an SWC parse) with the result's counts."""

import subprocess
import sys

import meshio
import networkx as nx
import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

import medialaxis as mx
from medialaxis.datasets import t_phantom


def _undirected(edges):
    e = np.sort(np.asarray(edges).reshape(-1, 2), axis=1)
    return {tuple(r) for r in e[e[:, 0] != e[:, 1]].tolist()}


def _lines(ma):
    """Edges on no face, counted here from the arrays."""
    f = np.asarray(ma.faces)
    on_face = _undirected(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])) if len(f) else set()
    return _undirected(ma.edges) - on_face


@pytest.fixture(scope="module")
def results():
    ph = t_phantom((40, 60, 60), margin=6)
    image = np.zeros((60, 90), bool)
    image[15:45, 10:80] = True
    return {
        "midsurface": mx.medial_axis(ph.volume, method="midsurface", iso=0.5),
        "flow": mx.medial_axis(trimesh.creation.torus(2.0, 0.5), method="flow"),
        "voronoi": mx.medial_axis(trimesh.creation.box(), method="voronoi"),
        "planar": mx.medial_axis(image),
        "voxels": mx.medial_axis(ph.volume, method="voxels", iso=0.5),  # points only
    }


def _pyvista_counts(path):
    code = f"import pyvista as pv; g = pv.read({str(path)!r}); print(g.n_points, g.n_cells)"
    out = subprocess.run([sys.executable, "-W", "ignore", "-c", code], capture_output=True, text=True, timeout=120,
                         check=False)
    assert out.returncode == 0, out.stderr[-500:]  # a crash of VTK's reader included
    return tuple(int(v) for v in out.stdout.split())


@pytest.mark.parametrize("name", ["midsurface", "flow", "voronoi", "planar", "voxels"])
@pytest.mark.parametrize("ext", [".ply", ".vtk", ".vtu"])
def test_mesh_files_open_with_the_results_counts(results, name, ext, tmp_path):
    ma = results[name]
    path = tmp_path / f"axis{ext}"
    ma.save(path)
    n, faces, lines = len(ma.points), len(ma.faces), len(_lines(ma))
    if ext == ".ply" and faces and lines:
        # triangles and curve pieces: the pieces are PLY's standard 'edge' element, which meshio's
        # reader does not know; trimesh keeps it, VTK reads the triangles
        with pytest.raises((meshio.ReadError, SystemExit)):  # meshio reports its ReadError and exits
            meshio.read(path)
        t = trimesh.load(path, process=False, force="mesh")
        assert len(t.vertices) == n and len(t.faces) == faces
        assert _undirected(np.array(t.metadata["_ply_raw"]["edge"]["data"].tolist())) == _lines(ma)
        assert _pyvista_counts(path) == (n, faces)
        return
    m = meshio.read(path)
    cells = {c.type: len(c.data) for c in m.cells}
    assert len(m.points) == n
    assert cells.get("triangle", 0) == faces and cells.get("line", 0) == lines
    lone = faces + lines == 0  # a point set: one vertex cell per point (VTK's PLY reader makes them too)
    if ext != ".ply":
        assert cells.get("vertex", 0) == (n if lone else 0)
    np.testing.assert_allclose(np.ravel(m.point_data["radius"]), ma.radii)
    assert _pyvista_counts(path) == (n, n if lone else faces + lines)
    t = trimesh.load(path, process=False, force=None if lone and ext == ".ply" else "mesh")  # a PLY point cloud
    assert len(t.vertices) == n and len(getattr(t, "faces", ())) == faces


@pytest.mark.parametrize("name", ["flow", "planar"])
def test_swc_is_a_forest_of_the_curve(results, name, tmp_path):
    ma = results[name]
    path = tmp_path / "axis.swc"
    ma.save(path)
    text = path.read_text().splitlines()
    rows = np.loadtxt([line for line in text if not line.startswith("#")], ndmin=2)
    cycles = [tuple(int(v) for v in line.split()[2:]) for line in text if line.startswith("# cycle")]
    ids, parents = rows[:, 0].astype(int), rows[:, 6].astype(int)
    assert sorted(ids) == list(range(1, len(ma.points) + 1))
    assert set(parents[parents > 0]) <= set(ids)
    points = np.c_[ma.points, np.zeros(len(ma.points))] if ma.dim == 2 else ma.points
    dist, index_of_row = cKDTree(points).query(rows[:, 2:5])  # each row's point of the result
    assert dist.max() <= 1e-8 and len(set(index_of_row.tolist())) == len(points)
    np.testing.assert_allclose(rows[:, 5], ma.radii[index_of_row], atol=1e-8)
    index = dict(zip(ids.tolist(), index_of_row.tolist()))
    tree = [(index[i], index[p]) for i, p in zip(ids.tolist(), parents.tolist()) if p > 0]
    swc_edges = _undirected(tree + [(index[a], index[b]) for a, b in cycles])
    assert swc_edges == _undirected(ma.edges)  # tree edges and cycle edges: the result's edges
    assert int((parents == -1).sum()) == ma.n_components


def test_swc_refuses_a_surface(results, tmp_path):
    with pytest.raises(mx.UnsupportedFormatError, match="SWC holds curve skeletons"):
        results["midsurface"].save(tmp_path / "mid.swc")
    assert not list(tmp_path.iterdir())  # nothing left behind


def test_graphml_edges_carry_length_and_radius(results, tmp_path):
    ma = results["flow"]
    path = tmp_path / "axis.graphml"
    ma.save(path)
    g = nx.read_graphml(path)
    assert g.number_of_nodes() == len(ma.points) and g.number_of_edges() == len(_undirected(ma.edges))
    for a, b, data in g.edges(data=True):
        i, j = int(a), int(b)
        assert np.isclose(data["length"], np.linalg.norm(ma.points[i] - ma.points[j]))
        assert np.isclose(data["radius"], 0.5 * (ma.radii[i] + ma.radii[j]))


@pytest.mark.parametrize("name", ["midsurface", "flow", "voronoi", "planar"])
def test_obj_opens_with_the_results_counts(results, name, tmp_path):
    # OBJ has no per-vertex radius (the other formats carry it). Curves are OBJ 'l' elements:
    # VTK (pyvista) reads them; meshio's and trimesh's OBJ readers skip 'l' lines altogether, so
    # for curve skeletons in those tools use .ply, .vtk, .vtu or .swc.
    ma = results[name]
    path = tmp_path / "axis.obj"
    ma.save(path)
    n, faces, lines = len(ma.points), len(ma.faces), len(_lines(ma))
    assert _pyvista_counts(path) == (n, faces + lines)
    m = meshio.read(path)
    assert len(m.points) == n and sum(len(c.data) for c in m.cells if c.type == "triangle") == faces
    if faces:  # trimesh's OBJ reader keeps the vertices its faces use
        t = trimesh.load(path, process=False, force="mesh")
        assert len(t.vertices) == len(np.unique(ma.faces)) and len(t.faces) == faces
    text = path.read_text()
    assert text.count("\nl ") == lines and text.count("\nf ") == faces
