"""The MedialAxis result type, graph utilities and file formats."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

import medialaxis as mx
from medialaxis.core import graph
from medialaxis.core._kernels import peel_leaves_kernel, peel_leaves_reference


@pytest.fixture(scope="module")
def bracket():
    plate = shapely.box(0, 0, 12, 5).union(shapely.box(9, 0, 12, 10))
    return mx.medial_axis(plate.difference(shapely.Point(3, 2.5).buffer(1.2)))


def test_result_is_immutable(bracket):
    with pytest.raises(dataclasses.FrozenInstanceError):
        bracket.points = np.zeros((1, 2))
    for arr in (bracket.points, bracket.radii, bracket.edges, bracket.faces, bracket.degree, bracket.junctions):
        with pytest.raises(ValueError):
            arr[...] = 0
    with pytest.raises(TypeError):
        bracket.metadata["lam"] = 3


def test_pickles_for_worker_processes(bracket):
    import pickle

    back = pickle.loads(pickle.dumps(bracket))
    np.testing.assert_array_equal(back.points, bracket.points)
    assert dict(back.metadata) == dict(bracket.metadata)
    assert not back.points.flags.writeable
    np.testing.assert_array_equal(back.prune(lam=2.0).edges, bracket.prune(lam=2.0).edges)


def test_construction_copies_and_validates():
    pts = np.array([[0.0, 0.0], [1.0, 0.0]])
    ma = mx.MedialAxis(pts, [1.0, 1.0], [[0, 1]])
    pts[0, 0] = 5
    assert ma.points[0, 0] == 0 and ma.faces.shape == (0, 3) and ma.edges.dtype == np.int64
    with pytest.raises(mx.InvalidInputError, match="radii"):
        mx.MedialAxis(pts, [1.0], [[0, 1]])
    with pytest.raises(mx.InvalidInputError, match="out of range"):
        mx.MedialAxis(pts, [1.0, 1.0], [[0, 2]])
    with pytest.raises(mx.InvalidInputError, match="points"):
        mx.MedialAxis(np.zeros((3, 4)), np.zeros(3))


def test_branches_cover_every_edge_once(bracket):
    brs = bracket.branches()
    walked = sorted(tuple(sorted(e)) for b in brs for e in zip(b.indices[:-1], b.indices[1:]))
    assert walked == sorted(tuple(sorted(e)) for e in bracket.edges.tolist())
    for b in brs:
        ends = bracket.degree[[b.indices[0], b.indices[-1]]]
        assert b.is_cycle or all(d != 2 for d in ends)
        np.testing.assert_array_equal(b.radii, bracket.radii[b.indices])
        assert b.length > 0


def test_pure_cycle_is_one_closed_branch():
    ma = mx.medial_axis(shapely.Point(0, 0).buffer(2, quad_segs=64).difference(shapely.Point(0, 0).buffer(1, quad_segs=64)))
    (b,) = ma.branches()
    assert b.is_cycle and len(ma.junctions) == 0


def test_to_networkx(bracket):
    import networkx as nx

    g = bracket.to_networkx()
    assert g.number_of_nodes() == len(bracket.points)
    assert nx.number_connected_components(g) == 1
    assert len(nx.cycle_basis(g)) == bracket.n_cycles == 1
    node = g.nodes[0]
    assert node["radius"] == bracket.radii[0] and len(node["pos"]) == 2


def test_prune_without_recomputing(bracket):
    coarse = bracket.prune(lam=2.0)
    assert coarse.metadata["lam"] == 2.0
    assert len(coarse.points) < len(bracket.points)
    assert coarse.n_cycles == 1 and coarse.n_components == 1
    same = coarse.prune(lam=bracket.metadata["lam"])
    np.testing.assert_array_equal(same.points, bracket.points)


@pytest.mark.parametrize("ext", [".json", ".npz"])
def test_lossless_round_trip(bracket, tmp_path, ext):
    path = tmp_path / f"a{ext}"
    bracket.save(path)
    back = mx.load(path)
    for name in ("points", "radii", "edges", "faces"):
        np.testing.assert_array_equal(getattr(back, name), getattr(bracket, name))
    assert dict(back.metadata) == dict(bracket.metadata)
    assert back.shape.equals(bracket.shape)
    for key, value in bracket.raw.extras.items():
        np.testing.assert_array_equal(back.raw.extras[key], value)
    np.testing.assert_array_equal(back.prune(lam=2.0).points, bracket.prune(lam=2.0).points)


def test_load_rejects_bad_files(tmp_path):
    (tmp_path / "x.json").write_text('{"hello": 1}')
    (tmp_path / "y.npz").write_bytes(b"garbage")
    (tmp_path / "z.svg").write_text("<svg/>")
    with pytest.raises(mx.InputFileError):
        mx.load(tmp_path / "x.json")
    with pytest.raises(mx.InputFileError):
        mx.load(tmp_path / "y.npz")
    with pytest.raises(mx.UnsupportedFormatError):
        mx.load(tmp_path / "z.svg")
    with pytest.raises(mx.InputFileError):
        mx.load(tmp_path / "missing.json")


def test_save_is_atomic_on_failure(bracket, tmp_path, monkeypatch):
    from medialaxis.core import lossless

    path = tmp_path / "a.json"
    path.write_text("old")

    def boom(*a, **k):
        raise RuntimeError("disk full")

    monkeypatch.setattr(lossless.json, "dump", boom)
    with pytest.raises(RuntimeError):
        bracket.save(path)
    assert path.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["a.json"]


def test_save_unknown_format(bracket, tmp_path):
    with pytest.raises(mx.UnsupportedFormatError, match="docx"):
        bracket.save(tmp_path / "a.docx")


def test_reconstruct_geometry_and_raster():
    mask = np.zeros((60, 100), bool)
    mask[10:50, 10:90] = True
    ma = mx.medial_axis(mask)
    raster = ma.reconstruct(raster=True)
    assert raster.shape == mask.shape
    iou = (raster & mask).sum() / (raster | mask).sum()
    assert iou > 0.95
    err = mx.reconstruction_error(ma, mask)
    assert err.iou > 0.97 and err.hausdorff < 3
    with pytest.raises(mx.InvalidInputError):
        mx.medial_axis(shapely.box(0, 0, 2, 1)).reconstruct(raster=True)


def test_reconstruction_error_of_exact_polygon_axis():
    ma = mx.medial_axis(shapely.box(0, 0, 4, 2))
    err = mx.reconstruction_error(ma)
    assert err.iou > 0.999 and err.hausdorff < 0.01 and err.mean_distance < 1e-3


def test_extras_are_attributes(bracket):
    raw = bracket.raw
    np.testing.assert_array_equal(raw.edge_contact_diameter, raw.extras["edge_contact_diameter"])
    with pytest.raises(AttributeError):
        _ = bracket.no_such_thing


@st.composite
def random_graphs(draw):
    n = draw(st.integers(1, 30))
    m = draw(st.integers(0, 60))
    edges = np.array(draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), min_size=m, max_size=m)), np.int64).reshape(-1, 2)
    edges = edges[edges[:, 0] != edges[:, 1]]
    if len(edges):
        edges = np.unique(np.sort(edges, 1), axis=0)
    removable = np.array(draw(st.lists(st.booleans(), min_size=len(edges), max_size=len(edges))), bool)
    return n, edges, removable


@given(random_graphs())
def test_peeling_kernel_matches_reference_and_keeps_topology(g):
    n, edges, removable = g
    adj = graph.adjacency(n, edges)
    args = (adj.indptr, adj.indices, (adj.data - 1).astype(np.int64), graph.degree(n, edges), edges, removable)
    a = np.ones(len(edges), bool)
    b = np.ones(len(edges), bool)
    peel_leaves_kernel(*args, a)
    peel_leaves_reference(*args, b)
    np.testing.assert_array_equal(a, b)
    kept = edges[a]
    assert graph.cycle_rank(n, kept) == graph.cycle_rank(n, edges)
    assert np.all(a[~removable])
    # components with edges stay one component each
    _, before = graph.component_labels(n, edges)
    _, after = graph.component_labels(n, kept)
    for comp in np.unique(before[edges.ravel()]) if len(edges) else []:
        nodes = np.unique(kept.ravel()[before[kept.ravel()] == comp]) if len(kept) else []
        if len(nodes):
            assert len(np.unique(after[nodes])) == 1


@given(st.integers(1, 30).flatmap(lambda n: st.tuples(
    st.just(n), st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=50))))
def test_compiled_branch_walk_equals_the_python_walk(g):
    # repeated edges and self-loops included: each edge walked exactly once, in the same order
    n, pairs = g
    edges = np.array(pairs, np.int64).reshape(-1, 2)
    got, want = graph.branches(n, edges), graph.branches_reference(n, edges)
    assert len(got) == len(want)
    for a, b in zip(got, want):
        np.testing.assert_array_equal(a, b)
    walked = sum(len(c) - 1 for c in got)
    assert walked == len(edges)
