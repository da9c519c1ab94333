"""The branch table (``MedialAxis.summary``) against shapes whose branches are known."""

import sys

import numpy as np
import pytest
import trimesh

import medialaxis as mx
from medialaxis.datasets import tripod_mesh


def _axis_length(ma):
    e = np.unique(np.sort(ma.edges, axis=1), axis=0)
    e = e[e[:, 0] != e[:, 1]]
    return float(np.linalg.norm(ma.points[e[:, 0]] - ma.points[e[:, 1]], axis=1).sum())


def test_rectangle_has_four_end_branches_and_one_middle():
    image = np.zeros((60, 90), bool)
    image[15:45, 10:80] = True
    ma = mx.medial_axis(image)
    table = ma.summary()
    assert sorted(table["kind"]) == ["endpoint-junction"] * 4 + ["junction-junction"]
    assert np.isclose(table["length"].sum(), _axis_length(ma))
    assert (table["euclidean"] <= table["length"] + 1e-9).all()
    assert (table["radius_min"] <= table["radius_mean"]).all() and (table["radius_mean"] <= table["radius_max"]).all()
    middle = table[table["kind"] == "junction-junction"].iloc[0]
    # the middle branch runs along the rectangle's long axis (row 29.5), 70 - 30 = 40 long
    assert np.isclose(middle["start_0"], 29.5, atol=0.5) and np.isclose(middle["length"], 40.0, rtol=0.05)
    assert np.isclose(middle["radius_mean"], 15.0, rtol=0.05)


def test_torus_skeleton_is_one_cycle():
    ma = mx.medial_axis(trimesh.creation.torus(2.0, 0.5), method="flow")
    table = ma.summary()
    assert list(table["kind"]) == ["cycle"] and table["euclidean"].iloc[0] == 0.0
    assert np.isclose(table["length"].iloc[0], 2 * np.pi * 2.0, rtol=0.02)
    assert np.isclose(table["radius_mean"].iloc[0], 0.5, rtol=0.05)


def test_tripod_has_three_arms():
    ma = mx.medial_axis(tripod_mesh(pitch=0.1), method="flow")
    table = ma.summary()
    assert sorted(table["kind"]) == ["endpoint-junction"] * 3
    assert np.isclose(table["length"].sum(), _axis_length(ma))
    assert set(table.columns) >= {"start_2", "end_2"}


def test_without_pandas_the_error_says_what_to_install(monkeypatch):
    image = np.zeros((40, 60), bool)
    image[10:30, 10:50] = True
    ma = mx.medial_axis(image)
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas now raises ImportError
    with pytest.raises(mx.MissingDependencyError, match="pip install pandas"):
        ma.summary()
